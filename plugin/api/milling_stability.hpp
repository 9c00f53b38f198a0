#pragma once
/// \file milling_stability.hpp
/// Milling dynamics and chatter stability of a cell at a pose (`roprec milling-stability`, and the
/// "dynamics"/"stability" blocks of `roprec forces`): the robot's modes at the joints (multibody
/// mass matrix, joint+servo stiffness, the cell's modal damping), the spindle/tool mode of the
/// cell's `<dynamics>`, and the zero-order stability lobes (compensator/process/milling_stability
/// .hpp; docs/process.md §4.6–4.7).
///
/// Units: SI in the structs; JSON and CSV in mm, Hz, rpm, N/µm, µm/N. Frames: the milling frame
/// (X = feed, Y, Z from the tool tip toward the spindle). Errors: InputError (cell file and line)
/// for a bad cell or a non-milling process; UsageError for a bad speed range.

#include <optional>
#include <string>

#include "compensator/compensation/milling_compensation.hpp"
#include "compensator/process/milling_stability.hpp"
#include "compensator/process/process_spec.hpp"
#include "compensator/robot/model.hpp"
#include "plugin/api/json.hpp"

namespace roprec::api {

/// "dynamics": the modes (frequency, damping, TCP direction and stiffness, joint shape), the tooth
/// frequency and the modal model's static compliance; `robot` says whether robot modes are in it.
Json millingDynamicsJson(const ModalModel& dyn, const MillingSpec& s, bool robot);
/// "stability": Kt, Kr, α and the zero-order limit at the cut's spindle speed (margin = ap_lim/ap).
Json millingStabilityJson(const ModalModel& dyn, const MillingModel& m);

/// A path point's chatter check (PathPointCompensation): checked, bounded, ap_limit_mm,
/// chatter_frequency_Hz, margin (limit/ap), stable, first_mode_Hz.
Json pathPointStabilityJson(const PathPointCompensation& p, double ap);

struct MillingStabilityRequest {
  std::string cell;                      ///< CELL.xml with a <process type="milling">
  std::optional<nc::Vec6> joints;        ///< the pose (rad); without it the tool mode alone
  std::optional<double> rpm_lo, rpm_hi;  ///< lobe range; default 0.2–2 × the cut's speed
  int steps{400};                        ///< speeds of the lobe diagram
  /// The mill of the cell's tool table (<mill tool>); needed when it has several mills.
  std::optional<std::string> tool;
};

struct MillingStabilityResult {
  Json json;           ///< cell, joints_deg, dynamics, stability, lobes summary
  std::string csv;     ///< spindle_rpm,ap_limit_mm,chatter_Hz,lobe (ap empty when unbounded)
  std::string report;  ///< HTML: the lobe diagram with the programmed cut marked
  bool stable{true};   ///< the cell's ap is below the limit at its spindle speed
};

MillingStabilityResult millingStability(const MillingStabilityRequest& request);

}  // namespace roprec::api
