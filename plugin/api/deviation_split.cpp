/// \file deviation_split.cpp
/// δrobot split by sequential re-evaluation (see deviation_split.hpp).
#include "plugin/api/deviation_split.hpp"

#include <algorithm>
#include <array>

#include "compensator/precision/parallel.hpp"

namespace roprec::api {
namespace {

/// `m` with the process wrench removed (the rotating force and δmach do not enter δrobot).
void dropProcessLoad(PredictionModel& m) {
  for (auto& [key, proc] : m.process_by_diameter) {
    proc.wrench.force.setZero();
    proc.wrench.torque.setZero();
  }
  for (auto& [key, proc] : m.process_by_hole) {
    proc.wrench.force.setZero();
    proc.wrench.torque.setZero();
  }
}

/// The four re-evaluated models (δ₁ links, δ₂ + tool, δ₃ + process, the process alone).
using Variants = std::array<PredictionModel, 4>;

/// One worker's prediction scratch for each of the four models.
struct VariantData {
  std::array<PredictionData, 4> d;
  explicit VariantData(const Variants& v)
      : d{PredictionData(v[0]), PredictionData(v[1]), PredictionData(v[2]), PredictionData(v[3])} {}
};

PredictionModel base(const PredictionModel& m) {
  PredictionModel v = m;
  v.controller = nc::ControllerReference{};  // kNone: no reference offset
  v.uncertainty.method = UncertaintyInputs::Method::kLinear;
  v.drill_models.clear();  // a variant of one model (splitRobotDeviations splits by drill)
  return v;
}

/// δ of hole `r` with the IK solution of `p` (the nearest solution to p's joints is p's own).
std::optional<Vec3> deviationOf(const PredictionModel& m, PredictionData& d, const HoleRequest& r,
                                const HolePrediction& p) {
  HoleRequest q = r;
  q.config.reset();
  q.ik_seed = p.joints;
  q.nominal_axis.reset();
  const HolePrediction e = predictHole(m, d, q, nullptr);
  if (e.status != HoleStatus::kOk) return std::nullopt;
  if ((e.joints - p.joints).cwiseAbs().maxCoeff() > 1e-9) return std::nullopt;
  return e.d_robot;
}

/// splitRobotDeviations with one model (`m` has no drill_models in use), its TCP T_flange_tcp.
std::vector<std::optional<DeviationSplit>> splitOneModel(
    const PredictionModel& m, const Pose& T_flange_tcp, const std::vector<HoleRequest>& requests,
    const std::vector<const HolePrediction*>& preds, int threads) {
  // δ₁: links only (tool massless, its TCP kept), no process, no reference
  PredictionModel links = base(m);
  nc::ToolAttachment massless;
  massless.T_flange_tcp = T_flange_tcp;
  links.model = nc::buildModel(m.robot.real_chain, massless);
  dropProcessLoad(links);
  // δ₂: links + tool
  PredictionModel weight = base(m);
  dropProcessLoad(weight);
  // δ₃: everything but the reference; the process alone: no weight at all
  PredictionModel loaded = base(m);
  PredictionModel alone = base(m);
  alone.gravity = false;

  const Variants v{std::move(links), std::move(weight), std::move(loaded), std::move(alone)};
  const int workers = std::max(1, threads);
  std::vector<VariantData> scratch;
  scratch.reserve(static_cast<size_t>(workers));
  for (int w = 0; w < workers; ++w) scratch.emplace_back(v);
  std::vector<std::optional<DeviationSplit>> out(preds.size());
  parallelFor(std::min(preds.size(), requests.size()), workers, [&](int w, size_t i) {
    const HolePrediction* p = preds[i];
    if (p == nullptr || p->status != HoleStatus::kOk) return;
    std::array<PredictionData, 4>& d = scratch[static_cast<size_t>(w)].d;
    const auto d1 = deviationOf(v[0], d[0], requests[i], *p);
    const auto d2 = deviationOf(v[1], d[1], requests[i], *p);
    const auto d3 = deviationOf(v[2], d[2], requests[i], *p);
    const auto d4 = deviationOf(v[3], d[3], requests[i], *p);
    if (!d1 || !d2 || !d3 || !d4) return;
    DeviationSplit s;
    if (m.calibrated) {
      const Pose real = chainForwardKinematics(m.robot.real_chain, p->joints) *
                        m.model.T_L6_flange.inverse() * m.model.T_L6_tcp;
      s.geometry = real.translation() - controllerTcp(m, p->joints).translation();
    }
    s.gravity = *d1 - s.geometry;
    s.tool = *d2 - *d1;
    s.process = *d3 - *d2;
    s.controller = p->d_robot - *d3;
    s.process_alone = *d4 - s.geometry;
    out[i] = s;
  });
  return out;
}

}  // namespace

std::vector<std::optional<DeviationSplit>> splitRobotDeviations(
    const PredictionModel& m, const nc::ToolAttachment& tool,
    const std::vector<HoleRequest>& requests, const std::vector<const HolePrediction*>& preds,
    int threads) {
  if (!hasDrillModels(m)) return splitOneModel(m, tool.T_flange_tcp, requests, preds, threads);
  // drills with TCPs of their own: the holes of each model split with it
  const size_t n = std::min(preds.size(), requests.size());
  std::vector<const PredictionModel*> models;
  for (size_t i = 0; i < n; ++i) {
    const PredictionModel* mi = &modelFor(m, requests[i]);
    if (std::find(models.begin(), models.end(), mi) == models.end()) models.push_back(mi);
  }
  std::vector<std::optional<DeviationSplit>> out(preds.size());
  for (const PredictionModel* mm : models) {
    std::vector<const HolePrediction*> own(preds.size(), nullptr);
    for (size_t i = 0; i < n; ++i)
      if (&modelFor(m, requests[i]) == mm) own[i] = preds[i];
    const Pose T =
        mm == &m ? tool.T_flange_tcp : Pose(mm->model.T_L6_flange.inverse() * mm->model.T_L6_tcp);
    std::vector<std::optional<DeviationSplit>> part = splitOneModel(*mm, T, requests, own, threads);
    for (size_t i = 0; i < n; ++i)
      if (own[i] != nullptr) out[i] = part[i];
  }
  return out;
}

}  // namespace roprec::api
