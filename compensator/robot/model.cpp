#include "compensator/robot/model.hpp"

#include <cassert>
#include <cmath>
#include <limits>

namespace roprec::nc {

namespace {

inline Eigen::Ref<const Vec3> seg(const VecQ& q, int idx) { return q.segment<3>(idx); }

/// A unit vector perpendicular to `u`, chosen deterministically (least-aligned basis vector).
Vec3 perpendicular(const Vec3& u) {
  Vec3 e = Vec3::UnitX();
  if (std::abs(u.x()) > std::abs(u.y()) || std::abs(u.x()) > std::abs(u.z())) {
    e = std::abs(u.y()) < std::abs(u.z()) ? Vec3::UnitY() : Vec3::UnitZ();
  }
  return (e - e.dot(u) * u).normalized();
}

/// Second-moment matrix K (4×4) of a rigid body over [p; d1; d2; d3] with orthonormal local
/// directions X̄ and the point at the link origin (docs/model.md §4.1):
///   K = [m, m aᵀ; m a, J],  m a = X̄ᵀ m ḡ,  J = X̄ᵀ J̄ X̄,  J̄ = ½ tr(I_G) I − I_G + m ḡ ḡᵀ.
Eigen::Matrix4d secondMoments(double m, const Vec3& com, const Mat3& I_G, const Mat3& Xbar) {
  Eigen::Matrix4d K = Eigen::Matrix4d::Zero();
  if (m <= 0.0) return K;
  const Mat3 Jbar = 0.5 * I_G.trace() * Mat3::Identity() - I_G + m * com * com.transpose();
  const Vec3 ma = Xbar.transpose() * (m * com);
  K(0, 0) = m;
  K.block<1, 3>(0, 1) = ma.transpose();
  K.block<3, 1>(1, 0) = ma;
  K.block<3, 3>(1, 1) = Xbar.transpose() * Jbar * Xbar;
  return K;
}

/// Parent elements (point, axis) of body i, from q or the ground.
inline Vec3 parentPoint(const Model& m, const VecQ& q, int i) {
  return i == 0 ? m.p0 : Vec3(seg(q, idxPnext(i - 1)));
}
inline Vec3 parentAxis(const Model& m, const VecQ& q, int i) {
  return i == 0 ? m.u0 : Vec3(seg(q, idxUnext(i - 1)));
}
/// Angle reference a_i = X_{i-1} alpha (ground constant for i = 0).
inline Vec3 angleRef(const Model& m, const VecQ& q, int i) {
  if (i == 0) return m.a0;
  const Vec3& al = m.bodies[static_cast<size_t>(i)].alpha;
  return al.x() * parentAxis(m, q, i - 1) + al.y() * Vec3(seg(q, idxV(i - 1))) +
         al.z() * Vec3(seg(q, idxW(i - 1)));
}

}  // namespace

Model buildModel(const ChainDescription& chain, const ToolAttachment& tool) {
  Model m;
  Pose T_W_J = Pose::Identity();  // world pose of the current joint frame at q = 0
  for (int i = 0; i < 6; ++i) {
    const ChainJoint& j = chain.joints[static_cast<size_t>(i)];
    Body& b = m.bodies[static_cast<size_t>(i)];
    m.origin[static_cast<size_t>(i)] = j.origin;
    m.axis[static_cast<size_t>(i)] = j.axis;
    b.ubar = j.axis.normalized();
    b.vbar = perpendicular(b.ubar);
    b.wbar = b.ubar.cross(b.vbar);
    b.Xbar << b.ubar, b.vbar, b.wbar;
    b.lower = j.lower;
    b.upper = j.upper;
    if (i == 0) {
      m.p0 = j.origin.translation();
      m.u0 = j.origin.linear() * b.ubar;
      m.a0 = j.origin.linear() * b.vbar;
    } else {
      const Body& parent = m.bodies[static_cast<size_t>(i - 1)];
      // a_i in the parent link frame = image of v̄_i at θ_i = 0.
      b.alpha = parent.Xbar.transpose() * (j.origin.linear() * b.vbar);
      Body& pm = m.bodies[static_cast<size_t>(i - 1)];
      pm.c_next = parent.Xbar.transpose() * j.origin.translation();
      pm.e_next = parent.Xbar.transpose() * (j.origin.linear() * b.ubar);
    }
    T_W_J = T_W_J * j.origin;
  }
  m.T_L6_flange = chain.tip;
  m.T_L6_tcp = chain.tip * tool.T_flange_tcp;
  const Body& b5 = m.bodies[5];
  m.c_tcp = b5.Xbar.transpose() * m.T_L6_tcp.translation();
  m.Rbar_tcp = b5.Xbar.transpose() * m.T_L6_tcp.linear();

  for (int i = 0; i < 6; ++i) {
    Body& b = m.bodies[static_cast<size_t>(i)];
    Inertial in = chain.inertials[static_cast<size_t>(i)];
    if (i == 5 && tool.mass > 0.0) {
      Inertial t;
      t.mass = tool.mass;
      t.com = tool.com;
      t.inertia = tool.inertia;
      t.present = true;
      in = combine(in, transformed(t, chain.tip));
    }
    b.mass = in.mass;
    b.com = in.com;
    b.inertia = in.inertia;
    b.K = secondMoments(in.mass, in.com, in.inertia, b.Xbar);
  }
  m.counterbalance = chain.counterbalance;
  if (!chain.gravity_modelled) m.gravity.setZero();
  return m;
}

Data::Data(const Model& /*model*/) {}

void evaluatePhi(const Model& model, Data& data, const VecQ& q) {
  VecC& Phi = data.Phi;
  for (int i = 0; i < 6; ++i) {
    const Body& b = model.bodies[static_cast<size_t>(i)];
    const int r = i < 5 ? rowBody(i) : 55;
    const Vec3 p = parentPoint(model, q, i);
    const Vec3 u = parentAxis(model, q, i);
    const Vec3 v = seg(q, idxV(i));
    const Vec3 w = seg(q, idxW(i));
    Phi[r] = v.dot(v) - 1.0;
    Phi[r + 1] = v.dot(u);
    Phi.segment<3>(r + 2) = w - u.cross(v);
    if (i < 5) {
      Phi.segment<3>(r + 5) =
          seg(q, idxPnext(i)) - p - (b.c_next.x() * u + b.c_next.y() * v + b.c_next.z() * w);
      Phi.segment<3>(r + 8) =
          seg(q, idxUnext(i)) - (b.e_next.x() * u + b.e_next.y() * v + b.e_next.z() * w);
    }
    const Vec3 a = angleRef(model, q, i);
    const double th = q[idxTheta(i)];
    Phi[kAngleRow + i] = data.cross_form[static_cast<size_t>(i)] ? u.dot(a.cross(v)) - std::sin(th)
                                                                 : a.dot(v) - std::cos(th);
  }
}

void factorize(const Model& model, Data& data) {
  const VecQ& q = data.q;
  for (int i = 0; i < 6; ++i) {
    const size_t s = static_cast<size_t>(i);
    Data::BodyCache& bc = data.body[s];
    const double th = q[idxTheta(i)];
    const double sn = std::sin(th);
    const double cs = std::cos(th);
    data.cross_form[s] = std::abs(sn) <= std::sqrt(0.5);
    bc.u = parentAxis(model, q, i);
    bc.v = seg(q, idxV(i));
    bc.w = seg(q, idxW(i));
    bc.a = angleRef(model, q, i);
    Mat3 G;
    G.row(0) = 2.0 * bc.v.transpose();
    G.row(1) = bc.u.transpose();
    if (data.cross_form[s]) {
      // Φ = u·(a×v) − sin θ:  ∂/∂u = a×v, ∂/∂a = v×u, ∂/∂v = u×a, ∂/∂θ = −cos θ
      G.row(2) = bc.u.cross(bc.a).transpose();
      bc.g_du = bc.a.cross(bc.v);
      bc.g_da = bc.v.cross(bc.u);
      bc.g_th = -cs;
    } else {
      // Φ = a·v − cos θ:  ∂/∂a = v, ∂/∂v = a, ∂/∂θ = sin θ
      G.row(2) = bc.a.transpose();
      bc.g_du.setZero();
      bc.g_da = bc.v;
      bc.g_th = sn;
    }
    // G is well conditioned by construction (rows ≈ orthogonal, switching rule of §2).
    bc.Ginv = G.inverse();
  }
  data.factorized = true;
}

void solveA(const Model& model, const Data& data, const VecQ& r, VecQ& x) {
  assert(data.factorized && "factorize() the configuration before solving with A");
  for (int i = 0; i < 6; ++i) x[idxTheta(i)] = r[kNc + i];
  Vec3 du = Vec3::Zero();  // increments of the parent's shared elements
  Vec3 dp = Vec3::Zero();
  Vec3 dup = Vec3::Zero();  // increment of the grandparent axis (parent body's u)
  for (int i = 0; i < 6; ++i) {
    const size_t s = static_cast<size_t>(i);
    const Body& b = model.bodies[s];
    const Data::BodyCache& bc = data.body[s];
    const int row = i < 5 ? rowBody(i) : 55;
    Vec3 da = Vec3::Zero();
    if (i > 0) {
      da = b.alpha.x() * dup + b.alpha.y() * x.segment<3>(idxV(i - 1)) +
           b.alpha.z() * x.segment<3>(idxW(i - 1));
    }
    const Vec3 sv(r[row], r[row + 1] - bc.v.dot(du),
                  r[kAngleRow + i] - bc.g_du.dot(du) - bc.g_da.dot(da) - bc.g_th * x[idxTheta(i)]);
    const Vec3 dv = bc.Ginv * sv;
    const Vec3 dw = r.segment<3>(row + 2) + du.cross(bc.v) + bc.u.cross(dv);
    x.segment<3>(idxV(i)) = dv;
    x.segment<3>(idxW(i)) = dw;
    if (i < 5) {
      const Vec3 dpn =
          r.segment<3>(row + 5) + dp + b.c_next.x() * du + b.c_next.y() * dv + b.c_next.z() * dw;
      const Vec3 dun =
          r.segment<3>(row + 8) + b.e_next.x() * du + b.e_next.y() * dv + b.e_next.z() * dw;
      x.segment<3>(idxPnext(i)) = dpn;
      x.segment<3>(idxUnext(i)) = dun;
      dup = du;
      du = dun;
      dp = dpn;
    }
  }
}

void solveAT(const Model& model, const Data& data, const VecQ& b_in, VecQ& y) {
  assert(data.factorized && "factorize() the configuration before solving with A^T");
  // Reverse-mode sweep of solveA: y = (A⁻¹)ᵀ b. `bar_*` are the adjoints of the increments.
  Vec3 bar_un = Vec3::Zero();  // adjoint of the next joint's axis/point (from the child body)
  Vec3 bar_pn = Vec3::Zero();
  Vec3 bar_v_acc = Vec3::Zero();  // contributions of the child's angle reference to this body
  Vec3 bar_w_acc = Vec3::Zero();
  Vec3 bar_u_acc = Vec3::Zero();  // ... and to this body's own axis (= the parent's next axis)
  for (int i = 5; i >= 0; --i) {
    const size_t s = static_cast<size_t>(i);
    const Body& b = model.bodies[s];
    const Data::BodyCache& bc = data.body[s];
    const int row = i < 5 ? rowBody(i) : 55;
    Vec3 bar_du = bar_u_acc;
    Vec3 bar_dp = Vec3::Zero();
    Vec3 bar_dv = b_in.segment<3>(idxV(i)) + bar_v_acc;
    Vec3 bar_dw = b_in.segment<3>(idxW(i)) + bar_w_acc;
    if (i < 5) {
      const Vec3 bu = b_in.segment<3>(idxUnext(i)) + bar_un;
      const Vec3 bp = b_in.segment<3>(idxPnext(i)) + bar_pn;
      y.segment<3>(row + 8) = bu;
      y.segment<3>(row + 5) = bp;
      bar_du += b.e_next.x() * bu + b.c_next.x() * bp;
      bar_dv += b.e_next.y() * bu + b.c_next.y() * bp;
      bar_dw += b.e_next.z() * bu + b.c_next.z() * bp;
      bar_dp += bp;
    }
    // dw = r_w + du × v + u × dv  =  r_w − [v]× du + [u]× dv
    y.segment<3>(row + 2) = bar_dw;
    bar_du += bc.v.cross(bar_dw);
    bar_dv -= bc.u.cross(bar_dw);
    // dv = G⁻¹ s
    const Vec3 bar_s = bc.Ginv.transpose() * bar_dv;
    y[row] = bar_s[0];
    y[row + 1] = bar_s[1];
    y[kAngleRow + i] = bar_s[2];
    bar_du -= bc.v * bar_s[1] + bc.g_du * bar_s[2];
    const Vec3 bar_da = -bc.g_da * bar_s[2];
    y[kNc + i] = b_in[idxTheta(i)] - bc.g_th * bar_s[2];
    // hand the adjoints of the shared parent elements to the parent body
    bar_un = bar_du;
    bar_pn = bar_dp;
    bar_u_acc = b.alpha.x() * bar_da;
    bar_v_acc = b.alpha.y() * bar_da;
    bar_w_acc = b.alpha.z() * bar_da;
  }
}

namespace {
/// Exact q for θ = z by the forward recursion T_i = T_{i-1} O_i Rot(axis_i, θ_i).
void closedFormGuess(const Model& model, Data& data, const Vec6& z) {
  VecQ& q = data.q;
  Pose T = Pose::Identity();
  for (int i = 0; i < 6; ++i) {
    const size_t s = static_cast<size_t>(i);
    T = T * model.origin[s];
    T.rotate(Eigen::AngleAxisd(z[i], model.axis[s]));
    const Body& b = model.bodies[s];
    const Mat3& Rw = T.linear();
    q.segment<3>(idxV(i)) = Rw * b.vbar;
    q.segment<3>(idxW(i)) = Rw * b.wbar;
    if (i < 5) {
      const Pose& On = model.origin[s + 1];
      q.segment<3>(idxPnext(i)) = T * On.translation();
      q.segment<3>(idxUnext(i)) = Rw * (On.linear() * model.axis[s + 1]);
    }
    q[idxTheta(i)] = z[i];
  }
}
}  // namespace

namespace {
/// The dot form a·v = cos θ is met by v = Rot(u, ±θ) a: Newton from a distant guess can land on
/// the mirror. True when every joint's sin θ has the sign of u·(a × v) (and cos θ of a·v).
bool onCommandedBranch(const Model& model, const Data& data) {
  const VecQ& q = data.q;
  for (int i = 0; i < 6; ++i) {
    const Vec3 u = parentAxis(model, q, i);
    const Vec3 v = seg(q, idxV(i));
    const Vec3 a = angleRef(model, q, i);
    const double th = q[idxTheta(i)];
    if (u.dot(a.cross(v)) * std::sin(th) < -1e-9 || a.dot(v) * std::cos(th) < -1e-9) return false;
  }
  return true;
}
}  // namespace

PositionResult solvePosition(const Model& model, Data& data, const Vec6& z, Guess guess) {
  // A warm start far from z (more than ~30° on a joint) is no better than the closed form.
  if (guess == Guess::kWarmStart && (z - data.z).lpNorm<Eigen::Infinity>() > 0.5)
    guess = Guess::kClosedForm;
  data.z = z;
  if (guess == Guess::kClosedForm) {
    closedFormGuess(model, data, z);
  } else {
    for (int i = 0; i < 6; ++i) data.q[idxTheta(i)] = z[i];
  }
  PositionResult res;
  // Angle-row forms are chosen once per configuration (from θ = z), never inside Newton.
  for (int i = 0; i < 6; ++i)
    data.cross_form[static_cast<size_t>(i)] = std::abs(std::sin(z[i])) <= std::sqrt(0.5);
  data.factorized = false;
  for (;;) {
    evaluatePhi(model, data, data.q);
    res.residual = data.Phi.lpNorm<Eigen::Infinity>();
    if (!std::isfinite(res.residual) || !data.Phi.allFinite() || !data.q.allFinite()) {
      res.residual = std::numeric_limits<double>::infinity();
      break;
    }
    if (res.residual < model.tol_phi) {
      res.converged = true;
      break;
    }
    if (res.iterations >= model.max_iterations) break;
    factorize(model, data);
    data.rhs.head<kNc>() = -data.Phi;
    data.rhs.tail<kNz>().setZero();
    solveA(model, data, data.rhs, data.scratch);
    data.q += data.scratch;
    ++res.iterations;
    data.factorized = false;
  }
  if (res.converged && guess == Guess::kWarmStart && !onCommandedBranch(model, data)) {
    // converged to a mirror configuration: restart from the exact forward recursion
    const int it = res.iterations;
    res = solvePosition(model, data, z, Guess::kClosedForm);
    res.iterations += it;
  }
  return res;
}

namespace {
void ensureFactorized(const Model& model, Data& data) {
  if (!data.factorized) factorize(model, data);
}
}  // namespace

const MatR& velocityTransform(const Model& model, Data& data) {
  ensureFactorized(model, data);
  MatR& R = data.R;
  R.setZero();
  // Column j: unit rate of θ_j; bodies before j do not move, body j's v responds to the angle
  // row alone, later bodies only to their parents (r = 0 there).
  for (int j = 0; j < kNz; ++j) {
    auto x = R.col(j);
    x[idxTheta(j)] = 1.0;
    Vec3 du = Vec3::Zero();
    Vec3 dp = Vec3::Zero();
    Vec3 dup = Vec3::Zero();
    for (int i = j; i < 6; ++i) {
      const size_t s = static_cast<size_t>(i);
      const Body& b = model.bodies[s];
      const Data::BodyCache& bc = data.body[s];
      Vec3 dv;
      if (i == j) {
        dv = bc.Ginv.col(2) * (-bc.g_th);
      } else {
        const Vec3 da = b.alpha.x() * dup + b.alpha.y() * Vec3(x.segment<3>(idxV(i - 1))) +
                        b.alpha.z() * Vec3(x.segment<3>(idxW(i - 1)));
        const Vec3 sv(0.0, -bc.v.dot(du), -bc.g_du.dot(du) - bc.g_da.dot(da));
        dv = bc.Ginv * sv;
      }
      const Vec3 dw = du.cross(bc.v) + bc.u.cross(dv);
      x.segment<3>(idxV(i)) = dv;
      x.segment<3>(idxW(i)) = dw;
      if (i < 5) {
        const Vec3 dpn = dp + b.c_next.x() * du + b.c_next.y() * dv + b.c_next.z() * dw;
        const Vec3 dun = b.e_next.x() * du + b.e_next.y() * dv + b.e_next.z() * dw;
        x.segment<3>(idxPnext(i)) = dpn;
        x.segment<3>(idxUnext(i)) = dun;
        dup = du;
        du = dun;
        dp = dpn;
      }
    }
  }
  return R;
}

const VecQ& velocities(const Model& model, Data& data, const Vec6& zd) {
  ensureFactorized(model, data);
  data.rhs.setZero();
  data.rhs.tail<kNz>() = zd;
  solveA(model, data, data.rhs, data.qd);
  return data.qd;
}

const VecQ& accelerationTerm(const Model& model, Data& data, const Vec6& zd) {
  ensureFactorized(model, data);
  const VecQ& q = data.q;
  const VecQ& qd = data.qd;
  VecC& c = data.c;
  c.setZero();
  for (int i = 0; i < 6; ++i) {
    const size_t s = static_cast<size_t>(i);
    const int row = i < 5 ? rowBody(i) : 55;
    const Vec3 ud = i == 0 ? Vec3::Zero() : Vec3(seg(qd, idxUnext(i - 1)));
    const Vec3 vd = seg(qd, idxV(i));
    c[row] = -2.0 * vd.dot(vd);
    c[row + 1] = -2.0 * vd.dot(ud);
    c.segment<3>(row + 2) = 2.0 * ud.cross(vd);
    // angle row
    const Vec3 u = parentAxis(model, q, i);
    const Vec3 v = seg(q, idxV(i));
    const Vec3 a = angleRef(model, q, i);
    Vec3 ad = Vec3::Zero();
    if (i > 0) {
      const Body& b = model.bodies[s];
      const Vec3 dup = i == 1 ? Vec3::Zero() : Vec3(seg(qd, idxUnext(i - 2)));
      ad = b.alpha.x() * dup + b.alpha.y() * Vec3(seg(qd, idxV(i - 1))) +
           b.alpha.z() * Vec3(seg(qd, idxW(i - 1)));
    }
    const double th = q[idxTheta(i)];
    const double thd = zd[i];
    if (data.cross_form[s]) {
      c[kAngleRow + i] = -2.0 * (ud.dot(ad.cross(v)) + ud.dot(a.cross(vd)) + u.dot(ad.cross(vd))) -
                         std::sin(th) * thd * thd;
    } else {
      c[kAngleRow + i] = -2.0 * ad.dot(vd) - std::cos(th) * thd * thd;
    }
  }
  data.rhs.head<kNc>() = c;
  data.rhs.tail<kNz>().setZero();
  solveA(model, data, data.rhs, data.Sc);
  return data.Sc;
}

void framePoses(const Model& model, Data& data) {
  const VecQ& q = data.q;
  const Vec3 p5 = seg(q, idxPnext(4));
  Mat3 X;
  X << Vec3(seg(q, idxUnext(4))), Vec3(seg(q, idxV(5))), Vec3(seg(q, idxW(5)));
  const Mat3 R_W_L6 = X * model.bodies[5].Xbar.transpose();
  data.T_W_tcp.linear() = X * model.Rbar_tcp;
  data.T_W_tcp.translation() = p5 + X * model.c_tcp;
  data.T_W_flange.linear() = R_W_L6 * model.T_L6_flange.linear();
  data.T_W_flange.translation() = p5 + R_W_L6 * model.T_L6_flange.translation();
}

const Mat6& tcpJacobian(const Model& model, Data& data) {
  velocityTransform(model, data);
  const VecQ& q = data.q;
  const Vec3 u = seg(q, idxUnext(4));
  const Vec3 v = seg(q, idxV(5));
  const Vec3 w = seg(q, idxW(5));
  const Vec3& c = model.c_tcp;
  for (int j = 0; j < kNz; ++j) {
    const auto Rj = data.R.col(j);
    const Vec3 dp = Rj.segment<3>(idxPnext(4));
    const Vec3 du = Rj.segment<3>(idxUnext(4));
    const Vec3 dv = Rj.segment<3>(idxV(5));
    const Vec3 dw = Rj.segment<3>(idxW(5));
    data.J_tcp.block<3, 1>(0, j) = dp + c.x() * du + c.y() * dv + c.z() * dw;
    data.J_tcp.block<3, 1>(3, j) = 0.5 * (u.cross(du) + v.cross(dv) + w.cross(dw));
  }
  return data.J_tcp;
}

PositionResult forwardKinematics(const Model& model, Data& data, const Vec6& z) {
  const PositionResult r = solvePosition(model, data, z, Guess::kClosedForm);
  framePoses(model, data);
  return r;
}

void assemblePhiq(const Model& model, const Data& data, Eigen::Ref<Eigen::MatrixXd> J) {
  J.setZero();
  const VecQ& q = data.q;
  auto put = [&](int row, int col, const Eigen::Matrix<double, 1, 3>& g) {
    if (col >= 0) J.block<1, 3>(row, col) += g;
  };
  auto putM = [&](int row, int col, const Mat3& g) {
    if (col >= 0) J.block<3, 3>(row, col) += g;
  };
  for (int i = 0; i < 6; ++i) {
    const size_t s = static_cast<size_t>(i);
    const Body& b = model.bodies[s];
    const int row = i < 5 ? rowBody(i) : 55;
    const int iu = i == 0 ? -1 : idxUnext(i - 1);
    const int ip = i == 0 ? -1 : idxPnext(i - 1);
    const Vec3 u = parentAxis(model, q, i);
    const Vec3 v = seg(q, idxV(i));
    put(row, idxV(i), 2.0 * v.transpose());
    put(row + 1, idxV(i), u.transpose());
    put(row + 1, iu, v.transpose());
    putM(row + 2, idxW(i), Mat3::Identity());
    putM(row + 2, iu, skew(v));  // ∂(−u×v)/∂u = v×· = [v]×
    putM(row + 2, idxV(i), -skew(u));
    if (i < 5) {
      putM(row + 5, idxPnext(i), Mat3::Identity());
      putM(row + 5, ip, -Mat3::Identity());
      putM(row + 5, iu, -b.c_next.x() * Mat3::Identity());
      putM(row + 5, idxV(i), -b.c_next.y() * Mat3::Identity());
      putM(row + 5, idxW(i), -b.c_next.z() * Mat3::Identity());
      putM(row + 8, idxUnext(i), Mat3::Identity());
      putM(row + 8, iu, -b.e_next.x() * Mat3::Identity());
      putM(row + 8, idxV(i), -b.e_next.y() * Mat3::Identity());
      putM(row + 8, idxW(i), -b.e_next.z() * Mat3::Identity());
    }
    const Vec3 a = angleRef(model, q, i);
    const double th = q[idxTheta(i)];
    const int ar = kAngleRow + i;
    Eigen::Matrix<double, 1, 3> ga;
    if (data.cross_form[s]) {
      put(ar, idxV(i), u.cross(a).transpose());
      put(ar, iu, a.cross(v).transpose());
      ga = v.cross(u).transpose();
      J(ar, idxTheta(i)) = -std::cos(th);
    } else {
      put(ar, idxV(i), a.transpose());
      ga = v.transpose();
      J(ar, idxTheta(i)) = std::sin(th);
    }
    if (i > 0) {
      put(ar, i == 1 ? -1 : idxUnext(i - 2), b.alpha.x() * ga);
      put(ar, idxV(i - 1), b.alpha.y() * ga);
      put(ar, idxW(i - 1), b.alpha.z() * ga);
    }
  }
}

}  // namespace roprec::nc
