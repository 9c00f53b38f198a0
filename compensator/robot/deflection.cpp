#include "compensator/robot/deflection.hpp"

#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "compensator/robot/fast_equilibrium.hpp"
#include "compensator/support/c_format.hpp"
#include "compensator/support/error.hpp"

namespace roprec::nc {

Vec6 JointCompliance::effective() const {
  Vec6 e;
  for (int i = 0; i < 6; ++i) e[i] = 1.0 / (1.0 / k[i] + 1.0 / k_servo[i]);
  return e;
}

JointCompliance complianceFromCard(const RobotCard& card) {
  JointCompliance c;
  for (int i = 0; i < 6; ++i) {
    const JointCard& j = card.joints[static_cast<size_t>(i)];
    c.k[i] = j.stiffness > 0 ? j.stiffness : 1e300;
    if (j.position_gain && j.velocity_gain) c.k_servo[i] = *j.position_gain * *j.velocity_gain;
  }
  return c;
}

JointCompliance requireComplianceFromCard(const RobotCard& card) {
  for (const JointCard& j : card.joints) {
    if (!(j.stiffness > 0)) {
      throw InputError(
          card.file, j.line,
          "joint '" + j.name +
              "' has no stiffness: give it in the robot card or with --stiffness \"k1 .. k6\"");
    }
  }
  return complianceFromCard(card);
}

Vec6 gravityCommandOffset(const Model& calibration_model, Data& data, const JointCompliance& c,
                          const Vec6& theta) {
  chainFrames(calibration_model, data, theta);
  const Loads gravity_only;
  Vec6 tau;
  StaticLoadSums sums;
  staticTorquesFromFrames(calibration_model, data, gravity_only, tau, sums);
  return tau.cwiseQuotient(c.effective());
}

std::string ControllerReference::description() const {
  switch (kind) {
    case Kind::kGravityCompensated:
      return "absolute-accuracy option: the controller compensates the gravity deflection of "
             "the arm and its calibration load (offset K_eff^-1 tau_g,cal(theta_cmd))";
    case Kind::kMastering: {
      std::string s = "mastering reference: kinematics exact at the calibration pose (";
      for (int i = 0; i < 6; ++i) {
        s += (i ? " " : "") + cFixed(calibration_pose[i] / kDeg, 3);
      }
      return s +
             " deg, URDF) under the robot's own weight (offset K_eff^-1 tau_g,robot(theta_cal))";
    }
    case Kind::kNone:
      break;
  }
  return "none (gravity not modelled or switched off)";
}

ControllerReference makeControllerReference(const ChainDescription& chain, const RobotCard& card,
                                            bool gravity, bool gravity_compensated,
                                            const ToolAttachment& calibration_load) {
  ControllerReference ref;
  if (!gravity || !chain.gravity_modelled) return ref;
  if (gravity_compensated) {
    ToolAttachment load;
    load.mass = calibration_load.mass;
    load.com = calibration_load.com;
    ref.kind = ControllerReference::Kind::kGravityCompensated;
    ref.calibration_model = buildModel(chain, load);
    return ref;
  }
  ref.kind = ControllerReference::Kind::kMastering;
  ref.calibration_pose = card.calibration_pose;
  const Model robot_only = buildModel(chain);
  Data data(robot_only);
  solvePosition(robot_only, data, ref.calibration_pose, Guess::kClosedForm);
  const Loads gravity_only;
  ref.calibration_pose_torque = staticTorques(robot_only, data, gravity_only);
  return ref;
}

Vec6 controllerReferenceOffset(const ControllerReference& ref, Data& data, const JointCompliance& c,
                               const Vec6& theta_cmd) {
  switch (ref.kind) {
    case ControllerReference::Kind::kGravityCompensated:
      return gravityCommandOffset(ref.calibration_model, data, c, theta_cmd);
    case ControllerReference::Kind::kMastering:
      return ref.calibration_pose_torque.cwiseQuotient(c.effective());
    case ControllerReference::Kind::kNone:
      break;
  }
  return Vec6::Zero();
}

namespace {
/// τ(θ) by the frame recursion (fast_equilibrium.hpp); data is left a natural-coordinate state
/// at θ with data.tau = τ.
void torquesAt(const Model& model, Data& data, const Vec6& theta, const Loads& loads, Vec6& tau,
               StaticLoadSums& sums) {
  chainFrames(model, data, theta);
  staticTorquesFromFrames(model, data, loads, tau, sums);
}

/// LU of ∂G/∂θ = I + K_eff⁻¹ ∂τ/∂θ without pivoting (Doolittle, in place): the matrix is the
/// identity plus a small compliance term on industrial robots, so the pivots stay near 1. When a
/// pivot falls below 0.25 (a very soft joint), partial pivoting (Eigen) takes over.
class EquilibriumLu {
 public:
  void compute(const Mat6& A) {
    lu_ = A;
    pivoted_ = false;
    for (int k = 0; k < 6; ++k) {
      const double pk = lu_(k, k);
      if (!(std::abs(pk) >= 0.25)) {
        pivoted_ = true;
        plu_.compute(A);
        return;
      }
      inv_pivot_[k] = 1.0 / pk;
      for (int i = k + 1; i < 6; ++i) {
        const double l = lu_(i, k) * inv_pivot_[k];
        lu_(i, k) = l;
        for (int j = k + 1; j < 6; ++j) lu_(i, j) -= l * lu_(k, j);
      }
    }
  }
  [[nodiscard]] Vec6 solve(const Vec6& b) const {
    if (pivoted_) return plu_.solve(b);
    Vec6 x = b;
    for (int i = 1; i < 6; ++i) {
      for (int j = 0; j < i; ++j) x[i] -= lu_(i, j) * x[j];
    }
    for (int i = 5; i >= 0; --i) {
      for (int j = i + 1; j < 6; ++j) x[i] -= lu_(i, j) * x[j];
      x[i] *= inv_pivot_[i];
    }
    return x;
  }

 private:
  Mat6 lu_;
  Vec6 inv_pivot_;
  bool pivoted_{false};
  Eigen::PartialPivLU<Mat6> plu_;
};

/// Leaves data as after solvePosition at data.frames, with the torques τ.
void finishState(const Model& model, Data& data, const Vec6& tau) {
  syncNaturalCoordinates(model, data);
  data.tau = tau;
  data.qd.setZero();
  data.qdd.setZero();
}
}  // namespace

Mat6 torqueSensitivity(const Model& model, Data& data, const Vec6& theta, const Loads& loads) {
  Vec6 tau;
  StaticLoadSums sums;
  torquesAt(model, data, theta, loads, tau, sums);
  Mat6 D;
  staticSensitivity(model, data, sums, D);
  finishState(model, data, tau);
  return D;
}

Deflection predictDeflection(const Model& model, Data& data, const JointCompliance& c,
                             const Vec6& theta_m, const Loads& loads, const DeflectionOptions& opt,
                             const Vec6& command_offset) {
  Deflection d;
  d.theta_m = theta_m;
  const Vec6 cmd = theta_m + command_offset;
  if (!cmd.allFinite() || !theta_m.allFinite()) {
    d.position_converged = false;
    return d;
  }
  Vec6 kinv;  // 1/k_eff
  for (int i = 0; i < 6; ++i) kinv[i] = 1.0 / c.k[i] + 1.0 / c.k_servo[i];
  // nominal (rigid) TCP
  JointTrig trig = jointTrig(theta_m);
  chainFrames(model, data, theta_m, trig);
  d.T_nominal.linear() = data.frames.R_tcp;
  d.T_nominal.translation() = data.frames.p_tcp;

  // Newton on G(θ) = θ − θ_cmd + K_eff⁻¹ τ(θ) = 0 with ∂G/∂θ = I + K_eff⁻¹ ∂τ/∂θ (analytic);
  // the joints' sin/cos follow the small steps by angle addition (shiftTrig)
  Vec6 theta = cmd;
  Vec6 trig_at = theta_m;  // the configuration `trig` belongs to
  Vec6 tau;
  StaticLoadSums sums;
  Mat6 D;
  EquilibriumLu lu;
  bool have_jacobian = false;
  double prev = std::numeric_limits<double>::infinity();
  const bool at_nominal = command_offset.isZero(0.0);  // the frames already belong to θ_m
  for (d.iterations = 0; d.iterations < opt.max_iterations; ++d.iterations) {
    if (d.iterations > 0 || !at_nominal) {
      shiftTrig(trig, trig_at, theta);
      trig_at = theta;
      chainFrames(model, data, theta, trig);
    }
    staticTorquesFromFrames(model, data, loads, tau, sums);
    const Vec6 G = theta - cmd + tau.cwiseProduct(kinv);
    d.residual = G.lpNorm<Eigen::Infinity>();
    if (!std::isfinite(d.residual)) break;
    if (d.residual <= opt.tol) {
      d.converged = true;
      break;
    }
    // ∂G/∂θ is re-formed only when the previous step contracted poorly: it changes by O(Δθ)
    // relative, so one factorisation usually serves every step (simplified Newton)
    if (!have_jacobian || d.residual > 1e-3 * prev) {
      staticSensitivity(model, data, sums, D);
      Mat6 Jg = kinv.asDiagonal() * D;
      Jg.diagonal().array() += 1.0;
      lu.compute(Jg);
      have_jacobian = true;
    }
    prev = d.residual;
    theta -= lu.solve(G);
  }
  // State at the final θ (torques and poses consistent with the reported angles): after
  // convergence the frames and τ already belong to θ; otherwise evaluate once more.
  if (!d.converged) {
    if (!theta.allFinite()) {
      d.position_converged = false;
      return d;
    }
    torquesAt(model, data, theta, loads, tau, sums);
  }
  if (opt.natural_state) {
    finishState(model, data, tau);
  } else {
    data.tau = tau;
  }
  d.theta = theta;
  d.tau = tau;
  d.phi = -tau.cwiseQuotient(c.k);
  d.dpsi = -tau.cwiseQuotient(c.k_servo);
  d.T_real.linear() = data.frames.R_tcp;
  d.T_real.translation() = data.frames.p_tcp;
  d.dp = d.T_real.translation() - d.T_nominal.translation();
  d.drot = smallRotationDifference(d.T_real.linear(), d.T_nominal.linear());
  return d;
}

void referToControllerPose(Deflection& d, const Pose& T_controller) {
  d.T_nominal = T_controller;
  d.dp = d.T_real.translation() - d.T_nominal.translation();
  d.drot = smallRotationDifference(d.T_real.linear(), d.T_nominal.linear());
}

Vec6 compensateCommand(const Model& model, Data& data, const JointCompliance& c,
                       const Vec6& theta_d, const Loads& loads) {
  Vec6 tau;
  StaticLoadSums sums;
  torquesAt(model, data, theta_d, loads, tau, sums);
  finishState(model, data, tau);
  return theta_d + tau.cwiseQuotient(c.effective());
}

}  // namespace roprec::nc
