// Vendor configuration flags (compensator/robot/configuration.hpp): the §7.1 table, independent
// geometric definitions of the branch bits, flags → solution → flags round trips, and the RoboDK
// corpus.
#include "compensator/robot/configuration.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <memory>
#include <random>
#include <regex>
#include <sstream>

#include "compensator/support/error.hpp"
#include "postproc/program.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

Vec6 randomWithinLimits(const ChainDescription& ch, std::mt19937& rng) {
  Vec6 q;
  for (int i = 0; i < 6; ++i) {
    std::uniform_real_distribution<double> u(ch.joints[static_cast<size_t>(i)].lower,
                                             ch.joints[static_cast<size_t>(i)].upper);
    q[i] = u(rng);
  }
  return q;
}

Vec6 deg(double a, double b, double c, double d, double e, double f) {
  Vec6 v;
  v << a, b, c, d, e, f;
  return v * kDeg;
}

/// Frame of joint i (0-based) in the base frame at q: T_B_Ji (the joint rotation not yet applied).
Pose jointFrame(const ChainDescription& ch, const Vec6& q, int i) {
  Pose T = Pose::Identity();
  for (int k = 0; k < i; ++k) {
    T = T * ch.joints[static_cast<size_t>(k)].origin;
    T.rotate(Eigen::AngleAxisd(q[k], ch.joints[static_cast<size_t>(k)].axis));
  }
  return T * ch.joints[static_cast<size_t>(i)].origin;
}

/// §7.1 definitions evaluated directly on the chain (independent of the IK model's formulas):
/// WC = joint-5 origin (axes 4 and 5 meet there in every bundled URDF); shoulder: x of WC in the
/// frame rotating with axis 1; elbow: sign of ((P3 − P2) × (WC − P3)) · ẑ2.
struct DirectBranch {
  double shoulder_x;
  double elbow_sign;
};
DirectBranch direct(const ChainDescription& ch, const Vec6& q) {
  const Pose J1 = jointFrame(ch, q, 0);
  const Pose L1 = J1 * Eigen::AngleAxisd(q[0], ch.joints[0].axis);
  const Vec3 wc = jointFrame(ch, q, 4).translation();
  const Vec3 wc1 = L1.inverse() * wc;  // in the link-1 frame
  const Pose J2 = jointFrame(ch, q, 1);
  const Pose J3 = jointFrame(ch, q, 2);
  const Vec3 z2 = J2.linear() * ch.joints[1].axis;
  const double e = (J3.translation() - J2.translation()).cross(wc - J3.translation()).dot(z2);
  return {wc1.x(), e};
}

TEST(Configuration, BranchBitsMatchTheDirectGeometricDefinition) {
  for (const std::string& name : bundledRobotNames()) {
    SCOPED_TRACE(name);
    const Robot robot = loadRobot({name, "", ""});
    const IkModel m = buildIkModel(robot);
    const Vec6 ref = vendorReferencePose(robot.card);
    const DirectBranch dref = direct(robot.chain, ref);
    ASSERT_GT(dref.shoulder_x, 0.0) << "the reference pose is in front (link-1 x ≥ 0)";
    EXPECT_EQ(ikBranch(m, ref).index(), 0) << "reference pose: front, elbow up, θ5 = 0";
    std::mt19937 rng(5);
    for (int n = 0; n < 1000; ++n) {
      const Vec6 q = randomWithinLimits(robot.chain, rng);
      const DirectBranch d = direct(robot.chain, q);
      const IkBranch b = ikBranch(m, q);
      if (std::abs(d.shoulder_x) > 1e-9) {
        EXPECT_EQ(b.shoulder, d.shoulder_x >= 0 ? 0 : 1);
      }
      if (std::abs(d.elbow_sign) > 1e-9) {
        EXPECT_EQ(b.elbow, (d.elbow_sign > 0) == (dref.elbow_sign > 0) ? 0 : 1);
      }
      const double t5 = toControllerJoints(robot.card, q)[4];
      EXPECT_EQ(b.wrist, t5 < 0 ? 1 : 0);
    }
  }
}

TEST(Configuration, Section71TableKukaAndFanucLetters) {
  // docs/programs.md §7.1: branch → KUKA S (bits 2,1,0) and FANUC letters.
  const int kukaS[8] = {2, 6, 0, 4, 3, 7, 1, 5};
  const char* fanuc[8] = {"F U T", "N U T", "F D T", "N D T", "F U B", "N U B", "F D B", "N D B"};
  int covered = 0;
  std::array<bool, 8> seen{};
  for (const std::string& name : bundledRobotNames()) {
    const Robot robot = loadRobot({name, "", ""});
    const IkModel m = buildIkModel(robot);
    std::mt19937 rng(11);
    for (int n = 0; n < 200; ++n) {
      const Vec6 q = randomWithinLimits(robot.chain, rng);
      const int b = ikBranch(m, q).index();
      seen[static_cast<size_t>(b)] = true;
      const KukaConfig k = kukaConfig(m, robot.card, q);
      EXPECT_EQ(*k.status, kukaS[b]);
      EXPECT_EQ(formatFanuc(fanucConfig(m, robot.card, q)).substr(0, 5), fanuc[b]);
      EXPECT_EQ(abbConfig(m, robot.card, q).cfx, b);
      VendorConfig v;
      v.vendor = Vendor::kKuka;
      v.kuka = k;
      EXPECT_EQ(branchOfConfig(v), b);
      ++covered;
    }
  }
  if (covered == 0) GTEST_SKIP() << "no bundled robots";
  for (bool s : seen) EXPECT_TRUE(s) << "every branch occurs among the random poses";
}

TEST(Configuration, TurnAndQuadrantRules) {
  // ABB cf = floor(θ/90°) [S13 p.165]; RoboDK writes θ6 = −180° as −2 [S8].
  EXPECT_EQ(abbQuadrant(0.0), 0);
  EXPECT_EQ(abbQuadrant(89.9 * kDeg), 0);
  EXPECT_EQ(abbQuadrant(90.0 * kDeg), 1);
  EXPECT_EQ(abbQuadrant(-0.1 * kDeg), -1);
  EXPECT_EQ(abbQuadrant(-90.0 * kDeg), -1);
  EXPECT_EQ(abbQuadrant(-90.1 * kDeg), -2);
  EXPECT_EQ(abbQuadrant(-180.0 * kDeg), -2);
  EXPECT_EQ(abbQuadrant(-180.0 * kDeg * (1 + 1e-14)), -2);
  EXPECT_EQ(abbQuadrant(-180.0 * kDeg * (1 + 1e-6)), -3);
  EXPECT_EQ(abbQuadrant(350.0 * kDeg), 3);
  // FANUC angle_2_turn [S8].
  EXPECT_EQ(fanucTurn(179.9 * kDeg), 0);
  EXPECT_EQ(fanucTurn(180.0 * kDeg), 1);
  EXPECT_EQ(fanucTurn(539.0 * kDeg), 1);
  EXPECT_EQ(fanucTurn(-179.9 * kDeg), 0);
  EXPECT_EQ(fanucTurn(-180.0 * kDeg), -1);
  EXPECT_EQ(fanucTurn(-300.0 * kDeg), -1);
  // KUKA T bit n ⇔ A(n+1) < 0; §2.4 example: T 34 = 'B100010' → A2 < 0, A6 < 0.
  if (bundledRobotNames().empty()) return;
  const Robot robot = loadRobot({"kuka-kr120-r2500-pro", "", ""});
  const IkModel m = buildIkModel(robot);
  EXPECT_EQ(*kukaConfig(m, robot.card, deg(10, -80, 100, 5, 30, -20)).turn, 34);
  EXPECT_EQ(*kukaConfig(m, robot.card, deg(-10, -80, 100, 5, 30, -20)).turn, 35);
}

TEST(Configuration, FlagsToSolutionToFlagsRoundTrip) {
  if (bundledRobotNames().empty()) GTEST_SKIP() << "no bundled robots";
  std::vector<std::pair<Robot, IkModel>> robots;
  for (const std::string& name : bundledRobotNames()) {
    Robot r = loadRobot({name, "", ""});
    IkModel m = buildIkModel(r);
    robots.emplace_back(std::move(r), std::move(m));
  }
  // A generic robot (bare URDF): the branch index alone.
  {
    Robot r = robots.front().first;
    r.card = RobotCard{};
    for (size_t i = 0; i < 6; ++i) r.card.joints[i].name = r.chain.joints[i].name;
    IkModel m = buildIkModel(r);
    robots.emplace_back(std::move(r), std::move(m));
  }
  for (const auto& [robot, m] : robots) {
    SCOPED_TRACE(robot.card.name + " " + vendorName(robot.card.vendor));
    std::mt19937 rng(17);
    int exact = 0;
    for (int n = 0; n < 300; ++n) {
      const Vec6 q = randomWithinLimits(robot.chain, rng);
      const IkBranch b = ikBranch(m, q);
      if (b.wrist_margin_rad < 1e-6 || b.elbow_margin_rad < 1e-6 || b.shoulder_margin_m < 1e-6)
        continue;
      const VendorConfig flags = configurationOf(m, robot.card, q);
      // Through the text form, as a program would carry it.
      const VendorConfig parsed = parseConfig(robot.card.vendor, formatConfig(flags));
      EXPECT_EQ(formatConfig(parsed), formatConfig(flags));
      const Pose T = chainForwardKinematics(robot.chain, q);
      const ConfiguredSolution s = solveIkWithConfiguration(m, robot.card, T, parsed);
      ASSERT_TRUE(s.found) << s.reason;
      EXPECT_TRUE(s.exact) << s.reason;
      EXPECT_EQ(formatConfig(configurationOf(m, robot.card, s.solution.q)), formatConfig(flags));
      if (robot.card.vendor != Vendor::kGeneric) {
        // Branch + turn flags pin the joint vector down completely for these robots.
        EXPECT_LE((s.solution.q - q).cwiseAbs().maxCoeff(), 1e-9) << formatConfig(flags);
      }
      exact += s.exact ? 1 : 0;
    }
    EXPECT_GT(exact, 250);
  }
}

TEST(Configuration, ParseAndFormat) {
  const KukaConfig k = parseKuka("S 'B010' T 'B100010'");
  EXPECT_EQ(*k.status, 2);
  EXPECT_EQ(*k.turn, 34);
  EXPECT_EQ(formatKuka(k), "S 2 T 34");
  EXPECT_EQ(formatKuka(parseKuka("{S 6, T 35}")), "S 6 T 35");
  EXPECT_EQ(formatKuka(parseKuka("s 18 t 0")), "S 18 T 0");
  EXPECT_FALSE(parseKuka("T 3").status.has_value());
  EXPECT_EQ(formatAbb(parseAbb("[0,-1,2,1]")), "[0,-1,2,1]");
  EXPECT_EQ(formatAbb(parseAbb(" 0 -1 , 2 1 ")), "[0,-1,2,1]");
  EXPECT_EQ(formatFanuc(parseFanuc("'N U T, 0, 0, 0'")), "N U T, 0, 0, 0");
  EXPECT_EQ(formatFanuc(parseFanuc("FDB,1,-1,0")), "F D B, 1, -1, 0");
  EXPECT_EQ(*branchOfConfig(parseConfig(Vendor::kFanuc, "F D B, 1, -1, 0")), 6);
  EXPECT_EQ(*branchOfConfig(parseConfig(Vendor::kKuka, "S 5 T 0")), 7);
  EXPECT_EQ(parseConfig(Vendor::kGeneric, "branch 5").branch, 5);
}

TEST(Configuration, ParseErrorsNameTheContext) {
  auto expectError = [](auto fn, const std::string& needle) {
    try {
      fn();
      ADD_FAILURE() << "expected InputError containing " << needle;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "prog.src");
      EXPECT_EQ(e.line(), 12);
      EXPECT_NE(e.message().find(needle), std::string::npos) << e.message();
    }
  };
  expectError([] { parseKuka("S x T 2", "prog.src", 12); }, "not a non-negative integer");
  expectError([] { parseKuka("Q 2", "prog.src", 12); }, "unknown field");
  expectError([] { parseKuka("S 2 T 64", "prog.src", 12); }, "beyond axis 6");
  expectError([] { parseKuka("S 'B012'", "prog.src", 12); }, "not a non-negative integer");
  expectError([] { parseAbb("[0,1,2]", "prog.src", 12); }, "needs 4 integers");
  expectError([] { parseAbb("[0,1,2,9]", "prog.src", 12); }, "cfx must be 0..7");
  expectError([] { parseAbb("[0,1,2,1", "prog.src", 12); }, "missing ']'");
  expectError([] { parseFanuc("X U T, 0, 0, 0", "prog.src", 12); }, "first letter");
  expectError([] { parseFanuc("N U T, 0, 0", "prog.src", 12); }, "three turn numbers");
  expectError([] { parseFanuc("N U T, a, 0, 0", "prog.src", 12); }, "not an integer");
  expectError([] { parseConfig(Vendor::kGeneric, "branch 9", "prog.src", 12); }, "0..7");
}

TEST(Configuration, ReverseReportsMissingBranch) {
  if (bundledRobotNames().empty()) GTEST_SKIP() << "no bundled robots";
  const Robot robot = loadRobot({"abb-irb6640-185-280", "", ""});
  const IkModel m = buildIkModel(robot);
  const Pose T = chainForwardKinematics(robot.chain, deg(0, 10, 20, 0, 30, 0));
  // Shoulder-back branches of this pose violate the joint limits of axis 3 (−180°…70°) or 2.
  int missing = 0;
  for (int b = 0; b < 8; ++b) {
    VendorConfig v;
    v.vendor = Vendor::kAbb;
    v.abb.cfx = b;
    const ConfiguredSolution s = solveIkWithConfiguration(m, robot.card, T, v);
    if (!s.found) {
      ++missing;
      EXPECT_NE(s.reason.find("branch"), std::string::npos) << s.reason;
    } else {
      EXPECT_EQ(s.solution.branch.index(), b);
    }
  }
  EXPECT_GT(missing, 0);
  Pose far = Pose::Identity();
  far.translation() = Vec3(9, 0, 0);
  VendorConfig v;
  v.vendor = Vendor::kAbb;
  const ConfiguredSolution s = solveIkWithConfiguration(m, robot.card, far, v);
  EXPECT_FALSE(s.found);
  EXPECT_NE(s.reason.find("unreachable"), std::string::npos);
}

// ---- RoboDK corpus: where the programs carry flags and the target lists carry joints ----

std::vector<Vec6> readTargetJoints(const std::string& csv,
                                   std::vector<std::string>* moves = nullptr) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<Vec6> out;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string cell;
    std::vector<std::string> cells;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    if (cells.size() < 10) continue;
    if (moves) moves->push_back(cells[0]);
    Vec6 q;
    for (int i = 0; i < 6; ++i) q[i] = std::stod(cells[4 + static_cast<size_t>(i)]) * kDeg;
    out.push_back(q);
  }
  return out;
}

TEST(ConfigurationCorpus, AbbConfdataFromRoboDk) {
  const std::string corpus = test::corpusDir();
  if (corpus.empty() || bundledRobotNames().empty()) GTEST_SKIP() << "no corpus or bundled robots";
  const std::string mod = test::readFile(corpus + "/robodk/DrillIRC5.mod");
  std::vector<std::string> moves;
  const auto joints = readTargetJoints(corpus + "/robodk/DrillIRC5_targets.csv", &moves);
  const std::regex conf(R"(MoveL \[\[[^\]]*\],\[[^\]]*\],(\[-?\d+,-?\d+,-?\d+,-?\d+\]))");
  std::vector<std::string> confs;
  for (std::sregex_iterator it(mod.begin(), mod.end(), conf), end; it != end; ++it)
    confs.push_back((*it)[1]);
  const Robot robot = loadRobot({"abb-irb6640-185-280", "", ""});
  const IkModel m = buildIkModel(robot);
  size_t c = 0;
  for (size_t i = 0; i < joints.size(); ++i) {
    if (moves[i] != "L") continue;
    ASSERT_LT(c, confs.size());
    const Vec6 q = fromControllerJoints(robot.card, joints[i]);
    EXPECT_EQ(formatAbb(abbConfig(m, robot.card, q)), confs[c]) << "target row " << i + 1;
    // Flags → solution: the program's confdata selects exactly the joints RoboDK computed.
    const ConfiguredSolution s = solveIkWithConfiguration(
        m, robot.card, chainForwardKinematics(robot.chain, q), parseConfig(Vendor::kAbb, confs[c]));
    ASSERT_TRUE(s.found) << s.reason;
    EXPECT_TRUE(s.exact);
    EXPECT_LE((s.solution.q - q).cwiseAbs().maxCoeff(), 1e-9);
    ++c;
  }
  EXPECT_EQ(c, confs.size());
  EXPECT_EQ(c, 15u);
}

TEST(ConfigurationCorpus, CompensatingRoboDkRapidKeepsTheProgrammedConfdata) {
  // RoboDK's IRB 6640 drilling program: MoveAbsJ approaches (J6 = +180°, −178.36°, −176.73°), then
  // MoveL targets with confdata [0,0,-2,0] under ConfL\Off. The compensated program must keep
  // cf6 = −2 on all 15 MoveL (the offset is a few µm) and choose the joints the program's own
  // MoveAbsJ starts from (J6 = −178.4° for the second hole, not +181.6°).
  const std::string corpus = test::corpusDir();
  if (corpus.empty() || bundledRobotNames().empty()) GTEST_SKIP() << "no corpus or bundled robots";
  const std::string dir = test::tempDir("irc5");
  test::writeFile(dir + "/cell.xml", R"(<?xml version="1.0" encoding="UTF-8"?>
<cell name="robodk-irc5">
  <robot ref="abb-irb6640-185-280"/>
  <tool name="spindle" xyz="0 0 250" rpy="0 0 0" mass_kg="25.8" com_mm="0 0 120" inertia_kgm2="0.35 0 0 0.33 0 0.08"/>
  <workobject xyz="1400 0 400" rpy="0 0 0"/>
  <process type="drilling">
    <drill diameter_mm="8.5" point_angle_deg="140" helix_angle_deg="30" web_mm="1.2" chisel_angle_deg="125" tool_material="carbide" stickout_mm="34"/>
    <cut feed_mm_per_rev="0.2" spindle_rpm="6000" depth_mm="20"/>
    <material name="AlSi9Cu3"/>
  </process>
  <tolerance position_mm="0.2"/>
  <uncertainty method="linear" stiffness_rel="0.10" position_gain_rel="0.20" process_halfwidth="0.15"/>
</cell>
)");
  const std::string mod = corpus + "/robodk/DrillIRC5.mod";
  // (flip-free: the 358° axis-6 turn between the first two MoveAbsJ is the program's own joint
  // move, not a jump the rotation about the drill axis could remove)
  for (const char* mode : {"keep", "flip-free"}) {
    SCOPED_TRACE(mode);
    const auto r =
        test::runRoprec("compensate --cell '" + dir + "/cell.xml' '" + mod + "' -o '" + dir +
                        "/out.mod' --targets '" + dir + "/t.json' --orientation " + mode);
    ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
    const std::string out = test::readFile(dir + "/out.mod");
    const std::regex conf(R"(MoveL \[\[[^\]]*\],\[[^\]]*\],(\[-?\d+,-?\d+,-?\d+,-?\d+\]))");
    int n = 0;
    for (std::sregex_iterator it(out.begin(), out.end(), conf), end; it != end; ++it) {
      EXPECT_EQ((*it)[1], "[0,0,-2,0]");
      ++n;
    }
    EXPECT_EQ(n, 15);
    // the joints: J6 of holes 2 and 3 as the program's MoveAbsJ (−178.36°, −176.73°), within the
    // compensation's few millidegrees
    const std::string t = test::readFile(dir + "/t.json");
    const nlohmann::json tj = nlohmann::json::parse(t);
    std::vector<double> q6;
    for (const auto& h : tj["holes"]) {
      q6.push_back(h["programmed"]["joints_deg"][5].get<double>());
      EXPECT_EQ(h["programmed"]["config"], "[0,0,-2,0]");
    }
    ASSERT_EQ(q6.size(), 3u) << t;
    EXPECT_NEAR(std::abs(q6[0]), 180.0, 0.01);
    EXPECT_NEAR(q6[1], -178.363, 0.01);
    EXPECT_NEAR(q6[2], -176.730, 0.01);
  }
}

TEST(ConfigurationCorpus, FanucConfigFromRoboDk) {
  const std::string corpus = test::corpusDir();
  if (corpus.empty() || bundledRobotNames().empty()) GTEST_SKIP() << "no corpus or bundled robots";
  const std::string ls = test::readFile(corpus + "/robodk/DRILLR30IA.LS");
  const auto joints = readTargetJoints(corpus + "/robodk/DRILLR30IA_targets.csv");
  const std::regex pos(R"(P\[(\d+)\]\{[^}]*?CONFIG : '([^']*)')");
  const Robot robot = loadRobot({"fanuc-r2000ic-165f", "", ""});
  const IkModel m = buildIkModel(robot);
  int checked = 0;
  for (std::sregex_iterator it(ls.begin(), ls.end(), pos), end; it != end; ++it) {
    const size_t idx = static_cast<size_t>(std::stoi((*it)[1])) - 1;
    ASSERT_LT(idx, joints.size());
    const std::string config = (*it)[2];
    const Vec6 q = fromControllerJoints(robot.card, joints[idx]);
    EXPECT_EQ(formatFanuc(fanucConfig(m, robot.card, q)), config) << "P[" << idx + 1 << "]";
    const ConfiguredSolution s = solveIkWithConfiguration(
        m, robot.card, chainForwardKinematics(robot.chain, q), parseConfig(Vendor::kFanuc, config));
    ASSERT_TRUE(s.found) << s.reason;
    EXPECT_TRUE(s.exact);
    EXPECT_LE((s.solution.q - q).cwiseAbs().maxCoeff(), 1e-9);
    ++checked;
  }
  EXPECT_EQ(checked, 15);
}

TEST(ConfigurationCorpus, KukaTargetsHaveNoStatusTurnButGetTheTaughtDefault) {
  const std::string corpus = test::corpusDir();
  if (corpus.empty() || bundledRobotNames().empty()) GTEST_SKIP() << "no corpus or bundled robots";
  // The 2018 RoboDK KUKA posts write E6POS without S/T (corpus README): nothing to compare with.
  const std::string dat = test::readFile(corpus + "/robodk/DrillKRC2DAT.dat");
  EXPECT_EQ(dat.find(",S "), std::string::npos);
  // Our flags for the RoboDK joints: front, elbow up, A5 > 0 → S 2 (the posture taught programs
  // carry most often [S11]); T from the signs: A2 < 0 (+ A1 < 0, A6 < 0 where applicable).
  const auto joints = readTargetJoints(corpus + "/robodk/DrillKRC2DAT_targets.csv");
  const Robot robot = loadRobot({"kuka-kr120-r2500-pro", "", ""});
  const IkModel m = buildIkModel(robot);
  for (const Vec6& qc : joints) {
    const Vec6 q = fromControllerJoints(robot.card, qc);
    const KukaConfig k = kukaConfig(m, robot.card, q);
    EXPECT_EQ(*k.status, 2);
    int t = 0;
    for (int n = 0; n < 6; ++n) t |= (qc[n] < 0 ? 1 : 0) << n;
    EXPECT_EQ(*k.turn, t);
    const ConfiguredSolution s =
        solveIkWithConfiguration(m, robot.card, chainForwardKinematics(robot.chain, q),
                                 VendorConfig{Vendor::kKuka, k, {}, {}, 0});
    ASSERT_TRUE(s.found);
    EXPECT_LE((s.solution.q - q).cwiseAbs().maxCoeff(), 1e-9);
  }
}

TEST(ConfigurationCorpus, CompensatedKukaAndFanucCorpusProgramsKeepTheirFlagsAndRotations) {
  // RoboDK's KRC4, KRC2 (.src + .dat) and R-30iA drilling programs, compensated in every
  // orientation mode: no target's configuration (KUKA S/T, FANUC CONFIG and turns) and no
  // rotation about a drill axis changes (the summary says "0 holes"); the programs' targets are
  // compared one by one, original against written.
  const std::string corpus = test::corpusDir();
  if (corpus.empty() || bundledRobotNames().empty()) GTEST_SKIP() << "no corpus or bundled robots";
  const std::string cells = test::sourceDir() + "/samples/cells/";
  struct Case {
    const char* program;
    const char* out;
    std::string cell;
    const char* options;
  };
  const Case cases[] = {
      {"DrillKRC4.src", "k4.src", cells + "housing-kr120.xml", "--tool program"},
      {"DrillKRC2DAT.src", "k2.src", cells + "housing-kr120.xml", "--tool program"},
      {"DRILLR30IA.LS", "f.ls", cells + "housing-r2000.xml", "--frame cell --tool cell"},
  };
  const std::string dir = test::tempDir("corpus-flags");
  for (const Case& c : cases) {
    const std::string in = corpus + "/robodk/" + c.program;
    const postproc::Program before = postproc::readProgram(in);
    for (const char* mode : {"keep", "flip-free", "stiffest"}) {
      SCOPED_TRACE(std::string(c.program) + " " + mode);
      const std::string out = dir + "/" + mode + "-" + c.out;
      const auto r = test::runRoprec("compensate --cell '" + c.cell + "' '" + in + "' -o '" + out +
                                     "' " + c.options + " --orientation " + mode);
      ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
      const std::string said = r.out + r.err;
      EXPECT_NE(said.find("rotation about the drill axis changed at 0 holes"), std::string::npos)
          << said;
      EXPECT_NE(said.find("configuration flags changed at 0 holes"), std::string::npos) << said;
      const postproc::Program after = postproc::readProgram(out);
      ASSERT_EQ(after.targets().size(), before.targets().size());
      int moved = 0;
      for (size_t t = 0; t < before.targets().size(); ++t) {
        const postproc::Target& a = before.targets()[t];
        const postproc::Target& b = after.targets()[t];
        EXPECT_EQ(b.config.text(), a.config.text()) << "target " << t << " line " << a.line;
        // the compensation tilts the tool axis by its small correction; the rotation about the
        // drill (tool z) axis stays as programmed
        if (a.kind == postproc::TargetKind::kCartesian && postproc::targetComplete(a)) {
          const Pose Ta = postproc::targetPose(before, a);
          const Pose Tb = postproc::targetPose(after, b);
          const Eigen::AngleAxisd d(Mat3(Ta.linear().transpose() * Tb.linear()));
          const Eigen::Vector3d w = d.angle() * d.axis();
          EXPECT_LT(std::abs(w.z()), 1e-3 * kDeg) << "target " << t << " line " << a.line;
          EXPECT_LT(w.norm(), 0.5 * kDeg) << "target " << t << " line " << a.line;
        }
        moved += b.pos[0].value != a.pos[0].value || b.pos[2].value != a.pos[2].value;
      }
      EXPECT_GT(moved, 0);  // the compensation did write something
    }
  }
}

}  // namespace
}  // namespace roprec
