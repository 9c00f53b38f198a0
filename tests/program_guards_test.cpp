// Compensation guards and program frames: a hole that is singular or unreachable at its
// programmed target is never "compensated" into another arm posture; a compensated program is
// marked and not compensated again unless --force; -o equal to the input is refused; controller-
// only frames and a program tool that differs from the cell's are errors unless resolved.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "compensator/compensation/compensation.hpp"
#include "compensator/robot/configuration.hpp"
#include "compensator/robot/ik.hpp"
#include "plugin/api/prediction_setup.hpp"
#include "postproc/program.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

namespace fs = std::filesystem;

std::string sample(const std::string& rel) { return test::sourceDir() + "/samples/" + rel; }

TEST(CompensationGuard, HoleSingularBeforeCompensationIsNotCompensatedIntoAnotherPosture) {
  const api::PredictionContext c = api::loadPredictionContext(sample("cells/housing-kr120.xml"), "",
                                                              std::nullopt, "", 0.5, false);
  // a reachable hole, and the same hole moved onto the wrist singularity (θ5 = 0)
  Vec6 q = c.model.reference_pose;
  q[1] += 0.2;
  q[3] = 0.4;
  q[5] = 0.3;
  q[4] = 0.6;
  // both state their configuration, as a KRL PTP with S/T does
  HoleRequest ok;
  ok.id = "OK1";
  ok.T_W_tcp = ikForwardKinematics(c.model.ik, q) * c.tool.T_flange_tcp;
  ok.config = configurationOf(c.model.ik, c.robot.card, q, c.model.config_options);
  HoleRequest sing = ok;
  sing.id = "SING";
  q[4] = -c.model.ik.alpha;
  sing.T_W_tcp = ikForwardKinematics(c.model.ik, q) * c.tool.T_flange_tcp;
  sing.config = configurationOf(c.model.ik, c.robot.card, q, c.model.config_options);
  for (const OrientationMode mode : {OrientationMode::kKeep, OrientationMode::kFlipFree}) {
    CompensationOptions o;
    o.mode = mode;
    o.grid = 8;
    o.allow_branch_change = true;
    const std::vector<HoleCompensation> r = compensateHoles(c.model, {ok, sing}, o);
    ASSERT_EQ(r.size(), 2U);
    EXPECT_TRUE(r[0].ok) << r[0].reason;
    EXPECT_FALSE(r[0].branch_changed);
    ASSERT_EQ(r[1].before.status, HoleStatus::kSingular)
        << r[1].before.reason << " joints " << r[1].before.joints.transpose() << " q "
        << q.transpose();
    EXPECT_FALSE(r[1].ok) << "a singular hole was compensated into branch " << r[1].branch;
    EXPECT_NE(r[1].reason.find("singular before compensation"), std::string::npos) << r[1].reason;
  }
}

/// The sample KRL job cut to its first two holes.
std::string twoHoleKrl(const std::string& dir, const std::string& name = "two.src") {
  std::ifstream in(sample("emotor-housing/housing_kr120.src"));
  std::string text;
  std::string l;
  for (int i = 1; i <= 30 && std::getline(in, l); ++i) text += l + "\n";
  text += "SPINDLE_OFF()\nEND\n";
  test::writeFile(dir + "/" + name, text);
  return dir + "/" + name;
}

std::string kr120Cell() { return sample("cells/housing-kr120.xml"); }

TEST(CompensationGuard, CompensatedProgramIsMarkedAndNotCompensatedAgainUnlessForced) {
  const std::string dir = test::tempDir("guard_marker");
  const std::string in = twoHoleKrl(dir);
  const std::string once = dir + "/once.src";
  const auto a =
      test::runRoprec("compensate --cell '" + kr120Cell() + "' '" + in + "' -o '" + once + "'");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const std::string text = test::readFile(once);
  // the marker is a KRL comment line right after the DEF line, naming the cell and the version
  const std::size_t at =
      text.find("\n;roprec compensated: cell housing-kr120 (housing-kr120.xml), roprec ");
  ASSERT_NE(at, std::string::npos) << text.substr(0, 300);
  EXPECT_EQ(text.rfind("DEF housing_kr120 ( )", at), text.rfind('\n', at - 1) + 1);
  const std::string twice = dir + "/twice.src";
  const auto b =
      test::runRoprec("compensate --cell '" + kr120Cell() + "' '" + once + "' -o '" + twice + "'");
  EXPECT_EQ(b.exit_code, 2) << b.err;
  EXPECT_NE(b.err.find("once.src:5: the program was already compensated by roprec"),
            std::string::npos)
      << b.err;
  EXPECT_NE(b.err.find("--force"), std::string::npos) << b.err;
  EXPECT_FALSE(fs::exists(twice));
  const auto c = test::runRoprec("compensate --cell '" + kr120Cell() + "' '" + once + "' -o '" +
                                 twice + "' --force");
  EXPECT_EQ(c.exit_code, 0) << c.err;
  EXPECT_TRUE(fs::exists(twice));
  EXPECT_NE(c.err.find("--force"), std::string::npos) << c.err;
  // predict reads a marked program as any other
  const auto p = test::runRoprec("predict --cell '" + kr120Cell() + "' '" + once + "' --quiet");
  EXPECT_LE(p.exit_code, 1) << p.err;
}

TEST(CompensationGuard, RapidAndTpMarkersUseTheirCommentSyntax) {
  const std::string dir = test::tempDir("guard_dialects");
  // RAPID: a `!` line after MODULE
  std::ifstream mod(sample("emotor-housing/housing_irb6640.mod"));
  std::string text;
  std::string l;
  for (int i = 1; i <= 21 && std::getline(mod, l); ++i) text += l + "\n";
  text += "  ENDPROC\nENDMODULE\n";
  test::writeFile(dir + "/two.mod", text);
  const auto r = test::runRoprec("compensate --cell '" + sample("cells/housing-irb6640.xml") +
                                 "' '" + dir + "/two.mod' -o '" + dir + "/once.mod'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(test::readFile(dir + "/once.mod")
                .find("MODULE housing_irb6640\n! roprec compensated: cell housing-irb6640 "),
            std::string::npos);
  const auto again = test::runRoprec("compensate --cell '" + sample("cells/housing-irb6640.xml") +
                                     "' '" + dir + "/once.mod' -o '" + dir + "/twice.mod'");
  EXPECT_EQ(again.exit_code, 2) << again.err;
  EXPECT_NE(again.err.find("once.mod:2:"), std::string::npos) << again.err;
  EXPECT_FALSE(fs::exists(dir + "/twice.mod"));

  // FANUC TP: a remark as /MN line 1, the other lines renumbered, LINE_COUNT + 1
  postproc::Program tp =
      postproc::readProgram(test::sourceDir() + "/tests/data/programs/tp_controller.ls");
  ASSERT_TRUE(postproc::markCompensated(tp, "cell c (c.xml), roprec 0.2.0, keep"));
  const std::string out = postproc::renderFiles(tp)[0];
  EXPECT_NE(out.find("LINE_COUNT\t= 15;"), std::string::npos);
  EXPECT_NE(out.find("/MN\r\n   1:  !roprec compensated: cell c (c.xml), roprec 0.2.0, keep ;\r\n"
                     "   2:  !Bohrzyklus"),
            std::string::npos)
      << out.substr(out.find("/MN"), 300);
  EXPECT_NE(out.find("  12:C P[4]"), std::string::npos);
  EXPECT_NE(out.find("  15:L P[6] 1200cm/min"), std::string::npos);
  const postproc::Program back = postproc::parseProgram(postproc::Dialect::kTp, "m.ls", out);
  const auto m = postproc::findCompensationMarker(back);
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ(m->line, 26);
  EXPECT_EQ(back.motions.size(), tp.motions.size());
}

TEST(CompensationGuard, OutputEqualToTheInputIsRefused) {
  const std::string dir = test::tempDir("guard_same");
  const std::string in = twoHoleKrl(dir);
  const std::string before = test::readFile(in);
  const auto a =
      test::runRoprec("compensate --cell '" + kr120Cell() + "' '" + in + "' -o '" + in + "'");
  EXPECT_EQ(a.exit_code, 2) << a.err;
  EXPECT_NE(a.err.find("is the input file"), std::string::npos) << a.err;
  EXPECT_EQ(test::readFile(in), before);
  // the same file under another name (hard link) and through a different spelling of the path
  fs::create_hard_link(in, dir + "/link.src");
  const auto b = test::runRoprec("compensate --cell '" + kr120Cell() + "' '" + in + "' -o '" + dir +
                                 "/link.src' --targets '" + dir + "/t.json'");
  EXPECT_EQ(b.exit_code, 2) << b.err;
  EXPECT_EQ(test::readFile(in), before);
  EXPECT_FALSE(fs::exists(dir + "/t.json"));
  const auto c = test::runRoprec("compensate --cell '" + kr120Cell() + "' '" + in + "' -o '" + dir +
                                 "/./two.src'");
  EXPECT_EQ(c.exit_code, 2) << c.err;
  // a report written over the input is refused too
  const auto d = test::runRoprec("compensate --cell '" + kr120Cell() + "' '" + in + "' -o '" + dir +
                                 "/ok.src' --report '" + in + "'");
  EXPECT_EQ(d.exit_code, 2) << d.err;
  EXPECT_FALSE(fs::exists(dir + "/ok.src"));
  EXPECT_EQ(test::readFile(in), before);
  // with two threads (the targets export is staged while the program is edited): the same
  // refusals, nothing written
  const auto b2 = test::runRoprec("compensate --cell '" + kr120Cell() + "' '" + in + "' -o '" +
                                  dir + "/link.src' --targets '" + dir + "/t.json' --threads 2");
  EXPECT_EQ(b2.exit_code, 2) << b2.err;
  EXPECT_NE(b2.err.find("is the input file"), std::string::npos) << b2.err;
  EXPECT_FALSE(fs::exists(dir + "/t.json"));
  const auto d2 =
      test::runRoprec("compensate --cell '" + kr120Cell() + "' '" + in + "' -o '" + dir +
                      "/ok.src' --targets '" + dir + "/t.json' --report '" + in + "' --threads 2");
  EXPECT_EQ(d2.exit_code, 2) << d2.err;
  EXPECT_NE(d2.err.find("is the input file"), std::string::npos) << d2.err;
  EXPECT_FALSE(fs::exists(dir + "/ok.src"));
  EXPECT_FALSE(fs::exists(dir + "/t.json"));
  EXPECT_EQ(test::readFile(in), before);
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".roprec-tmp."), std::string::npos) << e.path();
}

// ---- frames and tools the program and the cell disagree on, or only the controller knows

/// The sample RAPID job cut to its first two holes, its tooldata TCP z replaced by `tcp_z`.
std::string twoHoleRapid(const std::string& dir, const std::string& tcp_z) {
  std::ifstream mod(sample("emotor-housing/housing_irb6640.mod"));
  std::string text;
  std::string l;
  for (int i = 1; i <= 21 && std::getline(mod, l); ++i) text += l + "\n";
  text += "  ENDPROC\nENDMODULE\n";
  text.replace(text.find("[[0,0,320]"), 10, "[[0,0," + tcp_z + "]");
  test::writeFile(dir + "/tool" + tcp_z + ".mod", text);
  return dir + "/tool" + tcp_z + ".mod";
}

TEST(ProgramFrames, ProgramToolDifferentFromTheCellsIsAnErrorUnlessResolved) {
  const std::string dir = test::tempDir("frames_tool");
  const std::string cell = sample("cells/housing-irb6640.xml");
  const std::string prog = twoHoleRapid(dir, "300");
  const auto a = test::runRoprec("predict --cell '" + cell + "' '" + prog + "' --json '" + dir +
                                 "/a.json' --report '" + dir + "/a.html'");
  EXPECT_EQ(a.exit_code, 2) << a.err;
  EXPECT_NE(a.err.find("tool300.mod:3: the program's tool tSpindle"), std::string::npos) << a.err;
  EXPECT_NE(a.err.find("--tool program"), std::string::npos) << a.err;
  EXPECT_FALSE(fs::exists(dir + "/a.json"));
  EXPECT_FALSE(fs::exists(dir + "/a.html"));
  const auto c =
      test::runRoprec("compensate --cell '" + cell + "' '" + prog + "' -o '" + dir + "/c.mod'");
  EXPECT_EQ(c.exit_code, 2) << c.err;
  EXPECT_FALSE(fs::exists(dir + "/c.mod"));
  // resolved: stated on stderr, in the JSON notes and in the report header
  const auto b =
      test::runRoprec("predict --cell '" + cell + "' '" + prog + "' --tool cell --json '" + dir +
                      "/b.json' --report '" + dir + "/b.html'");
  ASSERT_LE(b.exit_code, 1) << b.err;
  EXPECT_NE(b.err.find("--tool cell"), std::string::npos) << b.err;
  EXPECT_NE(test::readFile(dir + "/b.json").find("resolution: the program's tool tSpindle"),
            std::string::npos);
  EXPECT_NE(test::readFile(dir + "/b.html").find("Frame/tool resolution"), std::string::npos);
  // --tool program predicts with the program's 300 mm TCP: the same as a cell with that tool
  const auto p = test::runRoprec("predict --cell '" + cell + "' '" + prog +
                                 "' --tool program --json '" + dir + "/p.json'");
  ASSERT_LE(p.exit_code, 1) << p.err;
  EXPECT_NE(p.err.find("--tool program"), std::string::npos) << p.err;
  std::string cell300 = test::readFile(cell);
  cell300.replace(cell300.find("xyz=\"0 0 320\""), 13, "xyz=\"0 0 300\"");
  test::writeFile(dir + "/cell300.xml", cell300);
  const std::string prog300 = twoHoleRapid(dir, "300");
  const auto q = test::runRoprec("predict --cell '" + dir + "/cell300.xml' '" + prog300 +
                                 "' --json '" + dir + "/q.json'");
  ASSERT_LE(q.exit_code, 1) << q.err;
  const std::string pj = test::readFile(dir + "/p.json");
  const std::string qj = test::readFile(dir + "/q.json");
  const auto dev = [](const std::string& j) { return j.substr(j.find("\"deviation_um\""), 200); };
  EXPECT_EQ(dev(pj), dev(qj));
  // the cell's own tool in the program: no error, no note
  const auto same = test::runRoprec("predict --cell '" + cell + "' '" + twoHoleRapid(dir, "320") +
                                    "' --json '" + dir + "/s.json'");
  ASSERT_LE(same.exit_code, 1) << same.err;
  EXPECT_EQ(test::readFile(dir + "/s.json").find("resolution:"), std::string::npos);
}

TEST(ProgramFrames, ControllerOnlyFramesAreErrorsUnlessResolved) {
  const std::string dir = test::tempDir("frames_controller");
  // KUKA: $BASE = BASE_DATA[1] lives in $config.dat
  std::string text = test::readFile(twoHoleKrl(dir));
  const std::string base = "$BASE = {FRAME: X 1350.000,Y 0.000,Z 300.000,A 0.000,B 0.000,C 0.000}";
  text.replace(text.find(base), base.size(), "$BASE = BASE_DATA[1]");
  test::writeFile(dir + "/bd.src", text);
  const auto a = test::runRoprec("predict --cell '" + kr120Cell() + "' '" + dir +
                                 "/bd.src' --json '" + dir + "/a.json'");
  EXPECT_EQ(a.exit_code, 2) << a.err;
  EXPECT_NE(a.err.find("bd.src:18: hole H1 uses the base frame BASE_DATA[1]"), std::string::npos)
      << a.err;
  EXPECT_NE(a.err.find("--frame cell"), std::string::npos) << a.err;
  EXPECT_FALSE(fs::exists(dir + "/a.json"));
  // the same pose as the original program's $BASE: the same prediction
  const auto b =
      test::runRoprec("predict --cell '" + kr120Cell() + "' '" + dir +
                      "/bd.src' --frame \"1350 0 300 0 0 0\" --json '" + dir + "/b.json'");
  ASSERT_LE(b.exit_code, 1) << b.err;
  EXPECT_NE(b.err.find("BASE_DATA[1]"), std::string::npos) << b.err;
  const auto o = test::runRoprec("predict --cell '" + kr120Cell() + "' '" + dir +
                                 "/two.src' --json '" + dir + "/o.json'");
  ASSERT_LE(o.exit_code, 1) << o.err;
  const auto dev = [](const std::string& j) { return j.substr(j.find("\"deviation_um\""), 300); };
  EXPECT_EQ(dev(test::readFile(dir + "/b.json")), dev(test::readFile(dir + "/o.json")));
  const auto n = test::runRoprec("predict --cell '" + kr120Cell() + "' '" + dir +
                                 "/bd.src' --frame 'BASE_DATA[1]=1350 0 300 0 0 0' --json '" + dir +
                                 "/n.json'");
  ASSERT_LE(n.exit_code, 1) << n.err;
  EXPECT_EQ(dev(test::readFile(dir + "/n.json")), dev(test::readFile(dir + "/o.json")));

  // FANUC: UFRAME[1] and UTOOL[1] are controller data
  const std::string ls = sample("emotor-housing/housing_r2000.ls");
  const std::string cell = sample("cells/housing-r2000.xml");
  const auto f =
      test::runRoprec("predict --cell '" + cell + "' '" + ls + "' --json '" + dir + "/f.json'");
  EXPECT_EQ(f.exit_code, 2) << f.err;
  EXPECT_NE(f.err.find("housing_r2000.ls:"), std::string::npos) << f.err;
  EXPECT_NE(f.err.find("UFRAME[1]"), std::string::npos) << f.err;
  EXPECT_FALSE(fs::exists(dir + "/f.json"));
  const auto g = test::runRoprec("predict --cell '" + cell + "' '" + ls +
                                 "' --frame cell --json '" + dir + "/g.json'");
  EXPECT_EQ(g.exit_code, 2) << g.err;
  EXPECT_NE(g.err.find("UTOOL[1]"), std::string::npos) << g.err;
  EXPECT_NE(g.err.find("--tool cell"), std::string::npos) << g.err;
  const auto h = test::runRoprec("predict --cell '" + cell + "' '" + ls +
                                 "' --frame cell --tool cell --json '" + dir + "/h.json' --quiet");
  ASSERT_LE(h.exit_code, 1) << h.err;
  const std::string hj = test::readFile(dir + "/h.json");
  EXPECT_NE(hj.find("resolution: base frame UFRAME[1]"), std::string::npos);
  EXPECT_NE(hj.find("resolution: tool UTOOL[1]"), std::string::npos);
  // TP UTOOL values when given: compared with the cell's tool like any program tool
  const std::string uf = "UFRAME[1]=1400 0 -370 0 0 0";
  const auto u = test::runRoprec("predict --cell '" + cell + "' '" + ls + "' --frame '" + uf +
                                 ";UTOOL[1]=0 0 300 0 0 0' --json '" + dir + "/u.json'");
  EXPECT_EQ(u.exit_code, 2) << u.err;
  EXPECT_NE(u.err.find("the program's tool UTOOL[1]"), std::string::npos) << u.err;
  EXPECT_FALSE(fs::exists(dir + "/u.json"));
  const auto v = test::runRoprec("predict --cell '" + cell + "' '" + ls + "' --frame '" + uf +
                                 ";UTOOL[1]=0 0 320 0 0 0' --json '" + dir + "/v.json' --quiet");
  ASSERT_LE(v.exit_code, 1) << v.err;
  EXPECT_EQ(dev(test::readFile(dir + "/v.json")), dev(hj));
}

}  // namespace
}  // namespace roprec

namespace roprec {
namespace {

// --frame cell names the cell's <workobject>; a cell without one defines no frame, so the option
// is an error (it used to fall back to the robot base frame without a word).
TEST(ProgramFrames, FrameCellWithoutAWorkobjectIsAnError) {
  const std::string dir = test::tempDir("frame-cell-no-wobj");
  std::string cell = test::readFile(test::sourceDir() + "/samples/cells/housing-r2000.xml");
  const std::string wobj = "<workobject xyz=\"1400 0 -370\" rpy=\"0 0 0\"/>";
  ASSERT_NE(cell.find(wobj), std::string::npos);
  cell.replace(cell.find(wobj), wobj.size(), "");
  test::writeFile(dir + "/cell.xml", cell);
  const auto r = test::runRoprec("predict --cell '" + dir + "/cell.xml' '" + test::sourceDir() +
                                 "/samples/emotor-housing/housing_r2000.ls' --frame cell --tool "
                                 "cell --json '" +
                                 dir + "/p.json'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(dir + "/cell.xml:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--frame cell: the cell has no <workobject>"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/p.json"));
}

}  // namespace
}  // namespace roprec
