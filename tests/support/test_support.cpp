#include "tests/support/test_support.hpp"

#ifndef _WIN32
#include <sys/wait.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "compensator/support/c_format.hpp"
#include "compensator/support/platform.hpp"
#include "tests/support/process.hpp"

namespace fs = std::filesystem;

namespace roprec::test {

std::string sourceDir() { return ROPREC_SOURCE_DIR; }

std::string corpusDir() {
  const fs::path p = fs::path(ROPREC_SOURCE_DIR) / ".." / "shared" / "corpus";
  if (fs::exists(p)) return fs::canonical(p).generic_string();
  // In CI the corpus is part of the job: a missing corpus must fail the test that wanted it (a
  // failure recorded before GTEST_SKIP() keeps the test failed), not skip it silently.
  if (const char* ci = std::getenv("CI"); ci != nullptr && std::string(ci) == "true") {
    ADD_FAILURE()
        << "CI=true but the test corpus " << p.lexically_normal().string()
        << " is missing (tests that read ../shared/corpus fail in CI instead of skipping)";
  }
  return std::string();
}

std::string roprecBin() { return ROPREC_BIN; }

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void writeFile(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

std::string krlDrillCycles(int n, const std::string& base, bool drill_comment,
                           const std::string& tail) {
  std::ostringstream s;
  s << "DEF big ( )\n"
    << base << "\n$TOOL = {FRAME: X 0.000,Y 0.000,Z 320.000,A 0.000,B 0.000,C 0.000}\n";
  for (int k = 0; k < n; ++k) {
    char p[96];
    std::snprintf(p, sizeof p, "X %.3f,Y %.3f,Z %%.1f,A 0.000,B 0.000,C 180.000",
                  -30 + 1.2 * (k % 50), -25 + 1.2 * std::floor(k / 50.0));
    char a[128];
    char f[128];
    std::snprintf(a, sizeof a, p, 300.0);
    std::snprintf(f, sizeof f, p, 270.0);  // 30 mm: the Ø8.5 drill cuts 34
    s << "$VEL.CP = 0.25\nPTP {" << a << "}\n$VEL.CP = 0.02\nLIN {" << f << "}\n"
      << (drill_comment ? "; spindle drill\n" : "") << "$VEL.CP = 0.25\nLIN {" << a << "}\n";
  }
  s << tail << "END\n";
  return s.str();
}

std::string krlCyclesOfDepths(const std::vector<double>& depths_mm) {
  std::ostringstream s;
  s << "DEF depths ( )\n"
    << kHousingBase << "\n$TOOL = {FRAME: X 0.000,Y 0.000,Z 320.000,A 0.000,B 0.000,C 0.000}\n";
  for (std::size_t k = 0; k < depths_mm.size(); ++k) {
    char a[128];
    char f[128];
    const double x = -40.0 + 40.0 * static_cast<double>(k);
    std::snprintf(a, sizeof a, "X %.3f,Y 0.000,Z 300.000,A 0.000,B 0.000,C 180.000", x);
    std::snprintf(f, sizeof f, "X %.3f,Y 0.000,Z %.3f,A 0.000,B 0.000,C 180.000", x,
                  300.0 - depths_mm[k]);
    s << "$VEL.CP = 0.25\nPTP {" << a << "}\n$VEL.CP = 0.02\nLIN {" << f << "}\n"
      << "$VEL.CP = 0.25\nLIN {" << a << "}\n";
  }
  s << "END\n";
  return s.str();
}

std::string tempDir(const std::string& tag) {
  static int counter = 0;
  const char* const root = std::getenv("ROPREC_TEST_TMPDIR");  // else the system's temp folder
  const fs::path p =
      (root != nullptr && *root != '\0' ? fs::path(root) : fs::temp_directory_path()) /
      ("roprec-test-" + std::to_string(platform::processId()) + "-" + tag + "-" +
       std::to_string(counter++));
  fs::remove_all(p);
  fs::create_directories(p);
  return p.generic_string();  // "/" between names on Windows too, like the paths tests join
}

RunResult runRoprec(const std::string& args) { return runCommand("'" + roprecBin() + "' " + args); }

namespace {
bool isAssignment(const std::string& word) {
  const std::size_t eq = word.find('=');
  return eq != std::string::npos && eq > 0 &&
         word.find_first_not_of(
             "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_") == eq;
}

/// A command line with shell operators, through /bin/sh (POSIX only).
RunResult runShell(const std::string& command) {
#ifdef _WIN32
  ADD_FAILURE() << "this command needs a POSIX shell: " << command;
  return RunResult{127, "", ""};
#else
  const std::string dir = tempDir("run");
  const std::string out = dir + "/stdout";
  const std::string err = dir + "/stderr";
  const std::string cmd = "{ " + command + "; } >'" + out + "' 2>'" + err + "' </dev/null";
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
  r.out = readFile(out);
  r.err = readFile(err);
  fs::remove_all(dir);
  return r;
#endif
}
}  // namespace

// A command line written with POSIX shell quoting: leading NAME=VALUE words (and `env -u NAME`)
// set the environment;
// a plain command (a program path and its words) is started directly by runProcess
// (tests/support/process.hpp: the same on Linux and Windows); one with shell operators (|, >, &&,
// ...) goes to /bin/sh, and fails the test on Windows.
RunResult runCommand(const std::string& command) {
  std::vector<std::string> words = shellWords(command);
  std::vector<std::string> env;
  while (!words.empty() && isAssignment(words.front())) {
    env.push_back(words.front());
    words.erase(words.begin());
  }
  // env -u NAME ... COMMAND: NAME removed from the child's environment (on Windows too)
  if (words.size() > 1 && words[0] == "env" && words[1] == "-u") {
    words.erase(words.begin());
    while (words.size() > 1 && words[0] == "-u") {
      env.push_back(words[1]);
      words.erase(words.begin(), words.begin() + 2);
    }
  }
  const bool plain = !words.empty() && std::none_of(words.begin(), words.end(), isShellOperator) &&
                     words.front().find('/') != std::string::npos;
  if (!plain) return runShell(command);
  const ProcessResult p = runProcess(words, env);
  return RunResult{p.exit_code, p.out, p.err};
}

std::string krlWallPass(int n) {
  const std::string sample = readFile(sourceDir() + "/samples/milling/wall_pass.src");
  const size_t head = sample.find('\n', sample.find("$VEL.CP = 0.06000")) + 1;
  const size_t tail = sample.find("LIN {X 70.000");
  std::string s = sample.substr(0, head);
  for (int i = 0; i < n; ++i) {
    s += "LIN {X " + cFixed(-50 + 120.0 * i / n, 4) +
         ",Y 0.000,Z -5.000,A 0.000,B 0.000,C 180.000} C_DIS\n";
  }
  return s + sample.substr(tail);
}

std::string rapidWallPass(int n) {
  const auto target = [](double x, double z) {
    return "[[" + cFixed(x, 4) + ",0.000," + cFixed(z, 3) +
           "],[0,1,0,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]]";
  };
  const std::string args = ", v60, z1, tSpindle \\WObj:=wPart;\n";
  std::string declared, late, body;
  for (int i = 0; i < n; ++i) {
    const double x = -50 + 120.0 * i / n;
    const std::string name = "p" + std::to_string(i);
    if (i % 2 == 0) {  // every other one after a WaitTime on its line
      body += std::string(i % 4 == 0 ? "    WaitTime 0.1; MoveL " : "    MoveL ") + target(x, -5) +
              ",\n      v60, z1, tSpindle \\WObj:=wPart;\n";
    } else {
      (i % 10 == 9 ? late : declared) +=
          "  CONST robtarget " + name + " := " + target(x, -5) + ";\n";
      body += "    MoveL " + name + args;
    }
  }
  return "MODULE wall_pass\n"
         "  ! pocket wall finishing pass (roprec test)\n"
         "  PERS tooldata tSpindle := "
         "[TRUE,[[0,0,300],[1,0,0,0]],[30,[0,0,140],[1,0,0,0],0,0,0]];\n"
         "  PERS wobjdata wPart := "
         "[FALSE,TRUE,\"\",[[1600,0,400],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n" +
         declared + "  PROC main()\n    ConfL \\Off;\n    MoveJ " + target(-60, 50) +
         ", v1000, z10, tSpindle \\WObj:=wPart;\n" + body + "    MoveL " + target(70, 50) +
         ", v1000, z10, tSpindle \\WObj:=wPart;\n  ENDPROC\n" + late + "ENDMODULE\n";
}

namespace {

/// samples/cells/alu-milling-7075.xml with robot `robot`, written to `dir`/`name`; returns its
/// path.
std::string millingCellWithRobot(const std::string& dir, const std::string& robot,
                                 const std::string& name) {
  std::string text = readFile(sourceDir() + "/samples/cells/alu-milling-7075.xml");
  const size_t at = text.find("<robot ref=\"");
  if (at == std::string::npos) throw std::runtime_error("milling sample cell: no <robot ref=");
  text.replace(at, text.find("/>", at) + 2 - at, "<robot ref=\"" + robot + "\"/>");
  writeFile(dir + "/" + name, text);
  return dir + "/" + name;
}

}  // namespace

std::string abbMillingCell(const std::string& dir) {
  return millingCellWithRobot(dir, "abb-irb6700-200-260", "abb-milling.xml");
}

std::string fanucMillingCell(const std::string& dir) {
  return millingCellWithRobot(dir, "fanuc-r2000ic-165f", "fanuc-milling.xml");
}

std::string tpWallPass(int n, const std::string& eol, bool late_record) {
  const auto record = [&](int k, double x, double z) {
    return "P[" + std::to_string(k) + "]{" + eol + "   GP1:" + eol +
           "\tUF : 1, UT : 1,\t\tCONFIG : 'N U T, 0, 0, 0'," + eol + "\tX = " + cFixed(x, 4) +
           "  mm,\tY =     0.000  mm,\tZ = " + cFixed(z, 3) + "  mm," + eol +
           "\tW =   180.000 deg,\tP =     0.000 deg,\tR =     0.000 deg" + eol + "};" + eol;
  };
  std::vector<std::string> mn = {"UFRAME_NUM=1 ;", "UTOOL_NUM=1 ;", "J PR[1] 50% CNT50 ;",
                                 "! wall pass ;",
                                 "J P[1:home] 50% CNT50 TB    .50sec,CALL SPINDLE_ON ;"};
  std::vector<std::string> sub = {"      1:  DO[3]=ON ;", "       ------ ;"};
  mn.push_back("L P[2] 250mm/sec CNT10 ;");
  std::vector<std::pair<int, std::string>> pos;  // (number, record) in /POS order
  pos.emplace_back(1, record(1, -60, 50));
  pos.emplace_back(2, record(2, -60, -5));
  const int first = 3;
  for (int i = 0; i < n; ++i) {
    const int k = first + i;
    mn.push_back("L P[" + std::to_string(k) + "] 60mm/sec CNT100 ;");
    if (i % 7 == 3) mn.push_back("WAIT    .10(sec) ;");
    pos.emplace_back(k, record(k, -50 + 120.0 * i / n, -5));
  }
  const int end = first + n;
  mn.push_back("L P[" + std::to_string(end) + "] 60mm/sec CNT100 ;");
  mn.push_back("C P[" + std::to_string(end + 1) + "] ");
  mn.push_back(":  P[" + std::to_string(end + 2) + "] 60mm/sec CNT100 ;");
  mn.push_back("L PR[3] 60mm/sec FINE ;");
  mn.push_back("L P[R[4]] 60mm/sec FINE ;");
  mn.push_back("L P[" + std::to_string(end + 3) + "] 60mm/sec FINE ;");  // never taught
  mn.push_back("L P[" + std::to_string(end + 9) + "] 60mm/sec FINE ;");  // not in /POS
  mn.push_back("L P[" + std::to_string(end + 4) + "] 250mm/sec CNT50 ;");
  mn.push_back("J P[1:home] 50% CNT50 ;");
  pos.emplace_back(end, record(end, 70, -5));
  pos.emplace_back(end + 1, record(end + 1, 75, 0));
  pos.emplace_back(end + 2, record(end + 2, 70, 5));
  pos.emplace_back(end + 3, "P[" + std::to_string(end + 3) + "]{" + eol + "   GP1:" + eol +
                                "\tUF : F, UT : F,\t\tCONFIG : 'N U T, 0, 0, 0'," + eol +
                                "\tX = ********  mm,\tY = ********  mm,\tZ = ********  mm," + eol +
                                "\tW = ******** deg,\tP = ******** deg,\tR = ******** deg" + eol +
                                "};" + eol);
  pos.emplace_back(end + 4, record(end + 4, 70, 50));
  pos.emplace_back(end + 5, "P[" + std::to_string(end + 5) + "]{" + eol + "   GP2:" + eol +
                                "\tUF : 1, UT : 1," + eol + "\tJ1=     0.000  mm" + eol + "};" +
                                eol);
  pos.emplace_back(
      end + 6, "P[" + std::to_string(end + 6) + "]{" + eol + "   GP1:" + eol + "\tUF : 1, UT : 1," +
                   eol + "\tJ1=     0.000 deg,\tJ2=   -10.000 deg,\tJ3=   -16.000 deg," + eol +
                   "\tJ4=     0.000 deg,\tJ5=   -73.000 deg,\tJ6=     0.000 deg" + eol + "};" +
                   eol);
  for (size_t k = first + 5; k + 1 < pos.size() && k < static_cast<size_t>(end); k += 5)
    std::swap(pos[k], pos[k + 1]);
  if (late_record && n > 4) {  // the fourth feed point's record last
    std::pair<int, std::string> late = pos[first + 3 - 1];
    pos.erase(pos.begin() + first + 3 - 1);
    pos.push_back(late);
  }
  std::string s = "/PROG  WALL_PASS" + eol + "/ATTR" + eol + "OWNER\t\t= MNEDITOR;" + eol +
                  "COMMENT\t\t= \"roprec test\";" + eol;
  for (int k = 0; k < 36; ++k)
    s += "/* CAM post header line " + std::to_string(k) + " */" + eol;  // ignored outside /MN
  s += "LINE_COUNT\t= " + std::to_string(mn.size()) + ";" + eol + "/MN" + eol;
  int line = 0;
  for (const std::string& m : mn) {
    if (m[0] == ':') {  // the continuation line of a circular motion
      s += "    " + m + eol;
      continue;
    }
    const std::string number = std::to_string(++line);
    s += std::string(4 - std::min<size_t>(4, number.size()), ' ') + number + ":" +
         (m[0] == 'J' || m[0] == 'L' || m[0] == 'C' ? "" : "  ") + m + eol;
    if (m.find("TB ") != std::string::npos)
      for (const std::string& b : sub) s += b + eol;
  }
  s += "/POS" + eol;
  for (const auto& [number, text] : pos) s += text;
  return s + "/END" + eol;
}

std::string twoMillCell() {
  return "<cell name=\"mills\">\n  <robot ref=\"kuka-kr120-r2500-pro\"/>\n"
         "  <tool name=\"spindle\" xyz=\"0 0 300\" rpy=\"0 0 0\" mass_kg=\"30\" com_mm=\"0 0 "
         "140\"/>\n  <workobject xyz=\"1600 0 400\" rpy=\"0 0 0\"/>\n"
         "  <process type=\"milling\">\n"
         "    <mill tool=\"1\" diameter_mm=\"10\" teeth=\"3\" helix_angle_deg=\"30\"/>\n"
         "    <mill tool=\"2\" diameter_mm=\"6\" teeth=\"4\" helix_angle_deg=\"35\">"
         "<cut ae_mm=\"1\" fz_mm=\"0.06\"/></mill>\n"
         "    <cut ap_mm=\"5\" ae_mm=\"2\" fz_mm=\"0.1\" mode=\"up\" spindle_rpm=\"12000\"/>\n"
         "    <material name=\"Al 7075-T6\"/>\n    <stock top_z_mm=\"0\"/>\n"
         "  </process>\n</cell>\n";
}

std::string krlMillPass(int tool, double y, int n) {
  const auto pt = [&](double x, double z) {
    return "LIN {X " + cFixed(x, 4) + ",Y " + cFixed(y, 3) + ",Z " + cFixed(z, 3) +
           ",A 0.0,B 0.0,C 180.0} C_DIS\n";
  };
  std::string s = "$TOOL = TOOL_DATA[" + std::to_string(tool) + "]\n$VEL.CP = 0.25\n" +
                  pt(-60, 50) + pt(-60, -5) + "$VEL.CP = 0.06\n";
  for (int k = 0; k < n; ++k) s += pt(-50 + 60.0 * k / n, -5);
  return s + "$VEL.CP = 0.25\n" + pt(-10, 50);
}

}  // namespace roprec::test
