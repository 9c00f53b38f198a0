#pragma once
/// \file deviation_split.hpp
/// Why a hole deviates: δrobot split into the parts caused by the arm's own weight, the tool
/// (spindle) weight, the process load and the controller's reference (its gravity compensation or
/// mastering offset), for the report's "why" columns (docs/reports.md §3).
///
/// The deflection is a nonlinear equilibrium (the loads act on the deflected arm, the process
/// wrench follows the real drill axis), so the parts are defined by re-evaluating the same
/// equilibrium at the hole's command (its joints, known: no IK; robotDeviationAt) with the loads
/// added one after the other, the controller reference last:
///   δ₁ = δ(link weight)                       → gravity    = δ₁
///   δ₂ = δ(link + tool weight)                → tool       = δ₂ − δ₁
///   δ₃ = δ(link + tool weight + process)      → process    = δ₃ − δ₂
///   δrobot (the prediction, with the reference) → controller = δrobot − δ₃
/// The parts sum to δrobot exactly (telescoping). How far the split depends on the order is shown
/// by `process_alone` = δ(process load only, no weight, no reference): for the small rotations of
/// a loaded arm it equals `process` to first order (tests/report_test.cpp checks within 2 %).
/// All vectors in the robot base frame, m.

#include <memory>
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

/// The re-evaluated models of a prediction model (one set per drill with a TCP of its own) and
/// per-worker scratch: split() gives one hole's split, on any of `workers` threads at once (each
/// with its own worker index). The split of a hole does not depend on the worker.
class DeviationSplitter {
 public:
  /// `tool` is the tool attachment `m` was built with (PredictionContext::tool). Without
  /// `process_alone` the splits leave DeviationSplit::process_alone zero (one re-evaluation less:
  /// the reports do not show it).
  DeviationSplitter(const PredictionModel& m, const nc::ToolAttachment& tool, int workers,
                    bool process_alone = true);
  ~DeviationSplitter();
  DeviationSplitter(const DeviationSplitter&) = delete;
  DeviationSplitter& operator=(const DeviationSplitter&) = delete;

  /// The split of hole `r` predicted as `p` (nullopt unless p.status is kOk, or when a
  /// re-evaluation does not converge), with worker `worker`'s scratch.
  [[nodiscard]] std::optional<DeviationSplit> split(const HoleRequest& r, HoleStatus status,
                                                    const Vec6& joints, const Vec3& d_robot,
                                                    int worker) const;

 private:
  struct Models;
  const PredictionModel& m_;
  std::vector<std::unique_ptr<Models>> models_;  ///< m_'s, then each drill model's
  bool process_alone_;
};

/// The split of each hole with status kOk (nullopt otherwise or when a re-evaluation does not
/// converge). `tool` is the tool attachment `m` was built with (PredictionContext::tool).
/// Monte Carlo uncertainty settings are not used (the re-evaluations need δ only). The holes are
/// shared out over `threads` workers (each hole's split does not depend on the count). Throws
/// nothing beyond std::bad_alloc.
std::vector<std::optional<DeviationSplit>> splitRobotDeviations(
    const PredictionModel& m, const nc::ToolAttachment& tool,
    const std::vector<HoleRequest>& requests, const std::vector<const HolePrediction*>& preds,
    int threads = 1, bool process_alone = true);

}  // namespace roprec::api
