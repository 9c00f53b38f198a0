/// Robot-card scaffolding and checks (plugin/api/card_tools.hpp).
#include "plugin/api/card_tools.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "compensator/precision/card_writer.hpp"
#include "compensator/precision/cell.hpp"
#include "compensator/robot/urdf_loader.hpp"
#include "compensator/robot/urdf_writer.hpp"
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

namespace {

namespace fs = std::filesystem;

/// `card_text` with its urdf="…" (in the <robot> tag) pointing at `urdf` from `out_path`'s folder,
/// when that folder is not the card's.
std::string relocateUrdf(const std::string& card_text, const RobotCard& card,
                         const std::string& out_path) {
  std::error_code ec;
  const fs::path card_dir = fs::absolute(fs::path(card.file).parent_path(), ec);
  const fs::path out_dir = fs::absolute(fs::path(out_path).parent_path(), ec);
  if (card_dir.lexically_normal() == out_dir.lexically_normal()) return card_text;
  const std::size_t robot = card_text.find("<robot");
  const std::size_t at = card_text.find("urdf=", robot);
  if (robot == std::string::npos || at == std::string::npos) return card_text;
  const char q = card_text[at + 5];
  const std::size_t end = card_text.find(q, at + 6);
  const std::string rel =
      fs::absolute(card.urdf_path, ec).lexically_normal().lexically_relative(out_dir).string();
  std::string out = card_text;
  return out.replace(at + 6, end - at - 6, rel);
}

std::string largestOffsets(const GeometryCalibration& c, const RobotCard& card) {
  std::string s = "derived the <calibration> block (origin errors in the nominal joint frames):\n";
  for (size_t i = 0; i < 6; ++i) {
    s += "  " + card.joints[i].name + ": " + cFixed(c.joints[i].dxyz.norm() * 1e3, 4) + " mm, " +
         cFixed(c.joints[i].drpy.norm() * 1e3, 4) + " mrad\n";
  }
  s += "  tool: " + cFixed(c.tool.dxyz.norm() * 1e3, 4) + " mm, " +
       cFixed(c.tool.drpy.norm() * 1e3, 4) + " mrad\n";
  return s + "then: roprec card check NEW.xml\n";
}

std::array<std::string, 6> jointNamesOf(const RobotCard& card) {
  std::array<std::string, 6> n;
  for (size_t i = 0; i < 6; ++i) n[i] = card.joints[i].name;
  return n;
}

std::string readWhole(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open the file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

CardImportResult cardImportCalibration(const std::string& card_path,
                                       const std::string& calibrated_urdf,
                                       const std::string& out_path) {
  const Robot robot = loadRobot({card_path, "", ""});
  const ChainDescription cal_chain =
      loadUrdfChain(calibrated_urdf, {robot.chain.base_link, robot.chain.tip_link});
  CardImportResult r;
  r.calibration = calibrationFromChains(robot.chain, cal_chain);
  r.calibration.source = "imported from " + calibrated_urdf + " (roprec card import-calibration)";
  const std::string text = replaceCardCalibration(
      readWhole(card_path), card_path, calibrationXml(r.calibration, jointNamesOf(robot.card)));
  r.card_text = relocateUrdf(text, robot.card, out_path);
  r.summary = largestOffsets(r.calibration, robot.card);
  return r;
}

std::string cardExportUrdf(const std::string& card_path) {
  const Robot robot = loadRobot({card_path, "", ""});
  if (!robot.card.calibration) {
    throw InputError(card_path, 0,
                     "the card has no <calibration> block: its URDF " + robot.card.urdf_path +
                         " already is the robot's model");
  }
  return calibratedUrdf(robot.card.urdf_path, robot.chain, *robot.card.calibration);
}

std::string calibrationNote(const RobotCard& card) {
  if (!card.calibration) return "";
  const GeometryCalibration& c = *card.calibration;
  std::string n = "robot card: calibrated geometry (" + c.source;
  if (!c.date.empty()) n += ", " + c.date;
  if (c.measurements > 0) n += ", " + std::to_string(c.measurements) + " measurements";
  if (c.residual_rms > 0) n += ", fit residual " + cFixed(c.residual_rms * 1e6, 1) + " um RMS";
  return n + "): real TCPs by FK_real, the controller's targets by the card's URDF";
}

std::vector<std::string> cardCheckOnLoad(const Robot& robot) {
  std::vector<std::string> notes;
  if (robot.card.file.empty()) return notes;
  if (robot.card.calibration) notes.push_back(calibrationNote(robot.card));
  const CardCheckReport report = checkRobotCard(robot);
  throwFirstCardError(report, robot.card);
  for (const CardFinding& f : report.findings) {
    notes.push_back("robot card: " + findingPlace(f) + ": " + f.message + " (hint: " + f.hint +
                    ")");
  }
  return notes;
}

}  // namespace roprec::api
