#pragma once
/// \file card_check.hpp
/// Checks a loaded robot card against its URDF, the vendor's joint and frame conventions and the
/// published class data (docs/cards.md, robots/README.md). Used by `roprec card check` and, on
/// load, by `predict` / `compensate` (errors stop them, warnings become notes).
///
/// Vendor conventions (controller convention, base frame B = the card's base_link, at the
/// controller's zero pose):
///   axis_i = controller-positive rotation axis of joint i in B:
///     KUKA  {−z, +y, +y, −x, +y, −x}   (A1, A4, A6 clockwise-positive)
///     ABB   {+z, +y, +y, +x, +y, +x}
///     FANUC {+z, +y, −y, −x, −y, −x}   (J3 from the horizontal: j23_coupling = −sign_2)
///   card rule: controller_sign_i · a_i = axis_i, a_i the URDF axis of joint i in B at q = 0.
///   home (controller deg) and the flange frame F there, expressed in B:
///     KUKA  {0, −90, 90, 0, 0, 0}: z_F = +x_B, x_F = −z_B  (A 0, B 90, C 0)
///     ABB   all 0:                  z_F = +x_B, x_F = −z_B  (tool0 q = [0.7071, 0, 0.7071, 0])
///     FANUC all 0:                  z_F = +x_B, x_F = +z_B  (W 180, P −90, R 0)
///   FANUC: B is the World frame, on the J1 axis at J2 height (the J2 axis passes through z = 0);
///   KUKA, ABB: B is on the mounting surface (J2 above it).
/// The flange's z points **out of the flange**: along the joint-6 axis, away from the wrist
/// centre (joint 5). ROS-Industrial `tool0` is that frame; ROS-Industrial `flange` is x-out.
///
/// Class data: stiffnessClass (published identified KUKA KR500 set, Jiao 2022 Eq. 38, for the
/// 120–500 kg class; scaled linearly by payload below 120 kg). A card stiffness 100× or more off
/// the class is an error, 10× a warning.
///
/// Calibrated URDFs (a URDF an external calibration wrote): axes, the flange z and its orientation
/// at home within 5 mrad of the convention are calibration offsets (ok, noted), up to 20 mrad a
/// warning, beyond an error; FANUC's J2 height likewise 1 mm / 5 mm. A card's <calibration>
/// offsets: per error |xyz| > 1 mm or |rpy| > 5 mrad a warning, > 5 mm / 20 mrad an error.
///
/// Placeholder inertials: three or more moving bodies with the same mass and inertia tensor (the
/// ROS-Industrial support packages give every link 2 kg and 0.01 kg m²); used as real weight
/// (no card <link> override, gravity modelled) they are an error.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "compensator/robot/robot_card.hpp"

namespace roprec {

struct VendorConvention {
  std::array<Vec3, 6> axes;              ///< controller-positive axes in B at zero
  Eigen::Matrix<double, 6, 1> home_deg;  ///< home pose, controller convention
  std::string home_text;                 ///< e.g. "HOME {0, -90, 90, 0, 0, 0}"
  Vec3 home_z{Vec3::UnitX()};            ///< flange z at home, in B
  Vec3 home_x{-Vec3::UnitZ()};           ///< flange x at home, in B
  std::string home_orientation;          ///< e.g. "A 0, B 90, C 0"
  bool world_at_j2{false};               ///< FANUC: B at J2 height
  bool j23_coupled{false};               ///< FANUC: J3 from the horizontal
  bool lower_arm_vertical{true};  ///< at the controller zero: J2->J3 vertical (KUKA: horizontal)
};

/// The convention of KUKA, ABB or FANUC; nullopt for a generic vendor.
std::optional<VendorConvention> vendorConvention(Vendor v);

/// Class joint stiffness (N m/rad) for a rated payload (kg; 0 = unknown: the heavy class):
/// k = k_KR500 · f, f = 1 for P ≥ 120 kg, f = P / 120 below (estimate: gear and bearing torque
/// capacity, hence stiffness, grows about linearly with the rated payload). `rule` states it.
struct StiffnessClass {
  Eigen::Matrix<double, 6, 1> k;
  double factor{1.0};
  std::string rule;
};
StiffnessClass stiffnessClass(double payload_kg);

/// Position-loop gain prior, 1/s (estimate: typical Kv of industrial robots, 30–60 1/s).
constexpr double kClassPositionGain = 40.0;
/// ISO 9283 pose repeatability class prior, mm (the upper end of the class; estimate).
constexpr double kClassRepeatabilityMm = 0.08;

/// Geometry of a chain at q = 0 in its base frame: joint points and URDF axes.
struct ChainZeroGeometry {
  std::array<Vec3, 6> p;  ///< joint frame origins, m
  std::array<Vec3, 6> a;  ///< URDF joint axes
};
ChainZeroGeometry zeroGeometry(const ChainDescription& chain);

/// Cosine between the tip frame's z and the direction out of the flange (joint-6 axis, pointing
/// away from the joint-5 origin); `known` false when the tip lies on the wrist centre (then +axis
/// is assumed).
double flangeZOutCosine(const ChainDescription& chain, bool* known = nullptr);

/// "" when the lower arm (joint-2 origin -> joint-3 origin, in B) at the URDF joint values
/// `q_urdf` of the controller's zero pose lies as the vendor's zero pose has it (ABB, FANUC:
/// vertical, J3 above J2; KUKA: horizontal, J3 in front of J2; within 0.02 of its length: a
/// calibrated URDF's tilt), else what is wrong.
std::string lowerArmProblem(const ChainDescription& chain,
                            const Eigen::Matrix<double, 6, 1>& q_urdf, const VendorConvention& v);

/// Bodies (0..5) whose URDF inertial is a placeholder (see file comment).
std::array<bool, 6> placeholderInertials(const ChainDescription& urdf_chain);

struct CardFinding {
  bool error{false};
  std::string file;
  int line{0};
  std::string message;
  std::string hint;
};

struct CardCheckRow {
  std::string check;      ///< what was checked
  std::string value;      ///< the card's value
  std::string reference;  ///< convention or class value
  std::string verdict;    ///< "ok", "estimate", "WARNING", "ERROR"
};

struct CardCheckReport {
  std::vector<CardCheckRow> rows;
  std::vector<CardFinding> findings;
  [[nodiscard]] int errors() const;
  [[nodiscard]] int warnings() const;
};

/// Runs every check on a robot loaded from a card (loadRobot). Reads the card's URDF again for
/// its raw inertials. Throws InputError only when the URDF cannot be read.
CardCheckReport checkRobotCard(const Robot& robot);

/// Throws InputError(file, line, "message; hint: hint (roprec card check CARD)") for the first
/// error of the report; does nothing when there is none.
void throwFirstCardError(const CardCheckReport& report, const RobotCard& card);

}  // namespace roprec
