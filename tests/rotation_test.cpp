#include "compensator/support/rotation.hpp"

#include <gtest/gtest.h>

#include <random>

namespace roprec {
namespace {

// Closed forms of docs/programs.md §6 against Eigen's AngleAxis products; seeded.
TEST(Rotation, ZyxRoundTripIncludingGimbal) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-kPi, kPi);
  for (int i = 0; i < 2000; ++i) {
    const double a = u(rng);
    const double b = (i % 50 == 0) ? (i % 100 == 0 ? kPi / 2 : -kPi / 2) : u(rng) / 2;
    const double c = u(rng);
    const Mat3 R = rotationFromZyx(a, b, c);
    const Mat3 ref = (Eigen::AngleAxisd(a, Vec3::UnitZ()) * Eigen::AngleAxisd(b, Vec3::UnitY()) *
                      Eigen::AngleAxisd(c, Vec3::UnitX()))
                         .toRotationMatrix();
    EXPECT_LT((R - ref).norm(), 1e-15);
    const Vec3 abc = zyxFromRotation(R);
    EXPECT_LT((rotationFromZyx(abc.x(), abc.y(), abc.z()) - R).norm(), 1e-12);
  }
}

TEST(Rotation, ShepperdQuaternionHandles180Degrees) {
  const Vec3 axis = Vec3(1, -1, 0).normalized();
  const Mat3 R = Eigen::AngleAxisd(kPi, axis).toRotationMatrix();
  const Eigen::Quaterniond q = quaternionFromRotation(R);
  EXPECT_LT((q.toRotationMatrix() - R).norm(), 1e-15);
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0, 1);
  for (int i = 0; i < 1000; ++i) {
    Eigen::Quaterniond r(n(rng), n(rng), n(rng), n(rng));
    r.normalize();
    const Eigen::Quaterniond back = quaternionFromRotation(r.toRotationMatrix());
    EXPECT_NEAR(std::abs(back.dot(r)), 1.0, 1e-14);
  }
}

TEST(Rotation, ZyxNearPicksClosestRepresentative) {
  const Mat3 R = rotationFromZyx(179.97 * kDeg, 10 * kDeg, -179.99 * kDeg);
  const Vec3 near = zyxFromRotationNear(R, Vec3(179.9 * kDeg, 10 * kDeg, -179.9 * kDeg));
  EXPECT_NEAR(near.x(), 179.97 * kDeg, 1e-12);
  EXPECT_NEAR(near.z(), -179.99 * kDeg, 1e-12);
}

TEST(Rotation, SmallRotationDifferenceIsExactForTinyAngles) {
  const Vec3 w(3e-9, -2e-9, 5e-9);
  const Mat3 R0 = rotationFromRpy(0.3, -0.2, 1.1);
  const Mat3 R1 = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix() * R0;
  EXPECT_LT((smallRotationDifference(R1, R0) - w).norm(), 1e-16);
}

}  // namespace
}  // namespace roprec
