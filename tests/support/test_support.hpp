#pragma once
/// Helpers shared by the tests: paths, running the CLI, KDL chains from the same URDF.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace roprec::test {

/// Whether a[0, n) and b[0, n) have the same bits (what byte-identical means for numbers: -0 is
/// not 0, a NaN equals the same NaN).
inline bool sameBits(const double* a, const double* b, std::size_t n = 1) {
  for (std::size_t i = 0; i < n; ++i) {
    if (std::bit_cast<std::uint64_t>(a[i]) != std::bit_cast<std::uint64_t>(b[i])) return false;
  }
  return true;
}
inline bool sameBits(double a, double b) { return sameBits(&a, &b); }

std::string sourceDir();
/// ../shared/corpus next to the source tree, or "" when absent (tests then GTEST_SKIP()). With
/// CI=true a missing corpus also records a test failure, so the test fails instead of skipping.
std::string corpusDir();
std::string roprecBin();

struct RunResult {
  int exit_code{0};
  std::string out;
  std::string err;
};
/// Runs `roprec ARGS` and captures stdout/stderr (ARGS quoted as for a POSIX shell: runCommand).
RunResult runRoprec(const std::string& args);
/// Runs a command line written with POSIX shell quoting (stdin empty) and captures stdout/stderr:
/// started directly by tests/support/process.hpp when it is plain (leading NAME=VALUE words set
/// the environment), through /bin/sh when it has shell operators (POSIX only).
RunResult runCommand(const std::string& command);
/// A fresh temporary directory in $ROPREC_TEST_TMPDIR when set (the Windows run: on the build
/// tree's drive), else in the system's temporary folder.
std::string tempDir(const std::string& tag);
std::string readFile(const std::string& path);
void writeFile(const std::string& path, const std::string& text);

/// The $BASE line of krlDrillCycles: the housing's top face in the KR 120 sample cell.
inline constexpr const char* kHousingBase =
    "$BASE = {FRAME: X 1350.000,Y 0.000,Z 300.000,A 0.000,B 0.000,C 0.000}";
/// A KRL .src of `n` drill cycles (PTP approach at z 300, feed to z 270 at a slower $VEL.CP,
/// retract) on a 1.2 mm grid of the housing's top face, 7 lines a cycle with `drill_comment`
/// (a "; spindle drill" marker after the feed), else 6, after three header lines (DEF, `base`,
/// $TOOL); `tail` goes before END.
std::string krlDrillCycles(int n, const std::string& base = kHousingBase,
                           bool drill_comment = false, const std::string& tail = "");
/// A KRL .src (header as krlDrillCycles) of one drill cycle per depth (mm), 40 mm apart along
/// x on the housing's top face: PTP approach at z 300, feed at a slower $VEL.CP to z 300 − depth,
/// retract; hole k's drill point is on line 7 + 6k.
std::string krlCyclesOfDepths(const std::vector<double>& depths_mm);
/// The sample wall pass (samples/milling/wall_pass.src) with `n` feed points over its 120 mm
/// instead of its own (scripts/bench-milling.sh's path): 3 lines before the feed points.
std::string krlWallPass(int n);
/// The sample wall pass as an ABB RAPID module (tool tSpindle, work object wPart: the KRL
/// sample's $TOOL and $BASE) with `n` feed points, every target shape a RAPID reader meets: the
/// even points inline targets written over two lines, the odd ones robtargets declared by name
/// before the routine, every tenth point's declared after the routine (the reader does not know
/// it where the motion is: an unresolved target, not a path point), every fourth point's motion
/// after a WaitTime on its line.
std::string rapidWallPass(int n);
/// samples/cells/alu-milling-7075.xml with the ABB IRB 6700 (compensate writes a RAPID module's
/// robtarget configuration only for a robot of its vendor), written to `dir`/abb-milling.xml;
/// returns its path.
std::string abbMillingCell(const std::string& dir);
/// The sample wall pass as a FANUC TP program (UFRAME 1 and UTOOL 1: the cell's workobject and
/// tool) with `n` feed points, with what TP readers meet: a header of 40 lines, remarks, point
/// logic with its sub-block, WAIT lines, a circular motion and its continuation line, motions to
/// position registers (the first motion), to P[R[4]], to a position never taught and to one not
/// in /POS; in /POS
/// every fifth pair of records swapped, one record (the fourth feed point's) last, a record of a
/// second group only, a joint record, and home P[1] used again at the end. `eol`: the line end;
/// `late_record`: without it no record is out of place by more than one.
std::string tpWallPass(int n, const std::string& eol = "\n", bool late_record = true);
/// samples/cells/alu-milling-7075.xml with the FANUC R-2000iC/165F, written to
/// `dir`/fanuc-milling.xml; returns its path.
std::string fanucMillingCell(const std::string& dir);
/// A milling cell of two mills (a tool table: tool 1 Ø10 mm, 3 teeth; tool 2 Ø6 mm, 4 teeth, its
/// own ae and fz) on the KR 120, plane stock at z 0 of the workobject (1600, 0, 400) mm.
std::string twoMillCell();
/// A KRL pass with tool `tool`: plunge at x −60 mm to z −5, `n` feed points along x from −50 mm
/// at y (mm), retract (no DEF/END).
std::string krlMillPass(int tool, double y, int n);

}  // namespace roprec::test
