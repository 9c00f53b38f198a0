#pragma once
/// \file prediction_json.hpp
/// The JSON of a prediction (docs/contract.md §9 keys): one hole, the capability summary.

#include "compensator/precision/prediction.hpp"
#include "plugin/api/prediction_setup.hpp"
#include "plugin/report/json.hpp"

namespace roprec::api {

/// Per-hole JSON object (contract keys + details). With `card`, the joints are also given in the
/// controller's convention (`controller_joints_deg`, toControllerJoints).
Json holeJson(const HolePrediction& h, const HoleRequest& r, const RobotCard* card = nullptr);
Json summaryJson(const CapabilitySummary& s);

}  // namespace roprec::api
