#pragma once
/// \file fast_equilibrium.hpp
/// The static-equilibrium kernel of the deflection path (docs/model.md §6.4): the same serial
/// chain, loads and sign convention as the mixed-natural-coordinate model (model.hpp,
/// inverse_dynamics.hpp — the model of record), evaluated by the forward recursion of the link
/// frames, with one sin/cos pair per joint and the analytic torque sensitivity ∂τ/∂θ for the
/// Newton iteration of the compliance equilibrium (deflection.hpp). tests/fast_equilibrium_test.cpp
/// checks it against the natural-coordinate model to 1e-9 relative on the bundled and the corpus
/// robots.
///
/// ## Frames (chain.hpp conventions; base frame W, SI)
///   R_W_Ji = R_W_L(i-1) R_Oi,  p_i = p_(i-1) + R_W_L(i-1) o_i,  u_i = R_W_Ji ū_i,
///   R_W_Li = R_W_Ji Rot(ū_i, θ_i),  Rot = c I + s [ū]× + (1 − c) ū ūᵀ   (Rodrigues),
/// with (R_Oi, o_i) = T_{L(i-1), Ji} the joint origin and ū_i its unit axis; TCP
/// T_W_tcp = T_W_L5 T_L6_tcp.
///
/// ## Static torques (virtual work; the drive torque that holds the distal chain, N m)
///   τ_j = −u_j · Σ_{loads beyond joint j} ((r − p_j) × f + n)
/// over the link weights m_k g at the centres of mass c_k (k ≥ j, if gravity), the TCP force
/// F = F_W + R_W_tcp F_tool at p_tcp and the couple N = N_W + R_W_tcp N_tool; the axis-2 balancer
/// subtracts τ_cb(θ_j) (counterbalance.hpp). This is τ = −Rᵀ Q_ext of inverse_dynamics.hpp.
///
/// ## Sensitivity D = ∂τ/∂θ (analytic; rotation of joint i turns the bodies k ≥ i about (u_i, p_i))
/// With W_j = Σ_{k ≥ j} f_k (r_k − p_j)ᵀ (formed only here) over the base-fixed forces (weights,
/// F_W) and the tool-fixed wrench (F_t, N_t) = R_W_tcp (F_tool, N_tool) with moment M_t,i = (p_tcp
/// − p_i) × F_t
/// + N_t about p_i:
///   i ≤ j:  D_ji = u_jᵀ (tr(W_j) I − W_j − [N_W]×) u_i     (the tool-fixed wrench turns along)
///   i > j:  D_ji = −u_j · ((W_iᵀ − tr(W_i) I) u_i + u_i × M_t,i + (p_i − p_j) × (u_i × F_t))
/// plus −dτ_cb/dθ_j on the balancer joint's diagonal (balancerTorqueAndSlope, analytic).
///
/// Everything is allocation-free and writes only into `Data` or the caller's objects.

#include <limits>

#include "compensator/robot/inverse_dynamics.hpp"

namespace roprec::nc {

/// Link frames and TCP at θ (rad) into data.frames.
void chainFrames(const Model& model, Data& data, const Vec6& theta);

/// sin θᵢ and cos θᵢ of a configuration.
struct JointTrig {
  Vec6 sn{Vec6::Zero()};
  Vec6 cs{Vec6::Constant(1.0)};
};
/// sin θᵢ, cos θᵢ (one sincos per joint).
JointTrig jointTrig(const Vec6& theta);
/// chainFrames with the joints' sines and cosines given (trig must belong to theta).
void chainFrames(const Model& model, Data& data, const Vec6& theta, const JointTrig& trig);
/// trig of `from` → trig of `to` without sin/cos where |δ| = |toᵢ − fromᵢ| ≤ 0.01 rad (a Newton
/// step of the equilibrium): angle addition with the Taylor series of sin δ (to δ⁷) and cos δ
/// (to δ⁸), truncation < 1e-20 — the result differs from std::sin/std::cos by round-off
/// (≤ 4e-16 absolute); larger or non-finite steps call std::sin/std::cos.
void shiftTrig(JointTrig& trig, const Vec6& from, const Vec6& to);

/// Load sums of one configuration (data.frames) and loads: what τ and ∂τ/∂θ are made of.
struct StaticLoadSums {
  std::array<Vec3, 6> f{};     ///< weight of body k (0 without gravity or mass), N
  std::array<Vec3, 6> r{};     ///< its centre of mass in W, m
  Vec3 F_all_w{Vec3::Zero()};  ///< base-fixed TCP force, N
  Vec3 N_w{Vec3::Zero()};      ///< base-fixed couple, N m
  Vec3 F_t{Vec3::Zero()};      ///< tool-fixed force in W, N
  Vec3 N_t{Vec3::Zero()};      ///< tool-fixed couple in W, N m
  bool balancer{false};        ///< the balancer acts (gravity on, present)
  double balancer_slope{0.0};  ///< dτ_cb/dθ at the balancer joint, N m/rad
  /// ψ of the last balancer evaluation (NaN: none yet) and its sin/cos: the next evaluation
  /// shifts them by angle addition when ψ moved by ≤ 0.01 rad (as shiftTrig), else evaluates.
  double balancer_psi{std::numeric_limits<double>::quiet_NaN()};
  double balancer_sin{0.0};
  double balancer_cos{1.0};
};

/// τ_cb(q) (N m, equal to counterbalance.hpp's balancerTorque) and its slope dτ_cb/dq (N m/rad),
/// analytic, with one sin/cos pair and at most one pow. With ψ = ψ₀ + s q, ℓ² = r² + d² − 2rd cos
/// ψ, the stroke σ = ±(ℓ − ℓ_ref), the load f(σ) (spring f_ref + kσ; gas p_ref A (V₀/(V₀ − Aσ))ⁿ,
/// df/dσ = n A f/(V₀ − Aσ)) and F = ±f (push +, pull −), so dF/dℓ = −df/dσ:
///   τ = s F r d sin ψ/ℓ,   dℓ/dq = s r d sin ψ/ℓ,
///   dτ/dq = s r d [(dF/dℓ dℓ/dq sin ψ + s F cos ψ)/ℓ − F sin ψ dℓ/dq/ℓ²].
/// Non-finite when the gas volume is exhausted (as balancerTorque); both 0 without a balancer.
struct BalancerTorque {
  double torque{0.0};
  double slope{0.0};
};
BalancerTorque balancerTorqueAndSlope(const Counterbalance& cb, double q);
/// The same from sin ψ and cos ψ.
BalancerTorque balancerTorqueAndSlope(const Counterbalance& cb, double sin_psi, double cos_psi);

/// τ (N m) at data.frames for `loads`; `sums` receives what staticSensitivity needs.
void staticTorquesFromFrames(const Model& model, const Data& data, const Loads& loads, Vec6& tau,
                             StaticLoadSums& sums);
/// D = ∂τ/∂θ (N m/rad) at data.frames from the sums of staticTorquesFromFrames.
void staticSensitivity(const Model& model, const Data& data, const StaticLoadSums& sums, Mat6& D);

/// TCP Jacobian [v; ω] (base frame, reference point the TCP) from data.frames into data.J_tcp:
/// column j = [u_j × (p_tcp − p_j); u_j]. Equal to tcpJacobian at the same configuration.
const Mat6& tcpJacobianFromFrames(const Model& model, Data& data);

/// Makes data a natural-coordinate state of data.frames: q (the exact closed-form coordinates,
/// Φ(q) = 0 to round-off), z, the angle-row forms, T_W_tcp, T_W_flange; the factorisation is left
/// to be made lazily (tcpJacobian, staticTorques, ... work as after solvePosition).
void syncNaturalCoordinates(const Model& model, Data& data);

}  // namespace roprec::nc
