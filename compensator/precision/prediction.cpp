#include "compensator/precision/prediction.hpp"

#include <mutex>
#include <set>

#include "compensator/robot/calibration_jacobian.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "compensator/precision/parallel.hpp"
#include "compensator/precision/uncertainty.hpp"
#include "compensator/robot/fast_equilibrium.hpp"
#include "compensator/support/error.hpp"

namespace roprec {

UncertaintyInputs defaultUncertaintyInputs() {
  UncertaintyInputs u;
  u.source =
      "stiffness 10 % per joint (identification residuals; docs/process.md §5.6: deflection-model "
      "error "
      "10-20 % "
      "of the predicted deflection [L]); servo stiffness 20 % (estimate: vendors publish no "
      "gains); "
      "process force scale rectangular ±15 % (docs/process.md §5.6: kc scatter ±10-15 % and the "
      "spread "
      "of "
      "coefficient sets, §4.2)";
  return u;
}

const char* verdictName(Verdict v) {
  switch (v) {
    case Verdict::kConforms:
      return "conforms";
    case Verdict::kConformsAfterCompensation:
      return "conforms-after-compensation";
    case Verdict::kNotCapable:
      return "not-capable";
    case Verdict::kUnreachable:
      return "unreachable";
    case Verdict::kSingular:
      return "singular";
    case Verdict::kNotConverged:
      return "not-converged";
  }
  return "?";
}

std::string verdictAndReason(Verdict v, const std::string& reason) {
  const std::string name = verdictName(v);
  if (reason.rfind(name + ":", 0) == 0 || reason == name) return reason;
  return reason.empty() ? name : name + ": " + reason;
}

Verdict verdictFor(double e, double U, double t) {
  const double half = 0.5 * t;
  if (U > half) return Verdict::kNotCapable;
  if (e + U > half) return Verdict::kConformsAfterCompensation;
  return Verdict::kConforms;
}

namespace {

long diameterKey(double d) { return std::lround(d * 1e6); }

/// The process of a hole of `diameter` drilled by drill `drill` of the tool table, with its
/// feed (m/rev) and speed (1/min) when > 0 (else the drill's <cut>).
ProcessAtDiameter processAt(const ProcessSpec& spec, double diameter, int drill = 0,
                            double feed = 0.0, double spindle_rpm = 0.0) {
  ProcessAtDiameter p;
  p.diameter = diameter;
  if (spec.type == ProcessType::kDrilling) {
    const DrillingSpec& own =
        spec.drills.empty() ? spec.drilling : spec.drills[static_cast<size_t>(drill)];
    const DrillingSpec s = holeDrilling(spec, drill, diameter, 0.0, feed, spindle_rpm);
    const DrillingModel dm = drillingModelOf(s);
    const DrillingForces F = drillingForces(dm, s.feed);
    ToolWrench w = toolWrench(F, 0.0);
    w.force.x() = 0.0;  // the rotating residual has zero mean
    w.force.y() = 0.0;
    p.wrench = w;
    p.rotating_force = F.residual;
    p.mach = machiningDeviation(s.deviation, s.geometry, F.residual);
    p.feed_rate = s.feed * s.spindle_rpm / 60.0;
    p.default_depth = s.hole_depth > 0 ? s.hole_depth : 2.0 * diameter;
    CuttingLength c = cuttingLengthAt(own, diameter);
    p.cutting_length = c.length;
    p.cutting_length_source = std::move(c.source);
  } else {
    const SteadyProcessLoad l = steadyProcessLoad(spec);
    p.wrench = l.wrench;
    DrillGeometry g;
    g.diameter = diameter > 0 ? diameter : 10e-3;
    const MachiningDeviationParams mp = defaultMachiningDeviation(g.diameter);
    g.runout = mp.runout;
    p.mach =
        machiningDeviation(mp, g, 0.0, Eigen::Vector2d(l.wrench.force.x(), l.wrench.force.y()));
    p.feed_rate = 0.0;
  }
  return p;
}

/// In-plane covariance (m², axes e1, e2) of the absolute-accuracy term at the real joint values θ
/// (AccuracyInputs): the data sheet's or the controller option's isotropic u², or the
/// calibration's covariance through ∂p_tcp/∂c (calibrationPositionCovariance), plus the
/// registration σ².
Eigen::Matrix2d accuracyCovariance(const PredictionModel& m, const Vec6& theta, const Vec3& e1,
                                   const Vec3& e2) {
  const AccuracyInputs& a = m.accuracy;
  double iso = a.registration_sigma * a.registration_sigma;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  if (a.kind == AccuracyInputs::Kind::kDataSheet ||
      a.kind == AccuracyInputs::Kind::kControllerOption) {
    iso += a.u * a.u;
  } else if (a.kind == AccuracyInputs::Kind::kCalibrated && m.robot.card.calibration) {
    Eigen::Matrix<double, 3, 2> E;
    E << e1, e2;
    cov = E.transpose() *
          calibrationPositionCovariance(m.robot.real_chain,
                                        m.model.T_L6_flange.inverse() * m.model.T_L6_tcp, theta,
                                        *m.robot.card.calibration) *
          E;
  }
  return cov + iso * Eigen::Matrix2d::Identity();
}

/// A process-lifetime copy of `text` (BudgetTerm::source must outlive every copy of the model and
/// of the predictions: predictions may be formatted after their model is gone). Thread-safe;
/// allocates only the first time a text is seen.
const char* internedText(const std::string& text) {
  static std::mutex mutex;
  static auto* texts = new std::set<std::string, std::less<>>();  // never freed: stable pointers
  const std::lock_guard<std::mutex> lock(mutex);
  return texts->insert(text).first->c_str();
}

bool hasAccuracyTerm(const AccuracyInputs& a) {
  return a.kind != AccuracyInputs::Kind::kNone || a.registration_sigma > 0;
}

}  // namespace

PredictionModel buildPredictionModel(const PredictionSetup& setup) {
  PredictionModel m;
  m.robot = setup.robot;
  m.model = nc::buildModel(setup.robot.real_chain, setup.tool);
  m.ik = buildIkModel(setup.robot);
  m.calibrated = setup.robot.card.calibration.has_value();
  if (m.calibrated) {
    m.nominal_model = nc::buildModel(setup.robot.chain, setup.tool);
    m.real_ik = buildRealIkModel(setup.robot);
  }
  m.compliance = nc::complianceFromCard(setup.robot.card);
  m.reference_pose = vendorReferencePose(setup.robot.card);
  m.controller = nc::makeControllerReference(setup.robot.real_chain, setup.robot.card, m.gravity,
                                             setup.controller_gravity, setup.calibration_load);
  m.uncertainty = setup.uncertainty;
  m.accuracy = setup.accuracy;
  m.capability = setup.capability;
  m.default_tolerance = setup.default_tolerance;
  if (setup.process) {
    m.has_process = true;
    m.process = *setup.process;
    std::vector<double> ds = setup.hole_diameters;
    if (m.process.type == ProcessType::kDrilling)
      ds.push_back(m.process.drilling.geometry.diameter);
    if (ds.empty()) ds.push_back(0.0);
    for (const double d : ds) {
      const long key = diameterKey(d);
      if (!m.process_by_diameter.count(key)) m.process_by_diameter[key] = processAt(m.process, d);
    }
    for (size_t i = 1; i < m.process.drills.size(); ++i) {
      HoleRequest h;
      h.drill = static_cast<int>(i);
      addHoleProcess(m, h);
    }
    for (const HoleRequest& h : setup.hole_processes) addHoleProcess(m, h);
  }
  for (size_t i = 0; i < setup.drill_tools.size(); ++i) {
    if (!setup.drill_tools[i]) continue;
    PredictionSetup own = setup;
    own.tool = setup.drill_tools[i]->tool;
    own.calibration_load = setup.drill_tools[i]->calibration_load;
    own.drill_tools.clear();
    m.drill_models.resize(setup.drill_tools.size());
    m.drill_models[i] = std::make_shared<PredictionModel>(buildPredictionModel(own));
  }
  return m;
}

const PredictionModel& modelFor(const PredictionModel& m, const HoleRequest& h) {
  const size_t i = static_cast<size_t>(std::max(h.drill, 0));
  return i < m.drill_models.size() && m.drill_models[i] ? *m.drill_models[i] : m;
}

bool hasDrillModels(const PredictionModel& m) {
  return std::any_of(m.drill_models.begin(), m.drill_models.end(),
                     [](const std::shared_ptr<PredictionModel>& p) { return p != nullptr; });
}

namespace {

/// Whether `h` is drilled by the first drill at its own cut data (process_by_diameter).
bool firstDrillAtItsCut(const PredictionModel& m, const HoleProcessKey& k) {
  if (m.process.type != ProcessType::kDrilling) return true;
  if (k.drill != 0) return false;
  const DrillingSpec& s = m.process.drilling;
  return k.feed_nm == std::lround(s.feed * 1e9) && k.rpm_milli == std::lround(s.spindle_rpm * 1e3);
}

}  // namespace

HoleRequest holeProcessOf(const HoleRequest& h) {
  HoleRequest p;
  p.diameter = h.diameter;
  p.drill = h.drill;
  p.feed = h.feed;
  p.spindle_rpm = h.spindle_rpm;
  return p;
}

HoleProcessKey holeProcessKey(const PredictionModel& m, const HoleRequest& h) {
  HoleProcessKey k;
  k.drill = std::max(h.drill, 0);
  if (m.process.type != ProcessType::kDrilling || m.process.drills.empty()) {
    k.diameter_um = diameterKey(h.diameter);
    return k;
  }
  const DrillingSpec& s = m.process.drills[static_cast<size_t>(k.drill)];
  k.diameter_um = diameterKey(h.diameter > 0 ? h.diameter : s.geometry.diameter);
  k.feed_nm = std::lround((h.feed > 0 ? h.feed : s.feed) * 1e9);
  k.rpm_milli = std::lround((h.spindle_rpm > 0 ? h.spindle_rpm : s.spindle_rpm) * 1e3);
  return k;
}

void addHoleProcess(PredictionModel& m, const HoleRequest& h) {
  if (!m.has_process) return;
  const size_t own = static_cast<size_t>(std::max(h.drill, 0));
  if (own < m.drill_models.size() && m.drill_models[own]) addHoleProcess(*m.drill_models[own], h);
  const HoleProcessKey k = holeProcessKey(m, h);
  if (firstDrillAtItsCut(m, k)) {
    const double d = h.diameter > 0 ? h.diameter
                     : m.process.type == ProcessType::kDrilling
                         ? m.process.drilling.geometry.diameter
                         : 0.0;
    const long key = diameterKey(d);
    if (!m.process_by_diameter.count(key)) m.process_by_diameter[key] = processAt(m.process, d);
    return;
  }
  if (m.process_by_hole.count(k)) return;
  const DrillingSpec& s = m.process.drills[static_cast<size_t>(k.drill)];
  m.process_by_hole[k] = processAt(m.process, h.diameter > 0 ? h.diameter : s.geometry.diameter,
                                   k.drill, h.feed, h.spindle_rpm);
}

const ProcessAtDiameter* processFor(const PredictionModel& m, const HoleRequest& h) {
  if (!m.has_process) return nullptr;
  if (h.drill <= 0 && h.feed <= 0 && h.spindle_rpm <= 0) return processFor(m, h.diameter);
  const HoleProcessKey k = holeProcessKey(m, h);
  if (firstDrillAtItsCut(m, k)) return processFor(m, h.diameter);
  const auto it = m.process_by_hole.find(k);
  if (it == m.process_by_hole.end())
    throw std::logic_error("processFor: hole " + h.id + "'s process was not built");
  return &it->second;
}

const nc::Model& controllerModel(const PredictionModel& m) {
  return m.calibrated ? m.nominal_model : m.model;
}

const IkModel& realIk(const PredictionModel& m) { return m.calibrated ? m.real_ik : m.ik; }

Pose controllerTcp(const PredictionModel& m, const Vec6& theta) {
  const nc::Model& n = controllerModel(m);
  return chainForwardKinematics(m.robot.chain, theta) * n.T_L6_flange.inverse() * n.T_L6_tcp;
}

PredictionData::PredictionData(const PredictionModel& m) : nc(m.model), rng(m.uncertainty.seed) {}

Vec6 controllerOffset(const PredictionModel& m, nc::Data& data, const Vec6& theta) {
  return controllerOffset(m, data, theta, m.compliance);
}

Vec6 controllerOffset(const PredictionModel& m, nc::Data& data, const Vec6& theta,
                      const nc::JointCompliance& c) {
  // The calibration model has the same chain (same coordinates), so the scratch can be shared.
  return nc::controllerReferenceOffset(m.controller, data, c, theta);
}

const ProcessAtDiameter* processFor(const PredictionModel& m, double diameter) {
  if (!m.has_process) return nullptr;
  double d = diameter;
  if (d <= 0 && m.process.type == ProcessType::kDrilling) d = m.process.drilling.geometry.diameter;
  auto it = m.process_by_diameter.find(diameterKey(d));
  if (it == m.process_by_diameter.end()) it = m.process_by_diameter.begin();
  return it == m.process_by_diameter.end() ? nullptr : &it->second;
}

nc::Loads processLoads(const PredictionModel& m, const ProcessAtDiameter* proc) {
  nc::Loads l;
  l.gravity = m.gravity;
  if (proc) {
    l.tcp_tool.force = proc->wrench.force;  // follows the real drill axis
    l.tcp_tool.moment = proc->wrench.torque;
  }
  return l;
}

namespace {

/// The hole's depth: its own, else the process's default depth (m).
double holeDepth(const HoleRequest& h, const ProcessAtDiameter* proc) {
  return h.depth > 0 ? h.depth : (proc ? proc->default_depth : 0.0);
}

/// Step 0: a hole deeper than the drill cuts fails on its own (p says why; true).
bool beyondDrill(const PredictionModel& m, const HoleRequest& h, HolePrediction& p) {
  const ProcessAtDiameter* proc = processFor(m, h);
  if (!proc || proc->cutting_length <= 0) return false;
  const double depth = holeDepth(h, proc);
  if (depth <= proc->cutting_length * (1.0 + 1e-9)) return false;
  p.status = HoleStatus::kUnreachable;
  p.verdict = Verdict::kUnreachable;
  p.beyond_drill = true;
  p.reason = "the drill cannot reach the bottom: the hole is " + numberText(depth * 1e3) +
             " mm deep, the Ø" + numberText(proc->diameter * 1e3) + " mm drill cuts " +
             numberText(proc->cutting_length * 1e3) + " mm at most (" +
             proc->cutting_length_source + ")";
  return true;
}

/// Step 1 (IK): the solution the hole's configuration selects, else the admissible one nearest
/// `ref` (from `ahead`, the hole's IK candidates computed beforehand, when given). On failure
/// p.status/verdict/reason say why and false is returned.
bool chooseSolution(const PredictionModel& m, PredictionData& d, const HoleRequest& h,
                    const Pose& T_W_flange, const Vec6& ref, HolePrediction& p, IkSolution& sol,
                    const IkCandidates* ahead = nullptr) {
  if (beyondDrill(m, h, p)) return false;
  if (h.config) {
    ConfigurationMatch match;
    match.explain_inexact = false;  // reason read only when nothing is found (no allocation)
    const ConfiguredSolution cs = solveIkWithConfiguration(m.ik, m.robot.card, T_W_flange,
                                                           *h.config, m.config_options, match);
    if (cs.found) {
      sol = cs.solution;
      return true;
    }
    p.status = HoleStatus::kUnreachable;
    p.verdict = Verdict::kUnreachable;
    p.reason = "no solution with the program's configuration " + formatConfig(*h.config) + ": " +
               cs.reason;
    return false;
  }
  // the admissible solution nearest ref; wrist joints weigh less: they move faster and matter
  // less for the arm posture
  static constexpr std::array<double, 6> kWeights{1.0, 1.0, 1.0, 0.5, 0.5, 0.3};
  if (solveIkNearest(m.ik, T_W_flange, ref, kWeights, ahead, d.ik, sol)) return true;
  p.status = HoleStatus::kUnreachable;
  p.verdict = Verdict::kUnreachable;
  if (d.ik.count == 0) {
    p.reason = describeIkFailure(d.ik);
  } else {
    bool any_in_limits = false;
    for (int i = 0; i < d.ik.count; ++i)
      any_in_limits |= d.ik.solutions[static_cast<size_t>(i)].within_limits;
    if (any_in_limits) {
      p.status = HoleStatus::kSingular;
      p.verdict = Verdict::kSingular;
      p.reason = "every in-limit solution is at a wrist or shoulder singularity";
    } else {
      p.reason = "no IK solution within the joint limits";
    }
  }
  return false;
}

/// The flange pose the controller's IK solves for a programmed TCP pose.
Pose flangeTarget(const PredictionModel& m, const HoleRequest& h) {
  const nc::Model& n = controllerModel(m);
  return h.T_W_tcp * n.T_L6_tcp.inverse() * n.T_L6_flange;
}

/// The IK seed of a hole: its own, else the sequence's, else the vendor's reference pose.
const Vec6& seedOf(const PredictionModel& m, const HoleRequest& h, const Vec6* seed) {
  return h.ik_seed ? *h.ik_seed : seed ? *seed : m.reference_pose;
}

/// How far a prediction goes: the whole (kFull), or up to the compliance equilibrium (kStatus:
/// PredictOptions::budget false).
enum class Depth : std::uint8_t { kFull, kStatus };

void predictAtSolution(const PredictionModel& m, PredictionData& d, const HoleRequest& h,
                       const IkSolution& sol, HolePrediction& p, Depth depth = Depth::kFull);

void holeFigures(const PredictionModel& m, const HoleRequest& h, const ProcessAtDiameter* proc,
                 HolePrediction& p);
bool takeSolution(const PredictionModel& m, const IkSolution& sol, HolePrediction& p);

/// The drill, feed and spindle speed hole `h` is drilled with (HolePrediction::drill, ...).
void setHoleProcess(const PredictionModel& m, const HoleRequest& h, HolePrediction& p) {
  p.drill = std::max(h.drill, 0);
  if (!m.has_process || m.process.type != ProcessType::kDrilling) return;
  const DrillingSpec& s = m.process.drills.empty() ? m.process.drilling
                                                   : m.process.drills[static_cast<size_t>(p.drill)];
  p.feed = h.feed > 0 ? h.feed : s.feed;
  p.spindle_rpm = h.spindle_rpm > 0 ? h.spindle_rpm : s.spindle_rpm;
}

}  // namespace

namespace {

/// Resets every field of p for hole h, keeping the capacity of its strings (no allocation; the
/// budget is inline).
void resetPrediction(const HoleRequest& h, HolePrediction& p) {
  std::string id = std::move(p.id);
  std::string reason = std::move(p.reason);
  std::string config = std::move(p.config);
  p = HolePrediction{};
  id.assign(h.id);
  reason.clear();
  config.clear();
  p.id = std::move(id);
  p.reason = std::move(reason);
  p.config = std::move(config);
}

}  // namespace

HolePrediction predictHole(const PredictionModel& m, PredictionData& d, const HoleRequest& h,
                           const Vec6* seed) {
  HolePrediction p;
  predictHole(m, d, h, seed, p);
  return p;
}

namespace {
/// predictHole to `depth`.
void predictHoleTo(const PredictionModel& base, PredictionData& d, const HoleRequest& h,
                   const Vec6* seed, HolePrediction& p, Depth depth) {
  const PredictionModel& m = modelFor(base, h);
  resetPrediction(h, p);
  IkSolution sol;
  chooseSolution(m, d, h, flangeTarget(m, h), seedOf(m, h, seed), p, sol);
  // without a solution: the per-hole process figures only
  predictAtSolution(m, d, h, sol, p, depth);
}
}  // namespace

void predictHole(const PredictionModel& base, PredictionData& d, const HoleRequest& h,
                 const Vec6* seed, HolePrediction& p) {
  predictHoleTo(base, d, h, seed, p, Depth::kFull);
}

void chooseHoleSolution(const PredictionModel& base, PredictionData& d, const HoleRequest& h,
                        const Vec6* seed, HolePrediction& p) {
  const PredictionModel& m = modelFor(base, h);
  resetPrediction(h, p);
  IkSolution sol;
  chooseSolution(m, d, h, flangeTarget(m, h), seedOf(m, h, seed), p, sol);
  const ProcessAtDiameter* proc = processFor(m, h);
  holeFigures(m, h, proc, p);
  if (p.status == HoleStatus::kOk) takeSolution(m, sol, p);
}

namespace {

/// The plane ⊥ the hole axis: unit vectors e1, e2 (the nominal TCP x and y) and the axis a (its z).
struct HolePlane {
  Vec3 e1, e2, a;
  /// The in-plane components (e1, e2) of a base-frame vector.
  Eigen::Vector2d of(const Vec3& v) const { return Eigen::Vector2d(v.dot(e1), v.dot(e2)); }
};

HolePlane holePlane(const Mat3& R_tcp) { return {R_tcp.col(0), R_tcp.col(1), R_tcp.col(2)}; }

/// The hole's own figures, predicted or not: tolerance, drill, feed, speed, diameter, depth and the
/// machining-centre time.
void holeFigures(const PredictionModel& m, const HoleRequest& h, const ProcessAtDiameter* proc,
                 HolePrediction& p) {
  p.tolerance = h.tolerance > 0 ? h.tolerance : m.default_tolerance;
  setHoleProcess(m, h, p);
  p.diameter = h.diameter > 0 ? h.diameter : (proc ? proc->diameter : 0.0);
  p.depth = holeDepth(h, proc);
  if (proc && proc->feed_rate > 0 && !p.beyond_drill)
    p.mc_time = p.depth / proc->feed_rate + m.capability.mc_approach_s;
}

/// The chosen IK solution as the hole's command (joints, branch, vendor flags); false,
/// with p saying why, at a wrist or shoulder singularity.
bool takeSolution(const PredictionModel& m, const IkSolution& sol, HolePrediction& p) {
  p.joints = sol.q;
  p.branch = 4 * sol.branch.shoulder + 2 * sol.branch.elbow + sol.branch.wrist;
  p.wrist_margin = sol.branch.wrist_margin_rad;
  p.config = formatConfig(configurationOf(m.ik, m.robot.card, sol.q, m.config_options));
  if (!sol.singular_wrist && !sol.singular_shoulder) return true;
  p.status = HoleStatus::kSingular;
  p.verdict = Verdict::kSingular;
  p.reason = sol.singular_wrist ? "wrist singularity (axis 5 near 0)" : "shoulder singularity";
  return false;
}

/// The process wrench on the TCP in the base frame, w = [R f; R m] (N, N m).
Vec6 processWrenchBase(const Mat3& R_tcp, const nc::Loads& loads) {
  Vec6 w;
  w << R_tcp * loads.tcp_tool.force, R_tcp * loads.tcp_tool.moment;
  return w;
}

/// δrobot: the compliance equilibrium at the command under gravity and the process
/// wrench (the controller's own offset `offset` applied), referred to the controller's pose when
/// the robot is calibrated; false, with p saying why, when it does not converge.
/// The compliance equilibrium at the command θ (the controller's own offset `offset` applied).
nc::Deflection equilibriumAt(const PredictionModel& m, PredictionData& d, const Vec6& theta,
                             const nc::Loads& loads, const Vec6& offset) {
  nc::DeflectionOptions dopt;
  // the linear budget reads data.frames only; Monte Carlo's share uses the full state
  dopt.natural_state = m.uncertainty.method != UncertaintyInputs::Method::kLinear;
  return nc::predictDeflection(m.model, d.nc, m.compliance, theta, loads, dopt, offset);
}

bool robotDeviation(const PredictionModel& m, PredictionData& d, const IkSolution& sol,
                    const nc::Loads& loads, const Vec6& offset, HolePrediction& p) {
  p.deflection = equilibriumAt(m, d, sol.q, loads, offset);
  if (!p.deflection.converged || !p.deflection.position_converged) {
    p.status = HoleStatus::kNotConverged;
    p.verdict = Verdict::kNotConverged;
    p.reason = "the compliance equilibrium did not converge (residual " +
               numberText(p.deflection.residual) + " rad)";
    return false;
  }
  if (m.calibrated) nc::referToControllerPose(p.deflection, controllerTcp(m, sol.q));
  p.d_robot = p.deflection.dp;
  p.d_rot = p.deflection.drot;
  return true;
}

/// δmach (its systematic part, in the tool XY plane), δwork = δrobot + δmach and the
/// errors ⊥ the hole axis: position error, axis tilt and, when the nominal hole is known, the real
/// drill point's distance from its axis.
void workDeviation(const HoleRequest& h, const ProcessAtDiameter* proc, const Mat3& R_tcp,
                   const HolePlane& plane, HolePrediction& p) {
  if (proc) p.d_mach = R_tcp * Vec3(proc->mach.delta_tool.x(), proc->mach.delta_tool.y(), 0.0);
  p.d_work = p.d_robot + p.d_mach;
  p.e_tool = plane.of(p.d_work);
  p.position_error = p.e_tool.norm();
  p.axis_tilt = (p.d_rot - p.d_rot.dot(plane.a) * plane.a).norm();
  if (h.nominal_axis) {
    const Vec3 real = p.deflection.T_real.translation() + p.d_mach;
    const Vec3 n = h.nominal_axis->second.normalized();
    const Vec3 r = real - h.nominal_axis->first;
    p.nominal_axis_error = (r - r.dot(n) * n).norm();
  }
}

/// In-plane covariances (m²) of δrobot's model uncertainty: the whole, and the part the process
/// force's scale uncertainty causes (the robot_deflection_process_force term).
struct DeflectionCovariance {
  Eigen::Matrix2d total{Eigen::Matrix2d::Zero()};
  Eigen::Matrix2d process_force{Eigen::Matrix2d::Zero()};
};

/// The process-force part, first order: the deviation J K_eff⁻¹ Jᵀ w of the wrench w alone,
/// scaled by the force scale's standard uncertainty (rectangular half-width a: a/√3).
Eigen::Matrix2d processForceCovariance(const PredictionModel& m, const nc::Mat6& J,
                                       const Vec6& w_base, const HolePlane& plane) {
  const double u_force_scale = m.uncertainty.process_halfwidth / std::sqrt(3.0);
  const Vec6 phi_w = (J.transpose() * w_base).cwiseQuotient(m.compliance.effective());
  const Eigen::Vector2d delta_u = plane.of(J.topRows<3>() * phi_w * u_force_scale);
  return delta_u * delta_u.transpose();
}

/// The deflection covariance, linear: the sensitivity of δrobot to each joint's stiffness k_i and
/// servo stiffness, with the TCP Jacobian at the deflected configuration (data.frames hold it after
/// robotDeviation), plus the process-force part.
DeflectionCovariance linearDeflectionCovariance(const PredictionModel& m, PredictionData& d,
                                                const IkSolution& sol, const Vec6* w_base,
                                                const HolePlane& plane, const HolePrediction& p) {
  const UncertaintyInputs& U = m.uncertainty;
  const nc::Mat6& J = nc::tcpJacobianFromFrames(m.model, d.nc);
  DeflectionCovariance cov;
  // Sensitivity to k_i of the part of the deflection roprec predicts (beyond a controller's own
  // gravity compensation): net joint deformation Δθ_i = θ_i − θ_m,i − offset_i, first order.
  for (int i = 0; i < 6; ++i) {
    const Vec3 col = J.block<3, 1>(0, i);
    const double net = p.deflection.theta[i] - sol.q[i] - p.deflection.dpsi[i];
    const Eigen::Vector2d sk = plane.of(col * net * U.stiffness_rel);
    cov.total += sk * sk.transpose();
    if (m.compliance.k_servo[i] < 1e299) {
      const Eigen::Vector2d ss = plane.of(col * p.deflection.dpsi[i] * U.position_gain_rel);
      cov.total += ss * ss.transpose();
    }
  }
  if (w_base) {
    cov.process_force = processForceCovariance(m, J, *w_base, plane);
    cov.total += cov.process_force;
  }
  return cov;
}

/// The deflection covariance, Monte Carlo: k_i ~ N(k_i, (rel k_i)²), k_servo likewise, force scale
/// ~ U(1 − a, 1 + a), one reproducible stream per hole (seed ^ FNV-1a of the id); the process-force
/// part by the linear sensitivity (for its share only).
DeflectionCovariance monteCarloDeflectionCovariance(const PredictionModel& m, PredictionData& d,
                                                    const HoleRequest& h, const IkSolution& sol,
                                                    const nc::Loads& loads, const Vec6& offset,
                                                    const Vec6* w_base, const HolePlane& plane) {
  const UncertaintyInputs& U = m.uncertainty;
  std::uint32_t hid = 2166136261u;  // FNV-1a of the id: per-hole streams, reproducible everywhere
  for (const char ch : h.id) hid = (hid ^ static_cast<unsigned char>(ch)) * 16777619u;
  std::mt19937 rng(U.seed ^ hid);
  std::normal_distribution<double> nd(0.0, 1.0);
  std::uniform_real_distribution<double> ud(-1.0, 1.0);
  const int n = std::max(10, U.samples);
  std::vector<Eigen::Vector2d> samples;
  samples.reserve(static_cast<size_t>(n));
  for (int s = 0; s < n; ++s) {
    nc::JointCompliance c = m.compliance;
    for (int i = 0; i < 6; ++i) {
      c.k[i] *= std::max(0.05, 1.0 + U.stiffness_rel * nd(rng));
      if (c.k_servo[i] < 1e299) c.k_servo[i] *= std::max(0.05, 1.0 + U.position_gain_rel * nd(rng));
    }
    nc::Loads l = loads;
    const double scale = 1.0 + U.process_halfwidth * ud(rng);
    l.tcp_tool.force *= scale;
    l.tcp_tool.moment *= scale;
    // the controller's offset (gravity compensation or mastering) was set up with the same
    // (uncertain) stiffness: Δθ_c = K_eff⁻¹ τ_ref scales with it
    const Vec6 off = offset.cwiseProduct(m.compliance.effective()).cwiseQuotient(c.effective());
    const nc::Deflection dd = nc::predictDeflection(m.model, d.nc, c, sol.q, l, {}, off);
    samples.push_back(plane.of(dd.dp));
  }
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& s : samples) mean += s;
  mean /= n;
  DeflectionCovariance cov;
  for (const auto& s : samples) cov.total += (s - mean) * (s - mean).transpose();
  cov.total /= (n - 1);
  const nc::Mat6& J = nc::tcpJacobian(m.model, d.nc);
  if (w_base) cov.process_force = processForceCovariance(m, J, *w_base, plane);
  return cov;
}

/// The budget terms (u per in-plane axis), u_robot, u_mach, u_work, their expansions by
/// the 2-D coverage factor k, the exact anisotropic U_work and the variance shares.
void uncertaintyBudget(const PredictionModel& m, const ProcessAtDiameter* proc,
                       const HolePlane& plane, const DeflectionCovariance& cov, HolePrediction& p) {
  const UncertaintyInputs& U = m.uncertainty;
  const double u_repeatability =
      m.robot.card.rp_mm > 0 ? sigmaFromRp(m.robot.card.rp_mm * 1e-3) : 0.0;
  p.robdef_cov = cov.total;
  const bool with_accuracy = hasAccuracyTerm(m.accuracy);
  const Eigen::Matrix2d cov_accuracy =
      with_accuracy ? accuracyCovariance(m, p.deflection.theta, plane.e1, plane.e2)
                    : Eigen::Matrix2d::Zero().eval();
  const double u_accuracy = std::sqrt(0.5 * cov_accuracy.trace());
  const double u_robdef = std::sqrt(0.5 * cov.total.trace());
  const double u_robdef_force = std::sqrt(0.5 * cov.process_force.trace());
  p.budget.reserve(3 + (proc ? proc->mach.components.size() : 0));  // within kMaxBudgetTerms
  p.budget.push_back({"robot_repeatability", u_repeatability, false});
  p.budget.push_back(
      {"robot_deflection_model",
       std::sqrt(std::max(0.0, u_robdef * u_robdef - u_robdef_force * u_robdef_force)), false});
  p.budget.push_back({"robot_deflection_process_force", u_robdef_force, true});
  if (with_accuracy)
    p.budget.push_back(
        {"robot_absolute_accuracy", u_accuracy, false, internedText(m.accuracy.source)});
  double u_mach2 = 0;
  if (proc) {
    for (const UncertaintyComponent& c : proc->mach.components) {
      const char* name = c.name == "delta_axis"     ? "mach_axis"
                         : c.name == "delta_runout" ? "mach_runout"
                                                    : "mach_tool_deflection";
      p.budget.push_back({name, c.standard, true});
      u_mach2 += c.standard * c.standard;
    }
  }
  p.u_robot = with_accuracy ? std::sqrt(u_repeatability * u_repeatability + u_robdef * u_robdef +
                                        u_accuracy * u_accuracy)
                            : std::sqrt(u_repeatability * u_repeatability + u_robdef * u_robdef);
  p.u_mach = std::sqrt(u_mach2);
  p.u_work = std::sqrt(p.u_robot * p.u_robot + p.u_mach * p.u_mach);
  p.k = rayleighCoverageFactor(U.coverage_probability);
  p.U_robot = p.k * p.u_robot;
  p.U_mach = p.k * p.u_mach;
  p.U_work = p.k * p.u_work;
  Eigen::Matrix2d cov_work =
      cov.total + (u_repeatability * u_repeatability + u_mach2) * Eigen::Matrix2d::Identity();
  if (with_accuracy) cov_work += cov_accuracy;
  p.U_work_exact = radialCoverage(cov_work, U.coverage_probability);
  p.process_share = p.u_work > 0 ? u_mach2 / (p.u_work * p.u_work) : 0.0;
  p.process_force_share =
      p.u_work > 0 ? u_robdef_force * u_robdef_force / (p.u_work * p.u_work) : 0.0;
}

/// The hole at its chosen IK solution, stage by stage: its figures, the command, δrobot, δmach
/// with δwork and the errors ⊥ the axis, the uncertainty budget and the verdict. A hole without a
/// solution (p.status set by the IK choice) gets its figures only.
void predictAtSolution(const PredictionModel& m, PredictionData& d, const HoleRequest& h,
                       const IkSolution& sol, HolePrediction& p, Depth depth) {
  const ProcessAtDiameter* proc = processFor(m, h);
  holeFigures(m, h, proc, p);
  if (p.status != HoleStatus::kOk || !takeSolution(m, sol, p)) return;

  const nc::Loads loads = processLoads(m, proc);
  const Mat3& R_tcp = h.T_W_tcp.linear();
  const Vec6 w_base = processWrenchBase(R_tcp, loads);
  p.force_base = w_base.head<3>();
  const Vec6 offset = controllerOffset(m, d.nc, sol.q);
  if (!robotDeviation(m, d, sol, loads, offset, p) || depth == Depth::kStatus) return;

  const HolePlane plane = holePlane(R_tcp);
  workDeviation(h, proc, R_tcp, plane, p);

  const Vec6* w_process = proc ? &w_base : nullptr;
  const DeflectionCovariance cov =
      m.uncertainty.method == UncertaintyInputs::Method::kLinear
          ? linearDeflectionCovariance(m, d, sol, w_process, plane, p)
          : monteCarloDeflectionCovariance(m, d, h, sol, loads, offset, w_process, plane);
  uncertaintyBudget(m, proc, plane, cov, p);

  // The verdict on the hole's real position error: from the nominal hole axis when the nominal hole
  // is known (e.g. a compensated program checked against its hole list), else from the programmed
  // pose.
  p.verdict =
      verdictFor(p.nominal_axis_error.value_or(p.position_error), p.U_work_exact, p.tolerance);
}

}  // namespace

std::optional<Vec3> robotDeviationAt(const PredictionModel& base, PredictionData& d,
                                     const HoleRequest& h, const Vec6& joints) {
  const PredictionModel& m = modelFor(base, h);
  const nc::Loads loads = processLoads(m, processFor(m, h));
  const Vec6 offset = controllerOffset(m, d.nc, joints);
  nc::Deflection def = equilibriumAt(m, d, joints, loads, offset);
  if (!def.converged || !def.position_converged) return std::nullopt;
  if (m.calibrated) nc::referToControllerPose(def, controllerTcp(m, joints));
  return def.dp;
}

std::vector<HolePrediction> predictHoles(const PredictionModel& m,
                                         std::span<const HoleRequest> holes) {
  return predictHoles(m, holes, PredictOptions{});
}

std::vector<HolePrediction> predictHoles(const PredictionModel& m,
                                         std::span<const HoleRequest> holes,
                                         const PredictOptions& options) {
  std::vector<HolePrediction> out(holes.size());
  predictHoles(m, holes, options, [&](size_t i) -> HolePrediction& { return out[i]; });
  return out;
}

namespace {
/// Holes whose IK candidates predictHoles computes ahead at a time (~0.4 kB each).
constexpr size_t kIkCandidateChunk = 4096;

/// Whether a hole's chosen solution seeds the next hole's choice (an admissible, non-singular
/// one).
bool seedsNext(char chosen, const IkSolution& sol) {
  return chosen != 0 && !sol.singular_wrist && !sol.singular_shoulder;
}

/// predictHoles' first stage: the IK choice of every hole in order, each seeded with the previous
/// admissible solution (continuity; `first` before the first hole): sol[i], chosen[i] and the
/// seed[i] it was chosen with. With more than one thread, the analytic candidates of a chunk of
/// holes (most of the IK's cost; they do not depend on the seed: ikCandidates) are computed on
/// the workers first and only the choice runs in order. An inexact chain's IK finishes every
/// branch from the start: nothing to compute ahead there.
void chooseInOrder(const PredictionModel& m, PredictionData& d, std::span<const HoleRequest> holes,
                   const std::optional<Vec6>& first, int threads, std::span<IkSolution> sol,
                   std::span<char> chosen, std::vector<std::optional<Vec6>>& seed) {
  const size_t n = holes.size();
  const bool compute_ahead = threads > 1 && m.ik.deviation.exact;
  std::vector<IkCandidates> ahead(compute_ahead ? std::min(n, kIkCandidateChunk) : 0);
  std::optional<Vec6> prev = first;
  HolePrediction probe;
  for (size_t c0 = 0; c0 < n; c0 += kIkCandidateChunk) {
    const size_t c1 = std::min(n, c0 + kIkCandidateChunk);
    if (compute_ahead) {
      parallelFor(c1 - c0, threads, [&](int, size_t k) {
        const HoleRequest& h = holes[c0 + k];
        ahead[k].valid = false;
        if (!h.config) ikCandidates(m.ik, flangeTarget(modelFor(m, h), h), ahead[k]);
      });
    }
    for (size_t i = c0; i < c1; ++i) {
      seed[i] = prev;
      probe.status = HoleStatus::kOk;
      const PredictionModel& mi = modelFor(m, holes[i]);
      chosen[i] = chooseSolution(mi, d, holes[i], flangeTarget(mi, holes[i]),
                                 seedOf(mi, holes[i], prev ? &*prev : nullptr), probe, sol[i],
                                 compute_ahead ? &ahead[i - c0] : nullptr);
      if (seedsNext(chosen[i], sol[i])) prev = sol[i].q;
    }
  }
}

/// The seeds chooseInOrder chose the holes with, from its choice (sol, chosen) and `first`.
void seedsOfChoice(const std::optional<Vec6>& first, std::span<const IkSolution> sol,
                   std::span<const char> chosen, std::vector<std::optional<Vec6>>& seed) {
  std::optional<Vec6> prev = first;
  for (size_t i = 0; i < sol.size(); ++i) {
    seed[i] = prev;
    if (seedsNext(chosen[i], sol[i])) prev = sol[i].q;
  }
}
}  // namespace

void predictHoles(const PredictionModel& m, std::span<const HoleRequest> holes,
                  const PredictOptions& options, const std::function<HolePrediction&(size_t)>& at) {
  const size_t n = holes.size();
  const int threads = std::max(1, options.threads);
  std::vector<PredictionData> scratch;
  scratch.reserve(static_cast<size_t>(threads));
  for (int w = 0; w < threads; ++w) scratch.emplace_back(m);
  // 1. the IK choice of every hole, in order (each seeds the next), or the one given
  std::vector<IkSolution> own_sol(options.choice.sol.empty() ? n : 0);
  std::vector<char> own_chosen(options.choice.sol.empty() ? n : 0, 0);
  const std::span<IkSolution> sol = options.choice.sol.empty() ? own_sol : options.choice.sol;
  const std::span<char> chosen = options.choice.sol.empty() ? own_chosen : options.choice.chosen;
  if (sol.size() != n || chosen.size() != n)
    throw std::invalid_argument("predictHoles: the IK choice is not one per hole");
  std::vector<std::optional<Vec6>> seed(n);
  if (options.choice.given)
    seedsOfChoice(options.seed, sol, chosen, seed);
  else
    chooseInOrder(m, scratch[0], holes, options.seed, threads, sol, chosen, seed);
  const Depth depth = options.budget ? Depth::kFull : Depth::kStatus;
  // 2. the rest of every hole, in parallel (per-worker scratch; each hole depends only on its
  //    request, its seed and the model, so the output does not depend on the thread count)
  parallelFor(n, threads, [&](int w, size_t i) {
    HolePrediction& p = at(i);
    p.id = holes[i].id;
    if (chosen[i]) {
      predictAtSolution(modelFor(m, holes[i]), scratch[static_cast<size_t>(w)], holes[i], sol[i], p,
                        depth);
    } else {
      predictHoleTo(m, scratch[static_cast<size_t>(w)], holes[i], seed[i] ? &*seed[i] : nullptr, p,
                    depth);
    }
  });
  // 3. the rare hole whose full prediction failed after an admissible IK (equilibrium not
  //    converged) seeds its successor differently: redo the sequence from there, sequentially
  std::optional<Vec6> prev = options.seed;
  for (size_t i = 0; i < n; ++i) {
    const bool same = prev.has_value() == seed[i].has_value() && (!prev || *prev == *seed[i]);
    HolePrediction& p = at(i);
    if (!same) predictHoleTo(m, scratch[0], holes[i], prev ? &*prev : nullptr, p, depth);
    if (p.status == HoleStatus::kOk) prev = p.joints;
  }
}

CapabilitySummary summarize(const std::vector<HolePrediction>& p) {
  SummaryAccumulator sum;
  for (const HolePrediction& h : p) sum.add(h);
  return sum.summary();
}

void SummaryAccumulator::add(const HolePrediction& h) {
  ++s_.holes;
  s_.mc_time_total += h.mc_time;
  switch (h.verdict) {
    case Verdict::kConforms:
      ++s_.conforms;
      break;
    case Verdict::kConformsAfterCompensation:
      ++s_.conforms_after_compensation;
      break;
    case Verdict::kNotCapable:
      ++s_.not_capable;
      break;
    case Verdict::kUnreachable:
      ++s_.unreachable;
      break;
    case Verdict::kSingular:
      ++s_.singular;
      break;
    case Verdict::kNotConverged:
      ++s_.not_converged;
      break;
  }
  if (h.verdict == Verdict::kConforms || h.verdict == Verdict::kConformsAfterCompensation) {
    ++s_.robot_can_take;
    s_.mc_time_taken += h.mc_time;
  }
  if (h.status == HoleStatus::kOk) {
    s_.max_process_share = std::max(s_.max_process_share, h.process_share);
    share_sum_ += h.process_share;
    ++share_n_;
  }
}

CapabilitySummary SummaryAccumulator::summary() const {
  CapabilitySummary s = s_;
  s.mean_process_share = share_n_ ? share_sum_ / share_n_ : 0.0;
  return s;
}

}  // namespace roprec
