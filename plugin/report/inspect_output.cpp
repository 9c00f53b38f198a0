/// The JSON and the summary text of `roprec inspect` (plugin/report/inspect_output.hpp).
#include "plugin/report/inspect_output.hpp"

#include <cstdint>

#include "plugin/report/pose_json.hpp"

namespace roprec::api {

namespace {

using postproc::Frame;
using postproc::Program;
using postproc::Target;

Json positionQuaternionJson(const Pose& T) {
  Json j = Json::object();
  setPositionQuaternion(j, T);
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
  if (f->resolved) setPositionQuaternion(j, f->pose);
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
    case postproc::Vendor::kNone:
      break;
  }
  j.set("text", Json::str(c.text()));
  if (const auto b = c.branch()) j.set("branch", Json::integer(*b));
  return j;
}

/// The values the program states, by their own names (x y z, A B C / W P R / q1..q4 / i j k).
Json nativeJson(const Target& t) {
  Json j = Json::object();
  static const char* const kKuka[] = {"A", "B", "C"};
  static const char* const kFanuc[] = {"W", "P", "R"};
  static const char* const kQuat[] = {"q1", "q2", "q3", "q4"};
  static const char* const kAxis[] = {"i", "j", "k"};
  const char* const xyz[] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    if (t.pos[static_cast<std::size_t>(i)].present())
      j.set(xyz[i], Json::number(t.pos[static_cast<std::size_t>(i)].value, -1));
  }
  const char* const* names = kKuka;
  int n = 3;
  switch (t.orientation) {
    case postproc::Orientation::kFanucWpr:
      names = kFanuc;
      break;
    case postproc::Orientation::kQuaternion:
      names = kQuat;
      n = 4;
      break;
    case postproc::Orientation::kAxis:
      names = kAxis;
      break;
    default:
      break;
  }
  for (int i = 0; i < n; ++i) {
    if (t.rot[static_cast<std::size_t>(i)].present())
      j.set(names[i], Json::number(t.rot[static_cast<std::size_t>(i)].value, -1));
  }
  return j;
}

/// Pose keys of a target: native values, pose in its frame and, where the base resolves, in the
/// base frame.
void setTargetPose(Json& j, const Program& p, const Target& t, const Frame* base) {
  if (t.kind != postproc::TargetKind::kCartesian) {
    Json jd = Json::array();
    for (const double v : postproc::targetJointsDeg(t)) jd.push(Json::number(v, -1));
    j.set("joints_deg", jd);
    return;
  }
  j.set("native", nativeJson(t));
  j.set("complete", Json::boolean(postproc::targetComplete(t)));
  const Pose T = postproc::targetPose(p, t);
  j.set("in_frame", positionQuaternionJson(T));
  if (base != nullptr && base->resolved && postproc::targetComplete(t))
    setPositionQuaternion(j, base->pose * T);
}

Json targetJson(const Program& p, std::size_t i) {
  const Target& t = p.targets()[i];
  Json j = Json::object();
  j.set("index", Json::integer(static_cast<std::int64_t>(i)));
  j.set("name", Json::str(t.name));
  j.set("file", Json::str(p.files[static_cast<std::size_t>(t.file)].path));
  j.set("line", Json::integer(t.line));
  j.set("kind", Json::str(t.kind == postproc::TargetKind::kJoint ? "joint" : "cartesian"));
  const Frame* base = postproc::targetBase(p, t);
  const Frame* tool = postproc::targetTool(p, t);
  setTargetPose(j, p, t, base);
  if (t.config.present()) j.set("config", configJson(t.config));
  Json ext = Json::array();
  for (const auto& e : t.ext) {
    if (e.present()) ext.push(Json::number(e.value, -1));
  }
  j.set("external_axes", ext);
  if (!t.frame_ref.empty()) j.set("declared_frame", Json::str(p.text(t.frame_ref)));
  if (!t.tool_ref.empty()) j.set("declared_tool", Json::str(p.text(t.tool_ref)));
  j.set("base", frameJson(base));
  j.set("tool", frameJson(tool));
  Json uses = Json::array();
  for (const int m : t.uses) uses.push(Json::integer(p.motions[static_cast<std::size_t>(m)].line));
  j.set("used_at_lines", uses);
  j.set("frames_consistent", Json::boolean(postproc::targetFramesConsistent(p, t)));
  return j;
}

Json motionJson(const Program& p, const postproc::Motion& m) {
  Json j = Json::object();
  j.set("instruction", Json::str(p.text(m.instruction)));
  j.set("line", Json::integer(m.line));
  j.set("target", Json::integer(m.target));
  if (m.aux >= 0) j.set("aux_target", Json::integer(m.aux));
  if (m.target < 0) j.set("target_text", Json::str(p.text(m.target_text)));
  if (!m.derivation.empty()) j.set("derivation", Json::str(p.text(m.derivation)));
  if (m.speed_mm_s >= 0) j.set("speed_mm_s", Json::number(m.speed_mm_s, 6));
  if (!m.speed_text.empty()) j.set("speed", Json::str(p.text(m.speed_text)));
  j.set("zone", Json::str(p.text(m.zone_text)));
  j.set("fine", Json::boolean(m.fine));
  j.set("config_honoured", Json::boolean(m.config_honoured));
  if (m.marker_count > 0) {
    Json mk = Json::array();
    for (const auto& s : p.markers(m)) mk.push(Json::str(s));
    j.set("markers", mk);
  }
  return j;
}

/// The hole-list ids matched to the recognised holes (empty without a hole list).
Json recognisedHoleJson(const Program& p, const std::vector<postproc::Hole>& holes, std::size_t h,
                        const HoleListMatch& list) {
  const postproc::Hole& hole = holes[h];
  Json j = Json::object();
  j.set("id", Json::str(hole.id));
  for (const auto& m : list.matches) {
    if (m.hole == static_cast<int>(h)) {
      j.set("hole_list_id", Json::str(list.specs[static_cast<std::size_t>(m.spec)].id));
      j.set("match_distance_mm", Json::number(m.distance_mm, 6));
    }
  }
  j.set("entry_target", Json::integer(hole.entry_target));
  j.set("bottom_target", Json::integer(hole.bottom_target));
  Json ts = Json::array();
  for (const int t : hole.targets) ts.push(Json::integer(t));
  j.set("targets", ts);
  // the hole is where it starts (the surface); the drill point is its bottom
  const bool surface = hole.surface_motion >= 0;
  if (surface) j.set("position_in_frame_mm", Json::vector(hole.surface * 1e3, 6));
  j.set("bottom_in_frame_mm", Json::vector(hole.position * 1e3, 6));
  j.set("axis_in_frame", Json::vector(hole.axis, 9));
  if (surface) j.set("depth_mm", Json::number(hole.depth * 1e3, 6));
  j.set("surface", Json::str(surface ? "start of the feed move" : "not known (no feed change)"));
  const Frame* base = hole.base >= 0 ? &p.frames[static_cast<std::size_t>(hole.base)] : nullptr;
  const Frame* tool = hole.tool >= 0 ? &p.frames[static_cast<std::size_t>(hole.tool)] : nullptr;
  if (base != nullptr && base->resolved) {
    if (surface) j.set("position_mm", Json::vector(base->pose * hole.surface * 1e3, 6));
    j.set("bottom_mm", Json::vector(base->pose * hole.position * 1e3, 6));
    j.set("axis", Json::vector(base->pose.linear() * hole.axis, 9));
  }
  j.set("base", frameJson(base));
  j.set("tool", frameJson(tool));
  Json ev = Json::array();
  for (const auto& e : holeEvidence(p, hole)) ev.push(Json::str(e));
  j.set("evidence", ev);
  return j;
}

Json unresolvedJson(const Program& p) {
  Json un = Json::array();
  for (const auto& u : p.unresolved) {
    Json j = Json::object();
    j.set("ref", Json::str(u.ref));
    j.set("file", Json::str(u.file >= 0 ? p.files[static_cast<std::size_t>(u.file)].path : ""));
    j.set("line", Json::integer(u.line));
    j.set("what", Json::str(u.what));
    un.push(j);
  }
  return un;
}

}  // namespace

Json inspectJson(const InspectedProgram& r) {
  const Program& p = r.program;
  const std::vector<postproc::Hole>& holes = r.holes;
  Json root = Json::object();
  root.set("program", Json::str(r.path));
  root.set("dialect", Json::str(postproc::dialectName(p.dialect)));
  Json files = Json::array();
  for (const auto& f : p.files) files.push(Json::str(f.path));
  root.set("files", files);
  root.set("drilling_axis_tcp", Json::vector(r.tool_axis, 6));
  Json targets = Json::array();
  for (std::size_t i = 0; i < p.targets().size(); ++i) targets.push(targetJson(p, i));
  root.set("targets", targets);
  Json motions = Json::array();
  for (const auto& m : p.motions) motions.push(motionJson(p, m));
  root.set("motions", motions);
  Json hj = Json::array();
  for (std::size_t h = 0; h < holes.size(); ++h) hj.push(recognisedHoleJson(p, holes, h, r.list));
  root.set("holes", hj);
  root.set("unresolved", unresolvedJson(p));
  Json notes = Json::array();
  for (const auto& n : p.notes) notes.push(Json::str(n));
  root.set("notes", notes);
  return root;
}

std::string inspectSummaryText(const InspectSummary& s) {
  std::string text = "roprec inspect: " + s.program + " (" + s.dialect + ", " +
                     std::to_string(s.files) + (s.files == 1 ? " file" : " files") + ")\n";
  text += "  " + std::to_string(s.targets) + " targets, " + std::to_string(s.motions) +
          " motions, " + std::to_string(s.holes) + " drill holes, " +
          std::to_string(s.unresolved.size()) + " unresolved references\n";
  for (const auto& u : s.unresolved) text += "  unresolved: " + u + "\n";
  for (const auto& n : s.notes) text += "  note: " + n + "\n";
  return text;
}

}  // namespace roprec::api
