/// \file hole_budget.cpp
/// The hole report's uncertainty budget (hole_sections.hpp): every budget term's mean and
/// maximum standard uncertainty and mean variance share over the predicted holes, as a stacked
/// bar and a table, then the combined and expanded uncertainties and the coverage factor.

#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>
#include <utility>

#include "compensator/support/str_cat.hpp"
#include "plugin/report/hole_sections.hpp"

namespace roprec::report {
namespace {

struct TermInfo {
  const char* name;
  const char* label;
  const char* basis;
};

constexpr std::array<TermInfo, 7> kTerms{{
    {"robot_repeatability", "Robot repeatability", "ISO 9283 RP, normal: \u03c3 = RP / 3.616"},
    {"robot_absolute_accuracy", "Robot absolute accuracy",
     "uncalibrated: AP / 2.7955 (card <accuracy>); calibrated: the calibration \u03c3 through the "
     "FK Jacobian; the controller option: its AP; + the registration \u03c3"},
    {"robot_deflection_model", "Deflection model",
     "joint stiffness and servo gain uncertainty propagated through the deflection"},
    {"robot_deflection_process_force", "Deflection under process-force scatter",
     "force scale rectangular, a/\u221a3, through the robot compliance"},
    {"mach_axis", "Drill axis deviation", "\u03b4axis = La tan \u03b8a, rectangular a/\u221a3"},
    {"mach_runout", "Spindle runout", "\u03b4\u03c1, arcsine a/\u221a2"},
    {"mach_tool_deflection", "Tool deflection",
     "\u03b4deftool under the rotating force Fr, arcsine a/\u221a2"},
}};

const TermInfo* termInfo(const std::string& name) {
  const auto it =
      std::find_if(kTerms.begin(), kTerms.end(), [&](const TermInfo& t) { return name == t.name; });
  return it != kTerms.end() ? &*it : nullptr;
}

constexpr std::array<const char*, 4> kRobotColours{"#1f4e79", "#3a7dbf", "#8fbbe6", "#c9def5"};
constexpr std::array<const char*, 5> kProcessColours{"#b45309", "#e8892b", "#f5b971", "#fbd9a6",
                                                     "#fdebd0"};

/// A budget term as the section shows it: its sums and its colour.
struct TermStats : api::BudgetSums::Term {
  std::string colour;  ///< robot terms blue, process terms orange, in order of appearance
  bool light{false};   ///< a light colour: dark text on it
};

using Sum = api::BudgetSums::Sum;

/// The budget over the predicted holes, its terms coloured.
struct BudgetStats {
  int n_ok{0};
  double k{0};  ///< coverage factor of the first predicted hole
  std::vector<TermStats> terms;
  std::array<Sum, 6> combined{};  ///< u_robot u_mach u_work U_robot U_mach U_work
  Sum process_share;
};

void colourTerms(std::vector<TermStats>& terms) {
  size_t nr = 0, np = 0;
  for (TermStats& t : terms) {
    size_t& seen = t.process ? np : nr;
    t.colour = t.process ? kProcessColours[seen % kProcessColours.size()]
                         : kRobotColours[seen % kRobotColours.size()];
    t.light = seen >= 2;
    ++seen;
  }
}

BudgetStats budgetStats(const api::BudgetSums& sums) {
  BudgetStats b;
  b.n_ok = sums.n_ok;
  b.k = sums.k;
  b.combined = sums.combined;
  b.process_share = sums.process_share;
  for (const api::BudgetSums::Term& t : sums.terms) {
    TermStats s;
    static_cast<api::BudgetSums::Term&>(s) = t;
    b.terms.push_back(std::move(s));
  }
  colourTerms(b.terms);
  return b;
}

}  // namespace

api::BudgetSums budgetSums(const std::vector<HoleView>& hv) {
  api::BudgetSums b;
  for (const HoleView& h : hv) {
    if (h.ok) b.add(*h.p);
  }
  return b;
}

namespace {

/// The term's label (markup): the known label, else its escaped name.
std::string labelOf(const TermStats& t) {
  const TermInfo* info = termInfo(t.name);
  return info ? std::string(info->label) : esc(t.name);
}

std::string basisOf(const TermStats& t) {
  const TermInfo* info = termInfo(t.name);
  return info ? std::string(info->basis) : esc(t.name);
}

/// Mean variance share of a term, %.
double sharePct(const BudgetStats& b, const TermStats& t) { return 100.0 * t.sum_share / b.n_ok; }

void renderStack(Html& h, const BudgetStats& b) {
  h.open("div", {{"class", "stack"}});
  for (const TermStats& t : b.terms) {
    const double sh = sharePct(b, t);
    const std::string label = labelOf(t);
    std::vector<Attr> a;
    if (t.light) a.emplace_back("class", "lt");
    a.push_back(Attr::markup("style", "width:" + num(sh, 3) + "%;background:" + t.colour));
    a.push_back(Attr::markup("title", label + ": " + num(sh, 1) + " %"));
    h.open("span", a).markup(sh >= 7.0 ? label + " " + num(sh, 0) + " %" : "").close("span");
  }
  h.close("div");
}

constexpr const char* kBudgetHead =
    "<thead><tr><th class=\"l\">Term</th><th class=\"l\">Basis</th><th>Part of</th><th>mean u "
    "[\u00b5m]</th><th>max u [\u00b5m]</th><th class=\"l\">mean variance share</th></tr></thead>";

void renderTermRow(Html& h, const BudgetStats& b, const TermStats& t) {
  const double sh = sharePct(b, t);
  h.open("tr")
      .open("td", {{"class", "l"}})
      .markupElement("span", {{"class", "sw"}, Attr::markup("style", "background:" + t.colour)}, "")
      .markup(labelOf(t))
      .close("td")
      .markupElement("td", {{"class", "l note"}}, basisOf(t))
      .element("td", {}, t.process ? "process" : "robot")
      .element("td", {}, num(t.sum_u / t.n * 1e6, 2))
      .element("td", {}, num(t.max_u * 1e6, 2))
      .open("td", {{"class", "l"}})
      .markup(num(sh, 1) + " %")
      .markupElement(
          "span",
          {{"class", "share"},
           Attr::markup("style", "width:" + num(1.6 * sh, 1) + "px;background:" + t.colour)},
          "")
      .close("td")
      .close("tr");
}

/// The combined (per axis) and expanded (radial) uncertainties, mean and max.
void renderCombinedRows(Html& h, const BudgetStats& b) {
  static constexpr std::array<const char*, 6> kNames{"u<sub>robot</sub>", "u<sub>mach</sub>",
                                                     "u<sub>work</sub>",  "U<sub>robot</sub>",
                                                     "U<sub>mach</sub>",  "U<sub>work</sub>"};
  for (size_t i = 0; i < 6; ++i) {
    const Sum& c = b.combined[i];
    h.open("tr", {{"class", "sum"}})
        .markupElement("td", {{"class", "l"}}, kNames[i])
        .markupElement("td", {{"class", "l note"}},
                       i < 3 ? "combined standard, per axis" : "expanded radial, k \u00b7 u")
        .element("td", {}, "")
        .element("td", {{"class", "n"}}, num(c.sum / b.n_ok * 1e6, 2))
        .element("td", {{"class", "n"}}, num(c.max * 1e6, 2))
        .element("td", {{"class", "l"}}, i == 2 ? "100 %" : "")
        .close("tr");
  }
}

constexpr const char* kBudgetNote =
    "Per-axis standard uncertainties in the plane \u22a5 the hole axis, independent terms combined "
    "by root-sum-square (GUM, JCGM 100:2008): u<sub>robot</sub>\u00b2 = "
    "u<sub>repeatability</sub>\u00b2 + u<sub>deflection</sub>\u00b2, u<sub>mach</sub>\u00b2 = "
    "\u03a3 process terms, u<sub>work</sub>\u00b2 = u<sub>robot</sub>\u00b2 + "
    "u<sub>mach</sub>\u00b2. Statistics over the ";

constexpr const char* kCoverageNote =
    "</strong>: the position error is a 2-D radius; for an isotropic normal scatter with u per "
    "axis the radius is Rayleigh-distributed and P(r \u2264 k u) = 95 % needs k = \u221a(\u22122 "
    "ln 0.05) = 2.448 (k = 2 would cover only 86 % of the radius; docs/process.md \u00a75.1). "
    "U<sub>work</sub> = \u221a(U<sub>robot</sub>\u00b2 + U<sub>mach</sub>\u00b2) = k \u00b7 "
    "u<sub>work</sub> is the isotropic equivalent; the verdict uses U<sub>95</sub>, the exact "
    "95 % radius of the anisotropic in-plane distribution (\u2265 U<sub>work</sub>).";

/// The coverage factor and the process share of the total uncertainty.
void renderCoverage(Html& h, const BudgetStats& b) {
  const double mean_share = b.process_share.sum / b.n_ok;
  h.markupElement("p", {}, "Coverage factor <strong>k = " + num(b.k, 3) + kCoverageNote);
  h.markupElement(
      "p", {},
      strCat("Process share of the total uncertainty (variance share of the process terms in "
             "u<sub>work</sub>\u00b2): <strong>mean ",
             num(100.0 * mean_share, 1), " %</strong>, max ", num(100.0 * b.process_share.max, 1),
             " % (as a linear share of u<sub>work</sub>: mean ",
             num(100.0 * std::sqrt(mean_share), 1), " %)."));
}

}  // namespace

void renderBudget(Html& h, const api::BudgetSums& sums) {
  const BudgetStats b = budgetStats(sums);
  h.open("section", {{"id", "budget"}}).element("h2", {}, "Uncertainty budget");
  if (b.n_ok == 0) {
    h.element("p", {}, "No hole could be predicted, so there is no budget to show.")
        .close("section");
    return;
  }
  h.markupElement("p", {{"class", "note"}},
                  kBudgetNote + plural(b.n_ok, "predicted hole", "predicted holes") + ".");
  renderStack(h, b);
  h.open("table", {{"class", "budget"}}).markup(kBudgetHead).open("tbody");
  for (const TermStats& t : b.terms) renderTermRow(h, b, t);
  renderCombinedRows(h, b);
  h.close("tbody").close("table");
  renderCoverage(h, b);
  h.close("section");
}

}  // namespace roprec::report

namespace roprec::api {

void BudgetSums::add(const ReportPrediction& p) {
  ++n_ok;
  if (k == 0) k = p.k;
  const double uw2 = p.u_work * p.u_work;
  for (const BudgetTerm& t : p.budget) {
    const std::string_view name = t.name ? t.name : "";
    auto it =
        std::find_if(terms.begin(), terms.end(), [&](const Term& s) { return s.name == name; });
    if (it == terms.end()) {
      Term fresh;
      fresh.name = std::string(name);
      fresh.process = t.process;
      terms.push_back(std::move(fresh));
      it = terms.end() - 1;
    }
    it->sum_u += t.u;
    it->max_u = std::max(it->max_u, t.u);
    it->sum_share += uw2 > 0 ? t.u * t.u / uw2 : 0.0;
    ++it->n;
  }
  const std::array<double, 6> v{p.u_robot, p.u_mach, p.u_work, p.U_robot, p.U_mach, p.U_work};
  for (size_t i = 0; i < 6; ++i) combined[i].add(v[i]);
  process_share.add(p.process_share);
}

}  // namespace roprec::api
