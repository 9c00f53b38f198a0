/// \file work_map_report.cpp
/// The CSV and the HTML heat maps of a work map (see work_map_report.hpp).
#include "plugin/report/work_map_report.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <map>
#include <sstream>

#include "plugin/api/job.hpp"
#include "plugin/report/html.hpp"
#include "plugin/report/json.hpp"
#include "plugin/report/palette.hpp"

namespace roprec::api {
namespace {

std::string mm(const Vec3& v) {
  return formatNumber(v.x(), 3) + " " + formatNumber(v.y(), 3) + " " + formatNumber(v.z(), 3);
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

using report::Attr;
using report::fixed;
using report::Html;

std::string n1(double v) { return formatNumber(v, 1); }

struct Scale {
  double lo{0}, hi{1};
  [[nodiscard]] double t(double v) const { return hi > lo ? (v - lo) / (hi - lo) : 0.5; }
};

using Quantity = double (*)(const HolePrediction&);
double qRobot(const HolePrediction& p) { return p.d_robot.norm() * 1e6; }
double qErr(const HolePrediction& p) { return p.position_error * 1e6; }
double qU(const HolePrediction& p) { return p.U_work_exact * 1e6; }

/// One scale over every reachable point of every layer.
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

/// One heat map: a slice of one layer, one quantity, on the plotted axes.
struct Heat {
  const WorkMap& map;
  const WorkMapLayer& layer;
  int slice;
  const std::array<int, 3>& ax;
  Quantity q;
  const Scale& sc;
  const std::string& dominant;
  int nx, ny;   ///< cells along the horizontal and vertical axes
  double cell;  ///< px

  /// The point of cell (i, j) (i to the right, j up).
  [[nodiscard]] const WorkMapPoint& at(int i, int j) const {
    std::array<int, 3> idx{};
    idx[static_cast<size_t>(ax[0])] = i;
    idx[static_cast<size_t>(ax[1])] = j;
    idx[static_cast<size_t>(ax[2])] = slice;
    const auto u = [](int v) { return static_cast<size_t>(v); };  // indices and counts are >= 0
    const std::array<int, 3>& n = map.counts;
    return layer.points[u(idx[0]) + u(n[0]) * (u(idx[1]) + u(n[1]) * u(idx[2]))];
  }
  [[nodiscard]] bool reachable(int i, int j) const {
    return at(i, j).prediction.status == HoleStatus::kOk;
  }
  [[nodiscard]] double x(int i) const { return kML + i * cell; }
  [[nodiscard]] double y(int j) const { return kMT + (ny - 1 - j) * cell; }
};

/// A reachable cell filled by its value (and outlined when its configuration is not the most
/// frequent one), or a crossed grey cell; each with its tooltip.
void renderCell(Html& h, const Heat& m, int i, int j) {
  const WorkMapPoint& pt = m.at(i, j);
  const HolePrediction& p = pt.prediction;
  const double x = m.x(i), y = m.y(j), c = m.cell;
  std::string tip = "(" + mm(pt.p_mm) + ") mm \u00b7 ";
  if (p.status == HoleStatus::kOk) {
    const double v = m.q(p);
    tip += n1(v) + " \u00b5m \u00b7 " + verdictName(p.verdict) + " \u00b7 " + p.config;
    h.open("rect", {{"class", "c"},
                    {"x", fixed(x, 1)},
                    {"y", fixed(y, 1)},
                    {"width", fixed(c, 1)},
                    {"height", fixed(c, 1)},
                    {"fill", report::viridisHex(m.sc.t(v))}})
        .element("title", {}, tip)
        .close("rect");
    if (p.config != m.dominant) {
      h.leaf("rect", {{"class", "cfg"},
                      {"x", fixed(x + 1.5, 1)},
                      {"y", fixed(y + 1.5, 1)},
                      {"width", fixed(c - 3, 1)},
                      {"height", fixed(c - 3, 1)}});
    }
    return;
  }
  tip += verdictName(p.verdict) + (p.reason.empty() ? "" : ": " + p.reason);
  h.open("g", {{"class", "unr"}})
      .leaf(
          "rect",
          {{"x", fixed(x, 1)}, {"y", fixed(y, 1)}, {"width", fixed(c, 1)}, {"height", fixed(c, 1)}})
      .leaf("path", {Attr::markup("d", "M" + n1(x + 2) + " " + n1(y + 2) + "L" + n1(x + c - 2) +
                                           " " + n1(y + c - 2) + "M" + n1(x + 2) + " " +
                                           n1(y + c - 2) + "L" + n1(x + c - 2) + " " + n1(y + 2))})
      .element("title", {}, tip)
      .close("g");
}

/// Red lines between neighbouring reachable cells whose configurations differ.
void renderConfigBoundaries(Html& h, const Heat& m) {
  const auto line = [&](double x1, double y1, double x2, double y2) {
    h.leaf(
        "line",
        {{"x1", fixed(x1, 1)}, {"y1", fixed(y1, 1)}, {"x2", fixed(x2, 1)}, {"y2", fixed(y2, 1)}});
  };
  const auto differs = [&](int i, int j, int i2, int j2) {
    return m.reachable(i2, j2) && m.at(i2, j2).prediction.config != m.at(i, j).prediction.config;
  };
  h.open("g", {{"class", "bnd"}});
  for (int j = 0; j < m.ny; ++j) {
    for (int i = 0; i < m.nx; ++i) {
      if (!m.reachable(i, j)) continue;
      const double x = m.x(i), y = m.y(j);
      if (i + 1 < m.nx && differs(i, j, i + 1, j)) line(x + m.cell, y, x + m.cell, y + m.cell);
      if (j + 1 < m.ny && differs(i, j, i, j + 1)) line(x, y, x + m.cell, y);
    }
  }
  h.close("g");
}

/// The first and last grid coordinate of both axes and the axis names.
void renderAxes(Html& h, const Heat& m) {
  const WorkMapRequest& q = m.map.request;
  const double x_lo = q.lo_mm[m.ax[0]], y_lo = q.lo_mm[m.ax[1]], step = *q.step_mm;
  const double bottom = kMT + m.ny * m.cell;
  const auto text = [&](double x, double y, const char* anchor, double v) {
    h.element("text", {{"x", fixed(x, 1)}, {"y", fixed(y, 1)}, {"text-anchor", anchor}}, n1(v));
  };
  text(kML + m.cell / 2, bottom + 14, "middle", x_lo);
  text(kML + (m.nx - 0.5) * m.cell, bottom + 14, "middle", x_lo + (m.nx - 1) * step);
  text(kML - 4, kMT + (m.ny - 0.5) * m.cell + 4, "end", y_lo);
  text(kML - 4, kMT + 0.5 * m.cell + 4, "end", y_lo + (m.ny - 1) * step);
  const auto name = [&](int axis) {
    return std::string("workobject ") +
           static_cast<char>(std::toupper("xyz"[static_cast<size_t>(axis)])) + " [mm]";
  };
  h.element("text",
            {{"class", "axis"},
             {"x", fixed(kML + m.nx * m.cell / 2, 1)},
             {"y", fixed(bottom + 30, 1)},
             {"text-anchor", "middle"}},
            name(m.ax[0]));
  h.element(
      "text",
      {{"class", "axis"},
       Attr::markup("transform", "translate(14 " + n1(kMT + m.ny * m.cell / 2) + ") rotate(-90)"),
       {"text-anchor", "middle"}},
      name(m.ax[1]));
}

/// t/2 on the colour bar, or where it lies when it is off the scale.
void renderTolerance(Html& h, const Heat& m, double by, double bw) {
  const double t2 = 0.5 * m.map.context.model.default_tolerance * 1e6;
  h.open("g", {{"class", "tol"}});
  if (t2 >= m.sc.lo && t2 <= m.sc.hi) {
    const double x = kML + bw * m.sc.t(t2);
    h.leaf("line", {{"x1", fixed(x, 1)},
                    {"y1", fixed(by - 4, 1)},
                    {"x2", fixed(x, 1)},
                    {"y2", fixed(by + 14, 1)}})
        .element("text", {{"x", fixed(x, 1)}, {"y", fixed(by + 38, 1)}, {"text-anchor", "middle"}},
                 "t/2 = " + n1(t2));
  } else {
    h.element("text",
              {{"x", fixed(kML + bw / 2, 1)}, {"y", fixed(by + 38, 1)}, {"text-anchor", "middle"}},
              "t/2 = " + n1(t2) + " \u00b5m " +
                  (t2 > m.sc.hi ? "(above every value)" : "(below every value)"));
  }
  h.close("g");
}

/// 40 steps of viridis, the scale's ends and (for e⊥ and U) t/2.
void renderColourBar(Html& h, const Heat& m, bool tol) {
  const double by = kMT + m.ny * m.cell + 48, bw = m.cell * m.nx;
  for (int k = 0; k < 40; ++k) {
    h.leaf("rect", {{"x", fixed(kML + bw * k / 40, 1)},
                    {"y", fixed(by, 1)},
                    {"width", fixed(bw / 40 + 0.6, 1)},
                    {"height", "10"},
                    {"fill", report::viridisHex((k + 0.5) / 40)}});
  }
  h.element("text", {{"x", fixed(kML, 1)}, {"y", fixed(by + 24, 1)}}, n1(m.sc.lo))
      .element("text",
               {{"x", fixed(kML + bw, 1)}, {"y", fixed(by + 24, 1)}, {"text-anchor", "end"}},
               n1(m.sc.hi) + " \u00b5m");
  if (tol) renderTolerance(h, m, by, bw);
}

void renderHeat(Html& h, const Heat& m, const char* title, bool tol) {
  const double W = kML + m.cell * m.nx + 16, H = kMT + m.cell * m.ny + 110;
  h.open("figure", {{"class", "panel"}})
      .markupElement("figcaption", {}, title)
      .open("svg", {{"xmlns", "http://www.w3.org/2000/svg"},
                    Attr::markup("viewBox", "0 0 " + n1(W) + " " + n1(H)),
                    {"role", "img"}});
  for (int j = 0; j < m.ny; ++j) {
    for (int i = 0; i < m.nx; ++i) renderCell(h, m, i, j);
  }
  renderConfigBoundaries(h, m);
  renderAxes(h, m);
  renderColourBar(h, m, tol);
  h.close("svg").close("figure");
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

/// What the page says about the map: counts of points in another configuration and unreachable.
struct MapCounts {
  size_t unreachable{0}, changed{0}, total{0};
};

MapCounts countPoints(const WorkMap& map, const std::string& dominant) {
  MapCounts n;
  for (const WorkMapLayer& l : map.layers) {
    for (const WorkMapPoint& pt : l.points) {
      ++n.total;
      if (pt.prediction.status != HoleStatus::kOk) {
        ++n.unreachable;
      } else if (pt.prediction.config != dominant) {
        ++n.changed;
      }
    }
  }
  return n;
}

void renderMeta(Html& h, const WorkMap& map, const std::string& dominant) {
  const WorkMapRequest& q = map.request;
  const PredictionContext& c = map.context;
  const MapCounts n = countPoints(map, dominant);
  const auto item = [&](const char* key, const std::string& text) {
    h.element("dt", {}, key).element("dd", {}, text);
  };
  h.open("dl");
  item("Robot", c.robot.card.name);
  item("Cell", c.cell.file);
  item("Process", c.process_description);
  item("Region (workobject)",
       "(" + mm(q.lo_mm) + ") \u2192 (" + mm(q.hi_mm) + ") mm, step " +
           formatNumber(*q.step_mm, 3) + " mm, " + std::to_string(map.counts[0]) + " \u00d7 " +
           std::to_string(map.counts[1]) + " \u00d7 " + std::to_string(map.counts[2]) + " points");
  item("Drilling direction (workobject)", "(" + formatNumber(q.direction.x(), 4) + ", " +
                                              formatNumber(q.direction.y(), 4) + ", " +
                                              formatNumber(q.direction.z(), 4) + ")");
  item("Tolerance", "\u2300 " + formatNumber(c.model.default_tolerance * 1e3, 3) +
                        " mm (t/2 = " + n1(0.5 * c.model.default_tolerance * 1e6) + " \u00b5m)");
  item("Configuration",
       "most frequent: " + (dominant.empty() ? std::string("\u2014") : dominant) + "; " +
           std::to_string(n.changed) + " of " + std::to_string(n.total) +
           " point predictions in another configuration (red squares, red lines between cells "
           "where it changes), " +
           std::to_string(n.unreachable) + " unreachable or singular (grey crosses)");
  h.close("dl");
}

/// Per feed and slice: a heading and the three heat maps.
void renderLayers(Html& h, const WorkMap& map, const std::string& dominant) {
  static constexpr std::array<const char*, 3> kTitles{
      "|\u03b4robot| \u2014 robot deviation under load",
      "e\u22a5 \u2014 position error \u22a5 the hole axis",
      "U<sub>95</sub> \u2014 95 % radius of the uncertainty"};
  static constexpr std::array<Quantity, 3> kQuantities{qRobot, qErr, qU};
  const WorkMapRequest& q = map.request;
  const std::array<int, 3> ax = plotAxes(map.counts);
  const int slices = map.counts[static_cast<size_t>(ax[2])];
  const std::array<Scale, 3> sc{scaleOf(map, qRobot), scaleOf(map, qErr), scaleOf(map, qU)};
  const int nx = map.counts[static_cast<size_t>(ax[0])],
            ny = map.counts[static_cast<size_t>(ax[1])];
  const double cell = std::min(kPlot / nx, kPlot / ny);
  for (const WorkMapLayer& l : map.layers) {
    for (int s = 0; s < slices; ++s) {
      h.open("h2").text("Feed " + formatNumber(l.feed_mm_per_rev, 3) + " mm/rev");
      if (slices > 1) {
        h.text(" \u00b7 slice " + std::string(1, "XYZ"[ax[2]]) + " = " +
               n1(q.lo_mm[ax[2]] + s * *q.step_mm) + " mm");
      }
      h.close("h2").open("div", {{"class", "maps"}});
      for (size_t k = 0; k < 3; ++k) {
        const Heat m{map, l, s, ax, kQuantities[k], sc[k], dominant, nx, ny, cell};
        renderHeat(h, m, kTitles[k], k > 0);
      }
      h.close("div");
    }
  }
}

}  // namespace

std::string workMapReport(const WorkMap& map) {
  const std::string dominant = dominantConfig(map);
  const std::string title = "roprec map \u2014 " + map.context.cell.name;
  std::string o;
  Html h(o);
  h.markup("<!DOCTYPE html>\n")
      .open("html", {{"lang", "en"}})
      .open("head")
      .open("meta", {{"charset", "utf-8"}})
      .element("title", {}, title)
      .markupElement("style", {}, kMapCss)
      .markup("</head><body><main>\n")
      .element("h1", {}, title);
  h.markupElement("p", {{"class", "note"}},
                  "Where on the table to put the part: the predicted deviation and uncertainty of "
                  "a hole drilled at each grid point of the region along one direction, for each "
                  "feed (each point predicted as <code>roprec predict</code> predicts a one-hole "
                  "hole list there).");
  renderMeta(h, map, dominant);
  renderLayers(h, map, dominant);
  h.markupElement("p", {{"class", "note"}},
                  "Colour scales are shared by all feeds and slices of a quantity (viridis). "
                  "Values in \u00b5m; U<sub>95</sub> is the verdict's U (the anisotropic 95 % "
                  "radius); a hole conforms when e\u22a5 + U<sub>95</sub> \u2264 t/2. Generated "
                  "by roprec " +
                      std::string(version()) + ".");
  h.markup("\n</main></body></html>\n");
  return o;
}

}  // namespace roprec::api
