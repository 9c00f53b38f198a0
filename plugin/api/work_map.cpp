/// \file work_map.cpp
/// Work-area maps (see work_map.hpp).
#include "plugin/api/work_map.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "compensator/support/error.hpp"
#include "plugin/api/job.hpp"
#include "plugin/api/robot_compliance.hpp"

namespace roprec::api {
namespace {

bool finite(const Vec3& v) { return v.allFinite(); }

/// The prediction model of the cell with the drilling feed replaced (everything else as
/// loadPredictionContext builds it).
PredictionModel modelAtFeed(const PredictionContext& c, double feed_m_per_rev) {
  PredictionSetup s;
  s.robot = c.robot;
  s.tool = c.tool;
  ProcessSpec proc = *c.process;
  proc.drilling.feed = feed_m_per_rev;
  if (!proc.drills.empty()) proc.drills.front().feed = feed_m_per_rev;  // the cell's (first) drill
  s.process = proc;
  s.uncertainty = c.model.uncertainty;
  s.accuracy = c.model.accuracy;
  s.capability = c.model.capability;
  s.default_tolerance = c.model.default_tolerance;
  const ControllerGravity cg = controllerGravityOf(c.robot.card, &c.cell, c.tool);
  s.controller_gravity = cg.gravity_compensated;
  s.calibration_load = cg.calibration_load;
  PredictionModel m = buildPredictionModel(s);
  m.config_options = c.model.config_options;
  return m;
}

int countAlong(double span, double step) {
  return static_cast<int>(std::floor(span / step + 1e-9)) + 1;
}

std::string pointId(const std::array<int, 3>& i) {
  return "P" + std::to_string(i[0]) + "_" + std::to_string(i[1]) + "_" + std::to_string(i[2]);
}

}  // namespace

WorkMap computeWorkMap(const WorkMapRequest& request,
                       const std::function<void(size_t, size_t)>& progress) {
  WorkMap map;
  WorkMapRequest& q = map.request;
  q = request;
  if (!finite(q.lo_mm) || !finite(q.hi_mm))
    throw UsageError("--region: six finite numbers \"x0 y0 z0 x1 y1 z1\" (mm) expected");
  for (int i = 0; i < 3; ++i) {
    if (q.hi_mm[i] < q.lo_mm[i]) {
      throw UsageError("--region: the second corner must not be below the first along " +
                       std::string(1, "xyz"[i]) + " (" + formatNumber(q.hi_mm[i], 3) + " < " +
                       formatNumber(q.lo_mm[i], 3) +
                       " mm); give \"x0 y0 z0 x1 y1 z1\" with x1 ≥ "
                       "x0, y1 ≥ y0, z1 ≥ z0");
    }
  }
  if (!finite(q.direction) || q.direction.norm() < 1e-9)
    throw UsageError(
        "--direction: a non-zero drilling direction \"i j k\" expected (e.g. \"0 0 -1\")");
  q.direction.normalize();
  const double span = (q.hi_mm - q.lo_mm).maxCoeff();
  if (q.step_mm) {
    if (!std::isfinite(*q.step_mm) || *q.step_mm <= 0)
      throw UsageError("--step must be > 0 mm, got " + numberText(*q.step_mm));
  } else {
    q.step_mm = std::max(1.0, span / 10.0);
  }
  for (const double f : q.feeds_mm_per_rev) {
    if (!std::isfinite(f) || f <= 0 || f > 5)
      throw UsageError("--feeds: feeds per revolution in (0, 5] mm/rev expected, got " +
                       formatNumber(f, 6));
  }
  const double step = *q.step_mm;
  int dims = 0;
  size_t points = 1;
  for (int i = 0; i < 3; ++i) {
    const double n = std::floor((q.hi_mm[i] - q.lo_mm[i]) / step + 1e-9) + 1;
    if (n > 1e7) {
      throw UsageError("--step " + numberText(step) + " mm gives more than 10^7 points along " +
                       std::string(1, "xyz"[i]) + "; use a larger --step");
    }
    map.counts[static_cast<size_t>(i)] = countAlong(q.hi_mm[i] - q.lo_mm[i], step);
    points *= static_cast<size_t>(map.counts[static_cast<size_t>(i)]);
    dims += map.counts[static_cast<size_t>(i)] > 1 ? 1 : 0;
  }
  const size_t feeds = std::max<size_t>(1, q.feeds_mm_per_rev.size());
  if (points * feeds > q.max_predictions) {
    const double grow =
        std::pow(static_cast<double>(points * feeds) / static_cast<double>(q.max_predictions),
                 1.0 / std::max(1, dims));
    throw UsageError(
        "the region with --step " + numberText(step) + " mm has " + std::to_string(points) +
        " points \u00d7 " + std::to_string(feeds) + " feeds = " + std::to_string(points * feeds) +
        " predictions, more than the limit " + std::to_string(q.max_predictions) + "; use --step " +
        formatNumber(std::ceil(step * grow * 1.01 * 10) / 10, 1) + " or a smaller region");
  }

  map.context = loadPredictionContext(q.cell_path, "", std::nullopt, "", 0.5, false);
  const PredictionContext& c = map.context;
  if (!c.process || c.process->type != ProcessType::kDrilling)
    throw UsageError("roprec map needs a cell with a drilling <process> (" + c.cell.file + ")");
  if (q.feeds_mm_per_rev.empty()) q.feeds_mm_per_rev.push_back(c.process->drilling.feed * 1e3);

  const Mat3 R_wobj_tcp = holeFrame(q.direction);
  const size_t total = points * q.feeds_mm_per_rev.size();
  size_t done = 0;
  for (const double feed : q.feeds_mm_per_rev) {
    const PredictionModel m = modelAtFeed(c, feed * 1e-3);
    const bool fresh = m.uncertainty.method == UncertaintyInputs::Method::kMonteCarlo;
    PredictionData data(m);
    WorkMapLayer layer;
    layer.feed_mm_per_rev = feed;
    layer.points.reserve(points);
    for (int iz = 0; iz < map.counts[2]; ++iz) {
      for (int iy = 0; iy < map.counts[1]; ++iy) {
        for (int ix = 0; ix < map.counts[0]; ++ix) {
          WorkMapPoint pt;
          pt.index = {ix, iy, iz};
          pt.p_mm = q.lo_mm + step * Vec3(ix, iy, iz);
          HoleRequest r;
          r.id = pointId(pt.index);
          Pose T_wobj_tcp = Pose::Identity();
          T_wobj_tcp.linear() = R_wobj_tcp;
          T_wobj_tcp.translation() = pt.p_mm * 1e-3;
          r.T_W_tcp = c.cell.T_base_wobj * T_wobj_tcp;
          // on the part where the cell's <part_registration> found it, as predict aims a hole
          if (c.cell.part_registration) r.T_W_tcp = partMotion(c.cell) * r.T_W_tcp;
          if (fresh) {
            PredictionData d(m);  // the sampler restarts at its seed, as in a one-hole predict
            pt.prediction = predictHole(m, d, r, nullptr);
          } else {
            pt.prediction = predictHole(m, data, r, nullptr);
          }
          layer.points.push_back(std::move(pt));
          if (progress) progress(++done, total);
        }
      }
    }
    map.layers.push_back(std::move(layer));
  }
  return map;
}

}  // namespace roprec::api
