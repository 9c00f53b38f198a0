#pragma once
/// \file calibration_jacobian.hpp
/// How the real TCP position moves with each component of a geometric calibration
/// (geometry_calibration.hpp), for propagating the calibration's σ into the budget
/// (prediction.hpp, AccuracyInputs::kCalibrated).
///
/// Columns (kCalibrationParameters = 48), each ∂p_tcp/∂c (m per m or m per rad, base frame W):
///   0..5    base:     dx dy dz (along x_W, y_W, z_W), droll dpitch dyaw (about x_W, y_W, z_W
///                     through the base origin);
///   6+6i..  joint i:  the same in joint i's frame J_i (origin_real · Rot(axis, q) follows);
///   42..47  tool:     the same in the flange frame F.
/// To first order in the error (the rpy rates at the identity are the axis rotations; the
/// calibrated errors are ≤ 20 mrad, so the columns are exact to that relative order):
///   translation along unit w:                ∂p = w
///   rotation about unit w through point o:    ∂p = w × (p_tcp − o)
/// with w = R_W_frame e_k, o the frame's origin, all at the calibrated chain's joint values θ.
/// Allocation-free.

#include <Eigen/Core>

#include "compensator/robot/geometry_calibration.hpp"

namespace roprec {

constexpr int kCalibrationParameters = 48;
using CalibrationJacobian = Eigen::Matrix<double, 3, kCalibrationParameters>;
using CalibrationSigmas = Eigen::Matrix<double, kCalibrationParameters, 1>;

/// ∂p_tcp/∂c at θ (rad) for the chain `real` (calibratedChain) and the TCP `T_flange_tcp`.
void tcpCalibrationJacobian(const ChainDescription& real, const Pose& T_flange_tcp,
                            const Eigen::Matrix<double, 6, 1>& theta, CalibrationJacobian& J);

/// The σ of each column's component (m, rad) in the same order; 0 where not stated.
CalibrationSigmas calibrationSigmas(const GeometryCalibration& cal);

/// Covariance (m², base frame W) of the real TCP position that the calibration `cal` leaves
/// unknown at θ:
///   with the fit's covariance Σ over components c (GeometryCalibration::covariance):
///     C = J_c Σ J_cᵀ with the columns J_c of tcpCalibrationJacobian, correlations included (what
///     the part's registration absorbed, e.g. joint 1's origin, cancels with the base
///     components it is stated in);
///   without: C = Σ_c σ_c² J_c J_cᵀ over the stated σ (each component independent);
/// plus model_error² I (the fit's unexplained scatter per axis). Allocates (the covariance's
/// columns).
Mat3 calibrationPositionCovariance(const ChainDescription& real, const Pose& T_flange_tcp,
                                   const Eigen::Matrix<double, 6, 1>& theta,
                                   const GeometryCalibration& cal);

}  // namespace roprec
