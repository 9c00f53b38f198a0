/// \file hole_table.cpp
/// The hole report's per-hole table (hole_sections.hpp): one row per hole in program order —
/// verdict, e⊥, U₉₅, δrobot with its split, δmach, every budget term, the posture (flags, IK
/// branch, joints as the controller shows them), the machining-center time and, after
/// compensation, the offset applied and the verdict after. Large jobs keep their rows in a script
/// array and show a page at a time (docs/reports.md §4).

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "compensator/precision/parallel.hpp"
#include "compensator/robot/robot_card.hpp"
#include "compensator/support/str_cat.hpp"
#include "plugin/report/hole_sections.hpp"
#include "plugin/report/palette.hpp"

namespace roprec::report {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr size_t kTableRowsPerPage = 200;  ///< rows a page of a large job's table
constexpr size_t kRowsPerRound = 2048;     ///< rows of a large table rendered at a time

struct Column {
  std::string head;  ///< markup
  std::string unit;  ///< shown under the head
  bool text{false};  ///< sorts as text, left-aligned
};

/// What every row reads: the report, the budget terms' order and which optional columns exist.
struct TableLayout {
  const ReportInput& in;
  std::vector<std::string> terms;  ///< budget terms, first-seen order over the predicted holes
  bool has_split{false};           ///< the δrobot split columns
  bool large{false};               ///< rows in a script array, a page at a time
};

const char* shortTerm(const std::string& name) {
  static constexpr std::array<std::array<const char*, 2>, 7> kShort{{
      {"robot_repeatability", "u repeat."},
      {"robot_absolute_accuracy", "u abs. acc."},
      {"robot_deflection_model", "u defl. model"},
      {"robot_deflection_process_force", "u defl. force"},
      {"mach_axis", "u axis"},
      {"mach_runout", "u runout"},
      {"mach_tool_deflection", "u tool defl."},
  }};
  for (const auto& s : kShort) {
    if (name == s[0]) return s[1];
  }
  return nullptr;
}

/// Where a row takes the columns the table may gain (RenderedRows::marks), offsets into the row:
/// a predicted hole's the place of the split cells and the place after its last budget term, or
/// another's colspan digits and their count.
struct RowMarks {
  size_t split{0}, terms{0};
  bool colspan{false};
};

// ------------------------------------------------------------------ head

std::vector<Column> columns(const TableLayout& t) {
  std::vector<Column> cols{{"#", "", false},
                           {"Hole", "", true},
                           {t.in.compensation ? "Verdict before" : "Verdict", "", true},
                           {"e\u22a5", "\u00b5m"},
                           {"U<sub>95</sub>", "\u00b5m"},
                           {"e\u22a5 + U", "\u00b5m"},
                           {"t/2", "\u00b5m"},
                           {"|\u03b4robot|", "\u00b5m"}};
  if (t.has_split) {
    for (const char* part : {"gravity", "tool weight", "process", "controller"})
      cols.push_back({std::string("\u2192 ") + part, "\u00b5m"});
  }
  for (const char* c : {"\u03b4robot x", "\u03b4robot y", "\u03b4robot z", "\u03b4mach x",
                        "\u03b4mach y", "\u03b4mach z"})
    cols.push_back({c, "\u00b5m"});
  cols.push_back({"tilt", "\u00b5rad"});
  for (const std::string& term : t.terms) {
    const char* sh = shortTerm(term);
    cols.push_back({sh ? std::string(sh) : esc(term), "\u00b5m"});
  }
  cols.push_back({"U<sub>robot</sub>", "\u00b5m"});
  cols.push_back({"U<sub>mach</sub>", "\u00b5m"});
  cols.push_back({"\u2300", "mm"});
  cols.push_back({"Config", "", true});
  cols.push_back({"Br.", ""});
  const std::string jconv = t.in.card != nullptr ? "deg, ctrl" : "deg, URDF";
  for (int j = 1; j <= 6; ++j) cols.push_back({"J" + std::to_string(j), jconv});
  cols.push_back({"MC", "s"});
  if (t.in.compensation) {
    for (const char* c : {"\u0394x", "\u0394y", "\u0394z", "|\u0394p|"}) cols.push_back({c, "mm"});
    cols.push_back({"\u0394rot", "deg"});
    cols.push_back({"rot. about axis", "deg"});
    cols.push_back({"Why rotated", "", true});
    cols.push_back({"Config before \u2192 after", "", true});
    cols.push_back({"Why config changed", "", true});
    cols.push_back({"Verdict after", "", true});
    cols.push_back({"Residual", "\u00b5m"});
  }
  return cols;
}

void renderHead(Html& h, const std::vector<Column>& cols) {
  h.markup("<thead><tr>");
  for (size_t c = 0; c < cols.size(); ++c) {
    std::vector<Attr> a;
    if (c == 0) a.emplace_back("class", "c0");
    if (c == 1) a.emplace_back("class", "l c1");
    if (c > 1 && cols[c].text) a.emplace_back("class", "l");
    if (cols[c].text) a.emplace_back("data-t", "1");
    h.open("th", a).markup(cols[c].head);
    if (!cols[c].unit.empty()) h.markup("<br>").markupElement("small", {}, cols[c].unit);
    h.close("th");
  }
  h.markup("</tr></thead>");
}

/// The table note on the joint convention (the J columns' unit line says "ctrl" or "URDF").
std::string jointConventionText(const ReportInput& in) {
  if (in.card == nullptr) return "Joints J1\u2013J6: motor-side command, URDF convention.";
  std::string s = "Joints J1\u2013J6: motor-side command as the " +
                  esc(vendorName(in.card->vendor)) +
                  " controller shows it (\u03b8<sub>ctrl</sub> = sign\u00b7\u03b8<sub>URDF</sub> "
                  "+ offset";
  if (in.card->j23_coupling != 0.0) {
    s += "; J3<sub>ctrl</sub> = J3<sub>URDF</sub> " +
         std::string(in.card->j23_coupling < 0 ? "\u2212 " : "+ ") +
         (std::fabs(in.card->j23_coupling) == 1.0
              ? ""
              : num(std::fabs(in.card->j23_coupling), 3) + "\u00b7") +
         "J2<sub>URDF</sub>";
  }
  return s + ").";
}

void renderNote(Html& h, const TableLayout& t) {
  h.open("p", {{"class", "note"}})
      .markup(
          "In program order; click a column head to sort, tick \u201cnot conforming only\u201d "
          "to filter. e\u22a5 = |\u03b4work \u22a5 hole axis|, U = U<sub>95</sub> (k as "
          "above): the hole conforms when e\u22a5 + U \u2264 t/2. Deviations in the robot base "
          "frame. ");
  if (t.has_split) {
    h.markup(
        "Why: the \u2192 columns split |\u03b4robot| into the parts caused by the arm's own "
        "weight, the tool weight, the process load and the controller reference (its "
        "gravity compensation or mastering offset), each part's component along \u03b4robot, "
        "so the four add up to |\u03b4robot| (hover for the part's vector; docs/reports.md "
        "\u00a73). ");
  }
  h.markup("u = per-axis standard uncertainty of each budget term. ")
      .markup(jointConventionText(t.in))
      .markup(" A ringed branch marks a configuration change from the previous hole.");
  if (t.in.compensation) {
    h.markup(
        " \u0394 = the offset applied to the target (programmed \u2212 original, base frame).");
  }
  h.close("p");
}

// ------------------------------------------------------------------ cells

void numCell(Html& h, double v, int decimals) {
  h.markup("<td>").number(v, decimals).markup("</td>");
}
void dashCells(Html& h, int n) {
  for (int i = 0; i < n; ++i) h.element("td", {}, kDash);
}
void optionalCell(Html& h, const std::optional<double>& v, int decimals) {
  if (v) {
    numCell(h, *v, decimals);
  } else {
    dashCells(h, 1);
  }
}

/// A text cell with a reason (dash when there is none).
void reasonCell(Html& h, const std::string& reason) {
  h.element("td", {{"class", "l why"}}, reason.empty() ? kDash : reason);
}

void verdictBadge(Html& h, Verdict v) {
  const VerdictStyle& vs = styleOf(v);
  h.open("td", {{"class", "l"}})
      .element("span", {{"class", std::string("badge b-") + vs.cls}, {"title", verdictName(v)}},
               vs.badge)
      .close("td");
}

/// δrobot split into its four causes, each part's component along δrobot (µm); small tables
/// carry the part's vector as a tooltip.
void splitCells(Html& h, const TableLayout& t, const HoleView& hole) {
  if (!*hole.split) return dashCells(h, 4);
  const api::ReportPrediction& p = *hole.p;
  const api::DeviationSplit& s = **hole.split;
  const double n = p.d_robot.norm();
  const Vec3 u = n > 0 ? Vec3(p.d_robot / n) : Vec3::Zero();
  for (const Vec3* part : {&s.gravity, &s.tool, &s.process, &s.controller}) {
    const Vec3 um = *part * 1e6;
    if (t.large) {  // the vectors only where the table is small (bytes, load time)
      numCell(h, part->dot(u) * 1e6, 1);
    } else {
      h.element("td",
                {{"title", "(" + num(um.x(), 1) + ", " + num(um.y(), 1) + ", " + num(um.z(), 1) +
                               ") \u00b5m"}},
                num(part->dot(u) * 1e6, 1));
    }
  }
}

/// e⊥, U, the verdict's sum, t/2, δrobot (and its split), δmach, the tilt, the budget terms and
/// the expanded robot and process uncertainties of a predicted hole.
void deviationCells(Html& h, const TableLayout& t, const HoleView& hole, RowMarks* marks) {
  const api::ReportPrediction& p = *hole.p;
  const double e = p.position_error * 1e6, U = p.U_work_exact * 1e6;
  h.open("td").element("strong", {}, num(e, 1)).close("td");
  for (const double v : {U, e + U, 0.5 * p.tolerance * 1e6, p.d_robot.norm() * 1e6})
    numCell(h, v, 1);
  if (marks != nullptr) marks->split = h.out().size();
  if (t.has_split) splitCells(h, t, hole);
  for (int k = 0; k < 3; ++k) numCell(h, p.d_robot[k] * 1e6, 1);
  for (int k = 0; k < 3; ++k) numCell(h, p.d_mach[k] * 1e6, 1);
  numCell(h, p.axis_tilt * 1e6, 1);
  for (const std::string& term : t.terms) {
    const auto it = std::find_if(p.budget.begin(), p.budget.end(), [&](const BudgetTerm& b) {
      return term == (b.name ? b.name : "");
    });
    if (it == p.budget.end()) {
      dashCells(h, 1);
    } else {
      numCell(h, it->u * 1e6, 2);
    }
  }
  if (marks != nullptr) marks->terms = h.out().size();
  numCell(h, p.U_robot * 1e6, 1);
  numCell(h, p.U_mach * 1e6, 1);
}

/// A hole that was not predicted: its reason over the deviation columns.
int reasonColumns(size_t terms, bool split) {
  return 14 + (split ? 4 : 0) + static_cast<int>(terms);
}

void reasonSpan(Html& h, const TableLayout& t, const api::ReportPrediction& p, RowMarks* marks) {
  const int span = reasonColumns(t.terms.size(), t.has_split);
  const size_t at = h.out().size();
  h.element("td", {{"class", "reason"}, {"colspan", span}},
            p.reason.empty() ? std::string(verdictName(p.verdict)) : p.reason);
  if (marks != nullptr) {
    constexpr std::string_view kColspan = "colspan=\"";
    marks->split = h.out().find(kColspan, at) + kColspan.size();
    marks->terms = marks->split + std::to_string(span).size();
    marks->colspan = true;
  }
}

/// Diameter, configuration flags, IK branch (ringed on a change) and the joints.
void postureCells(Html& h, const ReportInput& in, const HoleView& hole) {
  const api::ReportPrediction& p = *hole.p;
  numCell(h, p.diameter * 1e3, 2);
  h.element("td", {{"class", "l"}}, p.config.empty() ? kDash : p.config);
  const bool has_joints = hole.ok || !p.config.empty();
  if (hole.config_change) {
    h.open("td", {{"class", "chg"},
                  {"title", "configuration change: branch " + std::to_string(hole.prev_branch) +
                                " \u2192 " + std::to_string(p.branch)}})
        .element("b", {}, std::to_string(p.branch))
        .close("td");
  } else {
    h.element("td", {}, has_joints ? std::to_string(p.branch) : std::string(kDash));
  }
  const Vec6 q = in.card != nullptr ? toControllerJoints(*in.card, p.joints) : p.joints;
  for (int j = 0; j < 6; ++j) {
    if (has_joints) {
      numCell(h, q[j] * 180.0 / kPi, 1);
    } else {
      dashCells(h, 1);
    }
  }
}

/// The offset applied to the target: programmed − original position (mm, base frame), the angle
/// of the rotation between them (deg), the rotation about the drill axis and the flags before →
/// after, each change with its reason.
void offsetCells(Html& h, const ReportHole& rh, const api::ReportPrediction& p) {
  const Vec3 dp_mm = (rh.T_W_programmed->translation() - rh.T_W_tcp.translation()) * 1e3;
  const Eigen::AngleAxisd aa(rh.T_W_tcp.linear().transpose() * rh.T_W_programmed->linear());
  for (int k = 0; k < 3; ++k) numCell(h, dp_mm[k], 3);
  numCell(h, dp_mm.norm(), 3);
  numCell(h, std::abs(aa.angle()) * 180.0 / kPi, 3);
  const std::string& cb = rh.config_before.empty() ? p.config : rh.config_before;
  const std::string before = cb.empty() ? std::string(kDash) : cb;
  const std::string after = rh.config_after ? *rh.config_after : before;
  optionalCell(h, rh.rotation_about_axis_deg, 2);
  reasonCell(h, rh.rotation_reason);
  h.element("td", {{"class", after != before ? "l cfgchg" : "l"}}, before + " \u2192 " + after);
  reasonCell(h, rh.config_reason);
}

void compensationCells(Html& h, const HoleView& hole) {
  const ReportHole& rh = *hole.rh;
  if (rh.T_W_programmed) {
    offsetCells(h, rh, *hole.p);
  } else {
    dashCells(h, 5);
    optionalCell(h, rh.rotation_about_axis_deg, 2);
    reasonCell(h, rh.rotation_reason);
    h.element("td", {{"class", "l"}}, kDash);
    reasonCell(h, rh.config_reason);
  }
  verdictBadge(h, finalVerdict(hole));
  optionalCell(h, rh.residual_um, 1);
}

/// Row i (view `hole`) into `row` (cleared first); `marks`: where it takes more columns.
void rowInto(std::string& row, const TableLayout& t, const HoleView& hole, size_t i,
             RowMarks* marks = nullptr) {
  const api::ReportPrediction& p = *hole.p;
  row.clear();
  Html h(row);
  if (passes(hole)) {
    h.open("tr", {{"class", "pass"}});
  } else {
    h.open("tr");
  }
  h.element("td", {{"class", "c0"}}, std::to_string(i + 1))
      .element("td", {{"class", "id c1"}}, p.id);
  verdictBadge(h, p.verdict);
  if (hole.ok) {
    deviationCells(h, t, hole, marks);
  } else {
    reasonSpan(h, t, p, marks);
  }
  postureCells(h, t.in, hole);
  numCell(h, p.mc_time, 2);
  if (t.in.compensation) compensationCells(h, hole);
  h.close("tr");
}

// ------------------------------------------------------------------ large jobs

/// `row` as a JavaScript string literal appended to `s` (no "</" so it cannot end the script
/// element), each "</td><td" packed into the unit separator (JS "\x1f"): the rows are half the
/// bytes; the script joins them back for the page it shows.
/// `marks` (ascending offsets into `row`) get the offsets into `s` where their bytes went (an
/// offset inside a packed "</td><td": just after its unit separator).
void appendPackedJs(std::string& s, std::string_view row, std::span<size_t> marks = {}) {
  constexpr std::string_view kCut = "</td><td";
  // the bytes that may need packing: a cut's or "</"'s '<', and those escaped
  static constexpr std::array<bool, 256> kSpecial = [] {
    std::array<bool, 256> t{};
    for (const char c : {'<', '\\', '"', '\n', '\x1f'}) t[static_cast<unsigned char>(c)] = true;
    return t;
  }();
  s += '"';
  const size_t n = row.size();
  size_t run = 0;  // start of the bytes not appended yet (none of them needs an escape)
  size_t mk = 0;   // the next mark
  // the marks up to i: the bytes from run on go to s as they are (a mark inside a cut before
  // run: just after its separator)
  const auto markUpTo = [&](size_t i) {
    for (; mk < marks.size() && marks[mk] <= i; ++mk)
      marks[mk] = s.size() + (std::max(marks[mk], run) - run);
  };
  for (size_t i = 0; i < n; ++i) {
    const char c = row[i];
    if (!kSpecial[static_cast<unsigned char>(c)]) continue;
    markUpTo(i);
    if (c == '<') {
      if (row.compare(i, kCut.size(), kCut) == 0) {
        s.append(row.data() + run, i - run);
        s += "\\x1f";
        i += kCut.size() - 1;
        run = i + 1;
      } else if (i + 1 < n && row[i + 1] == '/') {  // "</": its '/' escaped
        markUpTo(i + 1);
        s.append(row.data() + run, i + 1 - run);
        s += "\\/";
        run = i + 2;
        ++i;
      }
      continue;
    }
    s.append(row.data() + run, i - run);
    run = i + 1;
    if (c == '\n') {
      s += "\\n";
    } else if (c == '\x1f') {
      s += "\\x1f";
    } else {
      s += '\\';
      s += c;
    }
  }
  markUpTo(n);
  s.append(row.data() + run, n - run);
  s += '"';
}

/// The rows in the table body (a small job's).
void renderRows(Html& h, const TableLayout& t, const std::vector<HoleView>& hv) {
  std::string row;
  for (size_t i = 0; i < hv.size(); ++i) {
    rowInto(row, t, hv[i], i);
    h.markup(row);
  }
}

/// Row i (view `hole`) as an item of the script array ROPREC_ROWS into `item`: a packed
/// JavaScript string, ",\n" before it unless it is the first; `row`: scratch.
void rowItem(const TableLayout& t, const HoleView& hole, size_t i, std::string& item,
             std::string& row) {
  rowInto(row, t, hole, i);
  item.clear();
  if (i > 0) item += ",\n";
  appendPackedJs(item, row);
}

/// The items of rows first.. (views `hv`), one per slot of `items` (resized), on `threads`
/// workers: each row's bytes do not depend on the count.
void rowItems(const TableLayout& t, std::span<const HoleView> hv, size_t first, int threads,
              std::vector<std::string>& items) {
  if (items.size() < hv.size()) items.resize(hv.size());
  std::vector<std::string> rows(static_cast<size_t>(std::max(1, threads)));
  parallelFor(hv.size(), threads, [&](int w, size_t k) {
    rowItem(t, hv[k], first + k, items[k], rows[static_cast<size_t>(w)]);
  });
}

/// Rows [b, e) of a large job as the items of the script array, rendered on t.in.threads workers
/// a round at a time and appended in order.
void renderItemRange(Html& h, const TableLayout& t, const std::vector<HoleView>& hv, size_t b,
                     size_t e, std::vector<std::string>& items) {
  const std::span<const HoleView> all(hv);
  for (size_t r = b; r < e; r += kRowsPerRound) {
    const size_t n = std::min(kRowsPerRound, e - r);
    rowItems(t, all.subspan(r, n), r, t.in.threads, items);
    for (size_t k = 0; k < n; ++k) h.markup(items[k]);
    h.flush(1 << 20);
  }
}

/// A run rendered ahead with fewer columns than the table has (RenderedRows::marks): a predicted
/// hole's row gains a dash cell per column it did not have (it had no split, none of the later
/// terms), another row's reason cell spans them.
std::string widenedRun(const api::RenderedRows& run, size_t terms, bool split) {
  const std::string dash = std::string(">") + kDash + "\\x1f";  // "<td>—</td>" packed
  const size_t rows = run.marks.size() / 2;
  std::string out;
  out.reserve(run.text.size() + rows * (4 + terms - run.terms) * dash.size());
  size_t at = 0;
  for (size_t k = 0; k + 1 < run.marks.size(); k += 2) {
    const std::uint32_t a = run.marks[k], b = run.marks[k + 1];
    if ((a & api::RenderedRows::kColspanMark) != 0) {
      const size_t digits = a & ~api::RenderedRows::kColspanMark;
      out.append(run.text, at, digits - at);
      out += std::to_string(reasonColumns(terms, split));
      at = digits + b;
      continue;
    }
    out.append(run.text, at, a - at);
    if (split && !run.split_columns) {
      for (int c = 0; c < 4; ++c) out += dash;
    }
    out.append(run.text, a, b - a);
    for (size_t n = run.terms; n < terms; ++n) out += dash;
    at = b;
  }
  out.append(run.text, at);
  return out;
}

/// A large streamed job's rows (ReportInput::mapped): every row rendered ahead, a run with fewer
/// columns than the table widened.
void renderMappedRows(Html& h, const TableLayout& t, size_t n) {
  size_t next = 0;  // the first row not written
  for (const api::RenderedRows& run : t.in.rows_ahead) {
    if (run.first != next || run.count > n - next || run.marks.size() != 2 * run.count)
      throw std::invalid_argument("renderReport: rows rendered ahead out of order");
    if (run.terms == t.terms.size() && run.split_columns == t.has_split) {
      h.bulk(run.text);
    } else {
      h.bulk(widenedRun(run, t.terms.size(), t.has_split));
    }
    next += run.count;
  }
  if (next != n) throw std::invalid_argument("renderReport: rows of mapped holes not rendered");
}

/// A large job's rows as the items of the script array ROPREC_ROWS (packed JavaScript strings,
/// ",\n" between them): the runs rendered ahead (ReportInput::rows_ahead) with the table's
/// columns as they are, the other rows rendered on t.in.threads workers: the bytes of rendering
/// them one after the other.
void renderPackedRows(Html& h, const TableLayout& t, const std::vector<HoleView>& hv) {
  std::vector<std::string> items;
  size_t next = 0;  // the first row not written
  for (const api::RenderedRows& run : t.in.rows_ahead) {
    if (run.first != next || run.count > hv.size() - next)
      throw std::invalid_argument("renderReport: rows rendered ahead out of order");
    if (run.terms == t.terms.size() && run.split_columns == t.has_split) {
      h.bulk(run.text);
    } else {
      renderItemRange(h, t, hv, run.first, run.first + run.count, items);
    }
    next += run.count;
  }
  renderItemRange(h, t, hv, next, hv.size(), items);
}

/// The table's script; a large job's rows packed into its array ROPREC_ROWS, written row by row.
void renderScript(Html& h, const TableLayout& t, const std::vector<HoleView>& hv) {
  h.open("script");
  if (t.large) {
    h.markup("var ROPREC_ROWS=[");
    if (t.in.mapped.empty()) {
      renderPackedRows(h, t, hv);
    } else {
      renderMappedRows(h, t, hv.size());
    }
    h.markup("];").markup(kPagedTableScript);
  } else {
    h.markup(kTableScript);
  }
  h.close("script");
}

}  // namespace

void renderTable(Html& h, const ReportInput& in, const std::vector<HoleView>& hv) {
  TableLayout t{in, {}, false, hv.size() > api::kReportAggregateAbove};
  long n_fail = 0;
  if (!in.mapped.empty()) {  // counted as the holes went past
    t.terms = in.totals.terms;
    t.has_split = in.totals.split;
    n_fail = in.totals.not_conforming;
  }
  for (const HoleView& v : hv) {  // one pass over the holes: terms, split, not conforming
    if (v.p == nullptr) break;
    addBudgetNames(t.terms, std::span(&v, 1));
    t.has_split = t.has_split || v.split->has_value();
    n_fail += passes(v) ? 0 : 1;
  }
  h.open("section", {{"id", "holes"}}).element("h2", {}, "Per-hole results");
  renderNote(h, t);
  if (t.large) {
    h.markup(strCat("<p><strong>", std::to_string(hv.size()), " holes: the table shows ",
                    std::to_string(kTableRowsPerPage),
                    " rows a page (sorting and filtering act on every hole).</strong></p>"));
  }
  h.open("label", {{"class", "filter"}})
      .open("input", {{"type", "checkbox"}, {"id", "failonly"}})
      .markup(" not conforming only (" + std::to_string(n_fail) + ")")
      .close("label");
  h.open("div", {{"class", "scroll"}}).open("table", {{"class", "holes"}, {"id", "holetable"}});
  renderHead(h, columns(t));
  h.open("tbody");
  if (!t.large) renderRows(h, t, hv);
  h.close("tbody").close("table").close("div");
  if (t.large) {
    h.markup(
        "<div class=\"pager\" id=\"pager\"><button class=\"prev\">\u25c0 previous</button> "
        "<span></span> <button class=\"next\">next \u25b6</button></div>");
  }
  h.close("section");
  renderScript(h, t, hv);
}

void addBudgetNames(std::vector<std::string>& names, std::span<const HoleView> hv) {
  for (const HoleView& h : hv) {
    if (!h.ok) continue;
    for (const BudgetTerm& b : h.p->budget) {
      const std::string_view n = b.name ? b.name : "";
      if (std::find(names.begin(), names.end(), n) == names.end()) names.emplace_back(n);
    }
  }
}

}  // namespace roprec::report

namespace roprec::api {

RowsAheadRenderer::RowsAheadRenderer(const RobotCard* card) { in_.card = card; }

void RowsAheadRenderer::render(std::span<const PredictedHole> holes, size_t first, int threads,
                               std::vector<RenderedRows>& out) {
  using namespace report;
  // what a row depends on beyond its hole, as far as the holes went: the IK branch before it,
  // the budget terms and whether a split was seen (positions are not shown in the table)
  std::vector<HoleView> hv;
  hv.reserve(holes.size());
  appendPredictedViews(hv, holes, Pose::Identity(), prev_branch_);
  addBudgetNames(terms_, hv);
  split_ = split_ || std::any_of(holes.begin(), holes.end(),
                                 [](const PredictedHole& h) { return h.split.has_value(); });
  const TableLayout t{in_, terms_, split_, true};
  // runs of rows, each rendered straight into its text by one worker
  constexpr size_t kRun = 128;
  const size_t runs = (holes.size() + kRun - 1) / kRun, at = out.size();
  for (size_t r = 0; r < runs; ++r) {
    RenderedRows& run = out.emplace_back();
    run.first = first + r * kRun;
    run.count = std::min(kRun, holes.size() - r * kRun);
    run.terms = terms_.size();
    run.split_columns = split_;
  }
  eachOnThreads(runs, threads, [&](size_t r) {
    RenderedRows& run = out[at + r];
    std::string row, text;  // text: grown here, kept at its size (no spare capacity)
    run.marks.resize(2 * run.count);
    for (size_t k = run.first - first, j = 0; k < run.first - first + run.count; ++k, j += 2) {
      RowMarks m;
      rowInto(row, t, hv[k], first + k, &m);
      if (first + k > 0) text += ",\n";
      std::array<size_t, 2> at_packed{m.split, m.terms};
      appendPackedJs(text, row, at_packed);
      if (m.colspan) {
        run.marks[j] = static_cast<std::uint32_t>(at_packed[0]) | RenderedRows::kColspanMark;
        run.marks[j + 1] = static_cast<std::uint32_t>(at_packed[1] - at_packed[0]);
      } else {
        run.marks[j] = static_cast<std::uint32_t>(at_packed[0]);
        run.marks[j + 1] = static_cast<std::uint32_t>(at_packed[1]);
      }
    }
    run.text = text;
  });
}

}  // namespace roprec::api
