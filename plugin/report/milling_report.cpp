#include "plugin/report/milling_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "compensator/support/c_format.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/xml_escape.hpp"

namespace roprec::api {
namespace {

/// A shown number: fixed decimals in the C locale; a non-finite value is refused.
std::string num(double v, int decimals, const char* what) {
  if (!std::isfinite(v))
    throw InputError("", 0, std::string("milling report: ") + what + " is not finite");
  return cFixed(v, decimals);
}

std::string esc(const std::string& s) { return escapeXml(s); }

/// Hands `s` to `sink` once it holds about 64 KiB (and clears it).
void flush(std::string& s, const ByteSink& sink, bool all = false) {
  if (s.empty() || (!all && s.size() < 64 * 1024)) return;
  sink(s);
  s.clear();
}

/// |deviation before| and |residual after| (µm) along the path as two polylines.
void pathPlot(const MillingReportSummary& sum, std::string& s, const ByteSink& sink) {
  const std::size_t n = sum.points.size();
  double top = 1.0;
  for (const auto& p : sum.points) top = std::max(top, p.before_um);
  const double w = 760;
  const double h = 220;
  const double x0 = 60;
  const double y0 = 20;
  auto px = [&](std::size_t i) {
    return x0 + (n > 1 ? w * static_cast<double>(i) / static_cast<double>(n - 1) : w / 2);
  };
  auto py = [&](double um) { return y0 + h - h * um / top; };
  s += "<svg width=\"860\" height=\"280\" role=\"img\" aria-label=\"deviation along the path\">\n";
  s += "<line x1=\"" + num(x0, 0, "") + "\" y1=\"" + num(y0 + h, 0, "") + "\" x2=\"" +
       num(x0 + w, 0, "") + "\" y2=\"" + num(y0 + h, 0, "") + "\" stroke=\"#444\"/>\n";
  s += "<line x1=\"" + num(x0, 0, "") + "\" y1=\"" + num(y0, 0, "") + "\" x2=\"" + num(x0, 0, "") +
       "\" y2=\"" + num(y0 + h, 0, "") + "\" stroke=\"#444\"/>\n";
  s += "<text x=\"4\" y=\"" + num(y0 + 4, 0, "") + "\" font-size=\"11\">" + num(top, 1, "scale") +
       " µm</text>\n<text x=\"40\" y=\"" + num(y0 + h + 4, 0, "") +
       "\" font-size=\"11\">0</text>\n";
  s += "<text x=\"" + num(x0 + w / 2 - 60, 0, "") + "\" y=\"" + num(y0 + h + 30, 0, "") +
       "\" font-size=\"12\">path point (program order)</text>\n";
  // the two polylines, point by point
  auto polyline = [&](const char* colour, const char* what, auto micrometres) {
    s += std::string("<polyline fill=\"none\" stroke=\"") + colour +
         "\" stroke-width=\"1.5\" points=\"";
    for (std::size_t i = 0; i < n; ++i) {
      s += num(px(i), 1, "x") + "," + num(py(micrometres(sum.points[i])), 1, what) + " ";
      flush(s, sink);
    }
    s += "\"/>\n";
  };
  polyline("#c0392b", "deviation",
           [](const MillingReportSummary::Point& p) { return p.before_um; });
  polyline("#1e7b34", "residual",
           [](const MillingReportSummary::Point& p) { return p.residual_um; });
  s += "<text x=\"" + num(x0 + 10, 0, "") + "\" y=\"" + num(y0 + 14, 0, "") +
       "\" font-size=\"12\" fill=\"#c0392b\">|deviation| before (coupled force)</text>\n";
  s += "<text x=\"" + num(x0 + 260, 0, "") + "\" y=\"" + num(y0 + 14, 0, "") +
       "\" font-size=\"12\" fill=\"#1e7b34\">|residual| after compensation</text>\n</svg>\n";
}

constexpr double kMarginTop = 5.0;  ///< the margin plot's clip

/// The chatter margin ap_limit/ap of the cutting points along the path (1 = the limit), clipped at
/// 5; points without a bounded limit at the top.
void marginPlot(const MillingReportSummary& sum, std::string& out, const ByteSink& sink) {
  const std::size_t n = sum.points.size();
  const double top = kMarginTop;
  const double w = 760;
  const double h = 160;
  const double x0 = 60;
  const double y0 = 20;
  auto px = [&](std::size_t i) {
    return x0 + (n > 1 ? w * static_cast<double>(i) / static_cast<double>(n - 1) : w / 2);
  };
  auto py = [&](double v) { return y0 + h - h * std::min(v, top) / top; };
  std::string& s = out;
  s += "<svg width=\"860\" height=\"210\" role=\"img\" aria-label=\"chatter margin\">\n";
  s += "<line x1=\"" + num(x0, 0, "") + "\" y1=\"" + num(py(1.0), 1, "") + "\" x2=\"" +
       num(x0 + w, 0, "") + "\" y2=\"" + num(py(1.0), 1, "") +
       "\" stroke=\"#c0392b\" stroke-dasharray=\"4 3\"/>\n";
  s += "<text x=\"4\" y=\"" + num(py(1.0) + 4, 0, "") + "\" font-size=\"11\">1</text>\n";
  s += "<text x=\"4\" y=\"" + num(y0 + 4, 0, "") + "\" font-size=\"11\">5</text>\n";
  s += "<text x=\"" + num(x0 + 10, 0, "") + "\" y=\"" + num(y0 + 14, 0, "") +
       "\" font-size=\"12\">chatter margin ap_limit / ap per cutting point (below 1: "
       "chatter; clipped at 5)</text>\n";
  for (std::size_t i = 0; i < n; ++i) {
    const MillingReportSummary::Point& p = sum.points[i];
    if (!p.checked) continue;
    s += "<circle cx=\"" + num(px(i), 1, "x") + "\" cy=\"" + num(py(p.margin), 1, "margin") +
         "\" r=\"3\" fill=\"" + (p.unstable ? "#c0392b" : "#1e7b34") + "\"/>\n";
    flush(s, sink);
  }
  s += "</svg>\n";
}

/// The chatter margin cell: limit/ap, "—" when not cutting or not checked, "∞" when unbounded.
std::string margin(const MillingCompensationResult& r, std::size_t i) {
  const PathPointCompensation& p = r.point(i);
  if (!p.cutting || !p.stability_checked) return "—";
  if (!p.stability_bounded) return "∞";
  return num(p.ap_limit / millOf(r, i).cut.ap, 2, "margin");
}

std::string pointRow(const MillingCompensationResult& r, std::size_t i) {
  const PathPointCompensation& p = r.point(i);
  const Vec3 b = p.deviation_before * 1e6;
  const Vec3 a = p.residual * 1e6;
  std::string s = "<tr" + std::string(p.ok ? "" : " class=\"bad\"") + "><td>" +
                  std::to_string(i + 1) + "</td><td>" + esc(r.targetName(i)) + "</td><td>" +
                  std::to_string(r.targetLine(i)) + "</td><td>" + (p.cutting ? "yes" : "no") +
                  "</td><td>" + esc(p.cutting_reason) + "</td><td>" +
                  num(p.force.norm(), 1, "force") + "</td>";
  for (int k = 0; k < 3; ++k) s += "<td>" + num(b[k], 2, "deviation") + "</td>";
  s += "<td>" + num(b.norm(), 2, "deviation") + "</td><td>" + num(a.norm(), 4, "residual") +
       "</td><td>" + esc(p.coupling_status) + "</td><td>" + std::to_string(p.coupling_iterations) +
       "</td><td>" + num(p.loop_gain, 3, "loop gain") + "</td><td>" + margin(r, i) + "</td><td>" +
       esc(p.config_text) + "</td><td>" + esc(p.ok ? "compensated" : p.reason) + "</td><td>" +
       num(p.surface_error_before * 1e6, 2, "surface error") + "</td><td>" +
       num(p.surface_error * 1e6, 4, "surface error") + "</td></tr>\n";
  return s;
}

}  // namespace

void addMillingReportPoints(MillingReportSummary& s, const MillingCompensationResult& r) {
  for (std::size_t k = 0; k < r.points_comp.size(); ++k) {
    const PathPointCompensation& p = r.points_comp[k];
    s.before = std::max(s.before, p.deviation_before.norm());
    s.after = std::max(s.after, p.residual.norm());
    s.wall_before = std::max(s.wall_before, std::abs(p.surface_error_before));
    s.wall_after = std::max(s.wall_after, std::abs(p.surface_error));
    s.cutting += p.cutting ? 1 : 0;
    MillingReportSummary::Point q;
    q.before_um = p.deviation_before.norm() * 1e6;
    q.residual_um = p.residual.norm() * 1e6;
    q.checked = p.cutting && p.stability_checked;
    if (q.checked) {
      const double ap = millOf(r, r.first + k).cut.ap;
      q.margin = p.stability_bounded ? p.ap_limit / ap : kMarginTop;
      q.unstable = p.unstable(ap);
    }
    s.points.push_back(q);
  }
}

void writeMillingReportRows(const MillingCompensationResult& r, const ByteSink& sink) {
  std::string s;
  for (std::size_t i = r.first; i < r.first + r.points_comp.size(); ++i) {
    s += pointRow(r, i);
    flush(s, sink);
  }
  flush(s, sink, true);
}

void writeMillingReport(const MillingReportSummary& sum, const MillingCompensationResult& r,
                        const std::string& program_path,
                        const std::function<void(const ByteSink&)>& rows, const ByteSink& sink) {
  const PredictionContext& c = r.context;
  std::string s =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>roprec milling "
      "compensation — " +
      esc(program_path) +
      "</title>\n<style>body{font-family:sans-serif;margin:1.5em}"
      "table{border-collapse:collapse;font-size:12px}td,th{border:1px solid #ccc;padding:2px 6px;"
      "text-align:right}td:nth-child(2),td:nth-child(5),td:nth-child(13),td:nth-child(17){text-"
      "align:left}"
      "th{background:#eee}tr.bad td{background:#fde2e2}</style></head><body>\n";
  s += "<h1>Milling path compensation</h1>\n<p>program <b>" + esc(program_path) + "</b>, cell <b>" +
       esc(c.cell.name) + "</b>, robot <b>" + esc(c.robot.card.name) +
       "</b><br>process: " + esc(c.process_description) + "</p>\n";
  s += "<p>" + std::to_string(sum.points.size()) + " linear path points, " +
       std::to_string(sum.cutting) + " cutting; deviation before (coupled force) max <b>" +
       num(sum.before * 1e6, 2, "deviation") + " µm</b>; predicted residual after max <b>" +
       num(sum.after * 1e6, 4, "residual") + " µm</b>; surface error normal to the wall max <b>" +
       num(sum.wall_before * 1e6, 2, "surface error") + " µm</b> before, <b>" +
       num(sum.wall_after * 1e6, 4, "surface error") + " µm</b> compensated.</p>\n";
  for (const auto& n : c.job.notes) s += "<p class=\"note\">note: " + esc(n) + "</p>\n";
  pathPlot(sum, s, sink);
  marginPlot(sum, s, sink);
  s += "<table>\n<tr><th>point</th><th>target</th><th>line</th><th>cuts</th><th>why</th>"
       "<th>|F| [N]</th><th>δx before [µm]</th><th>δy before [µm]</th><th>δz before [µm]</th>"
       "<th>|δ| before [µm]</th><th>|residual| after [µm]</th><th>coupling</th><th>iterations</th>"
       "<th>loop gain</th><th>chatter margin</th><th>configuration</th><th>status</th>"
       "<th>wall error before [µm]</th><th>wall error after [µm]</th></tr>\n";
  flush(s, sink, true);
  rows(sink);
  s += "</table>\n<p>Deviations in the robot base frame; the force in the milling frame; the wall "
       "error is the deviation normal to the wall, + into the material. "
       "roprec " +
       std::string(version()) + "</p>\n</body></html>\n";
  flush(s, sink, true);
}

void writeMillingCompensationReport(const MillingCompensationResult& r,
                                    const std::string& program_path, const ByteSink& sink) {
  MillingReportSummary sum;
  addMillingReportPoints(sum, r);
  writeMillingReport(
      sum, r, program_path, [&r](const ByteSink& out) { writeMillingReportRows(r, out); }, sink);
}

std::string millingCompensationReport(const MillingCompensationResult& r,
                                      const std::string& program_path) {
  std::string s;
  writeMillingCompensationReport(r, program_path, [&s](std::string_view v) { s += v; });
  return s;
}

}  // namespace roprec::api
