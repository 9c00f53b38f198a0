/// `roprec inspect PROGRAM`: what a robot program contains (docs/contract.md §11, docs/programs.md).
#include <cmath>
#include <sstream>

#include "compensator/support/error.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/api/json.hpp"
#include "postproc/drill.hpp"
#include "postproc/program.hpp"

namespace roprec::cli {
namespace {

using postproc::Frame;
using postproc::Program;
using postproc::Target;

Json poseJson(const Pose& T) {
  Json j = Json::object();
  j.set("position_mm", Json::vector(T.translation() * 1e3, 6));
  const Eigen::Quaterniond q = quaternionFromRotation(T.linear());
  j.set("quaternion_wxyz", Json::vector(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()), 9));
  return j;
}

Json frameJson(const Frame* f) {
  Json j = Json::object();
  if (f == nullptr) {
    j.set("ref", Json::str(""));
    j.set("resolved", Json::boolean(false));
    return j;
  }
  j.set("ref", Json::str(f->ref));
  j.set("resolved", Json::boolean(f->resolved));
  if (f->resolved) {
    j.set("position_mm", Json::vector(f->pose.translation() * 1e3, 6));
    const Eigen::Quaterniond q = quaternionFromRotation(f->pose.linear());
    j.set("quaternion_wxyz", Json::vector(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()), 9));
  }
  return j;
}

Json configJson(const postproc::Configuration& c) {
  Json j = Json::object();
  switch (c.vendor) {
    case postproc::Vendor::kKuka:
      if (c.status >= 0) j.set("S", Json::integer(c.status));
      if (c.turn >= 0) j.set("T", Json::integer(c.turn));
      break;
    case postproc::Vendor::kAbb: {
      Json a = Json::array();
      for (const int v : c.cf) a.push(Json::integer(v));
      j.set("cf1_cf4_cf6_cfx", a);
      break;
    }
    case postproc::Vendor::kFanuc: {
      j.set("letters", Json::str(std::string(1, c.flip) + " " + c.elbow + " " + c.front));
      Json a = Json::array();
      for (const int v : c.turns) a.push(Json::integer(v));
      j.set("turns", a);
      break;
    }
    case postproc::Vendor::kNone: break;
  }
  j.set("text", Json::str(c.text()));
  if (const auto b = c.branch()) j.set("branch", Json::integer(*b));
  return j;
}

Json nativeJson(const Target& t) {
  Json j = Json::object();
  static const char* const kKuka[] = {"A", "B", "C"};
  static const char* const kFanuc[] = {"W", "P", "R"};
  static const char* const kQuat[] = {"q1", "q2", "q3", "q4"};
  static const char* const kAxis[] = {"i", "j", "k"};
  const char* const xyz[] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    if (t.pos[static_cast<std::size_t>(i)].present()) j.set(xyz[i], Json::number(t.pos[static_cast<std::size_t>(i)].value, -1));
  }
  const char* const* names = kKuka;
  int n = 3;
  switch (t.orientation) {
    case postproc::Orientation::kFanucWpr: names = kFanuc; break;
    case postproc::Orientation::kQuaternion: names = kQuat; n = 4; break;
    case postproc::Orientation::kAxis: names = kAxis; break;
    default: break;
  }
  for (int i = 0; i < n; ++i) {
    if (t.rot[static_cast<std::size_t>(i)].present()) j.set(names[i], Json::number(t.rot[static_cast<std::size_t>(i)].value, -1));
  }
  return j;
}

int run(Args& args, CommandContext& ctx) {
  const std::string out = args.option("o").value_or(args.option("output").value_or("-"));
  const std::optional<std::string> holes_csv = args.option("holes");
  const std::optional<std::string> tol = args.option("match-tolerance");
  const std::optional<std::string> axis = args.option("tool-axis");
  const std::optional<std::string> frames = args.option("frame");
  const std::vector<std::string> pos = args.positionals();
  args.finish();
  if (pos.size() != 1) throw UsageError("inspect needs exactly one PROGRAM");
  Program p = postproc::readProgram(pos[0]);
  if (frames) {
    std::istringstream in(*frames);
    std::string item;
    while (std::getline(in, item, ';')) {
      const std::size_t eq = item.find('=');
      if (eq == std::string::npos) throw UsageError("--frame expects REF=\"x y z a b c\"[;REF=...]");
      postproc::resolveFrame(p, item.substr(0, eq), parsePoseXyzAbc(item.substr(eq + 1), "--frame REF=\"x y z a b c\" (mm, deg, KUKA ABC)"));
    }
  }
  postproc::RecognitionOptions ro;
  if (axis) {
    const Eigen::VectorXd a = parseNumberList(*axis, 3, "--tool-axis");
    if (a.norm() < 1e-9) throw UsageError("--tool-axis must not be zero");
    ro.tool_axis = a.normalized();
  }
  const std::vector<postproc::Hole> holes = postproc::recognizeHoles(p, ro);

  Json root = Json::object();
  root.set("program", Json::str(pos[0]));
  root.set("dialect", Json::str(postproc::dialectName(p.dialect)));
  Json files = Json::array();
  for (const auto& f : p.files) files.push(Json::str(f.path));
  root.set("files", files);
  root.set("drilling_axis_tcp", Json::vector(ro.tool_axis, 6));
  Json targets = Json::array();
  for (std::size_t i = 0; i < p.targets().size(); ++i) {
    const Target& t = p.targets()[i];
    Json j = Json::object();
    j.set("index", Json::integer(static_cast<std::int64_t>(i)));
    j.set("name", Json::str(t.name));
    j.set("file", Json::str(p.files[static_cast<std::size_t>(t.file)].path));
    j.set("line", Json::integer(t.line));
    j.set("kind", Json::str(t.kind == postproc::TargetKind::kJoint ? "joint" : "cartesian"));
    const Frame* base = postproc::targetBase(p, t);
    const Frame* tool = postproc::targetTool(p, t);
    if (t.kind == postproc::TargetKind::kCartesian) {
      j.set("native", nativeJson(t));
      j.set("complete", Json::boolean(postproc::targetComplete(t)));
      const Pose T = postproc::targetPose(p, t);
      j.set("in_frame", poseJson(T));
      if (base != nullptr && base->resolved && postproc::targetComplete(t)) {
        const Pose Tb = base->pose * T;
        j.set("position_mm", Json::vector(Tb.translation() * 1e3, 6));
        const Eigen::Quaterniond q = quaternionFromRotation(Tb.linear());
        j.set("quaternion_wxyz", Json::vector(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()), 9));
      }
    } else {
      Json jd = Json::array();
      for (const double v : postproc::targetJointsDeg(t)) jd.push(Json::number(v, -1));
      j.set("joints_deg", jd);
    }
    if (t.config.present()) j.set("config", configJson(t.config));
    Json ext = Json::array();
    for (const auto& e : t.ext) {
      if (e.present()) ext.push(Json::number(e.value, -1));
    }
    j.set("external_axes", ext);
    if (!t.frame_ref.empty()) j.set("declared_frame", Json::str(t.frame_ref));
    if (!t.tool_ref.empty()) j.set("declared_tool", Json::str(t.tool_ref));
    j.set("base", frameJson(base));
    j.set("tool", frameJson(tool));
    Json uses = Json::array();
    for (const int m : t.uses) uses.push(Json::integer(p.motions[static_cast<std::size_t>(m)].line));
    j.set("used_at_lines", uses);
    j.set("frames_consistent", Json::boolean(postproc::targetFramesConsistent(p, t)));
    targets.push(j);
  }
  root.set("targets", targets);
  Json motions = Json::array();
  for (const auto& m : p.motions) {
    Json j = Json::object();
    j.set("instruction", Json::str(m.instruction));
    j.set("line", Json::integer(m.line));
    j.set("target", Json::integer(m.target));
    if (m.aux >= 0) j.set("aux_target", Json::integer(m.aux));
    if (m.target < 0) j.set("target_text", Json::str(m.target_text));
    if (!m.derivation.empty()) j.set("derivation", Json::str(m.derivation));
    if (m.speed_mm_s >= 0) j.set("speed_mm_s", Json::number(m.speed_mm_s, 6));
    if (!m.speed_text.empty()) j.set("speed", Json::str(m.speed_text));
    j.set("zone", Json::str(m.zone_text));
    j.set("fine", Json::boolean(m.fine));
    j.set("config_honoured", Json::boolean(m.config_honoured));
    if (!m.markers.empty()) {
      Json mk = Json::array();
      for (const auto& s : m.markers) mk.push(Json::str(s));
      j.set("markers", mk);
    }
    motions.push(j);
  }
  root.set("motions", motions);
  Json hj = Json::array();
  std::vector<postproc::HoleSpec> specs;
  std::vector<postproc::HoleMatch> matches;
  if (holes_csv) {
    specs = postproc::readHoleList(*holes_csv);
    const double t = tol ? parseNumberList(*tol, 1, "--match-tolerance")[0] : 1.0;
    matches = postproc::matchHoles(holes, p, specs, t);
  }
  for (std::size_t h = 0; h < holes.size(); ++h) {
    const postproc::Hole& hole = holes[h];
    Json j = Json::object();
    j.set("id", Json::str(hole.id));
    for (const auto& m : matches) {
      if (m.hole == static_cast<int>(h)) {
        j.set("hole_list_id", Json::str(specs[static_cast<std::size_t>(m.spec)].id));
        j.set("match_distance_mm", Json::number(m.distance_mm, 6));
      }
    }
    j.set("entry_target", Json::integer(hole.entry_target));
    j.set("bottom_target", Json::integer(hole.bottom_target));
    Json ts = Json::array();
    for (const int t : hole.targets) ts.push(Json::integer(t));
    j.set("targets", ts);
    j.set("position_in_frame_mm", Json::vector(hole.position * 1e3, 6));
    j.set("axis_in_frame", Json::vector(hole.axis, 9));
    j.set("depth_mm", Json::number(hole.depth * 1e3, 6));
    const Frame* base = hole.base >= 0 ? &p.frames[static_cast<std::size_t>(hole.base)] : nullptr;
    const Frame* tool = hole.tool >= 0 ? &p.frames[static_cast<std::size_t>(hole.tool)] : nullptr;
    if (base != nullptr && base->resolved) {
      j.set("position_mm", Json::vector(base->pose * hole.position * 1e3, 6));
      j.set("axis", Json::vector(base->pose.linear() * hole.axis, 9));
    }
    j.set("base", frameJson(base));
    j.set("tool", frameJson(tool));
    Json ev = Json::array();
    for (const auto& e : hole.evidence) ev.push(Json::str(e));
    j.set("evidence", ev);
    hj.push(j);
  }
  root.set("holes", hj);
  Json un = Json::array();
  for (const auto& u : p.unresolved) {
    Json j = Json::object();
    j.set("ref", Json::str(u.ref));
    j.set("file", Json::str(u.file >= 0 ? p.files[static_cast<std::size_t>(u.file)].path : ""));
    j.set("line", Json::integer(u.line));
    j.set("what", Json::str(u.what));
    un.push(j);
  }
  root.set("unresolved", un);
  Json notes = Json::array();
  for (const auto& n : p.notes) notes.push(Json::str(n));
  root.set("notes", notes);
  emit(ctx, out, root.dump() + "\n");
  return 0;
}

const CommandRegistration reg{
    {"inspect", "what a robot program contains: targets, frames, configurations, holes",
     "usage: roprec inspect PROGRAM [-o OUT.json] [--holes HOLES.csv [--match-tolerance MM]]\n"
     "                      [--tool-axis \"x y z\"] [--frame 'REF=x y z a b c[;REF=...]']\n\n"
     "PROGRAM: KUKA .src (+ .dat beside it), ABB .mod/.prg/.sys, FANUC .ls, CSV/JSON target list or\n"
     "hole list. JSON: targets (pose in their frame and, where the frame resolves, in the robot base\n"
     "frame: position_mm, quaternion_wxyz; native values; configuration; external axes; tool/base),\n"
     "motions, recognised drill holes, unresolved references.\n"
     "--frame defines frames the program uses but does not define (e.g. 'UFRAME[1]=1400 0 400 0 0 0').\n"
     "--tool-axis: drilling axis in the TCP frame (default +z).\n",
     60, run}};

}  // namespace
}  // namespace roprec::cli
