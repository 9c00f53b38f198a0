#include "compensator/precision/cell.hpp"

#include <filesystem>

#include "compensator/process/process_spec.hpp"
#include "compensator/robot/urdf_loader.hpp"
#include "compensator/support/error.hpp"

namespace fs = std::filesystem;

namespace roprec {

namespace {
/// A vec3 attribute whose every |component| <= limit (e.g. 1e300 in a cell is a typo, and it
/// would overflow the kinematics and print 300 digits in messages).
Vec3 boundedVec3(const XmlNode& e, const char* name, double limit, const char* what) {
  Vec3 v = e.vec3(name, Vec3::Zero());
  if (!(v.cwiseAbs().maxCoeff() <= limit))
    e.fail("<" + e.name + "> " + name + " '" + e.str(name) + "' is beyond " + what);
  return v;
}
}  // namespace

Pose poseFromXyzRpyMm(const XmlNode& e) {
  Pose T = Pose::Identity();
  T.translation() = boundedVec3(e, "xyz", 1e5, "100 m (mm expected)") * 1e-3;
  const Vec3 rpy = boundedVec3(e, "rpy", 3600.0, "3600 deg (degrees expected)") * kDeg;
  T.linear() = rotationFromRpy(rpy.x(), rpy.y(), rpy.z());
  return T;
}

Pose partMotion(const CellSpec& cell) {
  if (!cell.part_registration) return Pose::Identity();
  return cell.T_base_wobj * cell.part_registration->inverse() * cell.T_base_wobj.inverse();
}

namespace {

/// The <part_registration> element: t in mm, R from rpy in mrad (URDF order, as <workobject>).
Pose parsePartRegistration(const XmlNode& e) {
  allowOnly(e, {"xyz_mm", "rpy_mrad", "source"});
  Pose F = Pose::Identity();
  F.translation() =
      boundedVec3(e, "xyz_mm", 1e3, "1 m (a registration is a small offset, mm)") * 1e-3;
  const Vec3 rpy =
      boundedVec3(e, "rpy_mrad", 200.0, "200 mrad (a registration is a small rotation)") * 1e-3;
  F.linear() = rotationFromRpy(rpy.x(), rpy.y(), rpy.z());
  return F;
}

/// Tool + spindle mass above this is not a tool (kg; the heaviest robots carry 2.3 t).
constexpr double kMaxToolMassKg = 5000.0;

/// The mass data of a <tool> (or a drill's <tcp>) element: mass, centre of mass and inertia.
void parseToolMass(const XmlNode& t, ToolSpec& tool) {
  tool.mass = t.number("mass_kg", 0.0);
  if (!(tool.mass >= 0 && tool.mass <= kMaxToolMassKg)) {
    t.fail("<" + t.name + "> mass_kg must lie in [0, " +
           std::to_string(static_cast<int>(kMaxToolMassKg)) + "] kg, got " + t.str("mass_kg"));
  }
  tool.com = boundedVec3(t, "com_mm", 1e5, "100 m (mm expected)") * 1e-3;
  tool.inertia = Mat3::Zero();
  if (t.has("inertia_kgm2")) {
    const Eigen::VectorXd I = t.numbers("inertia_kgm2", 6);  // ixx ixy ixz iyy iyz izz
    tool.inertia << I[0], I[1], I[2], I[1], I[3], I[4], I[2], I[4], I[5];
    if (const std::string why = inertiaProblem(tool.inertia); !why.empty())
      t.fail("<" + t.name + "> inertia_kgm2: " + why);
  }
}

ToolSpec parseTool(const XmlNode& t) {
  allowOnly(t, {"name", "xyz", "rpy", "mass_kg", "com_mm", "inertia_kgm2"});
  ToolSpec tool;
  tool.name = t.str("name", "tool");
  tool.T_flange_tcp = poseFromXyzRpyMm(t);
  parseToolMass(t, tool);
  return tool;
}

/// The TCP of every <drill> of a drilling process, or every <mill> of a milling process
/// (CellSpec::drill_tools): a tool's <tcp> is its TCP in the flange frame; its mass data are its
/// own when it states mass_kg, else the cell tool's (the same spindle, another cutter).
std::vector<std::optional<ToolSpec>> parseDrillTools(const XmlNode& process, const ToolSpec& cell) {
  std::vector<std::optional<ToolSpec>> out;
  const std::string type = process.str("type", "");
  if (type != "drilling" && type != "milling") return out;
  const char* const element = type == "drilling" ? "drill" : "mill";
  for (const XmlNode* d : process.childrenNamed(element)) {
    const XmlNode* t = d->child("tcp");
    if (t == nullptr) {
      out.emplace_back();
      continue;
    }
    allowOnly(*t, {"xyz", "rpy", "mass_kg", "com_mm", "inertia_kgm2"});
    ToolSpec tool = cell;
    tool.name = d->str("tool", d->str("name", element));
    tool.T_flange_tcp = poseFromXyzRpyMm(*t);
    if (t->has("mass_kg")) {
      parseToolMass(*t, tool);
    } else if (t->has("com_mm") || t->has("inertia_kgm2")) {
      t->fail("<tcp> com_mm and inertia_kgm2 belong to a mass: give mass_kg too (without it the " +
              std::string(element) + " carries the cell's <tool> mass data)");
    }
    out.emplace_back(std::move(tool));
  }
  return out;
}

}  // namespace

CellSpec loadCell(const std::string& path) {
  CellSpec cell;
  cell.root = loadXmlFile(path, InputKind::kCell);
  const XmlNode& root = cell.root;
  if (root.name != "cell")
    root.fail("a cell file's root element is <cell>, got <" + root.name + ">");
  allowOnly(root, {"name"});
  allowChildren(root, {"robot", "tool", "workobject", "process", "tolerance", "controller",
                       "uncertainty", "capability", "absolute_accuracy", "part_registration"});
  allowAtMostOnce(root, {"robot", "tool", "workobject", "process", "tolerance", "controller",
                         "uncertainty", "capability", "absolute_accuracy", "part_registration"});
  cell.file = path;
  cell.name = root.str("name", fs::path(path).stem().string());
  const fs::path dir = fs::path(path).parent_path();
  auto rel = [&](const std::string& p) {
    // a rooted path (Windows: "/x" or "C:/x") is kept as written, not joined to the cell's folder
    return fs::path(p).has_root_directory() ? p : (dir / p).lexically_normal().string();
  };

  const XmlNode* r = root.child("robot");
  if (r == nullptr) root.fail("the cell has no <robot ref|file|urdf=...> element");
  cell.robot_line = r->line;
  allowOnly(*r, {"ref", "file", "urdf", "base_link", "flange_link"});
  if (static_cast<int>(r->has("ref")) + static_cast<int>(r->has("file")) +
          static_cast<int>(r->has("urdf")) >
      1)
    r->fail("<robot> takes one of ref=, file= or urdf=, not several");
  if (r->has("ref")) {
    cell.robot.robot = r->str("ref");
  } else if (r->has("file")) {
    cell.robot.robot = rel(r->str("file"));
  } else if (r->has("urdf")) {
    // a bare URDF has no joint stiffness, repeatability or controller convention
    r->fail(
        "<robot urdf=...> names a bare URDF, which has no joint stiffness, repeatability or "
        "controller convention; make a card with `roprec card new --urdf " +
        rel(r->str("urdf")) +
        " ... -o robot.xml` and reference it with <robot file=\"robot.xml\"/>");
  } else {
    r->fail("<robot> needs ref=\"bundled-name\" or file=\"robot.xml\"");
  }
  cell.robot.base_link = r->str("base_link", "");
  cell.robot.tip_link = r->str("flange_link", "");

  if (const XmlNode* t = root.child("tool")) cell.tool = parseTool(*t);
  if (const XmlNode* w = root.child("workobject")) {
    allowOnly(*w, {"name", "xyz", "rpy", "sigma_mm", "sigma_source"});
    cell.T_base_wobj = poseFromXyzRpyMm(*w);
    if (w->has("sigma_mm") && !(w->number("sigma_mm") >= 0 && w->number("sigma_mm") <= 100))
      w->fail("sigma_mm (the registration's standard uncertainty per axis) must lie in [0, 100]");
  }
  if (const XmlNode* g = root.child("part_registration"))
    cell.part_registration = parsePartRegistration(*g);
  if (const XmlNode* p = root.child("process")) {
    cell.has_process = true;
    cell.process = *p;
    (void)parseProcess(*p);  // validates the whole element (unknown names, ranges) up front
    cell.drill_tools = parseDrillTools(*p, cell.tool);
  }
  if (const XmlNode* tol = root.child("tolerance")) {
    allowOnly(*tol, {"position_mm"});
    cell.tolerance_mm = tol->number("position_mm");
    if (!(cell.tolerance_mm > 0 && cell.tolerance_mm <= 10.0)) {
      tol->fail(
          "position_mm must lie in (0, 10] mm (a position tolerance of a drilled hole), "
          "got " +
          tol->str("position_mm"));
    }
  }
  if (const XmlNode* c = root.child("controller"))
    allowOnly(*c, {"gravity_compensated", "calibration_load", "fanuc_turn_axes"});
  if (const XmlNode* u = root.child("uncertainty"))
    allowOnly(*u, {"method", "stiffness_rel", "position_gain_rel", "process_halfwidth", "samples",
                   "seed", "source"});
  if (const XmlNode* c = root.child("capability")) allowOnly(*c, {"mc_approach_s", "source"});
  if (const XmlNode* a = root.child("absolute_accuracy")) {
    allowOnly(*a, {"ap_mm", "source"});
    if (!(a->number("ap_mm") > 0 && a->number("ap_mm") <= 10))
      a->fail("ap_mm (the absolute-accuracy option's residual, ISO 9283 AP) must lie in (0, 10]");
    if (a->str("source", "").empty()) a->fail("<absolute_accuracy> needs a source=");
  }
  return cell;
}

}  // namespace roprec
