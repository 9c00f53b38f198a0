#include "plugin/api/prediction_setup.hpp"

#include <cmath>
#include <cstdint>
#include <ostream>

#include "compensator/process/process_load.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/input_file.hpp"
#include "plugin/api/card_tools.hpp"
#include "plugin/api/robot_compliance.hpp"
#include "plugin/api/robot_setup.hpp"

namespace roprec::api {

namespace {

UncertaintyInputs uncertaintyFromCell(const CellSpec& cell) {
  UncertaintyInputs u = defaultUncertaintyInputs();
  if (const XmlNode* e = cell.root.child("uncertainty")) {
    const std::string method = e->str("method", "linear");
    if (method == "linear") {
      u.method = UncertaintyInputs::Method::kLinear;
    } else if (method == "montecarlo") {
      u.method = UncertaintyInputs::Method::kMonteCarlo;
    } else {
      e->fail("<uncertainty> method must be linear or montecarlo, got '" + method + "'");
    }
    u.stiffness_rel = e->number("stiffness_rel", u.stiffness_rel);
    u.position_gain_rel = e->number("position_gain_rel", u.position_gain_rel);
    u.process_halfwidth = e->number("process_halfwidth", u.process_halfwidth);
    // below 1 % a budget term claims a model known better than any identification gives it
    // (and 0 would silently drop the term)
    for (const char* a : {"stiffness_rel", "position_gain_rel", "process_halfwidth"}) {
      const double v = e->number(a, 0.1);
      if (!(v >= 0.01 && v <= 1)) {
        e->fail(std::string("<uncertainty> ") + a + " = " + numberText(v) +
                " must lie in [0.01, 1] (a relative standard uncertainty; below 1 % no robot "
                "model is known)");
      }
    }
    const double samples = e->number("samples", u.samples);
    if (!(samples >= 10 && samples <= 1e6 && samples == std::floor(samples)))
      e->fail("<uncertainty> samples must be an integer in [10, 1e6], got " + e->str("samples"));
    u.samples = static_cast<int>(samples);
    const double seed = e->number("seed", u.seed);
    if (!(seed >= 0 && seed <= 4294967295.0 && seed == std::floor(seed)))
      e->fail("<uncertainty> seed must be an integer in [0, 4294967295], got " + e->str("seed"));
    u.seed = static_cast<unsigned>(seed);
    if (e->has("source")) u.source = e->str("source");
  }
  return u;
}

CapabilityInputs capabilityFromCell(const CellSpec& cell) {
  CapabilityInputs c;
  c.source =
      "estimate: machining-center positioning, approach and retract per hole (rapid ~40 m/min, ~2 "
      "s)";
  if (const XmlNode* e = cell.root.child("capability")) {
    c.mc_approach_s = e->number("mc_approach_s", c.mc_approach_s);
    if (!(c.mc_approach_s >= 0 && c.mc_approach_s <= 3600))
      e->fail("<capability> mc_approach_s must lie in [0, 3600] s, got " + e->str("mc_approach_s"));
    if (e->has("source")) c.source = e->str("source");
  }
  return c;
}

/// The budget's absolute-accuracy term (AccuracyInputs): the cell's controller option
/// (<absolute_accuracy>), else the card's <calibration> σ, else the card's <accuracy>; the cell's
/// registration σ (<workobject sigma_mm>) in every case.
AccuracyInputs accuracyFromCell(const CellSpec& cell, const RobotCard& card) {
  constexpr double kMaxwell95 = 2.7955;  // P(|e| <= 2.7955 σ) = 0.95 for an isotropic 3-D normal
  AccuracyInputs a;
  if (const XmlNode* w = cell.root.child("workobject"))
    a.registration_sigma = w->number("sigma_mm", 0.0) * 1e-3;
  std::string registration;
  if (a.registration_sigma > 0) {
    const XmlNode* w = cell.root.child("workobject");
    registration = "; + registration σ " + w->str("sigma_mm") + " mm (" +
                   w->str("sigma_source", "cell <workobject sigma_mm>") + ")";
  }
  if (const XmlNode* e = cell.root.child("absolute_accuracy")) {
    a.kind = AccuracyInputs::Kind::kControllerOption;
    a.u = e->number("ap_mm") * 1e-3 / kMaxwell95;
    a.source = "controller absolute-accuracy option, AP " + e->str("ap_mm") + " mm / 2.7955 (" +
               e->str("source") + ")";
  } else if (card.calibration) {
    a.kind = AccuracyInputs::Kind::kCalibrated;
    a.source =
        std::string(card.calibration->covariance_parameters.empty() ? "calibration σ (independent)"
                                                                    : "calibration covariance") +
        " through the FK Jacobian" +
        (card.calibration->model_error > 0
             ? " + model error " + numberText(card.calibration->model_error * 1e3) + " mm"
             : std::string()) +
        " (" + card.calibration->source + ")";
  } else if (card.accuracy_ap_mm > 0) {
    a.kind = AccuracyInputs::Kind::kDataSheet;
    a.u = card.accuracy_ap_mm * 1e-3 / kMaxwell95;
    a.source = "uncalibrated, AP " + numberText(card.accuracy_ap_mm) + " mm / 2.7955 (" +
               card.accuracy_source + ")";
  } else if (a.registration_sigma > 0) {
    a.source = "registration only";
  }
  a.source += registration;
  return a;
}

}  // namespace

std::vector<std::optional<DrillTool>> drillToolsOf(const CellSpec& cell, const RobotCard& card) {
  std::vector<std::optional<DrillTool>> out;
  for (const std::optional<ToolSpec>& t : cell.drill_tools) {
    if (!t) {
      out.emplace_back();
      continue;
    }
    ToolSpec own = *t;
    CellSpec with = cell;
    with.tool = own;
    DrillTool d;
    d.tool = toolOf(with);
    d.calibration_load = controllerGravityOf(card, &cell, d.tool).calibration_load;
    out.emplace_back(d);
  }
  return out;
}

namespace {

/// Everything of the prediction model's setup that comes from the cell and the command line
/// (not the holes' diameters): throws as the cell's elements are read.
PredictionSetup setupFromCell(const PredictionContext& c, const std::string& uncertainty_override) {
  PredictionSetup s;
  s.robot = c.robot;
  s.tool = c.tool;
  s.process = c.process;
  s.uncertainty = uncertaintyFromCell(c.cell);
  if (uncertainty_override == "linear") s.uncertainty.method = UncertaintyInputs::Method::kLinear;
  if (uncertainty_override == "montecarlo")
    s.uncertainty.method = UncertaintyInputs::Method::kMonteCarlo;
  if (!uncertainty_override.empty() && uncertainty_override != "linear" &&
      uncertainty_override != "montecarlo") {
    throw UsageError("--uncertainty must be linear or montecarlo");
  }
  s.capability = capabilityFromCell(c.cell);
  s.accuracy = accuracyFromCell(c.cell, c.robot.card);
  // the controller's gravity handling: the one decision every command shares
  const ControllerGravity cg = controllerGravityOf(c.robot.card, &c.cell, c.tool);
  s.controller_gravity = cg.gravity_compensated;
  s.calibration_load = cg.calibration_load;
  s.default_tolerance = c.cell.tolerance_mm * 1e-3;
  s.drill_tools = drillToolsOf(c.cell, c.robot.card);
  return s;
}

std::optional<std::array<int, 3>> fanucTurnAxesFromCell(const CellSpec& cell) {
  const XmlNode* e = cell.root.child("controller");
  if (e == nullptr || !e->has("fanuc_turn_axes")) return std::nullopt;
  const Eigen::VectorXd ax = e->numbers("fanuc_turn_axes", 3);
  std::array<int, 3> axes{};
  for (int i = 0; i < 3; ++i) {
    if (ax[i] < 1 || ax[i] > 6 || ax[i] != std::floor(ax[i]))
      e->fail("fanuc_turn_axes: three joint numbers 1..6");
    axes[static_cast<size_t>(i)] = static_cast<int>(ax[i]);
  }
  return axes;
}

/// The cell's rule feed <= 0.1 Dc (process_spec.cpp) applies to a diameter from the hole list too:
/// a hole the cell's feed cannot drill is an error at its line (the force model would give 0 N
/// and "conforms").
void requireDrillableDiameters(const PredictionContext& c) {
  if (!c.process || c.process->type != ProcessType::kDrilling) return;
  for (const HoleRequest& r : c.job.requests) {
    const DrillingSpec& drill = c.process->drills[static_cast<size_t>(std::max(r.drill, 0))];
    const double feed = r.feed > 0 ? r.feed : drill.feed;
    const double diameter = r.diameter > 0 ? r.diameter : drill.geometry.diameter;
    if (feed <= 0.1 * diameter * (1 + 1e-12)) continue;
    throw InputError(c.job.path, r.line,
                     "hole " + clipForMessage(r.id) + ": diameter " + numberText(diameter * 1e3) +
                         " mm is too small for the " + (r.feed > 0 ? "hole's" : "cell's") +
                         " feed " + numberText(feed * 1e3) +
                         " mm/rev (feed <= 0.1 Dc: a diameter of at least " +
                         numberText(feed * 1e4) +
                         " mm); drill it with another cell (feed) or correct the diameter");
  }
}

}  // namespace

PredictionContext loadPredictionContext(const std::string& cell_path, const std::string& job_path,
                                        const std::optional<std::string>& hole_list,
                                        const std::string& uncertainty_override,
                                        double match_tol_mm, bool load_holes, int threads,
                                        bool defer_setup, bool keep_requests) {
  PredictionContext c;
  c.cell = loadCell(cell_path);
  try {
    c.robot = loadRobot(c.cell.robot);
  } catch (const InputError& e) {
    if (e.file().empty()) throw InputError(c.cell.file, c.cell.robot_line, e.message());
    throw;
  }
  if (!c.robot.card.has_stiffness) {
    throw InputError(c.cell.file, c.cell.robot_line,
                     "the robot has no joint stiffness (use a robot card with stiffness values)");
  }
  requireGravityModel(c.robot);
  c.tool.T_flange_tcp = c.cell.tool.T_flange_tcp;
  c.tool.mass = c.cell.tool.mass;
  c.tool.com = c.cell.tool.com;
  c.tool.inertia = c.cell.tool.inertia;
  if (c.cell.has_process) {
    c.process = parseProcess(c.cell.process);
    c.process_description = steadyProcessLoad(*c.process).description;
    if (c.process->drills.size() > 1) {  // a tool table: each hole its drill
      std::string table;
      for (const DrillingSpec& d : c.process->drills)
        table += (table.empty() ? "" : ", ") + drillLabel(d);
      c.process_description = "drilling with a tool table of " +
                              std::to_string(c.process->drills.size()) +
                              " drills, each hole its "
                              "own (" +
                              table + ")";
    }
  } else {
    c.process_description = "no process (gravity and tool weight only)";
  }
  if (load_holes) {
    c.job = loadJobHoles(job_path, c.cell, c.robot, hole_list, match_tol_mm, threads, defer_setup,
                         keep_requests);
  } else if (!job_path.empty()) {
    c.job.path = job_path;
    c.job.program = postproc::readProgram(job_path);
  }

  PredictionSetup s = setupFromCell(c, uncertainty_override);
  if (const std::string note = gravityNotModelledNote(c.robot.card); !note.empty())
    c.job.notes.push_back(note);
  for (std::string& note : cardCheckOnLoad(c.robot)) c.job.notes.push_back(std::move(note));
  c.fanuc_turn_axes = fanucTurnAxesFromCell(c.cell);
  for (const HoleRequest& r : c.job.requests) {
    if (r.diameter > 0) s.hole_diameters.push_back(r.diameter);
    if (r.drill > 0 || r.feed > 0 || r.spindle_rpm > 0)
      s.hole_processes.push_back(holeProcessOf(r));
  }
  requireDrillableDiameters(c);
  c.model = buildPredictionModel(s);
  if (c.fanuc_turn_axes) {
    c.model.config_options.fanuc_turn_axes = *c.fanuc_turn_axes;
    if (c.job.program) c.job.program->fanuc_turn_axes = *c.fanuc_turn_axes;
  }
  return c;
}

std::string uncertaintyMethodText(const UncertaintyInputs& u) {
  if (u.method == UncertaintyInputs::Method::kLinear)
    return "linearised (Jacobian at the deflected pose)";
  return "Monte Carlo (" + std::to_string(u.samples) + " samples, seed " + std::to_string(u.seed) +
         ")";
}

}  // namespace roprec::api
