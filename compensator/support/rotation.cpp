#include "compensator/support/rotation.hpp"

#include <cmath>

namespace roprec {

Mat3 rotationFromRpy(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
          Eigen::AngleAxisd(roll, Vec3::UnitX()))
      .toRotationMatrix();
}

Vec3 rpyFromRotation(const Mat3& R) {
  const Vec3 abc = zyxFromRotation(R);
  return {abc.z(), abc.y(), abc.x()};
}

Mat3 rotationFromZyx(double a, double b, double c) { return rotationFromRpy(c, b, a); }

Vec3 zyxFromRotation(const Mat3& R) {
  const double cb = std::hypot(R(0, 0), R(1, 0));
  const double b = std::atan2(-R(2, 0), cb);
  if (cb < 1e-9) {
    return {std::atan2(-R(0, 1), R(1, 1)), b, 0.0};
  }
  return {std::atan2(R(1, 0), R(0, 0)), b, std::atan2(R(2, 1), R(2, 2))};
}

double wrapAngle(double a) {
  if (a > -kPi && a <= kPi) return a;  // already wrapped (the common case): no remainder
  double w = std::remainder(a, 2.0 * kPi);
  if (w <= -kPi) w += 2.0 * kPi;
  return w;
}

Vec3 zyxFromRotationNear(const Mat3& R, const Vec3& reference) {
  const Vec3 p = zyxFromRotation(R);
  const Vec3 alt{p.x() + kPi, kPi - p.y(), p.z() + kPi};
  auto near = [&](const Vec3& v) {
    Vec3 out;
    for (int i = 0; i < 3; ++i) out[i] = reference[i] + wrapAngle(v[i] - reference[i]);
    return out;
  };
  Vec3 a = near(p);
  Vec3 b = near(alt);
  // Keep B in [-pi/2, pi/2] unless the alternative is clearly closer to the reference.
  if ((b - reference).squaredNorm() + 1e-18 < (a - reference).squaredNorm() &&
      std::abs(p.y()) > 1e-12) {
    return b;
  }
  return a;
}

Eigen::Quaterniond quaternionFromRotation(const Mat3& R) {
  const double t = R.trace();
  double w = 0;
  double x = 0;
  double y = 0;
  double z = 0;
  if (t > 0) {
    w = 0.5 * std::sqrt(1.0 + t);
    x = (R(2, 1) - R(1, 2)) / (4 * w);
    y = (R(0, 2) - R(2, 0)) / (4 * w);
    z = (R(1, 0) - R(0, 1)) / (4 * w);
  } else if (R(0, 0) >= R(1, 1) && R(0, 0) >= R(2, 2)) {
    x = 0.5 * std::sqrt(1.0 + R(0, 0) - R(1, 1) - R(2, 2));
    w = (R(2, 1) - R(1, 2)) / (4 * x);
    y = (R(0, 1) + R(1, 0)) / (4 * x);
    z = (R(0, 2) + R(2, 0)) / (4 * x);
  } else if (R(1, 1) >= R(2, 2)) {
    y = 0.5 * std::sqrt(1.0 - R(0, 0) + R(1, 1) - R(2, 2));
    w = (R(0, 2) - R(2, 0)) / (4 * y);
    x = (R(0, 1) + R(1, 0)) / (4 * y);
    z = (R(1, 2) + R(2, 1)) / (4 * y);
  } else {
    z = 0.5 * std::sqrt(1.0 - R(0, 0) - R(1, 1) + R(2, 2));
    w = (R(1, 0) - R(0, 1)) / (4 * z);
    x = (R(0, 2) + R(2, 0)) / (4 * z);
    y = (R(1, 2) + R(2, 1)) / (4 * z);
  }
  Eigen::Quaterniond q(w, x, y, z);
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  return q;
}

Mat3 skew(const Vec3& a) {
  Mat3 S;
  S << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return S;
}

Vec3 rotationVector(const Mat3& R) {
  const Eigen::AngleAxisd aa(quaternionFromRotation(R));
  return aa.axis() * aa.angle();
}

Vec3 smallRotationDifference(const Mat3& R_a, const Mat3& R_b) {
  const Mat3 D = R_a * R_b.transpose();
  const double s = 0.5 * (D.trace() - 1.0);
  if (s < 0.999) return rotationVector(D);
  return 0.5 * Vec3{D(2, 1) - D(1, 2), D(0, 2) - D(2, 0), D(1, 0) - D(0, 1)};
}

}  // namespace roprec
