// The milling job read by windows (compensateStreamedMillingJob) against the same job read whole
// (compensateMillingJob): the compensated program, the --targets exports (CSV and JSON) and the
// report are the same bytes whatever the window size (a window boundary inside a run of one mill,
// box stock passes spread over many windows), the block size and the thread count; an error the
// first reading finds late in the program exits 2 with nothing written.
#include "plugin/api/milling_job.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "compensator/support/c_format.hpp"
#include "plugin/api/job.hpp"
#include "plugin/report/milling_report.hpp"
#include "postproc/program.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

/// What compensate writes of a milling job.
struct MillingOutputs {
  std::string src, dat, csv, json, report;
  std::vector<std::string> failures, refused;
  std::vector<std::string> force_notes;  ///< the job's "--force: ..." notes
};

std::vector<std::string> forceNotes(const std::vector<std::string>& notes) {
  std::vector<std::string> out;
  for (const std::string& n : notes)
    if (n.rfind("--force", 0) == 0) out.push_back(n);
  return out;
}

MillingPathOptions pathOptions(int threads, size_t block) {
  MillingPathOptions o;
  o.resolve_edges = false;  // as compensate
  o.threads = threads;
  o.block = block;
  return o;
}

/// The job read whole: its edited program rendered, its exports and report.
MillingOutputs wholeJob(const std::string& cell, const std::string& prog, int threads, size_t block,
                        bool force = false) {
  const api::MillingCompensationResult r =
      api::compensateMillingJob(cell, prog, force, pathOptions(threads, block));
  MillingOutputs o;
  const std::vector<std::string> files = postproc::renderFiles(*r.context.job.program);
  o.src = files.at(0);
  if (files.size() > 1) o.dat = files[1];
  o.csv = api::millingTargetsCsv(r);
  o.json = api::millingTargetsJson(r, prog);
  o.report = api::millingCompensationReport(r, prog);
  o.failures = r.failures;
  o.refused = r.refused;
  o.force_notes = forceNotes(r.context.job.notes);
  return o;
}

/// The job read by windows of `window` bytes: the program as written, the exports and the report
/// from the blocks as they come.
MillingOutputs streamedJob(const std::string& cell, const std::string& prog, int threads,
                           size_t block, size_t window, bool force = false) {
  api::MillingCompensationResult r = api::loadStreamedMillingJob(cell, prog, window, force);
  MillingOutputs o;
  api::MillingTargetsStream csv(true, prog, [&](std::string_view v) { o.csv += v; });
  api::MillingTargetsStream json(false, prog, [&](std::string_view v) { o.json += v; });
  api::MillingReportSummary sum;
  std::string rows;
  std::optional<std::string> dat;
  api::compensateStreamedMillingJob(
      r, pathOptions(threads, block), [&](std::string_view v) { o.src += v; }, dat,
      [&](const api::MillingCompensationResult& blk) {
        csv.points(blk);
        json.points(blk);
        api::addMillingReportPoints(sum, blk);
        api::writeMillingReportRows(blk, [&](std::string_view v) { rows += v; });
      },
      window);
  csv.finish(r);
  json.finish(r);
  api::writeMillingReport(
      sum, r, prog, [&](const api::ByteSink& sink) { sink(rows); },
      [&](std::string_view v) { o.report += v; });
  if (dat) o.dat = *dat;
  o.failures = r.failures;
  o.refused = r.refused;
  o.force_notes = forceNotes(r.context.job.notes);
  return o;
}

void expectSameOutputs(const MillingOutputs& a, const MillingOutputs& b, const std::string& what) {
  EXPECT_EQ(a.src, b.src) << what;
  EXPECT_EQ(a.dat, b.dat) << what;
  EXPECT_EQ(a.csv, b.csv) << what;
  EXPECT_EQ(a.json, b.json) << what;
  EXPECT_EQ(a.report, b.report) << what;
  EXPECT_EQ(a.failures, b.failures) << what;
  EXPECT_EQ(a.refused, b.refused) << what;
  EXPECT_EQ(a.force_notes, b.force_notes) << what;
}

// A wall pass of 600 points: windows of 2 KB (about 30 points: boundaries everywhere, inside
// the blocks of the chains), 16 KB and the default, blocks of 7 and 512 points, 1 and 2 threads.
TEST(MillingJob, WindowedReadingWritesTheBytesOfTheWholeProgramJob) {
  const std::string dir = test::tempDir("milling_job");
  const std::string prog = dir + "/wall.src";
  test::writeFile(prog, test::krlWallPass(600));
  const std::string cell = test::sourceDir() + "/samples/cells/alu-milling-7075.xml";
  ASSERT_TRUE(api::millingStreams(prog));
  const MillingOutputs whole = wholeJob(cell, prog, 1, 512);
  ASSERT_TRUE(whole.failures.empty());
  ASSERT_NE(whole.src, test::readFile(prog));  // the targets moved
  for (const size_t window : {size_t{2048}, size_t{16384}, size_t{0}}) {
    for (const size_t block : {size_t{7}, size_t{512}}) {
      for (const int threads : {1, 2}) {
        expectSameOutputs(whole, streamedJob(cell, prog, threads, block, window),
                          "window " + std::to_string(window) + " block " + std::to_string(block) +
                              " threads " + std::to_string(threads));
      }
    }
  }
}

/// A RAPID wall pass of `n` points (n even) with two motions on each line, the second one ending
/// on the next line (a window ending inside it reads that line again after the first motion's
/// inline target), every fifth pair to robtargets declared by name two on one line, the second
/// declaration over two lines.
std::string rapidTwoPerLine(int n) {
  const auto target = [](double x) {
    return "[[" + cFixed(x, 4) +
           ",0.000,-5.000],[0,1,0,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]]";
  };
  const std::string args = ", v60, z1, tSpindle \\WObj:=wPart;";
  std::string declared, body;
  for (int i = 0; i < n; i += 2) {
    const double x = -50 + 120.0 * i / n;
    const double x2 = -50 + 120.0 * (i + 1) / n;
    std::string a = target(x), b = target(x2);
    if (i % 10 == 4) {
      const std::string qa = "q" + std::to_string(i), qb = "q" + std::to_string(i + 1);
      declared += "  CONST robtarget " + qa + " := " + a + "; CONST robtarget " + qb + " :=\n    " +
                  b + ";\n";
      a = qa;
      b = qb;
    }
    body += "    MoveL " + a + args + " MoveL " + b + ",\n     " + args.substr(1) + "\n";
  }
  return "MODULE wall_pass\n"
         "  PERS tooldata tSpindle := "
         "[TRUE,[[0,0,300],[1,0,0,0]],[30,[0,0,140],[1,0,0,0],0,0,0]];\n"
         "  PERS wobjdata wPart := "
         "[FALSE,TRUE,\"\",[[1600,0,400],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n" +
         declared + "  PROC main()\n    MoveJ " + target(-60) +
         ", v1000, z10, tSpindle \\WObj:=wPart;\n" + body + "  ENDPROC\nENDMODULE\n";
}

// ABB RAPID modules: inline targets (the CAM style), robtargets declared by name before and after
// the routine, a header longer than a window before MODULE, statements over two lines, two on one
// line: read by windows of 300 B to 4 KB that end inside statements (the next window reads such a
// line again) and of the default size, blocks of 7 points on 2 threads and of 512 on 1: the bytes
// of the whole-program job.
TEST(MillingJob, RapidModuleByWindowsWritesTheBytesOfTheWholeProgramJob) {
  const std::string dir = test::tempDir("milling_job");
  const std::string cell = test::abbMillingCell(dir);
  // a controller's header and comments over a window before MODULE (the marker's line)
  std::string header = "%%%\n  VERSION:1\n  LANGUAGE:ENGLISH\n%%%\n";
  for (int k = 0; k < 20; ++k)
    header += "! CAM post-processor header line " + std::to_string(k) + "\n";
  test::writeFile(dir + "/wall.mod", header + test::rapidWallPass(100));
  test::writeFile(dir + "/pairs.mod", rapidTwoPerLine(120));
  const std::vector<std::pair<std::string, std::vector<size_t>>> modules = {
      {"wall.mod", {700, 0}}, {"pairs.mod", {300, 1000, 4096}}};
  for (const auto& [name, windows] : modules) {
    const std::string prog = dir + "/" + name;
    ASSERT_TRUE(api::millingStreams(prog)) << name;
    const MillingOutputs whole = wholeJob(cell, prog, 1, 512);
    ASSERT_TRUE(whole.failures.empty()) << name;
    ASSERT_TRUE(whole.refused.empty()) << name << ": " << whole.refused.front();
    ASSERT_NE(whole.src, test::readFile(prog)) << name;  // the targets moved
    for (const size_t window : windows) {
      for (const auto& [block, threads] : {std::pair<size_t, int>{7, 2}, {512, 1}}) {
        expectSameOutputs(whole, streamedJob(cell, prog, threads, block, window),
                          name + " window " + std::to_string(window) + " block " +
                              std::to_string(block) + " threads " + std::to_string(threads));
      }
    }
  }
}

// FANUC TP programs (tpWallPass: records swapped and one last, a position never taught and one not
// in /POS, home used again, a header over several windows; LF and CRLF): read by windows of 300 B
// to 4 KB that end inside records and of the default size, blocks of 7 points on 2 threads and of
// 512 on 1: the bytes of the whole-program job (the marker renumbers every /MN line).
TEST(MillingJob, TpProgramByWindowsWritesTheBytesOfTheWholeProgramJob) {
  const std::string dir = test::tempDir("milling_job");
  const std::string cell = test::fanucMillingCell(dir);
  test::writeFile(dir + "/wall.ls", test::tpWallPass(90));
  test::writeFile(dir + "/crlf.ls", test::tpWallPass(40, "\r\n"));
  const std::vector<std::pair<std::string, std::vector<size_t>>> programs = {
      {"wall.ls", {300, 4096, 0}}, {"crlf.ls", {700, 1500}}};
  for (const auto& [name, windows] : programs) {
    const std::string prog = dir + "/" + name;
    ASSERT_TRUE(api::millingStreams(prog)) << name;
    const MillingOutputs whole = wholeJob(cell, prog, 1, 512);
    ASSERT_TRUE(whole.failures.empty()) << name << ": " << whole.failures.front();
    ASSERT_TRUE(whole.refused.empty()) << name << ": " << whole.refused.front();
    ASSERT_NE(whole.src.find("roprec compensated"), std::string::npos) << name;
    for (const size_t window : windows) {
      for (const auto& [block, threads] : {std::pair<size_t, int>{7, 2}, {512, 1}}) {
        expectSameOutputs(whole, streamedJob(cell, prog, threads, block, window),
                          name + " window " + std::to_string(window) + " block " +
                              std::to_string(block) + " threads " + std::to_string(threads));
      }
    }
  }
}

// A program roprec already compensated (its marker after the DEF line), compensated again with
// --force: read by windows too, the same bytes and the same "--force" note at the marker's line;
// without --force the same refusal.
TEST(MillingJob, ForcedCompensatedProgramByWindowsIsTheWholeProgramJob) {
  const std::string dir = test::tempDir("milling_job");
  const std::string cell = test::sourceDir() + "/samples/cells/alu-milling-7075.xml";
  test::writeFile(dir + "/wall.src", test::krlWallPass(300));
  const std::string prog = dir + "/marked.src";
  test::writeFile(prog, wholeJob(cell, dir + "/wall.src", 1, 512).src);
  ASSERT_FALSE(api::millingStreams(prog, false));
  ASSERT_TRUE(api::millingStreams(prog, true));
  const MillingOutputs whole = wholeJob(cell, prog, 1, 512, true);
  ASSERT_EQ(whole.force_notes.size(), 1u);
  EXPECT_NE(whole.force_notes[0].find("marked.src:5)"), std::string::npos) << whole.force_notes[0];
  for (const size_t window : {size_t{2048}, size_t{0}}) {
    for (const int threads : {1, 2}) {
      expectSameOutputs(whole, streamedJob(cell, prog, threads, 7, window, true),
                        "window " + std::to_string(window) + " threads " + std::to_string(threads));
    }
  }
  std::string whole_error;
  try {
    (void)api::compensateMillingJob(cell, prog);
  } catch (const InputError& e) {
    whole_error = e.what();
  }
  ASSERT_NE(whole_error.find("already compensated"), std::string::npos) << whole_error;
  try {
    (void)api::loadStreamedMillingJob(cell, prog, 2048);
    ADD_FAILURE() << "a marked program read by windows without force";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), whole_error);
  }
}

// The box stock sample: each pass engages what the earlier passes left (the engagement tracked
// along the real paths across windows of 512 bytes, a few lines each).
TEST(MillingJob, BoxStockPassesOverManyWindowsAreTheWholeProgramJobs) {
  const std::string cell = test::sourceDir() + "/samples/milling/box-stock-7075.xml";
  const std::string prog = test::sourceDir() + "/samples/milling/box_passes.src";
  const MillingOutputs whole = wholeJob(cell, prog, 1, 16);
  for (const size_t window : {size_t{512}, size_t{0}}) {
    for (const int threads : {1, 2}) {
      expectSameOutputs(whole, streamedJob(cell, prog, threads, 16, window),
                        "window " + std::to_string(window) + " threads " + std::to_string(threads));
    }
  }
}

std::string millProgram(const std::string& passes) {
  return "DEF mills ( )\nBAS (#INITMOV,0 )\n"
         "$BASE = {FRAME: X 1600.0,Y 0.0,Z 400.0,A 0.0,B 0.0,C 0.0}\n"
         "TOOL_DATA[1] = {X 0.0,Y 0.0,Z 300.0,A 0.0,B 0.0,C 0.0}\n"
         "TOOL_DATA[2] = {X 0.0,Y 0.0,Z 300.0,A 0.0,B 0.0,C 0.0}\n"
         "PTP {X -60.0,Y 0.0,Z 80.0,A 0.0,B 0.0,C 180.0}\n" +
         passes + "END\n";
}

// Three runs of two mills (a tool change between passes), each run spread over several windows
// and blocks: each run restarts its cutting decisions and chains as the whole-program job does.
TEST(MillingJob, RunsOfTwoMillsAcrossWindowsAreTheWholeProgramJobs) {
  const std::string dir = test::tempDir("milling_job");
  test::writeFile(dir + "/two.xml", test::twoMillCell());
  const std::string prog = dir + "/mills.src";
  test::writeFile(prog, millProgram(test::krlMillPass(1, 0, 80) + test::krlMillPass(2, 20, 70) +
                                    test::krlMillPass(1, 40, 60)));
  const api::MillingCompensationResult r = api::loadStreamedMillingJob(dir + "/two.xml", prog);
  ASSERT_EQ(r.runs.size(), 3u);
  EXPECT_EQ(r.runs[1].second, 1);
  const MillingOutputs whole = wholeJob(dir + "/two.xml", prog, 1, 512);
  for (const size_t window : {size_t{1024}, size_t{0}}) {
    for (const int threads : {1, 2}) {
      expectSameOutputs(whole, streamedJob(dir + "/two.xml", prog, threads, 32, window),
                        "window " + std::to_string(window) + " threads " + std::to_string(threads));
    }
  }
}

// A tool the cell's mills do not have at the last pass of a long program: the first reading
// finds it before any point is compensated; compensate exits 2 at its line, nothing written.
TEST(MillingJob, LateToolErrorExitsTwoWithNothingWritten) {
  const std::string dir = test::tempDir("milling_job");
  test::writeFile(dir + "/two.xml", test::twoMillCell());
  const std::string prog = dir + "/late.src";
  const std::string text = millProgram(test::krlMillPass(1, 0, 3000) + test::krlMillPass(3, 20, 5));
  test::writeFile(prog, text);
  ASSERT_TRUE(api::millingStreams(prog));
  const test::RunResult r =
      test::runRoprec("compensate --cell '" + dir + "/two.xml' '" + prog + "' -o '" + dir +
                      "/out.src' --targets '" + dir + "/t.csv' --report '" + dir + "/r.html'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const size_t line = static_cast<size_t>(
      std::count(
          text.begin(),
          text.begin() + static_cast<std::ptrdiff_t>(text.find("LIN", text.find("TOOL_DATA[3]"))),
          '\n') +
      1);
  EXPECT_NE(r.err.find("late.src:" + std::to_string(line) + ":"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("not a mill of the cell's tool table"), std::string::npos) << r.err;
  for (const char* f : {"out.src", "t.csv", "r.html"})
    EXPECT_FALSE(std::filesystem::exists(dir + "/" + f)) << f;
}

}  // namespace
}  // namespace roprec
