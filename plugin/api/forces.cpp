/// Process forces of a cell (plugin/api/forces.hpp).
#include "plugin/api/forces.hpp"

#include <sstream>
#include <vector>

#include "compensator/precision/cell.hpp"
#include "compensator/process/milling_robot.hpp"
#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "plugin/api/robot_compliance.hpp"
#include "plugin/api/robot_setup.hpp"

namespace roprec::api {

namespace {

constexpr double kMm = 1e-3;

std::string fixed(double v, int decimals) { return formatNumber(v, decimals); }

// ---------------------------------------------------------------- drilling

/// Calibrates kst0/ksa0 from one test: updates the spec and the model, keeps the calibration in
/// `d`, and gives the calibrated cell's text when `want_cell`.
void calibrate(const CellSpec& cell, DrillingSpec& s, DrillingModel& model,
               const DrillingMeasurement& meas, bool want_cell, DrillingForcesData& d,
               std::string& cell_text) {
  const DrillingCalibration cal = calibrateDrilling(model, s.feed, meas.thrust, meas.torque);
  d.measurement = meas;
  d.calibration = cal;
  std::ostringstream note;
  note << "calibrated by roprec forces from one test: Fa=" << fixed(meas.thrust, 3)
       << " N, M=" << fixed(meas.torque, 4) << " N m at Dc " << fixed(s.geometry.diameter / kMm, 3)
       << " mm, f " << fixed(s.feed / kMm, 4) << " mm/rev (" << s.material->name << ")";
  s.coeff = cal.coeff;
  s.coeff_source = note.str();
  model.coeff = cal.coeff;
  if (want_cell)
    cell_text =
        cellWithCalibratedCoefficients(readFileBytes(cell.file), cell.file, cal.coeff, note.str());
}

void drillingForcesOf(const CellSpec& cell, DrillingSpec& s, const ForcesRequest& req,
                      ForcesResult& out) {
  DrillingForcesData& d = out.drilling.emplace();
  d.coeff_before = s.coeff;
  DrillingModel model = drillingModelOf(s);
  if (req.calibrate)
    calibrate(cell, s, model, *req.calibrate, req.calibrated_cell, d, out.calibrated_cell);
  d.steady = drillingForces(model, s.feed);
  // Range checks before any sampling, located at the cell's <cut> (depth_mm) when the depth is
  // the problem, on the command line (--step-mm) otherwise.
  if (std::string p = depthProfileProblem(model, s.hole_depth, s.through, req.step); !p.empty()) {
    const bool depth = depthProfileProblem(model, s.hole_depth, s.through, 1e-3).size() > 0;
    if (depth) throw InputError(cell.file, s.feed_line, "<cut> depth_mm: " + p);
    throw InputError("", 0, "--step-mm: " + p);
  }
  if (req.axial_compliance) {
    if (std::string p = axialCouplingProblem(model, s.feed, s.hole_depth, s.through); !p.empty())
      throw InputError(cell.file, s.feed_line, "<cut>: " + p);
  }
  DrillingData data(model);
  d.step = req.step;
  d.profile = drillingDepthProfile(model, data, s.feed, s.hole_depth, s.through, req.step);
  if (req.axial_compliance) {
    d.axial_compliance = *req.axial_compliance;
    d.axial =
        drillingAxialCoupling(model, data, s.feed, s.hole_depth, s.through, *req.axial_compliance);
    bool all = true;
    for (const AxialCouplingSample& x : d.axial) all = all && x.converged;
    out.converged = all;
  }
  d.spec = s;
}

// ---------------------------------------------------------------- milling

/// The coupled force/deflection solve over `points` path points with the cell's linear
/// compliance or the robot's own (`robot`), and the corrected revolution of the last point.
MillingCouplingData millingCoupling(const MillingModel& m, const MillingSpec& s, int points,
                                    const std::optional<ComplianceFunction>& robot,
                                    const ModalModel& dyn, bool& converged) {
  MillingCouplingData cp;
  cp.robot = robot.has_value();
  cp.tool_compliance = toolStaticCompliance(s.tool_mode);
  const ComplianceFunction C =
      withToolCompliance(robot ? *robot : linearCompliance(*s.compliance), cp.tool_compliance);
  const std::vector<ComplianceFunction> path(static_cast<size_t>(points), C);
  cp.points = coupleMillingPath(m, path, s.coupling);
  for (const CouplingResult& r : cp.points)
    if (!r.converged) converged = false;
  cp.corrected = correctedRevolution(m, dyn, cp.points.back());
  return cp;
}

std::string unstablePointText(size_t i, int line, const PathPointCompensation& p, double ap) {
  const std::string at =
      "path point " + std::to_string(i + 1) + " (line " + std::to_string(line) + "): ";
  if (!p.regenerativeUnstable(ap)) {
    return at + "mode-coupling chatter: ap " + fixed(ap / kMm, 3) + " mm > limit " +
           fixed(p.mode_coupling_ap_limit / kMm, 3) + " mm (at " + fixed(p.mode_coupling_hz, 1) +
           " Hz)";
  }
  return at + "chatter: ap " + fixed(ap / kMm, 3) + " mm > limit " + fixed(p.ap_limit / kMm, 3) +
         " mm (chatter at " + fixed(p.chatter_hz, 1) + " Hz)";
}

/// Whether the points of the block `r` converged and which chatter (one line each, in order).
void notePathBlock(const MillingCompensationResult& r, bool& converged,
                   std::vector<std::string>& unstable) {
  for (size_t i = r.first; i < r.first + r.points_comp.size(); ++i) {
    const PathPointCompensation& p = r.point(i);
    const bool before_ok = !p.cutting || p.before_status == "converged";
    const double ap_i = pathPointAp(r, i);
    if (!before_ok || !p.ok) converged = false;
    if (p.unstable(ap_i)) unstable.push_back(unstablePointText(i, r.targetLine(i), p, ap_i));
  }
}

MillingPathOptions pathOptions(const ForcesRequest& req) {
  MillingPathOptions o;
  o.threads = req.threads;
  o.block = req.block;
  return o;
}

/// `--program`: every linear point of the program compensated; whether each converged and which
/// chatter.
MillingCompensationResult millingPath(const ForcesRequest& req, bool& converged,
                                      std::vector<std::string>& unstable) {
  MillingCompensationResult r =
      compensateMillingJob(req.cell, *req.program, false, pathOptions(req));
  notePathBlock(r, converged, unstable);
  return r;
}

/// millingPath handing each block of points to `sink` (after `head` got the result so far). A
/// program compensate reads by windows (millingStreams), or a RAPID module (millingPathStreams),
/// is read so here: a first reading
/// checks it whole (its errors before `head`), a second hands its points to the chains a block at
/// a time; memory is then constant in the number of points.
MillingCompensationResult millingPathStreamed(const ForcesRequest& req, const ForcesPathSink& sink,
                                              ForcesResult& out) {
  const MillingPointsSink each = [&](const MillingCompensationResult& blk) {
    notePathBlock(blk, out.converged, out.unstable);
    if (sink.points) sink.points(blk);
  };
  if (millingPathStreams(*req.program)) {
    MillingCompensationResult r = loadStreamedMillingJob(req.cell, *req.program, req.window_bytes);
    if (sink.head) sink.head(out);
    computeStreamedMillingPath(r, pathOptions(req), each, req.window_bytes);
    return r;
  }
  if (sink.head) sink.head(out);
  return compensateMillingJob(req.cell, *req.program, false, pathOptions(req), each);
}

/// The cell's robot model and joint compliance (milling with --joints).
struct CellRobot {
  nc::Model model;
  nc::JointCompliance compliance;
};
CellRobot cellRobot(const CellSpec& cell) {
  const Robot r = loadRobot(cell.robot);
  return {nc::buildModel(r.real_chain, toolOf(cell)), complianceOf(r.card)};
}

void millingForcesOf(const CellSpec& cell, const MillingSpec& s, const ForcesRequest& req,
                     const ForcesPathSink* sink, ForcesResult& out) {
  MillingForcesData& d = out.milling.emplace();
  d.spec = s;
  std::optional<ComplianceFunction> robot;
  ModalModel& dyn = d.dynamics;
  if (req.joints) {
    const CellRobot r = cellRobot(cell);
    robot = robotMillingCompliance(r.model, r.compliance, *req.joints);
    dyn = robotModes(r.model, r.compliance, *req.joints, s.robot_damping_ratio);
    d.joints = req.joints;
  }
  addToolMode(dyn, s.tool_mode);
  d.model = millingModelOf(s);
  d.profile = millingForceProfile(d.model);
  if (s.compliance || robot)
    d.coupling = millingCoupling(d.model, s, req.points, robot, dyn, out.converged);
  if (req.program) {
    d.program = *req.program;
    d.path = sink != nullptr ? millingPathStreamed(req, *sink, out)
                             : millingPath(req, out.converged, out.unstable);
  }
}

// ---------------------------------------------------------------- wrench

void wrenchForcesOf(const CellSpec& cell, const WrenchSpec& w, const ForcesRequest& req,
                    ForcesResult& out) {
  out.wrench = w;
  if (req.curve)
    throw InputError(cell.file, cell.process.line, "a wrench process has no curve: drop --csv");
}

}  // namespace

double pathPointAp(const MillingCompensationResult& r, size_t i) {
  const PathPointCompensation& p = r.point(i);
  const bool engaged = r.engagement(i).has_value();
  return p.cutting && engaged ? p.ap : millOf(r, i).cut.ap;
}

namespace {

ForcesResult forcesOf(const ForcesRequest& request, const ForcesPathSink* sink) {
  const CellSpec cell = loadCell(request.cell);
  if (!cell.has_process)
    throw InputError(cell.file, cell.root.line, "the cell has no <process> element");
  ProcessSpec spec = parseProcess(cell.process);
  if (request.calibrate && spec.type != ProcessType::kDrilling) {
    throw InputError(cell.file, cell.process.line,
                     "--calibrate needs a <process type=\"drilling\">");
  }
  if (request.program && spec.type != ProcessType::kMilling) {
    throw InputError(cell.file, cell.process.line, "--program needs a <process type=\"milling\">");
  }
  if (request.calibrated_cell && !request.calibrate) {
    throw UsageError("-o/--o writes the calibrated cell: use it with --calibrate");
  }
  if (request.program && request.tool) {
    throw UsageError(
        "--tool with --program: the program's active tool selects the mill of each "
        "point; leave out --tool");
  }
  const size_t k = request.program ? 0 : commandToolIndex(spec, request.tool);
  ForcesResult out;
  out.cell = cell.name;
  CellSpec with = cell;  // the tool's own <tcp>, else the cell's <tool>
  if (k < cell.drill_tools.size() && cell.drill_tools[k]) with.tool = *cell.drill_tools[k];
  switch (spec.type) {
    case ProcessType::kDrilling:
      drillingForcesOf(with, spec.drills[k], request, out);
      break;
    case ProcessType::kMilling:
      millingForcesOf(with, request.program ? spec.milling : spec.mills[k], request, sink, out);
      break;
    case ProcessType::kWrench:
      wrenchForcesOf(cell, spec.wrench, request, out);
      break;
  }
  return out;
}

}  // namespace

ForcesResult processForces(const ForcesRequest& request) { return forcesOf(request, nullptr); }

ForcesResult processForces(const ForcesRequest& request, const ForcesPathSink& sink) {
  return forcesOf(request, &sink);
}

}  // namespace roprec::api
