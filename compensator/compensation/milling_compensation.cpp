#include "compensator/compensation/milling_compensation.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>

#include "compensator/process/milling_consistent.hpp"
#include "compensator/process/milling_mode_coupling.hpp"
#include "compensator/process/milling_robot.hpp"
#include "compensator/process/milling_stability.hpp"
#include "compensator/support/c_format.hpp"

namespace roprec {

namespace {
/// milling frame (X feed = tool x, Z = −tool z, Y = −tool y) ↔ tool frame
Vec3 millToTool(const Vec3& v) { return Vec3(v.x(), -v.y(), -v.z()); }

std::string fmt(double v, int decimals) { return cFixed(v, decimals); }
std::string mm(double v_m) { return fmt(v_m * 1e3, 3); }

/// The last chatter check along the path: reused while the robot's modes stay within
/// kModeReuseTolerance of those it was computed with (they change slowly along a path; the limit
/// moves about as much as the modes do).
struct StabilityCache {
  ModalModel modes;
  StabilityLimit limit;
  bool valid{false};
};
constexpr double kModeReuseTolerance = 0.005;

bool sameModes(const ModalModel& a, const ModalModel& b) {
  if (a.modes.size() != b.modes.size()) return false;
  for (size_t r = 0; r < a.modes.size(); ++r) {
    const VibrationMode& x = a.modes[r];
    const VibrationMode& y = b.modes[r];
    if (std::abs(x.omega - y.omega) > kModeReuseTolerance * y.omega) return false;
    // the mode's TCP vector up to its sign
    const double d = std::min((x.tcp - y.tcp).norm(), (x.tcp + y.tcp).norm());
    if (d > kModeReuseTolerance * y.tcp.norm()) return false;
  }
  return true;
}

/// The cell's model with the engagement's ae and ap (the slices and helix lags follow ap).
MillingModel engagedModel(const MillingModel& cell, const MillingEngagement& e) {
  MillingCut cut = cell.cut;
  cut.ae = e.ae;
  cut.ap = e.ap;
  MillingModel m = makeMillingModel(cell.tool, cut, cell.coeff, cell.angle_steps, cell.slices);
  m.mean_law = cell.mean_law;
  return m;
}

/// The robot's modes at θ_d and the spindle/tool mode; none when the pose has no modes.
std::optional<ModalModel> pointModes(const PredictionModel& m, PathPointCompensation& p) {
  const MillingSpec& s = m.process.milling;
  ModalModel dyn;
  try {
    dyn = robotModes(m.model, m.compliance, p.theta_d, s.robot_damping_ratio);
  } catch (const std::runtime_error&) {
    return std::nullopt;  // no modes at this pose: not checked
  }
  if (!dyn.modes.empty()) p.first_mode_hz = dyn.modes.front().omega / (2 * kPi);
  addToolMode(dyn, s.tool_mode);
  return dyn;
}

/// The last resolved revolution along the path and the cut and modes it was computed with.
struct EdgeCache {
  ModalModel modes;
  double fz{0}, ae{0}, ap{0};
  EdgeRevolution nominal, corrected;
  bool valid{false};
};

/// The revolution resolved by edge angle at the cut (fz, ae, ap) with the modes `dyn`: the
/// cached one while the modes and the cut are those it was computed with.
const EdgeRevolution& edgesAt(const MillingModel& mm, const ModalModel& dyn, double fz, double ae,
                              double ap, EdgeCache& cache) {
  const bool same = cache.valid && sameModes(dyn, cache.modes) &&
                    std::abs(fz - cache.fz) <= kEdgeReuseTolerance &&
                    std::abs(ae - cache.ae) <= kEdgeReuseTolerance &&
                    std::abs(ap - cache.ap) <= kEdgeReuseTolerance;
  if (!same) {
    if (!cache.valid)
      cache.nominal = edgeRevolution(mm, ModalModel{}, mm.cut.fz, mm.cut.ae, mm.cut.ap);
    cache.corrected = edgeRevolution(mm, dyn, fz, ae, ap);
    cache.modes = dyn;
    cache.fz = fz;
    cache.ae = ae;
    cache.ap = ap;
    cache.valid = true;
  }
  return cache.corrected;
}

/// The coupled solve of a cutting point: with the point's modes, consistent with its resolved
/// revolution (milling.hpp coupleMillingPointConsistent, started from the previous point's force
/// correction); without modes the plain mean-force law.
CouplingResult solvePoint(const MillingModel& mm, const ComplianceFunction& C,
                          const std::optional<ModalModel>& dyn, const CouplingState& state,
                          const CouplingOptions& o, EdgeCache& cache, Vec3& correction) {
  if (!dyn) return coupleMillingPoint(mm, C, state, o);
  const EdgeRevolutionFunction edges = [&](double fz, double ae, double ap) {
    return edgesAt(mm, *dyn, fz, ae, ap, cache);
  };
  ConsistentCoupling cc = coupleMillingPointConsistent(mm, C, edges, state, o, correction);
  correction = cc.correction;
  if (cc.point.converged && !cc.consistent) {
    cc.point.converged = false;
    cc.point.status = CouplingStatus::kMaxIterations;
  }
  if (cc.consistent) cc.point.residual = cc.edge_residual;
  return cc.point;
}

/// The wall's normal into the material in the base frame (milling frame ±Y: up +Y, down −Y; none
/// for a slot, which has a wall on each side) at the path point's orientation R.
Vec3 wallNormalIn(const Mat3& R, MillingMode mode) {
  if (mode == MillingMode::kSlot) return Vec3::Zero();
  return R * millToTool(mode == MillingMode::kUp ? Vec3::UnitY() : Vec3(-Vec3::UnitY()));
}

/// The coupling options at path point i: the tooth passes since the previous point from the
/// program's spacing, |p_i − p_{i−1}| / fz (at least 1); the cell's for the first point.
CouplingOptions optionsAt(const CouplingOptions& cell, const std::vector<Pose>& points, size_t i,
                          double fz) {
  CouplingOptions o = cell;
  if (i > 0 && fz > 0) {
    const double spacing = (points[i].translation() - points[i - 1].translation()).norm();
    o.teeth_between_points = std::max(1, static_cast<int>(std::lround(spacing / fz)));
  }
  return o;
}

/// The revolution resolved by edge angle at the point's coupled cut into `p`.
void resolveEdges(const MillingModel& mm, const ModalModel& dyn, const CouplingResult& c,
                  EdgeCache& cache, PathPointCompensation& p) {
  const EdgeRevolution& r = edgesAt(mm, dyn, c.fz_effective, c.ae_effective, c.ap_effective, cache);
  p.edges_checked = true;
  p.edges_converged = r.converged;
  p.tooth_feed = r.tooth_feed;
  p.peak_xy_nominal = cache.nominal.peak_xy;
  p.peak_xy = r.peak_xy;
  Vec3 lo = Vec3::Constant(1e300);
  Vec3 hi = Vec3::Constant(-1e300);
  for (const Vec3& x : r.vibration) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  p.vibration_pp = r.vibration.empty() ? Vec3::Zero() : Vec3(hi - lo);
}

/// The zero-order stability limit with the modes `dyn` into `p`.
void checkStability(const ModalModel& dyn, const StabilityCut& cut, double spindle_rpm,
                    StabilityCache& cache, PathPointCompensation& p) {
  if (!cache.valid || !sameModes(dyn, cache.modes)) {
    cache.limit = limitingDepth(dyn, cut, spindle_rpm);
    cache.modes = dyn;
    cache.valid = true;
  }
  p.stability_checked = true;
  p.stability_bounded = cache.limit.bounded;
  p.ap_limit = cache.limit.ap_lim;
  p.chatter_hz = cache.limit.chatter_hz;
}

/// The last mode-coupling check along the path, reused as the stability's (same modes, same cut).
struct ModeCouplingCache {
  ModalModel modes;
  ModeCouplingLimit limit;
  bool valid{false};
};

/// The mode-coupling limit of the point's cut (the engagement's fz, ae, ap) with the modes `dyn`
/// into `p`.
void checkModeCoupling(const MillingModel& mm, const ModalModel& dyn, ModeCouplingCache& cache,
                       PathPointCompensation& p) {
  if (!cache.valid || !sameModes(dyn, cache.modes)) {
    const ProcessGradient g = processGradient(mm, mm.cut.fz, mm.cut.ae, mm.cut.ap);
    cache.limit = modeCouplingLimit(dyn, g, mm.cut.ap);
    cache.modes = dyn;
    cache.valid = true;
  }
  p.mode_coupling_checked = true;
  p.mode_coupling_bounded = cache.limit.bounded;
  p.mode_coupling_ap_limit = cache.limit.ap_lim;
  p.mode_coupling_hz = cache.limit.frequency_hz;
  p.mode_coupling_flutter = cache.limit.flutter;
}

/// The command the controller's IK gives for the path point T_W_tcp (the link angles θ_d of the
/// real robot seed it): θ_d itself without a calibration (nominal = real).
Vec6 uncompensatedCommand(const PredictionModel& m, const Pose& T_W_tcp, const Vec6& theta_d) {
  if (!m.calibrated) return theta_d;
  const nc::Model& n = controllerModel(m);
  const IkNearResult ik =
      solveIkNear(m.ik, T_W_tcp * n.T_L6_tcp.inverse() * n.T_L6_flange, theta_d);
  return ik.converged ? ik.q : theta_d;
}

CuttingDecision decision(bool cutting, std::string reason,
                         std::optional<MillingEngagement> engagement = std::nullopt) {
  CuttingDecision c;
  c.cutting = cutting;
  c.reason = std::move(reason);
  c.engagement = engagement;
  return c;
}

/// The decision of a non-rapid move a → b with a box stock (milling_engagement.hpp).
CuttingDecision engagedDecision(EngagementTracker& tracker, const std::optional<Vec3>& a,
                                const Vec3& b) {
  CuttingDecision c;
  if (!a) {
    c = decision(false, "first point of a feed chain: no move into it (box stock)", std::nullopt);
    return c;
  }
  const MillingEngagement e = tracker.cut(*a, b);
  if (!e.cuts()) {
    c = decision(false, "the move engages no material (box stock and the earlier passes)", e);
    return c;
  }
  c = decision(
      true,
      "engaged: ae " + mm(e.ae) + " mm, ap " + mm(e.ap) + " mm (box stock and the earlier passes)",
      e);
  return c;
}

}  // namespace

std::vector<CuttingDecision> decideCutting(const MillingSpec& s, const Pose& T_W_wobj,
                                           const std::vector<MillingPathPoint>& points) {
  const double vf = s.cut.fz * s.tool.teeth * s.cut.spindle_rpm / 60.0;  // m/s
  const double v_max = kRapidSpeedFactor * vf;
  const Pose T_wobj_W = T_W_wobj.inverse();
  std::optional<double> z_ref;  // tool height at the first non-rapid point (no <stock>)
  std::optional<EngagementTracker> tracker;  // a box stock: the engagement of every move
  if (s.stock_box_min && s.stock_box_max) {
    StockShape stock;
    stock.top_z = s.stock_box_max->z();
    stock.box_min = s.stock_box_min;
    stock.box_max = s.stock_box_max;
    tracker.emplace(stock, s.tool.diameter);
  }
  std::optional<Vec3> prev_tip;
  std::vector<CuttingDecision> out(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const MillingPathPoint& p = points[i];
    CuttingDecision& c = out[i];
    const Vec3 tip = (T_wobj_W * p.T_W_tcp).translation();
    const double z = tip.z();
    if (p.speed > v_max) {
      prev_tip.reset();  // a rapid move removes nothing (and breaks the chain of moves)
      c = decision(false, "rapid: programmed " + fmt(p.speed * 1e3, 1) + " mm/s > " +
                              fmt(kRapidSpeedFactor, 2) + " x feed speed " + fmt(vf * 1e3, 1) +
                              " mm/s");
      continue;
    }
    if (tracker) {
      c = engagedDecision(*tracker, prev_tip, tip);
      prev_tip = tip;
      continue;
    }
    if (s.stock_top_z) {
      const double depth = *s.stock_top_z - z;
      if (depth >= s.cut.ap - kDepthTolerance) {
        c = decision(true, "feed move at depth " + mm(depth) + " mm below the stock top (ap " +
                               mm(s.cut.ap) + " mm)");
      } else {
        c = decision(false, depth <= 0 ? "above the stock top by " + mm(-depth) + " mm"
                                       : "depth " + mm(depth) + " mm < ap " + mm(s.cut.ap) +
                                             " mm: not at the cutting depth");
      }
      continue;
    }
    if (!z_ref) z_ref = z;
    if (std::abs(z - *z_ref) <= kDepthTolerance) {
      c = decision(true, "feed move at the depth of the first feed move");
    } else {
      c = decision(false, "tool " + mm(z - *z_ref) + " mm from the depth of the first feed move");
    }
  }
  return out;
}

std::vector<PathPointCompensation> compensateMillingPath(
    const PredictionModel& m, const std::vector<Pose>& points,
    const std::vector<CuttingDecision>* cutting, const Vec6* seed) {
  if (!m.has_process || m.process.type != ProcessType::kMilling) {
    throw std::invalid_argument("compensateMillingPath needs a milling process");
  }
  const MillingModel mm = millingModelOf(m.process.milling);
  const StabilityCut stability_cut = stabilityCutOf(mm);
  const Mat3 C_tool = toolStaticCompliance(m.process.milling.tool_mode);
  StabilityCache stability_cache;
  ModeCouplingCache mode_coupling_cache;
  EdgeCache edge_cache;
  EdgeCache after_edge_cache;             // the compensated cut's revolution (the "after" solve)
  Vec3 before_correction = Vec3::Zero();  // ΔF of the consistent solves, carried point to point
  Vec3 after_correction = Vec3::Zero();
  // the cut at the point: the cell's, or the engagement's ae/ap (box stock), with its stability
  // cut and nominal force; rebuilt (and the caches dropped) when the engagement changes
  MillingModel pm = mm;
  StabilityCut pm_stability = stability_cut;
  Vec3 F_nom = millingMeanForce(mm, mm.cut.fz, mm.cut.ae);
  CouplingOptions copt = m.process.milling.coupling;
  PredictionData d(m);
  std::vector<PathPointCompensation> out(points.size());
  std::optional<Vec6> prev;
  if (seed != nullptr) prev = *seed;
  CouplingState before_state;  // the uncompensated path's memory (for the "before" deviation)
  CouplingState after_state;
  for (size_t i = 0; i < points.size(); ++i) {
    PathPointCompensation& p = out[i];
    if (cutting != nullptr && i < cutting->size()) {
      const CuttingDecision& cd = (*cutting)[i];
      p.cutting = cd.cutting;
      p.cutting_reason = cd.reason;
      if (cd.cutting && cd.engagement &&
          (cd.engagement->ae != pm.cut.ae || cd.engagement->ap != pm.cut.ap)) {
        pm = engagedModel(mm, *cd.engagement);
        pm_stability = stabilityCutOf(pm);
        F_nom = millingMeanForce(pm, pm.cut.fz, pm.cut.ae);
        stability_cache.valid = false;
        mode_coupling_cache.valid = false;
        edge_cache.valid = false;
        after_edge_cache.valid = false;
      }
    }
    p.ae = pm.cut.ae;
    p.ap = pm.cut.ap;
    // 1. IK of the real robot with continuity (realIk: FK_real(θ_d) = the path point)
    const Pose T_flange = points[i] * m.model.T_L6_tcp.inverse() * m.model.T_L6_flange;
    const Vec6 start = prev ? *prev : m.reference_pose;
    IkOptions opt;
    opt.seed = &start;
    solveIk(realIk(m), T_flange, opt, d.ik);
    double best = 1e300;
    bool found = false;
    for (int k = 0; k < d.ik.count; ++k) {
      const IkSolution& s = d.ik.solutions[static_cast<size_t>(k)];
      if (!s.converged || !s.within_limits || s.singular_wrist || s.singular_shoulder) continue;
      const double dist = (s.q - start).squaredNorm();
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
    // the spindle/tool's own deflection under F, base frame (it adds to the robot's)
    auto toolBending = [&](const Vec3& F_mill) -> Vec3 { return R * millToTool(C_tool * F_mill); };
    // uncompensated: the robot at θ_d under the coupled force
    Vec3 F_before = Vec3::Zero();
    std::optional<ModalModel> dyn;
    const CouplingOptions copt_i = optionsAt(copt, points, i, pm.cut.fz);
    p.teeth_between_points = copt_i.teeth_between_points;
    if (p.cutting) {
      dyn = pointModes(m, p);
      const CouplingResult cb = solvePoint(
          pm,
          withToolCompliance(robotMillingCompliance(m.model, m.compliance, p.theta_d, m.gravity),
                             C_tool),
          dyn, before_state, copt_i, edge_cache, before_correction);
      p.before_fz_effective = cb.fz_effective;
      before_state = cb.next;
      F_before = cb.force;
      p.before_status = couplingStatusName(cb.status);
      p.before_iterations = cb.iterations;
      p.before_residual = cb.residual;
      p.before_loop_gain = cb.loop_gain;
      p.before_force = cb.force;
      if (dyn) {
        checkStability(*dyn, pm_stability, m.process.milling.cut.spindle_rpm, stability_cache, p);
        checkModeCoupling(pm, *dyn, mode_coupling_cache, p);
        resolveEdges(pm, *dyn, cb, edge_cache, p);
      }
    } else {
      before_state = CouplingState{};  // the tool left the material
      p.before_status = "not_cutting";
    }
    {
      // the uncompensated command: the controller's IK of the path point (θ_d without a
      // calibration), its deviation from the path point
      const Vec6 q_before = uncompensatedCommand(m, points[i], p.theta_d);
      nc::Deflection db =
          nc::predictDeflection(m.model, d.nc, m.compliance, q_before, loadsWith(F_before), {},
                                controllerOffset(m, d.nc, q_before));
      if (m.calibrated) nc::referToControllerPose(db, controllerTcp(m, q_before));
      p.deviation_before = db.dp + toolBending(F_before);
      if (p.cutting) p.surface_error_before = p.deviation_before.dot(wallNormalIn(R, pm.cut.mode));
    }
    // the link-side target that pre-offsets the tool's bending: θ_d + J⁻¹ [−bending; 0]
    nc::forwardKinematics(m.model, d.nc, p.theta_d);
    const Eigen::ColPivHouseholderQR<Mat6> J_qr(nc::tcpJacobian(m.model, d.nc));
    auto targetFor = [&](const Vec3& G) -> Vec6 {
      if (G.isZero() || J_qr.rank() < 6) return p.theta_d;
      Vec6 twist = Vec6::Zero();
      twist.head<3>() = -toolBending(G);
      return p.theta_d + J_qr.solve(twist);
    };
    // the controller command that puts the link side at θ_d under force G (exact inverse; a
    // gravity-compensating controller adds its own offset: θ_cmd + off(θ_cmd) = θ_m)
    auto commandFor = [&](const Vec3& G) {
      const Vec6 theta_m =
          nc::compensateCommand(m.model, d.nc, m.compliance, targetFor(G), loadsWith(G));
      Vec6 cmd = theta_m;
      for (int it = 0; it < 20 && m.controller.kind != nc::ControllerReference::Kind::kNone; ++it)
        cmd = theta_m - controllerOffset(m, d.nc, cmd);
      return cmd;
    };
    // 2. force fixed point with the exact inverse (no force at a point that does not cut)
    Vec3 F = p.cutting ? F_nom : Vec3::Zero();
    bool conv = !p.cutting;
    CouplingResult ca;
    ca.converged = true;
    ca.status = CouplingStatus::kConverged;
    for (p.force_iterations = 1; p.cutting && p.force_iterations <= 20; ++p.force_iterations) {
      p.theta_cmd = commandFor(F);
      // the compensated robot's deviation from the nominal tool position under a force G (milling
      // frame)
      const ComplianceFunction residualCompliance = [&](const Vec3& G) -> Vec3 {
        const nc::Deflection dg =
            nc::predictDeflection(m.model, d.nc, m.compliance, p.theta_cmd, loadsWith(G), {},
                                  controllerOffset(m, d.nc, p.theta_cmd));
        if (!dg.converged) throw std::runtime_error("the compliance equilibrium did not converge");
        return millToTool(R.transpose() * (dg.T_real.translation() - points[i].translation())) +
               C_tool * G;
      };
      ca = solvePoint(pm, residualCompliance, dyn, after_state, copt_i, after_edge_cache,
                      after_correction);
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
    p.coupling_status = p.cutting ? couplingStatusName(ca.status) : "not_cutting";
    p.coupling_residual = ca.residual;
    p.loop_gain = ca.loop_gain;
    if (!p.cutting) p.force_iterations = 0;
    p.force = F;
    if (!conv) {
      p.reason = ca.converged ? "the force fixed point did not converge"
                              : std::string("the coupled milling iteration did not converge (") +
                                    couplingStatusName(ca.status) + ")";
      continue;
    }
    after_state = p.cutting ? ca.next : CouplingState{};
    p.theta_cmd = commandFor(F);
    if (!withinLimits(m.ik, p.theta_cmd)) {
      p.reason = "the compensated command leaves the joint limits";
      continue;
    }
    nc::forwardKinematics(controllerModel(m), d.nc, p.theta_cmd);  // FK_nom: what is programmed
    p.T_programmed = d.nc.T_W_tcp;
    const nc::Deflection da =
        nc::predictDeflection(m.model, d.nc, m.compliance, p.theta_cmd, loadsWith(F), {},
                              controllerOffset(m, d.nc, p.theta_cmd));
    p.residual = da.T_real.translation() + toolBending(F) - points[i].translation();
    if (p.cutting) p.surface_error = p.residual.dot(wallNormalIn(R, pm.cut.mode));
    p.config_text =
        formatConfig(configurationOf(m.ik, m.robot.card, p.theta_cmd, m.config_options));
    p.ok = da.converged;
    if (!p.ok) p.reason = "the compliance equilibrium did not converge at the compensated command";
  }
  return out;
}

}  // namespace roprec
