#pragma once
/// \file rotation.hpp
/// Orientation conventions used by roprec and by the robot-program dialects
/// (docs/programs.md §6). All angles in rad unless the name says `_deg`.
///
/// * URDF rpy (fixed axes X, Y, Z):             R = Rz(yaw) Ry(pitch) Rx(roll)
/// * KUKA A,B,C (intrinsic Z-Y'-X''):           R = Rz(A) Ry(B) Rx(C)
/// * FANUC W,P,R (fixed X, Y, Z):               R = Rz(R) Ry(P) Rx(W)   (same matrix, A=R, B=P,
/// C=W)
/// * ABB / contract quaternion [w, x, y, z]:    unit quaternion, scalar first.
/// * rotation vector (axis * angle):            used for small rotation deviations (µrad in
/// reports).

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace roprec {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Pose = Eigen::Isometry3d;

/// R = Rz(yaw) Ry(pitch) Rx(roll) (URDF `rpy`, fixed axes).
Mat3 rotationFromRpy(double roll, double pitch, double yaw);
/// Inverse of rotationFromRpy; returns (roll, pitch, yaw).
Vec3 rpyFromRotation(const Mat3& R);

/// R = Rz(A) Ry(B) Rx(C) (KUKA ABC; FANUC with A=R, B=P, C=W).
Mat3 rotationFromZyx(double a, double b, double c);
/// (A, B, C) of R; at B = ±90° (gimbal) C = 0 and A takes the whole rotation about z.
Vec3 zyxFromRotation(const Mat3& R);
/// Of the two (A,B,C) triples that give R, the one closest (wrapped, per angle) to `reference`.
Vec3 zyxFromRotationNear(const Mat3& R, const Vec3& reference);

/// Unit quaternion from R by Shepperd's method (robust for 180° rotations), with w >= 0.
Eigen::Quaterniond quaternionFromRotation(const Mat3& R);

/// Skew-symmetric matrix: skew(a) * b = a x b.
Mat3 skew(const Vec3& a);

/// Rotation vector (axis * angle, |angle| <= pi) of R.
Vec3 rotationVector(const Mat3& R);
/// Small-rotation difference vector of R_a relative to R_b, from the skew part of
/// R_a R_b^T (exact direction, |v| = sin(angle)); accurate to 1e-16 rad for small angles.
Vec3 smallRotationDifference(const Mat3& R_a, const Mat3& R_b);

/// Wraps an angle to (-pi, pi].
double wrapAngle(double a);

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

}  // namespace roprec
