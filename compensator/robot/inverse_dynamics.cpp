#include "compensator/robot/inverse_dynamics.hpp"

namespace roprec::nc {

namespace {
/// Slots of body i's elements [p_i, u_i, v_i, w_i] in q (−1: ground constant).
inline std::array<int, 4> slots(int i) {
  return {i == 0 ? -1 : idxPnext(i - 1), i == 0 ? -1 : idxUnext(i - 1), idxV(i), idxW(i)};
}
}  // namespace

void addMassTimes(const Model& model, const VecQ& x, VecQ& y) {
  for (int i = 0; i < 6; ++i) {
    const Eigen::Matrix4d& K = model.bodies[static_cast<size_t>(i)].K;
    if (K(0, 0) <= 0.0) continue;
    const auto s = slots(i);
    for (int k = 0; k < 4; ++k) {
      if (s[static_cast<size_t>(k)] < 0) continue;
      Vec3 acc = Vec3::Zero();
      for (int l = 0; l < 4; ++l) {
        if (s[static_cast<size_t>(l)] >= 0)
          acc += K(k, l) * x.segment<3>(s[static_cast<size_t>(l)]);
      }
      y.segment<3>(s[static_cast<size_t>(k)]) += acc;
    }
  }
}

void generalizedForces(const Model& model, const Data& data, const Loads& loads, VecQ& Q) {
  Q.setZero();
  if (loads.gravity) {
    for (int i = 0; i < 6; ++i) {
      const Eigen::Matrix4d& K = model.bodies[static_cast<size_t>(i)].K;
      if (K(0, 0) <= 0.0) continue;
      const auto s = slots(i);
      for (int k = 0; k < 4; ++k) {
        if (s[static_cast<size_t>(k)] >= 0)
          Q.segment<3>(s[static_cast<size_t>(k)]) += K(0, k) * model.gravity;
      }
    }
    // the axis-2 balancer belongs to the weight loads; it acts on the angle coordinate directly
    // (virtual power τ_cb δθ_j), so τ_j = τ_g,j − τ_cb (counterbalance.hpp)
    if (model.counterbalance.present() && !model.gravity.isZero(0.0)) {
      const int j = model.counterbalance.joint;
      Q[idxTheta(j)] += balancerTorque(model.counterbalance, data.q[idxTheta(j)]);
    }
  }
  Vec3 F = loads.tcp.force;
  Vec3 N = loads.tcp.moment;
  if (!loads.tcp_tool.force.isZero(0.0) || !loads.tcp_tool.moment.isZero(0.0)) {
    Mat3 X;
    X << Vec3(data.q.segment<3>(idxUnext(4))), Vec3(data.q.segment<3>(idxV(5))),
        Vec3(data.q.segment<3>(idxW(5)));
    const Mat3 R_W_tcp = X * model.Rbar_tcp;
    F += R_W_tcp * loads.tcp_tool.force;
    N += R_W_tcp * loads.tcp_tool.moment;
  }
  const Vec3& c = model.c_tcp;
  Q.segment<3>(idxPnext(4)) += F;
  Q.segment<3>(idxUnext(4)) += c.x() * F + 0.5 * N.cross(Vec3(data.q.segment<3>(idxUnext(4))));
  Q.segment<3>(idxV(5)) += c.y() * F + 0.5 * N.cross(Vec3(data.q.segment<3>(idxV(5))));
  Q.segment<3>(idxW(5)) += c.z() * F + 0.5 * N.cross(Vec3(data.q.segment<3>(idxW(5))));
}

const Vec6& inverseDynamics(const Model& model, Data& data, const Vec6& zd, const Vec6& zdd,
                            const Loads& loads) {
  velocities(model, data, zd);
  accelerationTerm(model, data, zd);  // c and Sc
  // q̈ = A⁻¹ [c; z̈]
  data.rhs.head<kNc>() = data.c;
  data.rhs.tail<kNz>() = zdd;
  solveA(model, data, data.rhs, data.qdd);
  generalizedForces(model, data, loads, data.scratch2);
  data.scratch2 = -data.scratch2;
  addMassTimes(model, data.qdd, data.scratch2);  // M q̈ − Q
  solveAT(model, data, data.scratch2, data.scratch);
  data.tau = data.scratch.tail<kNz>();
  data.lambda = -data.scratch.head<kNc>();
  return data.tau;
}

const Vec6& staticTorques(const Model& model, Data& data, const Loads& loads) {
  if (!data.factorized) factorize(model, data);
  generalizedForces(model, data, loads, data.scratch2);
  data.scratch2 = -data.scratch2;
  solveAT(model, data, data.scratch2, data.scratch);
  data.tau = data.scratch.tail<kNz>();
  data.lambda = -data.scratch.head<kNc>();
  data.qd.setZero();
  data.qdd.setZero();
  return data.tau;
}

Mat6 jointSpaceInertia(const Model& model, Data& data) {
  velocityTransform(model, data);
  Mat6 Mbar;
  for (int j = 0; j < kNz; ++j) {
    data.scratch.setZero();
    addMassTimes(model, data.R.col(j), data.scratch);
    Mbar.col(j) = data.R.transpose() * data.scratch;
  }
  return Mbar;
}

}  // namespace roprec::nc
