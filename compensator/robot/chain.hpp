#pragma once
/// \file chain.hpp
/// A serial 6R chain as plain data, extracted from a URDF between two named links.
/// No urdfdom type appears here (parsing is kept separate from modelling).
///
/// Frames: every pose is a rigid transform in SI (m, rad).
/// * `joints[i].origin` = T_{P_i, J_i}: from the frame of the previous moving body P_i
///   (the child link of joint i-1; the base link for i = 0) to the frame of joint i, with all
///   fixed joints in between folded in.
/// * The child link frame of joint i equals the joint frame rotated by q_i about `axis`.
/// * `tip` = T_{L_6, tip}: from the child link of joint 6 to the tip link (e.g. the flange).
/// * `inertials[i]` is body i (child link of joint i and every link fixed to it) in its own
///   link frame; `base_inertial` is unused by the dynamics (the base does not move).

#include <array>
#include <string>

#include "compensator/robot/counterbalance.hpp"
#include "compensator/support/rotation.hpp"

namespace roprec {

/// Rigid-body inertial data in a link frame: mass (kg), centre of mass (m), inertia tensor
/// about the centre of mass (kg m^2, axes of the link frame).
struct Inertial {
  double mass{0.0};
  Vec3 com{Vec3::Zero()};
  Mat3 inertia{Mat3::Zero()};
  bool present{false};  ///< false when the URDF had no <inertial> for any link of the body
};

/// Combines two inertials expressed in the same frame.
Inertial combine(const Inertial& a, const Inertial& b);
/// Re-expresses an inertial given in frame C in frame P, with T_P_C the pose of C in P.
Inertial transformed(const Inertial& in_C, const Pose& T_P_C);

struct ChainJoint {
  std::string name;
  std::string child_link;
  Pose origin{Pose::Identity()};  ///< T_{P_i, J_i}
  Vec3 axis{Vec3::UnitZ()};       ///< unit axis in the joint frame
  double lower{-kPi};             ///< rad
  double upper{kPi};              ///< rad
  double velocity{0.0};           ///< rad/s (0 = not given)
  double effort{0.0};             ///< N m (0 = not given)
  bool continuous{false};
  int line{0};  ///< line of the <joint> element in the URDF
};

struct ChainDescription {
  std::string file;        ///< URDF path (for messages)
  std::string robot_name;  ///< <robot name="...">
  std::string base_link;
  std::string tip_link;
  std::array<ChainJoint, 6> joints;
  std::array<Inertial, 6> inertials;
  Pose tip{Pose::Identity()};  ///< T_{L_6, tip}
  bool has_inertials{false};   ///< true when every moving body has mass > 0
  /// Weight handling from the robot card (robot_card.hpp): the axis-2 balancer (part of the
  /// gravity loads) and whether gravity is modelled at all (`<gravity model="none"/>`: false).
  Counterbalance counterbalance;
  bool gravity_modelled{true};
};

/// Rigid forward kinematics by the product of exponentials of the description itself:
/// T_B_tip(q) = Π_i (origin_i · Rot(axis_i, q_i)) · tip. A reference for tests and a warm start;
/// the production kinematics is the natural-coordinate model (model.hpp).
Pose chainForwardKinematics(const ChainDescription& chain, const Eigen::Matrix<double, 6, 1>& q);

}  // namespace roprec
