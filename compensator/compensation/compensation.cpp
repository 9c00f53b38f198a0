#include "compensator/compensation/compensation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "compensator/compensation/nlopt_problem.hpp"

namespace roprec {

const char* orientationModeName(OrientationMode m) {
  switch (m) {
    case OrientationMode::kKeep: return "keep";
    case OrientationMode::kFlipFree: return "flip-free";
    case OrientationMode::kStiffest: return "stiffest";
  }
  return "?";
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Pose rotZ(double psi) {
  Pose T = Pose::Identity();
  T.linear() = Eigen::AngleAxisd(psi, Vec3::UnitZ()).toRotationMatrix();
  return T;
}

/// One candidate: the IK solution for the hole at ψ and its costs.
struct Node {
  bool feasible{false};
  double psi{0.0};
  Vec6 q{Vec6::Zero()};
  int branch{-1};
  double u_def{0.0};      ///< m: linearised deflection-model uncertainty (stiffness proxy)
  double penalty{0.0};    ///< limits + wrist proximity (dimensionless)
  double wrist{0.0};      ///< |sin(θ5 + α)|
};

struct Evaluator {
  const PredictionModel& m;
  PredictionData& d;
  const CompensationOptions& o;

  nc::Loads loadsFor(const ProcessAtDiameter* proc) const { return processLoads(m, proc); }

  const ProcessAtDiameter* processFor(double diameter) const { return roprec::processFor(m, diameter); }

  /// IK at T_W_tcp in `branch` (−1: any) nearest `seed`; `enforce_wrist`: |θ5| ≥ margin.
  Node evaluate(const HoleRequest& h, double psi, int branch, const Vec6& seed, bool enforce_wrist,
                bool with_cost) {
    Node n;
    n.psi = psi;
    const Pose T = h.T_W_tcp * rotZ(psi);
    const Pose T_flange = T * m.model.T_L6_tcp.inverse() * m.model.T_L6_flange;
    IkOptions opt;
    opt.seed = &seed;
    solveIk(m.ik, T_flange, opt, d.ik);
    double best = kInf;
    for (int i = 0; i < d.ik.count; ++i) {
      const IkSolution& s = d.ik.solutions[static_cast<size_t>(i)];
      if (!s.converged || !s.within_limits || s.singular_shoulder || s.singular_wrist) continue;
      const int b = s.branch.index();
      if (branch >= 0 && b != branch) continue;
      if (enforce_wrist && s.branch.wrist_margin_rad < std::sin(o.wrist_margin)) continue;
      const double dist = (s.q - seed).squaredNorm();
      if (dist < best) {
        best = dist;
        n.q = s.q;
        n.branch = b;
        n.wrist = s.branch.wrist_margin_rad;
        n.feasible = true;
      }
    }
    if (!n.feasible || !with_cost) return n;
    // penalties: joint-limit proximity and wrist proximity
    for (int j = 0; j < 6; ++j) {
      const double margin = std::min(n.q[j] - m.ik.lower[j], m.ik.upper[j] - n.q[j]);
      if (margin < o.limit_margin) n.penalty += std::pow((o.limit_margin - margin) / o.limit_margin, 2);
    }
    const double s2 = std::sin(2.0 * o.wrist_margin);
    if (n.wrist < s2) n.penalty += std::pow((s2 - n.wrist) / s2, 2);
    // stiffness proxy: linearised deflection-model uncertainty ⊥ the axis
    const ProcessAtDiameter* proc = processFor(h.diameter);
    const nc::Loads loads = loadsFor(proc);
    nc::solvePosition(m.model, d.nc, n.q);
    const nc::Vec6 tau = nc::staticTorques(m.model, d.nc, loads);
    const nc::Mat6& J = nc::tcpJacobian(m.model, d.nc);
    const Mat3 R = T.linear();
    const Vec3 e1 = R.col(0);
    const Vec3 e2 = R.col(1);
    const nc::Vec6 keff = m.compliance.effective();
    double var = 0;
    for (int i = 0; i < 6; ++i) {
      const Vec3 v = J.block<3, 1>(0, i) * (tau[i] / keff[i]) * m.uncertainty.stiffness_rel;
      var += 0.5 * (std::pow(v.dot(e1), 2) + std::pow(v.dot(e2), 2));
    }
    n.u_def = std::sqrt(var);
    return n;
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

double nodeCost(const Node& n, OrientationMode mode) {
  if (mode == OrientationMode::kStiffest) return n.u_def * 1e6 + 0.1 * n.penalty;
  return 0.1 * n.penalty + 1e-3 * n.u_def * 1e6;
}

double transitionCost(const Node& a, const Node& b, OrientationMode mode) {
  if (mode == OrientationMode::kStiffest) return 1e-3 * travel(a.q, b.q);
  return travel(a.q, b.q);
}

}  // namespace

std::vector<HoleCompensation> compensateHoles(const PredictionModel& m, const std::vector<HoleRequest>& holes,
                                              const CompensationOptions& o, CompensationStats* stats) {
  CompensationStats st;
  PredictionData d(m);
  Evaluator ev{m, d, o};
  const size_t n = holes.size();
  std::vector<HoleCompensation> out(n);

  // 1. Predictions of the program as it is (continuity seeds, like `roprec predict`).
  std::optional<Vec6> prev;
  for (size_t i = 0; i < n; ++i) {
    out[i].id = holes[i].id;
    out[i].before = predictHole(m, d, holes[i], prev ? &*prev : nullptr);
    if (out[i].before.status == HoleStatus::kOk) prev = out[i].before.joints;
  }

  // 2. Candidate ψ per hole.
  std::vector<std::vector<Node>> nodes(n);
  const int grid = o.mode == OrientationMode::kKeep ? 1 : std::max(4, o.grid);
  Vec6 seed = m.reference_pose;
  for (size_t i = 0; i < n; ++i) {
    const HolePrediction& b = out[i].before;
    const Vec6 s = b.status == HoleStatus::kOk ? b.joints : seed;
    const int branch = (b.status == HoleStatus::kOk && !o.allow_branch_change) ? b.branch : -1;
    for (int k = 0; k < grid; ++k) {
      const double psi = grid == 1 ? 0.0 : -kPi + 2.0 * kPi * k / grid;
      Node nd = ev.evaluate(holes[i], psi, branch, s, o.mode != OrientationMode::kKeep, o.mode != OrientationMode::kKeep);
      ++st.dp_nodes;
      if (!nd.feasible) ++st.infeasible_nodes;
      nodes[i].push_back(nd);
    }
    bool any = false;
    for (const Node& nd : nodes[i]) any |= nd.feasible;
    if (!any && o.mode != OrientationMode::kKeep) {
      // With the drill on the flange axis, ψ turns axis 6 only: if |θ5| < margin for every ψ the
      // margin cannot be met here. Keep it as a penalty and say so, rather than drop the hole.
      for (int k = 0; k < grid; ++k) {
        const double psi = -kPi + 2.0 * kPi * k / grid;
        nodes[i][static_cast<size_t>(k)] = ev.evaluate(holes[i], psi, branch, s, false, true);
        any |= nodes[i][static_cast<size_t>(k)].feasible;
      }
      if (any) {
        ++st.relaxed_wrist;
        out[i].note = "no rotation about the drill axis meets |θ5| ≥ the wrist margin at this hole";
      }
    }
    for (const Node& nd : nodes[i]) {
      if (nd.feasible) {
        seed = nd.q;
        break;
      }
    }
  }

  // 3. Dynamic programming over the whole sequence (keep: the single ψ = 0 candidate).
  std::vector<int> choice(n, -1);
  auto runDp = [&](double thr) -> bool {
    std::vector<std::vector<double>> cost(n);
    std::vector<std::vector<int>> from(n);
    int last = -1;  // previous hole with a feasible node
    bool all_connected = true;
    for (size_t i = 0; i < n; ++i) {
      const size_t K = nodes[i].size();
      cost[i].assign(K, kInf);
      from[i].assign(K, -1);
      for (size_t k = 0; k < K; ++k) {
        const Node& nd = nodes[i][k];
        if (!nd.feasible) continue;
        const double c0 = nodeCost(nd, o.mode);
        if (last < 0) {
          cost[i][k] = c0;
          continue;
        }
        for (size_t l = 0; l < nodes[static_cast<size_t>(last)].size(); ++l) {
          const double cp = cost[static_cast<size_t>(last)][l];
          if (!std::isfinite(cp)) continue;
          const Node& pn = nodes[static_cast<size_t>(last)][l];
          if (o.mode != OrientationMode::kKeep && sameFace(holes[static_cast<size_t>(last)], holes[i]) &&
              !jumpOk(pn.q, nd.q, thr)) {
            continue;
          }
          const double c = cp + c0 + transitionCost(pn, nd, o.mode);
          if (c < cost[i][k]) {
            cost[i][k] = c;
            from[i][k] = static_cast<int>(l);
          }
        }
      }
      bool any = false;
      for (const double c : cost[i]) any |= std::isfinite(c);
      if (any) {
        last = static_cast<int>(i);
      } else {
        bool feasible_node = false;
        for (const Node& nd : nodes[i]) feasible_node |= nd.feasible;
        if (feasible_node) all_connected = false;  // reachable but not within the jump threshold
      }
    }
    if (!all_connected) return false;
    // backtrack
    std::fill(choice.begin(), choice.end(), -1);
    int cur = -1;
    for (size_t ii = n; ii-- > 0;) {
      if (cur >= 0) {
        choice[ii] = cur;
        cur = from[ii][static_cast<size_t>(cur)];
        continue;
      }
      if (choice[ii] >= 0) continue;
      double best = kInf;
      for (size_t k = 0; k < cost[ii].size(); ++k) {
        if (cost[ii][k] < best) {
          best = cost[ii][k];
          cur = static_cast<int>(k);
        }
      }
      if (cur >= 0) {
        choice[ii] = cur;
        cur = from[ii][static_cast<size_t>(cur)];
      }
    }
    return true;
  };
  double thr = o.jump_threshold;
  while (!runDp(thr)) {
    st.relaxed_jumps = true;
    thr *= 1.5;
    if (thr > 4 * kPi) {
      runDp(kInf);
      break;
    }
  }

  // stiffest: never worse than keep at a hole when ψ = 0 is admissible there
  if (o.mode == OrientationMode::kStiffest) {
    for (size_t i = 0; i < n; ++i) {
      if (choice[i] < 0) continue;
      const int k0 = grid / 2;  // ψ = 0
      const Node& c = nodes[i][static_cast<size_t>(choice[i])];
      const Node& z = nodes[i][static_cast<size_t>(k0)];
      if (z.feasible && z.u_def < c.u_def) choice[i] = k0;
    }
  }

  // 4. NLopt refinement of each hole's ψ with its neighbours fixed.
  std::vector<Node> chosen(n);
  for (size_t i = 0; i < n; ++i) {
    if (choice[i] >= 0) chosen[i] = nodes[i][static_cast<size_t>(choice[i])];
  }
  if (o.mode != OrientationMode::kKeep && o.refine) {
    for (size_t i = 0; i < n; ++i) {
      if (!chosen[i].feasible) continue;
      const Node* pn = nullptr;
      const Node* nn = nullptr;
      bool pn_face = false;
      bool nn_face = false;
      for (size_t k = i; k-- > 0;) {
        if (chosen[k].feasible) {
          pn = &chosen[k];
          pn_face = sameFace(holes[k], holes[i]);
          break;
        }
      }
      for (size_t k = i + 1; k < n; ++k) {
        if (chosen[k].feasible) {
          nn = &chosen[k];
          nn_face = sameFace(holes[k], holes[i]);
          break;
        }
      }
      const int branch = chosen[i].branch;
      const Vec6 seed_q = chosen[i].q;
      const bool enforce_wrist = out[i].note.empty();
      // COBYLA asks for the objective and the four constraints at the same ψ: evaluate once.
      double cached_psi = std::numeric_limits<double>::quiet_NaN();
      Node cached;
      auto evalAt = [&](double psi) {
        if (psi != cached_psi) {
          cached = ev.evaluate(holes[i], psi, branch, seed_q, enforce_wrist, true);
          cached_psi = psi;
        }
        return cached;
      };
      auto total = [&](const Node& nd) {
        double c = nodeCost(nd, o.mode);
        if (pn) c += transitionCost(*pn, nd, o.mode);
        if (nn) c += transitionCost(nd, *nn, o.mode);
        return c;
      };
      const double step = 2.0 * kPi / grid;
      NloptProblem prob(NLOPT_LN_COBYLA, 1);
      prob.setBounds({chosen[i].psi - step}, {chosen[i].psi + step});
      prob.setObjective([&](const std::vector<double>& x, std::vector<double>&) {
        const Node nd = evalAt(x[0]);
        return nd.feasible ? total(nd) : 1e9;
      });
      auto jumpConstraint = [&](const Node* other, int joint) {
        return [&, other, joint](const std::vector<double>& x, std::vector<double>&) {
          const Node nd = evalAt(x[0]);
          if (!nd.feasible || !other) return nd.feasible ? -1.0 : 1.0;
          return std::abs(nd.q[joint] - other->q[joint]) - thr;
        };
      };
      const Node* pj = pn_face ? pn : nullptr;
      const Node* nj = nn_face ? nn : nullptr;
      prob.addInequality(jumpConstraint(pj, 3));
      prob.addInequality(jumpConstraint(pj, 5));
      prob.addInequality(jumpConstraint(nj, 3));
      prob.addInequality(jumpConstraint(nj, 5));
      prob.setInitialStep(0.25 * step);
      prob.setXtolAbs(1e-4);
      prob.setMaxEvaluations(30);
      std::vector<double> x{chosen[i].psi};
      const NloptProblem::Result r = prob.optimize(x);
      st.nlopt_evaluations += r.evaluations;
      if (r.usable()) {
        const Node nd = evalAt(x[0]);
        const bool ok_jumps = (!pj || jumpOk(pj->q, nd.q, thr)) && (!nj || jumpOk(nd.q, nj->q, thr));
        const bool better = o.mode == OrientationMode::kStiffest ? nd.u_def <= chosen[i].u_def : total(nd) < total(chosen[i]);
        if (nd.feasible && ok_jumps && better) {
          chosen[i] = nd;
          ++st.refined;
        }
      }
    }
  }

  // 5. Exact compensation at the chosen ψ.
  // positions_only: keep the programmed orientation (iterate the position); else exact 6-DOF.
  auto finalize = [&](size_t i, const Node& node, bool positions_only) {
    HoleCompensation c;
    c.id = out[i].id;
    c.before = out[i].before;
    c.note = out[i].note;
    const HoleRequest& h = holes[i];
    c.psi = positions_only ? 0.0 : node.psi;
    c.T_nominal = h.T_W_tcp * rotZ(c.psi);
    c.theta_d = node.q;
    c.branch = node.branch;
    c.branch_changed = c.before.status == HoleStatus::kOk && c.branch != c.before.branch;
    const ProcessAtDiameter* proc = ev.processFor(h.diameter);
    const nc::Loads loads = ev.loadsFor(proc);
    if (positions_only) {
      // The programmed position p is corrected until the predicted real TCP position is the
      // nominal one: p ← p − (p_real(p) − p_nom) (∂p_real/∂p ≈ I: converges in a few iterations).
      Pose T = c.T_nominal;
      Vec6 q = c.theta_d;
      bool conv = false;
      for (int it = 0; it < 30; ++it) {
        const Pose T_flange = T * m.model.T_L6_tcp.inverse() * m.model.T_L6_flange;
        const IkNearResult ik = solveIkNear(m.ik, T_flange, q);
        if (!ik.converged) break;
        q = ik.q;
        const nc::Deflection df =
            nc::predictDeflection(m.model, d.nc, m.compliance, q, loads, {}, controllerOffset(m, d.nc, q));
        if (!df.converged) break;
        const Vec3 err = df.T_real.translation() - c.T_nominal.translation();
        if (err.norm() < 5e-10) {  // 0.0005 µm: the seeded IK stops at 1e-10
          conv = true;
          break;
        }
        T.translation() -= err;
      }
      if (!conv) {
        c.reason = "the position-only compensation did not converge";
        return c;
      }
      c.theta_cmd = q;
    } else {
      const Vec6 theta_m = nc::compensateCommand(m.model, d.nc, m.compliance, c.theta_d, loads);
      // a gravity-compensating controller adds its offset to the command: θ_cmd + off(θ_cmd) = θ_m
      c.theta_cmd = theta_m;
      for (int it = 0; it < 20 && m.controller_gravity; ++it) {
        const Vec6 next = theta_m - controllerOffset(m, d.nc, c.theta_cmd);
        const double step = (next - c.theta_cmd).lpNorm<Eigen::Infinity>();
        c.theta_cmd = next;
        if (step < 1e-14) break;
      }
    }
    const nc::PositionResult pr = nc::forwardKinematics(m.model, d.nc, c.theta_cmd);
    if (!pr.converged) {
      c.reason = "position problem did not converge at the compensated command";
      return c;
    }
    c.T_programmed = d.nc.T_W_tcp;
    if (positions_only) c.T_programmed.linear() = c.T_nominal.linear();  // exact by construction
    c.delta = c.T_programmed * c.T_nominal.inverse();
    c.config = configurationOf(m.ik, m.robot.card, c.theta_cmd, m.config_options);
    c.config_text = formatConfig(c.config);
    if (!withinLimits(m.ik, c.theta_cmd)) {
      c.reason = "the compensated command leaves the joint limits";
      return c;
    }
    const nc::Deflection def = nc::predictDeflection(m.model, d.nc, m.compliance, c.theta_cmd, loads, {},
                                                     controllerOffset(m, d.nc, c.theta_cmd));
    if (!def.converged) {
      c.reason = "the compliance equilibrium did not converge at the compensated command";
      return c;
    }
    c.residual = def.T_real.translation() - c.T_nominal.translation();
    c.residual_rot = smallRotationDifference(def.T_real.linear(), c.T_nominal.linear()).norm();
    HoleRequest after = h;
    after.T_W_tcp = c.T_programmed;
    after.config = c.config;
    after.nominal_axis.reset();
    c.after = predictHole(m, d, after, &c.theta_cmd);
    if (c.after.status != HoleStatus::kOk) {
      c.reason = "re-prediction of the compensated target failed: " + c.after.reason;
      return c;
    }
    const Vec3 a = c.T_nominal.linear().col(2);
    const double e = (c.residual - c.residual.dot(a) * a).norm();
    c.after.verdict = verdictFor(e, c.after.U_work, c.after.tolerance);
    c.ok = true;
    return c;
  };
  for (size_t i = 0; i < n; ++i) {
    if (!chosen[i].feasible) {
      out[i].ok = false;
      out[i].reason = out[i].before.status != HoleStatus::kOk
                          ? out[i].before.reason
                          : "no admissible orientation about the drill axis (limits, wrist margin)";
      continue;
    }
    HoleCompensation c = finalize(i, chosen[i], o.mode == OrientationMode::kKeep);
    if (o.mode == OrientationMode::kStiffest && !nodes[i].empty()) {
      // never stiffer-on-paper but worse than keep: compare with the keep result at this hole
      const Node& zero = nodes[i][static_cast<size_t>(grid / 2)];
      if (zero.feasible) {
        HoleCompensation k = finalize(i, zero, true);
        if (k.ok && (!c.ok || k.after.U_work < c.after.U_work)) c = std::move(k);
      }
    }
    out[i] = std::move(c);
  }
  if (stats) *stats = st;
  return out;
}

}  // namespace roprec
