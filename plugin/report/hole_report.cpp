/// \file hole_report.cpp
/// The self-contained HTML report of predict and compensate (see hole_report.hpp): the document,
/// its header with the plain-language summary, the verdicts and capability, and the footer. The
/// maps, the budget and the per-hole table have a file each (hole_sections.hpp).
///
/// Deterministic bytes: numbers through num() (locale-independent, fixed decimals, "-0" printed
/// as "0"), holes and budget terms visited in input order, no time stamp. Every string that comes
/// from the inputs is escaped by the element builder (html.hpp).

#include <algorithm>
#include <array>
#include <cctype>
#include <stdexcept>

#include "compensator/support/str_cat.hpp"
#include "plugin/report/hole_sections.hpp"
#include "plugin/report/palette.hpp"

namespace roprec::report {

namespace {

/// The view of one hole: its position and axis in the part frame, its branch change.
HoleView viewOf(const Pose& T_part_W, const Vec3& position, const Vec3& axis,
                const api::MapFacts& p, int& prev_branch) {
  HoleView h;
  h.f = &p;
  h.pos_mm = (T_part_W * position) * 1e3;
  const Vec3 a = T_part_W.linear() * axis;
  h.axis = a.norm() > 0 ? Vec3(a.normalized()) : Vec3(Vec3::UnitZ());
  h.ok = p.status == HoleStatus::kOk;
  if (h.ok) {
    h.config_change = prev_branch >= 0 && p.branch != prev_branch;
    h.prev_branch = prev_branch;
    prev_branch = p.branch;
  }
  return h;
}

}  // namespace

void appendPredictedViews(std::vector<HoleView>& out, std::span<const api::PredictedHole> holes,
                          const Pose& T_part_W, int& prev_branch) {
  for (const api::PredictedHole& ph : holes) {
    out.push_back(viewOf(T_part_W, ph.position, ph.axis, ph.prediction, prev_branch));
    out.back().p = &ph.prediction;
    out.back().split = &ph.split;
  }
}

void appendMappedViews(std::vector<HoleView>& out, std::span<const api::MappedHole> holes,
                       const Pose& T_part_W, int& prev_branch) {
  for (const api::MappedHole& mh : holes)
    out.push_back(viewOf(T_part_W, mh.position, mh.axis, mh.facts, prev_branch));
}

HoleViews holeViews(const ReportInput& in) {
  HoleViews out;
  int prev_branch = -1;
  const Pose T_part_W = in.T_W_part.inverse();
  out.views.reserve(in.holes.size() + in.predicted.size() + in.mapped.size());
  appendPredictedViews(out.views, in.predicted, T_part_W, prev_branch);
  appendMappedViews(out.views, in.mapped, T_part_W, prev_branch);
  // a ReportHole's predictions converted (stable addresses: reserved once)
  out.own.reserve(2 * in.holes.size());
  for (const ReportHole& rh : in.holes) {
    if (rh.prediction == nullptr)
      throw std::invalid_argument("renderReport: a hole without a prediction");
    const api::ReportPrediction& p = out.own.emplace_back(api::reportPrediction(*rh.prediction));
    HoleView h =
        viewOf(T_part_W, rh.T_W_tcp.translation(), rh.T_W_tcp.linear().col(2), p, prev_branch);
    h.p = &p;
    h.rh = &rh;
    h.split = &rh.split;
    if (rh.after != nullptr) h.after = &out.own.emplace_back(api::reportPrediction(*rh.after));
    out.views.push_back(h);
  }
  return out;
}

Verdict finalVerdict(const HoleView& h) {
  return h.after != nullptr ? h.after->verdict : h.f->verdict;
}

void addBranch(std::vector<std::pair<int, std::string>>& branches, int branch,
               const std::string& config) {
  const auto seen = [&](const auto& e) { return e.first == branch; };
  if (std::none_of(branches.begin(), branches.end(), seen)) branches.emplace_back(branch, config);
}

bool passes(const HoleView& h) { return finalVerdict(h) == Verdict::kConforms; }

std::string plural(long n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

double pct(double part, double whole) { return whole > 0 ? 100.0 * part / whole : 0.0; }

namespace {

// ------------------------------------------------------------------ header

/// One entry of the header's definition list; `value` is markup (an em dash when empty).
void metaItem(Html& h, const char* key, const std::string& value, bool wide = false) {
  if (wide) {
    h.open("div", {{"class", "wide"}});
  } else {
    h.open("div");
  }
  h.element("dt", {}, key).markupElement("dd", {}, value.empty() ? kDash : value).close("div");
}

/// Robot, cell, program, process, how frames and tool were resolved, the card's estimates, the
/// default tolerance and the uncertainty method with its sources.
void renderMeta(Html& h, const ReportInput& in) {
  h.open("dl", {{"class", "meta"}});
  metaItem(h, "Robot", esc(in.robot));
  metaItem(h, "Cell", esc(in.cell));
  metaItem(h, "Program", esc(in.program));
  metaItem(h, "Process", esc(in.process));
  for (const std::string& res : in.resolutions)
    metaItem(h, "Frame/tool resolution", esc(res), true);
  if (!in.card_estimates.empty()) {
    std::string e;
    for (const std::string& x : in.card_estimates) strAppend(e, e.empty() ? "" : "<br>", esc(x));
    metaItem(h, "Robot card estimates", "<span class=\"src\">" + e + "</span>", true);
  }
  metaItem(h, "Default position tolerance", "\u2300 " + num(in.default_tolerance_mm, 3) + " mm");
  metaItem(h, "Uncertainty method", esc(in.uncertainty_method));
  if (!in.uncertainty_source.empty()) {
    metaItem(h, "Uncertainty inputs and sources",
             "<span class=\"src\">" + esc(in.uncertainty_source) + "</span>", true);
  }
  h.close("dl");
}

/// "3 holes are unreachable, 1 hole is at a singularity and …" (empty when every hole was
/// predicted and is capable).
std::string problemSentence(const CapabilitySummary& s) {
  std::vector<std::string> rest;
  if (s.not_capable) {
    rest.push_back(plural(s.not_capable, "hole is", "holes are") +
                   " not capable: even after compensation the scatter alone exceeds the tolerance");
  }
  if (s.unreachable) rest.push_back(plural(s.unreachable, "hole is", "holes are") + " unreachable");
  if (s.singular) rest.push_back(plural(s.singular, "hole is", "holes are") + " at a singularity");
  if (s.not_converged)
    rest.push_back(plural(s.not_converged, "hole", "holes") + " did not converge");
  std::string sentence;
  for (size_t i = 0; i < rest.size(); ++i) {
    std::string t = rest[i];
    if (i == 0) t[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(t[0])));
    sentence += t + (i + 1 == rest.size() ? "." : i + 2 == rest.size() ? " and " : ", ");
  }
  return sentence;
}

/// What the robot can take, what stays on the machining center, how often the arm reconfigures.
void renderSummary(Html& h, const CapabilitySummary& s, const std::vector<HoleView>& hv) {
  const long changes =
      std::count_if(hv.begin(), hv.end(), [](const HoleView& v) { return v.config_change; });
  const std::string problems = problemSentence(s);
  h.open("p", {{"class", "summary"}})
      .markup(strCat(
          "<strong>", std::to_string(s.robot_can_take), " of ", plural(s.holes, "hole", "holes"),
          " can be taken by the robot</strong> (", std::to_string(s.conforms),
          " conform as programmed, ", std::to_string(s.conforms_after_compensation),
          " after compensation), representing <strong>", num(s.mc_time_taken, 1),
          " s</strong> of machining-center time (", num(pct(s.mc_time_taken, s.mc_time_total), 1),
          " % of the ", num(s.mc_time_total, 1), " s these holes take on the machining center)."))
      .markup(problems.empty() ? "" : " " + problems)
      .markup(" The robot changes its arm/wrist configuration " + plural(changes, "time", "times") +
              " along the program.")
      .close("p");
}

void kpi(Html& h, const std::string& big, const char* label, const char* colour) {
  h.open("div", {{"class", "kpi"}, Attr::markup("style", std::string("--c:") + colour)})
      .markupElement("b", {}, big)
      .markupElement("span", {}, label)
      .close("div");
}

void renderKpis(Html& h, const CapabilitySummary& s) {
  const int m = s.holes;
  h.open("div", {{"class", "kpis"}});
  kpi(h, std::to_string(m), "holes in the program", "#8c959f");
  kpi(h,
      std::to_string(s.robot_can_take) + " <small>(" + num(pct(s.robot_can_take, m), 0) +
          " %)</small>",
      "robot can take", "#0b5cad");
  kpi(h, std::to_string(s.conforms), "conform", styleOf(Verdict::kConforms).bar);
  kpi(h, std::to_string(s.conforms_after_compensation), "conform after compensation",
      styleOf(Verdict::kConformsAfterCompensation).bar);
  kpi(h, std::to_string(s.not_capable + s.unreachable + s.singular + s.not_converged),
      "stay on the machining center", styleOf(Verdict::kNotCapable).bar);
  kpi(h, num(s.mc_time_taken, 1) + " s", "machining-center time the robot takes", "#0b5cad");
  h.close("div");
}

void renderHeader(Html& h, const ReportInput& in, const std::vector<HoleView>& hv) {
  h.open("header").element("h1", {}, in.title);
  h.open("p", {{"class", "sub"}})
      .markup(
          "Per-hole deviation, uncertainty and ISO 14253-1 tolerance verdict of a robotic "
          "drilling program")
      .markup(in.compensation ? ", before and after compensation" : "")
      .markup(".")
      .close("p");
  renderMeta(h, in);
  renderSummary(h, in.summary, hv);
  renderKpis(h, in.summary);
  h.close("header");
}

// ------------------------------------------------------------------ verdicts and capability

/// One bar per verdict: label, track, bar (at least 2 px when the count is not 0), count and %.
void renderVerdictBars(Html& h, const CapabilitySummary& s) {
  const std::array<int, 6> counts{s.conforms,    s.conforms_after_compensation,
                                  s.not_capable, s.unreachable,
                                  s.singular,    s.not_converged};
  const int cmax = std::max(1, *std::max_element(counts.begin(), counts.end()));
  constexpr double kRow = 30, kLabel = 200, kBar = 330;
  h.open("svg", {{"xmlns", "http://www.w3.org/2000/svg"},
                 Attr::markup("viewBox", "0 0 640 " + num(kRow * 6 + 8, 0)),
                 {"role", "img"},
                 {"aria-label", "verdict counts"}});
  for (size_t i = 0; i < kVerdicts.size(); ++i) {
    const double y = 4 + kRow * static_cast<double>(i);
    const double w = kBar * counts[i] / cmax;
    h.element("text",
              {{"x", fixed(kLabel - 10, 0)},
               {"y", fixed(y + 19, 1)},
               {"text-anchor", "end"},
               {"class", "axis"}},
              kVerdicts[i].label);
    h.leaf("rect", {{"x", fixed(kLabel, 0)},
                    {"y", fixed(y + 5, 1)},
                    {"width", fixed(kBar, 1)},
                    {"height", "20"},
                    {"rx", "3"},
                    {"fill", "#f0f3f6"}});
    if (counts[i] > 0) {
      h.leaf("rect", {{"x", fixed(kLabel, 0)},
                      {"y", fixed(y + 5, 1)},
                      {"width", fixed(std::max(w, 2.0), 1)},
                      {"height", "20"},
                      {"rx", "3"},
                      {"fill", kVerdicts[i].bar}});
    }
    h.open("text",
           {{"x", fixed(kLabel + kBar + 10, 0)}, {"y", fixed(y + 19, 1)}, {"class", "axis"}})
        .element("tspan", {{"font-weight", "600"}}, std::to_string(counts[i]))
        .markup(" (" + num(pct(counts[i], s.holes), 1) + " %)")
        .close("text");
  }
  h.close("svg");
}

constexpr const char* kVerdictKey =
    "t = position tolerance \u2300, e\u22a5 = predicted position error \u22a5 the hole axis, U = "
    "U<sub>95</sub>, the 95 % radius of the anisotropic in-plane distribution (\u2265 "
    "U<sub>work</sub>). <b>conforms</b>: e\u22a5 + U \u2264 t/2; <b>conforms after "
    "compensation</b>: U \u2264 t/2 &lt; e\u22a5 + U (the systematic part is too large but can be "
    "compensated); <b>not capable</b>: U &gt; t/2 (the scatter alone is too large).";

/// A big number and a meter under it.
void meter(Html& h, const std::string& big, double percent, const char* extra_style) {
  h.markupElement("div", {{"class", "big"}}, big)
      .open("div", {{"class", "meter"}})
      .markupElement("i", {Attr::markup("style", "width:" + num(percent, 2) + "%" + extra_style)},
                     "")
      .close("div");
}

void renderCapability(Html& h, const CapabilitySummary& s) {
  const double share_taken = pct(s.mc_time_taken, s.mc_time_total);
  h.open("div", {{"class", "card"}})
      .markup("<h3>Capability \u2014 what the robot can take from the machining center</h3>");
  meter(h,
        std::to_string(s.robot_can_take) + " <small>of " + plural(s.holes, "hole", "holes") + " (" +
            num(pct(s.robot_can_take, s.holes), 1) + " %)</small>",
        pct(s.robot_can_take, s.holes), "");
  meter(h,
        num(s.mc_time_taken, 1) + " s <small>of " + num(s.mc_time_total, 1) +
            " s machining-center time (" + num(share_taken, 1) + " %)</small>",
        share_taken, ";background:#0b5cad");
  h.markupElement(
      "p", {},
      strCat("Drilling these holes on the robot instead of the machining center frees <strong>",
             num(s.mc_time_taken, 1), " s</strong> of machining-center time per part (",
             num(share_taken, 1), " % of its drilling time); ",
             plural(s.holes - s.robot_can_take, "hole", "holes"), " (",
             num(s.mc_time_total - s.mc_time_taken, 1), " s) stay on the machining center."));
  h.markupElement("p", {{"class", "note"}},
                  strCat("Machining-center time per hole = depth / feed rate + positioning and "
                         "approach. Process share of the total uncertainty (variance share): mean ",
                         num(100 * s.mean_process_share, 1), " %, max ",
                         num(100 * s.max_process_share, 1), " %."));
  h.close("div");
}

void renderVerdicts(Html& h, const ReportInput& in) {
  h.open("section", {{"id", "verdicts"}})
      .element("h2", {}, "Verdicts and capability")
      .open("div", {{"class", "two"}})
      .open("div", {{"class", "card vbars"}})
      .element("h3", {}, "Verdict per hole (ISO 14253-1 guard band)");
  renderVerdictBars(h, in.summary);
  h.markupElement("p", {{"class", "note"}}, kVerdictKey).close("div");
  renderCapability(h, in.summary);
  h.close("div").close("section");
}

// ------------------------------------------------------------------ footer

constexpr const char* kConventions =
    "<p>Conventions: SI inside; positions in mm and joints in degrees; deviations and "
    "uncertainties in \u00b5m, tilts in \u00b5rad; the robot base frame (URDF root link) for all "
    "vectors; TCP = flange \u00d7 tool frame, tool +z = drilling direction. \u03b4work = "
    "\u03b4robot + \u03b4mach; the position error e\u22a5 is the part of \u03b4work \u22a5 the "
    "hole "
    "axis. Position tolerance \u2300t per ISO 1101 (the axis must lie in a cylinder of diameter "
    "t, i.e. e\u22a5 \u2264 t/2).</p>"
    "<p>Decision rule ISO 14253-1 (guard band g = U): conformance is proven only when e\u22a5 + "
    "U<sub>work</sub> \u2264 t/2. U<sub>work</sub> is the expanded 2-D radial uncertainty with "
    "the Rayleigh coverage factor (95 %). Ferreras-Higuero et al., Robotics and "
    "Computer-Integrated Manufacturing (2020), give the method this report follows.</p>";

void renderFooter(Html& h, const ReportInput& in) {
  h.open("footer")
      .open("p")
      .markup("Generated by ")
      .text(in.generator)
      .markup(
          ". Self-contained document: no network resources; one inline script sorts and "
          "filters the table.")
      .close("p")
      .markup(kConventions)
      .close("footer");
}

void renderHead(Html& h, const ReportInput& in) {
  h.markup("<!DOCTYPE html>\n")
      .open("html", {{"lang", "en"}})
      .open("head")
      .open("meta", {{"charset", "utf-8"}})
      .open("meta", {{"name", "viewport"}, {"content", "width=device-width, initial-scale=1"}})
      .open("meta", {{"name", "generator"}, {"content", in.generator}})
      .element("title", {}, in.title)
      .markupElement("style", {}, kReportCss)
      .close("head")
      .open("body")
      .open("main")
      .markup("\n");
}

}  // namespace
}  // namespace roprec::report

namespace roprec::api {

const char* reportTableScript() { return report::kTableScript; }

ReportPrediction reportPrediction(const HolePrediction& p) {
  ReportPrediction r;
  reportPrediction(p, r);
  return r;
}

void reportPrediction(const HolePrediction& p, ReportPrediction& r) {
  r.id = p.id;
  r.status = p.status;
  r.verdict = p.verdict;
  r.reason = p.reason;
  r.config = p.config;
  r.branch = p.branch;
  r.joints = p.joints;
  r.d_robot = p.d_robot;
  r.d_mach = p.d_mach;
  r.d_work = p.d_work;
  r.position_error = p.position_error;
  r.axis_tilt = p.axis_tilt;
  r.budget = p.budget;
  r.u_robot = p.u_robot;
  r.u_mach = p.u_mach;
  r.u_work = p.u_work;
  r.k = p.k;
  r.U_robot = p.U_robot;
  r.U_mach = p.U_mach;
  r.U_work = p.U_work;
  r.U_work_exact = p.U_work_exact;
  r.process_share = p.process_share;
  r.tolerance = p.tolerance;
  r.mc_time = p.mc_time;
  r.diameter = p.diameter;
}

void StreamedTotals::add(std::span<const PredictedHole> holes) {
  for (const PredictedHole& h : holes) {
    const ReportPrediction& p = h.prediction;
    split = split || h.split.has_value();
    not_conforming += p.verdict == Verdict::kConforms ? 0 : 1;
    if (p.status != HoleStatus::kOk) continue;
    for (const BudgetTerm& b : p.budget) {  // as report::addBudgetNames
      const std::string_view n = b.name ? b.name : "";
      if (std::find(terms.begin(), terms.end(), n) == terms.end()) terms.emplace_back(n);
    }
    report::addBranch(branches, p.branch, p.config);
    budget.add(p);
  }
}

namespace {

/// The document into `o` (and, with a sink, on to it).
void renderDocument(const ReportInput& in, std::string& o, const report::Html::Sink* sink) {
  using namespace report;
  if (int(!in.holes.empty()) + int(!in.predicted.empty()) + int(!in.mapped.empty()) > 1)
    throw std::invalid_argument("renderReport: holes and predicted holes at once");
  if (!in.mapped.empty() && in.mapped.size() <= api::kReportAggregateAbove)
    throw std::invalid_argument("renderReport: mapped holes of a small job");
  const HoleViews views = holeViews(in);
  const std::vector<HoleView>& hv = views.views;
  if (sink == nullptr) o.reserve(65536 + 640 * hv.size());  // about 0.54 KB a hole
  Html h(o, sink);
  renderHead(h, in);
  renderHeader(h, in, hv);
  h.markup("\n");
  renderMaps(h, in, hv);
  h.markup("\n");
  renderVerdicts(h, in);
  h.markup("\n");
  renderBudget(h, in.mapped.empty() ? budgetSums(hv) : in.totals.budget);
  h.markup("\n");
  renderTable(h, in, hv);
  h.markup("\n");
  renderFooter(h, in);
  h.markup("\n</main></body></html>\n");
  h.flush();
}

}  // namespace

std::string renderReport(const ReportInput& in) {
  std::string o;
  renderDocument(in, o, nullptr);
  return o;
}

void renderReport(const ReportInput& in, const std::function<void(std::string_view)>& sink) {
  std::string o;
  o.reserve(1 << 20);
  renderDocument(in, o, &sink);
}

}  // namespace roprec::api
