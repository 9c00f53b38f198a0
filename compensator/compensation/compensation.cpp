#include "compensator/compensation/compensation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <future>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "compensator/compensation/nlopt_problem.hpp"
#include "compensator/precision/parallel.hpp"
#include "compensator/robot/fast_equilibrium.hpp"
#include "compensator/support/c_format.hpp"

namespace roprec {

const char* orientationModeName(OrientationMode m) {
  switch (m) {
    case OrientationMode::kKeep:
      return "keep";
    case OrientationMode::kFlipFree:
      return "flip-free";
    case OrientationMode::kStiffest:
      return "stiffest";
  }
  return "?";
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Equilibrium options of the compensation's checks: only T_real and data.frames are read after.
nc::DeflectionOptions framesOnly() {
  nc::DeflectionOptions o;
  o.natural_state = false;
  return o;
}

Pose rotZ(double psi) {
  Pose T = Pose::Identity();
  T.linear() = Eigen::AngleAxisd(psi, Vec3::UnitZ()).toRotationMatrix();
  return T;
}

/// Why a candidate rotation is not admissible.
enum class Why : std::uint8_t { kNone, kUnreachable, kLimits, kSingular, kWrist };

/// One candidate: the IK solution for the hole at ψ and its costs. 96 bytes: the candidate grids
/// of flip-free and stiffest hold `grid` of them per hole for the whole program.
struct Node {
  Vec6 q{Vec6::Zero()};
  double psi{0.0};
  double u_def{0.0};    ///< m: linearised deflection-model uncertainty (stiffness proxy)
  double penalty{0.0};  ///< limits + wrist proximity (dimensionless)
  double wrist{0.0};    ///< |sin(θ5 + α)|
  /// stiffest, ψ = 0 in a fixed branch: a bound on |u_def(ψ) − u_def| over every rotation ψ
  /// about the drill axis (m; Evaluator::rotationSpread), +inf where none is known
  double u_spread{kInf};
  std::int8_t branch{-1};
  Why why{Why::kNone};          ///< when not feasible
  std::int8_t limit_joint{-1};  ///< kLimits: a joint (0-based) outside its limits
  bool feasible{false};
  /// a solution was passed over for |θ5| < margin (enforce_wrist): without the requirement the
  /// evaluation may differ; without such a solution it is this node, bit for bit
  bool wrist_rejected{false};
};
static_assert(sizeof(Node) <= 96, "a grid holds many of them");

/// n rows of K values in one block (the per-hole candidate grids and DP tables: no allocation per
/// hole); row i is a span of K. The rows are first written by `threads` workers: a 10,000-hole
/// candidate grid is ~25 MB, whose pages fault in on one thread in ~10 ms otherwise.
template <class T>
class Grid {
  static_assert(std::is_trivially_destructible_v<T>, "rows are filled in place, never destroyed");

 public:
  Grid() = default;
  Grid(size_t n, size_t K, const T& fill, int threads = 1) : n_(n), K_(K), v_(allocate(n * K)) {
    parallelFor(n, threads, [&](int, size_t i) { std::uninitialized_fill_n(row(i), K_, fill); });
  }
  [[nodiscard]] size_t size() const { return n_; }
  [[nodiscard]] size_t width() const { return K_; }
  std::span<T> operator[](size_t i) { return {row(i), K_}; }
  std::span<const T> operator[](size_t i) const { return {v_.get() + i * K_, K_}; }

 private:
  static constexpr std::align_val_t kAlign{alignof(T)};
  struct Free {
    void operator()(T* p) const { ::operator delete(p, kAlign); }
  };
  static T* allocate(size_t count) {
    return static_cast<T*>(::operator new(count * sizeof(T), kAlign));
  }
  T* row(size_t i) { return v_.get() + i * K_; }
  size_t n_{0};
  size_t K_{0};
  std::unique_ptr<T, Free> v_;
};

/// What every candidate of a run evaluates with, computed once (the same values as computed per
/// candidate): the TCP → flange inverse, sin of the wrist margins, the effective joint stiffness.
struct EvaluatorConstants {
  Pose tcp_inverse;  ///< T_L6_tcp⁻¹ (of m.model)
  double sin_margin;
  double sin_twice_margin;
  nc::Vec6 keff;
  EvaluatorConstants(const PredictionModel& m, const CompensationOptions& o)
      : tcp_inverse(m.model.T_L6_tcp.inverse()),
        sin_margin(std::sin(o.wrist_margin)),
        sin_twice_margin(std::sin(2.0 * o.wrist_margin)),
        keff(m.compliance.effective()) {}
};

/// The ψ grid's rotations Rz(ψ_k) (gridPsi), made once per thread and grid size.
class GridRotations {
 public:
  const Pose& at(int k, int grid) {
    if (grid_ != grid) {
      rot_.resize(static_cast<size_t>(grid));
      for (int j = 0; j < grid; ++j) rot_[static_cast<size_t>(j)] = rotZ(gridPsiOf(j, grid));
      grid_ = grid;
    }
    return rot_[static_cast<size_t>(k)];
  }
  /// ψ_k = 2πk/grid wrapped to (−π, π]: node 0 is the programmed rotation ψ = 0.
  static double gridPsiOf(int k, int grid) {
    const double psi = 2.0 * kPi * k / grid;
    return psi > kPi + 1e-12 ? psi - 2.0 * kPi : psi;
  }

 private:
  int grid_{0};
  std::vector<Pose> rot_;
};

struct Evaluator {
  const PredictionModel& m;
  PredictionData& d;
  const CompensationOptions& o;
  bool after_budget{true};  ///< assemble re-predicts the compensated target (budget, verdict)
  EvaluatorConstants c{m, o};
  GridRotations grid_rot{};
  /// solveIk's scratch between the candidates (realIk(m) only): the rotations of a hole about its
  /// axis mostly share the wrist centre, hence joints 1–3, to the last bit
  IkArmCache ik_cache{};

  nc::Loads loadsFor(const ProcessAtDiameter* proc) const { return processLoads(m, proc); }

  const ProcessAtDiameter* processFor(const HoleRequest& h) const {
    return roprec::processFor(m, h);
  }

  /// IK of the real robot (the link angles θ_d that put the real TCP at T_W_tcp, realIk) in
  /// `branch` (−1: any) nearest `seed`; `enforce_wrist`: |θ5| ≥ margin.
  Node evaluate(const HoleRequest& h, double psi, int branch, const Vec6& seed, bool enforce_wrist,
                bool with_cost) {
    return evaluate(h, loadsFor(processFor(h)), psi, branch, seed, enforce_wrist, with_cost);
  }
  /// evaluate with h's loads (loadsFor(processFor(h))) given: a caller evaluating many rotations
  /// of one hole looks its process up once.
  Node evaluate(const HoleRequest& h, const nc::Loads& loads, double psi, int branch,
                const Vec6& seed, bool enforce_wrist, bool with_cost) {
    return evaluate(h, loads, psi, rotZ(psi), branch, seed, enforce_wrist, with_cost);
  }
  /// evaluate at node k of the ψ grid (its rotation made once), h's loads given.
  Node evaluateGrid(const HoleRequest& h, const nc::Loads& loads, int k, int grid, int branch,
                    const Vec6& seed, bool enforce_wrist, bool with_cost) {
    return evaluate(h, loads, GridRotations::gridPsiOf(k, grid), grid_rot.at(k, grid), branch, seed,
                    enforce_wrist, with_cost);
  }

 private:
  /// evaluate with Rz = rotZ(psi).
  Node evaluate(const HoleRequest& h, const nc::Loads& loads, double psi, const Pose& Rz,
                int branch, const Vec6& seed, bool enforce_wrist, bool with_cost) {
    Node n;
    n.psi = psi;
    const Pose T = h.T_W_tcp * Rz;
    const Pose T_flange = T * c.tcp_inverse * m.model.T_L6_flange;
    IkOptions opt;
    opt.seed = &seed;
    opt.branch = branch;  // the other branches are never candidates: not solved
    opt.arm_cache = &ik_cache;
    solveIk(realIk(m), T_flange, opt, d.ik);
    pickSolution(branch, seed, enforce_wrist, n);
    if (!n.feasible || !with_cost) return n;
    n.penalty = proximityPenalty(n);
    // flip-free reads u_def only through the finiteness check below (its costs and refinement
    // never read it): about a quarter of a flip-free candidate's cost goes to that check
    n.u_def = deflectionUncertainty(loads, T, n.q);
    if (o.mode == OrientationMode::kStiffest && psi == 0.0 && branch >= 0)
      n.u_spread = rotationSpread(loads, T, n.u_def);
    // one bad hole (e.g. a non-finite load) must not poison the sequence's DP: it has no
    // admissible candidate, and the hole is reported as not compensated
    if (!std::isfinite(n.u_def) || !std::isfinite(n.penalty)) {
      n.feasible = false;
      n.why = Why::kUnreachable;
    }
    return n;
  }

  /// The admissible solution of d.ik in `branch` nearest `seed` into n (else why none is).
  void pickSolution(int branch, const Vec6& seed, bool enforce_wrist, Node& n) const {
    double best = kInf;
    n.why = Why::kUnreachable;
    auto worse = [&](Why w) {
      if (static_cast<int>(w) > static_cast<int>(n.why)) n.why = w;
    };
    for (int i = 0; i < d.ik.count; ++i) {
      const IkSolution& s = d.ik.solutions[static_cast<size_t>(i)];
      const int b = s.branch.index();
      if (!s.converged || (branch >= 0 && b != branch)) continue;
      if (!s.within_limits) {
        worse(Why::kLimits);
        for (int j = 0; j < 6 && n.limit_joint < 0; ++j) {
          if (s.q[j] < m.ik.lower[j] - 1e-12 || s.q[j] > m.ik.upper[j] + 1e-12)
            n.limit_joint = static_cast<std::int8_t>(j);
        }
        continue;
      }
      if (s.singular_shoulder || s.singular_wrist) {
        worse(Why::kSingular);
        continue;
      }
      if (enforce_wrist && s.branch.wrist_margin_rad < c.sin_margin) {
        worse(Why::kWrist);
        n.wrist_rejected = true;
        n.wrist = s.branch.wrist_margin_rad;
        continue;
      }
      const double dist = (s.q - seed).squaredNorm();
      if (dist < best) {
        best = dist;
        n.q = s.q;
        n.branch = static_cast<std::int8_t>(b);
        n.wrist = s.branch.wrist_margin_rad;
        n.feasible = true;
      }
    }
    if (n.feasible) n.why = Why::kNone;
  }

  /// Joint-limit and wrist proximity penalties of n (dimensionless).
  double proximityPenalty(const Node& n) const {
    double penalty = 0.0;
    for (int j = 0; j < 6; ++j) {
      const double margin = std::min(n.q[j] - m.ik.lower[j], m.ik.upper[j] - n.q[j]);
      if (margin < o.limit_margin)
        penalty += std::pow((o.limit_margin - margin) / o.limit_margin, 2);
    }
    const double s2 = c.sin_twice_margin;
    if (n.wrist < s2) penalty += std::pow((s2 - n.wrist) / s2, 2);
    return penalty;
  }

  /// The stiffness proxy at q for the TCP pose T under `loads`: the linearised deflection-model
  /// uncertainty ⊥ the axis (m), from the frame recursion (fast_equilibrium.hpp; the model of
  /// record's τ and J to 1e-9 relative). Only the linear rows of the TCP Jacobian are read: each
  /// column is formed as tcpJacobianFromFrames forms it (the same bits), none is stored.
  double deflectionUncertainty(const nc::Loads& loads, const Pose& T, const Vec6& q) {
    nc::chainFrames(m.model, d.nc, q);
    nc::Vec6 tau;
    nc::StaticLoadSums sums;
    nc::staticTorquesFromFrames(m.model, d.nc, loads, tau, sums);
    const nc::Data::ChainFrames& f = d.nc.frames;
    const Mat3 R = T.linear();
    const Vec3 e1 = R.col(0);
    const Vec3 e2 = R.col(1);
    double var = 0;
    for (int i = 0; i < 6; ++i) {
      const size_t s = static_cast<size_t>(i);
      const Vec3 Jv = f.u[s].cross(f.p_tcp - f.p[s]);
      const Vec3 v = Jv * (tau[i] / c.keff[i]) * m.uncertainty.stiffness_rel;
      var += 0.5 * (std::pow(v.dot(e1), 2) + std::pow(v.dot(e2), 2));
    }
    return std::sqrt(var);
  }

  /// After deflectionUncertainty at ψ = 0 (its frames in d.nc, its result u): a bound on
  /// |u_def(ψ) − u| over every rotation ψ about the drill axis in the same branch (m), +inf
  /// unless the drill axis is joint 6's axis (to 1e-9). On that axis T · Rz(ψ) is reached by
  /// turning joint 6 alone: the branch's solution is (θ1..θ5, θ6 + ψ) up to whole turns, so the
  /// linear Jacobian columns u_j × (p_tcp − p_j) and the plane ⊥ the axis stay, and τ changes only
  /// through what turns with joint 6 — body 6's weight off the axis (its centre of mass moves by
  /// ≤ 2 r⊥) and the tool-fixed force and couple ⊥ the axis (each changes by ≤ twice its ⊥ part):
  /// |Δτ_j| ≤ 2 (m₆ g r⊥ + |F⊥| |p_tcp − p_j| + |N⊥|). With v_j as in deflectionUncertainty,
  /// |Δv_j| ≤ |J_j| |Δτ_j| s / k_j and, u being a Euclidean norm of the projected v_j over √2,
  /// |Δu| ≤ √(½ Σ |Δv_j|²). Added: 1e-6 u for the round-off of the rotated solutions (the IK's
  /// and the frames' last bits, the refinement's tolerance on a calibrated chain).
  double rotationSpread(const nc::Loads& loads, const Pose& T, double u) const {
    constexpr double kOnAxis = 1e-9;
    const nc::Data::ChainFrames& f = d.nc.frames;
    const Vec3& axis = f.u[5];
    const Vec3 to_tcp = f.p_tcp - f.p[5];
    if (axis.cross(T.linear().col(2)).norm() > kOnAxis || axis.cross(to_tcp).norm() > kOnAxis)
      return kInf;
    const nc::Body& b6 = m.model.bodies[5];
    const bool gravity = loads.gravity && !m.model.gravity.isZero(0.0);
    const double weight_moment =
        gravity ? b6.mass * m.model.gravity.norm() * axis.cross(f.R[5] * b6.com).norm() : 0.0;
    const double f_perp = axis.cross(f.R_tcp * loads.tcp_tool.force).norm();
    const double n_perp = axis.cross(f.R_tcp * loads.tcp_tool.moment).norm();
    double var = 0.0;
    for (int i = 0; i < 6; ++i) {
      const size_t s = static_cast<size_t>(i);
      const Vec3 lever = f.p_tcp - f.p[s];
      const double dtau = 2.0 * (weight_moment + f_perp * lever.norm() + n_perp);
      const double dv = f.u[s].cross(lever).norm() * dtau / c.keff[i] * m.uncertainty.stiffness_rel;
      var += 0.5 * dv * dv;
    }
    const double spread = std::sqrt(var) + 1e-6 * u;
    return std::isfinite(spread) ? spread : kInf;
  }
};

double travel(const Vec6& a, const Vec6& b) {
  static const double w[6] = {1.0, 1.0, 1.0, 0.6, 0.6, 0.4};
  double s = 0;
  for (int i = 0; i < 6; ++i) s += w[i] * (a[i] - b[i]) * (a[i] - b[i]);
  return s;
}

bool jumpOk(const Vec6& a, const Vec6& b, double thr) {
  return std::abs(a[3] - b[3]) <= thr && std::abs(a[5] - b[5]) <= thr;
}

/// The jump limit applies between consecutive holes of one face (drilling axes within 10°): moving
/// to another face is a repositioning move with a retract, where the wrist may turn.
bool sameFace(const HoleRequest& a, const HoleRequest& b) {
  return a.T_W_tcp.linear().col(2).dot(b.T_W_tcp.linear().col(2)) > std::cos(10.0 * kDeg);
}

/// Whether the jump limit applies from hole a to the next hole b: same face, and b's posture is
/// not set by a joint target the program moves to before it (`ik_seed`: MoveAbsJ, PTP to axis
/// values) — that joint move is the program's own, the compensation does not change it.
bool jumpLimited(const HoleRequest& a, const HoleRequest& b) {
  return sameFace(a, b) && !b.ik_seed;
}

/// Sequence cost, compared lexicographically: holes with ψ ≠ 0, then Σ|ψ| (rad), then the rest
/// (travel and proximity penalties; stiffest: the stiffness proxy first). Stiffest counts no
/// changes: its objective is the stiffness.
struct Cost {
  int changes{0};
  double dpsi{0.0};
  double rest{0.0};
  Cost operator+(const Cost& o) const {
    return {changes + o.changes, dpsi + o.dpsi, rest + o.rest};
  }
  bool operator<(const Cost& o) const {
    if (changes != o.changes) return changes < o.changes;
    if (std::abs(dpsi - o.dpsi) > 1e-9) return dpsi < o.dpsi;
    return rest < o.rest;
  }
};

const Cost kInfCost{std::numeric_limits<int>::max() / 2, kInf, kInf};

bool isFinite(const Cost& c) { return std::isfinite(c.rest); }

/// ψ values closer than this to 0 count as the programmed rotation.
constexpr double kPsiKept = 1e-9;

/// Stiffest turns a hole only for a gain of at least this share of its U_work: a rotation that
/// gains less is not worth changing the programmed orientation (with the drill on the flange
/// axis ψ turns axis 6 only, and the stiffness hardly changes).
constexpr double kStiffnessGainMin = 0.01;

Cost nodeCost(const Node& n, OrientationMode mode) {
  if (mode == OrientationMode::kStiffest) {
    const bool changed = std::abs(n.psi) > kPsiKept;
    return {0, 0.0, n.u_def * 1e6 * (changed ? 1.0 + kStiffnessGainMin : 1.0) + 0.1 * n.penalty};
  }
  const bool changed = std::abs(n.psi) > kPsiKept;
  return {changed ? 1 : 0, std::abs(n.psi), 0.1 * n.penalty};
}

Cost transitionCost(const Node& a, const Node& b, OrientationMode mode) {
  if (mode == OrientationMode::kStiffest) return {0, 0.0, 1e-3 * travel(a.q, b.q)};
  return {0, 0.0, travel(a.q, b.q)};
}

// ---- stage 1: the program as it is

/// Predictions of the original targets (continuity seeds, like `roprec predict`).
/// `at(i)`: where hole i's prediction goes.
template <class At>
void predictOriginal(const PredictionModel& m, PredictionData& d,
                     std::span<const HoleRequest> holes, const std::optional<Vec6>& first,
                     const At& at) {
  std::optional<Vec6> prev = first;
  for (size_t i = 0; i < holes.size(); ++i) {
    HolePrediction& b = at(i);
    try {
      b = predictHole(m, d, holes[i], prev ? &*prev : nullptr);
    } catch (const std::exception& e) {
      // isolated per hole: the others are predicted and compensated as usual
      b = HolePrediction{};
      b.id = holes[i].id;
      b.status = HoleStatus::kNotConverged;
      b.verdict = Verdict::kNotConverged;
      b.reason = std::string("prediction failed: ") + e.what();
      continue;
    }
    if (b.status == HoleStatus::kOk) prev = b.joints;
  }
}

// ---- stage 2: candidate rotations about each drill axis

/// Counters of one hole's candidates (summed into CompensationStats in hole order).
struct NodeCount {
  int nodes{0};
  int infeasible{0};
  bool relaxed_wrist{false};
  bool enforced{true};  ///< the grid is the one with |θ5| ≥ margin enforced (gridNode)
};

/// The note of a hole where no rotation meets the wrist margin (NodeCount::relaxed_wrist).
constexpr const char* kRelaxedWristNote =
    "no rotation about the drill axis meets |θ5| ≥ the wrist margin at this hole";

/// The ψ grid of hole h seeded with s (keep: the single ψ = 0 candidate). Where |θ5| ≥ margin
/// fails for every ψ, the margin becomes a penalty (relaxed_wrist: the hole's note says so).
NodeCount holeNodes(Evaluator& ev, const HoleRequest& h, const Vec6& s, int branch, int grid,
                    std::span<Node> nodes) {
  const bool choose = ev.o.mode != OrientationMode::kKeep;
  const nc::Loads loads = ev.loadsFor(ev.processFor(h));  // one process look-up per hole
  NodeCount count;
  bool any = false;
  for (int k = 0; k < grid; ++k) {
    Node& nd = nodes[static_cast<size_t>(k)];
    nd = ev.evaluateGrid(h, loads, k, grid, branch, s, choose, choose);
    ++count.nodes;
    if (!nd.feasible) ++count.infeasible;
    any |= nd.feasible;
  }
  count.enforced = any || !choose;
  if (!any && choose) {
    // With the drill on the flange axis, ψ turns axis 6 only: if |θ5| < margin for every ψ the
    // margin cannot be met here. Keep it as a penalty and say so, rather than drop the hole.
    for (int k = 0; k < grid; ++k) {
      nodes[static_cast<size_t>(k)] = ev.evaluateGrid(h, loads, k, grid, branch, s, false, true);
      any |= nodes[static_cast<size_t>(k)].feasible;
    }
    if (any) count.relaxed_wrist = true;
  }
  return count;
}

/// Node k of the grid holeNodes gives hole h in flip-free and stiffest (seeded with s, in
/// `branch`; `enforced`: NodeCount::enforced of that grid), evaluated again: the same node.
Node gridNode(Evaluator& ev, const HoleRequest& h, const Vec6& s, int branch, int k, int grid,
              bool enforced) {
  return ev.evaluateGrid(h, ev.loadsFor(ev.processFor(h)), k, grid, branch, s, enforced, true);
}

// ---- stage 3: dynamic programming over the whole sequence

/// What the DP's forward pass carries from hole to hole: the latest hole with a reachable node
/// (`last`), its candidates and their path costs, and whether every reachable hole so far
/// connected within the threshold.
struct DpFrontier {
  std::ptrdiff_t last{-1};
  std::vector<Node> nodes;
  std::vector<Cost> cost;
  bool all_connected{true};
};

/// What the DP keeps of hole i once its grid is dropped: per node, its predecessor on the
/// cheapest admissible path ending there (`from`, −1: none), and the hole's own cheapest node
/// (`best`, −1: none reachable), where the backtracking starts a chain.
struct DpRow {
  std::span<std::int16_t> from;
  std::int16_t& best;
};

/// Forward pass over hole i (its candidates `row`) after the holes before it (`f`): the cost of
/// the cheapest admissible path ending at each node (jumps ≤ thr between holes of one face) and
/// its predecessor. `f.all_connected` turns false when a reachable hole cannot be connected
/// within thr. `cost` is scratch.
void dpForwardHole(std::span<const Node> row, const std::vector<HoleRequest>& holes, size_t i,
                   OrientationMode mode, double thr, DpFrontier& f, DpRow out,
                   std::vector<Cost>& cost) {
  const size_t K = row.size();
  cost.assign(K, kInfCost);
  std::fill(out.from.begin(), out.from.end(), std::int16_t{-1});
  for (size_t k = 0; k < K; ++k) {
    const Node& nd = row[k];
    if (!nd.feasible) continue;
    const Cost c0 = nodeCost(nd, mode);
    if (f.last < 0) {
      cost[k] = c0;
      continue;
    }
    const size_t l0 = static_cast<size_t>(f.last);
    const bool limit_jumps = mode != OrientationMode::kKeep && jumpLimited(holes[l0], holes[i]);
    for (size_t l = 0; l < f.nodes.size(); ++l) {
      const Cost& cp = f.cost[l];
      if (!isFinite(cp) || (limit_jumps && !jumpOk(f.nodes[l].q, nd.q, thr))) continue;
      const Cost c = cp + c0 + transitionCost(f.nodes[l], nd, mode);
      if (c < cost[k]) {
        cost[k] = c;
        out.from[k] = static_cast<std::int16_t>(l);
      }
    }
  }
  out.best = -1;
  Cost best = kInfCost;
  for (size_t k = 0; k < K; ++k) {
    if (isFinite(cost[k]) && cost[k] < best) {
      best = cost[k];
      out.best = static_cast<std::int16_t>(k);
    }
  }
  if (out.best >= 0) {
    f.last = static_cast<std::ptrdiff_t>(i);
    f.nodes.assign(row.begin(), row.end());
    f.cost.swap(cost);
  } else if (std::any_of(row.begin(), row.end(), [](const Node& nd) { return nd.feasible; })) {
    f.all_connected = false;  // reachable but not within the jump threshold
  }
}

/// Backtracking: the cheapest end node, then its predecessors; a hole that starts a new chain
/// (after an unreachable one) takes its own cheapest node.
std::vector<int> dpBacktrack(const Grid<std::int16_t>& from,
                             const std::vector<std::int16_t>& best) {
  const size_t n = from.size();
  std::vector<int> choice(n, -1);
  int cur = -1;
  for (size_t ii = n; ii-- > 0;) {
    if (cur < 0) cur = best[ii];
    if (cur >= 0) {
      choice[ii] = cur;
      cur = from[ii][static_cast<size_t>(cur)];
    }
  }
  return choice;
}

// ---- stage 4: NLopt refinement of each hole's ψ with its neighbours fixed

/// The nearest chosen feasible node before (dir −1) or after (dir +1) hole i, and whether the
/// jump limit applies between them (jumpLimited).
std::pair<const Node*, bool> neighbour(const std::vector<Node>& chosen,
                                       const std::vector<HoleRequest>& holes, size_t i, int dir) {
  for (long k = static_cast<long>(i) + dir; k >= 0 && k < static_cast<long>(chosen.size());
       k += dir) {
    const size_t kk = static_cast<size_t>(k);
    if (chosen[kk].feasible)
      return {&chosen[kk],
              dir < 0 ? jumpLimited(holes[kk], holes[i]) : jumpLimited(holes[i], holes[kk])};
  }
  return {nullptr, false};
}

/// ψ wrapped to (−π, π].
double wrapPsi(double psi) {
  const double w = std::remainder(psi, 2.0 * kPi);
  return w <= -kPi ? w + 2.0 * kPi : w;
}

/// The outcome of one hole's refinement.
struct Refined {
  bool changed{false};  ///< `node` replaces the chosen one
  Node node;
  int evaluations{0};
};

/// COBYLA on ψ within ±1 grid step, subject to |Δθ4|, |Δθ6| ≤ thr against same-face neighbours;
/// flip-free: the smallest |ψ| (with a small limit/wrist-proximity term), stiffest: node cost
/// + transitions. The result replaces chosen[i] only when feasible and better. Reads chosen[i]
/// and its two neighbours (neighbour()) only. One Refiner per thread: its NLopt problem and
/// callbacks are built once (they read the current hole's data), so refining a hole allocates
/// nothing (NLopt's own C workspace uses malloc).
class Refiner {
 public:
  explicit Refiner(Evaluator& ev) : ev_(ev) {
    prob_.setObjective([this](const std::vector<double>& x, std::vector<double>&) {
      const Node nd = evalAt(x[0]);
      return nd.feasible ? total(nd) : 1e9;
    });
    prob_.addInequality(jumpConstraint(true, 3));
    prob_.addInequality(jumpConstraint(true, 5));
    prob_.addInequality(jumpConstraint(false, 3));
    prob_.addInequality(jumpConstraint(false, 5));
    prob_.setXtolAbs(1e-4);
    prob_.setMaxEvaluations(30);
  }
  Refiner(const Refiner&) = delete;
  Refiner& operator=(const Refiner&) = delete;

  Refined refine(const std::vector<HoleRequest>& holes, const std::vector<Node>& chosen, size_t i,
                 bool enforce_wrist, int grid, double thr) {
    setHole(holes, chosen, i, enforce_wrist, thr);
    const double step = 2.0 * kPi / grid;
    const double lower = chosen[i].psi - step, upper = chosen[i].psi + step;
    prob_.setBounds(&lower, &upper);
    prob_.setInitialStep(0.25 * step);
    x_[0] = chosen[i].psi;
    const NloptProblem::Result r = prob_.optimize(x_);
    Refined out;
    out.evaluations = r.evaluations;
    if (!r.usable()) return out;
    Node nd = evalAt(x_[0]);
    const bool ok_jumps =
        (!h_.pj || jumpOk(h_.pj->q, nd.q, thr)) && (!h_.nj || jumpOk(nd.q, h_.nj->q, thr));
    const bool better = ev_.o.mode == OrientationMode::kStiffest ? nd.u_def <= chosen[i].u_def
                                                                 : total(nd) < total(chosen[i]);
    if (nd.feasible && ok_jumps && better) {
      nd.psi = wrapPsi(nd.psi);
      out.node = nd;
      out.changed = true;
    }
    return out;
  }

 private:
  /// The hole being refined: its neighbours (pj, nj: those the jump limit applies to).
  struct Hole {
    const HoleRequest* hole{nullptr};
    const Node* pn{nullptr};
    const Node* nn{nullptr};
    const Node* pj{nullptr};
    const Node* nj{nullptr};
    int branch{-1};
    Vec6 seed_q{Vec6::Zero()};
    bool enforce_wrist{false};
    double thr{0.0};
    nc::Loads loads{};  ///< the hole's (loadsFor), looked up once
  };

  void setHole(const std::vector<HoleRequest>& holes, const std::vector<Node>& chosen, size_t i,
               bool enforce_wrist, double thr) {
    const std::pair<const Node*, bool> prev_nb = neighbour(chosen, holes, i, -1);
    const std::pair<const Node*, bool> next_nb = neighbour(chosen, holes, i, +1);
    h_.hole = &holes[i];
    h_.pn = prev_nb.first;
    h_.nn = next_nb.first;
    h_.pj = prev_nb.second ? prev_nb.first : nullptr;
    h_.nj = next_nb.second ? next_nb.first : nullptr;
    h_.branch = chosen[i].branch;
    h_.seed_q = chosen[i].q;
    h_.enforce_wrist = enforce_wrist;
    h_.thr = thr;
    h_.loads = ev_.loadsFor(ev_.processFor(holes[i]));
    cached_count_ = 0;
  }

  /// The hole's node at ψ, each ψ evaluated once: COBYLA asks for the objective and the four
  /// constraints at the same ψ, and the result is a ψ it has evaluated before. The evaluation
  /// depends on ψ and the hole's set-up only, so a node kept is the one evaluating would give.
  const Node& evalAt(double psi) {
    const size_t held = std::min(cached_count_, kCached);
    for (size_t k = 0; k < held; ++k) {
      if (cached_psi_[k] == psi) return cached_[k];
    }
    const size_t slot = cached_count_++ % kCached;
    cached_[slot] =
        ev_.evaluate(*h_.hole, h_.loads, psi, h_.branch, h_.seed_q, h_.enforce_wrist, true);
    cached_psi_[slot] = psi;
    return cached_[slot];
  }

  double total(const Node& nd) const {
    const OrientationMode mode = ev_.o.mode;
    if (mode == OrientationMode::kFlipFree) return std::abs(wrapPsi(nd.psi)) + 0.05 * nd.penalty;
    double c = nodeCost(nd, mode).rest;
    if (h_.pn) c += transitionCost(*h_.pn, nd, mode).rest;
    if (h_.nn) c += transitionCost(nd, *h_.nn, mode).rest;
    return c;
  }

  /// |θ_joint − θ_joint(neighbour)| − thr ≤ 0 against the previous (or next) limited neighbour.
  NloptProblem::Function jumpConstraint(bool previous, int joint) {
    return [this, previous, joint](const std::vector<double>& x, std::vector<double>&) {
      const Node nd = evalAt(x[0]);
      const Node* other = previous ? h_.pj : h_.nj;
      if (!nd.feasible || !other) return nd.feasible ? -1.0 : 1.0;
      return std::abs(nd.q[joint] - other->q[joint]) - h_.thr;
    };
  }

  Evaluator& ev_;
  NloptProblem prob_{NLOPT_LN_COBYLA, 1};
  std::vector<double> x_{0.0};
  Hole h_;
  /// the hole's evaluations (evalAt): ψ and node, the latest kCached of them
  static constexpr size_t kCached = 32;
  std::array<double, kCached> cached_psi_{};
  std::array<Node, kCached> cached_{};
  size_t cached_count_{0};
};

/// Index of the nearest chosen feasible node before hole i, or n when there is none.
size_t previousFeasible(const std::vector<Node>& chosen, size_t i) {
  for (size_t k = i; k-- > 0;) {
    if (chosen[k].feasible) return k;
  }
  return chosen.size();
}

/// Refines every turned hole (flip-free: towards the smallest change; stiffest: the stiffest), in
/// hole order, each against its already refined predecessor and its not yet refined successor.
/// All are first refined in parallel against the unrefined sequence; in hole order, a hole whose
/// predecessor changed is refined again (the only input that differs), so the result is the
/// sequential one for any thread count.
void refineTurned(std::vector<Evaluator>& evs, const std::vector<HoleRequest>& holes,
                  const std::vector<char>& relaxed, std::vector<Node>& chosen, int grid, double thr,
                  CompensationStats& st) {
  const size_t n = chosen.size();
  auto turned = [&](size_t i) { return chosen[i].feasible && std::abs(chosen[i].psi) > kPsiKept; };
  std::vector<std::unique_ptr<Refiner>> refiners;  // one per thread
  refiners.reserve(evs.size());
  for (Evaluator& ev : evs) refiners.push_back(std::make_unique<Refiner>(ev));
  std::vector<size_t> turns;  // the turned holes, in hole order (one allocation)
  turns.reserve(static_cast<size_t>(std::count_if(chosen.begin(), chosen.end(), [&](const Node& c) {
    return c.feasible && std::abs(c.psi) > kPsiKept;
  })));
  for (size_t i = 0; i < n; ++i) {
    if (turned(i)) turns.push_back(i);
  }
  std::vector<Refined> spec(turns.size());
  parallelFor(turns.size(), static_cast<int>(evs.size()), [&](int w, size_t k) {
    const size_t i = turns[k];
    spec[k] = refiners[static_cast<size_t>(w)]->refine(holes, chosen, i, !relaxed[i], grid, thr);
  });
  std::vector<char> changed(n, 0);
  for (size_t k = 0; k < turns.size(); ++k) {
    const size_t i = turns[k];
    const size_t p = previousFeasible(chosen, i);
    const Refined r = p < n && changed[p]
                          ? refiners[0]->refine(holes, chosen, i, !relaxed[i], grid, thr)
                          : std::move(spec[k]);
    st.nlopt_evaluations += r.evaluations;
    if (!r.changed) continue;
    chosen[i] = r.node;
    changed[i] = 1;
    ++st.refined;
  }
}

// ---- stage 5: exact compensation at the chosen ψ

/// Positions only (orientation kept): the programmed position p is corrected until the predicted
/// real TCP position is the nominal one: p ← p − (p_real(p) − p_nom) (∂p_real/∂p ≈ I: a few
/// iterations). Returns the command, or nullopt when it does not converge.
std::optional<Vec6> positionOnlyCommand(Evaluator& ev, const Pose& T_nominal, const Vec6& theta_d,
                                        const nc::Loads& loads, nc::Deflection* last = nullptr) {
  const PredictionModel& m = ev.m;
  const nc::Model& controller = controllerModel(m);
  Pose T = T_nominal;
  Vec6 q = theta_d;
  for (int it = 0; it < 30; ++it) {
    const Pose T_flange = T * controller.T_L6_tcp.inverse() * controller.T_L6_flange;
    const IkNearResult ik = solveIkNear(m.ik, T_flange, q);
    if (!ik.converged) return std::nullopt;
    q = ik.q;
    const nc::Deflection df = nc::predictDeflection(m.model, ev.d.nc, m.compliance, q, loads,
                                                    framesOnly(), controllerOffset(m, ev.d.nc, q));
    if (!df.converged) return std::nullopt;
    const Vec3 err = df.T_real.translation() - T_nominal.translation();
    if (err.norm() < 5e-10) {  // 0.0005 µm: the seeded IK stops at 1e-10
      if (last) *last = df;
      return q;
    }
    T.translation() -= err;
  }
  return std::nullopt;
}

/// Exact 6-DOF inverse θ_m = θ_d + K⁻¹τ(θ_d); the controller adds its reference offset
/// to the command, so θ_cmd solves θ_cmd + off(θ_cmd) = θ_m (fixed point).
Vec6 exactCommand(Evaluator& ev, const Vec6& theta_d, const nc::Loads& loads) {
  const PredictionModel& m = ev.m;
  const Vec6 theta_m = nc::compensateCommand(m.model, ev.d.nc, m.compliance, theta_d, loads);
  Vec6 cmd = theta_m;
  for (int it = 0; it < 20 && m.controller.kind != nc::ControllerReference::Kind::kNone; ++it) {
    const Vec6 next = theta_m - controllerOffset(m, ev.d.nc, cmd);
    const double step = (next - cmd).lpNorm<Eigen::Infinity>();
    cmd = next;
    if (step < 1e-14) break;
  }
  return cmd;
}

/// True when a and b are the same posture: every joint equal up to whole turns (1e-6 rad).
bool samePostureUpToTurns(const Vec6& a, const Vec6& b) {
  for (int j = 0; j < 6; ++j) {
    if (std::abs(std::remainder(a[j] - b[j], 2.0 * kPi)) > 1e-6) return false;
  }
  return true;
}

/// Why the written flags differ from `want` (the program's, else the planned posture's): the
/// cause (ψ or the offset), then the branch or the turn flags the command does not meet. Built in
/// place (c.config_reason, inline: no allocation for the phrases).
void configReason(const Evaluator& ev, const ConfiguredSolution& cs, const VendorConfig& want,
                  bool stated, HoleCompensation& c) {
  const PredictionModel& m = ev.m;
  ConfigReasonText& r = c.config_reason;
  r.clear();
  if (stated) {
    r.append("the compensated target cannot be reached with ")
        .append(c.config_before)
        .append(" in the planned posture: ");
  }
  if (std::abs(c.psi) > kPsiKept)
    r.append("the rotation of ")
        .append(cFixed(c.psi / kDeg, 1))
        .append(" deg about the drill axis");
  else
    r.append("the compensation offset");
  r.append(" gives ");
  const std::optional<int> want_branch = branchOfConfig(want);
  if (!cs.found) {
    r.append("no solution within the joint limits (").append(cs.reason).append(")");
  } else if (want_branch && *want_branch != c.config.branch) {
    r.appendf("the IK branch %d instead of %d (--allow-branch-change)", c.config.branch,
              *want_branch);
  } else {
    const std::string why = turnFlagMismatch(m.ik, m.robot.card, c.theta_cmd, want,
                                             m.config_options, kFlagBoundaryTolerance);
    r.append(why.empty() ? std::string_view("another solution than the flags select") : why);
  }
}

/// The flags written for the command c.theta_cmd at the pose T_flange: the program's own flags
/// (h.config — honoured by the controller — else h.written_config) when the target is reached with
/// them in the same posture (a joint within kFlagBoundaryTolerance of a flag boundary matches
/// either side); else the command's own flags, with the reason. With honoured flags whose solution
/// is the command up to whole turns, the command takes the controller's representative.
void settleFlags(Evaluator& ev, const HoleRequest& h, const Pose& T_flange, HoleCompensation& c) {
  const PredictionModel& m = ev.m;
  const VendorConfig own = configurationOf(m.ik, m.robot.card, c.theta_cmd, m.config_options);
  const std::optional<VendorConfig>& stated = h.config ? h.config : h.written_config;
  c.config_in_program = stated.has_value();
  // without flags in the program: those of the programmed posture (what the report compares)
  const VendorConfig want =
      stated ? *stated : configurationOf(m.ik, m.robot.card, c.before.joints, m.config_options);
  c.config_before = formatConfig(want);
  c.config = own;
  ConfigurationMatch match;
  match.seed = &c.theta_cmd;
  match.boundary_tolerance = kFlagBoundaryTolerance;
  match.explain_inexact = false;  // configReason reads cs.reason only when nothing is found
  const ConfiguredSolution cs =
      solveIkWithConfiguration(m.ik, m.robot.card, T_flange, want, m.config_options, match);
  if (cs.found && cs.exact && samePostureUpToTurns(cs.solution.q, c.theta_cmd)) {
    c.config = want;
    c.config_text = c.config_before;
    if (h.config) {
      const Vec6 shift = cs.solution.q - c.theta_cmd;  // whole turns only
      c.theta_cmd += shift;
      c.theta_d += shift;
    }
    c.config_changed = false;
    return;
  }
  if (m.robot.card.vendor == Vendor::kKuka && want.kuka.status && c.config.kuka.status)
    c.config.kuka.status = (*want.kuka.status & ~7) | (*c.config.kuka.status & 7);
  c.config_text = formatConfig(c.config);
  c.config_changed = c.config_text != c.config_before;
  if (!c.config_changed) return;
  configReason(ev, cs, want, stated.has_value(), c);
}

/// How far finalizeHole goes: the whole result, or only as far as decides whether it is ok (the
/// re-prediction up to its status: no budget or verdict after).
/// The programmed pose, flags, residual and re-predicted budget at the command c.theta_cmd.
/// Sets c.reason and returns with c.ok false when something fails.
void assemble(Evaluator& ev, const HoleRequest& h, const nc::Loads& loads, bool positions_only,
              HoleCompensation& c, const nc::Deflection* at_command = nullptr) {
  const PredictionModel& m = ev.m;
  PredictionData& d = ev.d;
  const nc::Model& controller = controllerModel(m);  // the programmed target is FK_nom(θ_cmd)
  nc::chainFrames(controller, d.nc, c.theta_cmd);    // rigid FK (frame recursion, closed form)
  if (!d.nc.frames.p_tcp.allFinite() || !d.nc.frames.R_tcp.allFinite()) {
    c.reason = "the rigid forward kinematics of the compensated command is not finite";
    return;
  }
  c.T_programmed.linear() = d.nc.frames.R_tcp;
  c.T_programmed.translation() = d.nc.frames.p_tcp;
  if (positions_only) c.T_programmed.linear() = c.T_nominal.linear();  // exact by construction
  c.delta = c.T_programmed * c.T_nominal.inverse();
  if (ev.after_budget) {
    settleFlags(ev, h, c.T_programmed * controller.T_L6_tcp.inverse() * controller.T_L6_flange, c);
  } else {  // a host's target: the command's own flags, no search for the program's
    c.config = configurationOf(m.ik, m.robot.card, c.theta_cmd, m.config_options);
    c.config_text = formatConfig(c.config);
  }
  if (!withinLimits(m.ik, c.theta_cmd)) {
    c.reason = "the compensated command leaves the joint limits";
    return;
  }
  // the deflection at the command when the caller has it (the position-only iteration's last)
  const nc::Deflection def =
      at_command ? *at_command
                 : nc::predictDeflection(m.model, d.nc, m.compliance, c.theta_cmd, loads,
                                         framesOnly(), controllerOffset(m, d.nc, c.theta_cmd));
  if (!def.converged) {
    c.reason = "the compliance equilibrium did not converge at the compensated command";
    return;
  }
  c.residual = def.T_real.translation() - c.T_nominal.translation();
  c.residual_rot = smallRotationDifference(def.T_real.linear(), c.T_nominal.linear()).norm();
  // the compensated target as a request: h's fields but the pose, the configuration, no nominal
  // axis and no evidence (not predicted from; copying its text would allocate per hole)
  HoleRequest after;
  after.id = h.id;
  after.T_W_tcp = c.T_programmed;
  after.tolerance = h.tolerance;
  after.diameter = h.diameter;
  after.depth = h.depth;
  after.drill = h.drill;
  after.feed = h.feed;
  after.spindle_rpm = h.spindle_rpm;
  after.config = c.config;
  after.written_config = h.written_config;
  after.line = h.line;
  after.surface_W = h.surface_W;
  after.ik_seed = h.ik_seed;
  if (!ev.after_budget) {
    c.ok = true;
    return;
  }
  c.after = predictHole(m, d, after, &c.theta_cmd);
  if (c.after.status != HoleStatus::kOk) {
    c.reason = "re-prediction of the compensated target failed: " + c.after.reason;
    return;
  }
  const Vec3 a = c.T_nominal.linear().col(2);
  const double e = (c.residual - c.residual.dot(a) * a).norm();
  c.after.verdict = verdictFor(e, c.after.U_work_exact, c.after.tolerance);
  c.ok = true;
}

/// Compensation of hole h at `node` (positions_only: keep the programmed orientation).
/// `original` (the stage-1 result of the hole: id, prediction, note) is taken over (moved from:
/// a reference, so that the caller's result is not copied first).
HoleCompensation finalizeHole(Evaluator& ev, const HoleRequest& h, HoleCompensation&& original,
                              const Node& node, bool positions_only) {
  HoleCompensation c;
  c.id = std::move(original.id);
  c.before = std::move(original.before);
  c.note = original.note;
  c.psi = positions_only ? 0.0 : node.psi;
  c.T_nominal = h.T_W_tcp * rotZ(c.psi);
  c.theta_d = node.q;
  c.branch = node.branch;
  c.branch_changed = c.before.status == HoleStatus::kOk && c.branch != c.before.branch;
  const nc::Loads loads = ev.loadsFor(ev.processFor(h));
  // a host's target (no budget after) reuses the iteration's last deflection at the command
  std::optional<nc::Deflection> last;
  if (positions_only) {
    if (!ev.after_budget) last.emplace();
    const std::optional<Vec6> q =
        positionOnlyCommand(ev, c.T_nominal, c.theta_d, loads, last ? &*last : nullptr);
    if (!q) {
      c.reason = "the position-only compensation did not converge";
      return c;
    }
    c.theta_cmd = *q;
  } else {
    c.theta_cmd = exactCommand(ev, c.theta_d, loads);
  }
  assemble(ev, h, loads, positions_only, c, last ? &*last : nullptr);
  return c;
}

/// What finalizeHole takes over of a hole's stage-1 result (id, prediction, note), copied from
/// `c`: the stage-1 result itself or a result finalizeHole made of it (which carries them as they
/// were).
HoleCompensation stageOne(const HoleCompensation& c) {
  HoleCompensation s;
  s.id = c.id;
  s.before = c.before;
  s.note = c.note;
  return s;
}

/// Largest |Δθ4|, |Δθ6| between a and b (rad) and the axis (4 or 6) it is on.
std::pair<double, int> largestWristJump(const Vec6& a, const Vec6& b) {
  const double d4 = std::abs(a[3] - b[3]);
  const double d6 = std::abs(a[5] - b[5]);
  return d4 >= d6 ? std::make_pair(d4, 4) : std::make_pair(d6, 6);
}

/// Why the ψ = 0 candidate `zero` is not admissible on its own (limits, wrist, singularity).
void infeasibleZeroReason(const Node& zero, const CompensationOptions& o, CompensationStats& st,
                          PsiReasonText& r) {
  switch (zero.why) {
    case Why::kWrist:
      ++st.psi_for_wrist;
      r.append("the programmed rotation puts |axis 5| at ")
          .append(cFixed(std::asin(zero.wrist) / kDeg, 1))
          .append(" deg, inside the wrist margin of ")
          .append(cFixed(o.wrist_margin / kDeg, 1))
          .append(" deg");
      return;
    case Why::kSingular:
      ++st.psi_for_limits;
      r = "the programmed rotation is at a wrist or shoulder singularity";
      return;
    case Why::kLimits:
      ++st.psi_for_limits;
      r = "the programmed rotation leaves the joint limits";
      if (zero.limit_joint >= 0) r.appendf(" (axis %d)", zero.limit_joint + 1);
      return;
    default:
      ++st.psi_for_limits;
      r = "the programmed rotation has no solution in the programmed IK branch";
      return;
  }
}

/// Why hole i does not keep ψ = 0 (`zero`: its ψ = 0 candidate); counts the reason in `st`.
/// Written into `r` (inline: no allocation).
void psiReason(const Evaluator& ev, const std::vector<HoleRequest>& holes,
               const std::vector<Node>& chosen, const Node& zero, size_t i, double thr,
               CompensationStats& st, PsiReasonText& r) {
  const CompensationOptions& o = ev.o;
  r.clear();
  if (!zero.feasible) {
    infeasibleZeroReason(zero, o, st, r);
    return;
  }
  // ψ = 0 is admissible on its own: a neighbour's chosen posture makes it jump
  double worst_jump = thr;
  for (const int dir : {-1, +1}) {
    const std::pair<const Node*, bool> nb = neighbour(chosen, holes, i, dir);
    if (!nb.first || !nb.second) continue;
    const std::pair<double, int> j = largestWristJump(zero.q, nb.first->q);
    if (j.first > worst_jump) {
      worst_jump = j.first;
      const size_t k = static_cast<size_t>(nb.first - chosen.data());
      r.clear();
      r.appendf("keeping the programmed rotation would turn axis %d by ", j.second)
          .append(cFixed(j.first / kDeg, 1))
          .append(dir < 0 ? " deg after hole " : " deg before hole ");
      r.append(holes[k].id)
          .append(" (jump threshold ")
          .append(cFixed(thr / kDeg, 1))
          .append(" deg)");
    }
  }
  if (!r.empty()) {
    ++st.psi_for_jumps;
    return;
  }
  if (o.mode == OrientationMode::kStiffest) {
    ++st.psi_for_stiffness;
    r = "stiffer than the programmed rotation (predicted U_work)";
    return;
  }
  ++st.psi_for_jumps;
  r = "the sequence's jump limit cannot be met with the programmed rotation here";
}

/// Holes whose keep results stiffestAgainstKeep holds at a time (bounds its memory).
constexpr size_t kKeepBlock = 4096;

/// Stiffest, hole i in hole order with its keep result k: records U_work(keep); a hole at ψ = 0
/// takes k; a turned hole goes back to it unless the turn gains at least kStiffnessGainMin of
/// U_work, when the jump constraints with the final neighbours allow it. A hole whose exact
/// compensation was deferred (`deferred`, deferredToKeep: at ψ = 0 the keep result is the
/// stiffest's) takes k whenever k is ok; its exact compensation c is made only where k fails
/// (settleDeferred).
void takeKeepWhereStiffEnough(const std::vector<HoleRequest>& holes, const Node& programmed,
                              double thr, size_t i, bool deferred, HoleCompensation& k,
                              std::vector<Node>& chosen, HoleCompensation& c) {
  if (!(c.ok || deferred) || !programmed.feasible || !k.ok) return;
  c.U_work_keep = k.after.U_work_exact;
  const bool turned = std::abs(c.psi) > kPsiKept;
  if (turned && k.after.U_work_exact * (1.0 - kStiffnessGainMin) >= c.after.U_work_exact)
    return;  // turned, and stiffer by the minimum gain
  // ψ = 0 is the keep result itself; a turned hole goes back when the jump limit allows
  bool ok = true;
  for (const int dir : {-1, +1}) {
    const std::pair<const Node*, bool> nb = neighbour(chosen, holes, i, dir);
    if (nb.first && nb.second && !jumpOk(programmed.q, nb.first->q, thr)) ok = false;
  }
  if (turned && !ok) return;
  chosen[i] = programmed;
  k.U_work_keep = k.after.U_work_exact;
  c = std::move(k);
}

/// Whether stiffest defers hole i's exact compensation at its chosen node to stiffestAgainstKeep
/// (`programmed`: its programmed posture; `why`: notCompensatedReason): a hole kept at ψ = 0 with
/// a programmed posture, whose result is its keep result whenever that is ok (at ψ = 0 keep is the
/// stiffest's own rotation: a hole keep compensates is not reported failed for its exact
/// compensation).
bool deferredToKeep(const Node& chosen, const Node& programmed, const std::string& why) {
  return why.empty() && programmed.feasible && std::abs(chosen.psi) <= kPsiKept;
}

/// Stiffest, a hole kept at ψ = 0 (deferredToKeep; `c`: its stage-1 result) at its chosen node
/// and its programmed posture: the keep result into `keep`, which takeKeepWhereStiffEnough gives
/// the hole where it is ok; else the exact compensation at the chosen node into c.
void settleDeferred(Evaluator& ev, const HoleRequest& h, const Node& chosen, const Node& programmed,
                    HoleCompensation& keep, HoleCompensation& c) {
  keep = finalizeHole(ev, h, stageOne(c), programmed, true);
  if (!keep.ok) c = finalizeHole(ev, h, stageOne(c), chosen, false);
}

/// Stiffest, holes [first, last) (`programmed`: their programmed postures; `deferred`: the holes
/// whose exact compensation was deferred, deferredToKeep): the keep result (ψ = 0, positions only)
/// of every hole with a ψ = 0 posture (holes in parallel, kKeepBlock holes at a time;
/// settleDeferred for the deferred ones), then takeKeepWhereStiffEnough for each hole of the block
/// in hole order (a keep result depends on no other hole's choice, so the blocks change nothing
/// but the memory). A compensated hole's result carries its stage-1 part (stageOne).
void stiffestAgainstKeep(std::vector<Evaluator>& evs, const std::vector<HoleRequest>& holes,
                         std::span<const Node> programmed, std::span<const char> deferred,
                         std::vector<Node>& chosen, double thr, std::span<HoleCompensation> res,
                         size_t first) {
  const size_t n = first + res.size();
  auto out = [&](size_t i) -> HoleCompensation& { return res[i - first]; };
  auto posture = [&](size_t i) -> const Node& { return programmed[i - first]; };
  std::vector<HoleCompensation> keep;  // the keep results of one block of holes
  for (size_t b = first; b < n; b += kKeepBlock) {
    const size_t e = std::min(n, b + kKeepBlock);
    keep.assign(e - b, HoleCompensation{});
    parallelFor(e - b, static_cast<int>(evs.size()), [&](int w, size_t j) {
      const size_t i = b + j;
      Evaluator& ev = evs[static_cast<size_t>(w)];
      if (deferred[i - first])
        settleDeferred(ev, holes[i], chosen[i], posture(i), keep[j], out(i));
      else if (out(i).ok && posture(i).feasible)
        keep[j] = finalizeHole(ev, holes[i], stageOne(out(i)), posture(i), true);
    });
    for (size_t i = b; i < e; ++i) {
      takeKeepWhereStiffEnough(holes, posture(i), thr, i, deferred[i - first] != 0, keep[i - b],
                               chosen, out(i));
    }
  }
}

/// Why hole i is not compensated before its stage 5 ("" when it is to be finalized).
std::string notCompensatedReason(const HoleCompensation& c, const Node& chosen) {
  if (c.before.status == HoleStatus::kNotConverged) return "not compensated: " + c.before.reason;
  if (c.before.beyond_drill) return c.before.reason;  // not a question of the arm's posture
  if (c.before.status != HoleStatus::kOk) {
    // No arm posture to keep: the controller cannot reach the programmed target as written, and
    // any "compensated" target would put the arm into a posture the program never asked for.
    return std::string("the programmed target is ") +
           (c.before.status == HoleStatus::kSingular ? "singular" : "unreachable") +
           " before compensation (" + c.before.reason +
           "); compensating it would move the arm into another posture";
  }
  if (!chosen.feasible)
    return "no admissible orientation about the drill axis (limits, wrist margin)";
  return "";
}

/// Stage 1 of the holes `req` seeded with `prev` (then the last admissible joints among them, the
/// seed of the next block): predictHoles on `threads` workers, the continuity seeds of `roprec
/// predict`; a hole whose prediction throws makes the block fall back to the sequential loop,
/// which isolates it. `at(j)`: where hole j's prediction goes. `budget` false: the predictions
/// go as far as their status, joints and branch (PredictOptions::budget; the fallback predicts
/// them whole). `choice`: the block's IK choice, kept or given (PredictOptions::choice). Returns
/// false when the block fell back to the sequential loop (a kept choice is then not made).
bool predictBlock(const PredictionModel& m, PredictionData& d, std::span<const HoleRequest> req,
                  int threads, std::optional<Vec6>& prev,
                  const std::function<HolePrediction&(size_t)>& at, bool budget = true,
                  const IkChoice& choice = {}) {
  for (size_t j = 0; j < req.size(); ++j) at(j) = HolePrediction{};  // what predictHoles expects
  bool whole = true;
  try {
    PredictOptions po;
    po.threads = threads;
    po.seed = prev;
    po.budget = budget;
    po.choice = choice;
    predictHoles(m, req, po, at);
  } catch (const std::exception&) {
    predictOriginal(m, d, req, prev, at);
    whole = false;
  }
  for (size_t j = 0; j < req.size(); ++j) {
    if (at(j).status == HoleStatus::kOk) prev = at(j).joints;
  }
  return whole;
}

/// Where a run's finished holes go: handed to a sink a block at a time, or (`whole`) kept in
/// one vector the run returns (compensateHoles' result; no second copy of the results).
struct RunOutput {
  const CompensationSink* sink{nullptr};
  size_t offset{0};  ///< index of the run's first hole in the request list
  std::vector<HoleCompensation>* whole{nullptr};
};

/// The IK branch a hole's grid is solved in: its original solution's, unless a branch change is
/// allowed or it has none (−1: any).
int gridBranch(const HolePrediction& b, const CompensationOptions& o) {
  return (b.status == HoleStatus::kOk && !o.allow_branch_change) ? b.branch : -1;
}

/// The per-thread evaluators of a run (their scratch first: an Evaluator holds a reference).
struct Workers {
  std::vector<PredictionData> scratch;
  std::vector<Evaluator> evs;
  Workers(const PredictionModel& m, const CompensationOptions& o, size_t n) {
    const int threads = static_cast<int>(
        std::clamp<size_t>(static_cast<size_t>(std::max(1, o.threads)), 1, std::max<size_t>(1, n)));
    scratch.reserve(static_cast<size_t>(threads));
    evs.reserve(static_cast<size_t>(threads));
    for (int w = 0; w < threads; ++w) {
      scratch.emplace_back(m);
      evs.push_back(Evaluator{m, scratch.back(), o, true});
    }
    block = std::max<size_t>(1, o.block);
  }
  [[nodiscard]] int threads() const { return static_cast<int>(evs.size()); }
  size_t block{kCompensationBlock};  ///< CompensationOptions::block (≥ 1)
};

/// The counters of the finished holes [b, e) of `out` (ψ reasons and U_work for the modes that
/// choose ψ: psiReason reads the final chosen postures of the neighbours and `zero[k]`, the ψ = 0
/// candidate of each turned hole b + k).
void countFinished(const Evaluator& ev, const std::vector<HoleRequest>& holes,
                   const std::vector<Node>& chosen, std::span<const Node> zero, double thr,
                   std::span<HoleCompensation> out, size_t b, CompensationStats& st) {
  for (size_t k = 0; k < out.size(); ++k) {
    HoleCompensation& c = out[k];
    if (!c.ok) continue;
    const size_t i = b + k;
    if (std::abs(c.psi) > kPsiKept) {
      ++st.psi_changed;
      psiReason(ev, holes, chosen, zero[k], i, thr, st, c.psi_reason);
    }
    if (c.config_changed && c.config_in_program) ++st.config_changed;
    if (std::isfinite(c.U_work_keep)) {
      ++st.stiffness_compared;
      st.U_work_keep_sum += c.U_work_keep;
      st.U_work_sum += c.after.U_work_exact;
      st.U_work_gain_max = std::max(st.U_work_gain_max, c.U_work_keep - c.after.U_work_exact);
    }
  }
}

/// Blocks keepRun and sequenceRun finish ahead of the sink at most (each a block of results
/// held).
constexpr size_t kHandedAhead = 2;

/// keep, block by block: each block of holes predicted (stage 1), its ψ = 0 candidate (stage 2;
/// keep's sequence is the candidate of every hole: no jump limit, one node), compensated
/// (stage 5) and handed over in order (with workers, while the next blocks are computed:
/// kHandedAhead). The results and counters of chooseSequence and the stage-5 pass over the
/// whole run.
void keepRun(Workers& w, const std::vector<HoleRequest>& holes, const std::optional<Vec6>& first,
             CompensationStats& st, const RunOutput& to) {
  std::vector<Evaluator>& evs = w.evs;
  const PredictionModel& m = evs[0].m;
  const int threads = w.threads();
  const size_t n = holes.size();
  PredictionData serial_scratch(m);
  Evaluator serial{m, serial_scratch, evs[0].o, true};
  std::optional<Vec6> prev = first;
  Vec6 seed = m.reference_pose;  // the serial candidates' seed (holes not predicted as they are)
  const size_t cap = std::min(n, w.block);
  // with workers, each block goes to the sink on a task of its own that first waits for the
  // block before's (the sink sees the blocks one at a time, in order) while the next blocks are
  // computed: the computation runs up to kHandedAhead blocks ahead of the sink (a sink slower
  // for a block or two does not stop it), kHandedAhead + 1 blocks of results
  constexpr size_t kSlots = kHandedAhead + 1;
  std::array<std::vector<HoleCompensation>, kSlots> own;
  std::vector<Node> node(cap);
  std::vector<NodeCount> counts(cap);
  if (to.whole) to.whole->resize(n);
  std::array<std::shared_future<void>, kSlots> handing;  // the sink's task of each slot's block
  std::shared_future<void> last;                         // the task of the block before
  size_t slot = 0;
  for (size_t b = 0; b < n; b += w.block, slot = (slot + 1) % kSlots) {
    const size_t e = std::min(n, b + w.block);
    // the slot's block before is handed over (or its error, or an earlier block's, thrown)
    if (handing[slot].valid()) handing[slot].get();
    std::vector<HoleCompensation>& blk = to.whole ? *to.whole : own[slot];
    const size_t o0 = to.whole ? b : 0;  // the block's first hole in blk
    // a slot's results are reused kSlots blocks later: every field is written again
    // (finalizeHole's fresh result, or stage 1's with the reason: a result as a fresh one)
    if (!to.whole && blk.size() != e - b) blk.resize(e - b);
    const std::span<HoleCompensation> out(blk.data() + o0, e - b);
    // stage 1 with the continuity seed carried from block to block (predictHoles' seeds over the
    // run)
    predictBlock(m, w.scratch[0], std::span<const HoleRequest>(holes).subspan(b, e - b), threads,
                 prev, [&](size_t j) -> HolePrediction& { return out[j].before; });
    for (size_t j = 0; j < e - b; ++j) out[j].id = holes[b + j].id;
    std::fill(counts.begin(), counts.end(), NodeCount{});
    parallelFor(e - b, threads, [&](int wk, size_t j) {
      const HolePrediction& bp = out[j].before;
      if (bp.status != HoleStatus::kOk) return;
      counts[j] = holeNodes(evs[static_cast<size_t>(wk)], holes[b + j], bp.joints,
                            gridBranch(bp, evs[0].o), 1, std::span<Node>(&node[j], 1));
    });
    for (size_t j = 0; j < e - b; ++j) {
      if (out[j].before.status != HoleStatus::kOk)
        counts[j] = holeNodes(serial, holes[b + j], seed, -1, 1, std::span<Node>(&node[j], 1));
      st.dp_nodes += counts[j].nodes;
      st.infeasible_nodes += counts[j].infeasible;
      out[j].note.clear();
      if (counts[j].relaxed_wrist) {
        ++st.relaxed_wrist;
        out[j].note = kRelaxedWristNote;
      }
      if (node[j].feasible) seed = node[j].q;
    }
    parallelFor(e - b, threads, [&](int wk, size_t j) {
      std::string why = notCompensatedReason(out[j], node[j]);
      if (!why.empty()) {
        HoleCompensation kept = stageOne(out[j]);
        kept.reason = std::move(why);
        out[j] = std::move(kept);
        return;
      }
      out[j] = finalizeHole(evs[static_cast<size_t>(wk)], holes[b + j], std::move(out[j]), node[j],
                            true);
    });
    countFinished(evs[0], holes, {}, {}, 0.0, out, b, st);
    if (to.sink && threads > 1) {
      handing[slot] = std::async(std::launch::async, [&to, b, out, before = last] {
                        if (before.valid()) before.get();  // an error there ends this one
                        (*to.sink)(to.offset + b, out);
                      }).share();
      last = handing[slot];
    } else if (to.sink) {
      (*to.sink)(to.offset + b, out);
    }
  }
  if (last.valid()) last.get();  // every block handed over (the tasks end in order)
  st.jump_threshold_used = evs[0].o.jump_threshold;
}

/// What flip-free and stiffest keep of each hole between their passes over the run (the
/// predictions, grids and path costs are held a block at a time): the DP's tables (DpRow), what
/// rebuilds a node of the hole's grid (gridNode: the seed, the branch, NodeCount::enforced),
/// whether the wrist margin was relaxed there, node 0 of its grid (ψ = 0: the chosen node of most
/// holes, the ψ = 0 candidate psiReason reads, stiffest's programmed posture; kept rather than
/// evaluated again), and the prediction seed of each block of CompensationOptions::block holes
/// (stage 1 is made again block by block as the holes are finished).
struct SequenceTables {
  Grid<std::int16_t> from;
  std::vector<std::int16_t> best;
  std::vector<Vec6> seed;
  std::vector<std::int8_t> branch;
  std::vector<char> enforced;
  std::vector<char> relaxed;
  std::vector<Node> zero;
  std::vector<std::optional<Vec6>> block_seed;
  /// the IK choice of the stage-1 predictions (PredictOptions::choice), kept for their second
  /// prediction; `choice_kept[b]`: block b's was made (its predictions did not fall back)
  std::vector<IkSolution> choice;
  std::vector<char> chosen;
  std::vector<char> choice_kept;

  SequenceTables(size_t n, int grid, int threads, size_t block)
      : from(n, static_cast<size_t>(grid), std::int16_t{-1}, threads),
        best(n, -1),
        seed(n, Vec6::Zero()),
        branch(n, -1),
        enforced(n, 1),
        relaxed(n, 0),
        zero(n),
        block_seed((n + block - 1) / block),
        choice(n),
        chosen(n, 0),
        choice_kept(block_seed.size(), 0) {}
  /// Node k of hole i's grid.
  Node node(Evaluator& ev, const std::vector<HoleRequest>& holes, size_t i, int k, int grid) const {
    return gridNode(ev, holes[i], seed[i], branch[i], k, grid, enforced[i] != 0);
  }
};

/// What the forward pass carries from hole to hole in hole order: the tables, the counters (when
/// `count`), the DP's frontier and the serial seed (the first admissible candidate of the latest
/// hole that has one, else the reference pose: a hole without an admissible prediction is seeded
/// with it).
struct OrderedPass {
  const std::vector<HoleRequest>& holes;
  OrientationMode mode;
  double thr;
  bool count;
  SequenceTables& t;
  CompensationStats& st;
  DpFrontier f{};
  Vec6 seed{Vec6::Zero()};
  std::vector<Cost> cost{};  ///< dpForwardHole's scratch

  /// Hole i's candidates `row` (counted by c) through the tables, the counters, the serial seed
  /// and the DP.
  void through(size_t i, const NodeCount& c, std::span<const Node> row) {
    t.enforced[i] = c.enforced ? 1 : 0;
    t.relaxed[i] = c.relaxed_wrist ? 1 : 0;
    t.zero[i] = row[0];
    if (count) {
      st.dp_nodes += c.nodes;
      st.infeasible_nodes += c.infeasible;
      if (c.relaxed_wrist) ++st.relaxed_wrist;
    }
    for (const Node& nd : row) {
      if (nd.feasible) {
        seed = nd.q;
        break;
      }
    }
    dpForwardHole(row, holes, i, mode, thr, f, DpRow{t.from[i], t.best[i]}, cost);
  }
};

/// Stiffest: a lower bound of the node cost of any rotation of a hole other than ψ = 0, less the
/// cost of node 0 `zero` (nodeCost: a turned node pays ×(1 + kStiffnessGainMin) on its u_def,
/// which is at least zero.u_def − zero.u_spread, and a penalty ≥ 0); −inf when no bound is known.
double turnGap(const Node& zero) {
  if (!std::isfinite(zero.u_spread)) return -kInf;
  Node turned;
  turned.psi = kPi;
  turned.u_def = std::max(0.0, zero.u_def - zero.u_spread);
  turned.penalty = 0.0;
  return nodeCost(turned, OrientationMode::kStiffest).rest -
         nodeCost(zero, OrientationMode::kStiffest).rest;
}

/// Stiffest: the dearest link from q to any posture within the joint limits `lower`, `upper`
/// (transitionCost; every admissible node is within them).
double dearestLink(const Vec6& q, const Vec6& lower, const Vec6& upper) {
  Node from;
  from.q = q;
  Node far;
  for (int j = 0; j < 6; ++j) far.q[j] = q[j] - lower[j] > upper[j] - q[j] ? lower[j] : upper[j];
  return transitionCost(from, far, OrientationMode::kStiffest).rest;
}

/// flip-free's and stiffest's forward pass over holes whose ψ = 0 candidate (node 0) is known
/// first. A run of holes S = [s, e) whose node 0 is admissible at every hole and connects within
/// thr from hole to hole, where the DP's link into S and out of it is not jump-limited (S starts
/// the program or follows its latest reachable hole s − 1 on another face or after a joint
/// target, and ends the program or is followed by hole e on such a link with an admissible
/// node 0), can be node 0 throughout whatever the nodes before and after it (no jump limit on the
/// links). It is node 0 throughout in the DP's result:
///  - flip-free: a path with a turned hole in S has more changes, the first term of the
///    lexicographic cost, than the same path with node 0 throughout S;
///  - stiffest (the cost is a sum: node costs and 10⁻³ travel per link): when every hole i of S
///    has a turn gap g_i (turnGap: any turned node's cost less node 0's is at least g_i) larger
///    than the node-0 links beside it — the link before (from node 0 of i − 1; at s from the
///    dearest node of the DP's frontier) plus the link after (to node 0 of i + 1; at e − 1 to
///    any posture within the joint limits, dearestLink; none at the program's end) — with a
///    margin for the round-off of the path costs (kRunMargin). A path that turns holes T ⊂ S
///    costs more than the same path with node 0 throughout S by at least Σ_T (g_i − its links),
///    > 0; step by step, every turned node's path cost at hole i exceeds node 0's by more than
///    the link after i, so node 0's predecessor is node 0.
/// So the DP's predecessor of node 0 inside S, of every node of hole e and the chain's end are
/// node 0: the other nodes of S are never read. Their grids are not evaluated; S's holes go
/// through dpForwardHole with node 0 alone (the same path costs, bit for bit) as they come, the
/// DP's frontier before S kept: a run that turns out not to be such an S goes back to it, and its
/// holes' grids are evaluated. Every other hole's grid is evaluated (holeNodes), in hole order
/// through the DP as before, a chunk of holes at a time on the workers.
class ZeroRunForward {
 public:
  ZeroRunForward(Workers& w, Evaluator& serial, int grid, OrderedPass& pass, Grid<Node>& nodes)
      : w_(w),
        serial_(serial),
        holes_(pass.holes),
        grid_(grid),
        thr_(pass.thr),
        count_(pass.count),
        stiffest_(pass.mode == OrientationMode::kStiffest),
        t_(pass.t),
        st_(pass.st),
        f_(pass.f),
        seed_(pass.seed),
        pass_(pass),
        nodes_(nodes),
        row_(static_cast<size_t>(grid), Node{}) {}

  /// Hole i (its set-up in t: seed, branch) after the holes before it; `zero`: its node 0 when its
  /// prediction is admissible (`ok`).
  void add(size_t i, bool ok, const Node& zero) {
    if (!ok || !zero.feasible) {
      if (run_size_ > 0) breakRun();
      if (ok) {
        waitFull(i);
        return;
      }
      flush();  // a hole without an admissible prediction: its grid seeded in hole order
      t_.seed[i] = seed_;
      NodeCount c = holeNodes(serial_, holes_[i], seed_, t_.branch[i], grid_, nodes_[0]);
      through(i, c, nodes_[0]);
      return;
    }
    if (run_size_ > 0) {
      if (!jumpLimited(holes_[i - 1], holes_[i])) {
        closeRun(true);
      } else if (!jumpOk(run_last_.q, zero.q, thr_) || !gapHolds(zero)) {
        breakRun();
        waitFull(i);
        return;
      } else {
        extendRun(i, zero);
        return;
      }
    }
    const bool free_link = i == 0 || !jumpLimited(holes_[i - 1], holes_[i]);
    if (free_link) flush();
    if (full_end_ > full_begin_) {  // on a limited link after holes that wait for their grids
      waitFull(i);
      return;
    }
    const bool starts = f_.last < 0 || (free_link && f_.last == static_cast<std::ptrdiff_t>(i) - 1);
    if (!starts || !startGapHolds(zero)) {
      waitFull(i);
      return;
    }
    run_begin_ = i;
    f0_ = f_;
    extendRun(i, zero);
  }
  /// The end of the program: the waiting holes' grids, the run closed.
  void finish() {
    flush();
    closeRun(false);
  }

 private:
  /// Stiffest: the margin a gap keeps over the links beside it, for the round-off of path costs
  /// of the DP's size (10⁻¹² of the dearest finite path cost of the frontier, and 10⁻⁹).
  [[nodiscard]] double margin() const {
    double scale = 0.0;
    for (const Cost& c : f_.cost) {
      if (isFinite(c)) scale = std::max(scale, std::abs(c.rest));
    }
    return 1e-9 + 1e-12 * scale;
  }
  /// Stiffest: whether hole `zero` can start a run after the DP's frontier: its gap less the
  /// dearest link into it stays above the margin (flip-free: always).
  bool startGapHolds(const Node& zero) {
    if (!stiffest_) return true;
    double into = 0.0;
    if (f_.last >= 0) {
      for (size_t l = 0; l < f_.nodes.size(); ++l) {
        if (isFinite(f_.cost[l]))
          into = std::max(into, transitionCost(f_.nodes[l], zero, OrientationMode::kStiffest).rest);
      }
    }
    rest_ = turnGap(zero) - into;
    return rest_ > margin();
  }
  /// Stiffest: whether hole `zero` extends the run: the run's last hole keeps its margin over the
  /// link to it, and so does its own gap (flip-free: always).
  bool gapHolds(const Node& zero) {
    if (!stiffest_) return true;
    const double link = transitionCost(run_last_, zero, OrientationMode::kStiffest).rest;
    const double m = margin();
    const double rest = turnGap(zero) - link;
    if (!(rest_ - link > m) || !(rest > m)) return false;
    rest_ = rest;
    return true;
  }
  void waitFull(size_t i) {
    if (full_end_ == full_begin_) full_begin_ = i;
    full_end_ = i + 1;
  }
  /// Hole i of the run, node 0 alone through the DP (counted when the run is closed).
  void extendRun(size_t i, const Node& zero) {
    row_[0] = zero;
    through(i, NodeCount{}, row_);
    run_last_ = zero;
    ++run_size_;
  }
  /// The run cannot be node 0 throughout: the DP goes back to its frontier before the run, whose
  /// holes wait for their grids.
  void breakRun() {
    f_ = f0_;
    full_begin_ = run_begin_;
    full_end_ = run_begin_ + run_size_;
    run_size_ = 0;
  }
  /// The run ends (`link_after`: on a free link to a next hole, else at the program's end): an S
  /// with one candidate evaluated per hole, unless stiffest's last hole cannot pay the dearest
  /// link out of it (the run's grids are then evaluated).
  void closeRun(bool link_after) {
    if (run_size_ == 0) return;
    if (stiffest_ && link_after &&
        !(rest_ - dearestLink(run_last_.q, serial_.m.ik.lower, serial_.m.ik.upper) > margin())) {
      breakRun();
      return;
    }
    if (count_) st_.dp_nodes += static_cast<int>(run_size_);
    run_size_ = 0;
  }
  /// The waiting holes' grids, a chunk of holes on the workers at a time, then through the DP in
  /// hole order.
  void flush() {
    const size_t chunk = nodes_.size();
    for (size_t b = full_begin_; b < full_end_; b += chunk) {
      const size_t e = std::min(full_end_, b + chunk);
      counts_.resize(chunk);
      parallelFor(e - b, w_.threads(), [&](int wk, size_t j) {
        const size_t i = b + j;
        counts_[j] = holeNodes(w_.evs[static_cast<size_t>(wk)], holes_[i], t_.seed[i], t_.branch[i],
                               grid_, nodes_[j]);
      });
      for (size_t j = 0; j < e - b; ++j) through(b + j, counts_[j], nodes_[j]);
    }
    full_begin_ = full_end_ = 0;
  }
  void through(size_t i, const NodeCount& c, std::span<const Node> row) {
    pass_.through(i, c, row);
  }

  Workers& w_;
  Evaluator& serial_;
  const std::vector<HoleRequest>& holes_;
  int grid_;
  double thr_;
  bool count_;
  bool stiffest_;
  SequenceTables& t_;
  CompensationStats& st_;
  DpFrontier& f_;
  Vec6& seed_;
  OrderedPass& pass_;
  Grid<Node>& nodes_;
  std::vector<Node> row_;  ///< node 0 and grid − 1 candidates that are not admissible
  size_t run_begin_{0};    ///< the run: holes [run_begin_, run_begin_ + run_size_)
  size_t run_size_{0};
  Node run_last_;     ///< node 0 of the run's last hole
  double rest_{0.0};  ///< stiffest: the run's last hole's gap less the links beside it so far
  DpFrontier f0_;     ///< the DP's frontier before the run
  size_t full_begin_{0}, full_end_{0};  ///< holes waiting for their grids
  std::vector<NodeCount> counts_;
};

/// Hole i's set-up in the tables: its own joints as the grid's seed when its prediction is
/// admissible, else `seed` (the latest admissible candidate before it); its grid branch.
void recordSetUp(SequenceTables& t, size_t i, const HolePrediction& h, const Vec6& seed,
                 const CompensationOptions& o) {
  t.seed[i] = h.status == HoleStatus::kOk ? h.joints : seed;
  t.branch[i] = static_cast<std::int8_t>(gridBranch(h, o));
}

/// The candidate grids of a block of predicted holes (`before`: holes b0, b0 + 1, ...) through
/// the ordered pass: 1,024 holes at a time (pipelinedFor), the workers evaluate the grids of the
/// holes with an admissible prediction (holeNodes, seeded with their joints) while the holes
/// before go through `pass` in hole order on a task of its own; a hole without one gets its grid
/// there, seeded with the serial seed (on `serial`).
void gridBlock(Workers& w, Evaluator& serial, std::span<const HolePrediction> before, size_t b0,
               int grid, Grid<Node>& nodes, std::vector<NodeCount>& counts, OrderedPass& pass) {
  constexpr size_t kBlock = 1024;  // holes per block of the pipeline (a block boundary costs
                                   // a wait for its slowest worker)
  const std::vector<HoleRequest>& holes = pass.holes;
  const CompensationOptions& o = serial.o;
  auto onWorker = [&](int wk, size_t j) {
    const HolePrediction& b = before[j];
    counts[j] = NodeCount{};
    if (b.status != HoleStatus::kOk) return;
    counts[j] = holeNodes(w.evs[static_cast<size_t>(wk)], holes[b0 + j], b.joints, gridBranch(b, o),
                          grid, nodes[j]);
  };
  auto inOrder = [&](size_t b, size_t e) {
    for (size_t j = b; j < e; ++j) {
      const size_t i = b0 + j;
      recordSetUp(pass.t, i, before[j], pass.seed, o);
      if (before[j].status != HoleStatus::kOk)
        counts[j] = holeNodes(serial, holes[i], pass.seed, pass.t.branch[i], grid, nodes[j]);
      pass.through(i, counts[j], nodes[j]);
    }
  };
  pipelinedFor(before.size(), std::min(kBlock, w.block), w.threads(), onWorker, inOrder);
}

/// flip-free's and stiffest's block of predicted holes: node 0 of the holes with an admissible
/// prediction on the workers (into `zero`), then the holes in order through ZeroRunForward.
void zeroRunBlock(Workers& w, std::span<const HolePrediction> before, size_t b0, int grid,
                  std::vector<Node>& zero, OrderedPass& pass, ZeroRunForward& ff) {
  const std::vector<HoleRequest>& holes = pass.holes;
  const CompensationOptions& o = w.evs[0].o;
  parallelFor(before.size(), w.threads(), [&](int wk, size_t j) {
    const HolePrediction& b = before[j];
    if (b.status != HoleStatus::kOk) return;
    Evaluator& ev = w.evs[static_cast<size_t>(wk)];
    const HoleRequest& h = holes[b0 + j];
    zero[j] = ev.evaluateGrid(h, ev.loadsFor(ev.processFor(h)), 0, grid, gridBranch(b, o), b.joints,
                              true, true);
  });
  for (size_t j = 0; j < before.size(); ++j) {
    const size_t i = b0 + j;
    recordSetUp(pass.t, i, before[j], pass.seed, o);
    ff.add(i, before[j].status == HoleStatus::kOk, zero[j]);
  }
}

/// Stages 1 to 3 at the jump threshold thr, a block of holes at a time: the block predicted
/// (stage 1, the continuity seed carried), then its candidate grids through the DP's forward
/// pass in hole order (gridBlock; flip-free and stiffest: zeroRunBlock, unless
/// CompensationOptions::skip_proven_grids is off), the counters when `count`. One
/// block's predictions and grids are held. False when a reachable hole cannot be connected within
/// thr. Grids are in the branch of the original solution unless a branch change is allowed.
bool forwardPass(Workers& w, const std::vector<HoleRequest>& holes,
                 const std::optional<Vec6>& first, int grid, double thr, bool count,
                 SequenceTables& t, CompensationStats& st) {
  const PredictionModel& m = w.evs[0].m;
  const CompensationOptions& o = w.evs[0].o;
  const size_t n = holes.size();
  const size_t cap = std::min(n, w.block);
  std::vector<HolePrediction> before(cap);
  Grid<Node> nodes(cap, static_cast<size_t>(grid), Node{}, w.threads());
  std::vector<NodeCount> counts(cap);
  PredictionData serial_scratch(m);
  Evaluator serial{m, serial_scratch, o, true};
  OrderedPass pass{holes, o.mode, thr, count, t, st};
  pass.seed = m.reference_pose;
  std::optional<ZeroRunForward> ff;
  if (o.mode != OrientationMode::kKeep && o.skip_proven_grids)
    ff.emplace(w, serial, grid, pass, nodes);
  std::vector<Node> zero(ff ? cap : 0);
  std::optional<Vec6> prev = first;
  for (size_t b0 = 0; b0 < n; b0 += w.block) {
    const size_t e0 = std::min(n, b0 + w.block);
    t.block_seed[b0 / w.block] = prev;
    // the search reads each prediction's status, joints and branch only: no budgets; the IK
    // choice is kept for the holes' second prediction (sequenceRun)
    const IkChoice choice{std::span<IkSolution>(t.choice).subspan(b0, e0 - b0),
                          std::span<char>(t.chosen).subspan(b0, e0 - b0), false};
    t.choice_kept[b0 / w.block] =
        predictBlock(
            m, w.scratch[0], std::span<const HoleRequest>(holes).subspan(b0, e0 - b0), w.threads(),
            prev, [&](size_t j) -> HolePrediction& { return before[j]; }, false, choice)
            ? 1
            : 0;
    const std::span<const HolePrediction> block(before.data(), e0 - b0);
    if (ff)
      zeroRunBlock(w, block, b0, grid, zero, pass, *ff);
    else
      gridBlock(w, serial, block, b0, grid, nodes, counts, pass);
  }
  if (ff) ff->finish();
  return pass.f.all_connected;
}

/// What stages 2 and 3 give the holes' finishing: the chosen node per hole (not feasible: none),
/// node 0 of each hole's grid (its ψ = 0 candidate: psiReason reads it; SequenceTables::zero) and
/// whether that grid enforced |θ5| ≥ margin, whether the wrist margin was relaxed, and the
/// prediction seeds of the blocks (SequenceTables::block_seed).
struct Sequence {
  std::vector<Node> chosen;
  std::vector<Node> zero;
  std::vector<char> enforced;
  std::vector<char> relaxed;
  std::vector<std::optional<Vec6>> block_seed;
  std::vector<IkSolution> choice;  ///< SequenceTables::choice, chosen and choice_kept
  std::vector<char> ik_chosen;
  std::vector<char> choice_kept;

  /// The IK choice of block b (holes [b0, e0)) to predict it again with, when it was made.
  [[nodiscard]] IkChoice choiceOf(size_t b, size_t b0, size_t e0) {
    if (!choice_kept[b]) return {};
    return {std::span<IkSolution>(choice).subspan(b0, e0 - b0),
            std::span<char>(ik_chosen).subspan(b0, e0 - b0), true};
  }

  /// Stiffest's programmed posture of hole i (ψ = 0 without the wrist requirement, in the
  /// branch of its prediction `b`, seeded with its joints): node 0 of its grid when that is the
  /// same evaluation (the grid's branch and seed are those of the prediction, and no solution was
  /// passed over for the wrist margin, or the grid did not enforce it), else evaluated.
  Node programmed(Evaluator& ev, const HoleRequest& h, const HolePrediction& b, size_t i) const {
    const Node& z = zero[i];
    if (gridBranch(b, ev.o) == b.branch && (!enforced[i] || !z.wrist_rejected)) return z;
    return ev.evaluate(h, 0.0, b.branch, b.joints, false, true);
  }
};

/// Stages 2 and 3: every hole's ψ grid (holeNodes) and the cheapest admissible path through
/// them (forwardPass, then dpBacktrack). When a reachable hole does not connect, the threshold is
/// relaxed ×1.5 and the whole pass repeated (the grids made again) until every reachable hole
/// connects (`thr` returns the threshold used). The chosen nodes and the turned holes' ψ = 0
/// candidates are evaluated again from the tables, which are then dropped.
Sequence chooseSequence(Workers& w, const std::vector<HoleRequest>& holes,
                        const std::optional<Vec6>& first, int grid, CompensationStats& st,
                        double& thr) {
  const size_t n = holes.size();
  SequenceTables t(n, grid, w.threads(), w.block);
  thr = w.evs[0].o.jump_threshold;
  bool connected = forwardPass(w, holes, first, grid, thr, true, t, st);
  while (!connected) {
    st.relaxed_jumps = true;
    thr *= 1.5;
    if (thr > 4 * kPi) {
      forwardPass(w, holes, first, grid, kInf, false, t, st);
      break;
    }
    connected = forwardPass(w, holes, first, grid, thr, false, t, st);
  }
  std::vector<int> choice = dpBacktrack(t.from, t.best);
  t.from = Grid<std::int16_t>();
  Sequence q;
  q.chosen.resize(n);
  parallelFor(n, w.threads(), [&](int wk, size_t i) {
    if (choice[i] == 0)
      q.chosen[i] = t.zero[i];
    else if (choice[i] > 0)
      q.chosen[i] = t.node(w.evs[static_cast<size_t>(wk)], holes, i, choice[i], grid);
  });
  q.zero = std::move(t.zero);
  q.enforced = std::move(t.enforced);
  q.relaxed = std::move(t.relaxed);
  q.block_seed = std::move(t.block_seed);
  q.choice = std::move(t.choice);
  q.ik_chosen = std::move(t.chosen);
  q.choice_kept = std::move(t.choice_kept);
  return q;
}

/// flip-free and stiffest: the sequence chosen over the whole run (stages 1 to 4, a block of
/// predictions and grids at a time), then the holes predicted again, finished (stage 5; stiffest
/// against keep) and handed over a block at a time. A stiffest hole is handed over once the next
/// hole with a chosen posture is final (its ψ reason reads it).
void sequenceRun(Workers& w, const std::vector<HoleRequest>& holes,
                 const std::optional<Vec6>& first, CompensationStats& st, const RunOutput& to) {
  std::vector<Evaluator>& evs = w.evs;
  const PredictionModel& m = evs[0].m;
  const CompensationOptions& o = evs[0].o;
  const int threads = w.threads();
  const size_t n = holes.size();
  const int grid = std::max(4, o.grid);
  if (grid > std::numeric_limits<std::int16_t>::max())
    throw std::invalid_argument("compensateHoles: the ψ grid has more than 32767 nodes");
  double thr = 0;
  Sequence q = chooseSequence(w, holes, first, grid, st, thr);
  std::vector<Node>& chosen = q.chosen;
  st.jump_threshold_used = thr;
  if (o.refine) refineTurned(evs, holes, q.relaxed, chosen, grid, thr, st);
  const bool stiffest = o.mode == OrientationMode::kStiffest;
  const size_t cap = std::min(n, w.block);
  std::vector<HolePrediction> before(cap);
  // the programmed posture (ψ = 0, no wrist requirement) of each hole of a block: stiffest's
  // reference
  std::vector<Node> programmed(stiffest ? cap : 0);
  std::vector<char> deferred(stiffest ? cap : 0);  // deferredToKeep of each hole of a block
  std::vector<Node> zero;  // the ψ = 0 candidates of the turned holes handed over (psiReason)
  if (to.whole) to.whole->reserve(to.whole->size() + n);
  // the finished holes [ready, e) not handed over yet are in bufs[k]; with workers, those handed
  // over go to the sink on a task of their own that first waits for the task before (the sink
  // sees them in order, one call at a time) while the next blocks are finished, up to
  // kHandedAhead blocks ahead of the sink (the holes that wait move to the next buffer first,
  // once its holes are handed over)
  constexpr size_t kSlots = kHandedAhead + 1;
  std::array<std::vector<HoleCompensation>, kSlots> bufs;
  std::array<std::shared_future<void>, kSlots> handing;  // the sink's task of each buffer
  std::shared_future<void> last;                         // the task of the holes before
  size_t k = 0;
  size_t ready = 0;
  for (size_t b = 0; b < n; b += w.block) {
    const size_t e = std::min(n, b + w.block);
    std::optional<Vec6> seed = q.block_seed[b / w.block];
    predictBlock(
        m, w.scratch[0], std::span<const HoleRequest>(holes).subspan(b, e - b), threads, seed,
        [&](size_t j) -> HolePrediction& { return before[j]; }, true,
        q.choiceOf(b / w.block, b, e));
    std::vector<HoleCompensation>& pend = bufs[k];
    const size_t p0 = pend.size();  // hole b in pend
    pend.resize(p0 + (e - b));
    // the stage-1 part (id, prediction, note) taken over; stiffest compares with the keep result
    // made later from the copy the result carries (stageOne)
    parallelFor(e - b, threads, [&](int wk, size_t j) {
      const size_t i = b + j;
      Evaluator& ev = evs[static_cast<size_t>(wk)];
      HoleCompensation& c = pend[p0 + j];
      c.id = holes[i].id;
      c.before = std::move(before[j]);
      if (stiffest) {
        programmed[j] = Node{};
        if (c.before.status == HoleStatus::kOk)
          programmed[j] = q.programmed(ev, holes[i], c.before, i);
      }
      if (q.relaxed[i]) c.note = kRelaxedWristNote;
      std::string why = notCompensatedReason(c, chosen[i]);
      if (stiffest) deferred[j] = deferredToKeep(chosen[i], programmed[j], why) ? 1 : 0;
      if (!why.empty()) {
        c.reason = std::move(why);
        return;
      }
      // (not one conditional expression: its prvalue would copy c when it is not stiffest)
      if (stiffest) {
        if (!deferred[j]) c = finalizeHole(ev, holes[i], stageOne(c), chosen[i], false);
      } else {
        c = finalizeHole(ev, holes[i], std::move(c), chosen[i], false);
      }
    });
    if (stiffest)
      stiffestAgainstKeep(evs, holes, std::span<const Node>(programmed.data(), e - b),
                          std::span<const char>(deferred.data(), e - b), chosen, thr,
                          std::span<HoleCompensation>(pend).subspan(p0), b);
    size_t upto = e;  // stiffest: the last hole with a posture waits for the next block
    if (stiffest && e < n) {
      for (size_t i = e; i-- > ready;) {
        if (chosen[i].feasible) {
          upto = i;
          break;
        }
      }
    }
    const std::span<HoleCompensation> done(pend.data(), upto - ready);
    zero.assign(done.size(), Node{});
    for (size_t j = 0; j < done.size(); ++j) {
      if (done[j].ok && std::abs(done[j].psi) > kPsiKept) zero[j] = q.zero[ready + j];
    }
    countFinished(evs[0], holes, chosen, zero, thr, done, ready, st);
    const size_t nk = (k + 1) % kSlots;
    // the next buffer's holes are handed over (or its error, or an earlier one's, thrown)
    if (handing[nk].valid()) handing[nk].get();
    std::vector<HoleCompensation>& next = bufs[nk];
    next.clear();
    for (size_t j = upto - ready; j < pend.size(); ++j) next.push_back(std::move(pend[j]));
    pend.resize(upto - ready);
    if (to.whole) {
      for (HoleCompensation& c : pend) to.whole->push_back(std::move(c));
    } else if (to.sink && threads > 1) {
      handing[k] = std::async(std::launch::async, [&to, ready, &pend, before = last] {
                     if (before.valid()) before.get();  // an error there ends this one
                     (*to.sink)(to.offset + ready, pend);
                   }).share();
      last = handing[k];
    } else if (to.sink) {
      (*to.sink)(to.offset + ready, pend);
    }
    ready = upto;
    k = nk;
  }
  if (last.valid()) last.get();  // every hole handed over (the tasks end in order)
}

/// compensateHoles over holes that share one model (one TCP), the first seeded with `first`.
void compensateRun(const PredictionModel& m, const std::vector<HoleRequest>& holes,
                   const CompensationOptions& o, const std::optional<Vec6>& first,
                   CompensationStats& st, const RunOutput& to) {
  Workers w(m, o, holes.size());
  if (o.mode == OrientationMode::kKeep) {
    keepRun(w, holes, first, st, to);
  } else {
    sequenceRun(w, holes, first, st, to);
  }
}

/// The statistics of two runs of holes as one sequence's.
void addStats(CompensationStats& to, const CompensationStats& s) {
  to.dp_nodes += s.dp_nodes;
  to.infeasible_nodes += s.infeasible_nodes;
  to.refined += s.refined;
  to.nlopt_evaluations += s.nlopt_evaluations;
  to.relaxed_jumps = to.relaxed_jumps || s.relaxed_jumps;
  to.jump_threshold_used = std::max(to.jump_threshold_used, s.jump_threshold_used);
  to.relaxed_wrist += s.relaxed_wrist;
  to.psi_changed += s.psi_changed;
  to.psi_for_limits += s.psi_for_limits;
  to.psi_for_wrist += s.psi_for_wrist;
  to.psi_for_jumps += s.psi_for_jumps;
  to.psi_for_stiffness += s.psi_for_stiffness;
  to.config_changed += s.config_changed;
  to.stiffness_compared += s.stiffness_compared;
  to.U_work_keep_sum += s.U_work_keep_sum;
  to.U_work_sum += s.U_work_sum;
  to.U_work_gain_max = std::max(to.U_work_gain_max, s.U_work_gain_max);
}

}  // namespace

namespace {

/// compensateHoles into `to`: each run of holes drilled at one TCP (drills with TCPs of their own)
/// with its model, seeded with the joints of the run before (a tool change is a repositioning
/// move).
void compensateAll(const PredictionModel& m, const std::vector<HoleRequest>& holes,
                   const CompensationOptions& o, const CompensationSink* sink,
                   std::vector<HoleCompensation>* whole, CompensationStats* stats) {
  CompensationStats st;
  if (!hasDrillModels(m)) {
    compensateRun(m, holes, o, std::nullopt, st, RunOutput{sink, 0, whole});
    if (stats) *stats = st;
    return;
  }
  if (whole) whole->reserve(holes.size());
  std::optional<Vec6> seed;
  for (size_t b = 0; b < holes.size();) {
    const PredictionModel& mb = modelFor(m, holes[b]);
    size_t e = b + 1;
    while (e < holes.size() && &modelFor(m, holes[e]) == &mb) ++e;
    const std::vector<HoleRequest> run(holes.begin() + static_cast<std::ptrdiff_t>(b),
                                       holes.begin() + static_cast<std::ptrdiff_t>(e));
    CompensationStats rs;
    std::vector<HoleCompensation> part;
    const CompensationSink each = [&](size_t first, std::span<HoleCompensation> done) {
      for (const HoleCompensation& c : done) {
        if (c.before.status == HoleStatus::kOk) seed = c.before.joints;
      }
      if (sink) (*sink)(first, done);
    };
    compensateRun(mb, run, o, seed, rs,
                  RunOutput{whole ? nullptr : &each, b, whole ? &part : nullptr});
    addStats(st, rs);
    if (whole) {
      for (HoleCompensation& c : part) {
        if (c.before.status == HoleStatus::kOk) seed = c.before.joints;
        whole->push_back(std::move(c));
      }
    }
    b = e;
  }
  if (stats) *stats = st;
}

}  // namespace

std::vector<HoleCompensation> compensateHoles(const PredictionModel& m,
                                              const std::vector<HoleRequest>& holes,
                                              const CompensationOptions& o,
                                              CompensationStats* stats) {
  std::vector<HoleCompensation> out;
  compensateAll(m, holes, o, nullptr, &out, stats);
  return out;
}

void compensateHoles(const PredictionModel& m, const std::vector<HoleRequest>& holes,
                     const CompensationOptions& o, const CompensationSink& sink,
                     CompensationStats* stats) {
  compensateAll(m, holes, o, &sink, nullptr, stats);
}

void compensateTarget(const PredictionModel& base, PredictionData& d, const HoleRequest& h,
                      const CompensationOptions& options, TargetBudgets budgets,
                      HoleCompensation& out) {
  const PredictionModel& m = modelFor(base, h);
  out.id = h.id;
  out.ok = false;
  out.reason.clear();
  if (budgets == TargetBudgets::kBoth)
    predictHole(m, d, h, nullptr, out.before);
  else
    chooseHoleSolution(m, d, h, nullptr, out.before);
  CompensationOptions o = options;
  o.mode = OrientationMode::kKeep;
  Evaluator ev{m, d, o, budgets == TargetBudgets::kBoth};
  Node node;
  const HolePrediction& b = out.before;
  if (b.status == HoleStatus::kOk && budgets == TargetBudgets::kNone && !m.calibrated) {
    // stage 2 of keep without a calibration: the real and the controller's IK are one, so the
    // solution in the programmed branch nearest the programmed joints is those joints (admissible:
    // the IK choice checked the limits and singularities)
    node.q = b.joints;
    node.branch = static_cast<std::int8_t>(b.branch);
    node.wrist = b.wrist_margin;
    node.feasible = true;
    node.why = Why::kNone;
  } else if (b.status == HoleStatus::kOk) {  // stage 2 of keep: ψ = 0 in the programmed branch
    node = ev.evaluate(h, 0.0, gridBranch(b, o), b.joints, false, false);
  }
  std::string why = notCompensatedReason(out, node);
  if (!why.empty()) {
    out.reason = std::move(why);
    return;
  }
  out = finalizeHole(ev, h, std::move(out), node, true);
}

}  // namespace roprec
