#pragma once
/// \file fit_validation.hpp
/// Is an identification (identification.hpp) to be trusted? Two checks a calibration must pass
/// before its card is used:
///
/// ## Goodness of fit (χ²)
///   χ² = Σ_i Σ_rows (r_i / σ_i)²  at the estimate (IdentificationResult::chi2), dof = equations −
///   estimated parameters. With a model that explains the measurements up to their σ, χ²/dof ≈ 1.
///   The fit is flagged **inconsistent** when √(χ²/dof) > `rms_limit` (default 2: the residual is
///   more than twice the measurement σ — beyond the 99.9 % χ² quantile for every dof ≥ 5, whose
///   √(χ²₀.₉₉₉/dof) is 2.03 at dof 5 and falls towards 1 — a plain-language rule a metrologist can
///   check). The 99.9 % χ² quantile itself (Wilson–Hilferty) is reported alongside.
///   What the model cannot explain is named by fitting the residuals (weighted by 1/σ) with the
///   usual unmodelled effects, each by linear least squares on the residual rows, its columns first
///   made orthogonal to the fit's Jacobian (IdentificationResult::jacobian: what the identified
///   parameters already absorbed of it cannot explain the residual):
///     * `length scale` s:            e(p) = s · (p_W − o_W)            (thermal growth of the arm;
///                                    o_W = the robot base origin)
///     * `drift with time` d (3):     e(p) = d · (i / (N − 1))           (the part, fixture or
///                                    tracker creeping during the run; i = measurement order)
///     * `scale drifting with time`:  e(p) = s · (i / (N − 1)) · (p_W − o_W)  (warm-up)
///   The effect that removes the largest share of χ² is named when it removes at least half of it
///   (with its value); otherwise the residual is "scatter without the structure of a scale or a
///   drift" (backlash, a loose fixture, measurement σ set too small).
///
/// ## Held-out validation (k-fold cross-validation)
///   Observation i belongs to fold i mod k (deterministic: the measurement order). For each fold
///   the identification is run on the other folds and its parameters (robot and registration)
///   predict the fold's observations (residualsAt): their RMS |measured − predicted| is the
///   expected residual after calibration. The original card is validated the same way with only
///   the registration estimated (IdentifySet::kNone) — the fixture offset is not the card's
///   fault — so the two figures compare the cards alone. A calibration whose held-out RMS is
///   not below the original card's is **worse** and must not be written.
///
/// Units: m inside; nothing here prints.

#include <string>
#include <vector>

#include "compensator/precision/identification.hpp"

namespace roprec {

/// A named candidate for what the model does not explain.
struct UnmodelledEffect {
  std::string name;   ///< "length scale", "drift with time", "scale drifting with time"
  std::string value;  ///< its estimate in words, e.g. "0.21 mm/m", "(12.0, -3.1, 0.4) µm"
  double share{0};    ///< fraction of χ² it removes
};

struct FitCheck {
  double chi2{0};
  int dof{0};
  double rms_normalized{0};  ///< √(χ²/dof): the residual in units of the measurement σ
  double chi2_999{0};        ///< the 99.9 % quantile of χ²(dof)
  double rms_limit{2.0};
  bool consistent{true};    ///< rms_normalized ≤ rms_limit
  UnmodelledEffect best;    ///< the candidate that removes the largest share of χ²
  std::string explanation;  ///< what the model cannot explain (empty when consistent)
};

/// The χ² check of `r`, identified from `holes` (the same observations, same order). The base
/// origin o_W is the base frame's origin (0, 0, 0).
FitCheck checkFit(const IdentificationResult& r, const std::vector<IdentificationHole>& holes,
                  double rms_limit = 2.0);

/// The p-quantile of χ²(dof) (Wilson–Hilferty; at p = 0.999 relative error < 1.5 % for dof ≥ 5,
/// < 1 % for dof ≥ 10).
double chiSquareQuantile(int dof, double p);

struct HeldOutValidation {
  int folds{0};
  /// Held-out |measured − predicted| per observation (input order), m: calibrated / original card.
  std::vector<double> calibrated, original;
  double rms_calibrated{0}, rms_original{0};
  bool better{false};  ///< rms_calibrated < rms_original
};

/// k-fold cross-validation of the identification `o` on `holes` (see the file comment). Throws
/// InputError("", 0, …) when folds < 2 or there are fewer observations than folds (and as
/// identifyStiffness / residualsAt do).
HeldOutValidation crossValidate(const PredictionModel& m,
                                const std::vector<IdentificationHole>& holes,
                                const IdentificationOptions& o, int folds);

/// The model error floor, m per axis: the scatter of residuals that the observations' own σ
/// (measurement, repeatability, machining: IdentificationHole::sigma) do not explain,
///   u_model² = max(0, inflation · Σ_i |r_i|² / Σ_i n_i − Σ_i n_i σ_i² / Σ_i n_i),
/// n_i = observationRows. `residual_norms` |r_i| per observation (holes' order): held-out ones
/// (HeldOutValidation::calibrated; inflation 1) or the fit's own (inflation equations/dof).
double modelErrorFloor(const std::vector<double>& residual_norms,
                       const std::vector<IdentificationHole>& holes, double inflation = 1.0);

/// Validation on separate observations: `r` (identified from the fit set `fit`) predicts
/// `held_out`; the original card is the registration-only fit on `fit`.
HeldOutValidation validateOn(const PredictionModel& m, const IdentificationResult& r,
                             const std::vector<IdentificationHole>& fit,
                             const std::vector<IdentificationHole>& held_out,
                             const IdentificationOptions& o);

}  // namespace roprec
