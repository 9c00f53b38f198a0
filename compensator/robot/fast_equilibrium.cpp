#include "compensator/robot/fast_equilibrium.hpp"

#include <cmath>
#include <limits>

namespace roprec::nc {

namespace {
/// sin x and cos x in one call where the C library has it (glibc's sincos: the same values).
void sinCos(double x, double& s, double& c) {
#if defined(__GLIBC__)
  ::sincos(x, &s, &c);
#else
  s = std::sin(x);
  c = std::cos(x);
#endif
}

/// (sn, cs) = (sin, cos)(from) → (sin, cos)(to): angle addition with the Taylor series of sin δ
/// and cos δ when |δ| ≤ 0.01 rad (Horner forms, reciprocals as constants), else sincos.
void shiftSinCos(double from, double to, double& sn, double& cs) {
  const double d = to - from;
  if (!(std::abs(d) <= 1e-2)) {  // far (or not finite): evaluate
    sinCos(to, sn, cs);
    return;
  }
  constexpr double k6 = 1.0 / 6.0, k20 = 1.0 / 20.0, k42 = 1.0 / 42.0;
  constexpr double k12 = 1.0 / 12.0, k30 = 1.0 / 30.0, k56 = 1.0 / 56.0;
  const double d2 = d * d;
  const double sd = d * (1.0 - d2 * k6 * (1.0 - d2 * k20 * (1.0 - d2 * k42)));
  const double cd = 1.0 - 0.5 * d2 * (1.0 - d2 * k12 * (1.0 - d2 * k30 * (1.0 - d2 * k56)));
  const double s = sn * cd + cs * sd;
  const double c = cs * cd - sn * sd;
  sn = s;
  cs = c;
}

/// k when ū = ±e_k (the common URDF case), else −1.
int coordinateAxis(const Vec3& a) {
  for (int k = 0; k < 3; ++k) {
    if (a[(k + 1) % 3] == 0.0 && a[(k + 2) % 3] == 0.0 && std::abs(a[k]) == 1.0) return k;
  }
  return -1;
}

/// R ← R Rot(ū, θ) (Rodrigues) in place, and u = R ū before the rotation; by columns when ū is a
/// coordinate axis (12 products instead of 27).
void rotateAbout(Mat3& R, const Vec3& a, double sn, double cs, Vec3& u) {
  const int k = coordinateAxis(a);
  if (k >= 0) {
    const int k1 = (k + 1) % 3;
    const int k2 = (k + 2) % 3;
    const double ss = a[k] * sn;  // rotation about ±e_k
    u = a[k] * R.col(k);
    const Vec3 c1 = R.col(k1);
    const Vec3 c2 = R.col(k2);
    R.col(k1) = cs * c1 + ss * c2;
    R.col(k2) = cs * c2 - ss * c1;
    return;
  }
  u = R * a;
  const double t = 1.0 - cs;
  Mat3 Rot;
  Rot << cs + t * a.x() * a.x(), t * a.x() * a.y() - sn * a.z(), t * a.x() * a.z() + sn * a.y(),
      t * a.y() * a.x() + sn * a.z(), cs + t * a.y() * a.y(), t * a.y() * a.z() - sn * a.x(),
      t * a.z() * a.x() - sn * a.y(), t * a.z() * a.y() + sn * a.x(), cs + t * a.z() * a.z();
  R = R * Rot;
}
/// True when R is exactly the identity (URDF joint origins without rpy: the common case).
bool isIdentity(const Mat3& R) {
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) {
      if (R(r, c) != (r == c ? 1.0 : 0.0)) return false;
    }
  }
  return true;
}
}  // namespace

BalancerTorque balancerTorqueAndSlope(const Counterbalance& cb, double q) {
  if (!cb.present()) return {};
  double sp = 0.0;
  double cp = 0.0;
  sinCos(cb.psi0 + cb.sign * q, sp, cp);
  return balancerTorqueAndSlope(cb, sp, cp);
}

BalancerTorque balancerTorqueAndSlope(const Counterbalance& cb, double sp, double cp) {
  BalancerTorque b;
  if (!cb.present()) return b;
  const double rd = cb.r * cb.d;
  const double l = std::sqrt(cb.r * cb.r + cb.d * cb.d - 2.0 * rd * cp);  // balancerLength
  const bool push = cb.action == Counterbalance::Action::kPush;
  const double stroke = push ? cb.length_ref - l : l - cb.length_ref;
  double f = 0.0;      // load magnitude f(σ), N
  double df_ds = 0.0;  // df/dσ, N/m
  if (cb.law == Counterbalance::Law::kSpring) {
    f = cb.force_ref + cb.stiffness * stroke;
    df_ds = cb.stiffness;
  } else {
    const double v = cb.volume_ref - cb.area * stroke;
    if (!(v > 0)) {  // exhausted gas volume: infinite load, as balancerForce
      f = df_ds = std::numeric_limits<double>::infinity();
    } else {
      const double ratio = cb.volume_ref / v;
      f = cb.pressure_ref * cb.area *
          (cb.polytropic == 1.0 ? ratio : std::pow(ratio, cb.polytropic));
      df_ds = f * cb.polytropic * cb.area / v;
    }
  }
  const double F = push ? f : -f;  // balancerForce
  b.torque = cb.sign * F * cb.r * cb.d * sp / l;
  // dF/dℓ = −df/dσ for both actions; dℓ/dq = sign r d sin ψ / ℓ
  const double dl_dq = cb.sign * rd * sp / l;
  b.slope =
      cb.sign * rd * ((-df_ds * dl_dq * sp + F * cb.sign * cp) / l - F * sp * dl_dq / (l * l));
  return b;
}

void chainFrames(const Model& model, Data& data, const Vec6& theta) {
  chainFrames(model, data, theta, jointTrig(theta));
}

JointTrig jointTrig(const Vec6& theta) {
  JointTrig t;
  for (int i = 0; i < 6; ++i) sinCos(theta[i], t.sn[i], t.cs[i]);
  return t;
}

void chainFrames(const Model& model, Data& data, const Vec6& theta, const JointTrig& trig) {
  Data::ChainFrames& f = data.frames;
  f.theta = theta;
  f.sin_theta = trig.sn;
  Mat3 R = Mat3::Identity();
  Vec3 p = Vec3::Zero();
  for (int i = 0; i < 6; ++i) {
    const size_t s = static_cast<size_t>(i);
    const Pose& O = model.origin[s];
    p += R * O.translation();
    if (!isIdentity(O.linear())) R = R * O.linear();  // R_W_Ji
    rotateAbout(R, model.bodies[s].ubar, trig.sn[i], trig.cs[i], f.u[s]);
    f.p[s] = p;
    f.R[s] = R;
  }
  f.R_tcp.noalias() = R * model.T_L6_tcp.linear();
  f.p_tcp = p + R * model.T_L6_tcp.translation();
}

void shiftTrig(JointTrig& trig, const Vec6& from, const Vec6& to) {
  for (int i = 0; i < 6; ++i) shiftSinCos(from[i], to[i], trig.sn[i], trig.cs[i]);
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
      // formed in registers, then stored: reading them back from `sums` stalled on the stores
      const Vec3 fk = b.mass * model.gravity;
      const Vec3 rk = f.p[s] + f.R[s] * b.com;
      sums.f[s] = fk;
      sums.r[s] = rk;
      Fs += fk;
      Ms += rk.cross(fk);
    } else {
      sums.f[s].setZero();
      sums.r[s] = f.p[s];
    }
    tau[j] = -f.u[s].dot(Ms - f.p[s].cross(Fs));
  }
  sums.balancer = gravity && model.counterbalance.present();
  if (sums.balancer) {
    const Counterbalance& cb = model.counterbalance;
    // sin/cos of ψ = ψ₀ + s θ_j follow the previous evaluation's (small Newton steps)
    const double psi = cb.psi0 + cb.sign * f.theta[cb.joint];
    shiftSinCos(sums.balancer_psi, psi, sums.balancer_sin, sums.balancer_cos);
    sums.balancer_psi = psi;
    const int j = cb.joint;
    const BalancerTorque b = balancerTorqueAndSlope(cb, sums.balancer_sin, sums.balancer_cos);
    tau[j] -= b.torque;
    sums.balancer_slope = b.slope;
  }
}

void staticSensitivity(const Model& model, const Data& data, const StaticLoadSums& sums, Mat6& D) {
  const Data::ChainFrames& f = data.frames;
  // One backward pass: W_j = A_j − F_j p_jᵀ with the suffix sums A_j = Σ_{k≥j} f_k r_kᵀ,
  // F_j = Σ_{k≥j} f_k of the base-fixed forces (weights and F_W at the TCP); per joint
  //   row_j = (tr W_j) u_j − W_jᵀ u_j + N_W × u_j           (D_ji = row_j · u_i, i ≤ j)
  //   a_i   = W_iᵀ u_i − (tr W_i) u_i + u_i × M_t,i + p_i × (u_i × F_t)
  //   b_j   = u_j × p_j                                      (D_ji = −u_j · a_i + t_i · b_j, i > j)
  // with t_i = u_i × F_t: −u_j · ((p_i − p_j) × t_i) = −u_j · (p_i × t_i) + t_i · (u_j × p_j).
  std::array<Vec3, 6> row;  // every entry is set in the pass below
  std::array<Vec3, 6> a;
  std::array<Vec3, 6> b;
  std::array<Vec3, 6> t;
  Mat3 A = sums.F_all_w * f.p_tcp.transpose();
  Vec3 Fw = sums.F_all_w;
  for (int j = 5; j >= 0; --j) {
    const size_t s = static_cast<size_t>(j);
    A.noalias() += sums.f[s] * sums.r[s].transpose();
    Fw += sums.f[s];
    const Vec3& u = f.u[s];
    const Vec3& p = f.p[s];
    // W_jᵀ u = A_jᵀ u − p (F_j · u), tr W_j = tr A_j − F_j · p
    const Vec3 Wtu = A.transpose() * u - p * Fw.dot(u);
    const double tr = A.trace() - Fw.dot(p);
    const Vec3 twist = tr * u - Wtu;
    row[s] = twist + sums.N_w.cross(u);
    t[s] = u.cross(sums.F_t);
    const Vec3 M_t = (f.p_tcp - p).cross(sums.F_t) + sums.N_t;
    a[s] = -twist + u.cross(M_t) + p.cross(t[s]);
    b[s] = u.cross(p);
  }
  for (int j = 0; j < 6; ++j) {
    const size_t sj = static_cast<size_t>(j);
    const Vec3& uj = f.u[sj];
    for (int i = 0; i <= j; ++i) D(j, i) = row[sj].dot(f.u[static_cast<size_t>(i)]);
    for (int i = j + 1; i < 6; ++i) {
      const size_t si = static_cast<size_t>(i);
      D(j, i) = t[si].dot(b[sj]) - uj.dot(a[si]);
    }
  }
  if (sums.balancer)
    D(model.counterbalance.joint, model.counterbalance.joint) -= sums.balancer_slope;
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
