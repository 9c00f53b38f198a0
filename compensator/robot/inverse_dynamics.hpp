#pragma once
/// \file inverse_dynamics.hpp
/// Inverse dynamics by the virtual power principle on the mixed-natural-coordinate model
/// (docs/model.md §4–§5; García de Jalón & Bayo 1994, velocity transformations):
///
///   τ = Rᵀ (M q̈ − Q_ext),   q̈ = R z̈ + Sc,
///
/// evaluated without forming R: solve Aᵀ x = M q̈ − Q_ext (one adjoint sweep), then
/// τ = x[66..71] (the B rows) and the constraint multipliers λ = −x[0..65] (joint reactions).
/// M is the constant natural-coordinate mass matrix (K ⊗ I₃ per body) and Q_ext collects
///   * gravity            Q_g = m [1, a₁, a₂, a₃]ᵀ ⊗ g           (constant)
///   * a force F at the TCP   Q = N(c_tcp) ⊗ F                  (constant map)
///   * a couple N on body 6   Q_{d_k} = ½ N × d_k  (orthonormal triad u, v, w)
///   * the axis-2 balancer    Q_{θ_j} = τ_cb(θ_j)   (counterbalance.hpp; with gravity only:
///     it is part of the weight loads and absent when the model has no gravity)
/// The tool/spindle mass and centre of mass are part of body 6 (buildModel's ToolAttachment).
///
/// Sign convention: τ_i is the torque the drive of joint i applies to the distal chain about
/// the joint axis (N m) — the torque needed to hold/move the arm; the wrench is what the
/// environment exerts ON the TCP, base frame, reference point the TCP (docs/contract.md §2).
/// Requires nc::solvePosition at z first.

#include "compensator/robot/model.hpp"

namespace roprec::nc {

/// Wrench on the TCP: force (N) and moment (N m), base frame, about the TCP.
struct Wrench {
  Vec3 force{Vec3::Zero()};
  Vec3 moment{Vec3::Zero()};
};

struct Loads {
  bool gravity{true};  ///< include link, tool and spindle weight (model.gravity)
  Wrench tcp;          ///< wrench on the TCP, fixed in the base frame
  /// Wrench on the TCP given in the TCP frame and following the TCP's actual orientation
  /// (a process load: the thrust acts along the real drill axis). Added to `tcp` after
  /// rotation by R_W_tcp(q).
  Wrench tcp_tool;
};

/// Q_ext into `Q` (72): gravity (if loads.gravity) + TCP wrench, at data.q.
void generalizedForces(const Model& model, const Data& data, const Loads& loads, VecQ& Q);
/// y += M x  (body by body with the constant K blocks).
void addMassTimes(const Model& model, const VecQ& x, VecQ& y);

/// τ = Rᵀ(M q̈ − Q_ext) into data.tau, λ into data.lambda; q̇, q̈ left in data.qd, data.qdd.
const Vec6& inverseDynamics(const Model& model, Data& data, const Vec6& zd, const Vec6& zdd,
                            const Loads& loads);

/// Static torques τ = −Rᵀ Q_ext (ż = z̈ = 0).
const Vec6& staticTorques(const Model& model, Data& data, const Loads& loads);

/// Joint-space inertia R^T M R (6×6, SPD) at data.q.
Mat6 jointSpaceInertia(const Model& model, Data& data);

}  // namespace roprec::nc
