/// Milling dynamics and chatter stability of a cell (plugin/api/milling_stability.hpp).
#include "plugin/api/milling_stability.hpp"

#include <algorithm>

#include "compensator/precision/cell.hpp"
#include "compensator/support/error.hpp"
#include "plugin/api/job.hpp"
#include "plugin/api/robot_compliance.hpp"
#include "plugin/api/robot_setup.hpp"

namespace roprec::api {

MillingStabilityResult millingStability(const MillingStabilityRequest& req) {
  const CellSpec cell = loadCell(req.cell);
  if (!cell.has_process)
    throw InputError(cell.file, cell.root.line, "the cell has no <process> element");
  const ProcessSpec spec = parseProcess(cell.process);
  if (spec.type != ProcessType::kMilling)
    throw InputError(cell.file, cell.process.line,
                     "milling-stability needs a <process type=\"milling\">");
  const size_t mill = commandToolIndex(spec, req.tool);
  const MillingSpec& s = spec.mills[mill];
  const double lo = req.rpm_lo.value_or(std::max(100.0, 0.2 * s.cut.spindle_rpm));
  const double hi = req.rpm_hi.value_or(2.0 * s.cut.spindle_rpm);
  if (!(lo > 0 && hi > lo)) throw UsageError("--rpm: give \"LO HI\" with 0 < LO < HI");
  MillingStabilityResult out;
  out.cell = cell.name;
  out.spec = s;
  out.joints = req.joints;
  ModalModel& dyn = out.dynamics;
  if (req.joints) {
    const Robot r = loadRobot(cell.robot);
    CellSpec with = cell;  // the mill's own <tcp>, else the cell's <tool>
    if (mill < cell.drill_tools.size() && cell.drill_tools[mill])
      with.tool = *cell.drill_tools[mill];
    const nc::Model model = nc::buildModel(r.real_chain, toolOf(with));
    dyn = robotModes(model, complianceOf(r.card), *req.joints, s.robot_damping_ratio);
  }
  addToolMode(dyn, s.tool_mode);
  out.model = millingModelOf(s);
  const StabilityCut cut = stabilityCutOf(out.model);
  out.lobes = stabilityLobes(dyn, cut, lo, hi, req.steps);
  out.at = limitingDepth(dyn, cut, s.cut.spindle_rpm);
  out.stable = !out.at.bounded || out.at.ap_lim > s.cut.ap;
  out.rpm_lo = lo;
  out.rpm_hi = hi;
  out.steps = req.steps;
  return out;
}

}  // namespace roprec::api
