#pragma once
/// \file counterbalance.hpp
/// The weight balancer of axis 2 (KUKA hydropneumatic balancer, ABB/FANUC spring balancers):
/// a two-force member between a point A fixed in the parent body and a point B of the arm,
/// both in the plane ⊥ the joint axis (docs/model.md §6.6).
///
///   ψ(q)  = ψ₀ + s·q                      angle AOB at the joint angle q (URDF, rad), s = ±1
///   ℓ(q)  = √(r² + d² − 2 r d cos ψ)      balancer length (law of cosines), m
///   dℓ/dq = s · r d sin ψ / ℓ
///   τ_cb(q) = F(ℓ) · dℓ/dq = s · F(ℓ) · r · d · sin ψ / ℓ          (N m)
///
/// with r = |OB| (pivot O on the joint axis → arm attachment), d = |OA| (pivot → attachment on
/// the parent body) and F the balancer force along AB, positive when it pushes A and B apart.
/// τ_cb is the generalised force the balancer exerts on the joint coordinate (+q direction);
/// the drive then supplies τ = τ_g − τ_cb (inverse_dynamics.hpp adds it to Q_ext of the angle
/// coordinate). It derives from the potential V(ℓ): τ_cb = −dV/dq.
///
/// Force laws (stroke σ: how far the balancer is loaded beyond its reference length ℓ_ref;
/// action "push": σ = ℓ_ref − ℓ, F = +f(σ); action "pull": σ = ℓ − ℓ_ref, F = −f(σ)):
///   spring: f(σ) = F_ref + k_s σ                    V = F_ref σ + ½ k_s σ²
///   gas:    f(σ) = p_ref A (V₀ / (V₀ − A σ))ⁿ        V = ∫₀^σ f dσ' (polytropic, n = 1 isothermal)
/// F_ref preload (N), k_s spring rate (N/m), p_ref gas pressure (Pa), A piston area (m²),
/// V₀ gas volume (m³), all at ℓ_ref.

#include <string>

namespace roprec {

struct Counterbalance {
  enum class Law { kSpring, kGas };
  enum class Action { kPush, kPull };
  int joint{-1};  ///< 0-based joint index; −1: no balancer
  Law law{Law::kSpring};
  Action action{Action::kPush};
  double r{0.0};             ///< m, pivot → arm attachment B
  double d{0.0};             ///< m, pivot → parent attachment A
  double psi0{0.0};          ///< rad, angle AOB at q = 0
  double sign{1.0};          ///< dψ/dq (±1)
  double length_ref{0.0};    ///< m
  double force_ref{0.0};     ///< N (spring preload at ℓ_ref)
  double stiffness{0.0};     ///< N/m (spring)
  double pressure_ref{0.0};  ///< Pa (gas, at ℓ_ref)
  double area{0.0};          ///< m² (gas piston)
  double volume_ref{0.0};    ///< m³ (gas, at ℓ_ref)
  double polytropic{1.0};    ///< gas exponent n (1 isothermal, 1.4 adiabatic)
  std::string source;
  int line{0};  ///< card line of the element (messages)
  [[nodiscard]] bool present() const { return joint >= 0; }
};

/// ℓ(q), m.
double balancerLength(const Counterbalance& cb, double q);
/// Stroke σ(ℓ) beyond ℓ_ref (m), see the file comment.
double balancerStroke(const Counterbalance& cb, double length);
/// F(ℓ) along AB, N, positive pushing apart. Non-finite when the gas volume is exhausted.
double balancerForce(const Counterbalance& cb, double length);
/// τ_cb(q), N m, on the joint coordinate (+q direction).
double balancerTorque(const Counterbalance& cb, double q);
/// V(q), J (τ_cb = −dV/dq); V = 0 at ℓ_ref.
double balancerEnergy(const Counterbalance& cb, double q);
/// "" when the balancer is physical on [lower, upper] (ℓ > 0, gas volume > 0, |s| = 1, r, d > 0),
/// else what is wrong.
std::string balancerProblem(const Counterbalance& cb, double lower, double upper);

}  // namespace roprec
