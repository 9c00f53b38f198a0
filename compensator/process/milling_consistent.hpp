#pragma once
/// \file milling_consistent.hpp
/// The coupled static solve of a path point made consistent with the revolution resolved by edge
/// angle (milling.hpp edgeRevolution), docs/process.md §4.5.

#include <functional>

#include "compensator/process/milling.hpp"

namespace roprec {

/// ## The edge-consistent static solve (docs/process.md §4.5)
/// The static deflection δ of a path point is the compliance under the mean force of the cut the
/// tool really makes: the revolution resolved by edge angle at the point's coupled cut (each edge
/// cutting what the previous edges left, runout, the vibration x(t) − x(t − kτ), ae(t), ap(t)),
///   δ = C( F̄_edge(fz_i(δ), ae_i(δ), ap_i(δ)) ),   F̄_edge = edgeRevolution(…).mean,
/// with fz_i, ae_i, ap_i as in coupleMillingPoint (the previous point's δ_{i−1}, δprev, the wall
/// normal and Z). Solved by an outer iteration on a force correction ΔF: round k solves the
/// coupled point (Newton, as coupleMillingPoint) with the law F̄(fz, ae)·ap/ap₀ + ΔF_k (ΔF only
/// while the tool cuts), then resolves the revolution at its cut and sets
///   ΔF_{k+1} = F̄_edge(cut(δ_k)) − F̄(cut(δ_k)).
/// Converged (consistent) when the residual of the consistent equation itself,
/// |δ_k − C(F̄_edge(cut(δ_k)))|, is ≤ options.tolerance; the reported force is then F̄_edge. ΔF is
/// the mean-force effect of the vibration and the discretisation of the revolution (it varies
/// slowly with δ, so one or two rounds suffice; at most kConsistencyRounds). Along a path the
/// previous point's ΔF is a good start. Without modes F̄_edge is the rigid revolution's mean
/// (= F̄ up to the revolution's sampling, ~0.1 %).
using EdgeRevolutionFunction = std::function<EdgeRevolution(double fz, double ae, double ap)>;
constexpr int kConsistencyRounds = 8;
struct ConsistentCoupling {
  CouplingResult point;           ///< the last round's solve (force = F̄_edge when consistent)
  EdgeRevolution edges;           ///< the revolution at its cut
  Vec3 correction{Vec3::Zero()};  ///< ΔF of the last round [N]
  int rounds{0};
  double edge_residual{0};  ///< |δ − C(F̄_edge)| [m]
  bool consistent{false};
  [[nodiscard]] bool converged() const { return point.converged && consistent; }
};
/// `edges(fz, ae, ap)`: the revolution at a cut (e.g. edgeRevolution with the point's modes, or a
/// cached one).
ConsistentCoupling coupleMillingPointConsistent(const MillingModel& m,
                                                const ComplianceFunction& compliance,
                                                const EdgeRevolutionFunction& edges,
                                                const CouplingState& state,
                                                const CouplingOptions& options = {},
                                                const Vec3& start_correction = Vec3::Zero());

}  // namespace roprec
