#include "compensator/precision/cell.hpp"

#include <filesystem>

#include "compensator/support/error.hpp"

namespace fs = std::filesystem;

namespace roprec {

Pose poseFromXyzRpyMm(const XmlNode& e) {
  Pose T = Pose::Identity();
  T.translation() = e.vec3("xyz", Vec3::Zero()) * 1e-3;
  const Vec3 rpy = e.vec3("rpy", Vec3::Zero()) * kDeg;
  T.linear() = rotationFromRpy(rpy.x(), rpy.y(), rpy.z());
  return T;
}

CellSpec loadCell(const std::string& path) {
  CellSpec cell;
  cell.root = loadXmlFile(path);
  const XmlNode& root = cell.root;
  if (root.name != "cell")
    root.fail("a cell file's root element is <cell>, got <" + root.name + ">");
  cell.file = path;
  cell.name = root.str("name", fs::path(path).stem().string());
  const fs::path dir = fs::path(path).parent_path();
  auto rel = [&](const std::string& p) {
    return fs::path(p).is_absolute() ? p : (dir / p).lexically_normal().string();
  };

  const XmlNode* r = root.child("robot");
  if (r == nullptr) root.fail("the cell has no <robot ref|file|urdf=...> element");
  cell.robot_line = r->line;
  if (r->has("ref")) {
    cell.robot.robot = r->str("ref");
  } else if (r->has("file")) {
    cell.robot.robot = rel(r->str("file"));
  } else if (r->has("urdf")) {
    cell.robot.robot = rel(r->str("urdf"));
  } else {
    r->fail("<robot> needs ref=\"bundled-name\", file=\"robot.xml\" or urdf=\"file.urdf\"");
  }
  cell.robot.base_link = r->str("base_link", "");
  cell.robot.tip_link = r->str("flange_link", "");

  if (const XmlNode* t = root.child("tool")) {
    cell.tool.name = t->str("name", "tool");
    cell.tool.T_flange_tcp = poseFromXyzRpyMm(*t);
    cell.tool.mass = t->number("mass_kg", 0.0);
    if (cell.tool.mass < 0) t->fail("mass_kg must be >= 0");
    cell.tool.com = t->vec3("com_mm", Vec3::Zero()) * 1e-3;
    if (t->has("inertia_kgm2")) {
      const Eigen::VectorXd I = t->numbers("inertia_kgm2", 6);  // ixx ixy ixz iyy iyz izz
      cell.tool.inertia << I[0], I[1], I[2], I[1], I[3], I[4], I[2], I[4], I[5];
    }
  }
  if (const XmlNode* w = root.child("workobject")) cell.T_base_wobj = poseFromXyzRpyMm(*w);
  if (const XmlNode* p = root.child("process")) {
    cell.has_process = true;
    cell.process = *p;
    const std::string type = p->str("type");
    if (type != "drilling" && type != "milling" && type != "wrench") {
      p->fail("unknown process type '" + type + "' (drilling, milling or wrench)");
    }
  }
  if (const XmlNode* tol = root.child("tolerance")) {
    cell.tolerance_mm = tol->number("position_mm");
    if (!(cell.tolerance_mm > 0)) tol->fail("position_mm must be > 0");
  }
  return cell;
}

}  // namespace roprec
