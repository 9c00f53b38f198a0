#include "compensator/robot/fast_equilibrium.hpp"

#include <cmath>

namespace roprec::nc {

namespace {
/// R_W_Li = R_W_Ji Rot(ū, θ) (Rodrigues), with the product by columns when ū is a coordinate axis
/// (±x, ±y, ±z: the common URDF case): 12 products instead of 27.
void rotateAbout(const Mat3& RJ, const Vec3& a, double sn, double cs, Mat3& R) {
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3;
    const int k2 = (k + 2) % 3;
    if (a[k1] == 0.0 && a[k2] == 0.0 && std::abs(a[k]) == 1.0) {
      const double ss = a[k] * sn;  // rotation about ±e_k
      R.col(k) = RJ.col(k);
      R.col(k1) = cs * RJ.col(k1) + ss * RJ.col(k2);
      R.col(k2) = cs * RJ.col(k2) - ss * RJ.col(k1);
      return;
    }
  }
  const double t = 1.0 - cs;
  Mat3 Rot;
  Rot << cs + t * a.x() * a.x(), t * a.x() * a.y() - sn * a.z(), t * a.x() * a.z() + sn * a.y(),
      t * a.y() * a.x() + sn * a.z(), cs + t * a.y() * a.y(), t * a.y() * a.z() - sn * a.x(),
      t * a.z() * a.x() - sn * a.y(), t * a.z() * a.y() + sn * a.x(), cs + t * a.z() * a.z();
  R.noalias() = RJ * Rot;
}
}  // namespace

void chainFrames(const Model& model, Data& data, const Vec6& theta) {
  Data::ChainFrames& f = data.frames;
  f.theta = theta;
  Mat3 R = Mat3::Identity();
  Vec3 p = Vec3::Zero();
  for (int i = 0; i < 6; ++i) {
    const size_t s = static_cast<size_t>(i);
    const Pose& O = model.origin[s];
    const Mat3 RJ = R * O.linear();
    p += R * O.translation();
    const Vec3& a = model.bodies[s].ubar;
    const double sn = std::sin(theta[i]);
    const double cs = std::cos(theta[i]);
    f.sin_theta[i] = sn;
    f.u[s] = RJ * a;
    rotateAbout(RJ, a, sn, cs, R);
    f.p[s] = p;
    f.R[s] = R;
  }
  f.R_tcp.noalias() = R * model.T_L6_tcp.linear();
  f.p_tcp = p + R * model.T_L6_tcp.translation();
}

void staticTorquesFromFrames(const Model& model, const Data& data, const Loads& loads, Vec6& tau,
                             StaticLoadSums& sums) {
  const Data::ChainFrames& f = data.frames;
  const bool gravity = loads.gravity && !model.gravity.isZero(0.0);
  sums.N_w = loads.tcp.moment;
  sums.F_all_w = loads.tcp.force;
  sums.F_t = f.R_tcp * loads.tcp_tool.force;
  sums.N_t = f.R_tcp * loads.tcp_tool.moment;
  const Vec3 F_all = loads.tcp.force + sums.F_t;
  // suffix sums over the loads beyond joint j: total force and moment about W's origin
  Vec3 Fs = F_all;
  Vec3 Ms = f.p_tcp.cross(F_all) + sums.N_w + sums.N_t;
  for (int j = 5; j >= 0; --j) {
    const size_t s = static_cast<size_t>(j);
    const Body& b = model.bodies[s];
    if (gravity && b.mass > 0.0) {
      sums.f[s] = b.mass * model.gravity;
      sums.r[s] = f.p[s] + f.R[s] * b.com;
      Fs += sums.f[s];
      Ms += sums.r[s].cross(sums.f[s]);
    } else {
      sums.f[s].setZero();
      sums.r[s] = f.p[s];
    }
    tau[j] = -f.u[s].dot(Ms - f.p[s].cross(Fs));
  }
  sums.balancer = gravity && model.counterbalance.present();
  if (sums.balancer) {
    const int j = model.counterbalance.joint;
    tau[j] -= balancerTorque(model.counterbalance, f.theta[j]);
  }
}

void staticSensitivity(const Model& model, const Data& data, const StaticLoadSums& sums, Mat6& D) {
  const Data::ChainFrames& f = data.frames;
  // W_j = A_j − F_j p_jᵀ with the suffix sums A_j = Σ_{k≥j} f_k r_kᵀ, F_j = Σ_{k≥j} f_k of the
  // base-fixed forces (weights and F_W at the TCP)
  std::array<Mat3, 6> Wj{};
  {
    Mat3 A = sums.F_all_w * f.p_tcp.transpose();
    Vec3 Fw = sums.F_all_w;
    for (int j = 5; j >= 0; --j) {
      const size_t s = static_cast<size_t>(j);
      A.noalias() += sums.f[s] * sums.r[s].transpose();
      Fw += sums.f[s];
      Wj[s] = A - Fw * f.p[s].transpose();
    }
  }
  std::array<Vec3, 6> distal{};   // (W_iᵀ − tr W_i) u_i + u_i × M_t,i
  std::array<Vec3, 6> turn_Ft{};  // u_i × F_t
  for (int i = 0; i < 6; ++i) {
    const size_t s = static_cast<size_t>(i);
    const Vec3& u = f.u[s];
    const Mat3& W = Wj[s];
    const Vec3 M_t = (f.p_tcp - f.p[s]).cross(sums.F_t) + sums.N_t;
    distal[s] = W.transpose() * u - W.trace() * u + u.cross(M_t);
    turn_Ft[s] = u.cross(sums.F_t);
  }
  for (int j = 0; j < 6; ++j) {
    const size_t sj = static_cast<size_t>(j);
    const Vec3& uj = f.u[sj];
    const Mat3& W = Wj[sj];
    // row u_jᵀ (tr W_j I − W_j − [N_W]×)
    const Vec3 row = W.trace() * uj - W.transpose() * uj + sums.N_w.cross(uj);
    for (int i = 0; i <= j; ++i) D(j, i) = row.dot(f.u[static_cast<size_t>(i)]);
    for (int i = j + 1; i < 6; ++i) {
      const size_t si = static_cast<size_t>(i);
      D(j, i) = -uj.dot(distal[si] + (f.p[si] - f.p[sj]).cross(turn_Ft[si]));
    }
  }
  if (sums.balancer) {
    const Counterbalance& cb = model.counterbalance;
    const int j = cb.joint;
    const double h = 1e-6;
    const double th = f.theta[j];
    D(j, j) -= (balancerTorque(cb, th + h) - balancerTorque(cb, th - h)) / (2.0 * h);
  }
}

const Mat6& tcpJacobianFromFrames(const Model& /*model*/, Data& data) {
  const Data::ChainFrames& f = data.frames;
  for (int j = 0; j < 6; ++j) {
    const size_t s = static_cast<size_t>(j);
    data.J_tcp.block<3, 1>(0, j) = f.u[s].cross(f.p_tcp - f.p[s]);
    data.J_tcp.block<3, 1>(3, j) = f.u[s];
  }
  return data.J_tcp;
}

void syncNaturalCoordinates(const Model& model, Data& data) {
  const Data::ChainFrames& f = data.frames;
  VecQ& q = data.q;
  for (int i = 0; i < 6; ++i) {
    const size_t s = static_cast<size_t>(i);
    const Body& b = model.bodies[s];
    q.segment<3>(idxV(i)) = f.R[s] * b.vbar;
    q.segment<3>(idxW(i)) = f.R[s] * b.wbar;
    if (i < 5) {
      q.segment<3>(idxPnext(i)) = f.p[s + 1];
      q.segment<3>(idxUnext(i)) = f.u[s + 1];
    }
    q[idxTheta(i)] = f.theta[i];
    data.cross_form[s] = std::abs(f.sin_theta[i]) <= std::sqrt(0.5);
  }
  data.z = f.theta;
  data.factorized = false;
  data.T_W_tcp.linear() = f.R_tcp;
  data.T_W_tcp.translation() = f.p_tcp;
  data.T_W_flange.linear().noalias() = f.R[5] * model.T_L6_flange.linear();
  data.T_W_flange.translation() = f.p[5] + f.R[5] * model.T_L6_flange.translation();
}

}  // namespace roprec::nc
