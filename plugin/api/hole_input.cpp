#include "plugin/api/hole_input.hpp"

#include <algorithm>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <exception>
#include <filesystem>
#include <future>
#include <mutex>
#include <unordered_map>

#include "compensator/precision/parallel.hpp"
#include "compensator/support/atomic_file.hpp"
#include "compensator/support/c_format.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/input_file.hpp"
#include "compensator/support/platform.hpp"
#include "postproc/program_stream.hpp"

namespace roprec::api {

std::vector<char> holesSharingTargets(const std::vector<HoleSource>& sources,
                                      const std::vector<char>& included, std::size_t targets) {
  std::vector<int> users(targets, 0);
  std::vector<int> last(targets, -1);  // the last hole that counted as a user
  auto eachTarget = [&](auto&& f) {
    for (std::size_t i = 0; i < sources.size(); ++i) {
      if (!included[i]) continue;
      for (const int t : sources[i].targets) f(i, static_cast<std::size_t>(t));
    }
  };
  eachTarget([&](std::size_t i, std::size_t t) {
    if (last[t] == static_cast<int>(i)) return;
    last[t] = static_cast<int>(i);
    ++users[t];
  });
  std::vector<char> shared(sources.size(), 0);
  eachTarget([&](std::size_t i, std::size_t t) {
    if (users[t] > 1) shared[i] = 1;
  });
  return shared;
}

Mat3 holeFrame(const Vec3& direction) {
  const Vec3 z = direction.normalized();
  const Vec3 ref = std::abs(z.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 y = z.cross(ref).normalized();
  const Vec3 x = y.cross(z);
  Mat3 R;
  R << x, y, z;
  return R;
}

std::string programToolKey(const std::string& ref) {
  for (const char* table : {"TOOL_DATA[", "UTOOL["}) {
    const std::string t(table);
    if (ref.size() > t.size() + 1 && ref.compare(0, t.size(), t) == 0 && ref.back() == ']')
      return ref.substr(t.size(), ref.size() - t.size() - 1);
  }
  return ref;
}

std::vector<const XmlNode*> cellDrills(const CellSpec& cell) {
  if (!cell.has_process || cell.process.str("type", "") != "drilling") return {};
  return cell.process.childrenNamed("drill");
}

namespace {

/// Whether the cell's process has more than one <drill> (a tool table): only then does a hole's
/// tool select its drill (HoleRequest::drill); a single drill drills every hole.
bool hasToolTable(const CellSpec& cell) {
  if (!cell.has_process) return false;
  int drills = 0;
  for (const XmlNode& c : cell.process.children) drills += c.name == "drill" ? 1 : 0;
  return drills > 1;
}

std::string toolTableText(const std::vector<const XmlNode*>& drills) {
  std::string t;
  for (const XmlNode* d : drills) {
    if (!t.empty()) t += ", ";
    t += d->str("tool", "?") + " (Ø" + d->str("diameter_mm", "?") + " mm)";
  }
  return t;
}

}  // namespace

void assignDrill(const CellSpec& cell, const std::string& tool, const std::string& named_as,
                 const std::string& file, int line, HoleRequest& r) {
  if (!hasToolTable(cell)) return;
  const std::vector<const XmlNode*> drills = cellDrills(cell);
  if (!tool.empty()) {
    for (size_t i = 0; i < drills.size(); ++i) {
      if (sameToolKey(drills[i]->str("tool", ""), tool)) {
        r.drill = static_cast<int>(i);
        r.tool = drills[i]->str("tool");
        return;
      }
    }
    throw InputError(file, line,
                     "hole " + clipForMessage(r.id) + " is drilled with tool " + named_as +
                         ", which the cell's tool table does not have (tools: " +
                         toolTableText(drills) + "); hint: add <drill tool=\"" + tool +
                         "\" .../> to the cell's <process> (" + cell.file + ")");
  }
  int found = -1;
  for (size_t i = 0; i < drills.size() && r.diameter > 0; ++i) {
    const double d = drills[i]->number("diameter_mm", 0.0) * 1e-3;
    if (std::abs(d - r.diameter) > 1e-6) continue;
    if (found >= 0) {
      found = -2;
      break;
    }
    found = static_cast<int>(i);
  }
  if (found >= 0) {
    r.drill = found;
    r.tool = drills[static_cast<size_t>(found)]->str("tool");
    return;
  }
  throw InputError(file, line,
                   "hole " + clipForMessage(r.id) +
                       ": nothing says which drill of the cell's tool table drills it (tools: " +
                       toolTableText(drills) +
                       "); hint: select the tool in the program (KRL $TOOL/BAS(#TOOL,n), RAPID "
                       "tooldata, FANUC UTOOL_NUM / UT) or give the hole list a tool column (or "
                       "a diameter only one drill has)");
}

namespace {

/// The hole-list row's own process: its tool's drill, feed and spindle speed.
void holeListProcess(const postproc::HoleSpec& s, const CellSpec& cell, const std::string& file,
                     HoleRequest& r) {
  if (s.feed_mm_per_rev) r.feed = *s.feed_mm_per_rev * 1e-3;
  if (s.spindle_rpm) r.spindle_rpm = *s.spindle_rpm;
  assignDrill(cell, s.tool, s.tool, file, s.line, r);
}

HoleRequest fromSpec(const postproc::HoleSpec& s, const CellSpec& cell) {
  HoleRequest r;
  r.id = s.id;
  Pose T_wobj_tcp = Pose::Identity();
  T_wobj_tcp.translation() = s.position_mm * 1e-3;
  T_wobj_tcp.linear() = holeFrame(s.direction);
  r.T_W_tcp = cell.T_base_wobj * T_wobj_tcp;
  if (s.tolerance_mm) r.tolerance = *s.tolerance_mm * 1e-3;
  if (s.diameter_mm) r.diameter = *s.diameter_mm * 1e-3;
  if (s.depth_mm) r.depth = *s.depth_mm * 1e-3;
  r.line = s.line;
  r.evidence = "on the hole list";
  return r;
}

/// The tool key of recognised hole `h` (its bottom motion's tool) and how the program names it;
/// empty when the program names none.
std::pair<std::string, std::string> holeTool(const postproc::Program& p, const postproc::Hole& h) {
  if (h.tool < 0) return {};
  const std::string& ref = p.frames[static_cast<size_t>(h.tool)].ref;
  return {programToolKey(ref), ref};
}

std::optional<VendorConfig> programConfig(const postproc::Configuration& c, const Robot& robot,
                                          const std::string& file, int line) {
  if (!c.present()) return std::nullopt;
  const Vendor v = robot.card.vendor;
  const bool match = (v == Vendor::kKuka && c.vendor == postproc::Vendor::kKuka) ||
                     (v == Vendor::kAbb && c.vendor == postproc::Vendor::kAbb) ||
                     (v == Vendor::kFanuc && c.vendor == postproc::Vendor::kFanuc);
  if (!match) return std::nullopt;
  if (v == Vendor::kKuka && c.status < 0)
    return std::nullopt;  // S absent: nothing selects a branch
  return parseConfig(v, c.text(), file, line);
}

/// The joints (URDF, rad) of the nearest joint target (MoveAbsJ, PTP to an axis target, FANUC
/// joint position) programmed before motion `until` and after motion `after`: the arm posture the
/// linear moves of a cycle start from (docs/configuration.md §6).
std::optional<Vec6> programmedJointsBefore(const postproc::Program& p, const Robot& robot,
                                           int after, int until) {
  for (int mi = until - 1; mi > after && mi >= 0; --mi) {
    const postproc::Motion& mo = p.motions[static_cast<size_t>(mi)];
    if (mo.target < 0) continue;
    const postproc::Target& t = p.targets()[static_cast<size_t>(mo.target)];
    if (t.kind != postproc::TargetKind::kJoint) continue;
    Vec6 qc;
    for (size_t k = 0; k < 6; ++k) {
      if (!t.joints[k].known()) return std::nullopt;
      qc[static_cast<Eigen::Index>(k)] = t.joints[k].value * kDeg;
    }
    return fromControllerJoints(robot.card, qc);
  }
  return std::nullopt;
}

/// At most this many ids are listed in a note about unmatched holes.
constexpr std::size_t kListedIds = 20;

std::string idList(const std::vector<std::string>& ids) {
  std::string out;
  for (std::size_t i = 0; i < ids.size() && i < kListedIds; ++i) out += (i ? ", " : "") + ids[i];
  if (ids.size() > kListedIds) out += " and " + std::to_string(ids.size() - kListedIds) + " more";
  return out;
}

std::string fileName(const std::string& path) {
  const auto slash = path.find_last_of(platform::kPathSeparators);
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

/// Throws when the hole list matches no job hole; notes which holes and entries stay unmatched.
/// `spec_of_hole[i]` is the list entry of job hole i (-1: none).
/// Holes whose program drill point lies off their hole-list axis by more than --match-tol, in
/// the world frame (an id match does not compare positions; a program frame and a cell
/// workobject that disagree move every hole by the same offset).
struct FarFromTheList {
  int count{0};
  double max_m{0};
  std::string worst;

  void add(const HoleRequest& r, double tol_mm) {
    if (!r.nominal_axis) return;
    const auto& [p0, a] = *r.nominal_axis;
    const Vec3 d = r.T_W_tcp.translation() - p0;
    const double off = (d - a * a.dot(d)).norm();
    if (!(off * 1e3 > tol_mm)) return;
    ++count;
    if (off > max_m) {
      max_m = off;
      worst = r.id;
    }
  }

  void note(JobHoles& job, double tol_mm) const {
    if (count == 0) return;
    job.notes.push_back("--holes: warning: " + std::to_string(count) + " of " +
                        std::to_string(job.requests.size()) +
                        " drill points of the program lie off their hole-list axis by more than "
                        "--match-tol " +
                        numberText(tol_mm) + " mm (up to " + numberText(max_m * 1e3, 4) +
                        " mm, hole " + worst +
                        "); check that the program's base frame and the cell's <workobject> "
                        "are the same frame");
  }
};

void reportMatching(JobHoles& job, const std::string& list_path,
                    const std::vector<postproc::HoleSpec>& specs,
                    const std::vector<int>& spec_of_hole, const std::string& how) {
  const std::string name = fileName(list_path);
  const std::size_t matched = static_cast<std::size_t>(
      std::count_if(spec_of_hole.begin(), spec_of_hole.end(), [](int s) { return s >= 0; }));
  if (matched == 0) {
    throw InputError(list_path, specs.empty() ? 1 : specs.front().line,
                     "--holes: none of the " + std::to_string(specs.size()) +
                         " entries of the hole list matches one of the " +
                         std::to_string(spec_of_hole.size()) + " holes of " + fileName(job.path) +
                         " (" + how +
                         "); is it the list of this program, in the cell's workobject frame?");
  }
  std::vector<std::string> lonely_holes;
  for (std::size_t i = 0; i < spec_of_hole.size(); ++i) {
    if (spec_of_hole[i] < 0) {
      const HoleRequest& r = job.requests[i];
      lonely_holes.push_back(r.line > 0 ? r.id + " (line " + std::to_string(r.line) + ")" : r.id);
    }
  }
  std::vector<bool> used(specs.size(), false);
  for (const int s : spec_of_hole)
    if (s >= 0) used[static_cast<std::size_t>(s)] = true;
  std::vector<std::string> lonely_specs;
  for (std::size_t s = 0; s < specs.size(); ++s) {
    if (!used[s])
      lonely_specs.push_back(specs[s].id + " (line " + std::to_string(specs[s].line) + ")");
  }
  if (!lonely_holes.empty()) {
    job.notes.push_back(
        "--holes: " + std::to_string(lonely_holes.size()) + " of " +
        std::to_string(spec_of_hole.size()) + " holes of " + fileName(job.path) +
        " have no entry in " + name + " (" + how +
        "; they keep the program's values and the cell's tolerance): " + idList(lonely_holes));
  }
  if (!lonely_specs.empty()) {
    job.notes.push_back("--holes: " + std::to_string(lonely_specs.size()) + " of " +
                        std::to_string(specs.size()) + " entries of " + name +
                        " match no hole of " + fileName(job.path) + ": " + idList(lonely_specs));
  }
}

}  // namespace

namespace {

/// Hole i's request and its place in the program (`spec`: its hole-list entry, -1 for none).
/// Reads only: the holes are set up on several threads. Throws InputError when the drill point
/// is not a plain Cartesian target or a target's configuration flags are not the robot's.
void setUpHole(const std::vector<postproc::Hole>& recognized, const postproc::Program& p,
               const CellSpec& cell, const Robot& robot,
               const std::vector<postproc::HoleSpec>& specs, int spec, size_t i, HoleRequest& r,
               HoleSource& src) {
  const postproc::Hole& h = recognized[i];
  src.hole = static_cast<int>(i);
  src.base = h.base;
  src.targets = h.targets;
  src.bottom_target = h.bottom_target;
  const postproc::Frame* base = h.base >= 0 ? &p.frames[static_cast<size_t>(h.base)] : nullptr;
  if (base && base->resolved) {
    src.T_W_frame = base->pose;
    src.frame_resolved = true;
    src.frame_ref = base->ref;
  } else {
    src.T_W_frame = cell.T_base_wobj;
    src.frame_ref = base ? base->ref : "(none)";
  }
  const postproc::Target& t = p.targets()[static_cast<size_t>(h.bottom_target)];
  const std::optional<Pose> T_frame_tcp =
      postproc::motionPose(p, p.motions[static_cast<size_t>(h.bottom_motion)]);
  if (!T_frame_tcp) {
    throw InputError(p.files[static_cast<size_t>(t.file)].path, t.line,
                     "hole " + h.id + ": the drill point is not a plain Cartesian target");
  }
  r.id = h.id;
  r.T_W_tcp = src.T_W_frame * *T_frame_tcp;
  r.line = t.line;
  r.evidence = postproc::drillingEvidence(p, h);
  r.depth = h.depth;
  if (h.surface_motion >= 0) r.surface_W = Vec3(src.T_W_frame * h.surface);
  // The drill point is reached by linear moves, which keep the arm configuration the robot had:
  // the configuration that selects the IK branch is the one of the cycle's approach when the
  // controller honours it there (KUKA PTP, ABB MoveJ with ConfJ\On, FANUC J), else the bottom
  // target's when honoured; otherwise none (continuity from the previous hole).
  for (const int mi : {h.entry_motion, h.bottom_motion}) {
    if (mi < 0 || r.config) continue;
    const postproc::Motion& mo = p.motions[static_cast<size_t>(mi)];
    if (!mo.config_honoured || mo.target < 0) continue;
    const postproc::Target& ct = p.targets()[static_cast<size_t>(mo.target)];
    r.config = programConfig(ct.config, robot, p.files[static_cast<size_t>(ct.file)].path, ct.line);
  }
  // The flags written at the drill point (honoured or not: the compensation keeps them), and the
  // posture the cycle starts from: the joint target programmed since the previous hole.
  r.written_config =
      r.config ? r.config
               : programConfig(t.config, robot, p.files[static_cast<size_t>(t.file)].path, t.line);
  r.ik_seed = programmedJointsBefore(p, robot, i > 0 ? recognized[i - 1].bottom_motion : -1,
                                     h.bottom_motion);
  if (spec >= 0) {
    const postproc::HoleSpec& s = specs[static_cast<size_t>(spec)];
    r.id = s.id;
    r.nominal_axis = std::make_pair(Vec3(cell.T_base_wobj * (s.position_mm * 1e-3)),
                                    Vec3(cell.T_base_wobj.linear() * s.direction.normalized()));
    if (s.tolerance_mm) r.tolerance = *s.tolerance_mm * 1e-3;
    if (s.diameter_mm) r.diameter = *s.diameter_mm * 1e-3;
    if (s.depth_mm) r.depth = *s.depth_mm * 1e-3;
    if (s.feed_mm_per_rev) r.feed = *s.feed_mm_per_rev * 1e-3;
    if (s.spindle_rpm) r.spindle_rpm = *s.spindle_rpm;
  }
  if (hasToolTable(cell)) {
    const auto [key, ref] = holeTool(p, h);
    const std::string list_tool = spec >= 0 ? specs[static_cast<size_t>(spec)].tool : "";
    const postproc::Motion& mo = p.motions[static_cast<size_t>(h.bottom_motion)];
    const std::string& file = p.files[static_cast<size_t>(std::max(0, mo.file))].path;
    if (!key.empty())
      assignDrill(cell, key, ref, file, mo.line, r);
    else
      assignDrill(cell, list_tool, list_tool, file, mo.line, r);
  }
}

/// setUpHole over holes [begin, end) on `threads` workers, hole i into requests[i - begin] and
/// sources[i - begin]; with null arrays into a scratch pair per worker (a check that every hole
/// can be set up). The error of the first failing hole (in hole order) is rethrown.
void setUpRange(const postproc::Program& p, const std::vector<postproc::Hole>& recognized,
                const CellSpec& cell, const Robot& robot,
                const std::vector<postproc::HoleSpec>& specs, const std::vector<int>& spec_of_hole,
                size_t begin, size_t end, int threads, HoleRequest* requests, HoleSource* sources) {
  const int workers = std::max(1, threads);
  std::vector<std::pair<size_t, std::exception_ptr>> failed(static_cast<size_t>(workers),
                                                            {end, nullptr});
  std::vector<HoleRequest> scratch_r(requests ? 0 : static_cast<size_t>(workers));
  std::vector<HoleSource> scratch_s(sources ? 0 : static_cast<size_t>(workers));
  parallelFor(end - begin, workers, [&](int w, size_t k) {
    const size_t i = begin + k;
    const auto wi = static_cast<size_t>(w);
    try {
      HoleRequest& r = requests ? requests[k] : (scratch_r[wi] = HoleRequest{});
      HoleSource& src = sources ? sources[k] : (scratch_s[wi] = HoleSource{});
      setUpHole(recognized, p, cell, robot, specs, spec_of_hole.empty() ? -1 : spec_of_hole[i], i,
                r, src);
    } catch (...) {
      auto& f = failed[wi];
      if (i < f.first) f = {i, std::current_exception()};
    }
  });
  const auto first = std::min_element(
      failed.begin(), failed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  if (first->second) std::rethrow_exception(first->second);
}

/// A single-drill cell drills every hole with its drill: a job whose holes name two tools (the
/// program changes tools, or the hole list's tool column does) is refused at the first hole of
/// the second tool. Fed the job's holes in order.
class OneToolForOneDrill {
 public:
  explicit OneToolForOneDrill(const CellSpec& cell)
      : on_(!hasToolTable(cell) && !cellDrills(cell).empty()) {}
  void check(const std::string& key, const std::string& ref, const std::string& file, int line) {
    if (!on_ || key.empty()) return;
    if (first_.empty()) {
      first_ = key;
      first_ref_ = ref;
      first_at_ = file + ":" + std::to_string(line);
      return;
    }
    if (sameToolKey(first_, key)) return;
    throw InputError(file, line,
                     "the job changes tools (" + first_ref_ + " at " + first_at_ + ", then " + ref +
                         ") but the cell has a single drill, which would drill every hole; hint: "
                         "give the cell a tool table, one <drill tool=\"n\" .../> per tool "
                         "(docs/process.md §8, tool table)");
  }
  /// Program hole `h`.
  void check(const postproc::Program& p, const postproc::Hole& h) {
    if (!on_) return;
    const auto [key, ref] = holeTool(p, h);
    const postproc::Motion& mo = p.motions[static_cast<size_t>(h.bottom_motion)];
    check(key, ref, p.files[static_cast<size_t>(std::max(0, mo.file))].path, mo.line);
  }

 private:
  bool on_;
  std::string first_, first_ref_, first_at_;
};

void requireOneToolForOneDrill(const JobHoles& job, const CellSpec& cell,
                               const std::vector<postproc::HoleSpec>& specs,
                               const std::string& path) {
  OneToolForOneDrill one(cell);
  if (job.is_hole_list) {
    for (const postproc::HoleSpec& s : specs) one.check(s.tool, "tool " + s.tool, path, s.line);
    return;
  }
  for (const postproc::Hole& h : job.recognized) one.check(*job.program, h);
}

/// The frame uses of program holes (HoleFrameUse), appended to `uses` for the holes whose base
/// frame or tool no hole before them had (`seen`: base and tool frames met so far).
void addFrameUses(const postproc::Program& p, const std::vector<postproc::Hole>& holes,
                  size_t begin, std::vector<char>& seen, std::vector<HoleFrameUse>& uses) {
  for (size_t i = begin; i < holes.size(); ++i) {
    const postproc::Hole& h = holes[i];
    const postproc::Motion& mo = p.motions[static_cast<size_t>(h.bottom_motion)];
    seen.resize(2 * p.frames.size(), 0);
    const bool new_base = h.base >= 0 && !seen[2 * static_cast<size_t>(h.base)];
    const bool new_tool = mo.tool >= 0 && !seen[2 * static_cast<size_t>(mo.tool) + 1];
    if (!new_base && !new_tool) continue;
    if (h.base >= 0) seen[2 * static_cast<size_t>(h.base)] = 1;
    if (mo.tool >= 0) seen[2 * static_cast<size_t>(mo.tool) + 1] = 1;
    uses.push_back({h.id, h.base, mo.tool, mo.file, mo.line});
  }
}

/// The note on the first hole whose base frame the program does not define (setUpHole:
/// frame_resolved); false when hole `h`'s is defined.
bool noteUndefinedBase(JobHoles& job, const postproc::Program& p, const postproc::Hole& h) {
  const postproc::Frame* base = h.base >= 0 ? &p.frames[static_cast<size_t>(h.base)] : nullptr;
  if (base && base->resolved) return false;
  job.notes.push_back("program base frame " + (base ? base->ref : std::string("(none)")) +
                      " is not defined in the program: the cell's <workobject> is used as that "
                      "frame");
  return true;
}

/// The note that says which holes the cell's single drill drills although nothing in the job
/// says so: the holes without a diameter of their own (a hole list's diameter scales the drill).
void noteDefaultDrill(JobHoles& job, const CellSpec& cell) {
  const std::vector<const XmlNode*> drills = cellDrills(cell);
  if (drills.size() != 1) return;
  size_t n = 0;
  std::string first;
  const size_t holes = job.hole_count;
  for (size_t i = 0; i < job.requests.size(); ++i) {
    if (job.requests[i].diameter > 0) continue;
    if (n++ == 0) first = job.requests[i].id;
  }
  if (job.deferred) n = holes;  // a deferred job has no hole list: no hole has a diameter
  if (n == 0) return;
  const XmlNode& d = *drills.front();
  job.notes.push_back(
      "drill: " + std::to_string(n) + " of " + std::to_string(holes) + " holes (the first " +
      (job.deferred ? job.first_hole_id : first) +
      ") state no drill or diameter: drilled with the cell's single drill Ø" +
      d.str("diameter_mm") + " mm and its <cut> (" + cell.file +
      "); hint: a hole list with diameters, or a tool table in the cell selected by the "
      "program's tool numbers, gives each hole its drill");
}

/// The error of a program without a drill cycle, at its first motion (or its first line when it
/// has none).
[[noreturn]] void throwNoDrillCycle(const postproc::Program& p, const std::string& path) {
  // point at the program's first motion (or its first line when it has none)
  std::string where = path;
  int line = 1;
  if (!p.motions.empty()) {
    const postproc::Motion& m0 = p.motions.front();
    if (m0.file >= 0 && static_cast<std::size_t>(m0.file) < p.files.size())
      where = p.files[static_cast<std::size_t>(m0.file)].path;
    line = std::max(1, m0.line);
  }
  std::string unknown;  // values roprec cannot evaluate cut cycles short
  if (!p.unresolved.empty()) {
    const postproc::Unresolved& u = p.unresolved.front();
    unknown = "; " + std::to_string(p.unresolved.size()) +
              " reference(s) roprec cannot resolve, the first '" + u.ref + "' at line " +
              std::to_string(u.line) + " (" + u.what + ")";
  }
  throw InputError(where, line,
                   "no drill cycle recognised in the program's " +
                       std::to_string(p.motions.size()) +
                       " motions (approach -> feed along the tool z axis -> retract)" + unknown +
                       "; hint: a hole list (.csv) or --holes gives the holes directly");
}

/// The program's own notes and its unresolved references as job notes.
void addProgramNotes(JobHoles& job, const postproc::Program& p) {
  for (const auto& note : p.notes) job.notes.push_back(note);
  for (const auto& u : p.unresolved) {
    const std::string& file = p.files[static_cast<size_t>(std::max(0, u.file))].path;
    const std::string where = u.line > 0 ? file + ":" + std::to_string(u.line) : file;
    // a frame the program names but does not define is resolved (or refused) by the job's
    // frame and tool resolution, which states it; a value roprec cannot know is a warning
    const bool frame = std::any_of(p.frames.begin(), p.frames.end(),
                                   [&](const postproc::Frame& f) { return f.ref == u.ref; });
    job.notes.push_back((frame ? "program frame " : kUnresolvedPrefix) + u.ref + " (" + where +
                        "): " + u.what);
  }
}

}  // namespace

/// The holes of a KRL program read by windows (postproc::ProgramStream), window after window:
/// before the next window is read, the motions behind the last hole given are retired.
class ProgramHoles {
 public:
  /// With threads > 1 the program's next window is read and lexed ahead on a task of its own.
  ProgramHoles(const std::string& path, int threads)
      : stream_(path, postproc::ProgramStream::kWindowBytes, threads > 1) {}
  ProgramHoles(const ProgramHoles&) = delete;
  ProgramHoles& operator=(const ProgramHoles&) = delete;
  ~ProgramHoles() { stopProducer(); }
  [[nodiscard]] bool windowed() const { return stream_.windowed(); }
  /// Reads on to the next holes: false once the program is read and every hole given.
  bool next() {
    retireBehind();
    while (!ended_) {
      if (stream_.next()) {
        rec_.advance(stream_.program(), false);
      } else {
        rec_.advance(stream_.program(), true);
        ended_ = true;
      }
      std::vector<postproc::Hole> fresh = rec_.take();
      if (fresh.empty()) continue;
      for (postproc::Hole& h : fresh) holes_.push_back(std::move(h));
      return true;
    }
    return false;
  }
  [[nodiscard]] postproc::Program& program() { return stream_.program(); }
  /// The window's holes: the hole before the new ones first (its bottom motion bounds the
  /// joint target the next hole starts from) when there is one, then the new ones.
  [[nodiscard]] const std::vector<postproc::Hole>& holes() const { return holes_; }
  [[nodiscard]] size_t firstNew() const { return first_new_; }
  /// Hands the set-up of the job's next `end - begin` holes (begin: the count handed so far).
  void take(const JobHoles& job, const CellSpec& cell, const Robot& robot, size_t begin, size_t end,
            int threads, std::vector<HoleRequest>& requests, std::vector<HoleSource>& sources) {
    if (begin != given_) throw InternalError("ProgramHoles::take: holes asked for out of order");
    requests.clear();
    sources.clear();
    while (given_ < end) {
      if (ready_ == ready_r_.size()) {
        if (threads > 1) {
          takeBatch(job, cell, robot);
        } else {
          setUpNext(job, cell, robot, threads);
        }
      }
      requests.push_back(std::move(ready_r_[ready_]));
      sources.push_back(std::move(ready_s_[ready_]));
      ++ready_;
      ++given_;
    }
    if (given_ == job.hole_count) stopProducer();  // it reads nothing the job needs any more
  }

 private:
  void retireBehind() {
    if (holes_.empty()) return;
    postproc::Hole last = std::move(holes_.back());
    holes_.clear();
    const size_t keep = std::min(static_cast<size_t>(last.bottom_motion), rec_.nextMotion() - 1);
    const postproc::Retired r = stream_.retire(keep);
    rec_.retired(r.motions, r.target_begin, r.target_end);
    last.bottom_motion -= static_cast<int>(r.motions);
    holes_.push_back(std::move(last));
    first_new_ = 1;
  }
  /// The next window's holes set up (base frames applied) into the ready list (one thread).
  void setUpNext(const JobHoles& job, const CellSpec& cell, const Robot& robot, int threads) {
    if (!next()) throw InternalError("ProgramHoles: fewer holes than the first reading found");
    setUpWindow(job, cell, robot, threads, ready_r_, ready_s_);
    ready_ = 0;
  }
  /// The new holes of the window read last, set up (base frames applied) into r and s.
  void setUpWindow(const JobHoles& job, const CellSpec& cell, const Robot& robot, int threads,
                   std::vector<HoleRequest>& r, std::vector<HoleSource>& s) {
    const size_t n = holes_.size() - first_new_;
    r.assign(n, HoleRequest{});
    s.assign(n, HoleSource{});
    setUpRange(program(), holes_, cell, robot, {}, {}, first_new_, holes_.size(), threads, r.data(),
               s.data());
    for (size_t k = 0; k < n; ++k) applyBaseFrame(job, r[k], s[k]);
  }

  /// With threads > 1 a task of its own reads the program on and sets its windows' holes up,
  /// up to kBatches windows ahead of the holes taken: the reading runs whenever a core is free,
  /// not in step with the prediction. A batch holds one window's holes, or the error that
  /// stopped the task (the reader's or a set-up's, where the one-thread reading throws it), or
  /// the end of the program.
  struct Batch {
    std::vector<HoleRequest> requests;
    std::vector<HoleSource> sources;
    std::exception_ptr error;
    bool end{false};
  };
  static constexpr size_t kBatches = 2;
  /// The task: batch after batch until the end, an error, or stopProducer(). `job`: the base
  /// frames alone (a copy: the task never reads the job, which may go first).
  void produce(const JobHoles& job, const CellSpec& cell, const Robot& robot) {
    try {
      while (true) {
        Batch b;
        b.end = !next();
        if (!b.end) setUpWindow(job, cell, robot, 1, b.requests, b.sources);
        const bool end = b.end;
        if (!push(std::move(b)) || end) return;
      }
    } catch (...) {
      Batch b;
      b.error = std::current_exception();
      push(std::move(b));
    }
  }
  /// Queues `b` once there is room; false when stopped.
  bool push(Batch&& b) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return stop_ || batches_.size() < kBatches; });
    if (stop_) return false;
    batches_.push_back(std::move(b));
    changed_.notify_all();
    return true;
  }
  /// Stops the task and waits for it (its errors are no one's any more). The cell and robot it
  /// reads outlive it: it is stopped once the job's last hole is taken, or by the destructor
  /// (the job's, before the cell's and the robot's: PredictionContext).
  void stopProducer() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    changed_.notify_all();
    if (producer_.valid()) producer_.wait();
  }
  /// The next batch into the ready list (the task started on the first call).
  void takeBatch(const JobHoles& job, const CellSpec& cell, const Robot& robot) {
    if (!producer_.valid()) {
      frames_.base_frames = job.base_frames;
      producer_ =
          std::async(std::launch::async, [this, &cell, &robot] { produce(frames_, cell, robot); });
    }
    Batch b;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [this] { return !batches_.empty(); });
      b = std::move(batches_.front());
      batches_.pop_front();
    }
    changed_.notify_all();
    if (b.error) std::rethrow_exception(b.error);
    if (b.end) throw InternalError("ProgramHoles: fewer holes than the first reading found");
    ready_r_ = std::move(b.requests);
    ready_s_ = std::move(b.sources);
    ready_ = 0;
  }

  postproc::ProgramStream stream_;
  postproc::HoleRecognizer rec_;
  std::vector<postproc::Hole> holes_;
  size_t first_new_{0};
  bool ended_{false};
  std::vector<HoleRequest> ready_r_;
  std::vector<HoleSource> ready_s_;
  size_t ready_{0};
  size_t given_{0};
  std::mutex mutex_;  ///< guards batches_ and stop_
  std::condition_variable changed_;
  std::deque<Batch> batches_;
  bool stop_{false};
  JobHoles frames_;             ///< the job's base frames, for the set-up task
  std::future<void> producer_;  ///< the set-up task (threads > 1); last: stopped first
};

namespace {

/// The requests a streamed job keeps (loadJobHoles' keep_requests), set up in place: `to` is
/// reserved once, when the first holes are met, for the holes the whole file holds at the first
/// window's holes per byte (and a quarter more); its pages are touched only as the requests
/// fill it, so a reservation above the count costs no memory. Holes past it (a program denser
/// in holes further on) go to chunks of their own, moved into `to` at the end (their pages
/// touched twice, as a request in a chunk is freed once moved: about one chunk more than the
/// requests at the peak).
class KeptRequests {
 public:
  explicit KeptRequests(std::vector<HoleRequest>& to) : to_(to) {}
  /// Room for the next `n` requests (default values), `window`: the window they were read in.
  HoleRequest* add(size_t n, const postproc::SourceFile& window) {
    if (!reserved_) reserve(n, window);
    if (chunks_.empty() && to_.size() + n <= to_.capacity()) {
      to_.resize(to_.size() + n);
      return to_.data() + to_.size() - n;
    }
    if (chunks_.empty() || chunks_.back().size() + n > std::max(kChunk, n)) {
      chunks_.emplace_back();
      chunks_.back().reserve(std::max(kChunk, n));
    }
    std::vector<HoleRequest>& c = chunks_.back();
    c.resize(c.size() + n);
    return c.data() + c.size() - n;
  }
  /// Moves the chunks' requests into `to` (after the requests set up in place).
  void finish() {
    if (chunks_.empty()) return;
    size_t count = to_.size();
    for (const std::vector<HoleRequest>& c : chunks_) count += c.size();
    to_.reserve(count);
    for (std::vector<HoleRequest>& c : chunks_) {
      for (HoleRequest& r : c) to_.push_back(std::move(r));
      std::vector<HoleRequest>().swap(c);
    }
    chunks_.clear();
  }

 private:
  static constexpr size_t kChunk = 65536;  // 37 MB: above the allocator's largest heap block
  void reserve(size_t n, const postproc::SourceFile& window) {
    reserved_ = true;
    std::error_code ec;
    const auto file = std::filesystem::file_size(window.path, ec);
    if (ec || window.bytes.empty()) return;
    const double holes = static_cast<double>(n) * static_cast<double>(file) /
                         static_cast<double>(window.bytes.size());
    try {
      to_.reserve(static_cast<size_t>(holes * 1.25) + n + 1024);
    } catch (const std::bad_alloc&) {
      // no such address range: the chunks take them all
    } catch (const std::length_error&) {
    }
  }
  std::vector<HoleRequest>& to_;
  std::vector<std::vector<HoleRequest>> chunks_;
  bool reserved_{false};
};

/// loadJobHoles of a deferred KRL program read by windows (`first`: its first reading): every
/// hole checked and counted, the notes and errors of the program read whole, in their order
/// (a hole's set-up error before a change of tools, wherever they are met); the holes are set
/// up on a second reading (setUpHoles).
JobHoles loadStreamedHoles(const std::string& path, const CellSpec& cell, const Robot& robot,
                           int threads, ProgramHoles& first, bool keep_requests) {
  JobHoles job;
  job.path = path;
  job.deferred = true;
  job.streamed = true;
  OneToolForOneDrill one(cell);
  std::vector<char> seen;
  std::string base_note;
  std::exception_ptr setup_error;
  std::exception_ptr tool_error;
  // keep_requests: the requests set up in place in the job's vector, reserved once for the
  // program's holes as the first window's holes per byte foretell them (KeptRequests); the
  // holes past that in chunks moved in at the end
  KeptRequests kept(job.requests);
  std::vector<HoleSource> src;
  while (first.next()) {  // a reader's error is thrown where it is met
    if (setup_error) continue;
    const postproc::Program& p = first.program();
    const std::vector<postproc::Hole>& hs = first.holes();
    try {
      if (keep_requests) {
        const size_t n = hs.size() - first.firstNew();
        src.assign(n, HoleSource{});
        HoleRequest* at = kept.add(n, p.files[0]);
        setUpRange(p, hs, cell, robot, {}, {}, first.firstNew(), hs.size(), threads, at,
                   src.data());
        for (size_t k = 0; k < n; ++k)
          job.undefined_base.push_back(src[k].frame_resolved ? -1 : src[k].base);
      } else {
        setUpRange(p, hs, cell, robot, {}, {}, first.firstNew(), hs.size(), threads, nullptr,
                   nullptr);
      }
    } catch (const InputError&) {
      setup_error = std::current_exception();
      continue;
    }
    if (job.hole_count == 0) job.first_hole_id = hs[first.firstNew()].id;
    job.hole_count += hs.size() - first.firstNew();
    addFrameUses(p, hs, first.firstNew(), seen, job.frame_uses);
    for (size_t i = first.firstNew(); i < hs.size(); ++i) {
      if (base_note.empty()) {
        JobHoles scratch;
        if (noteUndefinedBase(scratch, p, hs[i])) base_note = scratch.notes.front();
      }
      if (tool_error) continue;
      try {
        one.check(p, hs[i]);
      } catch (const InputError&) {
        tool_error = std::current_exception();
      }
    }
  }
  const postproc::Program& p = first.program();
  if (job.hole_count == 0 && !setup_error) throwNoDrillCycle(p, path);
  if (setup_error) std::rethrow_exception(setup_error);
  if (!base_note.empty()) job.notes.push_back(base_note);
  if (tool_error) std::rethrow_exception(tool_error);
  noteDefaultDrill(job, cell);
  addProgramNotes(job, p);
  job.program = std::move(first.program());
  // its frames, files, notes and unresolved references stay; the last window's motions go
  std::vector<postproc::Motion>().swap(job.program->motions);
  std::vector<postproc::Target>().swap(job.program->target_list);
  std::vector<postproc::TextId>().swap(job.program->marker_texts);
  kept.finish();
  if (!keep_requests) job.stream = std::make_shared<ProgramHoles>(path, threads);
  return job;
}

}  // namespace

void applyBaseFrame(const JobHoles& job, HoleRequest& r, HoleSource& src) {
  if (src.hole < 0 || src.frame_resolved) return;
  const int base = src.base;
  if (base < 0 || static_cast<size_t>(base) >= job.base_frames.size()) return;
  const std::optional<Pose>& T = job.base_frames[static_cast<size_t>(base)];
  if (!T) return;
  r.T_W_tcp = *T * src.T_W_frame.inverse() * r.T_W_tcp;
  src.T_W_frame = *T;
  src.frame_resolved = true;
}

void applyBaseFrames(JobHoles& job, const CellSpec& cell) {
  for (size_t i = 0; i < job.undefined_base.size() && i < job.requests.size(); ++i) {
    if (job.undefined_base[i] < 0) continue;
    HoleSource src;  // what setUpHole gives a hole whose base frame the program does not define
    src.hole = static_cast<int>(i);
    src.base = job.undefined_base[i];
    src.T_W_frame = cell.T_base_wobj;
    applyBaseFrame(job, job.requests[i], src);
  }
}

void setUpHoles(const JobHoles& job, const CellSpec& cell, const Robot& robot, size_t begin,
                size_t end, int threads, std::vector<HoleRequest>& requests,
                std::vector<HoleSource>& sources) {
  if (!job.deferred || !job.program || end > job.hole_count || begin > end)
    throw InternalError("setUpHoles: not a deferred job or holes out of range");
  if (job.streamed) {  // moved from the window's set-up (take clears both first)
    job.stream->take(job, cell, robot, begin, end, threads, requests, sources);
    return;
  }
  requests.assign(end - begin, HoleRequest{});
  sources.assign(end - begin, HoleSource{});
  setUpRange(*job.program, job.recognized, cell, robot, {}, {}, begin, end, threads,
             requests.data(), sources.data());
  for (size_t k = 0; k < requests.size(); ++k) applyBaseFrame(job, requests[k], sources[k]);
}

/// A motion to a position taught in another tool than the active one (postproc::ToolConflict):
/// the controller stops there, so the program cannot run as written (exit 2 at the motion).
void refuseToolConflicts(const postproc::Program& p) {
  if (p.tool_conflicts.empty()) return;
  const postproc::ToolConflict& k = p.tool_conflicts.front();
  const postproc::Motion& mo = p.motions[static_cast<size_t>(k.motion)];
  const std::string file = p.files[static_cast<size_t>(std::max(0, mo.file))].path;
  const std::string active = programToolKey(k.selected);
  const std::string taught = programToolKey(k.taught);
  throw InputError(file, mo.line,
                   "the motion's position was taught in tool " + taught + " (UT : " + taught +
                       ") but UTOOL_NUM=" + active + " is active (line " +
                       std::to_string(k.selected_line) +
                       "): the controller stops at this motion (a position's tool must be the "
                       "active one). Hint: select its tool with UTOOL_NUM=" +
                       taught + " before the motion, or re-teach the position in tool " + active);
}

JobHoles loadJobHoles(const std::string& path, const CellSpec& cell, const Robot& robot,
                      const std::optional<std::string>& hole_list, double match_tol_mm, int threads,
                      bool defer_setup, bool keep_requests) {
  if (defer_setup && !hole_list) {  // a KRL program is read by windows (twice)
    auto holes = std::make_shared<ProgramHoles>(path, threads);
    if (holes->windowed())
      return loadStreamedHoles(path, cell, robot, threads, *holes, keep_requests);
  }
  JobHoles job;
  job.path = path;
  std::string bytes = readInputFile(path, InputKind::kProgram);
  postproc::Dialect dialect = postproc::detectDialect(path, bytes);
  std::optional<postproc::Program> parsed;
  if (dialect == postproc::Dialect::kCsv) {
    parsed = postproc::parseProgram(dialect, path, bytes);
    dialect = parsed->dialect;  // the CSV reader recognises a hole list by its i,j,k columns
  }
  if (dialect == postproc::Dialect::kHoleCsv) {
    job.is_hole_list = true;
    const std::vector<postproc::HoleSpec> specs = postproc::parseHoleList(path, bytes);
    if (specs.empty()) throw InputError(path, 1, "the hole list has no holes");
    if (parsed)
      for (const auto& n : parsed->notes) job.notes.push_back(n);  // e.g. how it was read
    job.requests.reserve(specs.size());
    job.sources.reserve(specs.size());
    for (size_t i = 0; i < specs.size(); ++i) {
      const auto& s = specs[i];
      job.requests.push_back(fromSpec(s, cell));
      if (!s.tool.empty() || s.feed_mm_per_rev || s.spindle_rpm || hasToolTable(cell))
        holeListProcess(s, cell, path, job.requests.back());
      HoleSource src;
      if (parsed && i < parsed->targets().size()) {
        src.targets = {static_cast<int>(i)};
        src.bottom_target = static_cast<int>(i);
      }
      src.T_W_frame = cell.T_base_wobj;
      src.frame_resolved = true;
      src.frame_ref = "cell workobject";
      src.T_W_tcp_spec = job.requests.back().T_W_tcp;
      job.sources.push_back(src);
    }
    if (hole_list) {
      const std::vector<postproc::HoleSpec> ref = postproc::readHoleList(*hole_list);
      std::unordered_map<std::string, int> by_id;  // ids are unique in a hole list
      for (std::size_t s = 0; s < ref.size(); ++s) by_id.emplace(ref[s].id, static_cast<int>(s));
      std::vector<int> spec_of_hole(job.requests.size(), -1);
      for (std::size_t i = 0; i < job.requests.size(); ++i) {
        HoleRequest& r = job.requests[i];
        const auto it = by_id.find(r.id);
        if (it == by_id.end()) continue;
        const auto& s = ref[static_cast<std::size_t>(it->second)];
        spec_of_hole[i] = it->second;
        r.nominal_axis = std::make_pair(Vec3(cell.T_base_wobj * (s.position_mm * 1e-3)),
                                        Vec3(cell.T_base_wobj.linear() * s.direction.normalized()));
        if (s.tolerance_mm) r.tolerance = *s.tolerance_mm * 1e-3;
        if (s.diameter_mm) r.diameter = *s.diameter_mm * 1e-3;
        if (!s.tool.empty() || s.feed_mm_per_rev || s.spindle_rpm || hasToolTable(cell))
          holeListProcess(s, cell, *hole_list, r);
      }
      reportMatching(job, *hole_list, ref, spec_of_hole, "matched by id");
    }
    job.program = std::move(parsed);
    job.hole_count = job.requests.size();
    requireOneToolForOneDrill(job, cell, specs, path);
    noteDefaultDrill(job, cell);
    return job;
  }
  job.program = parsed ? std::move(*parsed) : postproc::readProgram(path, std::move(bytes));
  refuseToolConflicts(*job.program);
  job.deferred = defer_setup && !hole_list;
  if (job.deferred) {  // a job that writes no program: its bytes are not read again
    for (postproc::SourceFile& f : job.program->files) std::string().swap(f.bytes);
  }
  const postproc::Program& p = *job.program;
  job.recognized = postproc::recognizeHoles(p);
  std::vector<postproc::HoleSpec> specs;
  if (hole_list) {  // the hole list is drilling evidence too (a cycle with a dwell alone)
    specs = postproc::readHoleList(*hole_list);
    job.recognized =
        postproc::withHoleListEvidence(p, std::move(job.recognized), specs, match_tol_mm);
  }
  if (job.recognized.empty()) throwNoDrillCycle(p, path);
  std::vector<int> spec_of_hole(job.recognized.size(), -1);
  if (hole_list) {
    for (const postproc::HoleMatch& m :
         postproc::matchHoles(job.recognized, p, specs, match_tol_mm))
      spec_of_hole[static_cast<std::size_t>(m.hole)] = m.spec;
  }
  const size_t n = job.recognized.size();
  job.hole_count = n;
  job.first_hole_id = job.recognized.front().id;
  std::vector<char> seen;
  addFrameUses(p, job.recognized, 0, seen, job.frame_uses);
  // on the workers; the error of the first failing hole (in hole order) is the one thrown
  if (job.deferred) {
    setUpRange(p, job.recognized, cell, robot, specs, spec_of_hole, 0, n, threads, nullptr,
               nullptr);
  } else {
    job.requests.resize(n);
    job.sources.resize(n);
    setUpRange(p, job.recognized, cell, robot, specs, spec_of_hole, 0, n, threads,
               job.requests.data(), job.sources.data());
  }
  // the first hole whose base frame the program does not define (setUpHole: frame_resolved)
  for (const postproc::Hole& h : job.recognized) {
    if (noteUndefinedBase(job, p, h)) break;
  }
  FarFromTheList far;
  for (size_t i = 0; i < n; ++i) {
    if (spec_of_hole[i] >= 0) far.add(job.requests[i], match_tol_mm);
  }
  if (hole_list) {
    reportMatching(job, *hole_list, specs, spec_of_hole,
                   "matched by id, else by position within --match-tol " +
                       cGeneral(match_tol_mm, 6) + " mm on a parallel axis");
    far.note(job, match_tol_mm);
  }
  requireOneToolForOneDrill(job, cell, specs, path);
  noteDefaultDrill(job, cell);
  addProgramNotes(job, p);
  return job;
}

}  // namespace roprec::api
