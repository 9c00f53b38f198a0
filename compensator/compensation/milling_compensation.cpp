#include "compensator/compensation/milling_compensation.hpp"

#include <cmath>
#include <stdexcept>

#include "compensator/process/milling_robot.hpp"

namespace roprec {

namespace {
/// milling frame (X feed = tool x, Z = −tool z, Y = −tool y) ↔ tool frame
Vec3 millToTool(const Vec3& v) { return Vec3(v.x(), -v.y(), -v.z()); }
}  // namespace

std::vector<PathPointCompensation> compensateMillingPath(const PredictionModel& m,
                                                         const std::vector<Pose>& points) {
  if (!m.has_process || m.process.type != ProcessType::kMilling) {
    throw std::invalid_argument("compensateMillingPath needs a milling process");
  }
  const MillingModel mm = millingModelOf(m.process.milling);
  const Vec3 F_nom = millingMeanForce(mm, m.process.milling.cut.fz, m.process.milling.cut.ae);
  CouplingOptions copt = m.process.milling.coupling;
  PredictionData d(m);
  std::vector<PathPointCompensation> out(points.size());
  std::optional<Vec6> prev;
  CouplingState before_state;  // the uncompensated path's memory (for the "before" deviation)
  CouplingState after_state;
  for (size_t i = 0; i < points.size(); ++i) {
    PathPointCompensation& p = out[i];
    // 1. IK with continuity
    const Pose T_flange = points[i] * m.model.T_L6_tcp.inverse() * m.model.T_L6_flange;
    const Vec6 seed = prev ? *prev : m.reference_pose;
    IkOptions opt;
    opt.seed = &seed;
    solveIk(m.ik, T_flange, opt, d.ik);
    double best = 1e300;
    bool found = false;
    for (int k = 0; k < d.ik.count; ++k) {
      const IkSolution& s = d.ik.solutions[static_cast<size_t>(k)];
      if (!s.converged || !s.within_limits || s.singular_wrist || s.singular_shoulder) continue;
      const double dist = (s.q - seed).squaredNorm();
      if (dist < best) {
        best = dist;
        p.theta_d = s.q;
        found = true;
      }
    }
    if (!found) {
      p.reason = d.ik.count == 0 ? describeIkFailure(d.ik)
                                 : "no admissible IK solution (limits, singularity)";
      continue;
    }
    prev = p.theta_d;
    const Mat3 R = points[i].linear();
    auto loadsWith = [&](const Vec3& F_mill) {
      nc::Loads l;
      l.gravity = m.gravity;
      l.tcp_tool.force = millToTool(F_mill);
      return l;
    };
    // uncompensated: the robot at θ_d under the coupled force
    const CouplingResult cb =
        coupleMillingPoint(mm, robotMillingCompliance(m.model, m.compliance, p.theta_d, m.gravity),
                           before_state, copt);
    before_state = cb.next;
    {
      const nc::Deflection db =
          nc::predictDeflection(m.model, d.nc, m.compliance, p.theta_d, loadsWith(cb.force), {},
                                controllerOffset(m, d.nc, p.theta_d));
      p.deviation_before = db.dp;
    }
    // the controller command that puts the link side at θ_d under force G (exact inverse; a
    // gravity-compensating controller adds its own offset: θ_cmd + off(θ_cmd) = θ_m)
    auto commandFor = [&](const Vec3& G) {
      const Vec6 theta_m =
          nc::compensateCommand(m.model, d.nc, m.compliance, p.theta_d, loadsWith(G));
      Vec6 cmd = theta_m;
      for (int it = 0; it < 20 && m.controller.kind != nc::ControllerReference::Kind::kNone; ++it)
        cmd = theta_m - controllerOffset(m, d.nc, cmd);
      return cmd;
    };
    // 2. force fixed point with the exact inverse
    Vec3 F = F_nom;
    bool conv = false;
    CouplingResult ca;
    for (p.force_iterations = 1; p.force_iterations <= 20; ++p.force_iterations) {
      p.theta_cmd = commandFor(F);
      // the compensated robot's deviation from the nominal tool position under a force G (milling
      // frame)
      const ComplianceFunction residualCompliance = [&](const Vec3& G) -> Vec3 {
        const nc::Deflection dg =
            nc::predictDeflection(m.model, d.nc, m.compliance, p.theta_cmd, loadsWith(G), {},
                                  controllerOffset(m, d.nc, p.theta_cmd));
        if (!dg.converged) throw std::runtime_error("the compliance equilibrium did not converge");
        return millToTool(R.transpose() * (dg.T_real.translation() - points[i].translation()));
      };
      ca = coupleMillingPoint(mm, residualCompliance, after_state, copt);
      const double change = (ca.force - F).norm();
      F = ca.force;
      if (!ca.converged) break;
      if (change <= 1e-9) {
        conv = true;
        break;
      }
    }
    p.coupling_converged = ca.converged;
    p.coupling_iterations = ca.iterations;
    p.force = F;
    if (!conv) {
      p.reason = ca.converged ? "the force fixed point did not converge"
                              : std::string("the coupled milling iteration did not converge (") +
                                    couplingStatusName(ca.status) + ")";
      continue;
    }
    after_state = ca.next;
    p.theta_cmd = commandFor(F);
    if (!withinLimits(m.ik, p.theta_cmd)) {
      p.reason = "the compensated command leaves the joint limits";
      continue;
    }
    nc::forwardKinematics(m.model, d.nc, p.theta_cmd);
    p.T_programmed = d.nc.T_W_tcp;
    const nc::Deflection da =
        nc::predictDeflection(m.model, d.nc, m.compliance, p.theta_cmd, loadsWith(F), {},
                              controllerOffset(m, d.nc, p.theta_cmd));
    p.residual = da.T_real.translation() - points[i].translation();
    p.config_text =
        formatConfig(configurationOf(m.ik, m.robot.card, p.theta_cmd, m.config_options));
    p.ok = da.converged;
    if (!p.ok) p.reason = "the compliance equilibrium did not converge at the compensated command";
  }
  return out;
}

}  // namespace roprec
