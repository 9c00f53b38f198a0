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

PredictionModel base(const PredictionModel& m) {
  PredictionModel v = m;
  v.controller = nc::ControllerReference{};  // kNone: no reference offset
  v.uncertainty.method = UncertaintyInputs::Method::kLinear;
  v.drill_models.clear();  // a variant of one model (the splitter keeps one set per drill)
  return v;
}

/// The variants of one model (`m` has no drill_models in use), its TCP T_flange_tcp.
Variants variantsOf(const PredictionModel& m, const Pose& T_flange_tcp) {
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
  return {std::move(links), std::move(weight), std::move(loaded), std::move(alone)};
}

}  // namespace

/// One model's variants and each worker's prediction scratch for them.
struct DeviationSplitter::Models {
  const PredictionModel& m;
  Variants v;
  mutable std::vector<std::array<PredictionData, 4>> scratch;
  Models(const PredictionModel& model, const Pose& T_flange_tcp, int workers)
      : m(model), v(variantsOf(model, T_flange_tcp)) {
    scratch.reserve(static_cast<size_t>(std::max(1, workers)));
    for (int w = 0; w < std::max(1, workers); ++w)
      scratch.push_back(
          {PredictionData(v[0]), PredictionData(v[1]), PredictionData(v[2]), PredictionData(v[3])});
  }
};

DeviationSplitter::DeviationSplitter(const PredictionModel& m, const nc::ToolAttachment& tool,
                                     int workers, bool process_alone)
    : m_(m), process_alone_(process_alone) {
  models_.push_back(std::make_unique<Models>(m, tool.T_flange_tcp, workers));
  // drills with TCPs of their own: the holes of each drill split with its model
  for (const std::shared_ptr<PredictionModel>& d : m.drill_models) {
    models_.push_back(d ? std::make_unique<Models>(
                              *d, Pose(d->model.T_L6_flange.inverse() * d->model.T_L6_tcp), workers)
                        : nullptr);
  }
}

DeviationSplitter::~DeviationSplitter() = default;

std::optional<DeviationSplit> DeviationSplitter::split(const HoleRequest& r, HoleStatus status,
                                                       const Vec6& joints, const Vec3& d_robot,
                                                       int worker) const {
  if (status != HoleStatus::kOk) return std::nullopt;
  const PredictionModel* own = &modelFor(m_, r);
  const Models* set = models_.front().get();
  for (size_t i = 1; i < models_.size(); ++i)
    if (models_[i] && &models_[i]->m == own) set = models_[i].get();
  std::array<PredictionData, 4>& d = set->scratch[static_cast<size_t>(worker)];
  std::array<Vec3, 4> delta;
  for (size_t k = 0; k < (process_alone_ ? 4U : 3U); ++k) {
    const std::optional<Vec3> dk = robotDeviationAt(set->v[k], d[k], r, joints);
    if (!dk) return std::nullopt;
    delta[k] = *dk;
  }
  const PredictionModel& m = set->m;
  DeviationSplit s;
  if (m.calibrated) {
    const Pose real = chainForwardKinematics(m.robot.real_chain, joints) *
                      m.model.T_L6_flange.inverse() * m.model.T_L6_tcp;
    s.geometry = real.translation() - controllerTcp(m, joints).translation();
  }
  s.gravity = delta[0] - s.geometry;
  s.tool = delta[1] - delta[0];
  s.process = delta[2] - delta[1];
  s.controller = d_robot - delta[2];
  if (process_alone_) s.process_alone = delta[3] - s.geometry;
  return s;
}

std::vector<std::optional<DeviationSplit>> splitRobotDeviations(
    const PredictionModel& m, const nc::ToolAttachment& tool,
    const std::vector<HoleRequest>& requests, const std::vector<const HolePrediction*>& preds,
    int threads, bool process_alone) {
  const int workers = std::max(1, threads);
  const DeviationSplitter splitter(m, tool, workers, process_alone);
  std::vector<std::optional<DeviationSplit>> out(preds.size());
  parallelFor(std::min(preds.size(), requests.size()), workers, [&](int w, size_t i) {
    const HolePrediction* p = preds[i];
    if (p != nullptr) out[i] = splitter.split(requests[i], p->status, p->joints, p->d_robot, w);
  });
  return out;
}

}  // namespace roprec::api
