/// `roprec simulate`: transient of one drilling cycle at one hole (CVODE, compensator/robot/transient.hpp):
/// CSV time history of the process forces and the TCP deviation, JSON summary.
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "compensator/robot/configuration.hpp"
#include "compensator/support/error.hpp"
#include "compensator/robot/ik.hpp"
#include "compensator/process/process_load.hpp"
#include "compensator/robot/transient.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/api/json.hpp"
#include "plugin/api/robot_compliance.hpp"
#include "plugin/cli/robot_options.hpp"
#include "postproc/drill.hpp"
#include "postproc/program.hpp"

namespace roprec::cli {
namespace {

struct HoleCommand {
  nc::Vec6 q{nc::Vec6::Zero()};
  std::string source;  ///< how the joints were obtained
};

/// Joints of hole `id` of a program (any dialect, incl. the hole-list CSV): the drill point
/// (bottom target) of the recognised hole; its frame from the program when resolved, else the
/// cell's work object; the cell's tool; IK with the target's configuration flags when it states
/// them, else the in-limit, non-singular solution nearest the vendor reference pose.
/// Joints for a TCP pose in the base frame: IK nearest the vendor reference pose.
nc::Vec6 jointsNearReference(const RobotSetup& s, const Pose& T_base_tcp, const std::string& file, int line,
                             const std::string& id, int& exit_code) {
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
    if (!sol.converged || !sol.within_limits || sol.singular_wrist || sol.singular_shoulder || sol.singular_elbow) continue;
    const double d = (sol.q - ref).norm();
    if (d < best_d) {
      best_d = d;
      best = i;
    }
  }
  if (best < 0) {
    exit_code = 1;
    throw InputError(file, line,
                     "hole '" + id + "' is not reachable: " + (res.count == 0 ? describeIkFailure(res) : "no regular in-limit IK solution"));
  }
  return res.solutions[static_cast<size_t>(best)].q;
}

HoleCommand holeJoints(const std::string& path, const std::string& id, const RobotSetup& s, int& exit_code) {
  const postproc::Program prog = postproc::readProgram(path);
  HoleCommand hc;
  if (prog.dialect == postproc::Dialect::kHoleCsv) {
    // contract hole list: position and drilling direction in the cell's work object; the
    // rotation about the drill axis is free: tool x = base x projected ⊥ the axis (else base y)
    for (const postproc::HoleSpec& h : postproc::readHoleList(path)) {
      if (h.id != id) continue;
      const Vec3 z = s.cell->T_base_wobj.linear() * h.direction.normalized();
      Vec3 x = Vec3::UnitX() - Vec3::UnitX().dot(z) * z;
      if (x.norm() < 1e-6) x = Vec3::UnitY() - Vec3::UnitY().dot(z) * z;
      x.normalize();
      Pose T = Pose::Identity();
      T.linear() << x, z.cross(x), z;
      T.translation() = s.cell->T_base_wobj * (h.position_mm * 1e-3);
      hc.q = jointsNearReference(s, T, path, h.line, id, exit_code);
      hc.source = "hole list row " + std::to_string(h.line) + " (cell workobject, IK solution nearest the reference pose)";
      return hc;
    }
    throw InputError(path, 0, "no hole '" + id + "' in the hole list");
  }
  const std::vector<postproc::Hole> holes = postproc::recognizeHoles(prog);
  const postproc::Hole* hole = nullptr;
  std::string names;
  for (const postproc::Hole& h : holes) {
    names += (names.empty() ? "" : ", ") + h.id;
    if (h.id == id) hole = &h;
  }
  if (hole == nullptr) {
    throw InputError(path, 0, "no recognised hole '" + id + "' (holes: " + (names.empty() ? "none" : names) + ")");
  }
  const postproc::Target& t = prog.targets()[static_cast<size_t>(hole->bottom_target)];
  const std::string tfile = t.file >= 0 ? prog.files[static_cast<size_t>(t.file)].path : path;
  if (t.kind == postproc::TargetKind::kJoint) {
    const std::vector<double> j = postproc::targetJointsDeg(t);
    if (j.size() < 6) throw InputError(tfile, t.line, "joint target of hole '" + id + "' has fewer than 6 axes");
    nc::Vec6 qc;
    for (int i = 0; i < 6; ++i) qc[i] = j[static_cast<size_t>(i)] * kDeg;
    hc.q = fromControllerJoints(s.robot.card, qc);
    hc.source = "joint target " + t.name;
    return hc;
  }
  const std::optional<Pose> pose = postproc::motionPose(prog, prog.motions[static_cast<size_t>(hole->bottom_motion)]);
  if (!pose) throw InputError(tfile, t.line, "the drill point of hole '" + id + "' has no Cartesian pose");
  Pose T_base_frame = s.cell->T_base_wobj;
  std::string frame = "cell workobject";
  if (hole->base >= 0 && prog.frames[static_cast<size_t>(hole->base)].resolved) {
    T_base_frame = prog.frames[static_cast<size_t>(hole->base)].pose;
    frame = "program frame " + prog.frames[static_cast<size_t>(hole->base)].ref;
  }
  const Pose T_base_flange = T_base_frame * *pose * s.tool.T_flange_tcp.inverse();
  const IkModel ik = buildIkModel(s.robot);
  if (t.config.present()) {
    const VendorConfig vc = parseConfig(s.robot.card.vendor, t.config.text(), tfile, t.line);
    const ConfiguredSolution cs = solveIkWithConfiguration(ik, s.robot.card, T_base_flange, vc);
    if (!cs.found) {
      exit_code = 1;
      throw InputError(tfile, t.line, "hole '" + id + "' is not reachable with configuration " + t.config.text() + ": " + cs.reason);
    }
    hc.q = cs.solution.q;
    hc.source = "target " + t.name + " (" + frame + ", configuration " + t.config.text() + ")";
    return hc;
  }
  hc.q = jointsNearReference(s, T_base_frame * *pose, tfile, t.line, id, exit_code);
  hc.source = "target " + t.name + " (" + frame + ", IK solution nearest the reference pose)";
  return hc;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v == 0.0 ? 0.0 : v);  // no "-0"
  return buf;
}

std::string historyCsv(const nc::TransientResult& r) {
  std::string out =
      "t_s,depth_mm,Fa_N,Ft_N,M_Nm,Fr_N,dx_um,dy_um,dz_um,rx_urad,ry_urad,rz_urad,"
      "dq1_urad,dq2_urad,dq3_urad,dq4_urad,dq5_urad,dq6_urad,phase\n";
  out.reserve(r.samples.size() * 200 + out.size());
  const nc::Vec6 q0 = r.samples.empty() ? nc::Vec6::Zero() : nc::Vec6(r.samples.front().theta_m);
  for (const nc::TransientSample& s : r.samples) {
    out += fmt("%.6f", s.t) + ',' + fmt("%.6f", s.process.depth * 1e3) + ',' + fmt("%.3f", s.process.Fa) + ',' +
           fmt("%.3f", s.process.Ft) + ',' + fmt("%.4f", s.process.M) + ',' + fmt("%.3f", s.process.Fr);
    for (int i = 0; i < 3; ++i) out += ',' + fmt("%.4f", s.dp[i] * 1e6);
    for (int i = 0; i < 3; ++i) out += ',' + fmt("%.3f", s.drot[i] * 1e6);
    for (int i = 0; i < 6; ++i) out += ',' + fmt("%.3f", (s.theta[i] - q0[i]) * 1e6);
    out += ',';
    out += nc::phaseName(s.process.phase);
    out += '\n';
  }
  return out;
}

int run(Args& args, CommandContext& ctx) {
  RobotSetup s = loadRobotSetup(args);
  const auto joints = args.option("joints");
  const auto hole = args.option("hole");
  const auto out = args.option("o");
  const auto summary_path = args.option("summary");
  const auto duration_text = args.option("duration");
  const auto sample_text = args.option("sample-ms");
  const auto rtol_text = args.option("rtol");
  const bool bdf = args.flag("bdf");
  const bool runout = args.flag("runout");
  const bool no_integral = args.flag("no-integral");
  const bool no_gravity = args.flag("no-gravity");
  const std::vector<std::string> pos = args.positionals();
  args.finish();
  if (!s.cell) throw UsageError("simulate needs --cell CELL.xml (robot, tool and process)");
  if (joints && hole) throw UsageError("give either --joints or --hole ID PROGRAM, not both");
  if (!joints && !hole) throw UsageError("give --hole ID PROGRAM or --joints \"j1 .. j6\"");
  if (hole && pos.size() != 1) throw UsageError("--hole ID needs exactly one PROGRAM");
  if (joints && !pos.empty()) throw UsageError("unexpected argument '" + pos.front() + "' with --joints");
  auto positive = [](const std::optional<std::string>& t, const char* what, double def) {
    if (!t) return def;
    const double v = parseNumberList(*t, 1, what)[0];
    if (!(v > 0)) throw UsageError(std::string(what) + " must be > 0");
    return v;
  };
  const double duration = positive(duration_text, "--duration (s)", -1.0);
  const double sample = positive(sample_text, "--sample-ms", 1.0) * 1e-3;
  const double rtol = positive(rtol_text, "--rtol", 1e-8);

  int exit_code = 0;
  HoleCommand hc;
  if (joints) {
    hc.q = parseJointsDeg(*joints);
    hc.source = "--joints";
  } else {
    try {
      hc = holeJoints(pos[0], *hole, s, exit_code);
    } catch (const InputError& e) {
      if (exit_code != 1) throw;
      ctx.err << "roprec: " << formatInputError(e) << "\n";
      return 1;
    }
  }
  const auto viol = limitViolations(s.robot.chain, hc.q);
  if (!viol.empty()) throw InputError("", 0, "joints outside the joint limits: " + viol.front());

  const nc::Model model = nc::buildModel(s.robot.chain, s.tool);
  nc::Data data(model);
  nc::DriveEstimateOptions est;
  est.integral = !no_integral;
  nc::TransientProblem p;
  p.model = &model;
  p.drive = nc::driveModelFromCard(s.robot.card, model, data, hc.q, est);
  p.theta_cmd = hc.q;
  p.gravity = !no_gravity;
  p.command_offset = no_gravity ? nc::Vec6::Zero() : controllerGravityOffset(s.robot, p.drive.staticCompliance(), hc.q);

  std::unique_ptr<nc::ProcessCycle> cycle;
  std::optional<ProcessSpec> spec;
  if (s.cell->has_process) {
    spec = parseProcess(s.cell->process);
    cycle = nc::makeProcessCycle(*spec, {}, runout);
  } else {
    cycle = std::make_unique<nc::NoProcess>(0.5);
  }
  nc::TransientOptions opt;
  opt.method = bdf ? nc::Method::kBdf : nc::Method::kAdams;
  opt.rtol = rtol;
  opt.sample = sample;
  const double t_end = duration > 0 ? duration : cycle->duration();
  const nc::TransientResult r = nc::simulateCycle(p, *cycle, opt, t_end);

  // static references (the deflect model: same compliance, load at full engagement)
  nc::Loads gl;
  gl.gravity = p.gravity;
  const nc::Deflection d_gravity = nc::predictDeflection(model, data, p.drive.staticCompliance(), hc.q, gl, {}, p.command_offset);
  nc::Loads fl = gl;
  if (spec) {
    const SteadyProcessLoad pl = steadyProcessLoad(*spec);
    fl.tcp_tool.force = pl.wrench.force;
    fl.tcp_tool.moment = pl.wrench.torque;
  }
  const nc::Deflection d_full = nc::predictDeflection(model, data, p.drive.staticCompliance(), hc.q, fl, {}, p.command_offset);

  const nc::TransientSample* last_full = nullptr;
  double max_entry = 0.0;
  double max_dev = 0.0;
  double t_max = 0.0;
  double max_change = 0.0;
  const Vec3 dp0 = r.samples.empty() ? Vec3::Zero() : r.samples.front().dp;
  for (const nc::TransientSample& smp : r.samples) {
    const double n = smp.dp.norm();
    if (smp.process.phase == nc::CyclePhase::kFull) last_full = &smp;
    if (smp.process.phase == nc::CyclePhase::kEntry) max_entry = std::max(max_entry, n);
    if (n > max_dev) {
      max_dev = n;
      t_max = smp.t;
    }
    max_change = std::max(max_change, (smp.dp - dp0).norm());
  }

  Json root = Json::object();
  root.set("robot", Json::str(s.robot.card.name));
  root.set("cell", Json::str(s.cell->name));
  root.set("joints_deg", Json::vector(hc.q / kDeg, 6));
  root.set("joints_source", Json::str(hc.source));
  root.set("process", Json::str(spec ? steadyProcessLoad(*spec).description : "none (gravity only)"));
  Json drive = Json::object();
  drive.set("servo", Json::str(p.drive.servo == nc::ServoMode::kIdeal ? "ideal (no position_gain in the card)"
                                                                      : (p.drive.integral ? "cascade P + PI" : "cascade P + P")));
  drive.set("stiffness_Nm_per_rad", Json::vector(p.drive.k, -1));
  drive.set("motor_inertia_kgm2", Json::vector(p.drive.motor_inertia, 4));
  drive.set("damping_Nms_per_rad", Json::vector(p.drive.damping, 3));
  drive.set("position_gain_per_s", Json::vector(p.drive.kv, 3));
  drive.set("velocity_gain_Nms_per_rad", Json::vector(p.drive.kw, 3));
  root.set("drive", drive);
  Json st = Json::object();
  st.set("gravity_only_um", Json::vector(d_gravity.dp * 1e6, 4));
  st.set("full_engagement_um", Json::vector(d_full.dp * 1e6, 4));
  st.set("full_engagement_rotation_urad", Json::vector(d_full.drot * 1e6, 3));
  root.set("static", st);
  Json tr = Json::object();
  if (last_full != nullptr) {
    tr.set("end_of_full_engagement_t_s", Json::number(last_full->t, 6));
    tr.set("end_of_full_engagement_um", Json::vector(last_full->dp * 1e6, 4));
    tr.set("difference_to_static_um", Json::number((last_full->dp - d_full.dp).norm() * 1e6, 4));
  }
  tr.set("max_deviation_entry_um", Json::number(max_entry * 1e6, 4));
  tr.set("max_deviation_um", Json::number(max_dev * 1e6, 4));
  tr.set("max_deviation_t_s", Json::number(t_max, 6));
  tr.set("max_change_from_start_um", Json::number(max_change * 1e6, 4));
  root.set("transient", tr);
  Json cv = Json::object();
  cv.set("ok", Json::boolean(r.ok));
  if (!r.ok) cv.set("message", Json::str(r.message));
  cv.set("method", Json::str(bdf ? "BDF" : "Adams-Moulton"));
  cv.set("rtol", Json::number(opt.rtol, -1));
  cv.set("t_end_s", Json::number(t_end, 6));
  cv.set("t_reached_s", Json::number(r.t_reached, 6));
  cv.set("steps", Json::integer(r.stats.steps));
  cv.set("rhs_evaluations", Json::integer(r.stats.rhs_evals + r.stats.rhs_evals_jac));
  cv.set("rhs_evaluations_jacobian", Json::integer(r.stats.rhs_evals_jac));
  cv.set("jacobian_evaluations", Json::integer(r.stats.jac_evals));
  cv.set("error_test_failures", Json::integer(r.stats.error_test_failures));
  cv.set("restarts", Json::integer(r.stats.restarts));
  root.set("cvode", cv);

  emit(ctx, out.value_or("-"), historyCsv(r));
  if (summary_path) {
    emit(ctx, *summary_path, root.dump());
  } else {
    ctx.err << root.dump();
  }
  if (!r.ok) {
    ctx.err << "roprec: the transient stopped at t = " << r.t_reached << " s: " << r.message << "\n";
    return 1;
  }
  return exit_code;
}

const CommandRegistration reg{
    {"simulate", "transient drilling cycle at one hole (flexible joints + servo, CVODE)",
     "usage: roprec simulate --cell CELL.xml (--hole ID PROGRAM | --joints \"j1 .. j6\")\n"
     "                       [-o OUT.csv] [--summary F.json] [--duration S] [--bdf] [--runout]\n"
     "                       [--no-integral] [--no-gravity] [--sample-ms MS] [--rtol R] [--stiffness \"k1 .. k6\"]\n\n"
     "Integrates the flexible-joint robot under its cascade servo (position gain from the card,\n"
     "velocity PI estimated when absent) along the cell's process cycle: approach, progressive entry,\n"
     "full engagement, breakthrough, dwell, retract (drilling); a ramped step (wrench, milling).\n"
     "The arm holds the hole pose; only the process load varies. CVODE Adams-Moulton (--bdf: BDF).\n"
     "CSV (default stdout): t_s, depth_mm, Fa_N, Ft_N, M_Nm, Fr_N, dx_um, dy_um, dz_um (TCP deviation from\n"
     "the nominal rigid TCP, base frame), rx/ry/rz_urad, dq1..dq6_urad (link angle − command), phase.\n"
     "JSON summary (stderr or --summary): static deviation (as deflect), deviation at the end of full\n"
     "engagement, maximum during entry, CVODE statistics. docs/transient.md has the model.\n"
     "--runout: apply the rotating residual force Fr at spindle frequency. --no-integral: velocity loop\n"
     "without integral action (steady state = static model with k_servo = Kv·Kω).\n"
     "Exit 1 if the hole is unreachable or the integration fails, 2 for bad input.\n",
     35, run}};

}  // namespace
}  // namespace roprec::cli
