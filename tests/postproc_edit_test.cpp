// Edits: number style, only the changed tokens change, configuration flags, refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <tuple>
#include <utility>
#include <vector>

#include "compensator/support/error.hpp"
#include "postproc/drill.hpp"
#include "postproc/program.hpp"
#include "tests/support/test_support.hpp"

namespace roprec::postproc {
namespace {

std::string fixtures() { return test::sourceDir() + "/tests/data/programs"; }

TEST(PostprocNumberStyle, PrintsInTheStyleOfTheReplacedToken) {
  NumberHints kss{3, true, false};
  EXPECT_EQ(formatLike("-31.6425190", -31.5, kss), "-31.5000000");  // KSS: 9 significant digits
  EXPECT_EQ(formatLike("0.266879767", 0.1234567891, kss), "0.123456789");
  EXPECT_EQ(formatLike("-3704.29346", 1234.5, kss), "1234.50000");
  const NumberHints mm{3, false, false};
  EXPECT_EQ(formatLike("2.000", 2.0123456, mm), "2.012");  // RoboDK %.3f
  EXPECT_EQ(formatLike("-0.000", 1e-17, mm), "-0.000");    // sign of zero kept
  EXPECT_EQ(formatLike("0.000", -0.0004, mm), "0.000");
  EXPECT_EQ(formatLike("0", 12.5, mm), "12.500");  // integers gain µm resolution
  EXPECT_EQ(formatLike("1400.0", 1400.0234, mm), "1400.023");
  const NumberHints fanuc{3, false, true};
  EXPECT_EQ(formatLike("-.242", -0.5, fanuc), "-.500");  // FANUC: no leading zero
  EXPECT_EQ(formatLike("1000.000", 0.25, fanuc), ".250");
  EXPECT_EQ(formatLike(".000", 0.0, fanuc), ".000");
  EXPECT_EQ(formatLike("0.000", 0.0, fanuc), "0.000");
  const NumberHints quat{9, false, false};
  EXPECT_EQ(formatLike("9E+09", 9e9, mm), "9E+09");  // RAPID controller %G
  EXPECT_EQ(formatLike("-9.43398E-06", 1.2345678e-5, quat), "1.2345678E-05");
  EXPECT_EQ(formatLike("0.999998", 0.5, quat), "0.500000000");
  EXPECT_EQ(formatLike("+5.0", 6.0, mm), "+6.000");
  EXPECT_FALSE(parseNumber("1.2.3").has_value());
  EXPECT_FALSE(parseNumber("-").has_value());
  EXPECT_EQ(parseNumber("-245E-2").value_or(0), -2.45);
  EXPECT_EQ(parseNumber(".5").value_or(0), 0.5);
}

// Changing one target changes only the bytes of that target's numeric tokens.
void expectOnlyTargetChanges(const std::string& path, const std::string& name) {
  SCOPED_TRACE(path + " " + name);
  Program p = readProgram(path);
  int idx = -1;
  for (std::size_t i = 0; i < p.targets().size(); ++i) {
    if (p.targets()[i].name == name) idx = static_cast<int>(i);
  }
  ASSERT_GE(idx, 0);
  const Target before = p.targets()[static_cast<std::size_t>(idx)];
  Pose T = targetPose(p, before);
  T.translation() += Vec3(0.1234, -0.0567, 0.0891) * 1e-3;
  T.linear() =
      T.linear() * Eigen::AngleAxisd(0.01 * kDeg, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const EditResult r = replaceTargetPose(p, idx, T);
  ASSERT_TRUE(r.ok) << r.reason;
  ASSERT_FALSE(p.edits.empty());
  std::uint32_t lo = UINT32_MAX;
  std::uint32_t hi = 0;
  for (const NumberField* f : {&before.pos[0], &before.pos[1], &before.pos[2], &before.rot[0],
                               &before.rot[1], &before.rot[2], &before.rot[3]}) {
    if (!f->present()) continue;
    lo = std::min(lo, f->offset - f->pad);
    hi = std::max(hi, f->offset + f->length);
  }
  const auto out = renderFiles(p);
  for (std::size_t fi = 0; fi < out.size(); ++fi) {
    const std::string& a = p.files[fi].bytes;
    const std::string& b = out[fi];
    if (static_cast<int>(fi) != before.file) {
      EXPECT_TRUE(a == b);
      continue;
    }
    std::size_t pre = 0;
    while (pre < a.size() && pre < b.size() && a[pre] == b[pre]) ++pre;
    std::size_t suf = 0;
    while (suf < a.size() - pre && suf < b.size() - pre &&
           a[a.size() - 1 - suf] == b[b.size() - 1 - suf])
      ++suf;
    EXPECT_GE(pre, lo);
    EXPECT_GE(suf, a.size() - hi);
  }
  // the written file reads back to the new pose (within the token resolution)
  const std::string dir = test::tempDir("edit");
  const std::string out_path =
      dir + "/" + std::filesystem::path(p.files[0].path).filename().string();
  writeProgram(p, out_path);
  const Program q = readProgram(out_path);
  const Pose T2 = targetPose(q, q.targets()[static_cast<std::size_t>(idx)]);
  EXPECT_LT((T2.translation() - T.translation()).norm() * 1e3, 1e-3);
  if (before.orientation == Orientation::kAxis) {  // hole list: only the drilling axis is stored
    EXPECT_LT((T2.linear().col(2) - T.linear().col(2)).norm(), 2e-6);
  } else {
    EXPECT_LT(smallRotationDifference(T2.linear(), T.linear()).norm(), 2e-5);
  }
}

// setNumber queues a token's new text exactly when it differs from the text of the token's own
// value in the same style (else it drops the pending edit): values a few units of the last place
// apart, on both sides of each rounding, in the styles of positions, KSS, FANUC, RAPID's %G and
// signed or integer tokens, and seeded values far apart.
TEST(PostprocEdit, SetNumberWritesATokenWhenItsTextChanges) {
  const std::vector<std::pair<const char*, NumberHints>> cases = {
      {"-293.400", {5, false, false}}, {"300.000", {3, false, false}},
      {"0", {3, false, false}},        {"-31.6425190", {3, true, false}},
      {"-.242", {3, false, true}},     {"+5.0", {3, false, false}},
      {"-0.000", {3, false, false}},   {"1.5E-03", {3, false, false}},
      {"0.999998", {9, false, false}}, {"1400", {0, false, false}}};
  std::mt19937 rng(20261128);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const auto& [token, h] : cases) {
    SCOPED_TRACE(token);
    const double v0 = *parseNumber(token);
    std::vector<double> values{v0, -v0, 0.0};
    for (int d = 0; d <= 10; ++d) {
      const double place = std::pow(10.0, -d);
      for (const double k : {0.3, 0.5, 0.7, 1.0, 1.5, 1.9, 2.0, 2.1, 2.5, 3.0, 7.0})
        for (const double sign : {-1.0, 1.0}) values.push_back(v0 + sign * k * place);
      for (int i = 0; i < 20; ++i) values.push_back(v0 + unit(rng) * 5.0 * place);
    }
    for (int i = 0; i < 50; ++i) values.push_back(unit(rng) * 1e4);
    for (const double v : values) {
      Program p;
      p.files.push_back(SourceFile{});
      p.files[0].bytes = token;
      NumberField f;
      f.file = 0;
      f.length = static_cast<std::uint16_t>(p.files[0].bytes.size());
      f.value = v0;
      setNumber(p, f, v, h);
      const std::string want = formatLike(token, v, h);
      const bool changed = want != formatLike(token, v0, h);
      ASSERT_EQ(p.edits.size(), changed ? 1U : 0U) << v;
      if (changed) {
        EXPECT_EQ(p.edits.begin()->second.text, want) << v;
      }
    }
  }
}

TEST(PostprocEdit, ChangingOneTargetChangesOnlyItsTokens) {
  expectOnlyTargetChanges(fixtures() + "/kss_drill.src", "xp2");
  expectOnlyTargetChanges(fixtures() + "/kss_drill.src", "XP1");
  expectOnlyTargetChanges(fixtures() + "/rapid_drill.mod", "pH2");
  expectOnlyTargetChanges(fixtures() + "/tp_controller.ls", "P[3]");
  expectOnlyTargetChanges(fixtures() + "/targets_rxyz.csv", "T2");
  expectOnlyTargetChanges(fixtures() + "/targets.json", "P2");
  expectOnlyTargetChanges(fixtures() + "/holes.csv", "H2");
  if (!test::corpusDir().empty()) {
    expectOnlyTargetChanges(test::corpusDir() + "/robodk/DrillKRC2DAT.src", "XP5");
    expectOnlyTargetChanges(test::corpusDir() + "/robodk/DRILLR30IA.LS", "P[11]");
  }
}

TEST(PostprocEdit, FanucFieldsStayRightAligned) {
  Program p = readProgram(fixtures() + "/tp_controller.ls");
  const int idx = 2;  // P[3]
  ASSERT_EQ(p.targets()[idx].name, "P[3]");
  Pose T = targetPose(p, p.targets()[idx]);
  T.translation().z() = -0.25e-3;
  ASSERT_TRUE(replaceTargetPose(p, idx, T).ok);
  const std::string out = renderFiles(p)[0];
  EXPECT_NE(out.find("\tZ =     -.250  mm,"), std::string::npos);
  EXPECT_EQ(out.size(), p.files[0].bytes.size());
}

Program fromText(Dialect d, const std::string& name, const std::string& text,
                 std::optional<std::string> dat = std::nullopt) {
  return parseProgram(d, name, text, std::move(dat), "x.dat");
}

TEST(PostprocEdit, KukaStatusTurnKeepTheirLiteralStyleAndAreInsertedWhenAbsent) {
  Program p = readProgram(fixtures() + "/kss_drill.src");
  ASSERT_EQ(p.targets()[0].name, "XP1");
  Configuration c = p.targets()[0].config;
  EXPECT_EQ(c.status, 22);
  EXPECT_EQ(c.turn, 27);
  c.status = 6;
  c.turn = 2;
  ASSERT_TRUE(replaceTargetPose(p, 0, targetPose(p, p.targets()[0]), c).ok);
  const std::string dat = renderFiles(p)[1];
  EXPECT_NE(dat.find("S 'B00000110',T 'B00000010',E1"), std::string::npos);
  // RoboDK writes E6POS without S/T: explicit flags are appended inside the aggregate
  Program q = fromText(Dialect::kKrl, "x.src", "DEF x( )\nLIN XP1\nEND\n",
                       std::string("DEFDAT x\nDECL E6POS XP1={X 1.000,Y 2.000,Z 3.000,A 0.000,B "
                                   "0.000,C 180.000}\nENDDAT\n"));
  Configuration k;
  k.vendor = Vendor::kKuka;
  k.status = 2;
  k.turn = 35;
  ASSERT_TRUE(replaceTargetPose(q, 0, targetPose(q, q.targets()[0]), k).ok);
  EXPECT_NE(renderFiles(q)[1].find("C 180.000,S 2,T 35}"), std::string::npos);
  // a configuration of another vendor is refused
  Configuration a;
  a.vendor = Vendor::kAbb;
  EXPECT_FALSE(replaceTargetPose(q, 0, targetPose(q, q.targets()[0]), a).ok);
}

TEST(PostprocEdit, AbbQuaternionKeepsItsSignAndConfdataChanges) {
  Program p = readProgram(fixtures() + "/rapid_drill.mod");
  ASSERT_EQ(p.targets()[1].name, "pH2");  // q = [0,1,0,0]
  Pose T = targetPose(p, p.targets()[1]);
  T.linear() = T.linear() * Eigen::AngleAxisd(0.5 * kDeg, Vec3::UnitZ()).toRotationMatrix();
  Configuration c = p.targets()[1].config;
  c.cf = {0, -1, -2, 1};
  ASSERT_TRUE(replaceTargetPose(p, 1, T, c).ok);
  const Target& t = p.targets()[1];
  const Eigen::Vector4d q(t.rot[0].value, t.rot[1].value, t.rot[2].value, t.rot[3].value);
  EXPECT_NEAR(q.norm(), 1.0, 1e-12);
  EXPECT_GT(q[1], 0.99);  // same hemisphere as the old [0,1,0,0]
  EXPECT_NE(renderFiles(p)[0].find("[0,-1,-2,1]"), std::string::npos);
}

TEST(PostprocEdit, FanucTurnDigitsRefusedWhileTurnAxesUnknown) {
  Program p = readProgram(fixtures() + "/tp_controller.ls");
  const Target& t = p.targets()[0];
  Configuration c = t.config;
  c.flip = 'F';
  ASSERT_TRUE(replaceTargetPose(p, 0, targetPose(p, t), c).ok);
  EXPECT_NE(renderFiles(p)[0].find("CONFIG : 'F U T, 0, 0, 0'"), std::string::npos);
  Program q = readProgram(fixtures() + "/tp_controller.ls");
  Configuration d = q.targets()[0].config;
  d.turns = {0, 1, 0};  // J4 (RoboDK reading) or J5 (FANUC manual paraphrase): ambiguous
  const EditResult r = replaceTargetPose(q, 0, targetPose(q, q.targets()[0]), d);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.reason.find("TURN_AXIS"), std::string::npos);
  EXPECT_TRUE(q.edits.empty());
  d.turns = {0, 0, 1};  // J6 in both readings
  EXPECT_TRUE(replaceTargetPose(q, 0, targetPose(q, q.targets()[0]), d).ok);
  q.fanuc_turn_axes = std::array<int, 3>{4, 5, 6};
  d.turns = {1, 0, 1};
  EXPECT_TRUE(replaceTargetPose(q, 0, targetPose(q, q.targets()[0]), d).ok);
  EXPECT_NE(renderFiles(q)[0].find("CONFIG : 'N U T, 1, 0, 1'"), std::string::npos);
}

TEST(PostprocEdit, RefusesSharedJointAndIncompleteTargets) {
  Program p = fromText(Dialect::kKrl, "x.src",
                       "DEF x( )\n$TOOL=TOOL_DATA[1]\nLIN XP1\n$TOOL=TOOL_DATA[2]\nLIN XP1\nLIN {X "
                       "10}\nPTP XJ\nEND\n",
                       std::string("DEFDAT x\nDECL E6POS XP1={X 1,Y 2,Z 3,A 0,B 0,C 0}\nDECL "
                                   "E6AXIS XJ={A1 0,A2 -90,A3 90,A4 0,A5 0,A6 0}\nENDDAT\n"));
  ASSERT_EQ(p.targets().size(), 3u);
  const EditResult shared = replaceTargetPose(p, 0, Pose::Identity());
  EXPECT_FALSE(shared.ok);
  EXPECT_NE(shared.reason.find("different tools"), std::string::npos);
  EXPECT_FALSE(replaceTargetPose(p, 1, Pose::Identity()).ok);  // {X 10}: components omitted
  EXPECT_FALSE(replaceTargetPose(p, 2, Pose::Identity()).ok);  // joint target
  EXPECT_TRUE(p.edits.empty());
}

// replaceTargetPose into an EditLog replayed by applyEdits (compensate --threads prepares the
// targets of a program on several threads so) gives the edits, the target values and the bytes
// of the direct calls: every Cartesian target of every fixture dialect moved and turned, its
// flags changed where the dialect writes them, then moved back (the log's erase path: the tokens
// print as before, so no edit stays).
void expectLogEqualsDirect(const std::string& path) {
  SCOPED_TRACE(path);
  Program direct = readProgram(path);
  Program logged = readProgram(path);
  const Vendor v = direct.dialect == Dialect::kKrl     ? Vendor::kKuka
                   : direct.dialect == Dialect::kRapid ? Vendor::kAbb
                   : direct.dialect == Dialect::kTp    ? Vendor::kFanuc
                                                       : Vendor::kNone;
  int moved = 0;
  for (const bool back : {false, true}) {
    for (std::size_t i = 0; i < direct.targets().size(); ++i) {
      const Target& t = std::as_const(direct).targets()[i];
      if (t.kind != TargetKind::kCartesian) continue;
      Pose T = targetPose(direct, t);
      std::optional<Configuration> c;
      const double s = back ? -1.0 : 1.0;
      T.translation() += s * Vec3(0.1234, -0.0567, 0.0891) * 1e-3;
      T.linear() =
          T.linear() *
          Eigen::AngleAxisd(s * 0.01 * kDeg, Vec3(1, 2, 3).normalized()).toRotationMatrix();
      if (!back && v != Vendor::kNone && t.config.vendor == v) {
        c = t.config;
        c->status = c->status >= 0 ? (c->status ^ 2) : 2;
        c->cf[1] = c->cf[1] - 1;
        c->flip = c->flip == 'N' ? 'F' : 'N';
      }
      const int k = static_cast<int>(i);
      const EditResult a = replaceTargetPose(direct, k, T, c);
      EditLog log;
      const EditResult b = replaceTargetPose(logged, k, T, c, log);
      EXPECT_EQ(a.ok, b.ok);
      EXPECT_EQ(a.reason, b.reason);
      applyEdits(logged, std::move(log));
      moved += a.ok ? 1 : 0;
    }
    ASSERT_EQ(direct.edits.size(), logged.edits.size());
    for (auto it = direct.edits.begin(), jt = logged.edits.begin(); it != direct.edits.end();
         ++it, ++jt) {
      EXPECT_EQ(it->first, jt->first);
      EXPECT_EQ(it->second.length, jt->second.length);
      EXPECT_EQ(it->second.text, jt->second.text);
    }
    for (std::size_t i = 0; i < direct.targets().size(); ++i) {
      const Target& a = std::as_const(direct).targets()[i];
      const Target& b = std::as_const(logged).targets()[i];
      for (std::size_t j = 0; j < 3; ++j) EXPECT_EQ(a.pos[j].value, b.pos[j].value);
      for (std::size_t j = 0; j < 4; ++j) EXPECT_EQ(a.rot[j].value, b.rot[j].value);
      EXPECT_EQ(a.config.text(), b.config.text());
    }
    EXPECT_EQ(renderFiles(direct), renderFiles(logged));
  }
  EXPECT_GT(moved, 1);
}

TEST(PostprocEdit, EditLogReplayedGivesTheDirectEdits) {
  for (const char* f :
       {"kss_drill.src", "rapid_drill.mod", "tp_controller.ls", "targets.json", "targets_rxyz.csv"})
    expectLogEqualsDirect(fixtures() + "/" + f);
}

// The pending edits after puts and erases in and out of file order: an erase drops the edit at
// its key only (before, at and past the last pending key; in the other file; on no edits).
TEST(PostprocEdit, EraseDropsThePendingEditAtItsKeyOnly) {
  using Keys = std::vector<std::pair<int, std::uint32_t>>;
  Program p;
  const auto keys = [&p] {
    Keys k;
    for (const auto& [key, e] : p.edits) k.push_back(key);
    return k;
  };
  const auto replay = [&p](std::initializer_list<std::tuple<bool, int, std::uint32_t>> ops) {
    EditLog log;
    for (const auto& [erase, file, offset] : ops)
      log.ops.push_back({erase, Edit{file, offset, 1, erase ? "" : "9"}});
    applyEdits(p, std::move(log));
  };
  replay({{true, 0, 7}});  // nothing pending
  EXPECT_TRUE(p.edits.empty());
  replay({{false, 0, 10}, {false, 0, 20}, {false, 0, 30}});
  replay({{true, 0, 30}});  // the last
  EXPECT_EQ(keys(), (Keys{{0, 10}, {0, 20}}));
  replay({{true, 0, 40}, {true, 0, 5}, {true, 0, 15}, {true, 1, 0}});  // none of them pending
  EXPECT_EQ(keys(), (Keys{{0, 10}, {0, 20}}));
  replay({{false, 1, 3}, {true, 0, 10}});  // before the last, in the other file
  EXPECT_EQ(keys(), (Keys{{0, 20}, {1, 3}}));
  replay({{true, 1, 3}, {false, 0, 25}, {true, 0, 20}});
  EXPECT_EQ(keys(), (Keys{{0, 25}}));
  replay({{true, 0, 25}});
  EXPECT_TRUE(p.edits.empty());
}

TEST(PostprocDrill, KukaToolDirectionXIsAParameter) {
  const Program p = readProgram(fixtures() + "/kss_drill.src");
  EXPECT_TRUE(recognizeHoles(p).empty());  // tool z is horizontal here (B = 90°)
  RecognitionOptions o;
  o.tool_axis = Vec3::UnitX();
  const auto holes = recognizeHoles(p, o);
  ASSERT_EQ(holes.size(), 1u);
  EXPECT_EQ(p.targets()[static_cast<std::size_t>(holes[0].bottom_target)].name, "XP3");
  EXPECT_NEAR(holes[0].depth * 1e3, 20.0, 1e-9);
  EXPECT_LT((holes[0].axis - Vec3(0, 0, -1)).norm(), 1e-12);
  EXPECT_FALSE(
      p.frames[static_cast<std::size_t>(holes[0].base)].resolved);  // BASE_DATA[3]: $config.dat
}

TEST(PostprocDrill, RapidRelToolCycleAndTpDrillMacro) {
  const Program r = readProgram(fixtures() + "/rapid_drill.mod");
  const auto hr = recognizeHoles(r);
  ASSERT_GE(hr.size(), 1u);
  EXPECT_EQ(r.targets()[static_cast<std::size_t>(hr[0].bottom_target)].name, "pH1");
  // the feed (vDrill) starts at RelTool -5: depth -5 .. +12, not from the -50 approach
  EXPECT_NEAR(hr[0].depth * 1e3, 17.0, 1e-6);
  const Program t = readProgram(fixtures() + "/tp_controller.ls");
  const auto ht = recognizeHoles(t);
  ASSERT_EQ(ht.size(), 1u);
  EXPECT_EQ(t.targets()[static_cast<std::size_t>(ht[0].bottom_target)].name, "P[3]");
  bool pr_reported = false;
  for (const Motion& m : t.motions)
    pr_reported = pr_reported || t.text(m.derivation) == "Tool_Offset";
  EXPECT_TRUE(pr_reported);
}

}  // namespace
}  // namespace roprec::postproc
