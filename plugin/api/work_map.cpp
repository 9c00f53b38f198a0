/// \file work_map.cpp
/// Work-area maps (see work_map.hpp).
#include "plugin/api/work_map.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <sstream>

#include "compensator/support/error.hpp"
#include "compensator/support/xml_escape.hpp"
#include "plugin/api/job.hpp"
#include "plugin/api/report.hpp"
#include "plugin/api/robot_compliance.hpp"

namespace roprec::api {
namespace {

bool finite(const Vec3& v) { return v.allFinite(); }

std::string mm(const Vec3& v) {
  return formatNumber(v.x(), 3) + " " + formatNumber(v.y(), 3) + " " + formatNumber(v.z(), 3);
}

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

/// The most frequent configuration text over every reachable point of every layer.
std::string dominantConfig(const WorkMap& map) {
  std::map<std::string, size_t> n;
  for (const WorkMapLayer& l : map.layers) {
    for (const WorkMapPoint& p : l.points) {
      if (p.prediction.status == HoleStatus::kOk) ++n[p.prediction.config];
    }
  }
  std::string best;
  size_t most = 0;
  for (const auto& [cfg, k] : n) {
    if (k > most) {
      most = k;
      best = cfg;
    }
  }
  return best;
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

std::string workMapCsv(const WorkMap& map) {
  const std::string dominant = dominantConfig(map);
  std::ostringstream s;
  s << "feed_mm_per_rev,x_mm,y_mm,z_mm,status,verdict,branch,config,config_change,j1_deg,j2_deg,"
       "j3_deg,j4_deg,j5_deg,j6_deg,d_robot_um,position_error_um,U_work_um,U95_um,tolerance_mm,"
       "reason,j1_ctrl_deg,j2_ctrl_deg,j3_ctrl_deg,j4_ctrl_deg,j5_ctrl_deg,j6_ctrl_deg\n";
  for (const WorkMapLayer& l : map.layers) {
    for (const WorkMapPoint& pt : l.points) {
      const HolePrediction& p = pt.prediction;
      const bool ok = p.status == HoleStatus::kOk;
      const bool has_joints = ok || !p.config.empty();
      s << formatNumber(l.feed_mm_per_rev, 4) << "," << formatNumber(pt.p_mm.x(), 3) << ","
        << formatNumber(pt.p_mm.y(), 3) << "," << formatNumber(pt.p_mm.z(), 3) << ","
        << (ok ? "ok" : "failed") << "," << verdictName(p.verdict) << ","
        << (has_joints ? std::to_string(p.branch) : "") << ",\"" << p.config << "\","
        << (ok && p.config != dominant ? 1 : 0);
      for (int j = 0; j < 6; ++j)
        s << "," << (has_joints ? formatNumber(p.joints[j] / kDeg, 3) : "");
      if (ok) {
        s << "," << formatNumber(p.d_robot.norm() * 1e6, 3) << ","
          << formatNumber(p.position_error * 1e6, 3) << "," << formatNumber(p.U_work * 1e6, 3)
          << "," << formatNumber(p.U_work_exact * 1e6, 3);
      } else {
        s << ",,,,";
      }
      std::string reason = p.reason;
      std::replace(reason.begin(), reason.end(), '"', '\'');
      s << "," << formatNumber(p.tolerance * 1e3, 4) << ",\"" << reason << "\"";
      // the joints as the controller shows them (FANUC J3 relative to J2; docs/reports.md)
      const Vec6 q_ctrl = toControllerJoints(map.context.robot.card, p.joints);
      for (int j = 0; j < 6; ++j) s << "," << (has_joints ? formatNumber(q_ctrl[j] / kDeg, 3) : "");
      s << "\n";
    }
  }
  return s.str();
}

// ------------------------------------------------------------------ HTML

namespace {

std::string esc(const std::string& s) { return escapeXml(s); }
std::string n1(double v) { return formatNumber(v, 1); }

struct Scale {
  double lo{0}, hi{1};
  [[nodiscard]] double t(double v) const { return hi > lo ? (v - lo) / (hi - lo) : 0.5; }
};

using Quantity = double (*)(const HolePrediction&);
double qRobot(const HolePrediction& p) { return p.d_robot.norm() * 1e6; }
double qErr(const HolePrediction& p) { return p.position_error * 1e6; }
double qU(const HolePrediction& p) { return p.U_work_exact * 1e6; }

Scale scaleOf(const WorkMap& map, Quantity q) {
  Scale s;
  bool any = false;
  for (const WorkMapLayer& l : map.layers) {
    for (const WorkMapPoint& pt : l.points) {
      if (pt.prediction.status != HoleStatus::kOk) continue;
      const double v = q(pt.prediction);
      if (!any) s.lo = s.hi = v;
      any = true;
      s.lo = std::min(s.lo, v);
      s.hi = std::max(s.hi, v);
    }
  }
  if (s.hi - s.lo < 1e-3) s.hi = s.lo + 1e-3;
  return s;
}

/// The two plotted axes: the two with the most points (x, y on ties); the third is sliced.
std::array<int, 3> plotAxes(const std::array<int, 3>& counts) {
  std::array<int, 3> a{0, 1, 2};
  std::stable_sort(a.begin(), a.end(), [&](int i, int j) {
    return counts[static_cast<size_t>(i)] > counts[static_cast<size_t>(j)];
  });
  if (a[0] > a[1]) std::swap(a[0], a[1]);
  return a;  // a[0] horizontal, a[1] vertical, a[2] sliced
}

constexpr double kPlot = 300, kML = 56, kMT = 10;

void renderHeat(std::string& o, const WorkMap& map, const WorkMapLayer& layer, int slice,
                const std::array<int, 3>& ax, Quantity q, const Scale& sc, const std::string& title,
                const std::string& dominant, bool tol) {
  const std::array<int, 3>& n = map.counts;
  const int nx = n[static_cast<size_t>(ax[0])], ny = n[static_cast<size_t>(ax[1])];
  const double cell = std::min(kPlot / nx, kPlot / ny);
  const double W = kML + cell * nx + 16, H = kMT + cell * ny + 110;
  const char* names = "xyz";
  auto at = [&](int i, int j) -> const WorkMapPoint& {
    std::array<int, 3> idx{};
    idx[static_cast<size_t>(ax[0])] = i;
    idx[static_cast<size_t>(ax[1])] = j;
    idx[static_cast<size_t>(ax[2])] = slice;
    const auto u = [](int v) { return static_cast<size_t>(v); };  // indices and counts are >= 0
    return layer.points[u(idx[0]) + u(n[0]) * (u(idx[1]) + u(n[1]) * u(idx[2]))];
  };
  o += "<figure class=\"panel\"><figcaption>" + title +
       "</figcaption><svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " + n1(W) + " " +
       n1(H) + "\" role=\"img\">";
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const WorkMapPoint& pt = at(i, j);
      const HolePrediction& p = pt.prediction;
      const double x = kML + i * cell, y = kMT + (ny - 1 - j) * cell;
      std::string tip = "(" + mm(pt.p_mm) + ") mm \u00b7 ";
      if (p.status == HoleStatus::kOk) {
        const double v = q(p);
        tip += n1(v) + " \u00b5m \u00b7 " + verdictName(p.verdict) + " \u00b7 " + esc(p.config);
        o += "<rect class=\"c\" x=\"" + n1(x) + "\" y=\"" + n1(y) + "\" width=\"" + n1(cell) +
             "\" height=\"" + n1(cell) + "\" fill=\"" + viridisHex(sc.t(v)) + "\"><title>" + tip +
             "</title></rect>";
        if (p.config != dominant) {
          o += "<rect class=\"cfg\" x=\"" + n1(x + 1.5) + "\" y=\"" + n1(y + 1.5) + "\" width=\"" +
               n1(cell - 3) + "\" height=\"" + n1(cell - 3) + "\"/>";
        }
      } else {
        tip += verdictName(p.verdict) + (p.reason.empty() ? "" : ": " + esc(p.reason));
        o += "<g class=\"unr\"><rect x=\"" + n1(x) + "\" y=\"" + n1(y) + "\" width=\"" + n1(cell) +
             "\" height=\"" + n1(cell) + "\"/><path d=\"M" + n1(x + 2) + " " + n1(y + 2) + "L" +
             n1(x + cell - 2) + " " + n1(y + cell - 2) + "M" + n1(x + 2) + " " + n1(y + cell - 2) +
             "L" + n1(x + cell - 2) + " " + n1(y + 2) + "\"/><title>" + tip + "</title></g>";
      }
    }
  }
  // configuration boundaries between neighbouring reachable cells
  o += "<g class=\"bnd\">";
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const HolePrediction& p = at(i, j).prediction;
      if (p.status != HoleStatus::kOk) continue;
      const double x = kML + i * cell, y = kMT + (ny - 1 - j) * cell;
      if (i + 1 < nx && at(i + 1, j).prediction.status == HoleStatus::kOk &&
          at(i + 1, j).prediction.config != p.config) {
        o += "<line x1=\"" + n1(x + cell) + "\" y1=\"" + n1(y) + "\" x2=\"" + n1(x + cell) +
             "\" y2=\"" + n1(y + cell) + "\"/>";
      }
      if (j + 1 < ny && at(i, j + 1).prediction.status == HoleStatus::kOk &&
          at(i, j + 1).prediction.config != p.config) {
        o += "<line x1=\"" + n1(x) + "\" y1=\"" + n1(y) + "\" x2=\"" + n1(x + cell) + "\" y2=\"" +
             n1(y) + "\"/>";
      }
    }
  }
  o += "</g>";
  // axes: the first and last grid coordinate
  const double x_lo = map.request.lo_mm[ax[0]], y_lo = map.request.lo_mm[ax[1]];
  const double step = *map.request.step_mm;
  o += "<text x=\"" + n1(kML + cell / 2) + "\" y=\"" + n1(kMT + ny * cell + 14) +
       "\" text-anchor=\"middle\">" + n1(x_lo) + "</text><text x=\"" + n1(kML + (nx - 0.5) * cell) +
       "\" y=\"" + n1(kMT + ny * cell + 14) + "\" text-anchor=\"middle\">" +
       n1(x_lo + (nx - 1) * step) + "</text>";
  o += "<text x=\"" + n1(kML - 4) + "\" y=\"" + n1(kMT + (ny - 0.5) * cell + 4) +
       "\" text-anchor=\"end\">" + n1(y_lo) + "</text><text x=\"" + n1(kML - 4) + "\" y=\"" +
       n1(kMT + 0.5 * cell + 4) + "\" text-anchor=\"end\">" + n1(y_lo + (ny - 1) * step) +
       "</text>";
  o += "<text class=\"axis\" x=\"" + n1(kML + nx * cell / 2) + "\" y=\"" +
       n1(kMT + ny * cell + 30) + "\" text-anchor=\"middle\">workobject " +
       std::string(1, static_cast<char>(std::toupper(names[ax[0]]))) +
       " [mm]</text><text class=\"axis\" transform=\"translate(14 " + n1(kMT + ny * cell / 2) +
       ") rotate(-90)\" text-anchor=\"middle\">workobject " +
       std::string(1, static_cast<char>(std::toupper(names[ax[1]]))) + " [mm]</text>";
  // colour bar with t/2
  const double by = kMT + ny * cell + 48, bw = cell * nx;
  for (int k = 0; k < 40; ++k) {
    o += "<rect x=\"" + n1(kML + bw * k / 40) + "\" y=\"" + n1(by) + "\" width=\"" +
         n1(bw / 40 + 0.6) + "\" height=\"10\" fill=\"" + viridisHex((k + 0.5) / 40) + "\"/>";
  }
  o += "<text x=\"" + n1(kML) + "\" y=\"" + n1(by + 24) + "\">" + n1(sc.lo) + "</text><text x=\"" +
       n1(kML + bw) + "\" y=\"" + n1(by + 24) + "\" text-anchor=\"end\">" + n1(sc.hi) +
       " \u00b5m</text>";
  if (tol) {
    const double t2 = 0.5 * map.context.model.default_tolerance * 1e6;
    if (t2 >= sc.lo && t2 <= sc.hi) {
      const double x = kML + bw * sc.t(t2);
      o += "<g class=\"tol\"><line x1=\"" + n1(x) + "\" y1=\"" + n1(by - 4) + "\" x2=\"" + n1(x) +
           "\" y2=\"" + n1(by + 14) + "\"/><text x=\"" + n1(x) + "\" y=\"" + n1(by + 38) +
           "\" text-anchor=\"middle\">t/2 = " + n1(t2) + "</text></g>";
    } else {
      o += "<g class=\"tol\"><text x=\"" + n1(kML + bw / 2) + "\" y=\"" + n1(by + 38) +
           "\" text-anchor=\"middle\">t/2 = " + n1(t2) + " \u00b5m " +
           (t2 > sc.hi ? "(above every value)" : "(below every value)") + "</text></g>";
    }
  }
  o += "</svg></figure>";
}

constexpr const char* kMapCss = R"CSS(
body{margin:0;color:#1f2328;font:14px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,Arial,sans-serif;font-variant-numeric:tabular-nums}
main{max-width:1480px;margin:0 auto;padding:24px 32px 40px}
h1{font-size:24px;margin:0 0 4px}h2{font-size:18px;margin:28px 0 8px;border-bottom:1px solid #d1d9e0;padding-bottom:4px}
.note{color:#59636e;font-size:12.5px}
.maps{display:grid;grid-template-columns:repeat(3,minmax(0,1fr));gap:14px}
.panel{margin:0;border:1px solid #d1d9e0;border-radius:8px;padding:8px}
.panel figcaption{font-weight:600;font-size:13px}
.panel svg{display:block;width:100%;height:auto}
svg text{font-size:11px;fill:#424a53}svg .axis{fill:#1f2328}
svg .cfg{fill:none;stroke:#e3120b;stroke-width:2}
svg .unr rect{fill:#eaeef2;stroke:#afb8c1;stroke-width:.5}svg .unr path{stroke:#57606a;stroke-width:1.4}
svg .bnd line{stroke:#e3120b;stroke-width:3;stroke-linecap:round}
svg .tol line{stroke:#cf222e;stroke-width:2}svg .tol text{fill:#a40e26;font-weight:600}
dl{display:grid;grid-template-columns:max-content 1fr;gap:2px 14px;background:#f6f8fa;border:1px solid #d1d9e0;border-radius:8px;padding:10px 14px}
dt{color:#59636e}dd{margin:0}
)CSS";

}  // namespace

std::string workMapReport(const WorkMap& map) {
  const WorkMapRequest& q = map.request;
  const PredictionContext& c = map.context;
  const std::string dominant = dominantConfig(map);
  const std::array<int, 3> ax = plotAxes(map.counts);
  const int slices = map.counts[static_cast<size_t>(ax[2])];
  const std::array<Scale, 3> sc{scaleOf(map, qRobot), scaleOf(map, qErr), scaleOf(map, qU)};
  size_t unreachable = 0, changed = 0, total = 0;
  for (const WorkMapLayer& l : map.layers) {
    for (const WorkMapPoint& pt : l.points) {
      ++total;
      if (pt.prediction.status != HoleStatus::kOk) {
        ++unreachable;
      } else if (pt.prediction.config != dominant) {
        ++changed;
      }
    }
  }
  std::string o =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>roprec map \u2014 " +
      esc(c.cell.name) + "</title><style>" + kMapCss + "</style></head><body><main>\n";
  o += "<h1>roprec map \u2014 " + esc(c.cell.name) + "</h1>";
  o += "<p class=\"note\">Where on the table to put the part: the predicted deviation and "
       "uncertainty of a hole drilled at each grid point of the region along one direction, for "
       "each feed (each point predicted as <code>roprec predict</code> predicts a one-hole hole "
       "list there).</p><dl>";
  o += "<dt>Robot</dt><dd>" + esc(c.robot.card.name) + "</dd><dt>Cell</dt><dd>" + esc(c.cell.file) +
       "</dd><dt>Process</dt><dd>" + esc(c.process_description) + "</dd>";
  o += "<dt>Region (workobject)</dt><dd>(" + mm(q.lo_mm) + ") \u2192 (" + mm(q.hi_mm) +
       ") mm, step " + formatNumber(*q.step_mm, 3) + " mm, " + std::to_string(map.counts[0]) +
       " \u00d7 " + std::to_string(map.counts[1]) + " \u00d7 " + std::to_string(map.counts[2]) +
       " points</dd>";
  o += "<dt>Drilling direction (workobject)</dt><dd>(" + formatNumber(q.direction.x(), 4) + ", " +
       formatNumber(q.direction.y(), 4) + ", " + formatNumber(q.direction.z(), 4) + ")</dd>";
  o += "<dt>Tolerance</dt><dd>\u2300 " + formatNumber(c.model.default_tolerance * 1e3, 3) +
       " mm (t/2 = " + n1(0.5 * c.model.default_tolerance * 1e6) + " \u00b5m)</dd>";
  o += "<dt>Configuration</dt><dd>most frequent: " + esc(dominant.empty() ? "\u2014" : dominant) +
       "; " + std::to_string(changed) + " of " + std::to_string(total) +
       " point predictions in another configuration (red squares, red lines between cells where "
       "it changes), " +
       std::to_string(unreachable) + " unreachable or singular (grey crosses)</dd></dl>";
  const std::array<const char*, 3> titles{"|\u03b4robot| \u2014 robot deviation under load",
                                          "e\u22a5 \u2014 position error \u22a5 the hole axis",
                                          "U<sub>95</sub> \u2014 95 % radius of the uncertainty"};
  const std::array<Quantity, 3> qs{qRobot, qErr, qU};
  for (const WorkMapLayer& l : map.layers) {
    for (int s = 0; s < slices; ++s) {
      o += "<h2>Feed " + formatNumber(l.feed_mm_per_rev, 3) + " mm/rev";
      if (slices > 1) {
        o += " \u00b7 slice " + std::string(1, "XYZ"[ax[2]]) + " = " +
             n1(q.lo_mm[ax[2]] + s * *q.step_mm) + " mm";
      }
      o += "</h2><div class=\"maps\">";
      for (size_t k = 0; k < 3; ++k)
        renderHeat(o, map, l, s, ax, qs[k], sc[k], titles[k], dominant, k > 0);
      o += "</div>";
    }
  }
  o += "<p class=\"note\">Colour scales are shared by all feeds and slices of a quantity "
       "(viridis). Values in \u00b5m; U<sub>95</sub> is the verdict's U (the anisotropic 95 % "
       "radius); a hole conforms when e\u22a5 + U<sub>95</sub> \u2264 t/2. Generated by roprec " +
       std::string(version()) + ".</p>";
  o += "\n</main></body></html>\n";
  return o;
}

}  // namespace roprec::api
