/// CSV/JSON target lists and the contract's hole-list CSV (docs/programs.md §5, docs/contract.md
/// §7).
///
/// CSV: a header row, then one target a row; `#` starts a comment line. Column names are matched
/// case-insensitively after stripping `_mm`, `_deg`, `_frame` suffixes. Orientation columns and
/// their convention: `a,b,c` KUKA Z-Y'-X''; `w,p,r` FANUC fixed X-Y-Z; `qw,qx,qy,qz` or
/// `q1..q4` quaternion; `rx,ry,rz` only with a declaration comment `# euler: ZYX | XYZ_fixed |
/// XYZ_intrinsic` (ZYX ≡ XYZ_fixed: R = Rz(rz)Ry(ry)Rx(rx); XYZ_intrinsic: R = Rx(rx)Ry(ry)Rz(rz),
/// RoboDK's TxyzRxyz); `i,j,k` makes the file a hole list (drilling direction = TCP +z). Frames
/// may be declared by comments `# frame NAME: x y z qw qx qy qz` / `# tool NAME: ...` (mm) and
/// referenced by the `frame`/`tool` columns. `j1..j6` rows without a pose are joint targets.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <unordered_map>
#include <utility>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/input_file.hpp"
#include "compensator/support/xml_node.hpp"
#include "postproc/dialects.hpp"
#include "postproc/drill.hpp"
#include "postproc/lexer.hpp"

namespace roprec::postproc {
namespace {

struct Cell {
  std::uint32_t begin{0};
  std::uint32_t end{0};
};

std::string lower(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return r;
}

std::string columnKey(std::string_view raw) {
  std::string k = lower(raw);
  while (!k.empty() && (k.back() == ' ' || k.back() == '"')) k.pop_back();
  std::size_t lead = 0;  // one erase, not one a character (linear in the cell)
  while (lead < k.size() && (k[lead] == ' ' || k[lead] == '"')) ++lead;
  k.erase(0, lead);
  for (const char* suf : {"_mm", "_deg", "_frame"}) {
    const std::string s(suf);
    if (k.size() > s.size() && k.compare(k.size() - s.size(), s.size(), s) == 0)
      k.erase(k.size() - s.size());
  }
  return k;
}

// Hole-list bounds (docs/contract.md §7): values outside are typing or unit mistakes.
constexpr double kMinDiameterMm = 0.1;
constexpr double kMaxDiameterMm = 100.0;  // the cell's <drill> diameter_mm range too
constexpr double kMinDepthMm = 0.05;      // a spot drill's shallowest cone
constexpr double kMaxDepthMm = 2000.0;
constexpr double kMinToleranceMm = 0.001;
constexpr double kMaxToleranceMm = 50.0;
constexpr double kMinFeedMm = 0.001;  // mm/rev: the cell's <cut feed_mm_per_rev> range
constexpr double kMaxFeedMm = 10.0;
constexpr double kMinSpindleRpm = 10.0;  // 1/min: the cell's <cut spindle_rpm> range
constexpr double kMaxSpindleRpm = 100000.0;
constexpr double kMaxCoordinateMm = 1e5;    // 100 m from the workobject origin
constexpr double kDirectionNormTol = 1e-3;  // |n| within 1 ± this is normalised, else refused
// A file that looks like metres: every coordinate below this (mm) ...
constexpr double kMetresMaxCoordinateMm = 5.0;
// ... while distinct holes are closer than this (mm).
constexpr double kMetresSpacingMm = 1.0;

/// The columns a hole list may have (after columnKey).
const std::vector<std::string>& holeListColumns() {
  static const std::vector<std::string> k = {"id",   "x",    "y",           "z",      "i",
                                             "j",    "k",    "diameter",    "depth",  "tolerance",
                                             "tool", "feed", "spindle_rpm", "comment"};
  return k;
}

/// The columns a CSV target list may have (after columnKey, docs/programs.md §5).
const std::vector<std::string>& targetListColumns() {
  static const std::vector<std::string> k = {
      "id", "name", "x",      "y",     "z",    "a",    "b",      "c",     "w",     "p",      "r",
      "qw", "qx",   "qy",     "qz",    "q1",   "q2",   "q3",     "q4",    "rx",    "ry",     "rz",
      "j1", "j2",   "j3",     "j4",    "j5",   "j6",   "e1",     "e2",    "e3",    "e4",     "e5",
      "e6", "conf", "config", "frame", "tool", "move", "motion", "speed", "dwell", "comment"};
  return k;
}

/// The members a JSON target list may have: the document, each target, each frame.
const std::vector<std::string>& jsonRootMembers() {
  static const std::vector<std::string> k = {"format",  "source", "units",   "frames",
                                             "targets", "euler",  "comment", "cycle"};
  return k;
}
const std::vector<std::string>& jsonTargetMembers() {
  static const std::vector<std::string> k = {"id",          "name",
                                             "position_mm", "quaternion_wxyz",
                                             "x",           "y",
                                             "z",           "a",
                                             "b",           "c",
                                             "w",           "p",
                                             "r",           "rx",
                                             "ry",          "rz",
                                             "joints_deg",  "external_axes",
                                             "config",      "frame",
                                             "tool",        "motion",
                                             "speed_mm_s",  "fine",
                                             "dwell_s",     "hole",
                                             "comment"};
  return k;
}
const std::vector<std::string>& jsonFrameMembers() {
  static const std::vector<std::string> k = {"name", "position_mm", "quaternion_wxyz", "comment"};
  return k;
}

Pose poseFromText(const SourceFile& f, std::size_t off, std::string_view text) {
  std::vector<double> v;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && (text[i] == ' ' || text[i] == '\t' || text[i] == ',')) ++i;
    std::size_t j = i;
    while (j < text.size() && text[j] != ' ' && text[j] != '\t' && text[j] != ',') ++j;
    if (j > i) {
      const auto x = parseNumber(text.substr(i, j - i));
      if (!x)
        failAt(f, off,
               "broken number '" + std::string(text.substr(i, j - i)) + "' in frame declaration");
      v.push_back(*x);
    }
    i = j;
  }
  if (v.size() != 7) failAt(f, off, "frame declaration needs x y z qw qx qy qz (mm)");
  Pose T = Pose::Identity();
  T.translation() = Vec3(v[0], v[1], v[2]) * 1e-3;
  Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
  if (q.norm() < 1e-9) failAt(f, off, "zero quaternion in frame declaration");
  T.linear() = q.normalized().toRotationMatrix();
  return T;
}

/// Columns the row reader looks up (resolved once from the header, not per row).
enum Col : std::uint8_t {
  kId,
  kName,
  kX,
  kY,
  kZ,
  kA,
  kB,
  kC,
  kW,
  kP,
  kR,
  kQw,
  kQx,
  kQy,
  kQz,
  kRx,
  kRy,
  kRz,
  kI,
  kJ,
  kK,
  kJ1,
  kJ2,
  kJ3,
  kJ4,
  kJ5,
  kJ6,
  kE1,
  kE2,
  kE3,
  kE4,
  kE5,
  kE6,
  kConf,
  kConfig,
  kFrame,
  kTool,
  kMove,
  kMotion,
  kSpeed,
  kDiameter,
  kDepth,
  kTolerance,
  kFeed,
  kSpindleRpm,
  kColCount
};
constexpr const char* kColName[kColCount] = {
    "id",   "name", "x",      "y",     "z",        "a",     "b",         "c",      "w",
    "p",    "r",    "qw",     "qx",    "qy",       "qz",    "rx",        "ry",     "rz",
    "i",    "j",    "k",      "j1",    "j2",       "j3",    "j4",        "j5",     "j6",
    "e1",   "e2",   "e3",     "e4",    "e5",       "e6",    "conf",      "config", "frame",
    "tool", "move", "motion", "speed", "diameter", "depth", "tolerance", "feed",   "spindle_rpm"};

class CsvReader {
 public:
  explicit CsvReader(Program& p) : p_(p), f_(p.files[0]) {}

  void run() {
    const std::string& b = f_.bytes;
    std::size_t line = 0;
    bool have_header = false;
    for (; line < f_.line_starts.size(); ++line) {
      const std::size_t s = f_.line_starts[line] + (line == 0 && f_.bom ? 3 : 0);
      std::size_t e = line + 1 < f_.line_starts.size() ? f_.line_starts[line + 1] : b.size();
      while (e > s && (b[e - 1] == '\n' || b[e - 1] == '\r')) --e;
      std::size_t k = s;
      while (k < e && (b[k] == ' ' || b[k] == '\t')) ++k;
      if (k == e) continue;
      if (b[k] == '#') {
        comment(k, std::string_view(b).substr(k + 1, e - k - 1));
        continue;
      }
      if (!have_header) {
        have_header = true;
        const bool robodk = robodkExport(s, e);
        if (!robodk) header(s, e);
        resolveColumns();
        if (!robodk) continue;
      }
      row(s, e, static_cast<int>(line + 1));
    }
    if (!have_header) failAt(f_, 0, "empty CSV: a header row is required");
    if (holes_mode_) checkNotMetres();
  }

  std::vector<HoleSpec> holes;

 private:
  Program& p_;
  const SourceFile& f_;
  char delim_{','};
  std::unordered_map<std::string, int> col_;
  std::array<int, kColCount> idx_{};  ///< cell index of each Col (-1: no such column)
  std::vector<Cell> cells_;           ///< the current row's cells (reused)
  std::string conf_text_;             ///< last row's configuration text and its parse
  Configuration conf_;
  struct FrameMemo {
    bool valid{false};
    std::size_t frames{0};  ///< p_.frames.size() when `index` was found
    int index{-1};
    std::string ref;
  };
  FrameMemo base_memo_, tool_memo_;  ///< invalidated when a comment declares a frame or tool
  std::string euler_;
  std::unordered_map<std::string, Frame> frames_;
  std::unordered_map<std::string, Frame> tools_;
  Orientation orient_{Orientation::kNone};
  bool holes_mode_{false};
  std::unordered_map<std::string, int> hole_id_line_;  ///< upper-case id -> line of its row
  bool robodk_{false};           ///< a header-less RoboDK target export (robodkExport)
  std::size_t header_cells_{0};  ///< cells of the header row (0: no header)

  /// A row with a non-empty cell past the header's last column shifted its values (typically a
  /// decimal comma, `8,5`): refused, never read with the columns moved.
  void refuseExtraCells(const std::vector<Cell>& cells) const {
    if (header_cells_ == 0) return;
    for (std::size_t i = header_cells_; i < cells.size(); ++i) {
      if (cells[i].begin == cells[i].end) continue;
      failAt(f_, cells[i].begin,
             "this row has " + std::to_string(cells.size()) + " cells but the header has " +
                 std::to_string(header_cells_) +
                 " columns; hint: a decimal comma (8,5) splits a number in two: write 8.5");
    }
  }
  int data_rows_{0};

  /// RoboDK's target export has no header: rows `x,y,z,rx,ry,rz` or `name,x,y,z,rx,ry,rz` (mm,
  /// deg, RoboDK's TxyzRxyz pose R = Rx(rx) Ry(ry) Rz(rz)). A first line of that shape makes the
  /// file a hole list: each row one hole at (x, y, z) drilled along the pose's +z (the TCP's
  /// drilling direction), its id the name or R<n> for the n-th row; the reading is stated in
  /// the notes. Returns false (a header follows) for any other first line.
  bool robodkExport(std::size_t s, std::size_t e) {
    const std::vector<Cell> cells = split(s, e);
    if (cells.size() != 6 && cells.size() != 7) return false;
    const std::size_t first = cells.size() - 6;
    for (std::size_t i = first; i < cells.size(); ++i) {
      const std::string_view v =
          std::string_view(f_.bytes).substr(cells[i].begin, cells[i].end - cells[i].begin);
      if (!parseNumber(v)) return false;
    }
    if (first == 1 && parseNumber(std::string_view(f_.bytes).substr(cells[0].begin,
                                                                    cells[0].end - cells[0].begin)))
      return false;
    robodk_ = true;
    holes_mode_ = true;
    orient_ = Orientation::kAxis;
    p_.dialect = Dialect::kHoleCsv;
    if (first == 1) col_["id"] = 0;
    const char* const keys[] = {"x", "y", "z", "rx", "ry", "rz"};
    for (std::size_t i = 0; i < 6; ++i) col_[keys[i]] = static_cast<int>(first + i);
    p_.notes.push_back(
        kReadingNotePrefix + f_.path + " has no header: read as RoboDK's target export, columns " +
        std::string(first == 1 ? "name," : "") +
        "x,y,z (mm, work object) and rx,ry,rz (deg, R = Rx(rx) Ry(ry) Rz(rz)); each row is a "
        "hole drilled along the pose's +z" +
        (first == 1 ? "" : ", ids R1..Rn in row order") +
        "; diameter, depth and tolerance come from the cell");
    return true;
  }

  /// The drilling direction of a RoboDK row: +z of R = Rx(rx) Ry(ry) Rz(rz) (deg).
  void robodkAxis(const std::vector<Cell>& cells, std::size_t row, Target& t) {
    double a[3];
    const Col keys[] = {kRx, kRy, kRz};
    for (std::size_t i = 0; i < 3; ++i) {
      const auto v = num(cells, keys[i]);
      if (!v) fail(row, std::string("RoboDK row without ") + kColName[keys[i]]);
      a[i] = v->value * kDeg;
    }
    const Vec3 z = (Eigen::AngleAxisd(a[0], Vec3::UnitX()) *
                    Eigen::AngleAxisd(a[1], Vec3::UnitY()) * Eigen::AngleAxisd(a[2], Vec3::UnitZ()))
                       .toRotationMatrix()
                       .col(2);
    for (std::size_t i = 0; i < 3; ++i) {
      NumberField f;  // derived, not a field of the file: never rewritten
      f.value = z[static_cast<Eigen::Index>(i)];
      t.rot[i] = f;
    }
    if (t.name.empty()) t.name = "R" + std::to_string(data_rows_);
  }

  [[noreturn]] void fail(std::size_t off, const std::string& m) const { failAt(f_, off, m); }

  void resolveColumns() {
    for (std::size_t c = 0; c < kColCount; ++c) {
      const auto it = col_.find(kColName[c]);
      idx_[c] = it == col_.end() ? -1 : it->second;
    }
  }

  void comment(std::size_t off, std::string_view c) {
    std::string t = lower(c);
    while (!t.empty() && t.front() == ' ') t.erase(0, 1);
    for (const char* kw : {"euler:", "rotation:", "convention:"}) {
      if (t.rfind(kw, 0) == 0) {
        euler_ = upper(t.substr(std::string(kw).size()));
        euler_.erase(0, euler_.find_first_not_of(' '));
        euler_.erase(euler_.find_last_not_of(" \r") + 1);
      }
    }
    for (const char* kw : {"frame ", "tool "}) {
      if (t.rfind(kw, 0) == 0) {
        std::string_view rest = c.substr(c.find_first_not_of(' ') + std::string(kw).size());
        const std::size_t colon = rest.find(':');
        if (colon == std::string_view::npos) continue;
        std::string name(rest.substr(0, colon));
        name.erase(name.find_last_not_of(' ') + 1);
        const Pose T = poseFromText(f_, off, rest.substr(colon + 1));
        (std::string(kw) == "frame " ? frames_ : tools_)[upper(name)] =
            Frame{name, true, T, 0, f_.lineOf(off)};
        base_memo_.valid = tool_memo_.valid = false;
      }
    }
  }

  std::vector<Cell> split(std::size_t s, std::size_t e) const {
    std::vector<Cell> cells;
    splitInto(s, e, cells);
    return cells;
  }

  /// The cells of the line [s, e) into `cells` (cleared first).
  void splitInto(std::size_t s, std::size_t e, std::vector<Cell>& cells) const {
    cells.clear();
    const std::string& b = f_.bytes;
    std::size_t i = s;
    while (true) {
      std::size_t cs = i;
      std::size_t ce = i;
      if (i < e && b[i] == '"') {
        std::size_t j = i + 1;
        while (j < e && b[j] != '"') ++j;
        if (j >= e) fail(i, "unterminated quoted CSV cell");
        cs = i + 1;
        ce = j;
        i = j + 1;
        while (i < e && b[i] != delim_) ++i;
      } else {
        while (i < e && b[i] != delim_) ++i;
        ce = i;
      }
      while (cs < ce && (b[cs] == ' ' || b[cs] == '\t')) ++cs;
      while (ce > cs && (b[ce - 1] == ' ' || b[ce - 1] == '\t')) --ce;
      cells.push_back(Cell{static_cast<std::uint32_t>(cs), static_cast<std::uint32_t>(ce)});
      if (i >= e) break;
      ++i;
    }
  }

  void header(std::size_t s, std::size_t e) {
    const std::string_view h = std::string_view(f_.bytes).substr(s, e - s);
    if (h.find(',') == std::string_view::npos) {
      if (h.find(';') != std::string_view::npos)
        delim_ = ';';
      else if (h.find('\t') != std::string_view::npos)
        delim_ = '\t';
    }
    const std::vector<Cell> cells = split(s, e);
    header_cells_ = cells.size();
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const std::string k = columnKey(
          std::string_view(f_.bytes).substr(cells[i].begin, cells[i].end - cells[i].begin));
      if (!k.empty() && col_.count(k) == 0) col_[k] = static_cast<int>(i);
    }
    auto has = [&](std::initializer_list<const char*> ks) {
      for (const char* k : ks) {
        if (col_.count(k) == 0) return false;
      }
      return true;
    };
    if (has({"i", "j", "k"})) {
      orient_ = Orientation::kAxis;
      holes_mode_ = true;
      p_.dialect = Dialect::kHoleCsv;
      if (!has({"id", "x", "y", "z"})) fail(s, "hole list needs the columns id,x,y,z,i,j,k");
      checkColumns(cells, holeListColumns(), "hole list");
      return;
    }
    checkColumns(cells, targetListColumns(), "target list");
    if (has({"a", "b", "c"})) {
      orient_ = Orientation::kKukaAbc;
    } else if (has({"w", "p", "r"})) {
      orient_ = Orientation::kFanucWpr;
    } else if (has({"qw", "qx", "qy", "qz"}) || has({"q1", "q2", "q3", "q4"})) {
      orient_ = Orientation::kQuaternion;
      if (!has({"qw"})) {
        col_["qw"] = col_["q1"];
        col_["qx"] = col_["q2"];
        col_["qy"] = col_["q3"];
        col_["qz"] = col_["q4"];
      }
    } else if (has({"rx", "ry", "rz"})) {
      if (euler_ == "ZYX" || euler_ == "XYZ_FIXED") {
        orient_ = Orientation::kFanucWpr;
        col_["w"] = col_["rx"];
        col_["p"] = col_["ry"];
        col_["r"] = col_["rz"];
      } else if (euler_ == "XYZ_INTRINSIC" || euler_ == "TXYZRXYZ") {
        orient_ = Orientation::kXyzIntrinsic;
      } else {
        fail(s,
             "columns rx,ry,rz need a declared convention: '# euler: ZYX | XYZ_fixed | "
             "XYZ_intrinsic'");
      }
    } else if (!has({"j1", "j2", "j3", "j4", "j5", "j6"})) {
      fail(s,
           "no orientation columns (a,b,c | w,p,r | qw,qx,qy,qz | rx,ry,rz with '# euler:' | "
           "i,j,k) and no j1..j6");
    }
  }

  /// Every column is known and named once (a misspelt `dia` would silently drop every diameter,
  /// a misspelt `conf` every configuration).
  void checkColumns(const std::vector<Cell>& cells, const std::vector<std::string>& known,
                    const std::string& what) const {
    std::unordered_map<std::string, std::size_t> seen;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const std::string_view raw =
          std::string_view(f_.bytes).substr(cells[i].begin, cells[i].end - cells[i].begin);
      const std::string k = columnKey(raw);
      if (k.empty()) continue;
      if (std::find(known.begin(), known.end(), k) == known.end()) {
        std::string hint = didYouMean(k, known);
        if (hint.empty()) {
          hint = " (a " + what;
          hint += " has the columns ";
          for (std::size_t j = 0; j < known.size(); ++j) (hint += j ? "," : "") += known[j];
          hint += ")";
        }
        std::string msg = "unknown column '" + clipForMessage(raw);
        msg += "' in the " + what;
        fail(cells[i].begin, msg + hint);
      }
      if (const auto it = seen.find(k); it != seen.end()) {
        fail(cells[i].begin, "column '" + k + "' is given twice (columns " +
                                 std::to_string(it->second + 1) + " and " + std::to_string(i + 1) +
                                 ")");
      }
      seen[k] = i;
    }
  }

  /// Position of the named cell of a row (for messages), else the row start.
  std::size_t cellOffset(const std::vector<Cell>& cells, Col key, std::size_t row) const {
    const Cell* c = cell(cells, key);
    return c != nullptr ? c->begin : row;
  }

  /// An optional positive size column within [lo, hi] mm.
  std::optional<double> sizeMm(const std::vector<Cell>& cells, Col key, double lo, double hi,
                               const std::string& id, std::size_t row) const {
    const auto v = num(cells, key);
    if (!v) return std::nullopt;
    if (!(v->value >= lo && v->value <= hi) || !(v->value > 0)) {
      const std::string range = lo > 0 ? "outside " + numberText(lo) + ".." + numberText(hi) + " mm"
                                       : "not in (0, " + numberText(hi) + "] mm";
      fail(cellOffset(cells, key, row), "hole " + id + ": " + kColName[key] + " " +
                                            numberText(v->value) + " mm is " + range +
                                            " (hole lists are in mm)");
    }
    return v->value;
  }

  /// A per-hole process value (feed, spindle speed) within [lo, hi] in `unit`.
  std::optional<double> bounded(const std::vector<Cell>& cells, Col key, double lo, double hi,
                                const char* unit, const std::string& id, std::size_t row) const {
    const auto v = num(cells, key);
    if (!v) return std::nullopt;
    if (!(v->value >= lo && v->value <= hi)) {
      fail(cellOffset(cells, key, row), "hole " + id + ": " + kColName[key] + " " +
                                            numberText(v->value) + " " + unit + " is outside " +
                                            numberText(lo) + ".." + numberText(hi) + " " + unit);
    }
    return v->value;
  }

  /// Unit drilling direction: refused when zero or when |n| is off 1 by more than 1e-3.
  Vec3 unitDirection(const Vec3& d, const std::vector<Cell>& cells, const std::string& id,
                     std::size_t row) const {
    const double n = d.norm();
    const std::size_t at = cellOffset(cells, kI, row);
    if (n < 1e-9) fail(at, "hole " + id + ": drilling direction i,j,k is zero");
    if (std::abs(n - 1.0) > kDirectionNormTol) {
      fail(at, "hole " + id + ": drilling direction i,j,k has length " + numberText(n) +
                   ", not 1 (give a unit vector; lengths within 1e-3 of 1 are normalised)");
    }
    return d / n;
  }

  /// All coordinates tiny while distinct holes are sub-mm apart: the file is in metres.
  void checkNotMetres() const {
    if (holes.size() < 2) return;
    double max_abs = 0;
    for (const HoleSpec& h : holes)
      max_abs = std::max(max_abs, h.position_mm.cwiseAbs().maxCoeff());
    if (!(max_abs < kMetresMaxCoordinateMm)) return;
    std::vector<Vec3> p;
    p.reserve(holes.size());
    for (const HoleSpec& h : holes) p.push_back(h.position_mm);
    std::sort(p.begin(), p.end(), [](const Vec3& a, const Vec3& b) { return a.x() < b.x(); });
    double closest = kMetresSpacingMm;
    for (std::size_t a = 0; a < p.size(); ++a) {
      for (std::size_t b = a + 1; b < p.size() && p[b].x() - p[a].x() < closest; ++b) {
        const double d = (p[b] - p[a]).norm();
        if (d > 1e-9 && d < closest) closest = d;
      }
    }
    if (closest >= kMetresSpacingMm) return;
    const HoleSpec& first = holes.front();
    failAt(f_, f_.line_starts[static_cast<std::size_t>(std::max(1, first.line) - 1)],
           "the hole list looks like metres: all " + std::to_string(holes.size()) +
               " holes lie within " + numberText(max_abs) +
               " mm of the workobject origin and some are only " + numberText(closest) +
               " mm apart; hole lists are in mm (multiply by 1000)");
  }

  /// The row's cell of column `key`; nullptr when the file has no such column or the row is short.
  const Cell* cell(const std::vector<Cell>& cells, Col key) const {
    const int i = idx_[key];
    return i >= 0 && static_cast<std::size_t>(i) < cells.size()
               ? &cells[static_cast<std::size_t>(i)]
               : nullptr;
  }

  std::optional<NumberField> num(const std::vector<Cell>& cells, Col key) const {
    const Cell* c = cell(cells, key);
    if (c == nullptr || c->begin == c->end) return std::nullopt;
    return numberField(p_, 0, c->begin, c->end);
  }

  std::string_view text(const std::vector<Cell>& cells, Col key) const {
    const Cell* c = cell(cells, key);
    return c == nullptr ? std::string_view()
                        : std::string_view(f_.bytes).substr(c->begin, c->end - c->begin);
  }

  /// parseConfigurationText, once per distinct text in a run of equal rows.
  const Configuration& configuration(std::string_view text) {
    if (text != conf_text_ || conf_text_.empty()) {
      conf_text_ = text;
      conf_ = parseConfigurationText(conf_text_);
    }
    return conf_;
  }

  /// A motion's frame: the declared one or an unresolved reference, interned. `memo` skips the
  /// lookup and the intern for a run of rows naming the same frame while nothing was added.
  int frameIndex(const std::unordered_map<std::string, Frame>& table, const std::string& ref,
                 FrameMemo& memo) {
    if (memo.valid && memo.frames == p_.frames.size() && memo.ref == ref) return memo.index;
    const auto it = table.find(upper(ref));
    const int index = internFrame(
        p_, it != table.end() ? it->second : Frame{ref, false, Pose::Identity(), -1, 0});
    memo = FrameMemo{true, p_.frames.size(), index, ref};
    return index;
  }

  /// The orientation columns of the file's convention (count 0: none).
  struct RotColumns {
    std::array<Col, 4> col;
    int count;
  };
  RotColumns rotColumns() const {
    if (robodk_) return {{kRx, kRy, kRz, kRz}, 0};  // the axis came from rx,ry,rz
    switch (orient_) {
      case Orientation::kKukaAbc:
        return {{kA, kB, kC, kC}, 3};
      case Orientation::kFanucWpr:
        return {{kW, kP, kR, kR}, 3};
      case Orientation::kQuaternion:
        return {{kQw, kQx, kQy, kQz}, 4};
      case Orientation::kXyzIntrinsic:
        return {{kRx, kRy, kRz, kRz}, 3};
      case Orientation::kAxis:
        return {{kI, kJ, kK, kK}, 3};
      case Orientation::kNone:
        break;
    }
    return {{kA, kB, kC, kC}, -1};
  }

  /// Rotation fields of the row; false when one is missing.
  bool readRotation(const std::vector<Cell>& cells, Target& t) const {
    const RotColumns rc = rotColumns();
    if (rc.count < 0) return false;
    bool all = true;
    for (int i = 0; i < rc.count; ++i) {
      const auto v = num(cells, rc.col[static_cast<std::size_t>(i)]);
      if (v) t.rot[static_cast<std::size_t>(i)] = *v;
      all = all && v.has_value();
    }
    return all;
  }

  /// Joints j1..j6 (true when any) and external axes e1..e6 of the row.
  bool readAxes(const std::vector<Cell>& cells, Target& t) const {
    bool joints = false;
    for (std::size_t i = 0; i < 6; ++i) {
      if (const auto v = num(cells, static_cast<Col>(kJ1 + i))) {
        t.joints[i] = *v;
        joints = true;
      }
    }
    for (std::size_t i = 0; i < 6; ++i) {
      if (const auto v = num(cells, static_cast<Col>(kE1 + i))) t.ext[i] = *v;
    }
    return joints;
  }

  void hole(const std::vector<Cell>& cells, const Target& t, std::size_t s) {
    HoleSpec h;
    h.id = t.name;
    h.line = t.line;
    if (h.id.empty()) fail(s, "hole without an id");
    const auto [dup, fresh] = hole_id_line_.emplace(upper(h.id), h.line);
    if (!fresh) {
      fail(s, "duplicate hole id '" + h.id + "' (first at line " + std::to_string(dup->second) +
                  "; ids are compared without regard to case)");
    }
    h.position_mm = Vec3(t.pos[0].value, t.pos[1].value, t.pos[2].value);
    if (!(h.position_mm.cwiseAbs().maxCoeff() <= kMaxCoordinateMm)) {
      fail(s, "hole " + h.id + ": a coordinate is beyond " + numberText(kMaxCoordinateMm) +
                  " mm from the workobject origin");
    }
    h.direction =
        unitDirection(Vec3(t.rot[0].value, t.rot[1].value, t.rot[2].value), cells, h.id, s);
    h.diameter_mm = sizeMm(cells, kDiameter, kMinDiameterMm, kMaxDiameterMm, h.id, s);
    h.depth_mm = sizeMm(cells, kDepth, kMinDepthMm, kMaxDepthMm, h.id, s);
    h.tolerance_mm = sizeMm(cells, kTolerance, kMinToleranceMm, kMaxToleranceMm, h.id, s);
    h.tool = std::string(text(cells, kTool));
    h.feed_mm_per_rev = bounded(cells, kFeed, kMinFeedMm, kMaxFeedMm, "mm/rev", h.id, s);
    h.spindle_rpm = bounded(cells, kSpindleRpm, kMinSpindleRpm, kMaxSpindleRpm, "1/min", h.id, s);
    holes.push_back(h);
  }

  /// The row's motion to target `target` (one motion per row).
  void rowMotion(const std::vector<Cell>& cells, int target) {
    Motion m;
    const std::string_view move = text(cells, kMove);
    const std::string mv = upper(move.empty() ? text(cells, kMotion) : move);
    m.instruction = p_.addText(mv.empty() ? "row" : mv);
    m.type = (mv == "J" || mv == "PTP" || mv == "MOVEJ" || mv == "MOVEABSJ") ? MotionType::kJoint
                                                                             : MotionType::kLinear;
    m.file = 0;
    const Target& t = p_.target_list[static_cast<std::size_t>(target)];
    m.line = t.line;
    if (const auto v = num(cells, kSpeed)) {
      if (v->value < 0)
        fail(v->offset, "speed " + numberText(v->value) +
                            " mm/s is below zero: no motion runs at it; hint: a speed is > 0 mm/s");
      m.speed_mm_s = v->value;
    }
    if (!t.frame_ref.empty()) m.base = frameIndex(frames_, p_.text(t.frame_ref), base_memo_);
    if (!t.tool_ref.empty()) m.tool = frameIndex(tools_, p_.text(t.tool_ref), tool_memo_);
    m.target = target;
    p_.target_list[static_cast<std::size_t>(target)].uses.push_back(
        static_cast<int>(p_.motions.size()));
    p_.motions.push_back(std::move(m));
  }

  void row(std::size_t s, std::size_t e, int line) {
    splitInto(s, e, cells_);
    const std::vector<Cell>& cells = cells_;
    refuseExtraCells(cells);
    Target t;
    t.file = 0;
    t.line = line;
    const std::string_view id = text(cells, kId);
    t.name = id.empty() ? text(cells, kName) : id;
    const auto x = num(cells, kX);
    const auto y = num(cells, kY);
    const auto z = num(cells, kZ);
    if (x) t.pos[0] = *x;
    if (y) t.pos[1] = *y;
    if (z) t.pos[2] = *z;
    t.orientation = orient_;
    ++data_rows_;
    if (robodk_) robodkAxis(cells, s, t);
    const bool have_rot = robodk_ || readRotation(cells, t);
    const bool joints = readAxes(cells, t);
    const bool cart = x && y && z && have_rot;
    if (!cart && !joints) fail(s, "row has neither a complete pose nor joints j1..j6");
    t.kind = cart ? TargetKind::kCartesian : TargetKind::kJoint;
    if (!cart) t.orientation = Orientation::kNone;
    const std::string_view conf = text(cells, kConf);
    t.config = configuration(conf.empty() ? text(cells, kConfig) : conf);
    t.frame_ref = p_.addText(text(cells, kFrame));
    t.tool_ref = p_.addText(text(cells, kTool));
    if (holes_mode_) hole(cells, t, s);
    p_.target_list.push_back(std::move(t));
    rowMotion(cells, static_cast<int>(p_.target_list.size() - 1));
  }
};

// ---------------------------------------------------------------- JSON with byte spans

struct JValue {
  enum Kind { kNull, kBool, kNumber, kString, kArray, kObject } kind{kNull};
  std::uint32_t begin{0};
  std::uint32_t end{0};
  double number{0};
  std::string str;
  std::vector<std::string> keys;  // object members: keys[i] -> items[i]
  std::vector<JValue> items;      // array elements or object member values
  [[nodiscard]] const JValue* get(std::string_view k) const;
};

const JValue* JValue::get(std::string_view k) const {
  if (kind != kObject) return nullptr;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (keys[i] == k) return &items[i];
  }
  return nullptr;
}

/// JSON reader that keeps byte spans. The elements of the root object's first "targets" array
/// go to a sink one at a time as they are parsed (that array stays empty in the tree), in one
/// reused value: a 100,000-target list never exists as a tree.
class JsonParser {
 public:
  using Sink = std::function<void(const JValue&)>;
  JsonParser(const SourceFile& f, Sink sink)
      : f_(f), b_(f.bytes), i_(f.bom ? 3 : 0), sink_(std::move(sink)) {}
  JValue parse() {
    JValue v;
    valueInto(v, 0);
    ws();
    if (i_ != b_.size()) fail("trailing characters after the JSON document");
    return v;
  }

 private:
  const SourceFile& f_;
  const std::string& b_;
  std::size_t i_;
  Sink sink_;
  bool streamed_{false};
  JValue element_;  ///< the streamed target (its buffers reused)

  [[noreturn]] void fail(const std::string& m) const { failAt(f_, std::min(i_, b_.size()), m); }
  void ws() {
    while (i_ < b_.size() && (b_[i_] == ' ' || b_[i_] == '\t' || b_[i_] == '\n' || b_[i_] == '\r'))
      ++i_;
  }
  /// The string at i_ (a `\` keeps the next byte as it is).
  void stringInto(std::string& s) {
    s.clear();
    ++i_;
    const std::size_t n = b_.size();
    while (true) {
      std::size_t j = i_;
      while (j < n && b_[j] != '"' && b_[j] != '\\') ++j;
      s.append(b_, i_, j - i_);
      i_ = j;
      if (i_ >= n) fail("unterminated string");
      if (b_[i_] == '"') break;
      ++i_;  // backslash
      if (i_ >= n) fail("unterminated string");
      s += b_[i_++];
    }
    ++i_;
  }
  /// Slot `n` of a container being refilled (buffers of earlier contents reused).
  template <class T>
  static T& slot(std::vector<T>& v, std::size_t n) {
    if (n == v.size()) v.emplace_back();
    return v[n];
  }
  void object(JValue& v, int depth) {
    ++i_;
    ws();
    std::size_t n = 0;
    if (i_ < b_.size() && b_[i_] == '}') {
      ++i_;
    } else {
      while (true) {
        ws();
        if (i_ >= b_.size()) fail("unterminated object (missing '}')");
        if (b_[i_] != '"') fail("expected a key string");
        std::string& k = slot(v.keys, n);
        stringInto(k);
        ws();
        if (i_ >= b_.size() || b_[i_] != ':') fail("expected ':'");
        ++i_;
        JValue& item = slot(v.items, n);
        ++n;
        ws();
        if (depth == 0 && sink_ && !streamed_ && k == "targets" && i_ < b_.size() &&
            b_[i_] == '[') {
          streamed_ = true;
          streamTargets(item, depth + 1);
        } else {
          valueInto(item, depth + 1);
        }
        ws();
        if (i_ < b_.size() && b_[i_] == ',') {
          ++i_;
          continue;
        }
        if (i_ < b_.size() && b_[i_] == '}') {
          ++i_;
          break;
        }
        fail("unterminated object (missing '}')");
      }
    }
    v.keys.resize(n);
    v.items.resize(n);
  }
  /// The elements of `[...]` at i_: into v.items, or (stream) each to the sink.
  void array(JValue& v, int depth, bool stream) {
    ++i_;
    ws();
    std::size_t n = 0;
    if (i_ < b_.size() && b_[i_] == ']') {
      ++i_;
    } else {
      while (true) {
        if (stream) {
          valueInto(element_, depth + 1);
          sink_(element_);
        } else {
          valueInto(slot(v.items, n++), depth + 1);
        }
        ws();
        if (i_ < b_.size() && b_[i_] == ',') {
          ++i_;
          continue;
        }
        if (i_ < b_.size() && b_[i_] == ']') {
          ++i_;
          break;
        }
        fail("unterminated array (missing ']')");
      }
    }
    v.keys.clear();
    v.items.resize(n);
  }
  void streamTargets(JValue& v, int depth) {
    v.kind = JValue::kArray;
    v.begin = static_cast<std::uint32_t>(i_);
    array(v, depth, true);
    v.end = static_cast<std::uint32_t>(i_);
  }
  void number(JValue& v) {
    std::size_t j = i_ + 1;
    while (j < b_.size() && (isDigit(b_[j]) || b_[j] == '.' || b_[j] == 'e' || b_[j] == 'E' ||
                             b_[j] == '+' || b_[j] == '-'))
      ++j;
    const auto x = parseNumber(std::string_view(b_).substr(i_, j - i_));
    if (!x) fail("broken number '" + b_.substr(i_, j - i_) + "'");
    v.kind = JValue::kNumber;
    v.number = *x;
    i_ = j;
  }
  /// Parses the value at i_ into v (reusing v's buffers).
  void valueInto(JValue& v, int depth) {
    if (depth > 64) fail("JSON nested too deeply");
    ws();
    if (i_ >= b_.size()) fail("truncated JSON");
    v.begin = static_cast<std::uint32_t>(i_);
    v.number = 0;
    const char c = b_[i_];
    if (c == '{') {
      v.kind = JValue::kObject;
      v.str.clear();
      object(v, depth);
    } else if (c == '[') {
      v.kind = JValue::kArray;
      v.str.clear();
      array(v, depth, false);
    } else {
      v.keys.clear();
      v.items.clear();
      if (c == '"') {
        v.kind = JValue::kString;
        stringInto(v.str);
      } else {
        v.str.clear();
        scalar(v, c);
      }
    }
    v.end = static_cast<std::uint32_t>(i_);
  }
  void scalar(JValue& v, char c) {
    if (c == '-' || isDigit(c)) {
      number(v);
    } else if (b_.compare(i_, 4, "true") == 0 || b_.compare(i_, 4, "null") == 0) {
      v.kind = b_[i_] == 't' ? JValue::kBool : JValue::kNull;
      i_ += 4;
    } else if (b_.compare(i_, 5, "false") == 0) {
      v.kind = JValue::kBool;
      i_ += 5;
    } else {
      fail(std::string("unexpected character '") + c + "'");
    }
  }
};

/// Every member of a JSON object is one `known` name (a misspelt "quaternion_xyzw" would be
/// ignored and the target read without its orientation).
void checkMembers(const SourceFile& f, const JValue& o, const std::vector<std::string>& known,
                  const std::string& what) {
  for (std::size_t i = 0; i < o.keys.size(); ++i) {
    const std::string& k = o.keys[i];
    if (std::find(known.begin(), known.end(), k) != known.end()) continue;
    std::string hint = didYouMean(k, known);
    if (hint.empty()) {
      hint = " (" + what;
      hint += " has the members ";
      for (std::size_t j = 0; j < known.size(); ++j) (hint += j ? ", " : "") += known[j];
      hint += ")";
    }
    std::string msg = "unknown member \"" + clipForMessage(k);
    msg += "\" in " + what;
    failAt(f, o.items[i].begin, msg + hint);
  }
}

Frame jsonFrame(const SourceFile& f, const JValue& v) {
  if (v.kind == JValue::kObject) checkMembers(f, v, jsonFrameMembers(), "a frame");
  const JValue* name = v.get("name");
  const JValue* pos = v.get("position_mm");
  const JValue* q = v.get("quaternion_wxyz");
  Frame fr;
  fr.ref = name != nullptr ? name->str : "";
  fr.file = 0;
  fr.line = f.lineOf(v.begin);
  if (pos != nullptr && q != nullptr && pos->items.size() == 3 && q->items.size() == 4) {
    fr.resolved = true;
    fr.pose.translation() =
        Vec3(pos->items[0].number, pos->items[1].number, pos->items[2].number) * 1e-3;
    Eigen::Quaterniond qq(q->items[0].number, q->items[1].number, q->items[2].number,
                          q->items[3].number);
    if (qq.norm() < 1e-9) failAt(f, v.begin, "zero quaternion");
    fr.pose.linear() = qq.normalized().toRotationMatrix();
  }
  return fr;
}

}  // namespace

void parseCsv(Program& p) {
  CsvReader r(p);
  r.run();
}

std::vector<HoleSpec> parseHoleList(const std::string& path, const std::string& bytes) {
  Program p;
  p.dialect = Dialect::kHoleCsv;
  SourceFile f;
  f.path = path;
  f.bytes = bytes;
  f.indexLines();
  p.files.push_back(std::move(f));
  CsvReader r(p);
  r.run();
  if (p.dialect != Dialect::kHoleCsv)
    throw InputError(path, 1, "not a hole list: the header needs id,x,y,z,i,j,k");
  return r.holes;
}

std::vector<HoleSpec> readHoleList(const std::string& path) {
  return parseHoleList(path, readInputFile(path, InputKind::kHoleList));
}

namespace {

/// Members of a JSON target, in the order of jsonTargetMembers().
enum JMember : std::uint8_t {
  kJId,
  kJName,
  kJPosition,
  kJQuaternion,
  kJX,
  kJY,
  kJZ,
  kJA,
  kJB,
  kJC,
  kJW,
  kJP,
  kJR,
  kJRx,
  kJRy,
  kJRz,
  kJJoints,
  kJExternal,
  kJConfig,
  kJFrame,
  kJTool,
  kJMotion,
  kJSpeed,
  kJFine,
  kJDwell,
  kJHole,
  kJComment,
  kJMemberCount
};

/// Converts the JSON targets one at a time as the parser streams them. Frames and the Euler
/// convention may come after "targets" in the document: frame references are interned and rx,ry,rz
/// targets given their convention in finish(), in target order.
class JsonTargets {
 public:
  explicit JsonTargets(Program& p) : p_(p), f_(p.files[0]) {}

  void target(const JValue& o) {
    if (o.kind != JValue::kObject) failAt(f_, o.begin, "each target must be an object");
    const Members m = members(o);
    Target t;
    t.file = 0;
    t.line = f_.lineOf(o.begin);
    if (m[kJId] != nullptr) t.name = m[kJId]->str;
    position(m, t);
    rotation(m, t, o.begin);
    axes(m, t);
    const bool cart = t.pos[0].present() && t.orientation != Orientation::kNone;
    if (!cart && !std::as_const(t).joints[0].present())
      failAt(f_, o.begin, "target has neither a pose nor joints_deg");
    t.kind = cart ? TargetKind::kCartesian : TargetKind::kJoint;
    if (m[kJConfig] != nullptr) t.config = configuration(m[kJConfig]->str);
    if (m[kJFrame] != nullptr) t.frame_ref = p_.addText(m[kJFrame]->str);
    if (m[kJTool] != nullptr) t.tool_ref = p_.addText(m[kJTool]->str);
    const int line = t.line;
    p_.target_list.push_back(std::move(t));
    motion(m, line);
  }

  /// Interns the motions' frames (declared in `frames` or unresolved) and resolves rx,ry,rz
  /// targets by the document's "euler"; throws at the first such target when it has none.
  void finish(const std::unordered_map<std::string, Frame>& frames, const std::string& euler) {
    if (!rxyz_.empty()) {
      Orientation o = Orientation::kNone;
      if (euler == "ZYX" || euler == "XYZ_FIXED") o = Orientation::kFanucWpr;
      if (euler == "XYZ_INTRINSIC") o = Orientation::kXyzIntrinsic;
      if (o == Orientation::kNone)
        failAt(f_, rxyz_.front().second,
               "rx,ry,rz need a declared \"euler\": \"ZYX\" | \"XYZ_fixed\" | \"XYZ_intrinsic\"");
      for (const auto& r : rxyz_) p_.target_list[static_cast<std::size_t>(r.first)].orientation = o;
    }
    for (std::size_t k = 0; k < p_.motions.size(); ++k) {
      const Target& t = p_.target_list[static_cast<std::size_t>(p_.motions[k].target)];
      if (!t.frame_ref.empty()) p_.motions[k].base = frameIndex(frames, p_.text(t.frame_ref));
      if (!t.tool_ref.empty()) p_.motions[k].tool = frameIndex(frames, p_.text(t.tool_ref));
    }
  }

 private:
  using Members = std::array<const JValue*, kJMemberCount>;
  Program& p_;
  const SourceFile& f_;
  std::vector<std::pair<int, std::uint32_t>> rxyz_;  ///< rx,ry,rz targets and their offsets
  std::string conf_text_;                            ///< last configuration text and its parse
  Configuration conf_;
  std::string memo_ref_;  ///< last frame reference, its index and p_.frames.size() then
  int memo_index_{-1};
  std::size_t memo_frames_{0};

  /// The members of a target by JMember (the first of repeated keys); unknown keys refused.
  Members members(const JValue& o) const {
    Members m{};
    const std::vector<std::string>& known = jsonTargetMembers();
    for (std::size_t i = 0; i < o.keys.size(); ++i) {
      const auto it = std::find(known.begin(), known.end(), o.keys[i]);
      if (it == known.end()) checkMembers(f_, o, known, "a target");
      const auto k = static_cast<std::size_t>(it - known.begin());
      if (m[k] == nullptr) m[k] = &o.items[i];
    }
    return m;
  }

  NumberField field(const JValue& v) const {
    if (v.kind != JValue::kNumber) failAt(f_, v.begin, "expected a number");
    return tokenField(f_, 0, v.begin, v.end, v.number);
  }

  /// Fields a..c of `m` into out[0..2] when all three are given.
  bool triple(const Members& m, JMember a, std::array<NumberField, 4>& out) const {
    if (m[a] == nullptr || m[a + 1] == nullptr || m[a + 2] == nullptr) return false;
    for (std::size_t k = 0; k < 3; ++k) out[k] = field(*m[a + k]);
    return true;
  }

  void position(const Members& m, Target& t) const {
    if (const JValue* pos = m[kJPosition]) {
      if (pos->items.size() != 3) failAt(f_, pos->begin, "position_mm needs 3 numbers");
      for (std::size_t k = 0; k < 3; ++k) t.pos[k] = field(pos->items[k]);
    } else if (m[kJX] != nullptr && m[kJY] != nullptr && m[kJZ] != nullptr) {
      t.pos[0] = field(*m[kJX]);
      t.pos[1] = field(*m[kJY]);
      t.pos[2] = field(*m[kJZ]);
    }
  }

  void rotation(const Members& m, Target& t, std::uint32_t begin) {
    if (const JValue* q = m[kJQuaternion]) {
      if (q->items.size() != 4) failAt(f_, q->begin, "quaternion_wxyz needs 4 numbers");
      for (std::size_t k = 0; k < 4; ++k) t.rot[k] = field(q->items[k]);
      t.orientation = Orientation::kQuaternion;
    } else if (triple(m, kJA, t.rot)) {
      t.orientation = Orientation::kKukaAbc;
    } else if (triple(m, kJW, t.rot)) {
      t.orientation = Orientation::kFanucWpr;
    } else if (triple(m, kJRx, t.rot)) {
      t.orientation = Orientation::kXyzIntrinsic;  // convention set in finish()
      rxyz_.emplace_back(static_cast<int>(p_.target_list.size()), begin);
    }
  }

  void axes(const Members& m, Target& t) const {
    if (const JValue* j = m[kJJoints]) {
      if (j->items.size() > 6) failAt(f_, j->begin, "joints_deg holds at most 6 values");
      for (std::size_t k = 0; k < j->items.size(); ++k) t.joints[k] = field(j->items[k]);
    }
    if (const JValue* e = m[kJExternal]) {
      for (std::size_t k = 0; k < e->items.size() && k < 6; ++k) t.ext[k] = field(e->items[k]);
    }
  }

  const Configuration& configuration(const std::string& text) {
    if (text != conf_text_ || conf_text_.empty()) {
      conf_text_ = text;
      conf_ = parseConfigurationText(conf_text_);
    }
    return conf_;
  }

  /// The motion of the target appended last (its frames come in finish()).
  void motion(const Members& m, int line) {
    Motion mo;
    const std::string& instruction = m[kJMotion] != nullptr ? m[kJMotion]->str : "target";
    mo.instruction = p_.addText(instruction);
    const std::string u = upper(instruction);
    mo.type = (u == "J" || u == "PTP" || u == "MOVEJ" || u == "MOVEABSJ") ? MotionType::kJoint
                                                                          : MotionType::kLinear;
    mo.file = 0;
    mo.line = line;
    if (const JValue* s = m[kJSpeed]; s != nullptr && s->kind == JValue::kNumber) {
      if (s->number < 0)
        failAt(f_, s->begin,
               "speed_mm_s " + numberText(s->number) +
                   " is below zero: no motion runs at it; hint: a speed is > 0 mm/s");
      mo.speed_mm_s = s->number;
    }
    if (const JValue* s = m[kJFine]; s != nullptr)
      mo.fine = f_.bytes.compare(s->begin, 4, "true") == 0;
    mo.target = static_cast<int>(p_.target_list.size() - 1);
    p_.target_list.back().uses.push_back(static_cast<int>(p_.motions.size()));
    p_.motions.push_back(std::move(mo));
  }

  /// internFrame of the frame `ref` names; the last answer reused while no frame was added.
  int frameIndex(const std::unordered_map<std::string, Frame>& frames, const std::string& ref) {
    if (memo_index_ >= 0 && memo_frames_ == p_.frames.size() && memo_ref_ == ref)
      return memo_index_;
    const auto it = frames.find(upper(ref));
    memo_index_ = internFrame(
        p_, it != frames.end() ? it->second : Frame{ref, false, Pose::Identity(), -1, 0});
    memo_ref_ = ref;
    memo_frames_ = p_.frames.size();
    return memo_index_;
  }
};

}  // namespace

void parseJson(Program& p) {
  const SourceFile& f = p.files[0];
  JsonTargets targets(p);
  const JValue root = JsonParser(f, [&targets](const JValue& o) { targets.target(o); }).parse();
  if (root.kind != JValue::kObject) failAt(f, root.begin, "a target list must be a JSON object");
  checkMembers(f, root, jsonRootMembers(), "a JSON target list");
  const JValue* list = root.get("targets");
  if (list == nullptr || list->kind != JValue::kArray)
    failAt(f, root.begin, "a target list needs \"targets\": [...]");
  std::unordered_map<std::string, Frame> frames;
  if (const JValue* fr = root.get("frames"); fr != nullptr && fr->kind == JValue::kArray) {
    for (const JValue& v : fr->items) {
      const Frame g = jsonFrame(f, v);
      frames[upper(g.ref)] = g;
    }
  }
  std::string euler;
  if (const JValue* e = root.get("euler"); e != nullptr) euler = upper(e->str);
  targets.finish(frames, euler);
}

}  // namespace roprec::postproc
