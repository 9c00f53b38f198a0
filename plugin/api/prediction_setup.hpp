#pragma once
/// \file prediction_setup.hpp
/// Everything `roprec predict` and `roprec compensate` share: the cell (robot, tool, process,
/// tolerance, <uncertainty>, <capability>), the job's holes and the prediction model (the JSON of
/// a prediction: plugin/report/prediction_json.hpp).
///
/// Cell extensions read here (all optional):
///   <uncertainty method="linear|montecarlo" stiffness_rel="0.10" position_gain_rel="0.20"
///                process_halfwidth="0.15" samples="400" seed="20201" source="..."/>
///   <capability mc_approach_s="2.0" source="..."/>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "compensator/precision/prediction.hpp"
#include "plugin/api/hole_input.hpp"
#include "plugin/report/json.hpp"

namespace roprec::api {

struct PredictionContext {
  CellSpec cell;
  Robot robot;
  nc::ToolAttachment tool;
  std::optional<ProcessSpec> process;
  std::string process_description;
  JobHoles job;
  PredictionModel model;
  std::optional<std::array<int, 3>> fanuc_turn_axes;  ///< cell <controller fanuc_turn_axes>
};

/// `uncertainty_override`: "linear" / "montecarlo" from the command line (empty: the cell's).
/// `load_holes` false: the program is read (not its holes); an empty `job_path` then loads the
/// cell alone (per-target sessions). `threads`: workers for setting up the holes.
/// `defer_setup`: see loadJobHoles (the holes' requests are set up later, block by block);
/// `keep_requests`: see loadJobHoles (a streamed program's requests kept from its first reading).
PredictionContext loadPredictionContext(const std::string& cell_path, const std::string& job_path,
                                        const std::optional<std::string>& hole_list,
                                        const std::string& uncertainty_override,
                                        double match_tol_mm = 0.5, bool load_holes = true,
                                        int threads = 1, bool defer_setup = false,
                                        bool keep_requests = false);

/// The TCP and mass data of each drill of the cell's tool table that has a <tcp> of its own
/// (PredictionSetup::drill_tools), with the calibration load the cell's <controller> implies
/// while it is in (calibration_load="tool": that tool).
std::vector<std::optional<DrillTool>> drillToolsOf(const CellSpec& cell, const RobotCard& card);

/// Whether a hole's JSON states its drill (`"drill": {tool, feed_mm_per_rev, spindle_rpm}`): a
/// hole drilled with a drill of the cell's tool table, or with its own feed or spindle speed.
inline bool statesOwnProcess(const HoleRequest& r) {
  return r.drill >= 0 || r.feed > 0 || r.spindle_rpm > 0;
}
std::string uncertaintyMethodText(const UncertaintyInputs& u);

}  // namespace roprec::api
