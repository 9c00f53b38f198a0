#include "postproc/measured_poses.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <set>
#include <string_view>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/c_format.hpp"
#include "compensator/support/error.hpp"
#include "postproc/text_lines.hpp"

namespace roprec::postproc {
namespace {

std::vector<std::string> cells(std::string_view line) {
  std::vector<std::string> out;
  std::size_t i = 0;
  while (true) {
    const std::size_t j = line.find(',', i);
    const std::size_t e = j == std::string_view::npos ? line.size() : j;
    out.emplace_back(trimBlanks(line.substr(i, e - i)));
    if (j == std::string_view::npos) break;
    i = j + 1;
  }
  return out;
}

std::string lower(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return r;
}

/// The column groups: required (id, joints, position) and optional (all cells or none).
const std::vector<std::string> kJoints{"j1", "j2", "j3", "j4", "j5", "j6"};
const std::vector<std::string> kPosition{"x", "y", "z"};
const std::vector<std::string> kRpy{"rx", "ry", "rz"};
const std::vector<std::string> kPayload{"mass", "com_x", "com_y", "com_z"};
const std::vector<std::string> kWrench{"fx", "fy", "fz", "mx", "my", "mz"};

class Table {
 public:
  Table(const std::string& path, const TextLine& header) : path_(path) {
    const std::vector<std::string> names = cells(header.text);
    for (size_t c = 0; c < names.size(); ++c) column_.emplace(lower(names[c]), c);
    for (const auto& group : {std::vector<std::string>{"id"}, kJoints, kPosition}) {
      for (const std::string& n : group) {
        if (!column_.count(n))
          throw InputError(path, header.number,
                           "the pose file has no column '" + n +
                               "'; hint: the header is id,j1,j2,j3,j4,j5,j6,x,y,z "
                               "(optional rx,ry,rz, mass,com_x,com_y,com_z, fx..mz, u, u_rot)");
      }
    }
  }

  bool hasGroup(const std::vector<std::string>& g) const {
    for (const std::string& n : g) {
      if (!column_.count(n)) return false;
    }
    return true;
  }

  /// The group's numbers in this row, nullopt when all its cells are empty (or it has no
  /// columns); an incomplete group or a non-number is an error.
  std::optional<std::vector<double>> group(const std::vector<std::string>& row, int line,
                                           const std::vector<std::string>& g, bool required) const {
    if (!hasGroup(g)) return std::nullopt;
    std::vector<double> v;
    int empty = 0;
    for (const std::string& n : g) {
      const size_t c = column_.at(n);
      const std::string cell = c < row.size() ? row[c] : std::string();
      if (cell.empty()) {
        ++empty;
        continue;
      }
      v.push_back(number(cell, n, line));
    }
    if (empty == static_cast<int>(g.size()) && !required) return std::nullopt;
    if (empty > 0) {
      std::string names;
      for (const std::string& n : g) names += (names.empty() ? "" : ",") + n;
      throw InputError(
          path_, line,
          "the cells " + names + " must all be given" + (required ? "" : " or all left empty"));
    }
    return v;
  }

  std::string id(const std::vector<std::string>& row) const {
    const size_t c = column_.at("id");
    return c < row.size() ? row[c] : std::string();
  }

 private:
  double number(const std::string& cell, const std::string& name, int line) const {
    std::string_view s = cell;
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    double v = 0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v, std::chars_format::general);
    if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v))
      throw InputError(path_, line, "column " + name + ": '" + cell + "' is not a finite number");
    return v;
  }

  std::string path_;
  std::map<std::string, size_t> column_;
};

MeasuredPose poseOfRow(const Table& t, const std::vector<std::string>& row, const TextLine& l,
                       const std::string& path) {
  MeasuredPose p;
  p.line = l.number;
  p.id = t.id(row);
  if (p.id.empty()) throw InputError(path, l.number, "the pose has no id");
  if (const auto j = t.group(row, l.number, kJoints, false)) {
    for (int k = 0; k < 6; ++k) p.joints_deg[k] = (*j)[static_cast<size_t>(k)];
  } else {
    p.program_target = true;
  }
  const std::vector<double> x = *t.group(row, l.number, kPosition, true);
  p.p_mm = Vec3(x[0], x[1], x[2]);
  if (const auto r = t.group(row, l.number, kRpy, false))
    p.rpy_deg = Vec3((*r)[0], (*r)[1], (*r)[2]);
  if (const auto m = t.group(row, l.number, kPayload, false)) {
    if ((*m)[0] < 0) throw InputError(path, l.number, "the payload mass must be ≥ 0 kg");
    p.payload_kg = (*m)[0];
    p.payload_com_mm = Vec3((*m)[1], (*m)[2], (*m)[3]);
  }
  if (const auto w = t.group(row, l.number, kWrench, false)) {
    p.force_n = Vec3((*w)[0], (*w)[1], (*w)[2]);
    p.torque_nm = Vec3((*w)[3], (*w)[4], (*w)[5]);
  }
  if (const auto u = t.group(row, l.number, {"u"}, false)) {
    if (!((*u)[0] > 0))
      throw InputError(path, l.number, "the measurement uncertainty u must be > 0 µm");
    p.u_um = (*u)[0];
  }
  if (const auto u = t.group(row, l.number, {"u_rot"}, false)) {
    if (!((*u)[0] > 0))
      throw InputError(path, l.number, "the orientation uncertainty u_rot must be > 0 µrad");
    p.u_rot_urad = (*u)[0];
  }
  return p;
}

}  // namespace

bool looksLikeMeasuredPoses(const std::string& text) {
  for (const TextLine& l : splitTextLines(text)) {
    if (isBlankOrComment(l.text)) continue;
    bool j1 = false;
    bool x = false;
    for (const std::string& c : cells(l.text)) {
      j1 = j1 || lower(c) == "j1";
      x = x || lower(c) == "x";
    }
    return j1 && x;
  }
  return false;
}

MeasuredPoses parseMeasuredPoses(const std::string& text, const std::string& path) {
  MeasuredPoses out;
  out.path = path;
  const std::vector<TextLine> lines = splitTextLines(text);
  std::optional<Table> table;
  std::set<std::string> ids;
  for (const TextLine& l : lines) {
    if (isBlankOrComment(l.text)) continue;
    if (!table) {
      table.emplace(path, l);
      continue;
    }
    MeasuredPose p = poseOfRow(*table, cells(l.text), l, path);
    if (!ids.insert(p.id).second)
      throw InputError(path, l.number, "pose id " + p.id + " occurs twice");
    out.poses.push_back(std::move(p));
  }
  if (out.poses.empty())
    throw InputError(path, lines.empty() ? 0 : lines.back().number, "the pose file has no pose");
  return out;
}

MeasuredPoses readMeasuredPoses(const std::string& path) {
  return parseMeasuredPoses(readFileBytes(path), path);
}

std::string writeMeasuredPoses(const std::vector<MeasuredPose>& poses) {
  bool rpy = false;
  bool payload = false;
  bool wrench = false;
  bool u = false;
  bool u_rot = false;
  for (const MeasuredPose& p : poses) {
    rpy = rpy || p.rpy_deg.has_value();
    payload = payload || p.payload_kg.has_value();
    wrench = wrench || p.force_n.has_value();
    u = u || p.u_um.has_value();
    u_rot = u_rot || p.u_rot_urad.has_value();
  }
  std::string s = "id,j1,j2,j3,j4,j5,j6,x,y,z";
  if (rpy) s += ",rx,ry,rz";
  if (payload) s += ",mass,com_x,com_y,com_z";
  if (wrench) s += ",fx,fy,fz,mx,my,mz";
  if (u) s += ",u";
  if (u_rot) s += ",u_rot";
  s += "\n";
  const auto add = [&](bool present, int n, const auto& value, int decimals) {
    for (int k = 0; k < n; ++k) s += "," + (present ? cFixed(value(k), decimals) : std::string());
  };
  for (const MeasuredPose& p : poses) {
    s += p.id;
    add(
        !p.program_target, 6, [&](int k) { return p.joints_deg[k]; }, 6);
    add(
        true, 3, [&](int k) { return p.p_mm[k]; }, 4);
    if (rpy)
      add(
          p.rpy_deg.has_value(), 3, [&](int k) { return (*p.rpy_deg)[k]; }, 6);
    if (payload)
      add(
          p.payload_kg.has_value(), 4,
          [&](int k) { return k == 0 ? *p.payload_kg : p.payload_com_mm[k - 1]; }, 4);
    if (wrench)
      add(
          p.force_n.has_value(), 6,
          [&](int k) { return k < 3 ? (*p.force_n)[k] : p.torque_nm[k - 3]; }, 4);
    if (u)
      add(
          p.u_um.has_value(), 1, [&](int) { return *p.u_um; }, 3);
    if (u_rot)
      add(
          p.u_rot_urad.has_value(), 1, [&](int) { return *p.u_rot_urad; }, 3);
    s += "\n";
  }
  return s;
}

}  // namespace roprec::postproc
