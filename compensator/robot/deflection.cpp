#include "compensator/robot/deflection.hpp"

#include <cmath>
#include <cstdio>
#include <string>

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
  solvePosition(calibration_model, data, theta, Guess::kClosedForm);
  const Loads gravity_only;
  return staticTorques(calibration_model, data, gravity_only).cwiseQuotient(c.effective());
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
/// τ(θ): position problem + static torques. The closed-form recursion is exact, so Newton only
/// verifies it (cheaper than a warm-started Newton step). Returns false if it did not converge.
bool torquesAt(const Model& model, Data& data, const Vec6& theta, const Loads& loads, Vec6& tau) {
  if (!solvePosition(model, data, theta, Guess::kClosedForm).converged) return false;
  tau = staticTorques(model, data, loads);
  return true;
}
}  // namespace

Mat6 torqueSensitivity(const Model& model, Data& data, const Vec6& theta, const Loads& loads) {
  Mat6 D;
  const double h = 1e-6;
  Vec6 tp;
  Vec6 tm;
  for (int j = 0; j < 6; ++j) {
    Vec6 th = theta;
    th[j] += h;
    torquesAt(model, data, th, loads, tp);
    th[j] -= 2 * h;
    torquesAt(model, data, th, loads, tm);
    D.col(j) = (tp - tm) / (2 * h);
  }
  return D;
}

Deflection predictDeflection(const Model& model, Data& data, const JointCompliance& c,
                             const Vec6& theta_m, const Loads& loads, const DeflectionOptions& opt,
                             const Vec6& command_offset) {
  Deflection d;
  d.theta_m = theta_m;
  const Vec6 keff = c.effective();
  const Vec6 cmd = theta_m + command_offset;
  // nominal (rigid) TCP
  if (!solvePosition(model, data, theta_m, Guess::kClosedForm).converged) {
    d.position_converged = false;
    return d;
  }
  framePoses(model, data);
  d.T_nominal = data.T_W_tcp;

  Vec6 theta = cmd;
  Vec6 tau;
  double prev = std::numeric_limits<double>::infinity();
  bool newton = false;
  const bool at_nominal = command_offset.isZero(0.0);  // data already holds the position at θ_m
  for (d.iterations = 0; d.iterations < opt.max_iterations; ++d.iterations) {
    if (d.iterations == 0 && at_nominal) {
      tau = staticTorques(model, data, loads);
    } else if (!torquesAt(model, data, theta, loads, tau)) {
      d.position_converged = false;
      return d;
    }
    const Vec6 G = theta - cmd + tau.cwiseQuotient(keff);
    d.residual = G.lpNorm<Eigen::Infinity>();
    if (!std::isfinite(d.residual)) break;
    if (d.residual <= opt.tol) {
      d.converged = true;
      break;
    }
    if (!newton && d.iterations > 3 && d.residual > 0.5 * prev) newton = true;  // slow contraction
    prev = d.residual;
    if (newton) {
      const Mat6 D = torqueSensitivity(model, data, theta, loads);
      Mat6 Jg = Mat6::Identity();
      for (int i = 0; i < 6; ++i) Jg.row(i) += D.row(i) / keff[i];
      theta -= Jg.partialPivLu().solve(G);
    } else {
      theta = cmd - tau.cwiseQuotient(keff);
    }
  }
  // State at the final θ (torques and poses consistent with the reported angles): after
  // convergence data and τ already belong to θ; otherwise evaluate once more.
  if (!d.converged && !torquesAt(model, data, theta, loads, tau)) {
    d.position_converged = false;
    return d;
  }
  framePoses(model, data);
  d.theta = theta;
  d.tau = tau;
  d.phi = -tau.cwiseQuotient(c.k);
  d.dpsi = -tau.cwiseQuotient(c.k_servo);
  d.T_real = data.T_W_tcp;
  d.dp = d.T_real.translation() - d.T_nominal.translation();
  d.drot = smallRotationDifference(d.T_real.linear(), d.T_nominal.linear());
  return d;
}

Vec6 compensateCommand(const Model& model, Data& data, const JointCompliance& c,
                       const Vec6& theta_d, const Loads& loads) {
  Vec6 tau;
  torquesAt(model, data, theta_d, loads, tau);
  return theta_d + tau.cwiseQuotient(c.effective());
}

}  // namespace roprec::nc
