/// Transient of one process cycle at one pose (plugin/api/simulate.hpp).
#include "plugin/api/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>

#include "compensator/process/process_load.hpp"
#include "compensator/robot/configuration.hpp"
#include "compensator/robot/ik.hpp"
#include "compensator/support/c_format.hpp"
#include "compensator/support/fixed_chars.hpp"
#include "plugin/api/hole_input.hpp"
#include "plugin/api/robot_compliance.hpp"
#include "postproc/drill.hpp"
#include "postproc/program.hpp"

namespace roprec::api {

// ---------------------------------------------------------------- the joints of a hole

namespace {

/// Joints for a TCP pose in the base frame: the regular in-limit IK solution nearest the vendor
/// reference pose. Throws HoleUnreachable at FILE:LINE when there is none.
nc::Vec6 jointsNearReference(const RobotSetup& s, const Pose& T_base_tcp, const std::string& file,
                             int line, const std::string& id) {
  const Pose T_base_flange = T_base_tcp * s.tool.T_flange_tcp.inverse();
  const IkModel ik = buildIkModel(s.robot);
  const Vec6 ref = vendorReferencePose(s.robot.card);
  IkOptions o;
  o.seed = &ref;
  IkResult res;
  solveIk(ik, T_base_flange, o, res);
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (int i = 0; i < res.count; ++i) {
    const IkSolution& sol = res.solutions[static_cast<size_t>(i)];
    if (!sol.converged || !sol.within_limits || sol.singular_wrist || sol.singular_shoulder ||
        sol.singular_elbow)
      continue;
    const double d = (sol.q - ref).norm();
    if (d < best_d) {
      best_d = d;
      best = i;
    }
  }
  if (best < 0) {
    throw HoleUnreachable(
        file, line,
        "hole '" + id + "' is not reachable: " +
            (res.count == 0 ? describeIkFailure(res) : "no regular in-limit IK solution"));
  }
  return res.solutions[static_cast<size_t>(best)].q;
}

/// A contract hole list: position and drilling direction in the cell's work object.
HoleJoints holeListJoints(const RobotSetup& s, const std::string& path, const std::string& id) {
  for (const postproc::HoleSpec& h : postproc::readHoleList(path)) {
    if (h.id != id) continue;
    const Vec3 z = s.cell->T_base_wobj.linear() * h.direction.normalized();
    Vec3 x = Vec3::UnitX() - Vec3::UnitX().dot(z) * z;
    if (x.norm() < 1e-6) x = Vec3::UnitY() - Vec3::UnitY().dot(z) * z;
    x.normalize();
    Pose T = Pose::Identity();
    T.linear() << x, z.cross(x), z;
    T.translation() = s.cell->T_base_wobj * (h.position_mm * 1e-3);
    HoleJoints hc;
    hc.joints = jointsNearReference(s, T, path, h.line, id);
    hc.source = "hole list row " + std::to_string(h.line) +
                " (cell workobject, IK solution nearest the reference pose)";
    HoleRequest r;
    r.id = id;
    if (h.diameter_mm) r.diameter = *h.diameter_mm * 1e-3;
    assignDrill(*s.cell, h.tool, h.tool, path, h.line, r);
    HoleProcessChoice& pc = hc.process;
    pc.drill = r.drill;
    pc.diameter = r.diameter;
    pc.depth = h.depth_mm.value_or(0.0) * 1e-3;
    pc.feed = h.feed_mm_per_rev.value_or(0.0) * 1e-3;
    pc.spindle_rpm = h.spindle_rpm.value_or(0.0);
    pc.source = "hole list row " + std::to_string(h.line);
    return hc;
  }
  throw InputError(path, 0, "no hole '" + id + "' in the hole list");
}

const postproc::Hole& findHole(const std::vector<postproc::Hole>& holes, const std::string& path,
                               const std::string& id) {
  std::string names;
  const postproc::Hole* hole = nullptr;
  for (const postproc::Hole& h : holes) {
    names += (names.empty() ? "" : ", ") + h.id;
    if (h.id == id) hole = &h;
  }
  if (hole == nullptr) {
    throw InputError(
        path, 0,
        "no recognised hole '" + id + "' (holes: " + (names.empty() ? "none" : names) + ")");
  }
  return *hole;
}

HoleJoints jointTargetJoints(const RobotSetup& s, const postproc::Target& t,
                             const std::string& tfile, const std::string& id) {
  const std::vector<double> j = postproc::targetJointsDeg(t);
  if (j.size() < 6)
    throw InputError(tfile, t.line, "joint target of hole '" + id + "' has fewer than 6 axes");
  nc::Vec6 qc;
  for (int i = 0; i < 6; ++i) qc[i] = j[static_cast<size_t>(i)] * kDeg;
  return {fromControllerJoints(s.robot.card, qc), "joint target " + t.name, {}};
}

/// A Cartesian drill point: in the program's frame when it resolves, else the cell's work object;
/// IK with the target's configuration when it states one.
HoleJoints cartesianTargetJoints(const RobotSetup& s, const postproc::Program& prog,
                                 const postproc::Hole& hole, const std::string& tfile,
                                 const std::string& id) {
  const postproc::Target& t = prog.targets()[static_cast<size_t>(hole.bottom_target)];
  const std::optional<Pose> pose =
      postproc::motionPose(prog, prog.motions[static_cast<size_t>(hole.bottom_motion)]);
  if (!pose)
    throw InputError(tfile, t.line, "the drill point of hole '" + id + "' has no Cartesian pose");
  Pose T_base_frame = s.cell->T_base_wobj;
  std::string frame = "cell workobject";
  if (hole.base >= 0 && prog.frames[static_cast<size_t>(hole.base)].resolved) {
    T_base_frame = prog.frames[static_cast<size_t>(hole.base)].pose;
    frame = "program frame " + prog.frames[static_cast<size_t>(hole.base)].ref;
  }
  const IkModel ik = buildIkModel(s.robot);  // first: its errors precede a configuration's
  if (!t.config.present()) {
    return {jointsNearReference(s, T_base_frame * *pose, tfile, t.line, id),
            "target " + t.name + " (" + frame + ", IK solution nearest the reference pose)",
            {}};
  }
  const Pose T_base_flange = T_base_frame * *pose * s.tool.T_flange_tcp.inverse();
  const VendorConfig vc = parseConfig(s.robot.card.vendor, t.config.text(), tfile, t.line);
  const ConfiguredSolution cs = solveIkWithConfiguration(ik, s.robot.card, T_base_flange, vc);
  if (!cs.found) {
    throw HoleUnreachable(tfile, t.line,
                          "hole '" + id + "' is not reachable with configuration " +
                              t.config.text() + ": " + cs.reason);
  }
  return {cs.solution.q,
          "target " + t.name + " (" + frame + ", configuration " + t.config.text() + ")",
          {}};
}

}  // namespace

HoleJoints holeJoints(const RobotSetup& setup, const std::string& program_path,
                      const std::string& id) {
  if (!setup.cell)
    throw UsageError("the joints of a program's hole need a cell (work object and tool)");
  const postproc::Program prog = postproc::readProgram(program_path);
  if (prog.dialect == postproc::Dialect::kHoleCsv) return holeListJoints(setup, program_path, id);
  const std::vector<postproc::Hole> holes = postproc::recognizeHoles(prog);
  const postproc::Hole& hole = findHole(holes, program_path, id);
  const postproc::Target& t = prog.targets()[static_cast<size_t>(hole.bottom_target)];
  const std::string tfile =
      t.file >= 0 ? prog.files[static_cast<size_t>(t.file)].path : program_path;
  HoleJoints hj = t.kind == postproc::TargetKind::kJoint
                      ? jointTargetJoints(setup, t, tfile, id)
                      : cartesianTargetJoints(setup, prog, hole, tfile, id);
  HoleRequest r;
  r.id = id;
  const std::string ref = hole.tool >= 0 ? prog.frames[static_cast<size_t>(hole.tool)].ref : "";
  assignDrill(*setup.cell, ref.empty() ? "" : programToolKey(ref), ref, tfile, t.line, r);
  hj.process.drill = r.drill;
  hj.process.depth = hole.depth;
  hj.process.source = ref.empty() ? "program (no tool named)" : "program tool " + ref;
  return hj;
}

// ---------------------------------------------------------------- the transient

namespace {

nc::TransientProblem transientProblem(const RobotSetup& s, const nc::Model& model, nc::Data& data,
                                      const nc::Vec6& q, const SimulateOptions& o) {
  nc::DriveEstimateOptions est;
  est.integral = o.integral;
  nc::TransientProblem p;
  p.model = &model;
  p.drive = nc::driveModelFromCard(s.robot.card, model, data, q, est);
  p.theta_cmd = q;
  p.gravity = o.gravity;
  // the controller's gravity handling exactly as predict and deflect see it (robot_compliance.hpp)
  if (o.gravity) requireGravityModel(s.robot);
  const nc::ControllerReference ref =
      controllerReferenceOf(s.robot, s.cell ? &*s.cell : nullptr, s.tool, o.gravity);
  p.command_offset = nc::controllerReferenceOffset(ref, data, p.drive.staticCompliance(), q);
  if (s.robot.card.calibration)  // deviation from the pose the controller means, as deflect
    p.controller_tcp = chainForwardKinematics(s.robot.chain, q) * s.tool.T_flange_tcp;
  return p;
}

/// The static references (the deflect model: same compliance, load at full engagement, deviation
/// from the same reference as the transient's samples).
struct StaticReference {
  nc::Deflection gravity_only;
  nc::Deflection full_engagement;
};

nc::Deflection staticDeflection(const nc::Model& model, nc::Data& data,
                                const nc::TransientProblem& p, const nc::Loads& loads) {
  nc::Deflection d = nc::predictDeflection(model, data, p.drive.staticCompliance(), p.theta_cmd,
                                           loads, {}, p.command_offset);
  if (p.controller_tcp) nc::referToControllerPose(d, *p.controller_tcp);
  return d;
}

StaticReference staticReference(const nc::Model& model, nc::Data& data,
                                const nc::TransientProblem& p,
                                const std::optional<ProcessSpec>& spec) {
  StaticReference ref;
  nc::Loads gl;
  gl.gravity = p.gravity;
  ref.gravity_only = staticDeflection(model, data, p, gl);
  nc::Loads fl = gl;
  if (spec) {
    const SteadyProcessLoad pl = steadyProcessLoad(*spec);
    fl.tcp_tool.force = pl.wrench.force;
    fl.tcp_tool.moment = pl.wrench.torque;
  }
  ref.full_engagement = staticDeflection(model, data, p, fl);
  return ref;
}

/// What the summary reports of the history.
struct HistoryStats {
  const nc::TransientSample* last_full{nullptr};  ///< last sample in full engagement
  double max_entry{0.0};                          ///< |dp| max during entry, m
  double max_dev{0.0};                            ///< |dp| max, m
  double t_max{0.0};                              ///< its time, s
  double max_change{0.0};                         ///< max |dp − dp(0)|, m
};

HistoryStats historyStats(const nc::TransientResult& r) {
  HistoryStats h;
  const Vec3 dp0 = r.samples.empty() ? Vec3::Zero() : r.samples.front().dp;
  for (const nc::TransientSample& smp : r.samples) {
    const double n = smp.dp.norm();
    if (smp.process.phase == nc::CyclePhase::kFull) h.last_full = &smp;
    if (smp.process.phase == nc::CyclePhase::kEntry) h.max_entry = std::max(h.max_entry, n);
    if (n > h.max_dev) {
      h.max_dev = n;
      h.t_max = smp.t;
    }
    h.max_change = std::max(h.max_change, (smp.dp - dp0).norm());
  }
  return h;
}

Json driveJson(const nc::DriveModel& d) {
  Json drive = Json::object();
  drive.set("servo", Json::str(d.servo == nc::ServoMode::kIdeal
                                   ? "ideal (no position_gain in the card)"
                                   : (d.integral ? "cascade P + PI" : "cascade P + P")));
  drive.set("stiffness_Nm_per_rad", Json::vector(d.k, -1));
  drive.set("motor_inertia_kgm2", Json::vector(d.motor_inertia, 4));
  drive.set("damping_Nms_per_rad", Json::vector(d.damping, 3));
  drive.set("position_gain_per_s", Json::vector(d.kv, 3));
  drive.set("velocity_gain_Nms_per_rad", Json::vector(d.kw, 3));
  return drive;
}

Json staticJson(const StaticReference& ref) {
  Json st = Json::object();
  st.set("gravity_only_um", Json::vector(ref.gravity_only.dp * 1e6, 4));
  st.set("full_engagement_um", Json::vector(ref.full_engagement.dp * 1e6, 4));
  st.set("full_engagement_rotation_urad", Json::vector(ref.full_engagement.drot * 1e6, 3));
  return st;
}

/// Band of the settling time (the static model's resolution goal), m.
constexpr double kSettlingTolerance = 0.1e-6;

/// Settling onto the static deviation of the constant load that ends the run: the held load of a
/// constant process (from the end of its ramp), gravity alone after the end of a drilling cut,
/// gravity alone for no process.
Json settlingJson(const nc::TransientResult& r, const StaticReference& ref,
                  const nc::ProcessCycle& cycle) {
  const double t_last = r.samples.empty() ? 0.0 : r.samples.back().t;
  Vec3 dp_ref = ref.gravity_only.dp;
  double t_from = 0.0;
  double t_to = t_last;
  std::string reference = "static deviation under gravity alone";
  if (const auto* step = dynamic_cast<const nc::StepWrenchCycle*>(&cycle)) {
    dp_ref = ref.full_engagement.dp;
    t_from = step->holdStart();
    t_to = std::min(t_last, step->holdEnd());
    reference = "static deviation under the held load (deflect model, same compliance)";
  } else if (const auto* drill = dynamic_cast<const nc::DrillingCycle*>(&cycle)) {
    t_from = drill->cutEnd() >= 0 ? drill->cutEnd() : t_last;
    reference += " after the end of the cut";
  }
  const nc::Settling st = nc::settling(r.samples, dp_ref, t_from, t_to, kSettlingTolerance);
  Json j = Json::object();
  j.set("reference", Json::str(reference));
  j.set("tolerance_um", Json::number(kSettlingTolerance * 1e6, 3));
  j.set("from_t_s", Json::number(t_from, 6));
  j.set("settled", Json::boolean(st.settled));
  if (st.settled) {
    j.set("settling_time_s", Json::number(st.time, 6));
  } else {
    j.set("settling_time_s", Json::str("not settled within the run (extend --duration)"));
  }
  j.set("initial_error_um", Json::number(st.initial_error * 1e6, 4));
  j.set("final_error_um", Json::number(st.final_error * 1e6, 4));
  j.set("frequency_hz", Json::number(st.frequency_hz, 3));
  j.set("equivalent_damping_ratio", Json::number(st.damping_ratio, 4));
  return j;
}

/// The damping the run used: an estimate, not a card value.
Json dampingJson() {
  Json j = Json::object();
  j.set("joint_damping_ratio", Json::number(nc::DriveEstimateOptions{}.damping_ratio, 4));
  j.set("source",
        Json::str("estimate (not in the robot card): D = 2 zeta sqrt(k J_eff) per joint, "
                  "docs/transient.md; the equivalent damping ratio of the settling is what this "
                  "estimate produces, not a measurement"));
  return j;
}

/// What the drilling cycle did with the real penetration.
void drillingJson(const nc::TransientResult& r, const nc::DrillingCycle& c, Json& tr) {
  double fa_max = 0.0;
  double t_fa = 0.0;
  double h_min_cut = std::numeric_limits<double>::infinity();
  double last_cut = -1.0;
  for (const nc::TransientSample& smp : r.samples) {
    if (smp.process.Fa > fa_max) {
      fa_max = smp.process.Fa;
      t_fa = smp.t;
    }
    if (smp.process.cutting) {
      last_cut = smp.t;
      if (smp.t > c.feedEndTime()) h_min_cut = std::min(h_min_cut, smp.process.feed_per_rev);
    }
  }
  if (c.firstContact() >= 0) {
    tr.set("first_contact_t_s", Json::number(c.firstContact(), 6));
  } else {
    tr.set("first_contact_t_s", Json::str("no contact within the run"));
  }
  tr.set("feed_end_t_s", Json::number(c.feedEndTime(), 6));
  if (c.cutEnd() >= 0) {
    tr.set("end_of_cut_t_s", Json::number(c.cutEnd(), 6));
  } else {
    tr.set("end_of_cut_t_s", Json::str(last_cut >= 0 ? "still cutting at the end of the run"
                                                     : "no cut within the run"));
  }
  tr.set("end_of_cut_rule",
         Json::str("through hole: the corner leaves the plate; blind: the real feed per rev falls "
                   "below " +
                   cFixed(c.cutEndFeed() * 1e3, 4) +
                   " mm/rev (cut_end_feed_fraction of the feed) during the dwell"));
  tr.set("max_thrust_N", Json::number(fa_max, 3));
  tr.set("max_thrust_t_s", Json::number(t_fa, 6));
  const double depth = r.samples.empty() ? 0.0 : r.samples.back().process.depth;
  tr.set("cut_depth_mm", Json::number(depth * 1e3, 4));
  tr.set("commanded_end_depth_mm", Json::number(c.endDepth() * 1e3, 4));
  if (std::isfinite(h_min_cut))
    tr.set("dwell_min_feed_mm_per_rev", Json::number(h_min_cut * 1e3, 5));
}

Json transientJson(const nc::TransientResult& r, const StaticReference& ref,
                   const nc::ProcessCycle& cycle) {
  const HistoryStats h = historyStats(r);
  Json tr = Json::object();
  if (h.last_full != nullptr) {
    tr.set("end_of_full_engagement_t_s", Json::number(h.last_full->t, 6));
    tr.set("end_of_full_engagement_um", Json::vector(h.last_full->dp * 1e6, 4));
    tr.set("difference_to_static_um",
           Json::number((h.last_full->dp - ref.full_engagement.dp).norm() * 1e6, 4));
  }
  tr.set("max_deviation_entry_um", Json::number(h.max_entry * 1e6, 4));
  tr.set("max_deviation_um", Json::number(h.max_dev * 1e6, 4));
  tr.set("max_deviation_t_s", Json::number(h.t_max, 6));
  tr.set("max_change_from_start_um", Json::number(h.max_change * 1e6, 4));
  if (const auto* drill = dynamic_cast<const nc::DrillingCycle*>(&cycle)) {
    drillingJson(r, *drill, tr);
  }
  tr.set("settling", settlingJson(r, ref, cycle));
  tr.set("damping", dampingJson());
  return tr;
}

Json cvodeJson(const nc::TransientResult& r, const nc::TransientOptions& opt, double t_end) {
  Json cv = Json::object();
  cv.set("ok", Json::boolean(r.ok));
  if (!r.ok) cv.set("message", Json::str(r.message));
  cv.set("method", Json::str(opt.method == nc::Method::kBdf ? "BDF" : "Adams-Moulton"));
  cv.set("rtol", Json::number(opt.rtol, -1));
  cv.set("t_end_s", Json::number(t_end, 6));
  cv.set("stopped_at_cycle_end", Json::boolean(opt.stop_at_cycle_end && r.t_reached < t_end));
  cv.set("t_reached_s", Json::number(r.t_reached, 6));
  cv.set("steps", Json::integer(r.stats.steps));
  cv.set("rhs_evaluations", Json::integer(r.stats.rhs_evals + r.stats.rhs_evals_jac));
  cv.set("rhs_evaluations_jacobian", Json::integer(r.stats.rhs_evals_jac));
  cv.set("jacobian_evaluations", Json::integer(r.stats.jac_evals));
  cv.set("error_test_failures", Json::integer(r.stats.error_test_failures));
  cv.set("restarts", Json::integer(r.stats.restarts));
  cv.set("events", Json::integer(r.stats.events));
  return cv;
}

}  // namespace

SimulationResult simulateAt(const RobotSetup& setup, const HoleJoints& at,
                            const SimulateOptions& options) {
  if (!setup.cell) throw UsageError("a simulation needs a cell (robot, tool and process)");
  requireWithinLimits(setup.robot.chain, at.joints, "joints");
  const nc::Model model = nc::buildModel(setup.robot.real_chain, setup.tool);
  nc::Data data(model);
  const nc::TransientProblem p = transientProblem(setup, model, data, at.joints, options);

  std::optional<ProcessSpec> spec;
  std::unique_ptr<nc::ProcessCycle> cycle;
  std::string drill;  // the drill of the hole, as the summary names it
  if (setup.cell->has_process) {
    spec = parseProcess(setup.cell->process);
    if (spec->type == ProcessType::kDrilling) {
      const HoleProcessChoice& h = at.process;
      drill = drillLabel(spec->drills[static_cast<size_t>(std::max(h.drill, 0))]);
      spec->drilling = holeDrilling(*spec, h.drill, h.diameter, h.depth, h.feed, h.spindle_rpm);
    }
    cycle = nc::makeProcessCycle(*spec, {}, options.runout);
  } else {
    cycle = std::make_unique<nc::NoProcess>(0.5);
  }
  nc::TransientOptions opt;
  if (options.adams) opt.method = nc::Method::kAdams;
  if (options.rtol > 0) opt.rtol = options.rtol;
  opt.sample = options.sample;
  opt.stop_at_cycle_end = !(options.duration > 0);  // the cycle ends with the cut + retract
  const double t_end = options.duration > 0 ? options.duration : cycle->duration();

  SimulationResult r;
  r.transient = nc::simulateCycle(p, *cycle, opt, t_end);
  const StaticReference ref = staticReference(model, data, p, spec);

  Json& root = r.summary = Json::object();
  root.set("robot", Json::str(setup.robot.card.name));
  root.set("cell", Json::str(setup.cell->name));
  root.set("joints_deg", Json::vector(at.joints / kDeg, 6));
  root.set("joints_source", Json::str(at.source));
  root.set("process",
           Json::str(spec ? steadyProcessLoad(*spec).description : "none (gravity only)"));
  if (spec && spec->type == ProcessType::kDrilling && !at.process.source.empty())
    root.set("process_source", Json::str(at.process.source + ": " + drill));
  root.set("gravity_handling",
           gravityHandlingJson(setup.robot, controllerReferenceOf(setup.robot, &*setup.cell,
                                                                  setup.tool, options.gravity)));
  root.set("drive", driveJson(p.drive));
  root.set("static", staticJson(ref));
  root.set("transient", transientJson(r.transient, ref, *cycle));
  root.set("cvode", cvodeJson(r.transient, opt, t_end));
  return r;
}

namespace {

/// Fixed-point text with `decimals` decimals in the "C" locale; no "-0" ("nan"/"inf" as cFixed).
std::string fmt(int decimals, double v) {
  if (!std::isfinite(v)) return cFixed(v, decimals);
  std::string s;
  appendFixed(s, v, decimals);
  return s;
}

}  // namespace

std::string transientHistoryCsv(const nc::TransientResult& r) {
  std::string out =
      "t_s,depth_mm,Fa_N,Ft_N,M_Nm,Fr_N,dx_um,dy_um,dz_um,rx_urad,ry_urad,rz_urad,"
      "dq1_urad,dq2_urad,dq3_urad,dq4_urad,dq5_urad,dq6_urad,tip_mm,cut_depth_mm,"
      "feed_per_rev_mm,axial_um,phase\n";
  out.reserve(r.samples.size() * 200 + out.size());
  const nc::Vec6 q0 = r.samples.empty() ? nc::Vec6::Zero() : nc::Vec6(r.samples.front().theta_m);
  for (const nc::TransientSample& s : r.samples) {
    const double commanded = std::max(0.0, s.process.feed_position);
    out += fmt(6, s.t) + ',' + fmt(6, commanded * 1e3) + ',' + fmt(3, s.process.Fa) + ',' +
           fmt(3, s.process.Ft) + ',' + fmt(4, s.process.M) + ',' + fmt(3, s.process.Fr);
    for (int i = 0; i < 3; ++i) out += ',' + fmt(4, s.dp[i] * 1e6);
    for (int i = 0; i < 3; ++i) out += ',' + fmt(3, s.drot[i] * 1e6);
    for (int i = 0; i < 6; ++i) out += ',' + fmt(3, (s.theta[i] - q0[i]) * 1e6);
    out += ',' + fmt(6, s.process.tip * 1e3) + ',' + fmt(6, s.process.depth * 1e3) + ',' +
           fmt(6, s.process.feed_per_rev * 1e3) + ',' + fmt(4, s.process.axial * 1e6);
    out += ',';
    out += nc::phaseName(s.process.phase);
    out += '\n';
  }
  return out;
}

}  // namespace roprec::api
