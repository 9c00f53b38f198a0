#pragma once
/// \file robot_card.hpp
/// The robot card (`robots/<name>/robot.xml`, docs/contract.md §5): which URDF and links, and the
/// numbers the kinematic description lacks — joint stiffness k (N m/rad), servo gains, ISO 9283
/// pose repeatability RP, the controller's joint convention — each with its source. A source
/// beginning with `estimate:` marks an estimated value.
///
/// Controller joint convention (for configuration flags and program joint values):
///   theta_ctrl_i = sign_i * theta_urdf_i + offset_i  (+ j23_coupling * theta_urdf_2 for i = 3)
/// e.g. FANUC, whose controller J3 is measured from the horizontal (J2/J3 coupled).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "compensator/robot/chain.hpp"

namespace roprec {

enum class Vendor { kGeneric, kKuka, kAbb, kFanuc };

/// "KUKA" / "ABB" / "FANUC" (case-insensitive) or generic.
Vendor vendorFromString(const std::string& s);
std::string vendorName(Vendor v);

struct JointCard {
  std::string name;
  double stiffness{0.0};                ///< k_i, N m/rad (0 = not given)
  std::optional<double> position_gain;  ///< Kv, 1/s (position-loop gain); absent: ideal servo
  std::optional<double> velocity_gain;  ///< N m s/rad, link side (velocity-loop gain)
  double motor_inertia{0.0};            ///< reflected rotor inertia, kg m^2, link side
  std::string source;                   ///< citation, or "estimate: reason"
  double controller_sign{1.0};
  double controller_offset{0.0};  ///< rad
  int line{0};
  [[nodiscard]] bool estimated() const;
};

struct RobotCard {
  std::string file;  ///< robot.xml path ("" for a bare URDF)
  std::string name;
  Vendor vendor{Vendor::kGeneric};
  std::string vendor_label;  ///< as written
  std::string model;
  std::string urdf_path;  ///< resolved path
  std::string base_link;
  std::string flange_link;
  std::array<JointCard, 6> joints;
  bool has_stiffness{false};
  double rp_mm{0.0};  ///< ISO 9283 pose repeatability RP, mm (0 = unknown)
  std::string rp_source;
  bool gravity_compensated{false};          ///< controller already compensates gravity deflection
  double calibration_load_kg{0.0};          ///< load the compensation was calibrated for
  Vec3 calibration_load_com{Vec3::Zero()};  ///< m, flange frame
  double j23_coupling{0.0};                 ///< see file comment
  double rated_payload_kg{0.0};
  std::string dimensions_source;
  std::string inertial_source;
};

/// Loads a robot card; the URDF path is resolved relative to the card's folder.
RobotCard loadRobotCard(const std::string& path);

/// Folder holding the bundled robots, the first of:
/// 1. the environment variable ROPREC_ROBOTS_DIR, if set and not empty;
/// 2. `../share/roprec/robots` relative to the folder of the loaded libroprec shared object
///    (found with dladdr), if that folder exists: an installed or relocated prefix;
/// 3. the source tree's robots/ compiled in at build time (use from the build tree).
std::string bundledRobotsDir();
/// Names of the bundled robots (sorted).
std::vector<std::string> bundledRobotNames();

/// A loaded robot: its card and its kinematic chain base_link -> flange_link.
struct Robot {
  RobotCard card;
  ChainDescription chain;
};

struct RobotRequest {
  std::string robot;      ///< bundled name, path to robot.xml, or path to a .urdf
  std::string base_link;  ///< overrides (bare URDF)
  std::string tip_link;
};

/// Resolves and loads a robot. Unknown names throw InputError naming the bundled robots.
Robot loadRobot(const RobotRequest& request);

/// Controller joint values (rad) from URDF joint values (rad), and back.
Eigen::Matrix<double, 6, 1> toControllerJoints(const RobotCard& card,
                                               const Eigen::Matrix<double, 6, 1>& q_urdf);
Eigen::Matrix<double, 6, 1> fromControllerJoints(const RobotCard& card,
                                                 const Eigen::Matrix<double, 6, 1>& q_ctrl);

}  // namespace roprec
