#include "compensator/robot/ik.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "compensator/support/error.hpp"

namespace roprec {

namespace {

constexpr double kTwoPi = 2.0 * kPi;
constexpr double kMaxDeviationRad =
    0.02;  // estimate: beyond ~1° the ideal-model start may pick a wrong branch
constexpr double kMaxDeviationM = 0.02;  // estimate: same reasoning for a 2 m class arm
constexpr double kExactTol = 1e-12;
/// Slack of the joint limits (rad, 0.0006°): a pose taught exactly at a limit and written as
/// programs write it (mm with 3 decimals, angles with 4) comes back up to ~2e-6 rad past it.
constexpr double kLimitTol = 1e-5;
constexpr double kConvergedTol = 1e-9;  // contract of this module: m and rad
constexpr double kRefineTol = 1e-13;    // polish below this (m, rad)
constexpr double kReachClamp =
    1e-9;  // relative slack of cos ψ before a target counts as unreachable

Mat3 axisRotation(const Vec3& a, double q) {
  const double s = std::sin(q);
  const double c = std::cos(q);
  const double t = 1.0 - c;
  Mat3 R;
  R << t * a.x() * a.x() + c, t * a.x() * a.y() - s * a.z(), t * a.x() * a.z() + s * a.y(),
      t * a.x() * a.y() + s * a.z(), t * a.y() * a.y() + c, t * a.y() * a.z() - s * a.x(),
      t * a.x() * a.z() - s * a.y(), t * a.y() * a.z() + s * a.x(), t * a.z() * a.z() + c;
  return R;
}

/// R · Rot(axis_i, q) with the fast path for axes along the joint frame's coordinate axes.
void rotateJoint(const IkModel& m, size_t i, double q, Mat3& R) {
  const int kind = m.axis_kind[i];
  if (kind < 0) {
    R = R * axisRotation(m.axis[i], q);
    return;
  }
  const double th = m.axis_sign[i] * q;
  const double c = std::cos(th);
  const double s = std::sin(th);
  const int a = (kind + 1) % 3;  // Rot about e_k mixes columns k+1 and k+2 (cyclic)
  const int b = (kind + 2) % 3;
  const Vec3 ca = R.col(a);
  const Vec3 cb = R.col(b);
  R.col(a) = c * ca + s * cb;
  R.col(b) = -s * ca + c * cb;
}

/// R · origin_R_i, skipping identity rotations.
void applyOrigin(const IkModel& m, size_t i, Mat3& R) {
  if (!m.origin_rotation_identity[i]) R = R * m.origin_R[i];
}

/// ang(v) = atan2(v_x, v_z): angle of an (x, z) vector, increasing with rotations about +y.
double ang(const Eigen::Vector2d& v) { return std::atan2(v.x(), v.y()); }

/// Rotation of an (x, z) vector about +y by θ.
Eigen::Vector2d rotY(double theta, const Eigen::Vector2d& v) {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  return {c * v.x() + s * v.y(), -s * v.x() + c * v.y()};
}

Mat3 rotYMat(double theta) {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  Mat3 R;
  R << c, 0, s, 0, 1, 0, -s, 0, c;
  return R;
}

/// World rotation of link 3 for (q1, q2, q3).
Mat3 linkThreeRotation(const IkModel& m, double q1, double q2, double q3) {
  Mat3 R = m.origin_R[0];
  rotateJoint(m, 0, q1, R);
  applyOrigin(m, 1, R);
  rotateJoint(m, 1, q2, R);
  applyOrigin(m, 2, R);
  rotateJoint(m, 2, q3, R);
  return R;
}

/// |x| (m) and sin ψ beyond which rawSolutions knows a raw solution's shoulder and elbow labels
/// before computing it (round-off moves ikBranch's x and ψ by ≲ 1e-13 m, 1e-15 rad).
constexpr double kLabelMargin = 1e-6;

/// ikBranch's x of the wrist centre in the arm plane (lateral offset removed) at q2, q3.
double shoulderX(const IkModel& m, double q2, double q3) {
  const Eigen::Vector2d arm = rotY(q2, m.u0 + rotY(m.sigma3 * q3, m.v0));
  return m.p2x + arm.x();
}

/// ikBranch's sin ψ at q3.
double elbowSine(const IkModel& m, double q3) { return std::sin(m.psi0 + m.sigma3 * q3); }

/// ikBranch's wrist label (0 or 1) at q5.
int wristLabel(const IkModel& m, double q5) {
  const double t5 = wrapAngle(m.ctrl_sign5 * q5 + m.ctrl_offset5);
  return (t5 < 0.0 || t5 >= kPi) ? 1 : 0;
}

/// ikBranch's shoulder and elbow labels at q2, q3 as 4 s + 2 e (its index without the wrist).
int armLabels(const IkModel& m, double q2, double q3) {
  const int shoulder = m.shoulder_sign * shoulderX(m, q2, q3) >= 0.0 ? 0 : 1;
  const int elbow = m.elbow_sign * elbowSine(m, q3) >= 0.0 ? 0 : 1;
  return 4 * shoulder + 2 * elbow;
}

/// a and b are the same bits (IkArmCache's keys: −0 and +0 differ, as they may in atan2).
bool sameBits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

/// ikForwardKinematics' recursion from joint `first` on, with R and t those before it.
Pose forwardFrom(const IkModel& m, const Vec6& q, size_t first, Mat3 R, Vec3 t) {
  for (size_t i = first; i < 6; ++i) {
    t = t + R * m.origin_p[i];
    applyOrigin(m, i, R);
    rotateJoint(m, i, q[static_cast<int>(i)], R);
  }
  Pose T = Pose::Identity();
  T.translation() = t + R * m.tip_p;
  T.linear() = R * m.tip_R;
  return T;
}

/// ikForwardKinematics, with joints 1–3's part taken from `cache` when q's joints 1–3 are the
/// bits it was made at (else made and kept): the same pose, bit for bit.
Pose forwardKinematics(const IkModel& m, const Vec6& q, IkArmCache* cache) {
  if (cache == nullptr) return forwardFrom(m, q, 0, Mat3::Identity(), Vec3::Zero());
  if (!(cache->fk_valid && sameBits(cache->fk_q[0], q[0]) && sameBits(cache->fk_q[1], q[1]) &&
        sameBits(cache->fk_q[2], q[2]))) {
    Mat3 R = Mat3::Identity();
    Vec3 t = Vec3::Zero();
    for (size_t i = 0; i < 3; ++i) {
      t = t + R * m.origin_p[i];
      applyOrigin(m, i, R);
      rotateJoint(m, i, q[static_cast<int>(i)], R);
    }
    cache->fk_valid = true;
    cache->fk_q = {q[0], q[1], q[2]};
    cache->fk_R = R;
    cache->fk_t = t;
  }
  return forwardFrom(m, q, 3, cache->fk_R, cache->fk_t);
}

/// ikBranch with the arm's x (shoulderX) and sin ψ (elbowSine) of q's joints 2, 3 given.
IkBranch branchOf(const IkModel& m, const Vec6& q, double x, double spsi) {
  IkBranch b;
  b.shoulder = m.shoulder_sign * x >= 0.0 ? 0 : 1;
  b.elbow = m.elbow_sign * spsi >= 0.0 ? 0 : 1;
  b.wrist = wristLabel(m, q[4]);
  b.shoulder_margin_m = std::abs(x);
  b.elbow_margin_rad = std::abs(spsi);
  b.wrist_margin_rad = std::abs(std::sin(q[4] + m.alpha));
  return b;
}

/// ikBranch, with x and sin ψ taken from `cache` when q's joints 2, 3 are the bits they were made
/// at (else made and kept): the same labels and margins, bit for bit.
IkBranch branchOf(const IkModel& m, const Vec6& q, IkArmCache* cache) {
  if (cache == nullptr) return branchOf(m, q, shoulderX(m, q[1], q[2]), elbowSine(m, q[2]));
  if (!(cache->branch_valid && sameBits(cache->branch_q[0], q[1]) &&
        sameBits(cache->branch_q[1], q[2]))) {
    cache->branch_valid = true;
    cache->branch_q = {q[1], q[2]};
    cache->branch_x = shoulderX(m, q[1], q[2]);
    cache->branch_spsi = elbowSine(m, q[2]);
  }
  return branchOf(m, q, cache->branch_x, cache->branch_spsi);
}

/// Rotation error ω with R_target = Exp(ω) R and its exact angle.
Vec3 rotationError(const Mat3& R_target, const Mat3& R, double& angle) {
  const Mat3 Re = R_target * R.transpose();
  Vec3 v = 0.5 * Vec3(Re(2, 1) - Re(1, 2), Re(0, 2) - Re(2, 0), Re(1, 0) - Re(0, 1));
  const double s = v.norm();
  const double c = 0.5 * (Re.trace() - 1.0);
  angle = std::atan2(s, c);
  if (s < 1e-300) return v;
  return v * (angle / s);
}

bool finitePose(const Pose& T) { return T.matrix().allFinite(); }

/// Newton iterations on the exact chain; returns the steps taken and the residual at the final q.
/// `cache` (may be null): forwardKinematics' scratch.
int refine(const IkModel& m, const Pose& target, Vec6& q, int max_iterations, double tol,
           double max_step, IkResidual& residual, IkArmCache* cache = nullptr) {
  Pose T;
  Mat6 J;
  for (int it = 0;; ++it) {
    T = forwardKinematics(m, q, cache);  // the pose of ikForwardKinematicsJacobian, bit for bit
    Vec6 e;
    e.head<3>() = target.translation() - T.translation();
    e.tail<3>() = rotationError(target.linear(), T.linear(), residual.rotation);
    residual.position = e.head<3>().norm();
    if ((residual.position <= tol && residual.rotation <= tol) || it >= max_iterations) return it;
    ikForwardKinematicsJacobian(m, q, T, J);  // J only where a step is taken
    const Eigen::PartialPivLU<Mat6> lu(J);
    Vec6 dq = lu.solve(e);
    if (!dq.allFinite() || std::abs(lu.determinant()) < 1e-14) {
      // Damped least squares at (near) singular Jacobians: (JᵀJ + λ²I) dq = Jᵀ e.
      const Mat6 A = J.transpose() * J + 1e-10 * Mat6::Identity();
      dq = A.ldlt().solve(J.transpose() * e);
    }
    const double n = dq.cwiseAbs().maxCoeff();
    if (n > max_step) dq *= max_step / n;
    q += dq;
  }
}

void finishSolution(const IkModel& m, const Pose& target, const IkOptions& opt, IkSolution& s) {
  s.iterations =
      refine(m, target, s.q, opt.max_refine_iterations, kRefineTol, 0.5, s.residual, opt.arm_cache);
  for (int i = 0; i < 6; ++i) s.q[i] = wrapAngle(s.q[i]);
  s.converged = s.residual.position <= kConvergedTol && s.residual.rotation <= kConvergedTol;
  s.branch = branchOf(m, s.q, opt.arm_cache);
  s.singular_wrist = s.branch.wrist_margin_rad < opt.singular_angle;
  s.singular_elbow = s.branch.elbow_margin_rad < opt.singular_angle;
  s.singular_shoulder = s.branch.shoulder_margin_m < opt.singular_distance;
}

bool solutionLess(const IkSolution& a, const IkSolution& b) {
  if (a.branch.index() != b.branch.index()) return a.branch.index() < b.branch.index();
  for (int i = 0; i < 6; ++i) {
    if (a.turn[static_cast<size_t>(i)] != b.turn[static_cast<size_t>(i)]) {
      return a.turn[static_cast<size_t>(i)] < b.turn[static_cast<size_t>(i)];
    }
  }
  for (int i = 0; i < 6; ++i) {
    if (a.q[i] != b.q[i]) return a.q[i] < b.q[i];
  }
  return false;
}

/// Turn indices beyond ±kMaxTurnIndex are never enumerated (the loaders refuse joint limits
/// beyond ±10 turns; this keeps the enumeration bounded whatever an IkModel holds).
constexpr double kMaxTurnIndex = 16.0;

/// Appends the turn representatives of a wrapped solution.
void expandTurns(const IkModel& m, const IkSolution& base, const IkOptions& opt, IkResult& result) {
  std::array<int, 6> kmin{};
  std::array<int, 6> kcount{};
  bool inside = true;
  for (int i = 0; i < 6; ++i) {
    const size_t u = static_cast<size_t>(i);
    const double qw = base.q[i];
    // Turn counts in double, clamped before the conversion: absurd (or non-finite) limits must
    // neither overflow an int nor make the loops below run 2^31 times.
    const double lo_d = std::ceil((m.lower[i] - qw - kLimitTol) / kTwoPi);
    const double hi_d = std::floor((m.upper[i] - qw + kLimitTol) / kTwoPi);
    if (!(lo_d <= hi_d)) {  // also NaN limits
      inside = false;
      break;
    }
    const int lo = static_cast<int>(std::clamp(lo_d, -kMaxTurnIndex, kMaxTurnIndex));
    const int hi = static_cast<int>(std::clamp(hi_d, -kMaxTurnIndex, kMaxTurnIndex));
    if (hi < lo) {
      inside = false;
      break;
    }
    if (opt.turns == IkTurns::kPrimary) {
      const double ref = opt.seed ? (*opt.seed)[i] : 0.0;
      int best = lo;
      double best_d = std::abs(qw + kTwoPi * lo - ref);
      for (int k = lo + 1; k <= hi; ++k) {
        const double d = std::abs(qw + kTwoPi * k - ref);
        // Ties (e.g. ±180° for a zero reference, within 1e-9 rad) go to the larger representative.
        if (d < best_d - 1e-9 || (d <= best_d + 1e-9 && k > best)) {
          best = k;
          best_d = d;
        }
      }
      kmin[u] = best;
      kcount[u] = 1;
    } else {
      kmin[u] = lo;
      kcount[u] = hi - lo + 1;
    }
  }
  if (!inside) {  // out of limits: the wrapped representative only
    kmin.fill(0);
    kcount.fill(1);
  }
  int total = 1;
  for (int c : kcount) total *= c;
  if (total > kIkMaxTurnsPerBranch) {
    result.truncated = true;
    total = kIkMaxTurnsPerBranch;
  }
  for (int n = 0; n < total && result.count < kIkMaxSolutions; ++n) {
    IkSolution s = base;
    int rest = n;
    for (int i = 5; i >= 0; --i) {  // joint 1 varies slowest (lexicographic order of turns)
      const size_t u = static_cast<size_t>(i);
      const int k = kmin[u] + rest % kcount[u];
      rest /= kcount[u];
      s.turn[u] = static_cast<std::int8_t>(k);
      s.q[i] = base.q[i] + kTwoPi * k;
    }
    s.within_limits = inside;
    result.solutions[static_cast<size_t>(result.count++)] = s;
  }
}

}  // namespace

Vec6 vendorReferencePose(const RobotCard& card) {
  Vec6 ctrl = Vec6::Zero();
  if (card.vendor == Vendor::kKuka) {
    // KUKA mechanical reference / elbow-up pose {0, −90°, 90°, 0, 0, 0} (docs/programs.md §7.1).
    ctrl[1] = -90.0 * kDeg;
    ctrl[2] = 90.0 * kDeg;
  }
  return fromControllerJoints(card, ctrl);
}

namespace {
IkModelOptions ikOptionsOf(const RobotCard& card) {
  IkModelOptions o;
  o.reference_q = vendorReferencePose(card);
  o.ctrl_sign5 = card.joints[4].controller_sign;
  o.ctrl_offset5 = card.joints[4].controller_offset;
  return o;
}
}  // namespace

IkModel buildIkModel(const Robot& robot) {
  return buildIkModel(robot.chain, ikOptionsOf(robot.card));
}

IkModel buildRealIkModel(const Robot& robot) {
  return buildIkModel(robot.real_chain, ikOptionsOf(robot.card));
}

IkModel buildIkModel(const ChainDescription& chain, const IkModelOptions& options) {
  IkModel m;
  m.file = chain.file;
  for (size_t i = 0; i < 6; ++i) {
    const ChainJoint& j = chain.joints[i];
    m.origin_R[i] = j.origin.linear();
    m.origin_p[i] = j.origin.translation();
    m.axis[i] = j.axis.normalized();
    m.axis_kind[i] = -1;
    m.axis_sign[i] = 1.0;
    for (int k = 0; k < 3; ++k) {
      if (std::abs(std::abs(m.axis[i][k]) - 1.0) == 0.0) {
        m.axis_kind[i] = k;
        m.axis_sign[i] = m.axis[i][k] > 0 ? 1.0 : -1.0;
      }
    }
    m.origin_rotation_identity[i] = m.origin_R[i] == Mat3::Identity();
    m.lower[static_cast<int>(i)] = j.continuous ? -4.0 * kPi : j.lower;
    m.upper[static_cast<int>(i)] = j.continuous ? 4.0 * kPi : j.upper;
  }
  m.tip_R = chain.tip.linear();
  m.tip_p = chain.tip.translation();
  m.ctrl_sign5 = options.ctrl_sign5;
  m.ctrl_offset5 = options.ctrl_offset5;

  // Joint frames at q = 0 in the base frame.
  std::array<Vec3, 6> z;
  std::array<Vec3, 6> p;
  Mat3 R = Mat3::Identity();
  Vec3 t = Vec3::Zero();
  for (size_t i = 0; i < 6; ++i) {
    t = t + R * m.origin_p[i];
    R = R * m.origin_R[i];
    z[i] = R * m.axis[i];
    p[i] = t;
  }
  const Mat3 R3 = [&] {
    Mat3 r = Mat3::Identity();
    for (size_t i = 0; i < 3; ++i) r = r * m.origin_R[i];
    return r;
  }();
  const Mat3 R_tip0 = R * m.tip_R;
  const Vec3 p_tip0 = t + R * m.tip_p;

  auto fail = [&](int joint, const std::string& what) {
    throw InputError(
        chain.file, chain.joints[static_cast<size_t>(joint)].line,
        "not a spherical-wrist ortho-parallel 6R robot (analytic IK needs axis 2 ∥ axis 3 ⊥ "
        "axis 1 and axes 4, 5, 6 meeting in one point): " +
            what);
  };

  IkGeometryDeviation& dev = m.deviation;
  dev.axis12_rad = std::abs(std::asin(std::clamp(z[0].dot(z[1]), -1.0, 1.0)));
  dev.axis23_rad = std::acos(std::clamp(std::abs(z[1].dot(z[2])), 0.0, 1.0));
  // Wrist centre: least-squares point nearest to axes 4, 5, 6.
  Mat3 A = Mat3::Zero();
  Vec3 rhs = Vec3::Zero();
  for (size_t i = 3; i < 6; ++i) {
    const Mat3 P = Mat3::Identity() - z[i] * z[i].transpose();
    A += P;
    rhs += P * p[i];
  }
  const Eigen::FullPivLU<Mat3> luA(A);
  if (luA.rank() < 3) fail(4, "axes 4, 5 and 6 are parallel");
  const Vec3 C0 = luA.solve(rhs);
  for (size_t i = 3; i < 6; ++i) {
    const Vec3 d = (Mat3::Identity() - z[i] * z[i].transpose()) * (C0 - p[i]);
    dev.wrist_intersection_m = std::max(dev.wrist_intersection_m, d.norm());
  }
  dev.wrist_orthogonality_rad =
      std::max(std::abs(std::asin(std::clamp(z[3].dot(z[4]), -1.0, 1.0))),
               std::abs(std::asin(std::clamp(z[4].dot(z[5]), -1.0, 1.0))));
  if (dev.axis12_rad > kMaxDeviationRad) {
    fail(1, "axis 2 is not perpendicular to axis 1 (off by " + numberText(dev.axis12_rad / kDeg) +
                "°)");
  }
  if (dev.axis23_rad > kMaxDeviationRad) {
    fail(2, "axis 3 is not parallel to axis 2 (off by " + numberText(dev.axis23_rad / kDeg) + "°)");
  }
  if (dev.wrist_intersection_m > kMaxDeviationM) {
    fail(3, "axes 4, 5, 6 do not intersect (" + numberText(dev.wrist_intersection_m * 1e3) +
                " mm apart)");
  }
  if (dev.wrist_orthogonality_rad > kMaxDeviationRad) {
    fail(4, "wrist axes are not orthogonal (off by " +
                numberText(dev.wrist_orthogonality_rad / kDeg) + "°)");
  }
  dev.exact = dev.axis12_rad <= kExactTol && dev.axis23_rad <= kExactTol &&
              dev.wrist_intersection_m <= kExactTol && dev.wrist_orthogonality_rad <= kExactTol;

  // F0.
  const Vec3 z0 = z[0];
  const Vec3 y0 = (z[1] - z[1].dot(z0) * z0).normalized();
  const Vec3 x0 = y0.cross(z0);
  m.F0.col(0) = x0;
  m.F0.col(1) = y0;
  m.F0.col(2) = z0;
  m.o = p[0] + (p[1] - p[0]).dot(z0) * z0;
  const Vec3 P2 = m.F0.transpose() * (p[1] - m.o);
  const Vec3 P3 = m.F0.transpose() * (p[2] - m.o);
  const Vec3 Cf = m.F0.transpose() * (C0 - m.o);
  m.p2x = P2.x();
  m.u0 = Eigen::Vector2d(P3.x() - P2.x(), P3.z() - P2.z());
  m.v0 = Eigen::Vector2d(Cf.x() - P3.x(), Cf.z() - P3.z());
  m.b = Cf.y();
  m.L2 = m.u0.norm();
  m.L3 = m.v0.norm();
  if (m.L2 < 1e-6 || m.L3 < 1e-6)
    fail(2, "axis 3 lies on axis 2 or the wrist centre lies on axis 3");
  m.psi0 = ang(m.v0) - ang(m.u0);
  {
    // Reach tolerance of the ideal model: a non-ideal arm may reach up to ~slack_m farther or
    // nearer.
    const double slack_m =
        dev.exact
            ? 0.0
            : dev.wrist_intersection_m + std::abs(m.b) +
                  (dev.axis12_rad + dev.axis23_rad + dev.wrist_orthogonality_rad) * (m.L2 + m.L3);
    m.reach_slack = kReachClamp + (m.L2 + m.L3) * slack_m / (m.L2 * m.L3);
  }
  m.sigma3 = z[2].dot(y0) >= 0.0 ? 1.0 : -1.0;
  m.c_tip = R_tip0.transpose() * (C0 - p_tip0);

  // Wrist basis in the link-3 frame.
  const Vec3 w4 = R3.transpose() * z[3];
  const Vec3 w5r = R3.transpose() * z[4];
  const Vec3 w6 = R3.transpose() * z[5];
  const Vec3 e1 = w4.normalized();
  const Vec3 e2 = (w5r - w5r.dot(e1) * e1).normalized();
  const Vec3 e3 = e1.cross(e2);
  m.E.col(0) = e1;
  m.E.col(1) = e2;
  m.E.col(2) = e3;
  m.alpha = std::atan2(-w6.dot(e3), w6.dot(e1));
  const Mat3 R_w0 = R3.transpose() * R_tip0;
  m.B = R_w0.transpose() * m.E * rotYMat(m.alpha);

  // Branch calibration on the reference pose.
  const Vec6& qr = options.reference_q;
  const Eigen::Vector2d arm = rotY(qr[1], m.u0 + rotY(m.sigma3 * qr[2], m.v0));
  const double x_ref = m.p2x + arm.x();
  const double s_ref = std::sin(m.psi0 + m.sigma3 * qr[2]);
  if (std::abs(x_ref) < 1e-6) fail(0, "the reference pose has the wrist centre on axis 1");
  if (std::abs(s_ref) < 1e-6) fail(2, "the reference pose is at the elbow singularity");
  m.shoulder_sign = x_ref > 0 ? 1.0 : -1.0;
  m.elbow_sign = s_ref > 0 ? 1.0 : -1.0;

  // OPW read-out.
  OpwParameters& opw = m.opw;
  opw.a1 = m.shoulder_sign * m.p2x;
  // c1: distance of the shoulder plane (axis 2) from the base origin along axis 1, unsigned.
  opw.c1 = std::abs(m.o.dot(z0));
  opw.b = m.b;
  opw.c2 = m.L2;
  const Vec3 z4f = m.F0.transpose() * z[3];
  Eigen::Vector2d f(z4f.x(), z4f.z());
  if (f.norm() < 1e-9) {
    f = m.v0.normalized();
  } else {
    f.normalize();
    if (f.dot(m.v0) < 0) f = -f;
  }
  const Eigen::Vector2d n = rotY(-m.elbow_sign * 0.5 * kPi, f);
  opw.c3 = m.v0.dot(f);
  opw.a2 = -m.v0.dot(n);
  opw.c4 = std::abs((p_tip0 - C0).dot(z[5]));
  return m;
}

Pose ikForwardKinematics(const IkModel& m, const Vec6& q) {
  return forwardKinematics(m, q, nullptr);
}

void ikForwardKinematicsJacobian(const IkModel& m, const Vec6& q, Pose& T, Mat6& J) {
  Mat3 R = Mat3::Identity();
  Vec3 t = Vec3::Zero();
  std::array<Vec3, 6> z;
  std::array<Vec3, 6> o;
  for (size_t i = 0; i < 6; ++i) {
    t = t + R * m.origin_p[i];
    applyOrigin(m, i, R);
    z[i] = m.axis_kind[i] >= 0 ? Vec3(m.axis_sign[i] * R.col(m.axis_kind[i])) : Vec3(R * m.axis[i]);
    o[i] = t;
    rotateJoint(m, i, q[static_cast<int>(i)], R);
  }
  const Vec3 pt = t + R * m.tip_p;
  T = Pose::Identity();
  T.translation() = pt;
  T.linear() = R * m.tip_R;
  for (int i = 0; i < 6; ++i) {
    const size_t u = static_cast<size_t>(i);
    J.block<3, 1>(0, i) = z[u].cross(pt - o[u]);
    J.block<3, 1>(3, i) = z[u];
  }
}

IkResidual ikResidual(const IkModel& m, const Vec6& q, const Pose& target) {
  const Pose T = ikForwardKinematics(m, q);
  IkResidual r;
  r.position = (target.translation() - T.translation()).norm();
  rotationError(target.linear(), T.linear(), r.rotation);
  return r;
}

IkBranch ikBranch(const IkModel& m, const Vec6& q) { return branchOf(m, q, nullptr); }

bool withinLimits(const IkModel& m, const Vec6& q) {
  for (int i = 0; i < 6; ++i) {
    if (q[i] < m.lower[i] - kLimitTol || q[i] > m.upper[i] + kLimitTol) return false;
  }
  return true;
}

namespace {
/// The analytic solutions of the ideal model before refinement and turn expansion (wrapped q, at
/// most 8, in branch-construction order). Sets `failure` and `failure_value` when none.
/// `seed_used` (may be null) is set when opt.seed chose a joint (wrist centre on axis 1, or a
/// wrist-singular branch). `only` ≥ 0 (0..7): only the raw solutions of that branch — by ikBranch
/// of their wrapped q, the labels solveIk filters an exact chain's raw solutions by — are
/// computed (the shoulder and elbow labels are known beforehand — see kLabelMargin — or from q2,
/// q3, the wrist label from q5): the same values, in the same order, as the unfiltered list's.
int rawSolutions(const IkModel& m, const Pose& target, const IkOptions& opt,
                 std::array<IkSolution, 8>& raw, IkFailure& failure, double& failure_value,
                 bool* seed_used, int only = -1) {
  failure = IkFailure::kNone;
  failure_value = 0.0;
  if (!finitePose(target)) {
    failure = IkFailure::kNotFinite;
    return 0;
  }
  const Vec3 C = target * m.c_tip;
  const Vec3 c = m.F0.transpose() * (C - m.o);
  const double r2 = c.x() * c.x() + c.y() * c.y();
  double x2 = r2 - m.b * m.b;
  if (x2 < 0.0) {
    if (x2 > -2.0 * std::abs(m.b) * 1e-9 - 1e-18) {
      x2 = 0.0;
    } else {
      failure = IkFailure::kLateralOffset;
      failure_value = std::abs(m.b) - std::sqrt(r2);
      return 0;
    }
  }
  const double xabs = std::sqrt(x2);
  const bool on_axis = r2 < 1e-24;
  const Mat3 R_T = target.linear();

  int nraw = 0;
  bool reached = false;  // some (shoulder, elbow) pair is within reach (else `failure` is set)
  double far_excess = -1.0;
  double near_excess = -1.0;
  for (int s = 0; s < 2; ++s) {
    const double x = (s == 0 ? 1.0 : -1.0) * m.shoulder_sign * xabs;
    if (on_axis && seed_used) *seed_used = true;
    const Eigen::Vector2d d(x - m.p2x, c.z());
    double cpsi = (d.squaredNorm() - m.L2 * m.L2 - m.L3 * m.L3) / (2.0 * m.L2 * m.L3);
    const bool clamped = cpsi > 1.0 || cpsi < -1.0;
    if (cpsi > 1.0) {
      if (cpsi > 1.0 + m.reach_slack) {
        const double excess = d.norm() - (m.L2 + m.L3);
        far_excess = far_excess < 0.0 ? excess : std::min(far_excess, excess);
        continue;
      }
      cpsi = 1.0;
    } else if (cpsi < -1.0) {
      if (cpsi < -1.0 - m.reach_slack) {
        const double excess = std::abs(m.L2 - m.L3) - d.norm();
        near_excess = near_excess < 0.0 ? excess : std::min(near_excess, excess);
        continue;
      }
      cpsi = -1.0;
    }
    reached = true;
    const double spsi = std::sqrt(std::max(0.0, 1.0 - cpsi * cpsi));
    // Labels of (s, e) known beforehand: ikBranch rebuilds x and sin ψ from the wrapped q2, q3 —
    // the same x (Ry(q2) w = d when |w| = |d|, i.e. cos ψ not clamped) and an angle ψ + 2πk, up
    // to round-off (≲ 1e-13 m, 1e-15 rad): with |x| and sin ψ beyond kLabelMargin their signs,
    // hence the labels s and e, are certain.
    const bool known = only >= 0 && !clamped && xabs > kLabelMargin && spsi > kLabelMargin;
    double q1 = 0.0;
    bool have_q1 = false;
    for (int e = 0; e < 2; ++e) {
      if (known && 4 * s + 2 * e != (only & 6)) continue;
      const double psi = std::atan2((e == 0 ? 1.0 : -1.0) * m.elbow_sign * spsi, cpsi);
      const double q3 = m.sigma3 * (psi - m.psi0);
      const Eigen::Vector2d w = m.u0 + rotY(psi - m.psi0, m.v0);
      const double q2 = ang(d) - ang(w);
      if (only >= 0 && !known && armLabels(m, wrapAngle(q2), wrapAngle(q3)) != (only & 6)) continue;
      if (!have_q1) {
        q1 = on_axis ? (opt.seed ? (*opt.seed)[0] : 0.0) + (s == 0 ? 0.0 : kPi)
                     : std::atan2(c.y(), c.x()) - std::atan2(m.b, x);
        have_q1 = true;
      }
      const Mat3 R3 = linkThreeRotation(m, q1, q2, q3);
      const Mat3 N = m.E.transpose() * R3.transpose() * R_T * m.B;
      const double c5 = N(0, 0);
      const double s5 = std::hypot(N(1, 0), N(2, 0));
      for (int ws = 0; ws < 2; ++ws) {
        const double sg = ws == 0 ? 1.0 : -1.0;
        double q4 = 0.0;
        double q5p = 0.0;
        double q6 = 0.0;
        if (s5 > 1e-10) {
          q5p = std::atan2(sg * s5, c5);
          if (only >= 0 && wristLabel(m, wrapAngle(q5p - m.alpha)) != (only & 1)) continue;
          q4 = std::atan2(sg * N(1, 0), -sg * N(2, 0));
          q6 = std::atan2(sg * N(0, 1), sg * N(0, 2));
        } else {
          // Wrist singularity: only q4 + q6 (q5' = 0) or q4 − q6 (q5' = π) is defined.
          if (seed_used) *seed_used = true;
          const double q4ref = (opt.seed ? (*opt.seed)[3] : 0.0) + (ws == 0 ? 0.0 : kPi);
          const double rot = std::atan2(N(2, 1), N(1, 1));
          q4 = q4ref;
          if (c5 >= 0.0) {
            q5p = 0.0;
            q6 = rot - q4;
          } else {
            q5p = kPi;
            q6 = q4 - rot;
          }
          if (only >= 0 && wristLabel(m, wrapAngle(q5p - m.alpha)) != (only & 1)) continue;
        }
        IkSolution& sol = raw[static_cast<size_t>(nraw++)];
        sol = IkSolution{};
        sol.q << q1, q2, q3, q4, q5p - m.alpha, q6;
        for (int i = 0; i < 6; ++i) sol.q[i] = wrapAngle(sol.q[i]);
      }
    }
  }
  if (!reached) {
    if (far_excess >= 0.0) {
      failure = IkFailure::kOutOfReach;
      failure_value = far_excess;
    } else {
      failure = IkFailure::kTooClose;
      failure_value = near_excess;
    }
  }
  return nraw;
}

int rawSolutions(const IkModel& m, const Pose& target, const IkOptions& opt,
                 std::array<IkSolution, 8>& raw, IkResult& result, int only = -1) {
  result.count = 0;
  result.truncated = false;
  return rawSolutions(m, target, opt, raw, result.failure, result.failure_value, nullptr, only);
}

/// The primary-turn representative of a wrapped q (what expandTurns keeps in kPrimary mode: per
/// joint the in-limit turn nearest the seed, ties to the larger); false when a joint has none.
bool primaryRepresentative(const IkModel& m, const Vec6& qw, const Vec6* seed, Vec6& q) {
  for (int i = 0; i < 6; ++i) {
    const double lo_d = std::ceil((m.lower[i] - qw[i] - kLimitTol) / kTwoPi);
    const double hi_d = std::floor((m.upper[i] - qw[i] + kLimitTol) / kTwoPi);
    if (!(lo_d <= hi_d)) return false;
    const int lo = static_cast<int>(std::clamp(lo_d, -kMaxTurnIndex, kMaxTurnIndex));
    const int hi = static_cast<int>(std::clamp(hi_d, -kMaxTurnIndex, kMaxTurnIndex));
    if (hi < lo) return false;
    const double ref = seed ? (*seed)[i] : 0.0;
    int best = lo;
    double best_d = std::abs(qw[i] + kTwoPi * lo - ref);
    for (int k = lo + 1; k <= hi; ++k) {
      const double d = std::abs(qw[i] + kTwoPi * k - ref);
      if (d < best_d - 1e-9 || (d <= best_d + 1e-9 && k > best)) {
        best = k;
        best_d = d;
      }
    }
    q[i] = qw[i] + kTwoPi * best;
  }
  return true;
}

double weightedDistance(const Vec6& a, const Vec6& b, const std::array<double, 6>& w) {
  double s = 0;
  for (int i = 0; i < 6; ++i) s += w[static_cast<size_t>(i)] * (a[i] - b[i]) * (a[i] - b[i]);
  return s;
}

bool admissible(const IkSolution& s) {
  return s.within_limits && s.converged && !s.singular_wrist && !s.singular_shoulder;
}
}  // namespace

void solveIk(const IkModel& m, const Pose& target, const IkOptions& opt, IkResult& result) {
  // set up once per thread (8 solutions, ~1 kB): rawSolutions writes every entry it returns
  thread_local std::array<IkSolution, 8> raw;
  // an exact chain's refinement leaves q as it is: the other branches' raw solutions are skipped
  const bool one_branch = opt.branch >= 0 && m.deviation.exact;
  const int nraw = rawSolutions(m, target, opt, raw, result, one_branch ? opt.branch : -1);
  for (int k = 0; k < nraw; ++k) {
    IkSolution& sol = raw[static_cast<size_t>(k)];
    finishSolution(m, target, opt, sol);
    if (opt.branch >= 0 && sol.branch.index() != opt.branch) continue;
    expandTurns(m, sol, opt, result);
  }
  std::sort(result.solutions.begin(), result.solutions.begin() + result.count, solutionLess);
}

void ikCandidates(const IkModel& m, const Pose& target, IkCandidates& c) {
  c.count = 0;
  c.valid = false;
  if (!m.deviation.exact) return;  // solveIkNearest solves every branch there
  std::array<IkSolution, 8> raw;
  bool seed_used = false;
  c.count = rawSolutions(m, target, IkOptions{}, raw, c.failure, c.failure_value, &seed_used);
  for (int k = 0; k < c.count; ++k) c.q[static_cast<size_t>(k)] = raw[static_cast<size_t>(k)].q;
  c.valid = !seed_used;
}

bool solveIkNearest(const IkModel& m, const Pose& target, const Vec6& ref,
                    const std::array<double, 6>& weights, IkResult& result, IkSolution& best) {
  return solveIkNearest(m, target, ref, weights, nullptr, result, best);
}

bool solveIkNearest(const IkModel& m, const Pose& target, const Vec6& ref,
                    const std::array<double, 6>& weights, const IkCandidates* ahead,
                    IkResult& result, IkSolution& best) {
  IkOptions opt;
  opt.seed = &ref;
  auto full = [&] {  // every branch finished, then the nearest admissible (the reference path)
    solveIk(m, target, opt, result);
    const IkSolution* b = nullptr;
    double bd = 1e300;
    for (int i = 0; i < result.count; ++i) {
      const IkSolution& s = result.solutions[static_cast<size_t>(i)];
      if (!admissible(s)) continue;
      const double d = weightedDistance(s.q, ref, weights);
      if (d < bd) {
        b = &s;
        bd = d;
      }
    }
    if (b) best = *b;
    return b != nullptr;
  };
  if (!m.deviation.exact) return full();  // refinement moves q: distances unknown beforehand
  std::array<IkSolution, 8> raw;
  int nraw = 0;
  if (ahead != nullptr && ahead->valid) {  // the same raw solutions, computed without the seed
    result.count = 0;
    result.failure = ahead->failure;
    result.failure_value = ahead->failure_value;
    result.truncated = false;
    nraw = ahead->count;
    for (int k = 0; k < nraw; ++k) {
      raw[static_cast<size_t>(k)] = IkSolution{};
      raw[static_cast<size_t>(k)].q = ahead->q[static_cast<size_t>(k)];
    }
  } else {
    nraw = rawSolutions(m, target, opt, raw, result);
  }
  if (nraw == 0) return false;
  // candidates by their distance before finishing (an exact chain's finishing keeps q)
  std::array<std::pair<double, int>, 8> order;
  int n = 0;
  for (int k = 0; k < nraw; ++k) {
    Vec6 q;
    if (!primaryRepresentative(m, raw[static_cast<size_t>(k)].q, &ref, q)) continue;
    order[static_cast<size_t>(n++)] = {weightedDistance(q, ref, weights), k};
  }
  // by distance, an insertion sort of the ≤ 8 candidates (std::sort drew a false -Warray-bounds
  // from GCC 12 here: its 16-element stage on an 8-element array)
  for (int i = 1; i < n; ++i) {
    for (int j = i; j > 0 && order[static_cast<size_t>(j)] < order[static_cast<size_t>(j - 1)]; --j)
      std::swap(order[static_cast<size_t>(j)], order[static_cast<size_t>(j - 1)]);
  }
  bool found = false;
  double best_d = 0.0;
  for (int c = 0; c < n; ++c) {
    const double d0 = order[static_cast<size_t>(c)].first;
    if (found && d0 > best_d) break;  // every later candidate is farther
    IkSolution sol = raw[static_cast<size_t>(order[static_cast<size_t>(c)].second)];
    finishSolution(m, target, opt, sol);
    result.count = 0;
    expandTurns(m, sol, opt, result);
    if (result.count != 1 || sol.iterations != 0) return full();  // not the predicted case
    const IkSolution& s = result.solutions[0];
    const double d = weightedDistance(s.q, ref, weights);
    if (d != d0) return full();
    if (!admissible(s)) continue;
    // equal distances: the first in solveIk's order wins, as in the full path
    if (!found || d < best_d || (d == best_d && solutionLess(s, best))) {
      best = s;
      best_d = d;
      found = true;
    }
  }
  if (!found) return full();  // the caller's reasons read every solution
  result.count = 0;
  return true;
}

std::string describeIkFailure(const IkResult& r) {
  std::ostringstream s;
  switch (r.failure) {
    case IkFailure::kNone:
      return r.count > 0 ? "" : "no solution";
    case IkFailure::kOutOfReach:
      if (!std::isfinite(r.failure_value) || r.failure_value > 1e9) {  // a 1e300 mm target
        s << "unreachable: the wrist centre is far beyond the arm's reach (over 10^12 mm: check "
             "the target)";
        break;
      }
      s << "unreachable: the wrist centre is " << numberText(r.failure_value * 1e3)
        << " mm beyond the arm's reach";
      break;
    case IkFailure::kTooClose:
      s << "unreachable: the wrist centre is " << numberText(r.failure_value * 1e3)
        << " mm inside the arm's inner workspace boundary";
      break;
    case IkFailure::kLateralOffset:
      s << "unreachable: the wrist centre is " << numberText(r.failure_value * 1e3)
        << " mm closer to axis 1 than the arm's lateral offset";
      break;
    case IkFailure::kNotFinite:
      s << "the target pose is not finite";
      break;
  }
  return s.str();
}

IkNearResult solveIkNear(const IkModel& m, const Pose& target, const Vec6& seed,
                         const IkNearOptions& options) {
  IkNearResult r;
  r.q = seed;
  if (!finitePose(target) || !seed.allFinite()) return r;
  r.iterations = refine(m, target, r.q, options.max_iterations, options.tolerance, options.max_step,
                        r.residual);
  r.converged = r.residual.position <= kConvergedTol && r.residual.rotation <= kConvergedTol;
  if (!r.converged || ikBranch(m, r.q).index() != ikBranch(m, seed).index()) {
    IkResult all;
    IkOptions o;
    o.seed = &seed;
    solveIk(m, target, o, all);
    const int want = ikBranch(m, seed).index();
    const IkSolution* best = nullptr;
    double best_d = 0.0;
    for (int i = 0; i < all.count; ++i) {
      const IkSolution& s = all.solutions[static_cast<size_t>(i)];
      if (!s.converged) continue;
      const double d = (s.q - seed).norm() + (s.branch.index() == want ? 0.0 : 1e6);
      if (!best || d < best_d) {
        best = &s;
        best_d = d;
      }
    }
    if (best) {
      r.q = best->q;
      r.residual = best->residual;
      r.converged = true;
      r.analytic_fallback = true;
    }
  }
  r.within_limits = withinLimits(m, r.q);
  return r;
}

}  // namespace roprec
