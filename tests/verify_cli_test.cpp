// Verify through the CLI, on the shipped sample (samples/verification/): `roprec verify` prints
// the statistics; `--calibrate` writes a card that loads in a cell and whose compensation, executed
// by the truth robot (the truth card the sample was measured with), leaves a smaller residual than
// the bundled card's; bad measured files exit 2 with FILE:LINE and write nothing; the JSON is
// deterministic; `roprec plan-test` writes a program `roprec inspect` reads with N holes.
#include <gtest/gtest.h>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <sstream>
#include <vector>

#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string s(const std::string& rel) { return test::sourceDir() + "/samples/" + rel; }
std::string q(const std::string& p) { return "'" + p + "'"; }

const std::string& cell() {
  static const std::string c = s("cells/housing-kr120.xml");
  return c;
}
const std::string& program() {
  static const std::string p = s("verification/test_kr120.src");
  return p;
}
const std::string& measured() {
  static const std::string m = s("verification/measured.csv");
  return m;
}

/// The nominal holes of the test program, named like its drill points (V01…) as in the
/// measured file.
const std::string& holes() {
  static const std::string h = s("verification/test_kr120_holes.csv");
  return h;
}

std::string verifyArgs(const std::string& extra) {
  return "verify --cell " + q(cell()) + " " + q(program()) + " --holes " + q(holes()) +
         " --measured " + q(measured()) + " " + extra;
}

/// verify on the sample's geometry test part (geometry_kr120.src: planned for the geometry, the
/// compliances and the registration together), drilled by the same truth robot.
std::string verifyGeometryArgs(const std::string& extra) {
  return "verify --cell " + q(cell()) + " " + q(s("verification/geometry_kr120.src")) +
         " --holes " + q(s("verification/geometry_kr120_holes.csv")) + " --measured " +
         q(s("verification/measured_geometry.csv")) + " " + extra;
}

TEST(VerifyCli, SampleExitsZeroAndPrintsTheStatistics) {
  const std::string dir = test::tempDir("verify");
  const auto r = test::runRoprec(verifyArgs("--register translation --json " + q(dir + "/v.json") +
                                            " --report " + q(dir + "/v.html")));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  for (const char* what : {"measured", "predicted", "residual", "explained share", "coverage",
                           "registration (translation", "condition number", "k1 = "})
    EXPECT_NE(r.out.find(what), std::string::npos) << what << "\n" << r.out;
  const json j = json::parse(test::readFile(dir + "/v.json"));
  EXPECT_EQ(j["summary"]["holes"], 24);
  EXPECT_GT(j["summary"]["measured_um"]["rms"].get<double>(), 0.0);
  EXPECT_EQ(j["registration"]["kind"], "translation");
  const std::string html = test::readFile(dir + "/v.html");
  EXPECT_NE(html.find("<svg"), std::string::npos);
  // Self-contained (the reason this test once demanded no <script> at all): the
  // per-hole table sorts like the prediction report's, with one inline script; nothing is
  // loaded from anywhere.
  EXPECT_EQ(html.find("<script src"), std::string::npos);
  EXPECT_EQ(html.find(" src="), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  size_t scripts = 0;
  for (size_t p = html.find("<script"); p != std::string::npos; p = html.find("<script", p + 1))
    ++scripts;
  EXPECT_EQ(scripts, 1u);
  EXPECT_NE(html.find("<script>"), std::string::npos);
}

/// A cell like the sample's with `<robot file="CARD"/>`, written into `dir`.
std::string cellWithCard(const std::string& dir, const std::string& card) {
  std::string text = test::readFile(cell());
  text = std::regex_replace(text, std::regex("<robot ref=\"[^\"]*\"/>"),
                            "<robot file=\"" + card + "\"/>");
  const std::string path = dir + "/cell-" + fs::path(card).stem().string() + ".xml";
  test::writeFile(path, text);
  return path;
}

/// The holes of `prog` predicted with the truth card (the robot the sample was measured with).
json truthPrediction(const std::string& prog, const std::string& dir, const std::string& tag) {
  const std::string out = dir + "/" + tag + ".json";
  const auto r = test::runRoprec("predict --cell " + q(s("verification/truth-cell.xml")) + " " +
                                 q(prog) + " --quiet --json " + q(out));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return json::parse(test::readFile(out))["holes"];
}

Eigen::Vector3d vec(const json& a) {
  return {a[0].get<double>(), a[1].get<double>(), a[2].get<double>()};
}

/// RMS (µm) of the truth's real drill points of `prog` from the nominal hole axes (the drill
/// points and axes of the uncompensated test program `nominal`), hole by hole in program order.
double truthResidualRms(const json& nominal, const std::string& prog, const std::string& dir,
                        const std::string& tag) {
  const json holes = truthPrediction(prog, dir, tag);
  EXPECT_EQ(holes.size(), nominal.size());
  double sum = 0;
  for (size_t i = 0; i < holes.size(); ++i) {
    const Eigen::Vector3d real =
        vec(holes[i]["nominal"]["position_mm"]) + vec(holes[i]["deviation_um"]["work"]) * 1e-3;
    const Eigen::Vector3d p0 = vec(nominal[i]["nominal"]["position_mm"]);
    const Eigen::Vector3d a0 = vec(nominal[i]["nominal"]["axis"]);
    const Eigen::Vector3d d = real - p0;
    sum += (d - d.dot(a0) * a0).squaredNorm() * 1e6;
  }
  return std::sqrt(sum / static_cast<double>(holes.size()));
}

TEST(VerifyCli, CalibratedCardCompensatesBetterOnTheTruthRobot) {
  const std::string dir = test::tempDir("calibrate");
  const std::string card = dir + "/kr120-calibrated.xml";
  const auto v = test::runRoprec(verifyArgs("--register translation --calibrate " + q(card)));
  ASSERT_EQ(v.exit_code, 0) << v.err << v.out;
  const std::string text = test::readFile(card);
  EXPECT_NE(text.find("identified: 24 holes from measured.csv by roprec verify"),
            std::string::npos);
  // the card loads in a cell: roprec predict accepts it
  const std::string cal_cell = cellWithCard(dir, card);
  const auto p =
      test::runRoprec("predict --cell " + q(cal_cell) + " " + q(program()) + " --quiet --json -");
  ASSERT_EQ(p.exit_code, 0) << p.err;
  // compensate with each card, execute on the truth robot
  const std::string orig = dir + "/comp_orig.src";
  const std::string cal = dir + "/comp_cal.src";
  ASSERT_EQ(
      test::runRoprec("compensate --cell " + q(cell()) + " " + q(program()) + " -o " + q(orig))
          .exit_code,
      0);
  ASSERT_EQ(
      test::runRoprec("compensate --cell " + q(cal_cell) + " " + q(program()) + " -o " + q(cal))
          .exit_code,
      0);
  const json nominal = truthPrediction(program(), dir, "nominal");
  const double before = truthResidualRms(nominal, program(), dir, "uncompensated");
  const double with_card = truthResidualRms(nominal, orig, dir, "orig");
  const double with_calibrated = truthResidualRms(nominal, cal, dir, "cal");
  std::printf(
      "truth residual RMS: uncompensated %.1f um, bundled card %.1f um, calibrated %.1f um\n",
      before, with_card, with_calibrated);
  EXPECT_LT(with_calibrated, with_card);
  EXPECT_LT(with_calibrated, 0.5 * with_card);
}

TEST(VerifyCli, FailOnNonconformanceGatesTheExitCodeOnProvenNonconformingHoles) {
  // The uncalibrated sample has holes proven non-conforming: exit 0 without the gate, 1 with it
  // (outputs still written); the gate counts exactly the holes the JSON marks so.
  const std::string dir = test::tempDir("verify_gate");
  const auto plain = test::runRoprec(verifyArgs("--register none --quiet"));
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const auto gated = test::runRoprec(
      verifyArgs("--register none --fail-on nonconformance --json " + q(dir + "/v.json")));
  EXPECT_EQ(gated.exit_code, 1) << gated.err;
  ASSERT_TRUE(fs::exists(dir + "/v.json"));
  const json j = json::parse(test::readFile(dir + "/v.json"));
  int proven = 0;
  for (const auto& h : j["holes"]) proven += h.value("decision", "") == "non-conformance-proven";
  ASSERT_GT(proven, 0);
  EXPECT_NE(gated.err.find("roprec: " + std::to_string(proven) + " holes proven non-conforming"),
            std::string::npos)
      << gated.err;
  const auto bad = test::runRoprec(verifyArgs("--fail-on everything"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--fail-on takes nonconformance"), std::string::npos) << bad.err;
}

TEST(VerifyCli, BadMeasuredFilesExitTwoWithFileLineAndWriteNothing) {
  const std::string dir = test::tempDir("badmeasured");
  const std::string good = test::readFile(measured());
  // the first data row of the sample (after the comments and the header)
  const size_t header = good.find("id,x,y,z,u\n");
  ASSERT_NE(header, std::string::npos);
  const std::string head = good.substr(0, header);
  const std::string rows = good.substr(header + 11);
  const std::string row1 = rows.substr(0, rows.find('\n') + 1);
  std::string metres;
  {
    metres = head + "id,x,y,z,u\n";
    std::stringstream in(rows);
    for (std::string line; std::getline(in, line);) {
      std::stringstream cells(line);
      std::string id, x, y, z, u;
      std::getline(cells, id, ',');
      std::getline(cells, x, ',');
      std::getline(cells, y, ',');
      std::getline(cells, z, ',');
      std::getline(cells, u, ',');
      char buf[160];
      std::snprintf(buf, sizeof buf, "%s,%.7f,%.7f,%.7f,%s\n", id.c_str(), std::stod(x) * 1e-3,
                    std::stod(y) * 1e-3, std::stod(z) * 1e-3, u.c_str());
      metres += buf;
    }
  }
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"missing_column", head + "id,x,y,u\nV01,1.0,2.0,5\n"},
      {"not_a_number", head + "id,x,y,z,u\n" + row1 + "V02,12.5,abc,3.0,5\n"},
      {"duplicate", head + "id,x,y,z,u\n" + row1 + row1},
      {"metres", metres}};
  for (const auto& [tag, text] : bad) {
    SCOPED_TRACE(tag);
    const std::string file = dir + "/" + tag + ".csv";
    test::writeFile(file, text);
    const std::string out = dir + "/out_" + tag;
    const auto r =
        test::runRoprec("verify --cell " + q(cell()) + " " + q(program()) + " --holes " +
                        q(holes()) + " --measured " + q(file) + " --json " + q(out + ".json") +
                        " --report " + q(out + ".html") + " --calibrate " + q(out + ".xml"));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_TRUE(std::regex_search(r.err, std::regex(tag + "\\.csv:[0-9]+: "))) << r.err;
    for (const char* ext : {".json", ".html", ".xml"}) EXPECT_FALSE(fs::exists(out + ext)) << ext;
  }
}

TEST(VerifyCli, IdentifyToolReportsTheToolWithinItsSigma) {
  // The truth robot drilled with the cell's own tool: the identified changes of the tool mass and
  // centre of mass must be consistent with zero (within 3σ).
  const auto r = test::runRoprec(verifyGeometryArgs("--register none --identify-tool"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::regex mass("tool_mass = (-?[0-9.]+) ± ([0-9.]+) kg change");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, mass)) << r.out;
  EXPECT_LE(std::abs(std::stod(m[1])), 3.0 * std::stod(m[2]));
  EXPECT_NE(r.out.find("tool_com_z"), std::string::npos);
}

TEST(VerifyCli, JsonIsDeterministic) {
  const std::string dir = test::tempDir("determinism");
  for (const char* tag : {"a", "b"}) {
    const auto r = test::runRoprec(verifyArgs("--register rigid --quiet --json " +
                                              q(dir + "/" + tag + ".json") + " --calibrate " +
                                              q(dir + "/" + tag + ".xml")));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  EXPECT_EQ(test::readFile(dir + "/a.json"), test::readFile(dir + "/b.json"));
  EXPECT_EQ(test::readFile(dir + "/a.xml"), test::readFile(dir + "/b.xml"));
}

/// The three numbers of attribute `name` of the first `<tag .../>` in an XML text.
Eigen::Vector3d attributeTriple(const std::string& xml, const std::string& tag,
                                const std::string& name) {
  std::smatch m;
  const std::regex re("<" + tag + "[^>]*\\s" + name + "=\"([^\"]*)\"");
  EXPECT_TRUE(std::regex_search(xml, m, re)) << tag << " " << name;
  std::istringstream in(m.size() > 1 ? m.str(1) : "0 0 0");
  Eigen::Vector3d v;
  in >> v.x() >> v.y() >> v.z();
  return v;
}

/// The `date` of the `<calibration>` a geometry calibration writes from `measured` (+ `extra`).
std::string calibrationDateOf(const std::string& dir, const std::string& measured_file,
                              const std::string& env, const std::string& extra) {
  const std::string card = dir + "/card.xml";
  fs::remove(card);
  const auto r = test::runCommand(env + " '" + test::roprecBin() + "' verify --cell " + q(cell()) +
                                  " " + q(s("verification/geometry_kr120.src")) + " --holes " +
                                  q(s("verification/geometry_kr120_holes.csv")) + " --measured " +
                                  q(measured_file) + " --register none --quiet --calibrate " +
                                  q(card) + " " + extra);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::smatch m;
  const std::string text = fs::exists(card) ? test::readFile(card) : std::string();
  if (!std::regex_search(text, m, std::regex("<calibration [^>]*date=\"([^\"]*)\""))) return "";
  return m[1];
}

TEST(VerifyCli, CalibrationDateIsGivenOrSourceDateEpochOrTheMeasuredFilesDay) {
  const std::string dir = test::tempDir("caldate");
  const std::string measured_copy = dir + "/measured_geometry.csv";
  fs::copy_file(s("verification/measured_geometry.csv"), measured_copy);
  // 2021-03-04 12:00 UTC as the file's modification time
  const auto when =
      std::chrono::file_clock::from_sys(std::chrono::sys_seconds{std::chrono::seconds{1614859200}});
  fs::last_write_time(measured_copy, when);
  EXPECT_EQ(calibrationDateOf(dir, measured_copy, "env -u SOURCE_DATE_EPOCH", ""), "2021-03-04");
  EXPECT_EQ(calibrationDateOf(dir, measured_copy, "SOURCE_DATE_EPOCH=1700000000", ""),
            "2023-11-14");
  EXPECT_EQ(
      calibrationDateOf(dir, measured_copy, "SOURCE_DATE_EPOCH=1700000000", "--date 2026-11-20"),
      "2026-11-20");
  const auto bad = test::runRoprec(verifyGeometryArgs("--register none --calibrate " +
                                                      q(dir + "/bad.xml") + " --date 20-11-2026"));
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find("--date must be YYYY-MM-DD"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir + "/bad.xml"));
}

TEST(VerifyCli, WriteCellStatesThePartRegistrationAndUsesTheNewCard) {
  const std::string dir = test::tempDir("writecell");
  const std::string card = dir + "/kr120-cal.xml";
  const std::string new_cell = dir + "/cell-cal.xml";
  const auto v = test::runRoprec(verifyGeometryArgs("--register translation --json " +
                                                    q(dir + "/v.json") + " --calibrate " + q(card) +
                                                    " --write-cell " + q(new_cell)));
  ASSERT_EQ(v.exit_code, 0) << v.err << v.out;
  EXPECT_NE(v.out.find("held-out validation (5-fold)"), std::string::npos) << v.out;
  EXPECT_NE(v.out.find("fit check"), std::string::npos) << v.out;
  const std::string text = test::readFile(new_cell);
  EXPECT_NE(text.find("<robot file=\"kr120-cal.xml\"/>"), std::string::npos) << text;
  // the workobject stays; the registration is the cell's <part_registration> (t in mm)
  const json j = json::parse(test::readFile(dir + "/v.json"));
  const Eigen::Vector3d t_um = vec(j["registration"]["translation_um"]);
  EXPECT_EQ(attributeTriple(test::readFile(cell()), "workobject", "xyz"),
            attributeTriple(text, "workobject", "xyz"));
  const Eigen::Vector3d xyz = attributeTriple(text, "part_registration", "xyz_mm");
  EXPECT_LE((xyz - t_um * 1e-3).cwiseAbs().maxCoeff(), 1e-4);
  EXPECT_EQ(attributeTriple(text, "part_registration", "rpy_mrad"), Eigen::Vector3d::Zero());
  // the sample's fixture offset (make_measured.py: 40, -25, 30 µm) within 3σ of the estimate
  const Eigen::Vector3d sigma = vec(j["registration"]["translation_sigma_um"]);
  const Eigen::Vector3d truth(40, -25, 30);
  for (int a = 0; a < 3; ++a) EXPECT_LE(std::abs(t_um[a] - truth[a]), 3 * sigma[a] + 1.0) << a;
  // the next job uses both: compensate with the new cell runs on the new card
  const auto c = test::runRoprec("compensate --cell " + q(new_cell) + " " + q(program()) + " -o " +
                                 q(dir + "/comp.src"));
  EXPECT_EQ(c.exit_code, 0) << c.err;
  EXPECT_TRUE(j["identification"].contains("validation"));
  EXPECT_EQ(j["identification"]["card_refused"], "");
}

/// Real drill points (base frame, mm) of `prog` predicted with `cell_path`: the programmed point
/// plus δwork, hole by hole (the cell's robot is the truth here).
std::vector<Eigen::Vector3d> drilledPoints(const std::string& cell_path, const std::string& prog,
                                           const std::string& json_out, json* holes_out = nullptr) {
  const auto r = test::runRoprec("predict --cell " + q(cell_path) + " " + q(prog) +
                                 " --quiet --json " + q(json_out));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const json holes = json::parse(test::readFile(json_out))["holes"];
  std::vector<Eigen::Vector3d> out;
  for (const auto& h : holes)
    out.push_back(vec(h["nominal"]["position_mm"]) + vec(h["deviation_um"]["work"]) * 1e-3);
  if (holes_out) *holes_out = holes;
  return out;
}

/// The test program with its own $BASE (not the cell's workobject 1350 0 300, rpy 0), drilled
/// by the cell's robot (the truth here) on a part displaced by a known registration F = [R, t]
/// about the workobject — the CMM measures a real point p (base frame) at F · T_W_wobj⁻¹ · p —
/// and the cell verify --register rigid --write-cell wrote from it.
struct RegisteredPart {
  std::string dir, prog, own_base, new_cell;
  json nominal;                       ///< the program's holes predicted with the cell
  std::vector<Eigen::Vector3d> real;  ///< their real drill points, base frame, mm
  Eigen::Isometry3d T_W_wobj, F;      ///< mm
  /// The hole i of the nominal part where F puts it: T_W_wobj · F⁻¹ · T_W_wobj⁻¹ · p (mm).
  [[nodiscard]] Eigen::Vector3d registered(size_t i) const {
    return T_W_wobj *
           (F.inverse() * (T_W_wobj.inverse() * vec(nominal[i]["nominal"]["position_mm"])));
  }
};

RegisteredPart registeredPart(const std::string& name) {
  RegisteredPart r;
  r.dir = test::tempDir(name);
  r.prog = r.dir + "/test_kr120.src";
  std::string src = test::readFile(program());
  const std::string base = "$BASE={FRAME: X 1350.000000,Y 0.000000,Z 300.000000,A 0.000000000";
  EXPECT_NE(src.find(base), std::string::npos);
  r.own_base = "$BASE={FRAME: X 1362.500000,Y -14.000000,Z 291.000000,A 2.000000000";
  src.replace(src.find(base), base.size(), r.own_base);
  test::writeFile(r.prog, src);
  fs::copy_file(s("verification/test_kr120.dat"), r.dir + "/test_kr120.dat");
  r.real = drilledPoints(cell(), r.prog, r.dir + "/p.json", &r.nominal);
  r.T_W_wobj = Eigen::Isometry3d::Identity();
  r.T_W_wobj.translation() = Eigen::Vector3d(1350, 0, 300);  // mm, rpy 0
  r.F = Eigen::Isometry3d::Identity();
  r.F.linear() = (Eigen::AngleAxisd(0.6e-3, Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(-0.4e-3, Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(0.5e-3, Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
  r.F.translation() = Eigen::Vector3d(0.35, -0.20, 0.25);  // mm
  std::string csv = "id,x,y,z,u\n";
  for (size_t i = 0; i < r.real.size(); ++i) {
    const Eigen::Vector3d m = r.F * (r.T_W_wobj.inverse() * r.real[i]);
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s,%.5f,%.5f,%.5f,1.0\n",
                  r.nominal[i]["id"].get<std::string>().c_str(), m.x(), m.y(), m.z());
    csv += buf;
  }
  test::writeFile(r.dir + "/measured.csv", csv);
  r.new_cell = r.dir + "/cell.xml";
  const auto v = test::runRoprec("verify --cell " + q(cell()) + " " + q(r.prog) + " --measured " +
                                 q(r.dir + "/measured.csv") + " --register rigid --write-cell " +
                                 q(r.new_cell) + " --quiet");
  EXPECT_EQ(v.exit_code, 0) << v.err << v.out;
  return r;
}

/// The registration F of `F` as the cell writes it: rpy (URDF order), mrad.
Eigen::Vector3d rpyMrad(const Eigen::Isometry3d& F) {
  const Eigen::Matrix3d R = F.linear();
  return Eigen::Vector3d(std::atan2(R(2, 1), R(2, 2)), std::asin(-R(2, 0)),
                         std::atan2(R(1, 0), R(0, 0))) *
         1e3;
}

TEST(VerifyCli, WrittenPartRegistrationReachesAProgramWithItsOwnBase) {
  const RegisteredPart part = registeredPart("partreg");
  const std::string text = test::readFile(part.new_cell);
  EXPECT_NE(text.find("<workobject xyz=\"1350 0 300\" rpy=\"0 0 0\"/>"), std::string::npos) << text;
  EXPECT_LE((attributeTriple(text, "part_registration", "xyz_mm") - part.F.translation()).norm(),
            2e-3)
      << text;
  // compensate with the written cell; the cell's robot drills the result
  const std::string comp = part.dir + "/comp.src";
  const auto c = test::runRoprec("compensate --cell " + q(part.new_cell) + " " + q(part.prog) +
                                 " -o " + q(comp));
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_NE(test::readFile(comp).find(part.own_base), std::string::npos)
      << "the program keeps its $BASE";
  const std::vector<Eigen::Vector3d> drilled = drilledPoints(cell(), comp, part.dir + "/c.json");
  ASSERT_EQ(drilled.size(), part.real.size());
  // the displaced holes by hand: the real part is the nominal one moved by F⁻¹ about the
  // workobject, p_reg = T_W_wobj · F⁻¹ · T_W_wobj⁻¹ · p_nominal; distances ⊥ the nominal axis
  double worst = 0;
  double worst_unregistered = 1e9;
  for (size_t i = 0; i < drilled.size(); ++i) {
    const Eigen::Vector3d p = vec(part.nominal[i]["nominal"]["position_mm"]);
    const Eigen::Vector3d a = vec(part.nominal[i]["nominal"]["axis"]);
    const Eigen::Vector3d p_reg = part.registered(i);
    auto perp = [&](const Eigen::Vector3d& d) { return (d - d.dot(a) * a).norm(); };
    worst = std::max(worst, perp(drilled[i] - p_reg));
    worst_unregistered = std::min(worst_unregistered, perp(p - p_reg));
  }
  EXPECT_LE(worst, 2e-3) << worst << " mm from the displaced holes";
  EXPECT_GE(worst_unregistered, 0.1) << "the registration moves every hole by more than 0.1 mm";
  // a registration in metres instead of mm is refused at its line, nothing written
  std::string bad = text;
  const size_t at = bad.find("xyz_mm=\"");
  ASSERT_NE(at, std::string::npos);
  bad.insert(at + 8, "5000");
  test::writeFile(part.dir + "/bad.xml", bad);
  const auto b = test::runRoprec("compensate --cell " + q(part.dir + "/bad.xml") + " " +
                                 q(part.prog) + " -o " + q(part.dir + "/bad.src"));
  EXPECT_EQ(b.exit_code, 2) << b.err;
  EXPECT_NE(b.err.find("bad.xml:14:"), std::string::npos) << b.err;
  EXPECT_NE(b.err.find("xyz_mm"), std::string::npos) << b.err;
  EXPECT_FALSE(fs::exists(part.dir + "/bad.src"));
}

// predict with the written cell aims every hole at the registered part as compensate does: its
// nominal holes are the displaced ones computed by hand (to 1e-9 m: the JSON's 6 decimals of mm)
// and its deviations are compensate's "before" deviations, hole by hole.
TEST(VerifyCli, PredictWithARegisteredCellDeviatesFromTheRegisteredHoles) {
  const RegisteredPart part = registeredPart("predictreg");
  json predicted;
  drilledPoints(part.new_cell, part.prog, part.dir + "/reg.json", &predicted);
  const auto c =
      test::runRoprec("compensate --cell " + q(part.new_cell) + " " + q(part.prog) + " -o " +
                      q(part.dir + "/comp.src") + " --targets " + q(part.dir + "/targets.json"));
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const json targets = json::parse(test::readFile(part.dir + "/targets.json"))["holes"];
  ASSERT_EQ(predicted.size(), part.nominal.size());
  ASSERT_EQ(targets.size(), predicted.size());
  // the registered part as the cell states it (its 4 / 6 decimals), by hand
  const std::string text = test::readFile(part.new_cell);
  Eigen::Isometry3d F = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d rpy = attributeTriple(text, "part_registration", "rpy_mrad") * 1e-3;
  F.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  F.translation() = attributeTriple(text, "part_registration", "xyz_mm");
  for (size_t i = 0; i < predicted.size(); ++i) {
    const json& h = predicted[i];
    ASSERT_EQ(h["id"], part.nominal[i]["id"]);
    const Eigen::Vector3d p = vec(part.nominal[i]["nominal"]["position_mm"]);
    const Eigen::Vector3d p_reg = part.T_W_wobj * (F.inverse() * (part.T_W_wobj.inverse() * p));
    EXPECT_LE((vec(h["nominal"]["position_mm"]) - p_reg).cwiseAbs().maxCoeff(), 1.5e-6) << i;
    const json& t = targets[i];
    ASSERT_EQ(t["id"], h["id"]);
    EXPECT_LE((vec(h["deviation_um"]["work"]) - vec(t["before"]["deviation_um"]["translation"]))
                  .cwiseAbs()
                  .maxCoeff(),
              1e-3)
        << h["id"];
    EXPECT_EQ(h["verdict"], t["before"]["verdict"]) << h["id"];
  }
}

// verify again on the cell verify wrote (its registration applied): the new registration is the
// small rest, composed with the cell's (F_cell · F_new), and both runs are at the part's truth.
TEST(VerifyCli, VerifyingARegisteredCellAgainComposesTheRegistration) {
  const RegisteredPart part = registeredPart("regagain");
  const std::string second = part.dir + "/cell2.xml";
  const auto v =
      test::runRoprec("verify --cell " + q(part.new_cell) + " " + q(part.prog) + " --measured " +
                      q(part.dir + "/measured.csv") + " --register rigid --write-cell " +
                      q(second) + " --json " + q(part.dir + "/v2.json") + " --quiet");
  ASSERT_EQ(v.exit_code, 0) << v.err << v.out;
  const json j = json::parse(test::readFile(part.dir + "/v2.json"));
  const Eigen::Vector3d rest_um = vec(j["registration"]["translation_um"]);
  EXPECT_LE(rest_um.norm(), 2.0) << "the first registration already holds the offset";
  EXPECT_LE(j["summary"]["residual_um"]["rms"].get<double>(), 2.0);
  const std::string first = test::readFile(part.new_cell);
  const std::string text = test::readFile(second);
  const Eigen::Vector3d xyz1 = attributeTriple(first, "part_registration", "xyz_mm");
  const Eigen::Vector3d xyz2 = attributeTriple(text, "part_registration", "xyz_mm");
  const Eigen::Vector3d rpy2 = attributeTriple(text, "part_registration", "rpy_mrad");
  std::printf(
      "registration: truth t %.4f %.4f %.4f mm; first %.4f %.4f %.4f; second %.4f %.4f "
      "%.4f; rotation second - truth %.4f mrad\n",
      part.F.translation().x(), part.F.translation().y(), part.F.translation().z(), xyz1.x(),
      xyz1.y(), xyz1.z(), xyz2.x(), xyz2.y(), xyz2.z(), (rpy2 - rpyMrad(part.F)).norm());
  EXPECT_LE((xyz2 - part.F.translation()).norm(), 2e-3) << text;
  EXPECT_LE((rpy2 - rpyMrad(part.F)).cwiseAbs().maxCoeff(), 5e-3) << text;
  EXPECT_LE((xyz2 - xyz1).norm(), 2e-3) << "the second run stays where the first converged";
  EXPECT_NE(text.find(", on the cell's"), std::string::npos) << text;
}

TEST(VerifyCli, PosesAloneCalibrateAndRecoverATrackerOffset) {
  // tracker poses = the sample program's commanded joints, measured at the programmed TCP (the
  // cell's controller compensates gravity with this tool, and a tracker pose has no process
  // load: the real TCP is the programmed one to second order) shifted by a known
  // tracker-alignment offset (workobject frame): the registration recovers it
  const std::string dir = test::tempDir("poses");
  const auto p = test::runRoprec("predict --cell " + q(cell()) + " " + q(program()) +
                                 " --quiet --json " + q(dir + "/p.json"));
  ASSERT_EQ(p.exit_code, 0) << p.err;
  const json holes = json::parse(test::readFile(dir + "/p.json"))["holes"];
  const Eigen::Vector3d wobj = attributeTriple(test::readFile(cell()), "workobject", "xyz");
  const Eigen::Vector3d offset(120, -80, 60);  // µm
  std::string csv = "id,j1,j2,j3,j4,j5,j6,x,y,z\n";
  for (const auto& h : holes) {
    const Eigen::Vector3d real = vec(h["nominal"]["position_mm"]);
    const Eigen::Vector3d m = real - wobj + offset * 1e-3;  // workobject axes = base axes here
    csv += h["id"].get<std::string>();
    for (const auto& q : h["controller_joints_deg"]) csv += "," + std::to_string(q.get<double>());
    char buf[128];
    std::snprintf(buf, sizeof buf, ",%.4f,%.4f,%.4f\n", m.x(), m.y(), m.z());
    csv += buf;
  }
  test::writeFile(dir + "/poses.csv", csv);
  const auto v =
      test::runRoprec("verify --cell " + q(cell()) + " --poses " + q(dir + "/poses.csv") +
                      " --register translation --identify stiffness --json " + q(dir + "/v.json"));
  ASSERT_EQ(v.exit_code, 0) << v.err << v.out;
  EXPECT_NE(v.out.find("measured poses"), std::string::npos) << v.out;
  const json j = json::parse(test::readFile(dir + "/v.json"));
  EXPECT_EQ(j["poses"]["count"], holes.size());
  const Eigen::Vector3d t = vec(j["registration"]["translation_um"]);
  EXPECT_LE((t - offset).norm(), 5.0) << t.transpose();
  // a bad pose file: exit 2 at its line
  test::writeFile(dir + "/bad.csv", "id,j1,j2,j3,j4,j5,j6,x,y,z\nA,1,2,3,4,5,6,7,8\n");
  const auto b = test::runRoprec("verify --cell " + q(cell()) + " --poses " + q(dir + "/bad.csv"));
  EXPECT_EQ(b.exit_code, 2);
  EXPECT_NE(b.err.find("bad.csv:2:"), std::string::npos) << b.err;
}

TEST(VerifyCli, PlanTestWritesAProgramInspectReadsWithNHoles) {
  const std::string dir = test::tempDir("plantest");
  const std::string out = dir + "/coupon.src";
  const auto r = test::runRoprec(
      "plan-test --cell " + q(cell()) +
      " --region \"-150 -150 200 150 150 230\" --per-axis 3 --count 7 -o " + q(out));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("expected joint stiffness uncertainty"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir + "/coupon.dat"));
  const auto i = test::runRoprec("inspect " + q(out) + " -o " + q(dir + "/inspect.json"));
  ASSERT_EQ(i.exit_code, 0) << i.err;
  const json j = json::parse(test::readFile(dir + "/inspect.json"));
  ASSERT_TRUE(j.contains("holes")) << j.dump().substr(0, 400);
  EXPECT_EQ(j["holes"].size(), 7u);
  // bad region: exit 2, nothing written
  const std::string bad = dir + "/bad.src";
  EXPECT_EQ(test::runRoprec("plan-test --cell " + q(cell()) + " --region \"1 2 3\" --count 3 -o " +
                            q(bad))
                .exit_code,
            2);
  EXPECT_FALSE(fs::exists(bad));
}

}  // namespace
}  // namespace roprec
