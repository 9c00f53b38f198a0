#pragma once
/// \file milling_stability.hpp
/// Milling dynamics and chatter stability of a cell at a pose (`roprec milling-stability`, and the
/// "dynamics"/"stability" blocks of `roprec forces`): the robot's modes at the joints (multibody
/// mass matrix, joint+servo stiffness, the cell's modal damping), the spindle/tool mode of the
/// cell's `<dynamics>`, and the zero-order stability lobes (compensator/process/milling_stability
/// .hpp; docs/process.md §4.6–4.7).
///
/// Units: SI in the structs (the JSON, CSV and HTML: plugin/report/milling_output.hpp). Frames:
/// the milling frame
/// (X = feed, Y, Z from the tool tip toward the spindle). Errors: InputError (cell file and line)
/// for a bad cell or a non-milling process; UsageError for a bad speed range.

#include <optional>
#include <string>
#include <vector>

#include "compensator/compensation/milling_compensation.hpp"
#include "compensator/process/milling_stability.hpp"
#include "compensator/process/process_spec.hpp"
#include "compensator/robot/model.hpp"

namespace roprec::api {

struct MillingStabilityRequest {
  std::string cell;                      ///< CELL.xml with a <process type="milling">
  std::optional<nc::Vec6> joints;        ///< the pose (rad); without it the tool mode alone
  std::optional<double> rpm_lo, rpm_hi;  ///< lobe range; default 0.2–2 × the cut's speed
  int steps{400};                        ///< speeds of the lobe diagram
  /// The mill of the cell's tool table (<mill tool>); needed when it has several mills.
  std::optional<std::string> tool;
};

struct MillingStabilityResult {
  std::string cell;                ///< the cell's name
  std::optional<nc::Vec6> joints;  ///< the pose of the robot's modes (rad), if any
  MillingSpec spec;                ///< the cell's milling process
  ModalModel dynamics;             ///< robot modes at `joints` (if any) and the tool mode
  MillingModel model;              ///< the cut
  std::vector<LobeSample> lobes;   ///< the lobe diagram over [rpm_lo, rpm_hi]
  StabilityLimit at;               ///< the limit at the cut's spindle speed
  double rpm_lo{0}, rpm_hi{0};     ///< the lobe range, rpm
  int steps{0};                    ///< speeds of the lobe diagram
  bool stable{true};               ///< the cell's ap is below the limit at its spindle speed
};

MillingStabilityResult millingStability(const MillingStabilityRequest& request);

}  // namespace roprec::api
