// writeDrillProgram (postproc/drill_program.hpp): a drilling program written from a list of holes
// reads back through roprec's own readers and drill-cycle recognition as the same holes — id (or
// order), entry point, direction, depth, frame and tool — in every dialect; deterministic output;
// `roprec inspect` accepts it.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <stdexcept>

#include "postproc/drill.hpp"
#include "postproc/drill_program.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

namespace fs = std::filesystem;
using postproc::Dialect;
using postproc::DrillHole;
using postproc::DrillProgramOptions;
using postproc::DrillProgramText;
using postproc::Program;

constexpr double kMm = 1e-3;
// Positions are written with 6 decimals (mm): read back within 5e-7 mm per component.
constexpr double kPosTol = 1e-6 * kMm;

Pose pose(const Vec3& p_mm, const Mat3& R) {
  Pose T = Pose::Identity();
  T.linear() = R;
  T.translation() = p_mm * kMm;
  return T;
}

Mat3 aa(double deg, const Vec3& axis) {
  return Eigen::AngleAxisd(deg * kDeg, axis.normalized()).toRotationMatrix();
}

// Holes on three faces: top (drilled -z), a 45° chamfer (drilled (1,0,-1)/√2), a side (drilled +y),
// each with its own rotation about the drilling axis.
std::vector<DrillHole> holes(Dialect d) {
  std::vector<DrillHole> h;
  const Mat3 top = aa(180, Vec3::UnitX());
  const Mat3 chamfer = aa(135, Vec3::UnitY());
  const Mat3 side = aa(-90, Vec3::UnitX());
  h.push_back({"T001", pose({150.0, 0.0, 250.0}, top), 16.0 * kMm, 6.8 * kMm, std::nullopt});
  h.push_back({"T002", pose({-12.3456789, 150.123456789, 250.0}, top * aa(37.5, Vec3::UnitZ())),
               12.5 * kMm, 8.5 * kMm, std::nullopt});
  h.push_back({"F-1", pose({-175.355339, -105.0, 154.644661}, chamfer * aa(-20, Vec3::UnitZ())),
               24.0 * kMm, 12.0 * kMm, std::nullopt});
  h.push_back(
      {"F002", pose({-161.213203, -75.0, 168.786797}, chamfer), 24.0 * kMm, 0.0, std::nullopt});
  h.push_back({"R1", pose({-105.0, -170.0, 40.0}, side * aa(90, Vec3::UnitZ())), 30.0 * kMm,
               10.2 * kMm, std::nullopt});
  const std::map<Dialect, std::vector<std::optional<std::string>>> configs = {
      {Dialect::kKrl, {"S 2 T 35", std::nullopt, "S 'B110' T 'B100011'", "S 6", "T 3"}},
      {Dialect::kRapid, {"[0,-1,0,0]", std::nullopt, "[-1,0,-2,1]", " [0, 0, 0, 4] ", "[0,0,0,0]"}},
      {Dialect::kTp,
       {"N U T, 0, 0, 0", std::nullopt, "F D B, 0, 1, -1", "N U T, 0, 0, 0", "F U T, 0, 0, 0"}},
      {Dialect::kCsv, {"N U T, 0, 0, 0", std::nullopt, "S 2 T 35", "[0,-1,0,0]", std::nullopt}},
      {Dialect::kJson, {"[0,-1,0,0]", std::nullopt, "N U T, 0, 0, 0", std::nullopt, "S 6"}},
  };
  const auto it = configs.find(d);
  for (std::size_t i = 0; it != configs.end() && i < h.size(); ++i) h[i].config = it->second[i];
  return h;
}

DrillProgramOptions options(Dialect d) {
  DrillProgramOptions o;
  o.name = "plan_test";
  o.dialect = d;
  o.T_base_frame = pose({1350.0, 100.0, 300.0}, rotationFromZyx(12 * kDeg, -3 * kDeg, 1.5 * kDeg));
  o.T_flange_tcp = pose({10.0, -5.0, 320.0}, rotationFromZyx(0.0, 30 * kDeg, 0.0));
  o.tool_mass = 25.8;
  o.tool_cog = Vec3(0.0, 0.0, 0.12);
  o.comment = "stiffness identification; test holes";
  return o;
}

// The expected configuration text as roprec reads it back (Configuration::text()).
std::string readBackConfig(Dialect d, const std::optional<std::string>& c) {
  if (!c) return d == Dialect::kTp ? "F U T, 0, 0, 0" : d == Dialect::kRapid ? "[0,0,0,0]" : "";
  if (d == Dialect::kKrl && c->find('\'') != std::string::npos)
    return "S 6 T 35";  // 'B110', 'B100011'
  return postproc::parseConfigurationText(*c).text();
}

bool validName(Dialect d, const std::string& id) {
  if (d == Dialect::kTp) return false;  // TP records are numbered
  if (d == Dialect::kCsv || d == Dialect::kJson) return true;
  return id != "F-1";
}

void expectFrame(const Program& p, int index, const Pose& expected, const char* what) {
  ASSERT_GE(index, 0) << what;
  const postproc::Frame& f = p.frames[static_cast<std::size_t>(index)];
  EXPECT_TRUE(f.resolved) << what << " " << f.ref;
  EXPECT_LT((f.pose.translation() - expected.translation()).cwiseAbs().maxCoeff(), kPosTol) << what;
  EXPECT_LT(smallRotationDifference(f.pose.linear(), expected.linear()).norm(), 1e-9) << what;
}

// Every hole recognised, in order, with entry point, direction, depth, frames and configuration.
void expectRoundTrip(Dialect d) {
  SCOPED_TRACE(postproc::dialectName(d));
  const std::vector<DrillHole> in = holes(d);
  const DrillProgramOptions o = options(d);
  const DrillProgramText t = postproc::writeDrillProgram(in, o);
  Program p = postproc::parseDrillProgram(t);
  const double rot_tol = d == Dialect::kTp ? 2e-8 : 1e-9;  // TP W,P,R: 6 decimals (deg)
  if (d == Dialect::kTp) {
    ASSERT_FALSE(p.frames.empty());
    EXPECT_GT(postproc::resolveFrame(p, "UFRAME[1]", o.T_base_frame), 0);
    EXPECT_GT(postproc::resolveFrame(p, "UTOOL[1]", o.T_flange_tcp), 0);
  }
  const std::vector<postproc::Hole> rec = postproc::recognizeHoles(p);
  ASSERT_EQ(rec.size(), in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    SCOPED_TRACE(in[i].id);
    const postproc::Hole& h = rec[i];
    const Vec3 z = in[i].T_frame_tcp.linear().col(2);
    const Vec3 entry = in[i].T_frame_tcp.translation();
    EXPECT_EQ(h.id, "H" + std::to_string(i + 1));
    EXPECT_LT((h.axis - z).norm(), rot_tol);
    EXPECT_LT((h.position - (entry + z * in[i].depth)).cwiseAbs().maxCoeff(), kPosTol);
    // depth below the surface = where the feed starts (the clearance point, crossed at feed), not
    // below the cycle's first target (the approach point)
    EXPECT_NEAR(h.depth, o.clearance + in[i].depth, kPosTol);
    EXPECT_LT((h.surface - (entry - z * o.clearance)).cwiseAbs().maxCoeff(), kPosTol);
    EXPECT_LT((h.position - h.axis * in[i].depth - entry).cwiseAbs().maxCoeff(), kPosTol);
    // the cycle: approach, clearance, bottom (+ the retract row of a table)
    const std::size_t n_targets = (d == Dialect::kCsv || d == Dialect::kJson) ? 4 : 3;
    ASSERT_EQ(h.targets.size(), n_targets);
    const std::vector<double> along = {-o.approach, -o.clearance, in[i].depth, -o.approach};
    for (std::size_t k = 0; k < n_targets; ++k) {
      const postproc::Target& tg = p.targets()[static_cast<std::size_t>(h.targets[k])];
      const Pose T = postproc::targetPose(p, tg);
      EXPECT_LT((T.translation() - (entry + z * along[k])).cwiseAbs().maxCoeff(), kPosTol) << k;
      EXPECT_LT(smallRotationDifference(T.linear(), in[i].T_frame_tcp.linear()).norm(), rot_tol)
          << k;
      if (d != Dialect::kCsv && d != Dialect::kJson) {
        EXPECT_EQ(tg.config.text(), readBackConfig(d, in[i].config)) << k;
      } else {
        EXPECT_EQ(tg.config.text(),
                  in[i].config ? postproc::parseConfigurationText(*in[i].config).text() : "")
            << k;
      }
    }
    EXPECT_EQ(h.entry_target, h.targets[0]);
    EXPECT_EQ(h.bottom_target, h.targets[2]);
    const std::string bottom_name = p.targets()[static_cast<std::size_t>(h.bottom_target)].name;
    if (validName(d, in[i].id)) {
      EXPECT_EQ(bottom_name, in[i].id);
    }
    if (d == Dialect::kKrl && in[i].id == "F-1") {
      EXPECT_EQ(bottom_name, "H3");
    }
    if (d == Dialect::kTp) {
      EXPECT_EQ(bottom_name, "P[" + std::to_string(3 * i + 3) + "]");
    }
    expectFrame(p, h.base, o.T_base_frame, "base");
    expectFrame(p, h.tool, o.T_flange_tcp, "tool");
    if (d == Dialect::kTp) {
      EXPECT_EQ(p.frames[static_cast<std::size_t>(h.base)].ref, "UFRAME[1]");
      EXPECT_EQ(p.frames[static_cast<std::size_t>(h.tool)].ref, "UTOOL[1]");
    }
    // the drill point is an exact stop reached at the feed
    const postproc::Motion& mb = p.motions[static_cast<std::size_t>(h.bottom_motion)];
    if (d != Dialect::kCsv) {  // a CSV target list has no exact-stop column
      EXPECT_TRUE(mb.fine);
    }
    EXPECT_NEAR(mb.speed_mm_s, o.feed * 1e3, 1e-9);
  }
  EXPECT_TRUE(p.unresolved.empty());  // TP: after resolveFrame
}

TEST(DrillProgram, KrlRoundTrip) { expectRoundTrip(Dialect::kKrl); }
TEST(DrillProgram, RapidRoundTrip) { expectRoundTrip(Dialect::kRapid); }
TEST(DrillProgram, TpRoundTrip) { expectRoundTrip(Dialect::kTp); }
TEST(DrillProgram, CsvRoundTrip) { expectRoundTrip(Dialect::kCsv); }
TEST(DrillProgram, JsonRoundTrip) { expectRoundTrip(Dialect::kJson); }

TEST(DrillProgram, KrlStatesFramesAndDatPoints) {
  const DrillProgramText t =
      postproc::writeDrillProgram(holes(Dialect::kKrl), options(Dialect::kKrl));
  ASSERT_EQ(t.files.size(), 2U);
  EXPECT_EQ(t.files[0].suffix, ".src");
  EXPECT_EQ(t.files[1].suffix, ".dat");
  EXPECT_EQ(t.name, "plan_test");
  const std::string& src = t.files[0].text;
  const std::string& dat = t.files[1].text;
  EXPECT_NE(src.find("DEF plan_test( )"), std::string::npos);
  EXPECT_NE(src.find("$BASE={FRAME: X 1350.000000,Y 100.000000,Z 300.000000,A 12.000000000,B "
                     "-3.000000000,C 1.500000000}"),
            std::string::npos)
      << src;
  EXPECT_NE(src.find("$TOOL={FRAME: X 10.000000,Y -5.000000,Z 320.000000,A 0.000000000,B "
                     "30.000000000,C 0.000000000}"),
            std::string::npos)
      << src;
  EXPECT_NE(
      src.find(
          "PTP T001_APP C_PTP\nLIN T001_CLR C_DIS\n$VEL.CP=0.020000\nLIN T001\nWAIT SEC 0.500\n"
          "$VEL.CP=0.250000\nLIN T001_APP C_DIS\n"),
      std::string::npos)
      << src;
  EXPECT_NE(dat.find("DEFDAT plan_test\n"), std::string::npos);
  EXPECT_NE(dat.find("DECL E6POS T001={X 150.000000,Y 0.000000,Z 234.000000,A 0.000000000,B "
                     "0.000000000,C 180.000000000,S 2,T 35}"),
            std::string::npos)
      << dat;
  EXPECT_NE(dat.find(",S 'B110',T 'B100011'}"), std::string::npos);
  const std::size_t t002 = dat.find("DECL E6POS T002={");
  ASSERT_NE(t002, std::string::npos);
  const std::string line = dat.substr(t002, dat.find('\n', t002) - t002);
  EXPECT_EQ(line.find(",S "), std::string::npos) << line;  // no configuration given: S/T omitted
  EXPECT_EQ(line.find(",T "), std::string::npos) << line;
  EXPECT_NE(line.find("{X -12.345679,Y 150.123457,Z 237.500000,"), std::string::npos) << line;
}

TEST(DrillProgram, RapidStatesWobjAndTool) {
  const DrillProgramText t =
      postproc::writeDrillProgram(holes(Dialect::kRapid), options(Dialect::kRapid));
  ASSERT_EQ(t.files.size(), 1U);
  const std::string& s = t.files[0].text;
  EXPECT_NE(s.find("PERS tooldata tDrill:=[TRUE,[[10.000000,-5.000000,320.000000],"),
            std::string::npos)
      << s;
  EXPECT_NE(s.find("[25.800,[0.000,0.000,120.000],[1,0,0,0],0,0,0]];"), std::string::npos) << s;
  EXPECT_NE(s.find("PERS wobjdata wDrill:=[FALSE,TRUE,\"\",[[1350.000000,100.000000,300.000000],"),
            std::string::npos);
  EXPECT_NE(
      s.find(
          "CONST robtarget "
          "T001:=[[150.000000,0.000000,234.000000],[0.000000000000,1.000000000000,0.000000000000,"
          "0.000000000000],[0,-1,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];"),
      std::string::npos)
      << s;
  EXPECT_NE(s.find("CONST robtarget H3:="), std::string::npos);  // 'F-1' is no RAPID identifier
  EXPECT_NE(s.find("! F-1 drill D12.000 depth 24.000"), std::string::npos);
  EXPECT_NE(s.find("    ConfJ \\Off;\n    ! T002"), std::string::npos)
      << s;  // T002 has no configuration
  EXPECT_NE(s.find("MoveL T001,vDrillFeed,fine,tDrill\\WObj:=wDrill;\n    WaitTime 0.500;\n"),
            std::string::npos)
      << s;
  const Program p = postproc::parseDrillProgram(t);
  bool off = false;
  for (const postproc::Motion& m : p.motions) {
    if (m.type == postproc::MotionType::kJoint &&
        p.targets()[static_cast<std::size_t>(m.target)].name == "T002_APP") {
      off = !m.config_honoured;
    }
  }
  EXPECT_TRUE(off);
}

TEST(DrillProgram, TpRecordsAndFrameNumbers) {
  DrillProgramOptions o = options(Dialect::kTp);
  o.uframe = 3;
  o.utool = 2;
  const DrillProgramText t = postproc::writeDrillProgram(holes(Dialect::kTp), o);
  const std::string& s = t.files[0].text;
  EXPECT_EQ(t.files[0].suffix, ".ls");
  EXPECT_NE(s.find("/PROG  PLAN_TEST\n"), std::string::npos);
  EXPECT_NE(s.find("UFRAME_NUM=3 ;"), std::string::npos);
  EXPECT_NE(s.find("UTOOL_NUM=2 ;"), std::string::npos);
  EXPECT_NE(s.find("P[3]{\n   GP1:\n\tUF : 3, UT : 2,\t\tCONFIG : 'N U T, 0, 0, 0',\n"
                   "\tX =   150.000000  mm,\tY =     0.000000  mm,\tZ =   234.000000  mm,\n"
                   "\tW =   180.000000 deg,\tP =     0.000000 deg,\tR =     0.000000 deg\n};"),
            std::string::npos)
      << s;
  EXPECT_NE(s.find("L P[3] 20mm/sec FINE ;\n  12:  WAIT .50(sec) ;\n  13:L P[1] 250mm/sec CNT50 ;"),
            std::string::npos)
      << s;
  EXPECT_NE(s.find("CONFIG : 'F U T, 0, 0, 0'"),
            std::string::npos);  // T002: no configuration given
  bool noted = false;
  for (const std::string& n : t.notes) noted = noted || n.find("UFRAME[3]") != std::string::npos;
  EXPECT_TRUE(noted);
  // LINE_COUNT = the /MN lines
  const std::size_t mn = s.find("/MN\n");
  const std::size_t pos = s.find("/POS\n");
  int lines = 0;
  for (std::size_t k = mn + 4; k < pos; ++k) lines += s[k] == '\n';
  EXPECT_NE(s.find("LINE_COUNT\t= " + std::to_string(lines) + ";"), std::string::npos);
  Program p = postproc::parseDrillProgram(t);
  EXPECT_EQ(postproc::resolveFrame(p, "UFRAME[3]", o.T_base_frame) > 0, true);
  EXPECT_EQ(postproc::recognizeHoles(p).size(), 5U);
}

TEST(DrillProgram, HoleListRoundTrip) {
  const std::vector<DrillHole> in = holes(Dialect::kHoleCsv);
  const DrillProgramOptions o = options(Dialect::kHoleCsv);
  const DrillProgramText t = postproc::writeDrillProgram(in, o);
  ASSERT_EQ(t.files.size(), 1U);
  EXPECT_EQ(t.files[0].suffix, ".csv");
  const std::vector<postproc::HoleSpec> specs =
      postproc::parseHoleList("holes.csv", t.files[0].text);
  ASSERT_EQ(specs.size(), in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    SCOPED_TRACE(in[i].id);
    EXPECT_EQ(specs[i].id, in[i].id);
    EXPECT_LT((specs[i].position_mm - in[i].T_frame_tcp.translation() * 1e3).cwiseAbs().maxCoeff(),
              1e-6);
    EXPECT_LT((specs[i].direction - in[i].T_frame_tcp.linear().col(2)).norm(), 2e-9);
    ASSERT_TRUE(specs[i].depth_mm.has_value());
    EXPECT_NEAR(*specs[i].depth_mm, in[i].depth * 1e3, 1e-6);
    EXPECT_EQ(specs[i].diameter_mm.has_value(), in[i].diameter > 0);
    if (specs[i].diameter_mm) {
      EXPECT_NEAR(*specs[i].diameter_mm, in[i].diameter * 1e3, 1e-6);
    }
  }
  // the program reader takes it as a hole list too: one target per hole, TCP z = i,j,k
  const Program p = postproc::parseDrillProgram(t);
  EXPECT_EQ(p.dialect, Dialect::kHoleCsv);
  ASSERT_EQ(p.targets().size(), in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    const Pose T = postproc::targetPose(p, p.targets()[i]);
    EXPECT_LT((T.translation() - in[i].T_frame_tcp.translation()).cwiseAbs().maxCoeff(), kPosTol);
    EXPECT_LT((T.linear().col(2) - in[i].T_frame_tcp.linear().col(2)).norm(), 2e-9);
  }
  // every program dialect matches the hole list hole for hole (by id, else by position)
  for (const Dialect d :
       {Dialect::kKrl, Dialect::kRapid, Dialect::kTp, Dialect::kCsv, Dialect::kJson}) {
    SCOPED_TRACE(postproc::dialectName(d));
    Program q = postproc::parseDrillProgram(postproc::writeDrillProgram(holes(d), options(d)));
    const std::vector<postproc::Hole> rec = postproc::recognizeHoles(q);
    const std::vector<postproc::HoleMatch> m = postproc::matchHoles(rec, q, specs, 0.01);
    ASSERT_EQ(m.size(), in.size());
    for (const postproc::HoleMatch& x : m) {
      EXPECT_EQ(x.hole, x.spec);
      EXPECT_LT(x.distance_mm, 1e-6);
    }
  }
}

TEST(DrillProgram, Deterministic) {
  for (const Dialect d : {Dialect::kKrl, Dialect::kRapid, Dialect::kTp, Dialect::kCsv,
                          Dialect::kJson, Dialect::kHoleCsv}) {
    SCOPED_TRACE(postproc::dialectName(d));
    const DrillProgramText a = postproc::writeDrillProgram(holes(d), options(d));
    const DrillProgramText b = postproc::writeDrillProgram(holes(d), options(d));
    ASSERT_EQ(a.files.size(), b.files.size());
    for (std::size_t k = 0; k < a.files.size(); ++k) {
      EXPECT_EQ(a.files[k].suffix, b.files[k].suffix);
      EXPECT_EQ(a.files[k].text, b.files[k].text);
    }
    EXPECT_EQ(a.notes, b.notes);
    // CR LF: the same bytes with CR LF line ends, the same holes
    DrillProgramOptions o = options(d);
    o.crlf = true;
    const DrillProgramText c = postproc::writeDrillProgram(holes(d), o);
    for (std::size_t k = 0; k < a.files.size(); ++k) {
      std::string lf = c.files[k].text;
      for (std::size_t q = lf.find("\r\n"); q != std::string::npos; q = lf.find("\r\n", q))
        lf.erase(q, 1);
      EXPECT_EQ(lf, a.files[k].text);
    }
    if (d != Dialect::kHoleCsv) {
      EXPECT_EQ(postproc::recognizeHoles(postproc::parseDrillProgram(c)).size(), holes(d).size());
    }
  }
}

TEST(DrillProgram, NamesAvoidClashesAndKeywords) {
  DrillProgramOptions o = options(Dialect::kKrl);
  std::vector<DrillHole> in = holes(Dialect::kKrl);
  in.resize(3);
  in[0].id = "A";
  in[1].id = "A_APP";  // another hole's approach name
  in[2].id = "END";    // a KRL keyword
  const DrillProgramText t = postproc::writeDrillProgram(in, o);
  const Program p = postproc::parseDrillProgram(t);
  const auto rec = postproc::recognizeHoles(p);
  ASSERT_EQ(rec.size(), 3U);
  auto name = [&](int target) { return p.targets()[static_cast<std::size_t>(target)].name; };
  EXPECT_EQ(name(rec[0].bottom_target), "A");
  EXPECT_EQ(name(rec[0].entry_target), "A_APP_2");
  EXPECT_EQ(name(rec[1].bottom_target), "A_APP");
  EXPECT_EQ(name(rec[2].bottom_target), "H3");
  // a long id is no name: the fallback keeps KRL's 24 characters
  in.resize(1);
  in[0].id = "ABCDEFGHIJKLMNOPQRSTUVWXYZ";
  const Program q = postproc::parseDrillProgram(postproc::writeDrillProgram(in, o));
  for (const postproc::Target& tg : q.targets()) EXPECT_LE(tg.name.size(), 24U) << tg.name;
  EXPECT_EQ(postproc::recognizeHoles(q).size(), 1U);
}

TEST(DrillProgram, RefusesInvalidInput) {
  const DrillProgramOptions o = options(Dialect::kKrl);
  auto throws = [&](std::vector<DrillHole> h, DrillProgramOptions opt) {
    EXPECT_THROW(postproc::writeDrillProgram(h, opt), std::invalid_argument);
  };
  std::vector<DrillHole> h = holes(Dialect::kKrl);
  std::vector<DrillHole> dup = h;
  dup[1].id = dup[0].id;
  throws(dup, o);
  std::vector<DrillHole> depth = h;
  depth[0].depth = 0.0;
  throws(depth, o);
  std::vector<DrillHole> quote = h;
  quote[0].id = "a\"b";
  throws(quote, o);
  std::vector<DrillHole> other = h;
  other[0].config = "[0,0,0,1]";  // ABB flags in a KRL program
  throws(other, o);
  DrillProgramOptions slow = o;
  slow.rapid = slow.feed;
  throws(h, slow);
  DrillProgramOptions close = o;
  close.approach = close.clearance;
  throws(h, close);
  DrillProgramOptions rapid = options(Dialect::kRapid);
  std::vector<DrillHole> rh = holes(Dialect::kRapid);
  rh[0].config = "N U T, 0, 0, 0";
  throws(rh, rapid);
  // KRL: the file must carry the DEF name
  const std::string dir = test::tempDir("drill-program-name");
  const DrillProgramText t = postproc::writeDrillProgram(h, o);
  EXPECT_THROW(postproc::saveDrillProgram(t, dir + "/other.src"), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir + "/other.src"));
  fs::remove_all(dir);
}

int count(const std::string& s, const std::string& what) {
  int n = 0;
  for (std::size_t k = s.find(what); k != std::string::npos; k = s.find(what, k + 1)) ++n;
  return n;
}

TEST(DrillProgram, InspectAcceptsTheWrittenPrograms) {
  const std::string dir = test::tempDir("drill-program-cli");
  const DrillProgramText holes_csv =
      postproc::writeDrillProgram(holes(Dialect::kHoleCsv), options(Dialect::kHoleCsv));
  const std::vector<std::string> hl = postproc::saveDrillProgram(holes_csv, dir + "/holes");
  ASSERT_EQ(hl.size(), 1U);
  for (const Dialect d :
       {Dialect::kKrl, Dialect::kRapid, Dialect::kTp, Dialect::kCsv, Dialect::kJson}) {
    SCOPED_TRACE(postproc::dialectName(d));
    const DrillProgramText t = postproc::writeDrillProgram(holes(d), options(d));
    const std::vector<std::string> paths = postproc::saveDrillProgram(t, dir + "/plan_test");
    ASSERT_EQ(paths.size(), t.files.size());
    for (std::size_t k = 0; k < paths.size(); ++k)
      EXPECT_EQ(test::readFile(paths[k]), t.files[k].text);
    const auto r = test::runRoprec("inspect '" + paths[0] + "' --holes '" + hl[0] + "' --all");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(count(r.out, "\"entry_target\""), 5) << r.out;
    EXPECT_EQ(count(r.out, "\"hole_list_id\""), 5) << r.out;
    for (const std::string& p : paths) fs::remove(p);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace roprec
