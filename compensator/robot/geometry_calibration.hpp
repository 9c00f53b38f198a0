#pragma once
/// \file geometry_calibration.hpp
/// The robot's measured geometric errors (the card's `<calibration>` block, docs/cards.md §5):
/// small rigid errors of each joint origin, of the base and of the flange/TCP, relative to the
/// card's URDF, which stays the controller's **nominal** model.
///
/// Frames and convention (SI inside: m, rad; the card holds mm and mrad):
/// * FrameError e: the rigid transform E = Transl(e.dxyz) · RotRPY(e.drpy), URDF rpy (fixed
///   axes X, Y, Z: R = Rz(yaw) Ry(pitch) Rx(roll)).
/// * joint i:  origin_real_i = origin_nom_i · E_joint_i   (right: in the nominal joint frame J_i).
///   The component of drpy about the joint's own axis commutes with Rot(axis_i, q_i): it is the
///   joint's zero offset (θ_real_geometry = θ_controller + offset).
/// * base:     T_B_tip,real = E_base · T_chain,real(q)   (left: in the base frame B).
/// * tool:     tip_real = tip_nom · E_tool   (right: in the flange/tip frame).
/// So FK_real(q) = E_base · Π_i (origin_nom_i · E_i · Rot(axis_i, q_i)) · tip_nom · E_tool and
/// FK_nom(q) is the same product without the E's. The controller moves by FK_nom (it knows only
/// the nominal model); the robot's real TCP is FK_real of its (deflected) joint angles.

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "compensator/robot/chain.hpp"

namespace roprec {

struct XmlNode;

/// A small rigid error, SI.
struct FrameError {
  Vec3 dxyz{Vec3::Zero()};       ///< m
  Vec3 drpy{Vec3::Zero()};       ///< rad, roll-pitch-yaw (fixed axes X, Y, Z as URDF rpy)
  Vec3 sigma_xyz{Vec3::Zero()};  ///< m, standard uncertainty per component (0 = not stated)
  Vec3 sigma_rpy{Vec3::Zero()};  ///< rad, standard uncertainty per component (0 = not stated)
  /// Transl(dxyz) · RotRPY(drpy).
  [[nodiscard]] Pose transform() const;
  /// True when dxyz and drpy are both exactly zero.
  [[nodiscard]] bool isZero() const;
};

/// The FrameError whose transform() is T (xyz = translation, rpy = rpyFromRotation), σ = 0.
FrameError frameErrorFromTransform(const Pose& T);

struct GeometryCalibration {
  /// joint i origin: origin_real = origin_nom · joints[i].transform() (the component of drpy
  /// about the joint's own axis is its zero offset)
  std::array<FrameError, 6> joints;
  FrameError base;  ///< T_real = base.transform() · T_chain(...)  (left, base frame)
  FrameError tool;  ///< tip_real = tip_nom · tool.transform()  (flange/TCP error)
  std::string source;
  std::string date;
  int measurements{0};
  double residual_rms{0.0};  ///< m, RMS residual of the fit that produced the block
  /// m per axis: the scatter the fit's model leaves unexplained beyond the measurement σ (the
  /// cross-validated residual's excess, fit_validation.hpp modelErrorFloor); 0: not stated.
  double model_error{0.0};
  /// The fit's posterior covariance of the components it estimated together, correlations
  /// included (SI: m, rad), over `covariance_parameters` (calibrationComponent names). Empty:
  /// not stated (the σ above are then taken as independent).
  std::vector<std::string> covariance_parameters;
  Eigen::MatrixXd covariance;
  int line{0};  ///< line of the <calibration> element in the card (0: none)
};

/// Components of a calibration's covariance, by name (docs/cards.md §5), in the order of
/// calibration_jacobian.hpp's columns:
///   base_x base_y base_z base_rx base_ry base_rz   0..5    (FrameError base)
///   jI_x … jI_rz (I = 1..6)                        6+6(I−1) .. (joint I's origin error)
///   tip_x … tip_rz                                 42..47  (FrameError tool)
/// x/y/z are m (mm in the card), r* are rad (mrad in the card). −1: an unknown name.
/// A part registration estimated with the geometry is a base error to every hole (a rigid
/// displacement of the part in the base frame): `verify --calibrate` states it as the base
/// components.
constexpr int kCalibrationComponents = 48;
int calibrationComponent(const std::string& name);

/// The real chain: each joint origin right-multiplied by its error, the base error folded into
/// joint 1's origin (left-multiplied), the tip right-multiplied by the tool error. Inertials stay
/// in their (moved) link frames. chainForwardKinematics(calibratedChain(n, c), q) is FK_real(q).
ChainDescription calibratedChain(const ChainDescription& nominal, const GeometryCalibration& cal);

/// The calibration that turns `nominal` into `calibrated` (two chains of the same joints, e.g. the
/// card's URDF and a URDF an external calibration wrote): per joint
///   E_i = origin_nom_i⁻¹ · C_{i-1} · origin_cal_i · R_i,   C_i = R_iᵀ,   C_0 = I,
/// with R_i the smallest rotation taking the nominal joint axis onto the calibrated one (a tool
/// that tilts the axis vector instead of the origin; R_iᵀ is carried into the next origin), and
/// E_tool = tip_nom⁻¹ · C_5 · tip_cal. A URDF cannot tell a base error from joint 1's origin
/// error: both go into joint 1 (base stays zero; the real chain is the same). σ are 0 (not
/// stated). Throws InputError(calibrated.file, …) when the joint names differ.
GeometryCalibration calibrationFromChains(const ChainDescription& nominal,
                                          const ChainDescription& calibrated);

/// Parses a card's `<calibration>` element (docs/cards.md §5; native units mm, mrad, residual in
/// mm). `joint_names` are the card's joints in chain order; a `<joint_origin joint="…">` naming
/// another joint, a joint given twice, an unknown attribute or element, a negative σ or a missing
/// source throw InputError at the element's line. Joints not listed have no error.
GeometryCalibration parseCalibration(const XmlNode& block,
                                     const std::array<std::string, 6>& joint_names);

/// The `<calibration>` element for `cal` (what parseCalibration reads back, numbers in the
/// shortest text that round-trips the mm/mrad value), each line prefixed by `indent`, ending in a
/// newline. Components that are zero with zero σ are left out; joints without error are left out.
std::string calibrationXml(const GeometryCalibration& cal,
                           const std::array<std::string, 6>& joint_names,
                           const std::string& indent = "  ");

}  // namespace roprec
