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
///
/// Weight handling (docs/model.md §6.3, §6.6; schema robots/README.md):
///   <counterbalance joint law action r_mm d_mm psi0_deg sign length_ref_mm (spring: preload_N
///                   rate_N_per_mm | gas: pressure_ref_MPa piston_area_mm2 gas_volume_l
///                   polytropic_n) [sizing_fraction sizing_pose_deg] source/>
///       the axis-2 balancer, counterbalance.hpp;
///   <controller calibration_pose_deg="6 values, controller convention" calibration_pose_source>
///       the mastering pose (default per vendor, vendorCalibrationPoseDeg);
///   <gravity model="links|none" source/>   none: weight is not modelled at all;
///   <link name mass_kg com_mm [inertia_kgm2] source/>   replaces a chain body's URDF inertial.
///   <accuracy ap_mm source/>   absolute accuracy of the uncalibrated robot (ISO 9283 AP).
///   <calibration source [date measurements residual_mm]> <base|joint_origin joint|tool xyz_mm
///                rpy_mrad [sigma_xyz_mm sigma_rpy_mrad]/> </calibration>   the measured
///       geometric errors (geometry_calibration.hpp, docs/cards.md §5).
/// Unknown attributes of these elements (and of <controller>) throw InputError.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "compensator/robot/chain.hpp"
#include "compensator/robot/counterbalance.hpp"
#include "compensator/robot/geometry_calibration.hpp"

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
  int urdf_line{0};       ///< line of the card's <robot urdf=…> (for errors about the URDF)
  std::string base_link;
  std::string flange_link;
  std::array<JointCard, 6> joints;
  bool has_stiffness{false};
  double rp_mm{0.0};  ///< ISO 9283 pose repeatability RP, mm (0 = unknown)
  std::string rp_source;
  /// Absolute (pose) accuracy of the uncalibrated robot, mm: ISO 9283 AP or the data sheet's
  /// figure, read as the 95 % bound of the 3-D position error (`<accuracy ap_mm source/>`; 0 = not
  /// stated). The budget's absolute-accuracy term without a <calibration> (prediction.hpp).
  double accuracy_ap_mm{0.0};
  std::string accuracy_source;
  int accuracy_line{0};
  bool gravity_compensated{false};          ///< controller already compensates gravity deflection
  double calibration_load_kg{0.0};          ///< load the compensation was calibrated for
  Vec3 calibration_load_com{Vec3::Zero()};  ///< m, flange frame
  double j23_coupling{0.0};                 ///< see file comment
  double rated_payload_kg{0.0};
  std::string dimensions_source;
  std::string inertial_source;
  int controller_line{0};
  /// Mastering (calibration) pose, URDF convention, rad; the card's calibration_pose_deg or the
  /// vendor default (vendorCalibrationPoseDeg) converted with the joint convention.
  Eigen::Matrix<double, 6, 1> calibration_pose{Eigen::Matrix<double, 6, 1>::Zero()};
  std::string calibration_pose_source;
  Counterbalance counterbalance;         ///< joint < 0: none
  double balancer_sizing_fraction{0.0};  ///< stated share of τ_g,2 at the sizing pose (0: none)
  Eigen::Matrix<double, 6, 1> balancer_sizing_pose{Eigen::Matrix<double, 6, 1>::Zero()};  ///< URDF
  bool gravity_modelled{true};  ///< false: <gravity model="none"/>
  std::string gravity_source;
  struct LinkInertial {
    std::string name;
    double mass{0.0};             ///< kg
    Vec3 com{Vec3::Zero()};       ///< m, link frame
    std::optional<Mat3> inertia;  ///< kg m², about the com (absent: the URDF's, or zero)
    std::string source;
    int line{0};
  };
  std::vector<LinkInertial> links;  ///< <link> overrides of the URDF inertials
  /// The measured geometric errors relative to the URDF (<calibration>, docs/cards.md §5);
  /// absent: the robot is taken to be its nominal URDF.
  std::optional<GeometryCalibration> calibration;
};

/// The vendor's mastering/calibration pose in the controller convention, degrees: KUKA
/// {0, −90, 90, 0, 0, 0} (mastering position), ABB all 0 (calibration position), FANUC all 0
/// (zero position, J3 from the horizontal), generic all 0.
Eigen::Matrix<double, 6, 1> vendorCalibrationPoseDeg(Vendor v);

/// Loads a robot card; the URDF path is resolved relative to the card's folder.
RobotCard loadRobotCard(const std::string& path);

/// Folder holding the bundled robots, the first of:
/// 1. the environment variable ROPREC_ROBOTS_DIR, if set and not empty;
/// 2. `../share/roprec/robots` relative to the folder of the loaded libroprec shared object
///    (found with dladdr), if that folder exists: an installed or relocated prefix;
/// 3. the source tree's robots/, for the build tree only (installed: InputError with a hint).
std::string bundledRobotsDir();
/// Names of the bundled robots (sorted).
std::vector<std::string> bundledRobotNames();

/// A loaded robot: its card and its kinematic chain base_link -> flange_link.
/// `chain` is the NOMINAL chain of the URDF: the controller's model (inverse kinematics of
/// programmed targets, FK_nom). `real_chain` is the robot as it is: calibratedChain(chain,
/// *card.calibration), or a copy of `chain` when the card has no <calibration> (FK_real; every real
/// TCP, deflection and equilibrium is computed on it).
struct Robot {
  RobotCard card;
  ChainDescription chain;
  ChainDescription real_chain;
};

struct RobotRequest {
  std::string robot;      ///< bundled name, path to robot.xml, or path to a .urdf
  std::string base_link;  ///< overrides (bare URDF)
  std::string tip_link;
};

/// Resolves and loads a robot. Unknown names throw InputError naming the bundled robots. The
/// card's <link> overrides replace the chain bodies' inertials (a name that is not the child link
/// of a chain joint throws at the card line); the counterbalance and the gravity model go into
/// the chain; a balancer that is not physical over its joint range, or a calibration pose
/// outside the joint limits, throws InputError at the card line.
Robot loadRobot(const RobotRequest& request);

/// For the commands that model weight (predict, compensate, deflect, simulate, verify): throws
/// InputError `URDF:LINE: link 'x' has no <inertial> ...` (with the hint to give
/// `<link name mass_kg com_mm source>` in the card or declare `<gravity model="none"/>`) when a
/// chain body has no mass and the card does not say gravity is not modelled.
void requireGravityModel(const Robot& robot);

/// "" when gravity is modelled, else the statement every output carries.
std::string gravityNotModelledNote(const RobotCard& card);

/// Controller joint values (rad) from URDF joint values (rad), and back.
Eigen::Matrix<double, 6, 1> toControllerJoints(const RobotCard& card,
                                               const Eigen::Matrix<double, 6, 1>& q_urdf);
Eigen::Matrix<double, 6, 1> fromControllerJoints(const RobotCard& card,
                                                 const Eigen::Matrix<double, 6, 1>& q_ctrl);

}  // namespace roprec
