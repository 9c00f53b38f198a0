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
  r.static_reference = staticReference(model, data, p, spec);

  r.process = spec ? steadyProcessLoad(*spec).description : "none (gravity only)";
  if (spec && spec->type == ProcessType::kDrilling && !at.process.source.empty())
    r.process_source = at.process.source + ": " + drill;
  r.controller = controllerReferenceOf(setup.robot, &*setup.cell, setup.tool, options.gravity);
  r.drive = p.drive;
  r.options = opt;
  r.t_end = t_end;
  r.cycle = std::move(cycle);
  return r;
}

}  // namespace roprec::api
