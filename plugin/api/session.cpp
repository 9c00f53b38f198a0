/// Session: a cell loaded once, targets filtered and joints predicted one at a time
/// (plugin/api/session.hpp).
#include <optional>
#include <utility>

#include "plugin/api/job.hpp"
#include "plugin/api/robot_setup.hpp"

namespace roprec::api {

struct Session::Impl {
  PredictionContext context;
  CompensationOptions keep;            ///< orientation kept, positions compensated
  std::optional<PredictionData> data;  ///< scratch kept between calls
  HoleRequest request;                 ///< the call's request (its strings' storage kept)
  HoleCompensation compensation;       ///< the call's result (its strings' storage kept)
  std::string first_tool;  ///< a single-drill cell: the tool the host named first ("" none)

  /// Sets the process of `request` from `p` (the cell's where unset) and builds it into the
  /// model when it is new. Throws InputError for a tool or value the cell refuses.
  void setProcess(const HoleProcess& p);
  [[nodiscard]] ProcessUsed used(const HolePrediction& h, const HoleProcess& asked) const;
};

namespace {

/// Where a host call's process errors point: the cell file at its <process>.
[[noreturn]] void refuse(const PredictionContext& c, const std::string& what) {
  throw InputError(c.cell.file, c.process ? c.process->line : 0, what);
}

}  // namespace

void Session::Impl::setProcess(const HoleProcess& p) {
  HoleRequest& r = request;
  r.drill = -1;
  r.tool.clear();
  r.diameter = p.diameter;
  r.depth = p.depth;
  r.feed = p.feed;
  r.spindle_rpm = p.spindle_rpm;
  const bool drilling = context.process && context.process->type == ProcessType::kDrilling;
  if (!drilling) return;  // the process has no drill: its load whatever the hole
  const ProcessSpec& spec = *context.process;
  if (!p.tool.empty()) {
    r.drill = drillIndex(spec, p.tool);
    if (r.drill < 0 && spec.drills.size() > 1) {
      std::string tools;
      for (const DrillingSpec& d : spec.drills) tools += (tools.empty() ? "" : ", ") + d.tool;
      refuse(context, "tool '" + p.tool + "' is not in the cell's tool table (tools: " + tools +
                          "); hint: add <drill tool=\"" + p.tool + "\" .../> to its <process>");
    }
    if (r.drill < 0) {  // a single drill: it drills whatever tool the host names, one tool only
      if (!first_tool.empty() && !sameToolKey(first_tool, p.tool)) {
        refuse(context,
               "the host changes tools (" + first_tool + ", then " + p.tool +
                   ") but the cell has a single drill; hint: give the cell a tool "
                   "table, one <drill tool=\"n\" .../> per tool (docs/process.md §8, tool table)");
      }
      first_tool = p.tool;
      r.drill = 0;
    }
    r.tool = spec.drills[static_cast<size_t>(r.drill)].tool;
  }
  const DrillingSpec& d = spec.drills[static_cast<size_t>(std::max(r.drill, 0))];
  const double diameter = p.diameter > 0 ? p.diameter : d.geometry.diameter;
  const double feed = p.feed > 0 ? p.feed : d.feed;
  if (!(diameter >= 0.1e-3 && diameter <= 100e-3))
    refuse(context, "hole diameter " + numberText(diameter * 1e3) + " mm is outside 0.1 .. 100 mm");
  if (p.spindle_rpm > 0 && !(p.spindle_rpm >= 10 && p.spindle_rpm <= 100000))
    refuse(context,
           "spindle speed " + numberText(p.spindle_rpm) + " 1/min is outside 10 .. 100000");
  if (feed > 0.1 * diameter * (1 + 1e-12)) {
    refuse(context, "feed " + numberText(feed * 1e3) + " mm/rev is too large for a " +
                        numberText(diameter * 1e3) + " mm hole (feed <= 0.1 Dc)");
  }
  addHoleProcess(context.model, r);
}

ProcessUsed Session::Impl::used(const HolePrediction& h, const HoleProcess& asked) const {
  ProcessUsed u;
  u.diameter = h.diameter;
  u.depth = h.depth;
  u.feed = h.feed;
  u.spindle_rpm = h.spindle_rpm;
  u.from_cell = asked.tool.empty() && asked.diameter <= 0 && asked.depth <= 0 && asked.feed <= 0 &&
                asked.spindle_rpm <= 0;
  if (context.process && context.process->type == ProcessType::kDrilling) {
    const DrillingSpec& d = context.process->drills[static_cast<size_t>(h.drill)];
    u.tool = d.tool;
    u.drill = drillLabel(d);
  }
  return u;
}

Session::Session(const std::string& cell_path) : impl_(new Impl) {
  try {
    impl_->context = loadPredictionContext(cell_path, "", std::nullopt, "", 0.5, false);
    impl_->data.emplace(impl_->context.model);
    impl_->request.id = "target";
  } catch (...) {
    delete impl_;
    throw;
  }
}

Session::~Session() { delete impl_; }

const PredictionContext& Session::context() const { return impl_->context; }

Session::Filtered Session::filterTarget(const Pose& T_W_wanted, const Vec6* seed_controller,
                                        const HoleProcess& process, bool with_prediction) {
  Impl& s = *impl_;
  const PredictionModel& m = s.context.model;
  s.setProcess(process);
  HoleRequest& req = s.request;
  req.T_W_tcp =
      s.context.cell.part_registration ? partMotion(s.context.cell) * T_W_wanted : T_W_wanted;
  req.ik_seed.reset();
  if (seed_controller) req.ik_seed = fromControllerJoints(m.robot.card, *seed_controller);
  HoleCompensation& h = s.compensation;
  compensateTarget(m, *s.data, req, s.keep,
                   with_prediction ? TargetBudgets::kBoth : TargetBudgets::kNone, h);
  Filtered f;
  f.before = h.before;
  f.process = s.used(h.before, process);
  if (!h.ok) {
    f.reason = h.reason;
    return f;
  }
  f.ok = true;
  f.T_programmed = h.T_programmed;
  f.joints_controller = toControllerJoints(m.robot.card, h.theta_cmd);
  f.config = h.config_text;
  f.residual = h.residual.norm();
  return f;
}

std::vector<Session::Filtered> Session::filterTargets(std::span<const Pose> T_W_wanted,
                                                      std::span<const Vec6> seeds_controller,
                                                      std::span<const HoleProcess> processes) {
  if (!seeds_controller.empty() && seeds_controller.size() != T_W_wanted.size())
    throw UsageError("filterTargets: give no seeds or one per target");
  if (!processes.empty() && processes.size() != T_W_wanted.size())
    throw UsageError("filterTargets: give no processes or one per target");
  const PredictionModel& m = impl_->context.model;
  std::vector<Filtered> out;
  out.reserve(T_W_wanted.size());
  std::optional<Vec6> previous;  // the last admissible IK choice (URDF convention): continuity
  const HoleProcess none;
  for (size_t i = 0; i < T_W_wanted.size(); ++i) {
    std::optional<Vec6> seed;
    if (!seeds_controller.empty())
      seed = seeds_controller[i];
    else if (previous)
      seed = toControllerJoints(m.robot.card, *previous);
    out.push_back(filterTarget(T_W_wanted[i], seed ? &*seed : nullptr,
                               processes.empty() ? none : processes[i]));
    if (out.back().before.status == HoleStatus::kOk) previous = out.back().before.joints;
  }
  return out;
}

Session::JointPrediction Session::predictJoints(const Vec6& joints_controller,
                                                const HoleProcess& process) {
  Impl& s = *impl_;
  const PredictionModel& m = s.context.model;
  JointPrediction p;
  const Vec6 q = fromControllerJoints(m.robot.card, joints_controller);
  requireWithinLimits(m.robot.chain, q,
                      "joints_deg");  // as the CLI: bad input, not an item failure
  s.setProcess(process);
  // the pose the controller means by these joints (FK_nom; the real one without a calibration)
  PredictionData& d = *s.data;
  HoleRequest& req = s.request;
  const nc::PositionResult pr = nc::forwardKinematics(controllerModel(modelFor(m, req)), d.nc, q);
  if (!pr.converged) {
    p.reason = "the position problem did not converge at these joints";
    return p;
  }
  req.T_W_tcp = d.nc.T_W_tcp;
  req.ik_seed = q;  // the commanded joints select their own IK solution
  predictHole(m, d, req, &q, p.prediction);
  p.process = s.used(p.prediction, process);
  if (p.prediction.status != HoleStatus::kOk) {
    p.reason = p.prediction.reason;
    return p;
  }
  if ((p.prediction.joints - q).lpNorm<Eigen::Infinity>() > 1e-6) {
    p.reason =
        "these joints are not an admissible solution (joint limits or a singular wrist/shoulder)";
    return p;
  }
  p.ok = true;
  p.d_translation = p.prediction.d_robot;
  p.d_rotation = p.prediction.d_rot;
  p.U_work = p.prediction.U_work_exact;
  return p;
}

}  // namespace roprec::api
