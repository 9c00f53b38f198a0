// roprec inspect / convert through the CLI: good programs, and bad input -> exit 2 with
// FILE:LINE and nothing written (docs/contract.md §3).
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

namespace fs = std::filesystem;

struct Bad {
  std::string dir;
  std::string program;
};

Bad write(const std::string& tag, const std::string& name, const std::string& text,
          const std::string& dat_name = "", const std::string& dat = "") {
  Bad b{test::tempDir(tag), ""};
  b.program = b.dir + "/" + name;
  test::writeFile(b.program, text);
  if (!dat_name.empty()) test::writeFile(b.dir + "/" + dat_name, dat);
  return b;
}

// Both commands refuse with exit 2, name FILE:LINE, and write nothing.
void expectRejected(const Bad& b, const std::string& file_line, const std::string& what) {
  for (const std::string cmd : {"inspect", "convert"}) {
    SCOPED_TRACE(cmd);
    const std::string out = b.dir + "/out" + fs::path(b.program).extension().string();
    const auto r = test::runRoprec(cmd + " '" + b.program + "' --o '" + out + "'");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(file_line), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_TRUE(r.out.empty());
  }
}

TEST(PostprocCli, UnterminatedAggregate) {
  const Bad b = write("unterminated", "job.src", "DEF job( )\nLIN XP1\nEND\n", "job.dat",
                      "DEFDAT job\nDECL E6POS XP1={X 1.0,Y 2.0,Z 3.0,A 0.0,B 0.0\nENDDAT\n");
  expectRejected(b, "job.dat:2:", "unterminated aggregate");
  const Bad r = write("unterminated-rapid", "m.mod",
                      "MODULE m\n  CONST robtarget "
                      "p:=[[1,2,3],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9];\nENDMODULE\n");
  expectRejected(r, "m.mod:2:", "unterminated aggregate");
}

TEST(PostprocCli, BrokenNumber) {
  const Bad b =
      write("broken", "m.mod",
            "MODULE m\n  PROC main()\n    MoveL "
            "[[1.2.3,0,0],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]],v100,fine,tool0;\n"
            "  ENDPROC\nENDMODULE\n");
  expectRejected(b, "m.mod:3:", "broken number");
  const Bad k =
      write("broken-krl", "job.src", "DEF job( )\nLIN {X 12a,Y 0,Z 0,A 0,B 0,C 0}\nEND\n");
  expectRejected(k, "job.src:2:", "broken number");
  const Bad t = write("broken-tp", "j.ls",
                      "/PROG  J\n/MN\n   1:L P[1] 100mm/sec FINE ;\n/POS\nP[1]{\n   GP1:\n\tUF : "
                      "0, UT : 1,\t\tCONFIG : 'N U T, 0, 0, 0',\n"
                      "\tX =  1.0.0  mm,\tY = 0.000  mm,\tZ = 0.000  mm,\n\tW = 0.000 deg,\tP = "
                      "0.000 deg,\tR = 0.000 deg\n};\n/END\n");
  expectRejected(t, "j.ls:8:", "broken number");
}

TEST(PostprocCli, MissingDatNamesTheTargetAsUnresolved) {
  // a .src may stand alone (its points globals of $config.dat or another module): it reads, and
  // the target it cannot place is named with its line, not refused
  const Bad b = write("nodat", "job.src", "DEF job( )\nPTP $AXIS_ACT\nLIN XP1 C_DIS\nEND\n");
  const auto r = test::runRoprec("inspect '" + b.program + "' --all");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"ref\": \"XP1\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"line\": 3"), std::string::npos) << r.out;
  EXPECT_EQ(r.err.find("missing .dat"), std::string::npos) << r.err;
}

TEST(PostprocCli, TruncatedFile) {
  expectRejected(write("trunc-tp", "j.ls",
                       "/PROG  J\n/MN\n   1:L P[1] 100mm/sec FINE ;\n/POS\nP[1]{\n   GP1:\n"),
                 "j.ls:", "unterminated position record");
  expectRejected(write("trunc-tp2", "j.ls", "/PROG  J\n/MN\n   1:  WAIT 1.00(sec) ;\n"),
                 "j.ls:", "truncated file");
  expectRejected(
      write("trunc-krl", "job.src", "DEF job( )\nPTP {A1 0,A2 -90,A3 90,A4 0,A5 0,A6 0}\n"),
      "job.src:", "truncated file");
  expectRejected(
      write("trunc-rapid", "m.mod", "MODULE m\n  PROC main()\n    WaitTime 1;\n  ENDPROC\n"),
      "m.mod:", "truncated file");
  expectRejected(
      write("trunc-json", "t.json", "{\"targets\": [ {\"id\": \"a\", \"position_mm\": [1, 2"),
      "t.json:", "unterminated");
}

TEST(PostprocCli, UnknownInstructionsAreKeptVerbatim) {
  const struct {
    const char* name;
    const char* text;
  } cases[] = {
      {"job.src",
       "DEF job( )\nFOO_BAR 1, 2 ; vendor macro\nLIN {X 1,Y 2,Z 3,A 0,B 0,C "
       "0}\nZAUBERN(#SCHNELL)\nEND\n"},
      {"m.mod",
       "MODULE m\n  PROC main()\n    FrobnicateL \\Fast, 3;\n    MoveL "
       "[[1,2,3],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]],v100,fine,tool0;\n  "
       "ENDPROC\nENDMODULE\n"},
      {"j.ls",
       "/PROG  J\n/MN\n   1:  WKZ_NUM=1 ;\n   2:  WENN R[1]=1,SPRUNG LBL[2] ;\n   3:L P[1] "
       "100mm/sec FINE ;\n/POS\nP[1]{\n   GP1:\n\tUF : 0, UT : 1,\t\tCONFIG : 'N U T, 0, 0, 0',\n"
       "\tX = 1.000  mm,\tY = 0.000  mm,\tZ = 0.000  mm,\n\tW = 0.000 deg,\tP = 0.000 deg,\tR = "
       "0.000 deg\n};\n/END\n"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const Bad b = write("unknown", c.name, c.text);
    const std::string out = b.dir + "/out" + fs::path(c.name).extension().string();
    const auto r = test::runRoprec("convert '" + b.program + "' --o '" + out + "'");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(test::readFile(out), c.text);
    const auto i = test::runRoprec("inspect '" + b.program + "' --all");
    EXPECT_EQ(i.exit_code, 0) << i.err;
    EXPECT_NE(i.out.find("\"targets\""), std::string::npos);
  }
}

TEST(PostprocCli, InspectAndConvertCorpus) {
  if (test::corpusDir().empty()) GTEST_SKIP() << "no corpus";
  const std::string dir = test::tempDir("cli-corpus");
  const std::string src = test::corpusDir() + "/robodk/DrillKRC2DAT.src";
  const auto r = test::runRoprec("convert '" + src + "' --o '" + dir + "/copy.src'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::readFile(dir + "/copy.src"), test::readFile(src));
  EXPECT_EQ(test::readFile(dir + "/copy.dat"),
            test::readFile(test::corpusDir() + "/robodk/DrillKRC2DAT.dat"));
  const auto i = test::runRoprec("inspect '" + src + "' --holes '" + test::sourceDir() +
                                 "/tests/data/programs/holes.csv' --all");
  ASSERT_EQ(i.exit_code, 0) << i.err;
  EXPECT_NE(i.out.find("\"hole_list_id\": \"H3\""), std::string::npos);
  EXPECT_NE(i.out.find("\"position_mm\": [1400.000000, 80.000000, 388.000000]"), std::string::npos);
  // deterministic
  EXPECT_EQ(test::runRoprec("inspect '" + src + "' --all").out,
            test::runRoprec("inspect '" + src + "' --all").out);
  const auto c = test::runRoprec("convert '" + src + "' --to tp --o '" + dir + "/t.ls'");
  EXPECT_EQ(c.exit_code, 1);  // joint approach targets are listed
  EXPECT_TRUE(fs::exists(dir + "/t.ls"));
}

}  // namespace
}  // namespace roprec
