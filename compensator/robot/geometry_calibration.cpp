#include "compensator/robot/geometry_calibration.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

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

int calibrationComponent(const std::string& name) {
  static const char* const kAxes[] = {"x", "y", "z", "rx", "ry", "rz"};
  const auto axis = [&](const std::string& tail, const char* const* names) {
    for (int a = 0; a < 6; ++a)
      if (tail == names[a]) return a;
    return -1;
  };
  const size_t us = name.find('_');
  if (us == std::string::npos) return -1;
  const std::string head = name.substr(0, us);
  const std::string tail = name.substr(us + 1);
  int first = -1;
  if (head == "base") first = 0;
  if (head == "tip") first = 42;
  if (head.size() == 2 && head[0] == 'j' && head[1] >= '1' && head[1] <= '6')
    first = 6 + 6 * (head[1] - '1');
  if (first >= 0) {
    const int a = axis(tail, kAxes);
    return a < 0 ? -1 : first + a;
  }
  return -1;
}

namespace {

constexpr double kMm = 1e-3;    // m per mm
constexpr double kMrad = 1e-3;  // rad per mrad

/// Card unit of a component (mm for lengths, mrad for angles), in SI.
double componentUnit(int component) {
  const int a = component % 6;
  return a < 3 ? kMm : kMrad;
}

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

/// 9 significant digits (the factor's entries; "C" locale).
std::string digits9(double v) {
  if (v == 0.0) return "0";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 9);
  return {buf, r.ptr};
}

/// The lower-triangular factor L (card units) of the covariance, Σ = L Lᵀ: Cholesky, with a
/// jitter of 1e-12 of the largest variance when Σ is only semi-definite (rounding).
Eigen::MatrixXd covarianceFactor(const GeometryCalibration& cal) {
  const auto n = static_cast<Eigen::Index>(cal.covariance_parameters.size());
  Eigen::VectorXd unit(n);
  for (Eigen::Index i = 0; i < n; ++i)
    unit[i] =
        componentUnit(calibrationComponent(cal.covariance_parameters[static_cast<size_t>(i)]));
  const Eigen::MatrixXd S =
      unit.cwiseInverse().asDiagonal() * cal.covariance * unit.cwiseInverse().asDiagonal();
  Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (S + S.transpose()));
  for (double jitter = 1e-12; llt.info() != Eigen::Success && jitter < 1e-3; jitter *= 100) {
    Eigen::MatrixXd Sj = 0.5 * (S + S.transpose());
    Sj.diagonal().array() += jitter * S.diagonal().maxCoeff();
    llt.compute(Sj);
  }
  return llt.matrixL();
}

std::string covarianceXml(const GeometryCalibration& cal, const std::string& indent) {
  std::string names;
  for (const std::string& n : cal.covariance_parameters) names += (names.empty() ? "" : " ") + n;
  std::string x = indent + "<covariance parameters=\"" + names + "\">\n";
  const Eigen::MatrixXd L = covarianceFactor(cal);
  for (Eigen::Index i = 0; i < L.rows(); ++i) {
    std::string row;
    for (Eigen::Index k = 0; k <= i; ++k) row += (k ? " " : "") + digits9(L(i, k));
    x += indent + "  <row l=\"" + row + "\"/>\n";
  }
  return x + indent + "</covariance>\n";
}

bool stated(const FrameError& f) {
  return !f.isZero() || !f.sigma_xyz.isZero(0.0) || !f.sigma_rpy.isZero(0.0);
}

/// `<covariance parameters="…">` with one `<row l="…"/>` per parameter: row i holds the i+1
/// entries of the lower-triangular factor L (card units) with Σ = L Lᵀ.
void parseCovariance(const XmlNode& e, GeometryCalibration& cal) {
  allowOnly(e, {"parameters"});
  allowChildren(e, {"row"});
  std::istringstream names(e.str("parameters"));
  std::vector<int> seen;
  for (std::string n; names >> n;) {
    const int c = calibrationComponent(n);
    if (c < 0)
      e.fail("<covariance> parameter '" + n +
             "' is not a calibration component (base_x…base_rz, j1_x…j6_rz, tip_x…tip_rz)");
    if (std::find(seen.begin(), seen.end(), c) != seen.end())
      e.fail("<covariance> parameter '" + n + "' is given twice");
    seen.push_back(c);
    cal.covariance_parameters.push_back(n);
  }
  const std::vector<const XmlNode*> rows = e.childrenNamed("row");
  const auto n = static_cast<int>(seen.size());
  if (n == 0 || static_cast<int>(rows.size()) != n)
    e.fail("<covariance> needs one <row> per parameter (" + std::to_string(n) + "), got " +
           std::to_string(rows.size()));
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    allowOnly(*rows[static_cast<size_t>(i)], {"l"});
    const Eigen::VectorXd v = rows[static_cast<size_t>(i)]->numbers("l", i + 1);
    for (int k = 0; k <= i; ++k) L(i, k) = v[k] * componentUnit(seen[static_cast<size_t>(i)]);
  }
  cal.covariance = L * L.transpose();
}

}  // namespace

GeometryCalibration parseCalibration(const XmlNode& block,
                                     const std::array<std::string, 6>& joint_names) {
  allowOnly(block, {"source", "date", "measurements", "residual_mm", "model_error_mm"});
  allowChildren(block, {"joint_origin", "base", "tool", "covariance"});
  allowAtMostOnce(block, {"base", "tool", "covariance"});
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
  cal.model_error = block.number("model_error_mm", 0.0) * kMm;
  if (cal.model_error < 0) block.fail("<calibration> model_error_mm must be >= 0");
  parseJointOrigins(block, joint_names, cal);
  for (const char* name : {"base", "tool"}) {
    if (const XmlNode* e = block.child(name)) {
      allowOnly(*e, {"xyz_mm", "rpy_mrad", "sigma_xyz_mm", "sigma_rpy_mrad"});
      (std::string(name) == "base" ? cal.base : cal.tool) = parseFrameError(*e);
    }
  }
  if (const XmlNode* e = block.child("covariance")) parseCovariance(*e, cal);
  return cal;
}

std::string calibrationXml(const GeometryCalibration& cal,
                           const std::array<std::string, 6>& joint_names,
                           const std::string& indent) {
  std::string x = indent + "<calibration source=\"" + escapeXml(cal.source, '"') + "\"";
  if (!cal.date.empty()) x += " date=\"" + escapeXml(cal.date, '"') + "\"";
  x += " measurements=\"" + std::to_string(cal.measurements) + "\"";
  x += " residual_mm=\"" + shortest(cal.residual_rms / kMm) + "\"";
  if (cal.model_error > 0) x += " model_error_mm=\"" + shortest(cal.model_error / kMm) + "\"";
  x += ">\n";
  if (stated(cal.base)) x += indent + "  <base" + frameErrorAttributes(cal.base) + "/>\n";
  for (size_t i = 0; i < 6; ++i) {
    if (!stated(cal.joints[i])) continue;
    x += indent + "  <joint_origin joint=\"" + escapeXml(joint_names[i], '"') + "\"" +
         frameErrorAttributes(cal.joints[i]) + "/>\n";
  }
  if (stated(cal.tool)) x += indent + "  <tool" + frameErrorAttributes(cal.tool) + "/>\n";
  if (!cal.covariance_parameters.empty()) x += covarianceXml(cal, indent + "  ");
  return x + indent + "</calibration>\n";
}

}  // namespace roprec
