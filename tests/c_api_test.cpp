// The C ABI (plugin/c/roprec.h, libroprec_c): the same numbers as the CLI on the sample job
// (predict and compensate keep, by file), roprec_filter_target against the library's keep
// compensation and the CLI's on every sample hole, the real TCP of a filtered target, error texts
// and statuses, buffers, and sessions on threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "compensator/precision/cell.hpp"
#include "compensator/robot/robot_card.hpp"
#include "compensator/support/rotation.hpp"
#include "plugin/api/hole_input.hpp"
#include "plugin/api/job.hpp"
#include "plugin/c/roprec.h"
#include "postproc/drill.hpp"
#include "tests/support/part_registration.hpp"
#include "tests/support/process.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using test::readFile;
using test::runRoprec;
using test::sourceDir;
using test::tempDir;
using test::writeFile;

const std::string kCell = sourceDir() + "/samples/cells/housing-kr120.xml";
const std::string kProgram = sourceDir() + "/samples/emotor-housing/housing_kr120.src";
const std::string kHoles = sourceDir() + "/samples/emotor-housing/holes.csv";

/// Compares two JSON documents: same structure, keys and strings; numbers within `rel`
/// (relative). Appends the first differences to `diffs`.
void compareJson(const nlohmann::json& a, const nlohmann::json& b, const std::string& path,
                 double rel, std::vector<std::string>& diffs) {
  if (diffs.size() > 20) return;
  if (a.is_number() && b.is_number()) {
    const double x = a.get<double>();
    const double y = b.get<double>();
    if (std::abs(x - y) > rel * std::max(std::abs(x), std::abs(y))) {
      diffs.push_back(path + ": " + a.dump() + " vs " + b.dump());
    }
    return;
  }
  if (a.type() != b.type()) {
    diffs.push_back(path + ": type " + a.type_name() + " vs " + b.type_name());
    return;
  }
  if (a.is_object()) {
    if (a.size() != b.size())
      diffs.push_back(path + ": " + std::to_string(a.size()) + " vs " + std::to_string(b.size()) +
                      " keys");
    for (auto it = a.begin(); it != a.end(); ++it) {
      if (!b.contains(it.key())) {
        diffs.push_back(path + "/" + it.key() + ": missing");
        continue;
      }
      compareJson(it.value(), b.at(it.key()), path + "/" + it.key(), rel, diffs);
    }
  } else if (a.is_array()) {
    if (a.size() != b.size()) {
      diffs.push_back(path + ": " + std::to_string(a.size()) + " vs " + std::to_string(b.size()) +
                      " items");
      return;
    }
    for (size_t i = 0; i < a.size(); ++i)
      compareJson(a[i], b[i], path + "/" + std::to_string(i), rel, diffs);
  } else if (a != b) {
    diffs.push_back(path + ": " + a.dump() + " vs " + b.dump());
  }
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += "  " + x + "\n";
  return s;
}

std::array<double, 16> rowMajorMm(const Pose& T) {
  std::array<double, 16> m{};
  for (int r = 0; r < 3; ++r) {
    const auto row = 4 * static_cast<size_t>(r);
    for (int c = 0; c < 3; ++c) m[row + static_cast<size_t>(c)] = T.linear()(r, c);
    m[row + 3] = T.translation()[r] * 1e3;
  }
  m[15] = 1.0;
  return m;
}

Mat3 rotationOf(const std::array<double, 16>& m) {
  Mat3 R;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R(r, c) = m[4 * static_cast<size_t>(r) + static_cast<size_t>(c)];
  }
  return R;
}

double angleBetween(const Mat3& A, const Mat3& B) {
  return Eigen::AngleAxisd(A.transpose() * B).angle();
}

/// The CLI's message for an error: stderr without "roprec: error: " and the newline.
std::string cliErrorText(const test::RunResult& r) {
  std::string e = r.err;
  const std::string prefix = "roprec: error: ";
  if (e.rfind(prefix, 0) == 0) e.erase(0, prefix.size());
  while (!e.empty() && e.back() == '\n') e.pop_back();
  return e;
}

bool validUtf8(const char* s) {
  const auto* p = reinterpret_cast<const unsigned char*>(s);
  while (*p) {
    const int n = *p < 0x80 ? 1 : *p >= 0xF0 ? 4 : *p >= 0xE0 ? 3 : *p >= 0xC0 ? 2 : 0;
    if (n == 0) return false;
    for (int i = 1; i < n; ++i) {
      if ((p[i] & 0xC0) != 0x80) return false;
    }
    p += n;
  }
  return true;
}

TEST(CApi, VersionIsTheLibrarys) {
  ASSERT_NE(roprec_version(), nullptr);
  EXPECT_STREQ(roprec_version(), api::version());
}

TEST(CApi, ExportsExactlyTheHeadersFunctions) {
  const std::string header = readFile(sourceDir() + "/plugin/c/roprec.h");
  const std::regex decl(R"(ROPREC_API[^;(]*\b(roprec_\w+)\s*\()");
  std::set<std::string> declared;
  for (auto it = std::sregex_iterator(header.begin(), header.end(), decl);
       it != std::sregex_iterator(); ++it) {
    declared.insert((*it)[1]);
  }
  EXPECT_EQ(declared.size(), 24U);
  // nm -D --defined-only: every dynamic symbol libroprec_c defines.
  const test::ProcessResult nm =
      test::runProcess({"/usr/bin/nm", "-D", "--defined-only", ROPREC_C_LIB});
  const std::string& listing = nm.out;
  ASSERT_EQ(nm.exit_code, 0) << nm.err;
  std::set<std::string> exported;
  std::istringstream lines(listing);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string address, type, name;
    words >> address >> type >> name;
    if (!name.empty()) exported.insert(name);
  }
  EXPECT_EQ(exported, declared) << listing;
}

TEST(CApi, PredictFileGivesTheCliNumbers) {
  const std::string dir = tempDir("capi-predict");
  const test::RunResult cli =
      runRoprec("predict --cell '" + kCell + "' '" + kProgram + "' --holes '" + kHoles +
                "' --json '" + dir + "/cli.json' --quiet");
  ASSERT_LE(cli.exit_code, 1) << cli.err;
  char summary[ROPREC_SUMMARY_LEN];
  char err[4096];
  const std::string out = dir + "/c.json";
  const int rc = roprec_predict_file(kCell.c_str(), kProgram.c_str(), kHoles.c_str(), out.c_str(),
                                     summary, sizeof summary, err, sizeof err);
  EXPECT_EQ(rc, cli.exit_code) << err;
  const auto a = nlohmann::json::parse(readFile(dir + "/cli.json"));
  const auto b = nlohmann::json::parse(readFile(out));
  ASSERT_EQ(a.at("holes").size(), 204U);
  std::vector<std::string> diffs;
  compareJson(a, b, "", 1e-9, diffs);
  EXPECT_TRUE(diffs.empty()) << joined(diffs);
  // The summary is the JSON's summary plus the count of holes not predicted.
  auto s = nlohmann::json::parse(summary);
  int failed = 0;
  for (const auto& h : a.at("holes"))
    failed += h.at("verdict") == "unreachable" || h.at("verdict") == "singular" ||
              h.at("verdict") == "not-converged";
  EXPECT_EQ(s.at("failed").get<int>(), failed);
  s.erase("failed");
  diffs.clear();
  compareJson(a.at("summary"), s, "summary", 1e-9, diffs);
  EXPECT_TRUE(diffs.empty()) << joined(diffs);
  std::filesystem::remove_all(dir);
}

TEST(CApi, CompensateKeepFileGivesTheCliNumbersAndBytes) {
  const std::string dir = tempDir("capi-comp");
  const test::RunResult cli = runRoprec("compensate --cell '" + kCell + "' '" + kProgram +
                                        "' --holes '" + kHoles + "' --orientation keep -o '" + dir +
                                        "/cli.src' --targets '" + dir + "/cli.json' --quiet");
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  char summary[ROPREC_SUMMARY_LEN];
  char err[4096];
  const std::string out = dir + "/c.src";
  const std::string targets = dir + "/c.json";
  const int rc =
      roprec_compensate_file(kCell.c_str(), kProgram.c_str(), kHoles.c_str(), out.c_str(), "keep",
                             targets.c_str(), summary, sizeof summary, err, sizeof err);
  ASSERT_EQ(rc, ROPREC_OK) << err;
  EXPECT_STREQ(err, "");
  const auto a = nlohmann::json::parse(readFile(dir + "/cli.json"));
  const auto b = nlohmann::json::parse(readFile(targets));
  ASSERT_EQ(a.at("holes").size(), 204U);
  std::vector<std::string> diffs;
  compareJson(a, b, "", 1e-9, diffs);
  EXPECT_TRUE(diffs.empty()) << joined(diffs);
  // The corrected program is the CLI's, byte for byte (the sample's points are inline: no .dat).
  EXPECT_EQ(readFile(dir + "/cli.src"), readFile(out));
  EXPECT_FALSE(std::filesystem::exists(dir + "/c.dat"));
  const auto s = nlohmann::json::parse(summary);
  EXPECT_EQ(s.at("orientation"), "keep");
  EXPECT_EQ(s.at("holes").get<int>(), 204);
  EXPECT_EQ(s.at("compensated").get<int>(), 204);
  EXPECT_EQ(s.at("failed").get<int>(), 0);
  EXPECT_LT(s.at("residual_after_um").at("max").get<double>(), 0.01);
  EXPECT_EQ(s.at("written"), (nlohmann::json{out, targets}));
  std::filesystem::remove_all(dir);
}

/// The sample hole list as a JSON target program (docs/programs.md): per hole an approach 20 mm
/// before the hole and a slow linear feed to it, in a frame equal to the cell's workobject, at
/// full precision — so the program's drill points are the hole-list poses.
std::string holeListProgram(const std::vector<postproc::HoleSpec>& specs, const Pose& T_base_wobj) {
  char buf[512];
  const Eigen::Quaterniond qw = quaternionFromRotation(T_base_wobj.linear());
  const Vec3 pw = T_base_wobj.translation() * 1e3;
  std::string s = "{\"frames\": [";
  std::snprintf(buf, sizeof buf,
                "{\"name\": \"wobj\", \"position_mm\": [%.17g, %.17g, %.17g], \"quaternion_wxyz\": "
                "[%.17g, %.17g, %.17g, %.17g]}",
                pw.x(), pw.y(), pw.z(), qw.w(), qw.x(), qw.y(), qw.z());
  s += buf;
  s += "],\n\"targets\": [\n";
  for (size_t i = 0; i < specs.size(); ++i) {
    const postproc::HoleSpec& h = specs[i];
    const Eigen::Quaterniond q = quaternionFromRotation(api::holeFrame(h.direction));
    const Vec3 d = h.direction.normalized();
    for (int k = 0; k < 2; ++k) {
      const Vec3 p = k == 0 ? Vec3(h.position_mm - 20.0 * d) : h.position_mm;
      std::snprintf(
          buf, sizeof buf,
          "%s{\"id\": \"%s%s\", \"motion\": \"L\", \"frame\": \"wobj\", \"speed_mm_s\": %d, "
          "\"position_mm\": [%.17g, %.17g, %.17g], \"quaternion_wxyz\": [%.17g, %.17g, %.17g, "
          "%.17g]}",
          i == 0 && k == 0 ? "" : ",\n", h.id.c_str(), k == 0 ? "_approach" : "", k == 0 ? 250 : 10,
          p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z());
      s += buf;
    }
  }
  s += "\n]}\n";
  return s;
}

TEST(CApi, FilterTargetEqualsKeepCompensationOnEverySampleHole) {
  const std::vector<postproc::HoleSpec> specs = postproc::readHoleList(kHoles);
  ASSERT_EQ(specs.size(), 204U);
  const CellSpec cell = loadCell(kCell);
  const std::string dir = tempDir("capi-filter");
  const std::string program = dir + "/holes_program.json";
  writeFile(program, holeListProgram(specs, cell.T_base_wobj));

  // The library's keep compensation of those holes (double precision) ...
  const api::CompensationResult job = api::compensateJob(kCell, program);
  ASSERT_EQ(job.holes.size(), specs.size());
  // ... and the CLI's (its export prints 6 decimals of mm and 9 of the quaternion).
  const test::RunResult cli =
      runRoprec("compensate --cell '" + kCell + "' '" + program + "' --orientation keep -o '" +
                dir + "/out.json' --targets '" + dir + "/targets.json' --quiet");
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  const auto exported = nlohmann::json::parse(readFile(dir + "/targets.json")).at("holes");
  ASSERT_EQ(exported.size(), specs.size());

  roprec_session* s = nullptr;
  char err[1024];
  ASSERT_EQ(roprec_open(kCell.c_str(), &s, err, sizeof err), ROPREC_OK) << err;
  const RobotCard& card = job.context.robot.card;
  double worst_pos_um = 0;
  double worst_rot = 0;
  double worst_real_um = 0;
  for (size_t i = 0; i < specs.size(); ++i) {
    SCOPED_TRACE(specs[i].id);
    const HoleCompensation& h = job.holes[i];
    ASSERT_TRUE(h.ok) << h.reason;
    // The hole-list pose: the cell's workobject times the hole frame.
    Pose T_wobj_tcp = Pose::Identity();
    T_wobj_tcp.linear() = api::holeFrame(specs[i].direction);
    T_wobj_tcp.translation() = specs[i].position_mm * 1e-3;
    const Pose T_want = cell.T_base_wobj * T_wobj_tcp;
    ASSERT_LT((job.context.job.requests[i].T_W_tcp.translation() - T_want.translation()).norm(),
              1e-12);
    ASSERT_LT(angleBetween(job.context.job.requests[i].T_W_tcp.linear(), T_want.linear()), 1e-12);

    // Seeded with the joints the job predicted the hole at (its IK branch and turns).
    const Vec6 seed_deg = toControllerJoints(card, h.before.joints) / kDeg;
    const std::array<double, 16> want = rowMajorMm(T_want);
    std::array<double, 16> prog{};
    std::array<double, 6> joints{};
    ASSERT_EQ(roprec_filter_target(s, want.data(), seed_deg.data(), prog.data(), joints.data(), err,
                                   sizeof err),
              ROPREC_OK)
        << err;

    // = the library's compensation: ≤ 1e-3 µm, ≤ 1e-9 rad; orientation kept bit for bit.
    const Vec3 p(prog[3], prog[7], prog[11]);
    const double dpos_um = (p - h.T_programmed.translation() * 1e3).norm() * 1e3;
    const double drot = angleBetween(rotationOf(prog), h.T_programmed.linear());
    EXPECT_LE(dpos_um, 1e-3);
    EXPECT_LE(drot, 1e-9);
    EXPECT_EQ(rotationOf(prog), T_want.linear());
    EXPECT_EQ(prog[12], 0.0);
    EXPECT_EQ(prog[15], 1.0);
    const Vec6 j_job = toControllerJoints(card, h.theta_cmd) / kDeg;
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(joints[static_cast<size_t>(k)], j_job[k], 1e-7);
    worst_pos_um = std::max(worst_pos_um, dpos_um);
    worst_rot = std::max(worst_rot, drot);

    // = the CLI's export to its printed precision (half a unit of the last printed digit).
    const auto& e = exported[i].at("programmed");
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(e.at("position_mm")[static_cast<size_t>(k)].get<double>(), p[k], 0.5e-6 + 1e-9);
    const Eigen::Quaterniond q = quaternionFromRotation(rotationOf(prog));
    const Eigen::Vector4d qv(q.w(), q.x(), q.y(), q.z());
    for (int k = 0; k < 4; ++k)
      EXPECT_NEAR(e.at("quaternion_wxyz")[static_cast<size_t>(k)].get<double>(), qv[k],
                  0.5e-9 + 1e-12);

    // The predicted real TCP at the returned joints (programmed pose + deviation) is the wanted
    // pose.
    std::array<double, 6> dev{};
    double U = 0;
    ASSERT_EQ(roprec_predict_joints(s, joints.data(), dev.data(), &U, err, sizeof err), ROPREC_OK)
        << err;
    const Vec3 real = p + Vec3(dev[0], dev[1], dev[2]) * 1e-3;
    const double miss_um = (real - T_want.translation() * 1e3).norm() * 1e3;
    EXPECT_LE(miss_um, 0.1);
    EXPECT_GT(U, 0.0);
    EXPECT_NEAR(U, h.after.U_work_exact * 1e6, 1e-6 * h.after.U_work_exact * 1e6);
    worst_real_um = std::max(worst_real_um, miss_um);
  }
  std::printf(
      "filter_target vs compensate keep over %zu holes: max %.3g um, %.3g rad; real TCP off the "
      "hole by max %.3g um\n",
      specs.size(), worst_pos_um, worst_rot, worst_real_um);

  // Without a seed the reference pose picks the IK solution: the first hole's, like the job's.
  std::array<double, 16> prog0{};
  std::array<double, 6> joints0{};
  Pose T0 = Pose::Identity();
  T0.linear() = api::holeFrame(specs[0].direction);
  T0.translation() = specs[0].position_mm * 1e-3;
  const std::array<double, 16> want0 = rowMajorMm(cell.T_base_wobj * T0);
  ASSERT_EQ(
      roprec_filter_target(s, want0.data(), nullptr, prog0.data(), joints0.data(), err, sizeof err),
      ROPREC_OK)
      << err;
  EXPECT_LE(
      (Vec3(prog0[3], prog0[7], prog0[11]) - job.holes[0].T_programmed.translation() * 1e3).norm(),
      1e-6);
  // The output may alias the input.
  std::array<double, 16> inout = want0;
  ASSERT_EQ(
      roprec_filter_target(s, inout.data(), nullptr, inout.data(), joints0.data(), err, sizeof err),
      ROPREC_OK);
  EXPECT_EQ(inout, prog0);
  roprec_close(s);
  std::filesystem::remove_all(dir);
}

// A cell with a <part_registration> (verify --write-cell): filter_target takes a pose on the
// nominal part and aims it where the registration found the part — the same programmed pose as
// filter_target on the cell without it for the registered pose computed by hand,
// G = T_W_wobj · F⁻¹ · T_W_wobj⁻¹ — and as compensate (keep) of the registered cell, to 1e-9 m.
TEST(CApi, FilterTargetOfARegisteredCellAimsAtTheRegisteredPart) {
  const std::vector<postproc::HoleSpec> specs = postproc::readHoleList(kHoles);
  const CellSpec cell = loadCell(kCell);
  const std::string dir = tempDir("capi-registered");
  const std::string text = test::withPartRegistration(readFile(kCell));
  ASSERT_FALSE(text.empty());
  const std::string registered = dir + "/registered.xml";
  writeFile(registered, text);
  const Pose F = test::partRegistration();  // the registration by hand
  const Pose G = cell.T_base_wobj * F.inverse() * cell.T_base_wobj.inverse();
  std::vector<postproc::HoleSpec> some(specs.begin(), specs.begin() + 12);
  const std::string program = dir + "/holes_program.json";
  writeFile(program, holeListProgram(some, cell.T_base_wobj));
  api::CompensationJob cj;
  cj.options.mode = OrientationMode::kKeep;
  const api::CompensationResult job = api::compensateJobHoles(registered, program, cj);
  ASSERT_EQ(job.holes.size(), some.size());
  roprec_session* s = nullptr;
  roprec_session* plain = nullptr;
  char err[1024];
  ASSERT_EQ(roprec_open(registered.c_str(), &s, err, sizeof err), ROPREC_OK) << err;
  ASSERT_EQ(roprec_open(kCell.c_str(), &plain, err, sizeof err), ROPREC_OK) << err;
  const RobotCard& card = job.context.robot.card;
  for (size_t i = 0; i < some.size(); ++i) {
    SCOPED_TRACE(some[i].id);
    const HoleCompensation& h = job.holes[i];
    ASSERT_TRUE(h.ok) << h.reason;
    Pose T_wobj_tcp = Pose::Identity();
    T_wobj_tcp.linear() = api::holeFrame(some[i].direction);
    T_wobj_tcp.translation() = some[i].position_mm * 1e-3;
    const Pose T_want = cell.T_base_wobj * T_wobj_tcp;
    const Vec6 seed_deg = toControllerJoints(card, h.before.joints) / kDeg;
    std::array<double, 16> prog{};
    std::array<double, 16> prog_hand{};
    std::array<double, 6> joints{};
    const std::array<double, 16> want = rowMajorMm(T_want);
    const std::array<double, 16> want_hand = rowMajorMm(G * T_want);
    ASSERT_EQ(roprec_filter_target(s, want.data(), seed_deg.data(), prog.data(), joints.data(), err,
                                   sizeof err),
              ROPREC_OK)
        << err;
    ASSERT_EQ(roprec_filter_target(plain, want_hand.data(), seed_deg.data(), prog_hand.data(),
                                   joints.data(), err, sizeof err),
              ROPREC_OK)
        << err;
    const Vec3 p(prog[3], prog[7], prog[11]);
    EXPECT_LE((p - Vec3(prog_hand[3], prog_hand[7], prog_hand[11])).norm(), 1e-6);  // mm
    EXPECT_LE(angleBetween(rotationOf(prog), rotationOf(prog_hand)), 1e-9);
    EXPECT_LE((p - h.T_programmed.translation() * 1e3).norm(), 1e-6);
    EXPECT_GE((p - Vec3(want[3], want[7], want[11])).norm(), 0.1) << "the part moved ≥ 0.1 mm";
  }
  roprec_close(s);
  roprec_close(plain);
  std::filesystem::remove_all(dir);
}

TEST(CApi, ReadmeTableListsEveryExportedFunction) {
  const std::string header = readFile(sourceDir() + "/plugin/c/roprec.h");
  const std::string readme = readFile(sourceDir() + "/README.md");
  const std::regex decl(R"(ROPREC_API[^;(]*\b(roprec_\w+)\s*\()");
  std::set<std::string> declared;
  for (auto it = std::sregex_iterator(header.begin(), header.end(), decl);
       it != std::sregex_iterator(); ++it) {
    declared.insert((*it)[1]);
  }
  EXPECT_EQ(declared.size(), 24U);
  for (const std::string& name : declared) {
    EXPECT_NE(readme.find("`" + name + "`"), std::string::npos)
        << name << " is not in README's C table";
  }
}

TEST(CApi, JointsOutsideTheLimitsAreBadInputAsInTheCli) {
  // the CLI refuses them (exit 2): so do the per-joint calls (2, not an item failure)
  const test::RunResult cli =
      runRoprec("deflect --cell '" + kCell + "' --joints \"0 -90 90 0 0 400\"");
  EXPECT_EQ(cli.exit_code, 2) << cli.err;
  EXPECT_NE(cli.err.find("outside the joint limits: joint_a6 = 400"), std::string::npos) << cli.err;
  roprec_session* s = nullptr;
  char err[1024];
  ASSERT_EQ(roprec_open(kCell.c_str(), &s, err, sizeof err), ROPREC_OK) << err;
  const std::array<double, 6> out_of_range{0, -90, 90, 0, 0, 400};
  std::array<double, 6> dev{};
  EXPECT_EQ(roprec_predict_joints(s, out_of_range.data(), dev.data(), nullptr, err, sizeof err),
            ROPREC_BAD_INPUT);
  EXPECT_NE(std::string(err).find("joints_deg outside the joint limits: joint_a6 = "),
            std::string::npos)
      << err;
  EXPECT_EQ(roprec_predict_joints_hole(s, out_of_range.data(), nullptr, dev.data(), nullptr,
                                       nullptr, err, sizeof err),
            ROPREC_BAD_INPUT);
  roprec_close(s);
}

TEST(CApi, HoleProcessCallsStateTheProcessAndRefuseAToolTheCellLacks) {
  const std::string cell = sourceDir() + "/samples/cells/housing-kr120-tools.xml";
  roprec_session* s = nullptr;
  char err[1024];
  ASSERT_EQ(roprec_open(cell.c_str(), &s, err, sizeof err), ROPREC_OK) << err;
  const std::array<double, 16> pose{1, 0, 0, 1500, 0, -1, 0, 0, 0, 0, -1, 550, 0, 0, 0, 1};
  std::array<double, 16> out{};
  std::array<double, 6> joints{};
  roprec_process_used used{};
  // nothing given: the cell's first drill, its cut, the cell's depth
  ASSERT_EQ(roprec_filter_target_hole(s, pose.data(), nullptr, nullptr, out.data(), joints.data(),
                                      &used, err, sizeof err),
            ROPREC_OK)
      << err;
  EXPECT_STREQ(used.tool, "1");
  EXPECT_DOUBLE_EQ(used.diameter_mm, 6.8);
  EXPECT_DOUBLE_EQ(used.depth_mm, 20.0);
  EXPECT_DOUBLE_EQ(used.feed_mm_per_rev, 0.2);
  EXPECT_DOUBLE_EQ(used.spindle_rpm, 6000.0);
  EXPECT_EQ(used.from_cell, 1);
  // tool 4: its own cut; the old call equals the hole call without a process
  roprec_hole_process hole{"4", 0.0, 24.0, 0.0, 0.0};
  std::array<double, 16> out4{};
  ASSERT_EQ(roprec_filter_target_hole(s, pose.data(), nullptr, &hole, out4.data(), joints.data(),
                                      &used, err, sizeof err),
            ROPREC_OK)
      << err;
  EXPECT_STREQ(used.tool, "4");
  EXPECT_DOUBLE_EQ(used.diameter_mm, 12.0);
  EXPECT_DOUBLE_EQ(used.depth_mm, 24.0);
  EXPECT_DOUBLE_EQ(used.feed_mm_per_rev, 0.25);
  EXPECT_DOUBLE_EQ(used.spindle_rpm, 5000.0);
  EXPECT_EQ(used.from_cell, 0);
  EXPECT_NE(out4, out);  // a larger drill, a larger thrust: another pre-offset
  std::array<double, 16> plain{};
  ASSERT_EQ(
      roprec_filter_target(s, pose.data(), nullptr, plain.data(), joints.data(), err, sizeof err),
      ROPREC_OK);
  EXPECT_EQ(plain, out);
  // a tool the table does not have, a feed the hole cannot take, a negative value: bad input
  hole.tool = "9";
  EXPECT_EQ(roprec_filter_target_hole(s, pose.data(), nullptr, &hole, out4.data(), joints.data(),
                                      nullptr, err, sizeof err),
            ROPREC_BAD_INPUT);
  EXPECT_NE(std::string(err).find("tool '9' is not in the cell's tool table (tools: 1, 2, 3, 4)"),
            std::string::npos)
      << err;
  hole = {"1", 1.0, 0.0, 0.0, 0.0};
  EXPECT_EQ(roprec_filter_target_hole(s, pose.data(), nullptr, &hole, out4.data(), joints.data(),
                                      nullptr, err, sizeof err),
            ROPREC_BAD_INPUT);
  EXPECT_NE(std::string(err).find("feed <= 0.1 Dc"), std::string::npos) << err;
  hole = {nullptr, -1.0, 0.0, 0.0, 0.0};
  EXPECT_EQ(roprec_filter_target_hole(s, pose.data(), nullptr, &hole, out4.data(), joints.data(),
                                      nullptr, err, sizeof err),
            ROPREC_BAD_INPUT);
  EXPECT_STREQ(err, "process.diameter_mm must be finite and >= 0 (0: the cell's)");
  // the batch: one target unreachable among reachable ones → 1, its status 1, the rest written
  std::array<double, 48> poses{};
  std::copy(pose.begin(), pose.end(), poses.begin());
  std::copy(pose.begin(), pose.end(), poses.begin() + 16);
  std::copy(pose.begin(), pose.end(), poses.begin() + 32);
  poses[16 + 3] = 9000.0;  // 9 m away
  std::array<double, 48> outs{};
  std::array<double, 18> outj{};
  std::array<int, 3> status{9, 9, 9};
  EXPECT_EQ(roprec_filter_targets(s, 3, poses.data(), nullptr, nullptr, outs.data(), outj.data(),
                                  status.data(), err, sizeof err),
            ROPREC_ITEM_FAILED);
  EXPECT_EQ(status, (std::array<int, 3>{0, 1, 0}));
  EXPECT_EQ(std::string(err).rfind("target 1: ", 0), 0U) << err;
  EXPECT_TRUE(std::equal(out.begin(), out.end(), outs.begin()));
  EXPECT_TRUE(std::all_of(outs.begin() + 16, outs.begin() + 32, [](double v) { return v == 0; }));
  roprec_close(s);
}

/// The hole-list row's process as the CLI stated it in the prediction JSON ("drill").
struct CliHole {
  std::string tool;
  roprec_hole_process process;
};

CliHole cliHole(const nlohmann::json& h) {
  CliHole c{h.at("drill").at("tool").get<std::string>(), {}};
  c.process = {nullptr, h.at("diameter_mm").get<double>(), h.at("depth_mm").get<double>(), 0.0,
               0.0};
  return c;
}

/// The process object of a JSON answer states the CLI's drill of that hole.
void expectCliProcess(const nlohmann::json& used, const nlohmann::json& h) {
  EXPECT_EQ(used.at("tool"), h.at("drill").at("tool"));
  EXPECT_NEAR(used.at("diameter_mm").get<double>(), h.at("diameter_mm").get<double>(), 1e-9);
  EXPECT_NEAR(used.at("depth_mm").get<double>(), h.at("depth_mm").get<double>(), 1e-9);
  EXPECT_NEAR(used.at("feed_mm_per_rev").get<double>(),
              h.at("drill").at("feed_mm_per_rev").get<double>(), 1e-9);
  EXPECT_NEAR(used.at("spindle_rpm").get<double>(), h.at("drill").at("spindle_rpm").get<double>(),
              1e-9);
  EXPECT_EQ(used.at("from_cell"), false);
}

TEST(CApi, HoleJsonCallsGiveTheCliPerHoleNumbersAndTheSessionsValues) {
  const std::string cell = sourceDir() + "/samples/cells/housing-kr120-tools.xml";
  const std::string dir = tempDir("capi-hole-json");
  const test::RunResult cli = runRoprec("predict --cell '" + cell + "' '" + kHoles + "' --json '" +
                                        dir + "/p.json' --quiet");
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  const auto holes = nlohmann::json::parse(readFile(dir + "/p.json")).at("holes");
  const api::PredictionResult job = api::predictJob(cell, kHoles);  // full-precision joints
  ASSERT_EQ(job.holes.size(), holes.size());
  const RobotCard& card = job.context.robot.card;
  api::Session session(cell);  // the C++ call the C ABI wraps
  roprec_session* s = nullptr;
  char err[1024];
  ASSERT_EQ(roprec_open(cell.c_str(), &s, err, sizeof err), ROPREC_OK) << err;
  std::vector<char> json(ROPREC_SUMMARY_LEN);
  std::vector<CliHole> rows;
  rows.reserve(holes.size());  // process.tool points into its row
  double worst_um = 0;
  for (size_t i = 0; i < holes.size(); ++i) {
    SCOPED_TRACE(holes[i].at("id").get<std::string>());
    rows.push_back(cliHole(holes[i]));
    CliHole& row = rows.back();
    row.process.tool = row.tool.c_str();
    const Vec6 q_deg = toControllerJoints(card, job.holes[i].joints) / kDeg;
    ASSERT_EQ(roprec_predict_joints_hole_json(s, q_deg.data(), &row.process, json.data(),
                                              json.size(), err, sizeof err),
              ROPREC_OK)
        << err;
    const auto j = nlohmann::json::parse(json.data());
    // the CLI's deviation of the hole (printed to 1e-3 µm): 1e-9 m
    const auto& robot = holes[i].at("deviation_um").at("robot");
    for (size_t k = 0; k < 3; ++k)
      worst_um = std::max(worst_um,
                          std::abs(j.at("deviation_um")[k].get<double>() - robot[k].get<double>()));
    EXPECT_NEAR(j.at("U_work_um").get<double>(),
                holes[i].at("uncertainty_um").at("U_work_anisotropic").get<double>(), 1e-3);
    expectCliProcess(j.at("process"), holes[i]);
    // the session's call with the same process: value for value (shortest round-trip text)
    const api::HoleProcess hp{row.tool, row.process.diameter_mm * 1e-3, row.process.depth_mm * 1e-3,
                              0.0, 0.0};
    const api::Session::JointPrediction p = session.predictJoints(q_deg * kDeg, hp);
    ASSERT_TRUE(p.ok) << p.reason;
    for (Eigen::Index k = 0; k < 3; ++k) {
      EXPECT_EQ(j.at("deviation_um")[static_cast<size_t>(k)].get<double>(),
                p.d_translation[k] * 1e6);
      EXPECT_EQ(j.at("rotation_urad")[static_cast<size_t>(k)].get<double>(), p.d_rotation[k] * 1e6);
    }
    EXPECT_EQ(j.at("U_work_um").get<double>(), p.U_work * 1e6);
    EXPECT_EQ(j.at("config"), p.prediction.config);
    EXPECT_EQ(j.at("process").at("drill"), p.process.drill);
  }
  EXPECT_LE(worst_um, 1e-3);
  std::printf("per-hole deviation vs the CLI: %.3g um worst over %zu holes\n", worst_um,
              holes.size());

  // the batch: the CLI's compensated targets (printed to 1e-6 mm), each hole's process stated
  const test::RunResult comp =
      runRoprec("compensate --cell '" + cell + "' '" + kHoles + "' --orientation keep -o '" + dir +
                "/c.csv' --targets '" + dir + "/t.json' --quiet");
  ASSERT_EQ(comp.exit_code, 0) << comp.err;
  const auto targets = nlohmann::json::parse(readFile(dir + "/t.json")).at("holes");
  ASSERT_EQ(targets.size(), holes.size());
  const size_t n = holes.size();
  std::vector<double> poses;
  std::vector<roprec_hole_process> processes;
  for (size_t i = 0; i < n; ++i) {
    const std::array<double, 16> m = rowMajorMm(job.context.job.requests[i].T_W_tcp);
    poses.insert(poses.end(), m.begin(), m.end());
    processes.push_back(rows[i].process);
  }
  std::vector<char> batch(2048 * n);
  ASSERT_EQ(roprec_filter_targets_json(s, n, poses.data(), nullptr, processes.data(), batch.data(),
                                       batch.size(), err, sizeof err),
            ROPREC_OK)
      << err;
  const auto b = nlohmann::json::parse(batch.data());
  std::vector<double> outs(16 * n);
  std::vector<double> outj(6 * n);
  ASSERT_EQ(roprec_filter_targets(s, n, poses.data(), nullptr, processes.data(), outs.data(),
                                  outj.data(), nullptr, err, sizeof err),
            ROPREC_OK)
      << err;
  double worst_mm = 0;
  for (size_t i = 0; i < n; ++i) {
    SCOPED_TRACE(holes[i].at("id").get<std::string>());
    EXPECT_EQ(b.at("ok")[i], true);
    EXPECT_TRUE(b.at("reasons")[i].is_null());
    for (size_t k = 0; k < 16; ++k)
      EXPECT_EQ(b.at("poses_mm")[i][k].get<double>(), outs[16 * i + k]);
    for (size_t k = 0; k < 6; ++k)
      EXPECT_EQ(b.at("joints_deg")[i][k].get<double>(), outj[6 * i + k]);
    const auto& at = targets[i].at("programmed").at("position_mm");
    for (size_t k = 0; k < 3; ++k)
      worst_mm = std::max(worst_mm, std::abs(outs[16 * i + 4 * k + 3] - at[k].get<double>()));
    expectCliProcess(b.at("process")[i], holes[i]);
  }
  EXPECT_LE(worst_mm, 0.5e-6 + 1e-9);
  std::printf("filtered targets vs the CLI's export: %.3g mm worst\n", worst_mm);

  // one target: the details of the batch's first, and the session's configuration and residual
  ASSERT_EQ(roprec_filter_target_hole_json(s, poses.data(), nullptr, &processes[0], json.data(),
                                           json.size(), err, sizeof err),
            ROPREC_OK)
      << err;
  const auto one = nlohmann::json::parse(json.data());
  EXPECT_EQ(one.at("pose_mm"), b.at("poses_mm")[0]);
  EXPECT_EQ(one.at("joints_deg"), b.at("joints_deg")[0]);
  EXPECT_EQ(one.at("process"), b.at("process")[0]);
  const api::HoleProcess hp0{rows[0].tool, rows[0].process.diameter_mm * 1e-3,
                             rows[0].process.depth_mm * 1e-3, 0.0, 0.0};
  const api::Session::Filtered f =
      session.filterTarget(job.context.job.requests[0].T_W_tcp, nullptr, hp0);
  ASSERT_TRUE(f.ok) << f.reason;
  EXPECT_EQ(one.at("config"), f.config);
  EXPECT_EQ(one.at("residual_um").get<double>(), f.residual * 1e6);
  EXPECT_LT(f.residual, 1e-9);
  roprec_close(s);
  std::filesystem::remove_all(dir);
}

TEST(CApi, HoleJsonCallsRefuseWhatTheCliRefusesAndReportTheUnfiltered) {
  const std::string cell = sourceDir() + "/samples/cells/housing-kr120-tools.xml";
  roprec_session* s = nullptr;
  char err[1024];
  ASSERT_EQ(roprec_open(cell.c_str(), &s, err, sizeof err), ROPREC_OK) << err;
  std::vector<char> json(ROPREC_SUMMARY_LEN);
  // a joint outside the limits: bad input (the CLI's exit 2), an input error, the CLI's text
  const test::RunResult cli =
      runRoprec("deflect --cell '" + cell + "' --joints \"0 -90 90 0 0 400\"");
  EXPECT_EQ(cli.exit_code, 2) << cli.err;
  const std::array<double, 6> out_of_range{0, -90, 90, 0, 0, 400};
  EXPECT_EQ(roprec_predict_joints_hole_json(s, out_of_range.data(), nullptr, json.data(),
                                            json.size(), err, sizeof err),
            ROPREC_BAD_INPUT);
  EXPECT_EQ(roprec_error_kind(), ROPREC_ERROR_INPUT);
  EXPECT_NE(std::string(err).find("outside the joint limits: joint_a6 = 400"), std::string::npos)
      << err;
  EXPECT_STREQ(json.data(), "");
  // a tool the cell's table lacks: an input error
  const std::array<double, 16> pose{1, 0, 0, 1500, 0, -1, 0, 0, 0, 0, -1, 550, 0, 0, 0, 1};
  const roprec_hole_process nine{"9", 0.0, 0.0, 0.0, 0.0};
  EXPECT_EQ(roprec_filter_target_hole_json(s, pose.data(), nullptr, &nine, json.data(), json.size(),
                                           err, sizeof err),
            ROPREC_BAD_INPUT);
  EXPECT_EQ(roprec_error_kind(), ROPREC_ERROR_INPUT);
  EXPECT_NE(std::string(err).find("tool '9' is not in the cell's tool table"), std::string::npos)
      << err;
  // a buffer too small: a usage error stating the bytes needed, nothing written
  std::array<char, 16> tiny{'x'};
  EXPECT_EQ(roprec_filter_target_hole_json(s, pose.data(), nullptr, nullptr, tiny.data(),
                                           tiny.size(), err, sizeof err),
            ROPREC_BAD_INPUT);
  EXPECT_EQ(roprec_error_kind(), ROPREC_ERROR_USAGE);
  EXPECT_NE(std::string(err).find("are needed; nothing was written"), std::string::npos) << err;
  EXPECT_EQ(tiny[0], '\0');
  // the batch with an unreachable target: 1, the JSON still written, that target kept and stated
  std::array<double, 32> poses{};
  std::copy(pose.begin(), pose.end(), poses.begin());
  std::copy(pose.begin(), pose.end(), poses.begin() + 16);
  poses[3] = 9000.0;  // 9 m away
  EXPECT_EQ(roprec_filter_targets_json(s, 2, poses.data(), nullptr, nullptr, json.data(),
                                       json.size(), err, sizeof err),
            ROPREC_ITEM_FAILED);
  EXPECT_EQ(std::string(err).rfind("target 0: ", 0), 0U) << err;
  const auto b = nlohmann::json::parse(json.data());
  EXPECT_EQ(b.at("ok"), nlohmann::json::parse("[false, true]"));
  EXPECT_TRUE(b.at("joints_deg")[0].is_null());
  EXPECT_EQ(b.at("reasons")[0].get<std::string>(), std::string(err).substr(10));
  EXPECT_TRUE(b.at("reasons")[1].is_null());
  EXPECT_EQ(b.at("poses_mm")[0][3].get<double>(), 9000.0);
  EXPECT_EQ(b.at("process")[0].at("from_cell"), true);
  EXPECT_EQ(b.at("process")[0].at("tool"), "1");
  roprec_close(s);
}

TEST(CApi, ErrorsAreStatusesWithTheCliText) {
  char err[1024];
  roprec_session* s = reinterpret_cast<roprec_session*>(&err);  // must be reset to NULL
  const std::string missing = sourceDir() + "/samples/cells/no-such-cell.xml";
  EXPECT_EQ(roprec_open(missing.c_str(), &s, err, sizeof err), ROPREC_BAD_INPUT);
  EXPECT_EQ(s, nullptr);
  const test::RunResult cli =
      runRoprec("predict --cell '" + missing + "' '" + kProgram + "' --json -");
  EXPECT_EQ(cli.exit_code, 2);
  EXPECT_EQ(std::string(err), cliErrorText(cli));

  // A broken cell: FILE:LINE: what, as the CLI prints it.
  const std::string dir = tempDir("capi-errors");
  const std::string bad = dir + "/bad.xml";
  writeFile(bad, "<cell name=\"x\">\n  <robot ref=\"no-such-robot\"/>\n</cell>\n");
  EXPECT_EQ(roprec_open(bad.c_str(), &s, err, sizeof err), ROPREC_BAD_INPUT);
  const test::RunResult cli_bad =
      runRoprec("predict --cell '" + bad + "' '" + kProgram + "' --json -");
  EXPECT_EQ(cli_bad.exit_code, 2);
  EXPECT_EQ(std::string(err), cliErrorText(cli_bad));
  EXPECT_EQ(std::string(err).rfind(bad, 0), 0U) << err;

  // Error buffers: truncated, always NUL-terminated; NULL with length 0 is allowed.
  char small[8];
  std::memset(small, 'x', sizeof small);
  EXPECT_EQ(roprec_open(missing.c_str(), &s, small, sizeof small), ROPREC_BAD_INPUT);
  EXPECT_EQ(std::strlen(small), 7U);
  EXPECT_EQ(std::string(small), cliErrorText(cli).substr(0, 7));
  char one[1] = {'x'};
  EXPECT_EQ(roprec_open(missing.c_str(), &s, one, 1), ROPREC_BAD_INPUT);
  EXPECT_EQ(one[0], '\0');
  EXPECT_EQ(roprec_open(missing.c_str(), &s, nullptr, 0), ROPREC_BAD_INPUT);
  EXPECT_EQ(roprec_open(nullptr, &s, err, sizeof err), ROPREC_BAD_INPUT);
  EXPECT_STREQ(err, "cell_path is NULL");
  EXPECT_EQ(roprec_open(kCell.c_str(), nullptr, err, sizeof err), ROPREC_BAD_INPUT);

  ASSERT_EQ(roprec_open(kCell.c_str(), &s, err, sizeof err), ROPREC_OK) << err;
  EXPECT_STREQ(err, "");
  std::array<double, 16> pose{1, 0, 0, 1500, 0, -1, 0, 0, 0, 0, -1, 550, 0, 0, 0, 1};
  std::array<double, 16> out{};
  std::array<double, 6> joints{};
  std::array<double, 6> dev{};
  EXPECT_EQ(roprec_filter_target(nullptr, pose.data(), nullptr, out.data(), joints.data(), err,
                                 sizeof err),
            ROPREC_BAD_INPUT);
  EXPECT_STREQ(err, "session is NULL");
  EXPECT_EQ(roprec_filter_target(s, nullptr, nullptr, out.data(), joints.data(), err, sizeof err),
            ROPREC_BAD_INPUT);
  // A non-rigid pose; its message holds multi-byte characters: truncation keeps whole characters.
  std::array<double, 16> skew = pose;
  skew[1] = 0.01;
  EXPECT_EQ(
      roprec_filter_target(s, skew.data(), nullptr, out.data(), joints.data(), err, sizeof err),
      ROPREC_BAD_INPUT);
  const std::string full = err;
  EXPECT_NE(full.find("not orthonormal"), std::string::npos) << full;
  const size_t mb = full.find("ᵀ");
  ASSERT_NE(mb, std::string::npos);
  for (size_t cut = mb + 1; cut <= mb + 3; ++cut) {
    std::vector<char> buf(cut + 1, 'x');
    EXPECT_EQ(roprec_filter_target(s, skew.data(), nullptr, out.data(), joints.data(), buf.data(),
                                   buf.size()),
              ROPREC_BAD_INPUT);
    EXPECT_TRUE(validUtf8(buf.data())) << cut;
    EXPECT_EQ(std::strlen(buf.data()), cut == mb + 3 ? mb + 3 : mb);
  }
  std::array<double, 16> row = pose;
  row[14] = 0.5;
  EXPECT_EQ(
      roprec_filter_target(s, row.data(), nullptr, out.data(), joints.data(), err, sizeof err),
      ROPREC_BAD_INPUT);
  std::array<double, 16> nan = pose;
  nan[3] = std::nan("");
  EXPECT_EQ(
      roprec_filter_target(s, nan.data(), nullptr, out.data(), joints.data(), err, sizeof err),
      ROPREC_BAD_INPUT);
  std::array<double, 6> bad_seed{0, -90, 90, 0, std::nan(""), 0};
  EXPECT_EQ(roprec_filter_target(s, pose.data(), bad_seed.data(), out.data(), joints.data(), err,
                                 sizeof err),
            ROPREC_BAD_INPUT);

  // Out of reach: an item failure, outputs unchanged.
  std::array<double, 16> far = pose;
  far[3] = 9000;
  out.fill(7.0);
  EXPECT_EQ(
      roprec_filter_target(s, far.data(), nullptr, out.data(), joints.data(), err, sizeof err),
      ROPREC_ITEM_FAILED);
  EXPECT_NE(std::string(err).find("target not filtered"), std::string::npos) << err;
  EXPECT_EQ(out[0], 7.0);
  EXPECT_EQ(roprec_predict_joints(s, nullptr, dev.data(), nullptr, err, sizeof err),
            ROPREC_BAD_INPUT);
  const std::array<double, 6> home{0, -90, 90, 0, 45, 0};
  EXPECT_EQ(roprec_predict_joints(s, home.data(), nullptr, nullptr, err, sizeof err),
            ROPREC_BAD_INPUT);
  EXPECT_EQ(roprec_predict_joints(s, home.data(), dev.data(), nullptr, err, sizeof err), ROPREC_OK)
      << err;
  roprec_close(s);
  roprec_close(nullptr);

  // Whole jobs: a summary buffer too small writes nothing; a missing program; bad options.
  char tiny[16];
  const std::string json = dir + "/p.json";
  EXPECT_EQ(roprec_predict_file(kCell.c_str(), kHoles.c_str(), nullptr, json.c_str(), tiny,
                                sizeof tiny, err, sizeof err),
            ROPREC_BAD_INPUT);
  EXPECT_NE(std::string(err).find("summary_json"), std::string::npos) << err;
  EXPECT_FALSE(std::filesystem::exists(json));
  EXPECT_EQ(roprec_predict_file(kCell.c_str(), kHoles.c_str(), nullptr, nullptr, nullptr, 5, err,
                                sizeof err),
            ROPREC_BAD_INPUT);
  EXPECT_EQ(roprec_predict_file(kCell.c_str(), kHoles.c_str(), nullptr, json.c_str(), nullptr, 0,
                                err, sizeof err),
            ROPREC_OK)
      << err;
  EXPECT_TRUE(std::filesystem::exists(json));
  const std::string out_prog = dir + "/o.src";
  const std::string no_program = dir + "/no-such-program.src";
  EXPECT_EQ(roprec_compensate_file(kCell.c_str(), no_program.c_str(), nullptr, out_prog.c_str(),
                                   "keep", nullptr, nullptr, 0, err, sizeof err),
            ROPREC_BAD_INPUT);
  const test::RunResult cli_missing = runRoprec("compensate --cell '" + kCell + "' '" + no_program +
                                                "' -o '" + out_prog + "' --quiet");
  EXPECT_EQ(cli_missing.exit_code, 2);
  EXPECT_EQ(std::string(err), cliErrorText(cli_missing));
  EXPECT_EQ(roprec_compensate_file(kCell.c_str(), kProgram.c_str(), nullptr, out_prog.c_str(),
                                   "sideways", nullptr, nullptr, 0, err, sizeof err),
            ROPREC_BAD_INPUT);
  EXPECT_NE(std::string(err).find("keep, flip-free or stiffest"), std::string::npos) << err;
  EXPECT_FALSE(std::filesystem::exists(out_prog));
  std::filesystem::remove_all(dir);
}

TEST(CApi, DistinctSessionsRunOnThreads) {
  const std::vector<postproc::HoleSpec> specs = postproc::readHoleList(kHoles);
  const CellSpec cell = loadCell(kCell);
  constexpr size_t kTargets = 24;
  auto run = [&](size_t first, std::vector<std::array<double, 16>>& results, int& status) {
    roprec_session* s = nullptr;
    char err[512];
    status = roprec_open(kCell.c_str(), &s, err, sizeof err);
    if (status != ROPREC_OK) return;
    for (size_t i = 0; i < kTargets; ++i) {
      const postproc::HoleSpec& h = specs[(first + i) % specs.size()];
      Pose T = Pose::Identity();
      T.linear() = api::holeFrame(h.direction);
      T.translation() = h.position_mm * 1e-3;
      const std::array<double, 16> want = rowMajorMm(cell.T_base_wobj * T);
      std::array<double, 6> joints{};
      status = std::max(status, roprec_filter_target(s, want.data(), nullptr, results[i].data(),
                                                     joints.data(), err, sizeof err));
    }
    roprec_close(s);
  };
  std::vector<std::array<double, 16>> serial_a(kTargets), serial_b(kTargets), par_a(kTargets),
      par_b(kTargets);
  int sa = -1, sb = -1, pa = -1, pb = -1;
  run(0, serial_a, sa);
  run(100, serial_b, sb);
  std::thread ta([&] { run(0, par_a, pa); });
  std::thread tb([&] { run(100, par_b, pb); });
  ta.join();
  tb.join();
  EXPECT_EQ(sa, ROPREC_OK);
  EXPECT_EQ(sb, ROPREC_OK);
  EXPECT_EQ(pa, ROPREC_OK);
  EXPECT_EQ(pb, ROPREC_OK);
  EXPECT_EQ(serial_a, par_a);
  EXPECT_EQ(serial_b, par_b);
}

}  // namespace

// ---------------------------------------------------------------- job options

namespace {

const std::string kFanucCell = sourceDir() + "/samples/cells/housing-r2000.xml";
const std::string kFanucProgram = sourceDir() + "/samples/emotor-housing/housing_r2000.ls";

struct Options {
  Options() { EXPECT_EQ(roprec_options_new(&o, err, sizeof err), ROPREC_OK) << err; }
  ~Options() { roprec_options_free(o); }
  Options(const Options&) = delete;
  Options& operator=(const Options&) = delete;
  int set(const char* key, const char* value) {
    return roprec_options_set(o, key, value, err, sizeof err);
  }
  roprec_options* o{nullptr};
  char err[1024]{};
};

}  // namespace

TEST(CApi, OptionsRefuseUnknownKeysAndBadValuesAndStayUnchanged) {
  Options opt;
  EXPECT_EQ(opt.set("frme", "cell"), ROPREC_BAD_INPUT);
  EXPECT_NE(std::string(opt.err).find("unknown option 'frme'"), std::string::npos) << opt.err;
  EXPECT_EQ(opt.set("tool", "flange"), ROPREC_BAD_INPUT);
  EXPECT_STREQ(opt.err, "--tool must be program or cell");
  EXPECT_EQ(opt.set("frame", "1 2 3"), ROPREC_BAD_INPUT);
  EXPECT_NE(std::string(opt.err).find("needs 6 numbers"), std::string::npos) << opt.err;
  EXPECT_EQ(opt.set("force", "yes"), ROPREC_BAD_INPUT);
  EXPECT_EQ(opt.set("orientation", "stiff"), ROPREC_BAD_INPUT);
  EXPECT_EQ(opt.set("match_tol_mm", "-1"), ROPREC_BAD_INPUT);
  EXPECT_EQ(opt.set("threads", "1.5"), ROPREC_BAD_INPUT);
  EXPECT_EQ(opt.set("threads", "-1"), ROPREC_BAD_INPUT);
  EXPECT_EQ(opt.set("frame", nullptr), ROPREC_BAD_INPUT);
  EXPECT_STREQ(opt.err, "value is NULL");
  EXPECT_EQ(roprec_options_new(nullptr, opt.err, sizeof opt.err), ROPREC_BAD_INPUT);
  roprec_options_free(nullptr);
  // The refused values left the defaults: the FANUC sample's controller frames are unresolved.
  char summary[ROPREC_SUMMARY_LEN];
  EXPECT_EQ(roprec_predict_file_ex(kFanucCell.c_str(), kFanucProgram.c_str(), opt.o, nullptr,
                                   summary, sizeof summary, opt.err, sizeof opt.err),
            ROPREC_BAD_INPUT);
  const test::RunResult cli =
      runRoprec("predict --cell '" + kFanucCell + "' '" + kFanucProgram + "' --json -");
  EXPECT_EQ(cli.exit_code, 2);
  EXPECT_EQ(std::string(opt.err), cliErrorText(cli));
}

TEST(CApi, PredictFileExResolvesFramesAndToolAsTheCli) {
  const std::string dir = tempDir("capi-frame");
  const test::RunResult cli =
      runRoprec("predict --cell '" + kFanucCell + "' '" + kFanucProgram +
                "' --frame cell --tool cell --quiet --json '" + dir + "/cli.json'");
  ASSERT_LE(cli.exit_code, 1) << cli.err;
  Options opt;
  ASSERT_EQ(opt.set("frame", "cell"), ROPREC_OK) << opt.err;
  ASSERT_EQ(opt.set("tool", "cell"), ROPREC_OK) << opt.err;
  ASSERT_EQ(opt.set("threads", "2"), ROPREC_OK) << opt.err;  // the same bytes as 1 thread
  char summary[ROPREC_SUMMARY_LEN];
  const std::string out = dir + "/c.json";
  EXPECT_EQ(roprec_predict_file_ex(kFanucCell.c_str(), kFanucProgram.c_str(), opt.o, out.c_str(),
                                   summary, sizeof summary, opt.err, sizeof opt.err),
            cli.exit_code)
      << opt.err;
  EXPECT_EQ(readFile(out), readFile(dir + "/cli.json"));
  const auto j = nlohmann::json::parse(readFile(out));
  bool stated = false;
  for (const auto& n : j.at("notes"))
    stated = stated || n.get<std::string>().rfind("resolution: ", 0) == 0;
  EXPECT_TRUE(stated) << j.at("notes").dump();
  std::filesystem::remove_all(dir);
}

TEST(CApi, CompensateFileExForceAndFrameOptions) {
  const std::string dir = tempDir("capi-force");
  Options opt;
  ASSERT_EQ(opt.set("frame", "cell"), ROPREC_OK) << opt.err;
  ASSERT_EQ(opt.set("tool", "cell"), ROPREC_OK) << opt.err;
  ASSERT_EQ(opt.set("orientation", "keep"), ROPREC_OK) << opt.err;
  char summary[ROPREC_SUMMARY_LEN];
  const std::string once = dir + "/once.ls";
  ASSERT_EQ(
      roprec_compensate_file_ex(kFanucCell.c_str(), kFanucProgram.c_str(), opt.o, once.c_str(),
                                nullptr, summary, sizeof summary, opt.err, sizeof opt.err),
      ROPREC_OK)
      << opt.err;
  const test::RunResult cli =
      runRoprec("compensate --cell '" + kFanucCell + "' '" + kFanucProgram +
                "' --frame cell --tool cell -o '" + dir + "/cli.ls' --quiet");
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  EXPECT_EQ(readFile(once), readFile(dir + "/cli.ls"));
  // Compensating the compensated program again is refused, unless force.
  const std::string twice = dir + "/twice.ls";
  EXPECT_EQ(roprec_compensate_file_ex(kFanucCell.c_str(), once.c_str(), opt.o, twice.c_str(),
                                      nullptr, summary, sizeof summary, opt.err, sizeof opt.err),
            ROPREC_BAD_INPUT);
  EXPECT_NE(std::string(opt.err).find("--force"), std::string::npos) << opt.err;
  EXPECT_FALSE(std::filesystem::exists(twice));
  ASSERT_EQ(opt.set("force", "1"), ROPREC_OK) << opt.err;
  EXPECT_EQ(roprec_compensate_file_ex(kFanucCell.c_str(), once.c_str(), opt.o, twice.c_str(),
                                      nullptr, summary, sizeof summary, opt.err, sizeof opt.err),
            ROPREC_OK)
      << opt.err;
  EXPECT_TRUE(std::filesystem::exists(twice));
  std::filesystem::remove_all(dir);
}

// A milling cell: a RAPID module and a FANUC TP program (each read by windows) compensated on two
// threads with a CSV export give the bytes of the CLI's job on one thread, and the summary counts
// their path points.
TEST(CApi, CompensateFileExOfMillingProgramsIsTheClisJob) {
  const std::string dir = tempDir("capi-milling");
  struct Case {
    std::string cell, program, ext;
    int points;
  };
  const std::vector<Case> cases = {// rapidWallPass(60): 55 linear path points; tpWallPass(60): 63
                                   {test::abbMillingCell(dir), dir + "/wall.mod", ".mod", 55},
                                   {test::fanucMillingCell(dir), dir + "/wall.ls", ".ls", 63}};
  test::writeFile(dir + "/wall.mod", test::rapidWallPass(60));
  test::writeFile(dir + "/wall.ls", test::tpWallPass(60));
  for (const Case& c : cases) {
    SCOPED_TRACE(c.program);
    const std::string cli_out = dir + "/cli" + c.ext;
    const std::string c_out = dir + "/c" + c.ext;
    const test::RunResult cli =
        runRoprec("compensate --cell '" + c.cell + "' '" + c.program + "' -o '" + cli_out +
                  "' --targets '" + dir + "/cli.csv' --quiet");
    ASSERT_EQ(cli.exit_code, 0) << cli.err;
    Options opt;
    ASSERT_EQ(opt.set("threads", "2"), ROPREC_OK) << opt.err;
    char summary[ROPREC_SUMMARY_LEN];
    ASSERT_EQ(roprec_compensate_file_ex(c.cell.c_str(), c.program.c_str(), opt.o, c_out.c_str(),
                                        (dir + "/c.csv").c_str(), summary, sizeof summary, opt.err,
                                        sizeof opt.err),
              ROPREC_OK)
        << opt.err;
    EXPECT_EQ(readFile(c_out), readFile(cli_out));
    EXPECT_EQ(readFile(dir + "/c.csv"), readFile(dir + "/cli.csv"));
    const auto j = nlohmann::json::parse(summary);
    EXPECT_EQ(j.at("process"), "milling");
    EXPECT_EQ(j.at("points"), c.points);
    EXPECT_EQ(j.at("failed"), 0);
    EXPECT_EQ(j.at("written"), nlohmann::json::array({c_out, dir + "/c.csv"}));
  }
  std::filesystem::remove_all(dir);
}

TEST(CApi, VerifyFileExWritesTheCliCardCellAndJsonByteForByte) {
  const std::string dir = tempDir("capi-verify-ex");
  const std::string v = sourceDir() + "/samples/verification/";
  const std::string program = v + "geometry_kr120.src";
  const std::string holes = v + "geometry_kr120_holes.csv";
  const std::string measured = v + "measured_geometry.csv";
  std::filesystem::create_directories(dir + "/cli");
  std::filesystem::create_directories(dir + "/c");
  const test::RunResult cli = runRoprec("verify --cell '" + kCell + "' '" + program +
                                        "' --holes '" + holes + "' --measured '" + measured +
                                        "' --register none --identify all --folds 4 --calibrate '" +
                                        dir + "/cli/card.xml' --write-cell '" + dir +
                                        "/cli/cell.xml' --json '" + dir + "/cli/v.json' --quiet");
  ASSERT_EQ(cli.exit_code, 0) << cli.err << cli.out;
  Options opt;
  ASSERT_EQ(opt.set("holes", holes.c_str()), ROPREC_OK) << opt.err;
  ASSERT_EQ(opt.set("identify", "all"), ROPREC_OK) << opt.err;
  ASSERT_EQ(opt.set("folds", "4"), ROPREC_OK) << opt.err;
  ASSERT_EQ(opt.set("write_cell", (dir + "/c/cell.xml").c_str()), ROPREC_OK) << opt.err;
  EXPECT_EQ(opt.set("folds", "2.5"), ROPREC_BAD_INPUT);
  EXPECT_EQ(opt.set("identify", "everything"), ROPREC_BAD_INPUT);
  char summary[ROPREC_SUMMARY_LEN];
  // the measured file in the system's own separators ("\\" on Windows): the card names it
  // without its folder, as the CLI does
  const std::string measured_native = std::filesystem::path(measured).make_preferred().string();
  ASSERT_EQ(roprec_verify_file_ex(kCell.c_str(), program.c_str(), measured_native.c_str(), "none",
                                  opt.o, (dir + "/c/v.json").c_str(), (dir + "/c/card.xml").c_str(),
                                  summary, sizeof summary, opt.err, sizeof opt.err),
            ROPREC_OK)
      << opt.err;
  for (const char* f : {"/card.xml", "/cell.xml", "/v.json"})
    EXPECT_EQ(readFile(dir + "/c" + f), readFile(dir + "/cli" + f)) << f;
  EXPECT_NE(std::string(summary).find("cell.xml"), std::string::npos) << summary;
  // write_cell with neither a registration nor a new card: nothing to write (2), as the CLI
  const std::string none = dir + "/none.json";
  EXPECT_EQ(roprec_verify_file_ex(kCell.c_str(), program.c_str(), measured.c_str(), "none", opt.o,
                                  none.c_str(), nullptr, summary, sizeof summary, opt.err,
                                  sizeof opt.err),
            ROPREC_BAD_INPUT);
  EXPECT_FALSE(std::filesystem::exists(none));
  std::filesystem::remove_all(dir);
}

}  // namespace roprec
