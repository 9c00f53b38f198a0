// postproc::StreamedEdits on a RAPID module read by windows (ProgramStream with `rapid`) against
// the same edits made in the module read whole: the bytes writeProgram gives, whatever the window
// size, when every byte that may be written is written after each window (a window that ends
// inside a statement leaves that statement's line to the next window: its bytes wait).
#include "postproc/streamed_edits.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "compensator/support/c_format.hpp"
#include "postproc/program.hpp"
#include "postproc/program_stream.hpp"
#include "tests/support/test_support.hpp"

namespace roprec::postproc {
namespace {

/// A module of `n` inline targets, two MoveL a line, the second ending on the next line.
std::string twoMovesALine(int n) {
  const auto target = [](double x) {
    return "[[" + cFixed(x, 4) +
           ",0.000,-5.000],[0,1,0,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]]";
  };
  std::string body;
  for (int i = 0; i < n; i += 2) {
    body += "    MoveL " + target(i) + ", v60, z1, tool0; MoveL " + target(i + 1) +
            ",\n      v60, z1, tool0;\n";
  }
  return "MODULE pass\n  PROC main()\n" + body + "  ENDPROC\nENDMODULE\n";
}

/// The inline target of every linear motion moved 1 mm along x.
Pose moved(const Program& p, const Target& t) {
  Pose T = targetPose(p, t);
  T.translation().x() += 1e-3;
  return T;
}

const std::string kMarker = "streamed edits test";

std::string wholeModuleEdited(const std::string& path) {
  Program p = readProgram(path);
  markCompensated(p, kMarker);
  for (const Motion& mo : p.motions) {
    if (mo.type != MotionType::kLinear || mo.target < 0) continue;
    EXPECT_TRUE(replaceTargetPose(p, mo.target, moved(p, p.targets()[mo.target])).ok);
  }
  return renderFiles(p).at(0);
}

/// Read by windows of `window` bytes: each window's motions' targets edited but the last `lag`
/// ones, edited after the next window is read (a target read on a line that window reads again
/// is then edited in the new window's bytes); after each window, the bytes before the first
/// target not edited yet are written (every byte that may be written when none is left).
std::string streamedModuleEdited(const std::string& path, const SourceFile& style,
                                 std::size_t window, std::size_t lag) {
  ProgramStream s(path, window, false, true);
  EXPECT_TRUE(s.windowed());
  std::string out;
  StreamedEdits e(
      s, [&](std::string_view v) { out += v; }, kMarker, style);
  std::size_t done = 0;  // the stream's motions edited
  const auto editUpTo = [&](std::size_t end) {
    Program& p = s.program();
    for (; done < end; ++done) {
      const Motion& mo = p.motions[done];
      if (mo.type != MotionType::kLinear || mo.target < 0) continue;
      EXPECT_TRUE(
          e.replaceTargetPose(mo.target, moved(p, p.targets()[mo.target]), std::nullopt).ok);
    }
  };
  while (s.next()) {
    e.installed();
    const Program& p = s.program();
    editUpTo(p.motions.size() > lag ? p.motions.size() - lag : 0);
    int line = std::numeric_limits<int>::max();
    if (done < p.motions.size()) line = p.targets()[p.motions[done].target].line;
    e.flushBeforeLine(line);
  }
  editUpTo(s.program().motions.size());
  e.finish();
  return out;
}

// Windows of 300 B to 7 KB end inside statements all along a 45 KB module (a line's
// first MoveL read in one window, its second in the next), its targets edited as each window is
// read or three motions later: the bytes of the whole module's edits.
TEST(StreamedEdits, RapidModuleByWindowsWritesTheWholeModulesEdits) {
  const std::string dir = test::tempDir("streamed_edits");
  const std::string path = dir + "/pass.mod";
  test::writeFile(path, twoMovesALine(400));
  const std::string whole = wholeModuleEdited(path);
  ASSERT_NE(whole, test::readFile(path));
  const Program style = readProgram(path);
  for (const std::size_t window : {300, 700, 1500, 4096, 7000}) {
    for (const std::size_t lag : {0, 3}) {
      EXPECT_EQ(streamedModuleEdited(path, style.files[0], window, lag), whole)
          << "window " << window << " lag " << lag;
    }
  }
}

/// The style of `path` as a first reading by windows of `window` bytes leaves it (the job's): its
/// last window's file, whose line ends count the windows before.
SourceFile firstReadingStyle(const std::string& path, std::size_t window) {
  ProgramStream s(path, window, false, true);
  while (s.next()) {
  }
  return s.program().files[0];
}

// The compensation marker of FANUC TP programs (the remark as /MN line 1, every /MN line
// renumbered, LINE_COUNT + 1) made window by window: the bytes of the whole program's marker, for
// a header longer than a window, CRLF, a file whose last 60 lines end in CRLF and the others in LF
// (the remark takes the whole file's line end, LF, which its last windows' lines do not show), an
// empty /MN, and a LINE_COUNT without a number.
TEST(StreamedEdits, TpMarkerByWindowsIsTheWholeProgramsMarker) {
  const std::string dir = test::tempDir("streamed_edits_tp");
  std::string mixed = test::tpWallPass(40);
  for (std::size_t k = 0, at = mixed.size(); k < 60; ++k) {  // the last 60 lines end in CRLF
    at = mixed.rfind('\n', at - 1);
    mixed.insert(at, 1, '\r');
  }
  const std::string empty =
      "/PROG  EMPTY\n/ATTR\nLINE_COUNT\t= ;\n/MN\n/POS\nP[1]{\n   GP1:\n\tUF : 0, UT : 1,\n"
      "\tX = 1.000  mm,\tY = 0.000  mm,\tZ = 0.000  mm,\n\tW = 0.000 deg,\tP = 0.000 deg,"
      "\tR = 0.000 deg\n};\n/END\n";
  const std::vector<std::pair<std::string, std::string>> programs = {
      {"wall.ls", test::tpWallPass(40)},
      {"crlf.ls", test::tpWallPass(40, "\r\n")},
      {"mixed.ls", mixed},
      {"empty.ls", empty}};
  for (const auto& [name, text] : programs) {
    const std::string path = dir + "/" + name;
    test::writeFile(path, text);
    Program p = readProgram(path);
    ASSERT_TRUE(markCompensated(p, kMarker)) << name;
    const std::string whole = renderFiles(p).at(0);
    ASSERT_NE(whole, text) << name;
    for (const std::size_t window : {std::size_t{64}, std::size_t{300}, std::size_t{2000}}) {
      ProgramStream s(path, window, false, true);
      std::string out;
      StreamedEdits e(
          s, [&](std::string_view v) { out += v; }, kMarker, firstReadingStyle(path, window));
      while (s.next()) {
        e.installed();
        e.flushBeforeLine(std::numeric_limits<int>::max());
      }
      e.finish();
      EXPECT_EQ(out, whole) << name << " window " << window;
    }
  }
}

}  // namespace
}  // namespace roprec::postproc
