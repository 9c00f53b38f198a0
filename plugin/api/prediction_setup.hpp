#pragma once
/// \file prediction_setup.hpp
/// Everything `roprec predict` and `roprec compensate` share: the cell (robot, tool, process,
/// tolerance, <uncertainty>, <capability>), the job's holes, the prediction model, and the JSON
/// of a prediction (docs/contract.md §9 keys).
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
#include "plugin/api/json.hpp"

namespace roprec::api {

class HoleLookahead;
/// Holes a lookahead predicts at most (about 24 MB of requests, predictions and JSON texts held).
/// On a KRL drill program with two threads, about as many as the worker predicts and formats
/// while the program is read.
inline constexpr std::size_t kLookaheadHoles = 6144;
/// Programs larger than this (~45,000 drill cycles of 7 lines) are read without a lookahead:
/// its memory would add to the read's peak (a 36 MB program: ~190 MB) for a few per cent of
/// the holes.
inline constexpr std::uintmax_t kLookaheadProgramBytes = std::uintmax_t{16} << 20U;

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

/// Writes into `out` (replacing what it held) the text a job's output makes of hole k, predicted
/// from `request`: e.g. its item of the prediction JSON (PredictionJsonStream::itemFormat). Called
/// on any thread, several at once.
using HoleFormat = std::function<void(std::size_t k, const HolePrediction& hole,
                                      const HoleRequest& request, std::string& out)>;
/// Makes a HoleFormat from a job's context once its cell and robot are loaded (before its
/// program is read): the lookahead formats what it predicts while the program is read.
using HoleFormatFactory = std::function<HoleFormat(const PredictionContext&)>;

/// `uncertainty_override`: "linear" / "montecarlo" from the command line (empty: the cell's).
/// `load_holes` false: the program is read (not its holes); an empty `job_path` then loads the
/// cell alone (per-target sessions). `threads`: workers for setting up the holes.
/// `defer_setup`: see loadJobHoles (the holes' requests are set up later, block by block).
/// `lookahead` (with `defer_setup`, no hole list and more than one thread): receives a
/// HoleLookahead that predicted the program's first holes (at most kLookaheadHoles) while it was
/// read (lookahead.hpp), or null (a cell the job then reports as wrong, a program larger than
/// kLookaheadProgramBytes); with `format_ahead`, it also formatted them (HoleLookahead::take).
PredictionContext loadPredictionContext(const std::string& cell_path, const std::string& job_path,
                                        const std::optional<std::string>& hole_list,
                                        const std::string& uncertainty_override,
                                        double match_tol_mm = 0.5, bool load_holes = true,
                                        int threads = 1, bool defer_setup = false,
                                        std::unique_ptr<HoleLookahead>* lookahead = nullptr,
                                        const HoleFormatFactory& format_ahead = {});

/// Per-hole JSON object (contract keys + details). With `card`, the joints are also given in the
/// controller's convention (`controller_joints_deg`, toControllerJoints; issue 14).
Json holeJson(const HolePrediction& h, const HoleRequest& r, const RobotCard* card = nullptr);
Json summaryJson(const CapabilitySummary& s);
/// Whether a hole's JSON states its drill (`"drill": {tool, feed_mm_per_rev, spindle_rpm}`): a
/// hole drilled with a drill of the cell's tool table, or with its own feed or spindle speed.
inline bool statesOwnProcess(const HoleRequest& r) {
  return r.drill >= 0 || r.feed > 0 || r.spindle_rpm > 0;
}
std::string uncertaintyMethodText(const UncertaintyInputs& u);

}  // namespace roprec::api
