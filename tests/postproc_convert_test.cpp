// Conversion between dialects keeps poses (< 1e-6 mm, < 1e-9 rad), frames and the configuration
// branch (docs/programs.md §7.1).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <regex>
#include <sstream>

#include "compensator/support/error.hpp"
#include "postproc/convert.hpp"
#include "postproc/program.hpp"
#include "tests/support/test_support.hpp"

namespace roprec::postproc {
namespace {

struct Seen {
  Pose T;
  std::optional<Pose> base;
  std::optional<Pose> tool;
  std::optional<int> branch;
  MotionType type;
};

std::vector<Seen> cartesianMotions(const Program& p) {
  std::vector<Seen> out;
  for (const Motion& m : p.motions) {
    const std::optional<Pose> T = motionPose(p, m);
    if (!T) continue;
    Seen s{*T, std::nullopt, std::nullopt,
           p.targets()[static_cast<std::size_t>(m.target)].config.branch(), m.type};
    if (m.base >= 0 && p.frames[static_cast<std::size_t>(m.base)].resolved)
      s.base = p.frames[static_cast<std::size_t>(m.base)].pose;
    if (m.tool >= 0 && p.frames[static_cast<std::size_t>(m.tool)].resolved)
      s.tool = p.frames[static_cast<std::size_t>(m.tool)].pose;
    out.push_back(s);
  }
  return out;
}

Program readBack(const std::vector<std::pair<std::string, std::string>>& files, Dialect d) {
  for (const auto& [path, bytes] : files) test::writeFile(path, bytes);
  Program p = readProgram(files[0].first);
  EXPECT_EQ(p.dialect == Dialect::kHoleCsv ? Dialect::kCsv : p.dialect, d);
  return p;
}

void expectSame(const std::vector<Seen>& a, const std::vector<Seen>& b, bool frames, bool branch) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_LT((a[i].T.translation() - b[i].T.translation()).norm() * 1e3, 1e-6);
    EXPECT_LT(smallRotationDifference(a[i].T.linear(), b[i].T.linear()).norm(), 1e-9);
    EXPECT_EQ(a[i].type, b[i].type);
    if (frames) {
      ASSERT_EQ(a[i].base.has_value(), b[i].base.has_value());
      if (a[i].base) {
        EXPECT_LT((a[i].base->translation() - b[i].base->translation()).norm() * 1e3, 1e-6);
        EXPECT_LT(smallRotationDifference(a[i].base->linear(), b[i].base->linear()).norm(), 1e-9);
      }
      ASSERT_EQ(a[i].tool.has_value(), b[i].tool.has_value());
      if (a[i].tool) {
        EXPECT_LT((a[i].tool->translation() - b[i].tool->translation()).norm() * 1e3, 1e-6);
      }
    }
    if (branch && a[i].branch) {
      EXPECT_EQ(a[i].branch, b[i].branch);
    }
  }
}

// A source program with random poses (incl. gimbal orientations), frames and all eight branches.
std::string randomRapid(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::string s =
      "MODULE mRand\n  PERS tooldata "
      "tT:=[TRUE,[[1.5,-2.25,250.125],[0.9238795325,0,0.3826834324,0]],[5,[0,0,100],[1,0,0,0],0,0,"
      "0]];\n";
  s += "  PERS wobjdata "
       "wW:=[FALSE,TRUE,\"\",[[1400.5,-12.75,400.25],[0.965925826289068,0,0,0.258819045102521]],[["
       "10,0,0],[1,0,0,0]]];\n";
  s += "  PROC main()\n";
  for (int i = 0; i < 40; ++i) {
    Eigen::Quaterniond q(u(rng), u(rng), u(rng), u(rng));
    if (i % 10 == 3)
      q = Eigen::Quaterniond(Eigen::AngleAxisd(kPi / 2, Vec3::UnitY()) *
                             Eigen::AngleAxisd(u(rng), Vec3::UnitX()));
    q.normalize();
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "    %s "
                  "[[%.6f,%.6f,%.6f],[%.12f,%.12f,%.12f,%.12f],[0,-1,2,%d],[9E+09,9E+09,9E+09,9E+"
                  "09,9E+09,9E+09]],v100,%s,tT\\WObj:=wW;\n",
                  i % 3 == 0 ? "MoveJ" : "MoveL", 500 * u(rng), 500 * u(rng), 500 * u(rng), q.w(),
                  q.x(), q.y(), q.z(), i % 8, i % 2 ? "fine" : "z1");
    s += buf;
  }
  s += "  ENDPROC\nENDMODULE\n";
  return s;
}

TEST(PostprocConvert, EveryDialectPairKeepsPoseFramesAndBranch) {
  std::mt19937 rng(7);
  const std::string dir = test::tempDir("convert");
  test::writeFile(dir + "/rand.mod", randomRapid(rng));
  const Program src = readProgram(dir + "/rand.mod");
  const std::vector<Seen> ref = cartesianMotions(src);
  ASSERT_EQ(ref.size(), 40u);
  for (const Dialect d :
       {Dialect::kKrl, Dialect::kRapid, Dialect::kTp, Dialect::kCsv, Dialect::kJson}) {
    SCOPED_TRACE(dialectName(d));
    ConversionReport rep;
    const auto files = convertProgram(src, d, dir + "/out_" + dialectName(d), rep);
    EXPECT_TRUE(rep.skipped.empty());
    Program back = readBack(files, d);
    if (d == Dialect::kTp) {  // UFRAME/UTOOL values live in the controller
      resolveFrame(back, "UFRAME[1]", *ref[0].base);
      resolveFrame(back, "UTOOL[1]", *ref[0].tool);
    }
    const bool branch = d != Dialect::kCsv && d != Dialect::kJson;
    expectSame(ref, cartesianMotions(back), true, branch);
    // and onwards: d -> every other dialect
    for (const Dialect e : {Dialect::kKrl, Dialect::kRapid, Dialect::kTp, Dialect::kJson}) {
      if (e == d) continue;
      ConversionReport rep2;
      const auto files2 =
          convertProgram(back, e, dir + "/out_" + dialectName(d) + "_" + dialectName(e), rep2);
      Program back2 = readBack(files2, e);
      if (e == Dialect::kTp) {
        resolveFrame(back2, "UFRAME[1]", *ref[0].base);
        resolveFrame(back2, "UTOOL[1]", *ref[0].tool);
      }
      expectSame(ref, cartesianMotions(back2), true, branch && e != Dialect::kJson);
    }
  }
}

TEST(PostprocConvert, CorpusProgramsConvertAndJointTargetsAreReported) {
  if (test::corpusDir().empty()) GTEST_SKIP() << "no corpus";
  const std::string dir = test::tempDir("convert-corpus");
  for (const char* f : {"DrillKRC4.src", "DrillKRC2DAT.src", "DrillIRC5.mod"}) {
    SCOPED_TRACE(f);
    const Program src = readProgram(test::corpusDir() + "/robodk/" + f);
    const auto ref = cartesianMotions(src);
    ASSERT_EQ(ref.size(), 15u);
    for (const Dialect d : {Dialect::kKrl, Dialect::kRapid, Dialect::kCsv}) {
      ConversionReport rep;
      const auto files = convertProgram(src, d, dir + "/o_" + dialectName(d), rep);
      if (d == Dialect::kCsv) {
        EXPECT_LE(rep.skipped.size(), 1u);  // only KRL's `PTP $AXIS_ACT`
      } else {
        EXPECT_GE(rep.skipped.size(), 3u);  // the three joint approach targets
      }
      const Program back = readBack(files, d);
      expectSame(ref, cartesianMotions(back), true, d != Dialect::kCsv);
    }
  }
}

// The streamed form: the notes go to the report's callback (none kept), the files are the same,
// and an error of the file writer (on the conversion's writing thread) stops the conversion.
TEST(PostprocConvert, NotesGoToTheCallbackAndAWriteErrorStopsTheConversion) {
  std::mt19937 rng(7);
  const std::string dir = test::tempDir("convert-sink");
  test::writeFile(dir + "/rand.mod", randomRapid(rng));
  const Program src = readProgram(dir + "/rand.mod");
  for (const Dialect d :
       {Dialect::kKrl, Dialect::kRapid, Dialect::kTp, Dialect::kCsv, Dialect::kJson}) {
    SCOPED_TRACE(dialectName(d));
    ConversionReport rep;
    const auto files = convertProgram(src, d, dir + "/o", rep);
    ConversionReport called;
    std::vector<std::string> notes;
    called.on_note = [&notes](const std::string& n) { notes.push_back(n); };
    std::vector<std::pair<std::string, std::string>> streamed;
    convertProgram(
        src, d, dir + "/o", called, false,
        [&](const std::string& path, const std::function<void(const ByteWriter&)>& produce) {
          std::string bytes;
          produce([&bytes](std::string_view s) { bytes.append(s); });
          streamed.emplace_back(path, bytes);
        });
    EXPECT_EQ(streamed, files);
    EXPECT_EQ(notes, rep.notes);
    EXPECT_TRUE(called.notes.empty());
    EXPECT_EQ(called.not_carried, rep.not_carried);
    ConversionReport failing;
    EXPECT_THROW(convertProgram(src, d, dir + "/o", failing, false,
                                [](const std::string& path,
                                   const std::function<void(const ByteWriter&)>& produce) {
                                  produce([&path](std::string_view) {
                                    throw InputError(path, 0, "cannot write output file: full");
                                  });
                                }),
                 InputError);
  }
}

TEST(PostprocConvert, UnresolvedFrameNeedsAValue) {
  if (test::corpusDir().empty()) GTEST_SKIP() << "no corpus";
  const Program src = readProgram(test::corpusDir() + "/robodk/DRILLR30IA.LS");
  ConversionReport rep;
  EXPECT_THROW(convertProgram(src, Dialect::kRapid, test::tempDir("cv") + "/x.mod", rep),
               InputError);
  const auto r = test::runRoprec(
      "convert '" + test::corpusDir() + "/robodk/DRILLR30IA.LS' --to rapid --o '" +
      test::tempDir("cv2") + "/x.mod' --frame 'UFRAME[1]=1400 0 400 0 0 0;UTOOL[1]=0 0 250 0 0 0'");
  EXPECT_EQ(r.exit_code, 1) << r.err;  // joint targets listed
  EXPECT_NE(r.err.find("joint target"), std::string::npos);
}

// ------------------------------------------------------------------ what is not carried

std::string dataProgram(const std::string& name) {
  return test::sourceDir() + "/tests/data/programs/" + name;
}

/// Line `n` (1-based) of a file, read independently of the program reader.
std::string fileLine(const std::string& path, int n) {
  std::istringstream in(test::readFile(path));
  std::string line;
  for (int i = 0; i < n && std::getline(in, line); ++i) {
  }
  return line;
}

bool listed(const std::vector<std::string>& v, const std::string& what) {
  return std::any_of(v.begin(), v.end(),
                     [&](const std::string& s) { return s.find(what) != std::string::npos; });
}

/// Every "FILE:LINE: text (kind)" entry names a line whose text holds `text` and no motion.
void expectLinesTrue(const Program& src, const std::vector<std::string>& not_carried) {
  const std::string& path = src.files[0].path;
  for (const std::string& s : not_carried) {
    if (s.rfind("zone ", 0) == 0) continue;
    SCOPED_TRACE(s);
    ASSERT_EQ(s.rfind(path + ":", 0), 0u);
    const int line = std::stoi(s.substr(path.size() + 1));
    const size_t t0 = s.find(": ", path.size()) + 2, t1 = s.rfind(" (");
    std::string text = s.substr(t0, t1 - t0);
    if (text.size() > 3 && text.compare(text.size() - 3, 3, "...") == 0)
      text.resize(text.size() - 3);
    std::vector<int> at{line};
    const size_t more = s.find(" in all, lines ", t1);
    if (more != std::string::npos) {  // a repeated instruction: every line it is on
      at.clear();
      std::stringstream ss(s.substr(more + 15));
      for (std::string n; std::getline(ss, n, ',');) at.push_back(std::stoi(n));
      EXPECT_EQ(at.front(), line);
      EXPECT_EQ(std::to_string(at.size()),
                s.substr(s.rfind("; ", more) + 2, more - s.rfind("; ", more) - 2));
    }
    for (const int l : at) {
      EXPECT_NE(fileLine(path, l).find(text), std::string::npos) << l;
      for (const Motion& m : src.motions) EXPECT_NE(m.line, l);
    }
  }
}

TEST(PostprocConvert, ListsWaitsCallsAndZoneMappingsItDoesNotCarry) {
  const std::string dir = test::tempDir("convert-carry");
  struct Case {
    const char* file;
    Dialect to;
    std::vector<std::string> expect;
  };
  const std::vector<Case> cases{
      {"rapid_drill.mod",
       Dialect::kKrl,
       {"rapid_drill.mod:23: WaitTime 0.5; (wait)", "rapid_drill.mod:20: SpindleOn 12000; (call)",
        "rapid_drill.mod:31: nCount := nCount + 1; (assignment)",
        "zone z10 -> C_DIS at " + dataProgram("rapid_drill.mod") + ":24, 25 (2 motions",
        "zone z10 -> C_PTP at " + dataProgram("rapid_drill.mod") + ":18 (1 motion"}},
      {"rapid_drill.mod",
       Dialect::kTp,
       {"rapid_drill.mod:23: WaitTime 0.5; (wait)",
        "zone z10 -> CNT100 at " + dataProgram("rapid_drill.mod") + ":18, 24, 25 (3 motions"}},
      {"tp_controller.ls",
       Dialect::kRapid,
       {"tp_controller.ls:32: WAIT    .25(sec) (wait)",
        "tp_controller.ls:35: CALL DRILL_20_3 (call)",
        "zone CNT50 -> z1 at " + dataProgram("tp_controller.ls") + ":29 (1 motion"}},
      {"../../../samples/emotor-housing/housing_kr120.src",
       Dialect::kRapid,
       {"housing_kr120.src:12: SPINDLE_ON() (call)",
        "housing_kr120.src:19: WAIT SEC 0.3 (wait; 204 in all, lines 19, 28, 37,"}},
      {"kss_drill.src",
       Dialect::kTp,
       {"kss_drill.src:46: WAIT SEC 0.5 (wait)", "kss_drill.src:61: MyCustomMacro(1, 2) (call)",
        "kss_drill.src:62: IF $IN[5] THEN (control flow)"}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.file) + " -> " + dialectName(c.to));
    Program src = readProgram(dataProgram(c.file));
    for (const char* f : {"UFRAME[9]", "UTOOL[1]", "wUnknown", "TOOL_DATA[2]", "BASE_DATA[3]"})
      resolveFrame(src, f, Pose::Identity());
    ConversionReport rep;
    convertProgram(src, c.to, dir + "/o_" + dialectName(c.to), rep, true);
    for (const std::string& e : c.expect) EXPECT_TRUE(listed(rep.not_carried, e)) << e;
    expectLinesTrue(src, rep.not_carried);
    // the motions' zones that a dialect keeps are not listed
    EXPECT_FALSE(listed(rep.not_carried, "FINE ->"));
    EXPECT_FALSE(listed(rep.not_carried, "fine ->"));
  }
  // the CLI says it on stderr (also with --quiet), exit code as before (joint targets skipped)
  const auto r = test::runRoprec("convert '" + dataProgram("rapid_drill.mod") + "' --to krl -o '" +
                                 dir + "/cli.src' --quiet --frame 'wUnknown=0 0 0 0 0 0'");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("roprec: not carried: " + dataProgram("rapid_drill.mod") +
                       ":23: WaitTime 0.5; (wait)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("zone z1 -> C_DIS at "), std::string::npos) << r.err;
}

/// A repeated instruction or zone of a large program is one notice of about 1 KB that states the
/// count and its first lines; asked for every line (--verbose), it lists all of them.
TEST(PostprocConvert, RepeatedNoticesAreCutToAboutOneKilobyteUnlessEveryLineIsAsked) {
  const std::string dir = test::tempDir("convert-notice");
  std::string prog = "DEF big ( )\n" + std::string(test::kHousingBase) +
                     "\n$TOOL = {FRAME: X 0,Y 0,Z 320,A 0,B 0,C 0}\n";
  for (int k = 0; k < 600; ++k) {  // a wait and two approximated motions per cycle
    const std::string xy = "X " + std::to_string(k) + ",Y 0,";
    prog += "PTP {" + xy + "Z 300,A 0,B 0,C 180} C_PTP\nLIN {" + xy +
            "Z 270,A 0,B 0,C 180}\nWAIT SEC 0.3\nLIN {" + xy + "Z 300,A 0,B 0,C 180} C_DIS\n";
  }
  test::writeFile(dir + "/big.src", prog + "END\n");
  const Program src = readProgram(dir + "/big.src");
  ConversionReport cut;
  convertProgram(src, Dialect::kRapid, dir + "/cut.mod", cut);
  ConversionReport all;
  convertProgram(src, Dialect::kRapid, dir + "/all.mod", all, true);
  ASSERT_EQ(cut.not_carried.size(), all.not_carried.size());
  const auto unspaced = [](std::string s) {  // every line is listed with ", " between them
    s.erase(std::remove(s.begin(), s.end(), ' '), s.end());
    return s;
  };
  bool any_cut = false;
  for (size_t i = 0; i < cut.not_carried.size(); ++i) {
    const std::string& c = cut.not_carried[i];
    const std::string& a = all.not_carried[i];
    SCOPED_TRACE(a.substr(0, 80));
    EXPECT_LE(c.size(), kNoticeBytes + 8);
    const size_t dots = c.find(",...");
    if (dots == std::string::npos) {
      EXPECT_EQ(unspaced(c), unspaced(a));
      continue;
    }
    any_cut = true;
    const std::string first = unspaced(c.substr(0, dots));  // the first lines of the full list
    EXPECT_EQ(unspaced(a).compare(0, first.size(), first), 0);
    // the count stays
    EXPECT_TRUE(c.find("600 in all") != std::string::npos ||
                c.find("(600 motions") != std::string::npos);
  }
  EXPECT_TRUE(any_cut);
  // the CLI: the last WAIT (line 2402) is listed with --verbose only, and not cut on stderr
  const std::string cmd = "convert '" + dir + "/big.src' --to rapid -o '" + dir + "/cli.mod'";
  const test::RunResult brief = test::runRoprec(cmd);
  const test::RunResult verbose = test::runRoprec(cmd + " --verbose");
  EXPECT_EQ(brief.exit_code, 0) << brief.err;
  EXPECT_EQ(verbose.exit_code, 0) << verbose.err;
  EXPECT_EQ(brief.err.find("2402"), std::string::npos) << brief.err;
  EXPECT_NE(verbose.err.find(", 2402)"), std::string::npos) << verbose.err;
}

/// A KRL source states E1..E6 = 0 for axes the cell does not have: RAPID gets 9E+09 for them and
/// the used axis (E1 = 1545 mm on one target) keeps its value.
TEST(PostprocConvert, KrlSourceUnusedExternalAxesBecome9E09InRapid) {
  Program src = readProgram(dataProgram("kss_drill.src"));
  resolveFrame(src, "TOOL_DATA[2]", Pose::Identity());
  resolveFrame(src, "BASE_DATA[3]", Pose::Identity());
  ConversionReport rep;
  const auto files = convertProgram(src, Dialect::kRapid, test::tempDir("cv-ext") + "/x.mod", rep);
  const std::regex ext("robtarget [^:]+:=\\[.*\\],\\[([^\\]]*)\\]\\];");
  int n = 0;
  bool e1_kept = false;
  const std::string& mod = files[0].second;
  for (std::sregex_iterator it(mod.begin(), mod.end(), ext), end; it != end; ++it, ++n) {
    std::vector<std::string> v;
    std::stringstream ss((*it)[1].str());
    for (std::string x; std::getline(ss, x, ',');) v.push_back(x);
    ASSERT_EQ(v.size(), 6u) << (*it)[0];
    for (size_t k = 1; k < 6; ++k) EXPECT_EQ(v[k], "9E+09") << (*it)[0];
    e1_kept = e1_kept || v[0] == "1545.000000";
  }
  EXPECT_GE(n, 3);
  EXPECT_TRUE(e1_kept);
  EXPECT_TRUE(listed(rep.notes, "E2, E3, E4, E5, E6 = 0 in every target")) << rep.notes.size();
  // and the KRL/TP writers do not invent the unused axes either
  ConversionReport rep2;
  const auto krl = convertProgram(src, Dialect::kKrl, test::tempDir("cv-ext2") + "/x.src", rep2);
  EXPECT_EQ(krl[1].second.find(",E2 "), std::string::npos);
  EXPECT_NE(krl[1].second.find(",E1 1545.000000"), std::string::npos);
}

/// RoboDK's RAPID: the %%% header and the frame/speed assignments the new program states by
/// value are not listed; the spindle calls and the waits are.
TEST(PostprocConvert, RoboDkRapidListsOnlyWhatIsLost) {
  if (test::corpusDir().empty()) GTEST_SKIP() << "no corpus";
  const Program src = readProgram(test::corpusDir() + "/robodk/DrillIRC5.mod");
  ConversionReport rep;
  convertProgram(src, Dialect::kKrl, test::tempDir("cv-rdk") + "/x.src", rep);
  EXPECT_TRUE(listed(rep.not_carried, "DrillIRC5.mod:28: SPINDLE_ON; (call)"));
  EXPECT_TRUE(listed(rep.not_carried, "DrillIRC5.mod:39: WaitTime 0.500; (wait; 3 in all"));
  EXPECT_TRUE(listed(rep.not_carried, "SPINDLE_OFF; (call)"));
  EXPECT_FALSE(listed(rep.not_carried, "%%%"));
  EXPECT_FALSE(listed(rep.not_carried, "VERSION"));
  EXPECT_FALSE(listed(rep.not_carried, "rdkWObj.uframe"));
  EXPECT_FALSE(listed(rep.not_carried, "rdkSpeed"));
  expectLinesTrue(src, rep.not_carried);
}

}  // namespace
}  // namespace roprec::postproc
