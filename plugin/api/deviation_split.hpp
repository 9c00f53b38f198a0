#pragma once
/// \file deviation_split.hpp
/// Why a hole deviates: δrobot split into the parts caused by the arm's own weight, the tool
/// (spindle) weight, the process load and the controller's reference (its gravity compensation or
/// mastering offset), for the report's "why" columns (docs/reports.md §3).
///
/// The deflection is a nonlinear equilibrium (the loads act on the deflected arm, the process
/// wrench follows the real drill axis), so the parts are defined by re-evaluating the same
/// prediction (predictHole, same IK solution) with the loads added one after the other, the
/// controller reference last:
///   δ₁ = δ(link weight)                       → gravity    = δ₁
///   δ₂ = δ(link + tool weight)                → tool       = δ₂ − δ₁
///   δ₃ = δ(link + tool weight + process)      → process    = δ₃ − δ₂
///   δrobot (the prediction, with the reference) → controller = δrobot − δ₃
/// The parts sum to δrobot exactly (telescoping). How far the split depends on the order is shown
/// by `process_alone` = δ(process load only, no weight, no reference): for the small rotations of
/// a loaded arm it equals `process` to first order (tests/report_test.cpp checks within 2 %).
/// All vectors in the robot base frame, m.

#include <optional>
#include <vector>

#include "compensator/precision/prediction.hpp"

namespace roprec::api {

struct DeviationSplit {
  Vec3 gravity{Vec3::Zero()};     ///< link (and counterbalance) weight
  Vec3 tool{Vec3::Zero()};        ///< tool / spindle weight (the cell's <tool> mass)
  Vec3 process{Vec3::Zero()};     ///< steady process wrench
  Vec3 controller{Vec3::Zero()};  ///< the controller reference (compensation / mastering)
  Vec3 process_alone{Vec3::Zero()};
  /// the robot's geometric error FK_real − FK_nom at the command (a calibrated robot, robot card
  /// <calibration>; zero otherwise): part of every re-evaluation, taken out of `gravity` and
  /// `process_alone`, so the five parts sum to δrobot
  Vec3 geometry{Vec3::Zero()};
};

/// The split of each hole with status kOk (nullopt otherwise or when a re-evaluation does not
/// converge). `tool` is the tool attachment `m` was built with (PredictionContext::tool).
/// Monte Carlo uncertainty settings are not used (the re-evaluations need δ only). The holes are
/// shared out over `threads` workers (each hole's split does not depend on the count). Throws
/// nothing beyond std::bad_alloc.
std::vector<std::optional<DeviationSplit>> splitRobotDeviations(
    const PredictionModel& m, const nc::ToolAttachment& tool,
    const std::vector<HoleRequest>& requests, const std::vector<const HolePrediction*>& preds,
    int threads = 1);

}  // namespace roprec::api
