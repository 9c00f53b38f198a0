#include "compensator/robot/chain.hpp"

namespace roprec {

Inertial combine(const Inertial& a, const Inertial& b) {
  Inertial c;
  c.mass = a.mass + b.mass;
  c.present = a.present || b.present;
  if (c.mass <= 0.0) return c;
  c.com = (a.mass * a.com + b.mass * b.com) / c.mass;
  auto shifted = [&](const Inertial& x) {
    const Vec3 d = x.com - c.com;
    return Mat3(x.inertia + x.mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose()));
  };
  c.inertia = shifted(a) + shifted(b);
  return c;
}

Inertial transformed(const Inertial& in_C, const Pose& T_P_C) {
  Inertial out = in_C;
  out.com = T_P_C * in_C.com;
  out.inertia = T_P_C.linear() * in_C.inertia * T_P_C.linear().transpose();
  return out;
}

Pose chainForwardKinematics(const ChainDescription& chain, const Eigen::Matrix<double, 6, 1>& q) {
  Pose T = Pose::Identity();
  for (int i = 0; i < 6; ++i) {
    const ChainJoint& j = chain.joints[static_cast<size_t>(i)];
    T = T * j.origin;
    T.rotate(Eigen::AngleAxisd(q[i], j.axis));
  }
  return T * chain.tip;
}

}  // namespace roprec
