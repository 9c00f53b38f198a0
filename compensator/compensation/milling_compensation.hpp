#pragma once
/// \file milling_compensation.hpp
/// Compensation of a milling path (issue 7 item 5): every path point's target is pre-offset so that
/// the predicted real tool lands on the nominal path under the milling force, which itself depends
/// on the deviation (docs/process.md §4.3–4.4). Per point i, in path order:
///   1. θ_d = IK(T_nom,i) (continuity from the previous point);
///   2. fixed point on the force: F⁽⁰⁾ = F(fz, ae) nominal; θ_m⁽ᵏ⁾ = θ_d + K⁻¹τ(θ_d; F⁽ᵏ⁾) (exact
///   inverse);
///      the coupled iteration of milling.hpp is then run with the compensated robot's compliance
///      (δ(F) = real − nominal tool position under F, milling frame) from the previous point's
///      state: F⁽ᵏ⁺¹⁾ = its converged force, until |F⁽ᵏ⁺¹⁾ − F⁽ᵏ⁾| ≤ 1e-9 N — with an exact
///      compensation the tool stays on the path, the chip is nominal and this converges at the
///      first check;
///   3. programmed target = rigid FK(θ_m); the residual is re-predicted with the converged force.
/// Non-convergence (coupling or force fixed point) is reported per point, never silently emitted.

#include <string>
#include <vector>

#include "compensator/precision/prediction.hpp"

namespace roprec {

struct PathPointCompensation {
  bool ok{false};
  std::string reason;
  Vec6 theta_d{Vec6::Zero()};
  Vec6 theta_cmd{Vec6::Zero()};
  Pose T_programmed{Pose::Identity()};
  Vec3 deviation_before{Vec3::Zero()};  ///< m, base frame, uncompensated (coupled force)
  Vec3 residual{Vec3::Zero()};          ///< m, base frame, after compensation
  Vec3 force{Vec3::Zero()};             ///< converged force on the tool, milling frame, N
  int force_iterations{0};
  int coupling_iterations{0};
  bool coupling_converged{false};
  std::string config_text;
};

/// `m` must carry a milling process. Points are nominal TCP poses in the base frame (path order).
std::vector<PathPointCompensation> compensateMillingPath(const PredictionModel& m,
                                                         const std::vector<Pose>& points);

}  // namespace roprec
