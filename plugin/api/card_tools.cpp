/// Robot-card scaffolding and checks (plugin/api/card_tools.hpp).
#include "plugin/api/card_tools.hpp"

#include <algorithm>

#include "compensator/precision/cell.hpp"
#include "compensator/support/c_format.hpp"
#include "compensator/support/error.hpp"

namespace roprec::api {

namespace {

std::string pad(const std::string& s, size_t w) {
  return s.size() >= w ? s : s + std::string(w - s.size(), ' ');
}

std::string tableText(const std::vector<CardCheckRow>& rows) {
  size_t w[3] = {5, 4, 9};
  for (const auto& r : rows) {
    w[0] = std::max(w[0], r.check.size());
    w[1] = std::max(w[1], r.value.size());
    w[2] = std::max(w[2], r.reference.size());
  }
  std::string t =
      pad("check", w[0]) + "  " + pad("card", w[1]) + "  " + pad("reference", w[2]) + "  verdict\n";
  for (const auto& r : rows) {
    t += pad(r.check, w[0]) + "  " + pad(r.value, w[1]) + "  " + pad(r.reference, w[2]) + "  " +
         r.verdict + "\n";
  }
  return t;
}

/// FILE:LINE, or FILE when the finding has no line (never "FILE:0").
std::string findingPlace(const CardFinding& f) {
  return f.line > 0 ? f.file + ":" + std::to_string(f.line) : f.file;
}

std::string findingText(const CardFinding& f) {
  return findingPlace(f) + ": " + (f.error ? "error" : "warning") + ": " + f.message +
         "\n  hint: " + f.hint + "\n";
}

/// The cell's tool against the card's rated payload.
void checkCellTool(const CellSpec& cell, const Robot& robot, CardCheckReport& report) {
  const double P = robot.card.rated_payload_kg;
  const double m = cell.tool.mass;
  const bool heavy = P > 0 && m > P;
  report.rows.push_back({"cell tool mass (kg)", cGeneral(m, 5),
                         "<= rated payload " + cGeneral(P, 5), heavy ? "WARNING" : "ok"});
  if (heavy) {
    report.findings.push_back({false, cell.file, cell.robot_line,
                               "the cell's tool (" + cGeneral(m, 5) +
                                   " kg) is heavier than the robot's rated payload (" +
                                   cGeneral(P, 5) + " kg)",
                               "check the tool's mass_kg and the card's rated_payload_kg"});
  }
}

}  // namespace

CardNewResult cardNew(const CardScaffoldRequest& request) {
  CardNewResult r;
  r.card = scaffoldCard(request);
  std::string s = "card for a " + vendorName(r.card.vendor) + " arm, rated payload " +
                  cGeneral(r.card.payload_kg, 6) + " kg: base_link '" + r.card.base_link +
                  "', flange_link '" + r.card.flange_link + "' (z out of the flange)\n";
  s += "still to confirm (each is marked estimate: in the card):\n";
  for (const std::string& c : r.card.confirm) s += "  - " + c + "\n";
  s += "then: roprec card check " + request.card_path + "\n";
  r.summary = s;
  return r;
}

CardCheckResult cardCheck(const std::string& card_path, const std::optional<std::string>& cell) {
  std::optional<CellSpec> spec;
  if (cell) spec = loadCell(*cell);
  std::string path = card_path;
  if (path.empty() && spec) path = spec->robot.robot;
  if (path.empty()) throw UsageError("give the robot card (robot.xml) or --cell CELL.xml");
  const Robot robot = loadRobot({path, "", ""});
  CardCheckResult r;
  r.report = checkRobotCard(robot);
  if (spec) checkCellTool(*spec, robot, r.report);
  r.table = tableText(r.report.rows);
  for (const CardFinding& f : r.report.findings) r.findings += findingText(f);
  r.table += robot.card.file + ": " + std::to_string(r.report.errors()) + " error(s), " +
             std::to_string(r.report.warnings()) + " warning(s)\n";
  r.exit_code = r.report.errors() > 0 ? 2 : 0;
  return r;
}

std::vector<std::string> cardCheckOnLoad(const Robot& robot) {
  std::vector<std::string> notes;
  if (robot.card.file.empty()) return notes;
  const CardCheckReport report = checkRobotCard(robot);
  throwFirstCardError(report, robot.card);
  for (const CardFinding& f : report.findings) {
    notes.push_back("robot card: " + findingPlace(f) + ": " + f.message + " (hint: " + f.hint +
                    ")");
  }
  return notes;
}

}  // namespace roprec::api
