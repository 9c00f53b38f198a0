#include "compensator/robot/card_check.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "compensator/robot/urdf_loader.hpp"
#include "compensator/support/c_format.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/str_cat.hpp"

namespace roprec {

namespace {

using Vec6d = Eigen::Matrix<double, 6, 1>;

/// Directions agree within ~1.4 mrad.
constexpr double kAligned = 1.0 - 1e-6;

/// How far a measured (calibrated) geometry may plausibly lie from the nominal one
/// (docs/cards.md §3): up to 1 mm / 5 mrad is a calibration offset, up to 5 mm / 20 mrad a warning,
/// beyond an error (a unit, frame or convention mistake, not a calibration).
constexpr double kCalibrationWarnM = 1e-3;
constexpr double kCalibrationErrorM = 5e-3;
constexpr double kCalibrationWarnRad = 5e-3;
constexpr double kCalibrationErrorRad = 20e-3;

/// The angle (rad) between two unit directions (|cos| clamped to 1).
double angleBetween(const Vec3& a, const Vec3& b) { return std::acos(std::min(1.0, a.dot(b))); }

/// Verdict of an offset against the calibration bounds: "ok", "WARNING" or "ERROR".
const char* offsetVerdict(double metres, double radians) {
  if (metres > kCalibrationErrorM || radians > kCalibrationErrorRad) return "ERROR";
  if (metres > kCalibrationWarnM || radians > kCalibrationWarnRad) return "WARNING";
  return "ok";
}

/// " (a calibrated URDF: N mrad off the convention)" for a direction within the calibration bound.
std::string calibratedNote(double radians) {
  return " (calibrated URDF? " + cFixed(radians * 1e3, 2) + " mrad off the convention)";
}

std::string axisText(const Vec3& a) {
  static const char* names[3] = {"x", "y", "z"};
  for (int c = 0; c < 3; ++c) {
    if (std::abs(a[c]) > kAligned) return std::string(a[c] > 0 ? "+" : "-") + names[c];
  }
  return "(" + cFixed(a.x(), 3) + ", " + cFixed(a.y(), 3) + ", " + cFixed(a.z(), 3) + ")";
}

struct Checker {
  const Robot& robot;
  CardCheckReport report;
  std::optional<VendorConvention> conv;

  [[nodiscard]] const RobotCard& card() const { return robot.card; }
  void add(std::string check, std::string value, std::string reference, std::string verdict) {
    report.rows.push_back(
        {std::move(check), std::move(value), std::move(reference), std::move(verdict)});
  }
  void find(bool error, int line, std::string message, std::string hint) {
    report.findings.push_back({error, card().file, line, std::move(message), std::move(hint)});
  }
};

// ---- frames -----------------------------------------------------------------------------------

bool urdfHasLink(const std::string& urdf, const std::string& name) {
  for (const std::string& l : urdfLinkNames(urdf))
    if (l == name) return true;
  return false;
}

/// Flange +z out of the flange. Returns false when it is not.
bool checkFlange(Checker& c) {
  bool known = true;
  const double cz = flangeZOutCosine(c.robot.chain, &known);
  const std::string value = "z.out = " + cFixed(cz, 6);
  const double off = std::acos(std::clamp(cz, -1.0, 1.0));
  if (cz <= kAligned && off <= kCalibrationErrorRad) {
    // a calibrated URDF: the flange is off the joint-6 axis by its calibration
    const char* verdict = offsetVerdict(0.0, off);
    c.add("flange z out of the flange (" + c.card().flange_link + ")", value + calibratedNote(off),
          "1", verdict);
    if (std::string(verdict) != "ok") {
      c.find(false, c.card().urdf_line,
             "flange '" + c.card().flange_link + "' z is " + cFixed(off * 1e3, 2) +
                 " mrad off the joint-6 axis, more than a calibration usually moves it",
             "check that the URDF is the robot's (a calibrated URDF is within a few mrad)");
    }
    return true;
  }
  if (cz > kAligned) {
    c.add("flange z out of the flange (" + c.card().flange_link + ")", value, "1",
          known ? "ok" : "WARNING");
    if (!known) {
      c.find(false, c.card().urdf_line,
             "flange '" + c.card().flange_link +
                 "' lies on the wrist centre, so which way is 'out' cannot be told from the "
                 "chain; +joint-6 axis assumed",
             "confirm that the flange frame's z points away from the robot");
    }
    return true;
  }
  c.add("flange z out of the flange (" + c.card().flange_link + ")", value, "1", "ERROR");
  std::string hint =
      "flange_link must be the controller's tool-0 frame, z out of the flange (ROS-Industrial "
      "URDFs: tool0; their `flange` is x-out)";
  if (c.card().flange_link != "tool0" && urdfHasLink(c.card().urdf_path, "tool0"))
    hint = "use flange_link=\"tool0\" (the ROS-Industrial z-out tool frame); " + hint;
  c.find(true, c.card().urdf_line,
         "flange_link '" + c.card().flange_link + "' does not have z out of the flange (cos " +
             cFixed(cz, 6) + " between its z and the joint-6 axis pointing out)",
         hint);
  return false;
}

void checkHome(Checker& c) {
  const VendorConvention& v = *c.conv;
  const Vec6d q = fromControllerJoints(c.card(), v.home_deg * kDeg);
  const Pose T = chainForwardKinematics(c.robot.chain, q);
  const Vec3 z = T.linear().col(2);
  const Vec3 x = T.linear().col(0);
  const Vec3 abc = zyxFromRotation(T.linear()) / kDeg;
  const std::string value = "abc " + cFixed(abc.x(), 3) + ", " + cFixed(abc.y(), 3) + ", " +
                            cFixed(abc.z(), 3) + " (z " + axisText(z) + ", x " + axisText(x) + ")";
  const std::string ref =
      v.home_orientation + " (z " + axisText(v.home_z) + ", x " + axisText(v.home_x) + ")";
  const bool ok = z.dot(v.home_z) > kAligned && x.dot(v.home_x) > kAligned;
  const double off = std::max(angleBetween(z, v.home_z), angleBetween(x, v.home_x));
  if (!ok && off <= kCalibrationErrorRad) {  // a calibrated URDF
    const char* verdict = offsetVerdict(0.0, off);
    c.add("flange at " + v.home_text, value + calibratedNote(off), ref, verdict);
    if (std::string(verdict) != "ok") {
      c.find(false, c.card().urdf_line,
             "at the " + v.home_text + " the flange is " + cFixed(off * 1e3, 2) +
                 " mrad off the vendor's orientation, more than a calibration usually moves it",
             "check that the URDF is the robot's (a calibrated URDF is within a few mrad)");
    }
    return;
  }
  c.add("flange at " + v.home_text, value, ref, ok ? "ok" : "ERROR");
  if (!ok) {
    c.find(
        true, c.card().urdf_line,
        "at the " + vendorName(c.card().vendor) + " " + v.home_text + " the flange is oriented " +
            value + ", the controller shows " + ref,
        "check flange_link (z out of the flange), the joints' controller_sign / "
        "controller_offset_deg and j23_coupling against the vendor convention (robots/README.md)");
  }
}

void checkBase(Checker& c) {
  const ChainZeroGeometry g = zeroGeometry(c.robot.chain);
  const double h = g.p[1].z();
  const std::string value = "J2 axis at z = " + cFixed(h * 1e3, 3) + " mm";
  if (c.conv->world_at_j2) {
    const bool ok = std::abs(h) < 1e-6;
    if (!ok && std::abs(h) <= kCalibrationErrorM) {  // a calibrated URDF's J2 height
      const char* verdict = offsetVerdict(std::abs(h), 0.0);
      c.add("base frame (FANUC World at J2 height)", value + " (calibrated URDF?)", "z = 0",
            verdict);
      if (std::string(verdict) != "ok") {
        c.find(false, c.card().urdf_line,
               "the J2 axis is " + cFixed(h * 1e3, 3) +
                   " mm off the World frame's z = 0, more than a calibration usually moves it",
               "check base_link (FANUC World at J2 height)");
      }
      return;
    }
    c.add("base frame (FANUC World at J2 height)", value, "z = 0", ok ? "ok" : "ERROR");
    if (!ok) {
      c.find(true, c.card().urdf_line,
             "base_link '" + c.card().base_link + "' is " + cFixed(h * 1e3, 3) +
                 " mm below the J2 axis, but FANUC positions are in the World frame at J2 height",
             "use base_link=\"base\" (ROS-Industrial FANUC URDFs put `base` at J2 height) or add "
             "a fixed link there");
    }
    return;
  }
  const bool ok = h > 1e-6;
  c.add("base frame (mounting surface, below J2)", value, "z > 0", ok ? "ok" : "WARNING");
  if (!ok) {
    c.find(false, c.card().urdf_line,
           "base_link '" + c.card().base_link + "' is not below the J2 axis; the " +
               vendorName(c.card().vendor) + " base frame is on the mounting surface",
           "use the URDF root (ROS-Industrial base_link)");
  }
}

// ---- joints -----------------------------------------------------------------------------------

void checkAxes(Checker& c) {
  const ChainZeroGeometry g = zeroGeometry(c.robot.chain);
  for (int i = 0; i < 6; ++i) {
    const JointCard& j = c.card().joints[static_cast<size_t>(i)];
    const Vec3& e = c.conv->axes[static_cast<size_t>(i)];
    const double d = g.a[static_cast<size_t>(i)].dot(e);
    std::string value = "URDF " + axisText(g.a[static_cast<size_t>(i)]) + ", sign " +
                        cGeneral(j.controller_sign, 2);
    const double off = std::acos(std::min(1.0, std::abs(d)));
    if (std::abs(d) < kAligned && off <= kCalibrationErrorRad) {  // a calibrated URDF
      value += calibratedNote(off);
      if (off > kCalibrationWarnRad) {
        c.find(false, j.line,
               "joint '" + j.name + "' axis is " + cFixed(off * 1e3, 2) + " mrad off the " +
                   vendorName(c.card().vendor) + " axis " + std::to_string(i + 1) +
                   ", more than a calibration usually moves it",
               "check that the URDF is the robot's (a calibrated URDF is within a few mrad)");
      }
    } else if (std::abs(d) < kAligned) {
      c.add("joint " + j.name + " axis", value, axisText(e), "ERROR");
      c.find(
          true, j.line,
          "joint '" + j.name + "' turns about " + axisText(g.a[static_cast<size_t>(i)]) +
              " at the URDF zero pose, the " + vendorName(c.card().vendor) + " axis " +
              std::to_string(i + 1) + " about " + axisText(e),
          "the URDF's zero pose differs from the vendor's: fix the URDF or the card's base_link");
      continue;
    }
    const double sign = d > 0 ? 1.0 : -1.0;
    const bool ok = j.controller_sign == sign;
    c.add("joint " + j.name + " axis", value, axisText(e),
          !ok                         ? "ERROR"
          : off > kCalibrationWarnRad ? "WARNING"
                                      : "ok");
    if (!ok) {
      c.find(true, j.line,
             "joint '" + j.name + "': the URDF axis is " + axisText(g.a[static_cast<size_t>(i)]) +
                 " and the " + vendorName(c.card().vendor) + " axis " + std::to_string(i + 1) +
                 " turns positive about " + axisText(e),
             "set controller_sign=\"" + cGeneral(sign, 2) + "\"");
    }
  }
  const double s2 = g.a[1].dot(c.conv->axes[1]) > 0 ? 1.0 : -1.0;
  const double want = c.conv->j23_coupled ? -s2 : 0.0;
  const bool ok = c.card().j23_coupling == want;
  c.add("j23_coupling", cGeneral(c.card().j23_coupling, 3), cGeneral(want, 3), ok ? "ok" : "ERROR");
  if (!ok) {
    c.find(true, c.card().controller_line > 0 ? c.card().controller_line : c.card().urdf_line,
           "j23_coupling is " + cGeneral(c.card().j23_coupling, 3) + ", the " +
               vendorName(c.card().vendor) + " convention needs " + cGeneral(want, 3),
           c.conv->j23_coupled ? "FANUC J3 is measured from the horizontal: <controller "
                                 "j23_coupling=\"" +
                                     cGeneral(want, 3) + "\"/>"
                               : "only FANUC couples J2 and J3: j23_coupling=\"0\"");
  }
}

void checkLimits(Checker& c) {
  std::optional<Vec6d> home;
  if (c.conv) home = fromControllerJoints(c.card(), c.conv->home_deg * kDeg);
  for (int i = 0; i < 6; ++i) {
    const ChainJoint& j = c.robot.chain.joints[static_cast<size_t>(i)];
    const JointCard& jc = c.card().joints[static_cast<size_t>(i)];
    const std::string value = cFixed(j.lower / kDeg, 1) + " .. " + cFixed(j.upper / kDeg, 1);
    std::string problem;
    if (j.continuous) {
      problem = "is continuous (no limits): the controller has software limits";
    } else if (home && ((*home)[i] < j.lower - 1e-9 || (*home)[i] > j.upper + 1e-9)) {
      problem = "range does not contain the vendor's " + c.conv->home_text + " (" +
                cFixed((*home)[i] / kDeg, 1) + " deg in the URDF)";
    } else if (j.upper - j.lower > 900 * kDeg + 1e-9) {
      problem = "range exceeds 900 deg (limits in radians?)";
    }
    c.add("joint " + j.name + " range (deg, URDF)", value,
          home ? "holds home, <= 900 deg span" : "<= 900 deg span",
          problem.empty() ? "ok" : "WARNING");
    if (!problem.empty()) {
      c.find(false, jc.line, strCat("joint '", j.name, "' ", problem, " (", value, " deg)"),
             "compare with the data sheet's axis ranges and the joint's controller_sign / "
             "controller_offset_deg");
    }
  }
}

// ---- numbers ----------------------------------------------------------------------------------

void checkStiffness(Checker& c) {
  if (!c.card().has_stiffness) {
    c.add("joint stiffness", "missing", "all 6", "ERROR");
    c.find(true, c.card().urdf_line, "the card does not give every joint a stiffness=",
           "give stiffness=\"N m/rad\" with its source on each <joint> (roprec card new writes "
           "the class values)");
    return;
  }
  const StiffnessClass cls = stiffnessClass(c.card().rated_payload_kg);
  for (int i = 0; i < 6; ++i) {
    const JointCard& j = c.card().joints[static_cast<size_t>(i)];
    const double ratio = j.stiffness / cls.k[i];
    const double off = std::max(ratio, 1.0 / ratio);
    const std::string verdict =
        off >= 99.5 ? "ERROR" : (off >= 9.95 ? "WARNING" : (j.estimated() ? "estimate" : "ok"));
    c.add("k" + std::to_string(i + 1) + " " + j.name + " (N m/rad)", formatCardNumber(j.stiffness),
          formatCardNumber(cls.k[i]) + " (class)", verdict);
    if (off >= 9.95) {
      c.find(off >= 99.5, j.line,
             "joint '" + j.name + "': stiffness " + formatCardNumber(j.stiffness) + " N m/rad is " +
                 cGeneral(off, 3) + "x " + (ratio > 1 ? "above" : "below") + " the class value " +
                 formatCardNumber(cls.k[i]) + " N m/rad (" + cls.rule + ")",
             "check the unit (N m/rad, not N mm/rad) and rated_payload_kg");
    }
  }
}

void checkRepeatability(Checker& c) {
  const double rp = c.card().rp_mm;
  const bool odd = rp < 0.005 || rp > 0.5;
  const bool est = c.card().rp_source.rfind("estimate:", 0) == 0;
  c.add("repeatability RP (mm)", cGeneral(rp, 4), "0.005 .. 0.5",
        odd ? "WARNING" : (est ? "estimate" : "ok"));
  if (odd) {
    c.find(false, c.card().urdf_line,
           "repeatability rp_mm " + cGeneral(rp, 4) + " mm is outside 0.005..0.5 mm",
           "ISO 9283 pose repeatability RP from the data sheet, in mm");
  }
}

void checkInertials(Checker& c) {
  if (!c.card().gravity_modelled) {
    c.add("link inertials", "gravity not modelled", "-", "ok");
    return;
  }
  const ChainDescription raw =
      loadUrdfChain(c.card().urdf_path, {c.robot.chain.base_link, c.robot.chain.tip_link});
  const std::array<bool, 6> ph = placeholderInertials(raw);
  double moving = 0;
  for (int i = 0; i < 6; ++i) {
    const std::string& link = c.robot.chain.joints[static_cast<size_t>(i)].child_link;
    bool overridden = false;
    for (const auto& l : c.card().links) overridden = overridden || l.name == link;
    const Inertial& in = c.robot.chain.inertials[static_cast<size_t>(i)];
    moving += in.mass;
    std::string from = overridden ? "card <link>" : (in.mass > 0 ? "URDF" : "none");
    std::string verdict = "ok";
    if (!overridden && ph[static_cast<size_t>(i)]) {
      from = "URDF placeholder";
      verdict = "ERROR";
      c.find(true, c.card().urdf_line,
             "link '" + link + "' has a placeholder inertial in the URDF (" + cGeneral(in.mass, 4) +
                 " kg, the same as other links: ROS-Industrial packages carry no real masses) "
                 "and the card would use it as the link's real weight",
             "give <link name=\"" + link +
                 "\" mass_kg=... com_mm=... inertia_kgm2=... source=\"estimate: ...\"/> (roprec "
                 "card new writes class estimates)");
    } else if (overridden) {
      for (const auto& l : c.card().links)
        if (l.name == link && l.source.rfind("estimate:", 0) == 0) verdict = "estimate";
    }
    c.add("link " + link + " mass (kg)", cGeneral(in.mass, 5) + " from " + from, "> 0", verdict);
  }
  const double P = c.card().rated_payload_kg;
  if (P > 0) {
    const double ratio = moving / P;
    const bool odd = ratio < 1.5 || ratio > 40;
    c.add("moving mass / rated payload", cGeneral(ratio, 3), "1.5 .. 40", odd ? "WARNING" : "ok");
    if (odd) {
      c.find(false, c.card().urdf_line,
             "the moving links weigh " + cGeneral(moving, 4) + " kg, " + cGeneral(ratio, 3) +
                 "x the rated payload " + cGeneral(P, 4) + " kg (industrial 6R arms: about 3..25x)",
             "check the link masses (kg) and rated_payload_kg against the data sheet");
    }
  }
}

}  // namespace

// ---- public -----------------------------------------------------------------------------------

std::optional<VendorConvention> vendorConvention(Vendor v) {
  if (v == Vendor::kGeneric) return std::nullopt;
  VendorConvention c;
  const Vec3 X = Vec3::UnitX(), Y = Vec3::UnitY(), Z = Vec3::UnitZ();
  c.home_deg.setZero();
  if (v == Vendor::kKuka) {
    c.axes = {-Z, Y, Y, -X, Y, -X};
    c.home_deg[1] = -90;
    c.home_deg[2] = 90;
    c.home_text = "HOME {0, -90, 90, 0, 0, 0}";
    c.home_orientation = "A 0, B 90, C 0";
    c.lower_arm_vertical = false;
  } else if (v == Vendor::kAbb) {
    c.axes = {Z, Y, Y, X, Y, X};
    c.home_text = "calibration position (all axes 0)";
    c.home_orientation = "q [0.7071, 0, 0.7071, 0]";
  } else {
    c.axes = {Z, Y, -Y, -X, -Y, -X};
    c.home_text = "zero position (all axes 0)";
    c.home_orientation = "W 180, P -90, R 0";
    c.home_x = Z;
    c.world_at_j2 = true;
    c.j23_coupled = true;
  }
  return c;
}

StiffnessClass stiffnessClass(double payload_kg) {
  StiffnessClass s;
  s.k << 1.58e7, 6.12e6, 5.28e6, 4.66e5, 2.19e5, 3.49e5;
  s.factor = (payload_kg > 0 && payload_kg < 120) ? payload_kg / 120.0 : 1.0;
  s.k *= s.factor;
  s.rule =
      "class rule: identified KUKA KR500 set (Jiao et al. 2022, Eq. 38) unscaled for 120-500 kg "
      "arms, times payload/120 kg below";
  return s;
}

ChainZeroGeometry zeroGeometry(const ChainDescription& chain) {
  ChainZeroGeometry g;
  Pose T = Pose::Identity();
  for (size_t i = 0; i < 6; ++i) {
    T = T * chain.joints[i].origin;
    g.p[i] = T.translation();
    g.a[i] = (T.linear() * chain.joints[i].axis).normalized();
  }
  return g;
}

double flangeZOutCosine(const ChainDescription& chain, bool* known) {
  // In the frame of link 6 at q6 = 0 (= joint-6 frame): joint-5 origin and the tip.
  const Pose& o6 = chain.joints[5].origin;
  const Vec3 p_L6_j5 = -(o6.linear().transpose() * o6.translation());
  const Vec3 axis = chain.joints[5].axis.normalized();
  const double s = (chain.tip.translation() - p_L6_j5).dot(axis);
  const bool k = std::abs(s) > 1e-3;
  if (known != nullptr) *known = k;
  const Vec3 out = (k && s < 0) ? Vec3(-axis) : axis;
  return chain.tip.linear().col(2).dot(out);
}

std::string lowerArmProblem(const ChainDescription& chain,
                            const Eigen::Matrix<double, 6, 1>& q_urdf, const VendorConvention& v) {
  Pose T = Pose::Identity();
  std::array<Vec3, 3> p;
  for (size_t i = 0; i < 3; ++i) {
    T = T * chain.joints[i].origin;
    p[i] = T.translation();
    T.linear() = T.linear() *
                 Eigen::AngleAxisd(q_urdf[static_cast<int>(i)], chain.joints[i].axis.normalized())
                     .toRotationMatrix();
  }
  const Vec3 d = p[2] - p[1];
  // up to a calibrated URDF's tilt (kCalibrationErrorRad); a wrong convention is ~90° off
  const double tol = kCalibrationErrorRad * d.norm();
  const bool ok = v.lower_arm_vertical ? (std::abs(d.x()) + std::abs(d.y()) <= tol && d.z() > 0)
                                       : (std::abs(d.z()) + std::abs(d.y()) <= tol && d.x() > 0);
  if (ok) return "";
  return "at the controller's zero pose the lower arm (" + chain.joints[1].name + " -> " +
         chain.joints[2].name + ") points (" + cFixed(d.x() * 1e3, 1) + ", " +
         cFixed(d.y() * 1e3, 1) + ", " + cFixed(d.z() * 1e3, 1) +
         ") mm, the vendor's zero pose has it " +
         (v.lower_arm_vertical ? "vertical (J3 above J2)" : "horizontal (J3 in front of J2)");
}

std::array<bool, 6> placeholderInertials(const ChainDescription& urdf_chain) {
  std::array<bool, 6> out{};
  for (size_t i = 0; i < 6; ++i) {
    const Inertial& a = urdf_chain.inertials[i];
    if (!(a.mass > 0)) continue;
    int same = 0;
    for (size_t j = 0; j < 6; ++j) {
      const Inertial& b = urdf_chain.inertials[j];
      if (b.mass == a.mass && (b.inertia - a.inertia).norm() <= 1e-12 * (1 + a.inertia.norm()))
        ++same;
    }
    out[i] = same >= 3;
  }
  return out;
}

int CardCheckReport::errors() const {
  int n = 0;
  for (const auto& f : findings) n += f.error ? 1 : 0;
  return n;
}
int CardCheckReport::warnings() const { return static_cast<int>(findings.size()) - errors(); }

namespace {

/// The card's <calibration> offsets against the plausible bounds (one row per stated error).
void checkCalibration(Checker& c) {
  const GeometryCalibration& cal = *c.card().calibration;
  const auto row = [&](const std::string& what, const FrameError& e) {
    if (e.isZero()) return;
    const double m = e.dxyz.norm();
    const double rad = e.drpy.norm();
    const char* verdict = offsetVerdict(m, rad);
    c.add("calibration " + what, cFixed(m * 1e3, 3) + " mm, " + cFixed(rad * 1e3, 3) + " mrad",
          "<= 1 mm, <= 5 mrad", verdict);
    if (std::string(verdict) == "ok") return;
    c.find(std::string(verdict) == "ERROR", cal.line,
           "<calibration> " + what + " moves by " + cFixed(m * 1e3, 3) + " mm / " +
               cFixed(rad * 1e3, 3) + " mrad (a calibration: up to ~1 mm / 5 mrad; an error " +
               "above 5 mm / 20 mrad)",
           "check the units (xyz_mm in mm, rpy_mrad in mrad) and the frame (docs/cards.md §5)");
  };
  row("base", cal.base);
  for (size_t i = 0; i < 6; ++i) row("joint " + c.card().joints[i].name, cal.joints[i]);
  row("tool", cal.tool);
}

}  // namespace

CardCheckReport checkRobotCard(const Robot& robot) {
  Checker c{robot, {}, vendorConvention(robot.card.vendor)};
  c.add("vendor", robot.card.vendor_label.empty() ? "(none)" : robot.card.vendor_label,
        "KUKA | ABB | FANUC", c.conv ? "ok" : "WARNING");
  const bool flange_ok = checkFlange(c);
  if (c.conv) {
    checkBase(c);
    checkAxes(c);
    const std::string arm =
        lowerArmProblem(robot.chain, fromControllerJoints(robot.card, Vec6d::Zero()), *c.conv);
    c.add("lower arm at the controller's zero", arm.empty() ? "as the vendor's" : "differs",
          c.conv->lower_arm_vertical ? "vertical" : "horizontal", arm.empty() ? "ok" : "ERROR");
    if (!arm.empty()) {
      c.find(true, robot.card.joints[1].line, arm,
             "the URDF's zero pose is not the " + vendorName(robot.card.vendor) +
                 " one: check the vendor, or set controller_offset_deg on joints 2 and 3");
    }
    if (flange_ok) checkHome(c);
  } else {
    c.find(false, robot.card.urdf_line,
           "vendor '" + robot.card.vendor_label +
               "' is not KUKA, ABB or FANUC: joint signs, home pose and base frame not checked",
           "set vendor=\"KUKA|ABB|FANUC\" if it is one of them");
  }
  checkLimits(c);
  checkStiffness(c);
  checkRepeatability(c);
  checkInertials(c);
  if (robot.card.calibration) checkCalibration(c);
  return c.report;
}

void throwFirstCardError(const CardCheckReport& report, const RobotCard& card) {
  for (const CardFinding& f : report.findings) {
    if (!f.error) continue;
    throw InputError(f.file, f.line,
                     f.message + "; hint: " + f.hint + " (roprec card check " + card.file + ")");
  }
}

}  // namespace roprec
