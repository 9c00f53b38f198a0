#pragma once
/// \file milling_mode_coupling.hpp
/// Mode-coupling chatter of the robot's low modes (Tlusty; Pan, Zhang et al. 2006), docs/process.md
/// §4.8 — the other chatter mechanism of robot milling beside the regenerative one
/// (milling_stability.hpp).
///
/// The robot's modes (10–60 Hz) are far below the tooth frequency (hundreds of Hz): over one of
/// their periods the cut follows the tool's slow displacement x quasi-statically. The engagement
/// moves with it, ae(x) = ae + x·n_wall and ap(x) = ap − x·Z (milling.hpp), and so does the mean
/// force F̄ (linear in ap):
///   F(x) = F̄ + G x,   G = ∂F̄/∂x = (∂F̄/∂ae) n_wallᵀ − (F̄/ap) Zᵀ   [N/m], milling frame.
/// G is not symmetric: the force turns in a direction other than the one it is fed by. With the
/// modal model (milling_dynamics.hpp: x = Σ_r u_r q_r, mass-normalised), the linearised motion is
///   q̈ + diag(2ζ_r ω_r) q̇ + (diag(ω_r²) − Uᵀ G U) q = 0,
/// stable when every eigenvalue s of its state matrix has Re s < 0. A complex pair crossing the
/// axis is mode-coupling chatter (flutter: two modes of different stiffness coupled by the
/// non-symmetric process stiffness); a real root crossing it is the static divergence (the wall's
/// pull beyond the structure's stiffness: the coupled solve's runaway). The feed-direction memory
/// (x(t) − x(t − τ), the regenerative chip) is left to milling_stability.hpp.
///
/// Closed form (2 DOF, undamped: masses m, principal stiffnesses k1, k2 along e1, e2, G = −k_p f nᵀ
/// with unit f, n): with f_i = f·e_i, n_i = n·e_i, the eigenvalues of K + k_p f nᵀ are complex
/// (flutter) when
///   D(k_p) = (f·n)² k_p² + 2 (k1 − k2)(f1 n1 − f2 n2) k_p + (k1 − k2)² < 0,
/// which needs f1 f2 n1 n2 < 0 (the force and the normal on opposite sides of a principal axis)
/// and holds between the roots k_p = (k1 − k2)(−a ± √(a² − (f·n)²))/(f·n)², a = f1 n1 − f2 n2.
///
/// Limit: G at a depth ap' = s·ap is s G_ae + G_ap (G_ae = (∂F̄/∂ae) n_wallᵀ ∝ ap, G_ap = −(F̄/ap)
/// Zᵀ independent of it); the limiting depth is the smallest s > 0 at which the largest Re s of the
/// state matrix crosses zero: scanned on kScanPoints depths geometric in [kScanMin, kScanMax] × ap,
/// then bisected to 1e-4 relative. Damping shifts it above the undamped closed form.

#include "compensator/process/milling.hpp"
#include "compensator/process/milling_dynamics.hpp"

namespace roprec {

constexpr int kScanPoints = 96;
constexpr double kScanMin = 0.01;
constexpr double kScanMax = 100.0;

/// The process stiffness at a cut, split by its dependence on the depth (see the file comment).
struct ProcessGradient {
  Mat3 per_depth{Mat3::Zero()};  ///< G_ae at the cut's ap [N/m] (scales with ap'/ap)
  Mat3 fixed{Mat3::Zero()};      ///< G_ap [N/m]
  [[nodiscard]] Mat3 at(double scale) const { return scale * per_depth + fixed; }
};
/// ∂F̄/∂ae by central differences (±1 µm, one-sided at ae = 0 or D) of millingMeanForce at
/// (fz, ae), scaled to ap; F̄/ap from the same law.
ProcessGradient processGradient(const MillingModel& m, double fz, double ae, double ap);

struct ModeCouplingState {
  bool stable{true};
  bool flutter{false};     ///< the most unstable root is a complex pair (mode coupling)
  double growth_rate{0};   ///< max Re s [1/s] (< 0 stable)
  double frequency_hz{0};  ///< |Im s|/2π of that root [Hz]
};
/// The linearised motion with the process stiffness G (milling frame) [N/m].
ModeCouplingState modeCouplingAt(const ModalModel& dyn, const Mat3& G);

struct ModeCouplingLimit {
  bool bounded{false};       ///< false: stable up to kScanMax × ap
  double ap_lim{0};          ///< [m] (when bounded)
  double margin{0};          ///< ap_lim/ap (when bounded)
  bool flutter{false};       ///< the root crossing at the limit is a complex pair
  double frequency_hz{0};    ///< its frequency at the limit [Hz]
  ModeCouplingState at_cut;  ///< at the cut's own ap
};
ModeCouplingLimit modeCouplingLimit(const ModalModel& dyn, const ProcessGradient& g, double ap);

}  // namespace roprec
