#pragma once
/// KDL reference chains built by kdl_parser from the same URDF file (tests and benchmarks only).
#include <kdl/chain.hpp>
#include <kdl/frames.hpp>
#include <string>
#include <utility>
#include <vector>

#include "compensator/robot/geometry_calibration.hpp"
#include "compensator/robot/robot_card.hpp"
#include "compensator/support/rotation.hpp"

namespace roprec::test {

/// Chain base -> tip from the URDF; `extra` is appended as a fixed segment (e.g. a tool).
/// Fails the current test (ADD_FAILURE) and returns an empty chain when kdl_parser refuses.
KDL::Chain kdlChain(const std::string& urdf, const std::string& base, const std::string& tip,
                    const Pose& extra = Pose::Identity());

/// Static gravity torques (N m, g = 9.80665 m/s² along −z of the chain base) of the chain at the
/// joint values q (rad) by KDL's recursive Newton–Euler (ChainIdSolver_RNE, zero velocity and
/// acceleration, no external wrench). Fails the current test when the solver reports an error.
Eigen::Matrix<double, 6, 1> kdlGravity(const KDL::Chain& chain,
                                       const Eigen::Matrix<double, 6, 1>& q);

/// URDF text of `urdf_path` with the <origin> of each named joint right-multiplied by its error:
/// origin' = origin · E (composed with KDL frames and KDL's RPY, independent of roprec's
/// rotation code; written with 17 significant digits). A joint without <origin> gets one. Fails
/// the current test when a named joint is not in the URDF.
std::string perturbedUrdf(const std::string& urdf_path,
                          const std::vector<std::pair<std::string, Pose>>& joint_errors);

/// Seeded geometric errors of an uncalibrated arm: every joint origin, the base and the tool,
/// uniform in ±mm (per translation component, mm) and ±mrad (per rpy component, mrad); σ = 0.
GeometryCalibration seededGeometryErrors(unsigned seed, double mm, double mrad);

/// The error's transform built with KDL (KDL::Rotation::RPY), not FrameError::transform.
Pose kdlErrorPose(const FrameError& e);

/// The truth geometry of a calibrated robot for KDL, built without roprec's chain code: `urdf` a
/// perturbedUrdf of the robot's URDF with each joint's error, `base` to put in front of the chain
/// (a fixed segment: gravity stays along −z of the base frame), `tool` after the flange.
struct KdlTruthGeometry {
  std::string urdf;
  Pose base{Pose::Identity()};
  Pose tool{Pose::Identity()};
  /// KDL chain base -> flange: base segment, perturbed chain, tool segment, then `extra`.
  [[nodiscard]] KDL::Chain chain(const std::string& base_link, const std::string& tip_link,
                                 const Pose& extra = Pose::Identity()) const;
};
/// Writes the perturbed URDF into `dir` (robot: a loaded bundled robot).
KdlTruthGeometry kdlTruthGeometry(const Robot& robot, const GeometryCalibration& cal,
                                  const std::string& dir);

/// A copy of the card of `robot` in `dir` (robot.xml, its URDF referenced by absolute path) with
/// `block` (calibrationXml) before </robot>; returns its path.
std::string cardWithCalibration(const Robot& robot, const std::string& block,
                                const std::string& dir);

/// The KDL chain base -> flange (then `extra`) of the URDF `roprec card export-urdf` writes for
/// the calibrated card `card_path` (written into `dir` as real.urdf, read by kdl_parser): the
/// real robot as other tools see it, the reference FK_cal of a command is checked against.
KDL::Chain kdlExportedChain(const std::string& card_path, const std::string& dir,
                            const Pose& extra = Pose::Identity());

/// KDL's forward kinematics of `chain` at q (rad) as a pose (base frame, m); fails the current test
/// when the solver reports an error.
Pose kdlPose(const KDL::Chain& chain, const Eigen::Matrix<double, 6, 1>& q);

KDL::Frame toKdl(const Pose& T);
Pose fromKdl(const KDL::Frame& F);

}  // namespace roprec::test
