#include "compensator/robot/geometry_calibration.hpp"

#include <charconv>
#include <cmath>

#include "compensator/support/error.hpp"
#include "compensator/support/xml_escape.hpp"
#include "compensator/support/xml_node.hpp"

namespace roprec {

Pose FrameError::transform() const {
  Pose T = Pose::Identity();
  T.translation() = dxyz;
  T.linear() = rotationFromRpy(drpy.x(), drpy.y(), drpy.z());
  return T;
}

bool FrameError::isZero() const { return dxyz.isZero(0.0) && drpy.isZero(0.0); }

FrameError frameErrorFromTransform(const Pose& T) {
  FrameError e;
  e.dxyz = T.translation();
  e.drpy = rpyFromRotation(T.linear());
  return e;
}

ChainDescription calibratedChain(const ChainDescription& nominal, const GeometryCalibration& cal) {
  ChainDescription real = nominal;
  for (size_t i = 0; i < 6; ++i)
    real.joints[i].origin = nominal.joints[i].origin * cal.joints[i].transform();
  real.joints[0].origin = cal.base.transform() * real.joints[0].origin;
  real.tip = nominal.tip * cal.tool.transform();
  return real;
}

namespace {

/// The smallest rotation taking unit vector a onto unit vector b (identity when equal).
Mat3 rotationOnto(const Vec3& a, const Vec3& b) {
  const Vec3 axis = a.cross(b);
  const double s = axis.norm();
  if (s < 1e-15) return Mat3::Identity();  // equal (opposite axes are refused by the caller)
  return Eigen::AngleAxisd(std::atan2(s, a.dot(b)), axis / s).toRotationMatrix();
}

}  // namespace

GeometryCalibration calibrationFromChains(const ChainDescription& nominal,
                                          const ChainDescription& calibrated) {
  GeometryCalibration cal;
  Pose carry = Pose::Identity();
  for (size_t i = 0; i < 6; ++i) {
    const ChainJoint& n = nominal.joints[i];
    const ChainJoint& c = calibrated.joints[i];
    if (n.name != c.name || n.axis.dot(c.axis) < 0.5) {
      throw InputError(calibrated.file, c.line,
                       "joint " + std::to_string(i + 1) + " '" + c.name +
                           "' is not the nominal chain's '" + n.name +
                           "' turning about the same axis: not a calibration of this robot");
    }
    Pose R = Pose::Identity();
    R.linear() = rotationOnto(n.axis, c.axis);
    cal.joints[i] = frameErrorFromTransform(n.origin.inverse() * carry * c.origin * R);
    carry = R.inverse();
  }
  cal.tool = frameErrorFromTransform(nominal.tip.inverse() * carry * calibrated.tip);
  return cal;
}

namespace {

constexpr double kMm = 1e-3;    // m per mm
constexpr double kMrad = 1e-3;  // rad per mrad

/// Reads one error element's xyz_mm / rpy_mrad / sigma_xyz_mm / sigma_rpy_mrad (all optional).
FrameError parseFrameError(const XmlNode& e) {
  FrameError f;
  f.dxyz = e.vec3("xyz_mm", Vec3::Zero()) * kMm;
  f.drpy = e.vec3("rpy_mrad", Vec3::Zero()) * kMrad;
  f.sigma_xyz = e.vec3("sigma_xyz_mm", Vec3::Zero()) * kMm;
  f.sigma_rpy = e.vec3("sigma_rpy_mrad", Vec3::Zero()) * kMrad;
  if ((f.sigma_xyz.array() < 0).any() || (f.sigma_rpy.array() < 0).any())
    e.fail("<" + e.name + "> standard uncertainties (sigma_*) must be >= 0");
  return f;
}

int jointIndex(const XmlNode& e, const std::array<std::string, 6>& names) {
  const std::string name = e.str("joint");
  for (int i = 0; i < 6; ++i)
    if (names[static_cast<size_t>(i)] == name) return i;
  std::string known;
  for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
  e.fail("<joint_origin joint=\"" + name + "\"> is not one of the card's joints (" + known + ")");
}

void parseJointOrigins(const XmlNode& block, const std::array<std::string, 6>& names,
                       GeometryCalibration& cal) {
  std::array<int, 6> seen{};
  for (const XmlNode* e : block.childrenNamed("joint_origin")) {
    allowOnly(*e, {"joint", "xyz_mm", "rpy_mrad", "sigma_xyz_mm", "sigma_rpy_mrad"});
    const int i = jointIndex(*e, names);
    if (seen[static_cast<size_t>(i)] != 0) {
      e->fail("<joint_origin joint=\"" + names[static_cast<size_t>(i)] +
              "\"> is given twice (first at line " + std::to_string(seen[static_cast<size_t>(i)]) +
              ")");
    }
    seen[static_cast<size_t>(i)] = e->line;
    cal.joints[static_cast<size_t>(i)] = parseFrameError(*e);
  }
}

/// Shortest text that parses back to v (locale-independent).
std::string shortest(double v) {
  if (v == 0.0) return "0";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return {buf, r.ptr};
}

std::string vecText(const Vec3& v, double unit) {
  return shortest(v.x() / unit) + " " + shortest(v.y() / unit) + " " + shortest(v.z() / unit);
}

/// ` xyz_mm="…" rpy_mrad="…" [sigma_xyz_mm="…"] [sigma_rpy_mrad="…"]`
std::string frameErrorAttributes(const FrameError& f) {
  std::string a =
      " xyz_mm=\"" + vecText(f.dxyz, kMm) + "\" rpy_mrad=\"" + vecText(f.drpy, kMrad) + "\"";
  if (!f.sigma_xyz.isZero(0.0)) a += " sigma_xyz_mm=\"" + vecText(f.sigma_xyz, kMm) + "\"";
  if (!f.sigma_rpy.isZero(0.0)) a += " sigma_rpy_mrad=\"" + vecText(f.sigma_rpy, kMrad) + "\"";
  return a;
}

bool stated(const FrameError& f) {
  return !f.isZero() || !f.sigma_xyz.isZero(0.0) || !f.sigma_rpy.isZero(0.0);
}

}  // namespace

GeometryCalibration parseCalibration(const XmlNode& block,
                                     const std::array<std::string, 6>& joint_names) {
  allowOnly(block, {"source", "date", "measurements", "residual_mm"});
  allowChildren(block, {"joint_origin", "base", "tool"});
  allowAtMostOnce(block, {"base", "tool"});
  GeometryCalibration cal;
  cal.line = block.line;
  cal.source = block.str("source", "");
  if (cal.source.empty())
    block.fail("<calibration> needs a source= (who measured it, how; or \"estimate: ...\")");
  cal.date = block.str("date", "");
  const double n = block.number("measurements", 0.0);
  if (!(n >= 0 && n <= 1e9 && std::floor(n) == n))
    block.fail("<calibration> measurements must be a whole number >= 0");
  cal.measurements = static_cast<int>(n);
  cal.residual_rms = block.number("residual_mm", 0.0) * kMm;
  if (cal.residual_rms < 0) block.fail("<calibration> residual_mm must be >= 0");
  parseJointOrigins(block, joint_names, cal);
  for (const char* name : {"base", "tool"}) {
    if (const XmlNode* e = block.child(name)) {
      allowOnly(*e, {"xyz_mm", "rpy_mrad", "sigma_xyz_mm", "sigma_rpy_mrad"});
      (std::string(name) == "base" ? cal.base : cal.tool) = parseFrameError(*e);
    }
  }
  return cal;
}

std::string calibrationXml(const GeometryCalibration& cal,
                           const std::array<std::string, 6>& joint_names,
                           const std::string& indent) {
  std::string x = indent + "<calibration source=\"" + escapeXml(cal.source, '"') + "\"";
  if (!cal.date.empty()) x += " date=\"" + escapeXml(cal.date, '"') + "\"";
  x += " measurements=\"" + std::to_string(cal.measurements) + "\"";
  x += " residual_mm=\"" + shortest(cal.residual_rms / kMm) + "\">\n";
  if (stated(cal.base)) x += indent + "  <base" + frameErrorAttributes(cal.base) + "/>\n";
  for (size_t i = 0; i < 6; ++i) {
    if (!stated(cal.joints[i])) continue;
    x += indent + "  <joint_origin joint=\"" + escapeXml(joint_names[i], '"') + "\"" +
         frameErrorAttributes(cal.joints[i]) + "/>\n";
  }
  if (stated(cal.tool)) x += indent + "  <tool" + frameErrorAttributes(cal.tool) + "/>\n";
  return x + indent + "</calibration>\n";
}

}  // namespace roprec
