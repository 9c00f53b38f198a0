// `roprec forces --program` read by windows (processForces with a ForcesPathSink on a program
// compensate reads by windows) against the same request computed on the program read whole
// (processForces without a sink): the JSON bytes, the curve CSV, the convergence and the chatter
// lines are the same whatever the window size (windows of a few points: blocks cross windows),
// the block size and the thread count, for one pass, the box stock's passes and two mills.
#include "plugin/api/forces.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <string_view>

#include "compensator/support/c_format.hpp"
#include "plugin/report/forces_output.hpp"
#include "tests/support/same_bytes.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

/// What `roprec forces --program` writes of a request, and its exit status's inputs.
struct ForcesOutputs {
  std::string json, csv;
  bool converged{true};
  std::vector<std::string> unstable;
};

api::ForcesRequest programRequest(const std::string& cell, const std::string& prog) {
  api::ForcesRequest req;
  req.cell = cell;
  req.program = prog;
  return req;
}

/// The request computed on the program read whole (no sink).
ForcesOutputs wholeForces(const api::ForcesRequest& req) {
  const api::ForcesResult r = api::processForces(req);
  EXPECT_FALSE(r.milling->path->streamed);
  const api::ForcesOutput o = api::forcesOutput(r);
  return {o.json.dump(), o.curve_csv, r.converged, r.unstable};
}

/// The request streamed block by block from the program read by windows of `window` bytes.
ForcesOutputs windowedForces(api::ForcesRequest req, std::size_t window, std::size_t block,
                             int threads) {
  req.window_bytes = window;
  req.block = block;
  req.threads = threads;
  ForcesOutputs o;
  api::ForcesJsonStream json([&](std::string_view v) { o.json.append(v); });
  api::ForcesPathSink sink;
  sink.head = [&](const api::ForcesResult& head) { o.csv = json.head(head); };
  sink.points = [&](const api::MillingCompensationResult& b) { json.points(b); };
  const api::ForcesResult r = api::processForces(req, sink);
  json.finish();
  EXPECT_TRUE(r.milling->path->streamed);  // read by windows, not whole
  EXPECT_TRUE(r.milling->path->points.empty());
  o.converged = r.converged;
  o.unstable = r.unstable;
  return o;
}

void expectSame(const ForcesOutputs& a, const ForcesOutputs& b, const std::string& what) {
  EXPECT_TRUE(test::sameBytes(a.json, b.json)) << what;
  EXPECT_TRUE(test::sameBytes(a.csv, b.csv)) << what;
  EXPECT_EQ(a.converged, b.converged) << what;
  EXPECT_EQ(a.unstable, b.unstable) << what;
}

// A wall pass of 60 points: windows of 1 KB (about 15 points: boundaries inside the blocks of
// the chains) with blocks of 7 points on 1 and 2 threads (the default window and block:
// ForcesCli.MillingProgramByWindowsStdoutIsTheJsonFilesBytes).
TEST(Forces, ProgramReadByWindowsGivesTheWholeProgramsJson) {
  const std::string dir = test::tempDir("forces_windows");
  const std::string prog = dir + "/wall.src";
  test::writeFile(prog, test::krlWallPass(60));
  const api::ForcesRequest req =
      programRequest(test::sourceDir() + "/samples/cells/alu-milling-7075.xml", prog);
  const ForcesOutputs whole = wholeForces(req);
  ASSERT_NE(whole.json.find("\"point\": 63"), std::string::npos);  // every point is there
  expectSame(whole, windowedForces(req, 1024, 7, 1), "1 KB windows, 1 thread");
  expectSame(whole, windowedForces(req, 1024, 7, 2), "1 KB windows, 2 threads");
}

/// The box stock sample's first two passes, each cut after its first `feed_points` feed points
/// (the second pass still cuts what the first left; the third pass is left out).
std::string boxPassesHead(int feed_points) {
  std::istringstream sample(test::readFile(test::sourceDir() + "/samples/milling/box_passes.src"));
  std::string s, line;
  bool third_pass = false;
  int fed = -1;  // feed points of the current pass, -1 outside the feed
  while (std::getline(sample, line)) {
    if (line.rfind("; pass 3", 0) == 0) third_pass = true;
    if (line.rfind("SPINDLE_OFF", 0) == 0) third_pass = false;
    if (line.rfind("$VEL.CP", 0) == 0) fed = line == "$VEL.CP = 0.06000" ? 0 : -1;
    const bool feed = fed >= 0 && line.rfind("LIN", 0) == 0;
    if (third_pass || (feed && fed++ >= feed_points)) continue;
    s += line + "\n";
  }
  return s;
}

// The box stock sample's first passes (the second engages what the first left: the engagements
// in the JSON) read by the smallest windows, a few lines each, on 2 threads (the read-ahead).
TEST(Forces, BoxStockPassesReadByWindowsGiveTheWholeProgramsJson) {
  const std::string dir = test::tempDir("forces_windows");
  const std::string prog = dir + "/box.src";
  test::writeFile(prog, boxPassesHead(10));
  const api::ForcesRequest req =
      programRequest(test::sourceDir() + "/samples/milling/box-stock-7075.xml", prog);
  const ForcesOutputs whole = wholeForces(req);
  ASSERT_NE(whole.json.find("\"programmed_ae_mm\""), std::string::npos);
  expectSame(whole, windowedForces(req, 512, 16, 2), "512-byte windows");
}

// Three runs of two mills (the "tool" of each point in the JSON) across windows of 1 KB.
TEST(Forces, RunsOfTwoMillsReadByWindowsGiveTheWholeProgramsJson) {
  const std::string dir = test::tempDir("forces_windows");
  test::writeFile(dir + "/two.xml", test::twoMillCell());
  const std::string prog = dir + "/mills.src";
  test::writeFile(prog,
                  "DEF mills ( )\nBAS (#INITMOV,0 )\n"
                  "$BASE = {FRAME: X 1600.0,Y 0.0,Z 400.0,A 0.0,B 0.0,C 0.0}\n"
                  "TOOL_DATA[1] = {X 0.0,Y 0.0,Z 300.0,A 0.0,B 0.0,C 0.0}\n"
                  "TOOL_DATA[2] = {X 0.0,Y 0.0,Z 300.0,A 0.0,B 0.0,C 0.0}\n"
                  "PTP {X -60.0,Y 0.0,Z 80.0,A 0.0,B 0.0,C 180.0}\n" +
                      test::krlMillPass(1, 0, 50) + test::krlMillPass(2, 20, 40) +
                      test::krlMillPass(1, 40, 30) + "END\n");
  const api::ForcesRequest req = programRequest(dir + "/two.xml", prog);
  const ForcesOutputs whole = wholeForces(req);
  ASSERT_NE(whole.json.find("\"tool\": \"2\""), std::string::npos);
  for (const int threads : {1, 2})
    expectSame(whole, windowedForces(req, 1024, 32, threads), "threads " + std::to_string(threads));
}

// An ABB RAPID wall pass (inline targets over two lines, robtargets declared before the routine,
// some after it: not path points) read by windows of 4 KB, a few points each, with blocks of 7
// points on 2 threads: the JSON of the module read whole (the KRL twins above vary the threads).
TEST(Forces, RapidModuleReadByWindowsGivesTheWholeProgramsJson) {
  const std::string dir = test::tempDir("forces_windows");
  const std::string prog = dir + "/wall.mod";
  test::writeFile(prog, test::rapidWallPass(60));
  const api::ForcesRequest req =
      programRequest(test::sourceDir() + "/samples/cells/alu-milling-7075.xml", prog);
  ASSERT_TRUE(api::millingPathStreams(prog));
  const ForcesOutputs whole = wholeForces(req);
  // 30 inline, 24 declared before the routine, the retract: 55 points (6 declared after it)
  ASSERT_NE(whole.json.find("\"point\": 55,"), std::string::npos);
  ASSERT_EQ(whole.json.find("\"point\": 56,"), std::string::npos);
  expectSame(whole, windowedForces(req, 4096, 7, 2), "4 KB windows, 2 threads");
}

// A FANUC TP wall pass (records swapped and one last, positions not known) read by windows of
// 2 KB, with blocks of 7 points on 2 threads: the JSON of the program read whole.
TEST(Forces, TpProgramReadByWindowsGivesTheWholeProgramsJson) {
  const std::string dir = test::tempDir("forces_windows");
  const std::string prog = dir + "/wall.ls";
  test::writeFile(prog, test::tpWallPass(60));
  const api::ForcesRequest req = programRequest(test::fanucMillingCell(dir), prog);
  ASSERT_TRUE(api::millingPathStreams(prog));
  const ForcesOutputs whole = wholeForces(req);
  // the approach, 60 feed points, the end of the pass and the retract
  ASSERT_NE(whole.json.find("\"point\": 63,"), std::string::npos);
  ASSERT_EQ(whole.json.find("\"point\": 64,"), std::string::npos);
  expectSame(whole, windowedForces(req, 2048, 7, 2), "2 KB windows, 2 threads");
}

// A robtarget of the wrong shape at the end of a RAPID module read by windows: `roprec forces
// --program` exits 2 at its line, as the whole read does, and writes nothing (the first reading
// finds it before the JSON's head).
TEST(Forces, LateRapidErrorExitsTwoWithNothingWritten) {
  const std::string dir = test::tempDir("forces_windows");
  std::string text = test::rapidWallPass(10000);
  const size_t late = text.find("[0,1,0,0]", text.rfind("MoveL p"));
  text.replace(late, 9, "[0,1,0]");
  const std::string prog = dir + "/late.mod";
  test::writeFile(prog, text);
  ASSERT_GT(text.size(), size_t{1} << 20U);  // more than one window of 1 MB
  ASSERT_TRUE(api::millingPathStreams(prog));
  const test::RunResult r = test::runRoprec("forces --cell '" + test::sourceDir() +
                                            "/samples/cells/alu-milling-7075.xml' --program '" +
                                            prog + "' --json '" + dir + "/f.json'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const auto line =
      std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(late), '\n') + 1;
  EXPECT_NE(r.err.find("late.mod:" + std::to_string(line) + ": robtarget rot needs 4 elements"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_FALSE(std::filesystem::exists(dir + "/f.json"));
}

}  // namespace
}  // namespace roprec
