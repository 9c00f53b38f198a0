#pragma once
/// \file milling_stability.hpp
/// Regenerative chatter by the zero-order approximation (Altintas & Budak 1995; Altintas,
/// Manufacturing Automation, 2nd ed., Ch. 3.5), docs/process.md §4.7.
///
/// Milling frame (milling.hpp): X = feed, φ clockwise from +Y, forces on the tool; r(t) is the
/// tool's vibration in the XY plane, so the dynamic chip is Δh = (r(t) − r(t − T))·n(φ),
/// n = (sin φ, cos φ), T = 60/(Nt n) the tooth period. Linearised force law (Kienzle tangent at
/// the mean chip thickness h_m of the cut, milling.hpp):
///   Kt = kc1.1 (1 − mc) (h_m/h0)^(−mc)  [N/m²],  Kr = radial_ratio.
/// Averaged over the tooth period (the zero-order term of the Fourier series):
///   F(t) = (Nt a Kt / 4π) α (r(t) − r(t − T)),  α = ∫_{φst}^{φex} A(φ) dφ,
///   α_xx = ½[cos 2φ − 2Kr φ + Kr sin 2φ],   α_xy = ½[−sin 2φ − 2φ + Kr cos 2φ],
///   α_yx = ½[−sin 2φ + 2φ + Kr cos 2φ],     α_yy = ½[−cos 2φ − 2Kr φ − Kr sin 2φ]
/// (each evaluated from φst to φex). With r = G F (G: the XY block of the receptance,
/// milling_dynamics.hpp — robot modes and their coupling through G_xy, plus the tool mode):
///   det[I + Λ Φ0(iω_c)] = 0,  Φ0 = α G(iω_c),  Λ = −(Nt/4π) a Kt (1 − e^{−iω_c T}).
/// For each eigenvalue λ of Φ0: Λ = −1/λ, κ = Λ_I/Λ_R, and (where Λ_R < 0)
///   a_lim = −2π Λ_R (1 + κ²) / (Nt Kt),   ε = π − 2 atan κ,   T = (ε + 2kπ)/ω_c,
///   n = 60/(Nt T),  k = 0, 1, 2, … (lobe number).
/// The limiting depth at a spindle speed n is the smallest a_lim over the chatter frequencies where
/// ω_c T(n) − ε = 2kπ for an integer k ≥ 0 (found on a frequency grid — bands around each mode
/// and steps ≤ 1/16 of the tooth frequency elsewhere — by interpolating a_lim linearly in the
/// real lobe number (ω_c T − ε)/2π between grid points where it crosses an integer; eigenvalue
/// branches are followed between grid points by nearest match). Helix and the axial (Z) modes
/// are not in the zero-order model.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "compensator/process/milling.hpp"
#include "compensator/process/milling_dynamics.hpp"

namespace roprec {

/// What the zero-order model needs of the cut.
struct StabilityCut {
  int teeth{3};
  double Kt{0};  ///< tangential cutting coefficient (tangent) [N/m²]
  double Kr{0};  ///< radial/tangential ratio
  ImmersionAngles arc;
};
/// The cut of a milling model (Kt the Kienzle tangent at h_m of m.cut).
StabilityCut stabilityCutOf(const MillingModel& m);

/// α (the integrals above) for the immersion `arc`.
Eigen::Matrix2d directionalFactors(const ImmersionAngles& arc, double Kr);

/// One eigenvalue branch at a chatter frequency.
struct ChatterRoot {
  double a_lim{0};    ///< [m]; ≤ 0 (or not finite): this branch cannot chatter at ω_c
  double epsilon{0};  ///< phase ε in (0, 2π) [rad]
};
/// Both eigenvalue branches of Φ0 at ω_c [rad/s] (unordered).
std::array<ChatterRoot, 2> chatterRoots(const ModalModel& dyn, const StabilityCut& cut,
                                        double omega_c);

struct StabilityLimit {
  bool bounded{false};   ///< false: no chatter frequency found at this speed (stable at any depth)
  double ap_lim{0};      ///< limiting axial depth [m] (when bounded)
  double chatter_hz{0};  ///< chatter frequency at the limit [Hz]
  int lobe{0};           ///< k
};
/// The limiting depth at `spindle_rpm`.
StabilityLimit limitingDepth(const ModalModel& dyn, const StabilityCut& cut, double spindle_rpm);

struct LobeSample {
  double spindle_rpm{0};
  StabilityLimit limit;
};
/// The stability lobe diagram: limitingDepth at `steps` speeds equally spaced on [lo, hi] rpm.
std::vector<LobeSample> stabilityLobes(const ModalModel& dyn, const StabilityCut& cut,
                                       double rpm_lo, double rpm_hi, int steps);

}  // namespace roprec
