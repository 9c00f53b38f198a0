// compensateHoles over threads: the result is byte-identical to one thread for keep,
// flip-free and stiffest — every hole's doubles bit for bit, its strings, and the run's counters —
// and through the job the written program, the targets CSV/JSON and the HTML report are the same
// bytes for 1, 2 and 3 threads. The sequence carries from hole to hole (IK seeds after an
// unreachable hole, the DP, each NLopt refinement against its refined predecessor), so the jobs
// below have unreachable holes and turned holes next to each other.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <thread>

#include "compensator/support/atomic_file.hpp"
#include "plugin/api/hole_input.hpp"
#include "plugin/api/job.hpp"
#include "plugin/api/prediction_setup.hpp"
#include "postproc/edited_file_writer.hpp"
#include "postproc/program.hpp"
#include "postproc/program_stream.hpp"
#include "tests/support/compensation_compare.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using test::expectSameHole;
using test::expectSameJobResult;
using test::expectSameStats;

std::string sharedTargetJob(const std::string& dir);

TEST(CompensateThreads, HolesAreBitIdenticalForOneTwoThreeThreads) {
  api::PredictionContext c = api::loadPredictionContext(
      test::sourceDir() + "/samples/cells/housing-kr120.xml",
      test::sourceDir() + "/samples/emotor-housing/holes.csv", std::nullopt, "");
  // the housing six times (1,200+ holes: stages 2 and 3 run in pipelined blocks of 1,024 holes,
  // and the sequence carries across the block boundary), every 9th hole of the odd copies and
  // the first hole of the second block shifted out of reach (the holes after them are seeded in
  // the sequential pass), and every hole of a band of copies 0 and 4 (which ends just before the
  // boundary) turned by 170° about its axis so that flip-free turns consecutive holes and refines
  // each against its turned predecessor
  std::vector<HoleRequest> req;
  for (int k = 0; k < 6; ++k) {
    for (HoleRequest h : c.job.requests) {
      h.id.append("_").append(std::to_string(k));
      if ((k % 2 == 1 && req.size() % 9 == 0) || req.size() == 1024)
        h.T_W_tcp.translation().x() += 3.0;
      if ((k == 0 || k == 4) && req.size() % 40 < 12)
        h.T_W_tcp.linear() =
            h.T_W_tcp.linear() * Eigen::AngleAxisd(170.0 * kDeg, Vec3::UnitZ()).toRotationMatrix();
      req.push_back(h);
    }
  }
  for (const OrientationMode mode :
       {OrientationMode::kKeep, OrientationMode::kFlipFree, OrientationMode::kStiffest}) {
    SCOPED_TRACE(orientationModeName(mode));
    CompensationOptions o;
    o.mode = mode;
    o.grid = 12;
    CompensationStats ref_stats;
    const std::vector<HoleCompensation> ref = compensateHoles(c.model, req, o, &ref_stats);
    int failed = 0;
    for (const HoleCompensation& h : ref) failed += h.ok ? 0 : 1;
    EXPECT_GT(failed, 10);  // the unreachable holes
    if (mode == OrientationMode::kFlipFree) {
      EXPECT_GT(ref_stats.psi_changed, 20);
      EXPECT_GT(ref_stats.refined, 5);
    }
    for (const int threads : {2, 3}) {
      SCOPED_TRACE(threads);
      o.threads = threads;
      CompensationStats stats;
      const std::vector<HoleCompensation> got = compensateHoles(c.model, req, o, &stats);
      ASSERT_EQ(got.size(), ref.size());
      for (size_t i = 0; i < ref.size(); ++i) expectSameHole(got[i], ref[i]);
      expectSameStats(stats, ref_stats);
    }
  }
}

// The sink overload hands over the holes of the vector result, in order, a block at a time
// (more than one block here; stiffest may hold a hole back until its next neighbour is final),
// bit for bit, with the same counters, for one and two threads. Also with blocks of 5 holes and
// a sink that sleeps now and then (the holes are finished ahead of it, as far as they may): the
// memory of a block's results is reused a few blocks later, so a failed hole (a reason, nothing
// compensated) takes the place of a compensated one the sink moved from, and the other way.
TEST(CompensateThreads, SinkGetsTheVectorResultBlockByBlock) {
  api::PredictionContext c = api::loadPredictionContext(
      test::sourceDir() + "/samples/cells/housing-kr120.xml",
      test::sourceDir() + "/samples/emotor-housing/holes.csv", std::nullopt, "");
  // the housing twelve times (more than kCompensationBlock holes), every 7th hole of the odd
  // copies out of reach, a band of each even copy turned by 170° about its axis
  std::vector<HoleRequest> req;
  while (req.size() <= kCompensationBlock + 100) {
    const size_t copy = req.size() / c.job.requests.size();
    for (HoleRequest h : c.job.requests) {
      h.id.append("_").append(std::to_string(copy));
      if (copy % 2 == 1 && req.size() % 7 == 0) h.T_W_tcp.translation().x() += 3.0;
      if (copy % 2 == 0 && req.size() % 40 < 12)
        h.T_W_tcp.linear() =
            h.T_W_tcp.linear() * Eigen::AngleAxisd(170.0 * kDeg, Vec3::UnitZ()).toRotationMatrix();
      req.push_back(h);
    }
  }
  for (const OrientationMode mode :
       {OrientationMode::kKeep, OrientationMode::kFlipFree, OrientationMode::kStiffest}) {
    SCOPED_TRACE(orientationModeName(mode));
    CompensationOptions o;
    o.mode = mode;
    o.grid = 12;
    CompensationStats ref_stats;
    const std::vector<HoleCompensation> ref = compensateHoles(c.model, req, o, &ref_stats);
    for (const auto& [threads, block] :
         {std::pair{1, kCompensationBlock}, std::pair{2, kCompensationBlock},
          std::pair{1, size_t{5}}, std::pair{2, size_t{5}}}) {
      SCOPED_TRACE(testing::Message() << "threads " << threads << ", block " << block);
      o.threads = threads;
      o.block = block;
      std::vector<HoleCompensation> got;
      int blocks = 0;
      const CompensationSink sink = [&](size_t first, std::span<HoleCompensation> holes) {
        EXPECT_EQ(first, got.size());
        EXPECT_FALSE(holes.empty());
        EXPECT_LE(holes.size(), 2 * kCompensationBlock);
        ++blocks;
        for (HoleCompensation& h : holes) got.push_back(std::move(h));
        if (block != kCompensationBlock && blocks % 16 == 0)
          std::this_thread::sleep_for(std::chrono::milliseconds(5));
      };
      CompensationStats stats;
      compensateHoles(c.model, req, o, sink, &stats);
      EXPECT_GE(blocks, 2);
      ASSERT_EQ(got.size(), ref.size());
      for (size_t i = 0; i < ref.size(); ++i) expectSameHole(got[i], ref[i]);
      expectSameStats(stats, ref_stats);
      EXPECT_EQ(stats.psi_for_jumps, ref_stats.psi_for_jumps);
      EXPECT_EQ(stats.stiffness_compared, ref_stats.stiffness_compared);
    }
  }
}

// compensateLoadedStreaming, its program's first file written piece by piece as the blocks come
// (EditedFileWriter up to each block's `stable` byte) and its targets export by rows
// (CompensationTargetsStream), writes the bytes of compensateJob and its whole-result writers;
// the counters and the summary are the same. A program with a .dat and targets two holes share,
// and the housing, in each orientation.
TEST(CompensateThreads, StreamedJobWritesTheBytesOfTheWholeJob) {
  const std::string dir = test::tempDir("compensate_threads_streamed");
  const std::string cell = test::sourceDir() + "/samples/cells/housing-kr120.xml";
  for (const std::string& program :
       {sharedTargetJob(dir), test::sourceDir() + "/samples/emotor-housing/housing_kr120.src"}) {
    for (const OrientationMode mode :
         {OrientationMode::kKeep, OrientationMode::kFlipFree, OrientationMode::kStiffest}) {
      SCOPED_TRACE(program + " " + orientationModeName(mode));
      api::CompensationJob job;
      job.options.mode = mode;
      job.job.threads = 2;
      api::CompensationResult whole = api::compensateJob(cell, program, job);
      const std::vector<std::string> want = postproc::renderFiles(*whole.context.job.program);
      api::CompensationResult r = api::loadCompensationJob(cell, program, job);
      std::string src, csv, json;
      postproc::Program& p = *r.context.job.program;
      postproc::EditedFileWriter w(p, 0, [&](std::string_view b) { src.append(b); });
      api::CompensationTargetsStream csv_rows(
          r.context, r.orientation, program, true, [&](std::string_view b) { csv.append(b); }, 2);
      api::CompensationTargetsStream json_rows(r.context, r.orientation, program, false,
                                               [&](std::string_view b) { json.append(b); });
      api::compensateLoadedStreaming(
          r, job,
          [&](api::CompensationResult& res, size_t first, std::span<const HoleCompensation> holes,
              size_t stable) {
            EXPECT_TRUE(res.holes.empty());
            const std::span<const HoleRequest> q =
                std::span<const HoleRequest>(res.context.job.requests).subspan(first, holes.size());
            w.flushBefore(stable);
            csv_rows.holes(holes, q);
            json_rows.holes(holes, q);
          });
      w.finish();
      csv_rows.finish();
      json_rows.finish();
      EXPECT_TRUE(src == want[0]);
      if (want.size() > 1) {
        EXPECT_TRUE(postproc::renderFiles(p)[1] == want[1]);
      }
      EXPECT_TRUE(csv == api::compensationTargets(whole, program, true));
      EXPECT_TRUE(json == api::compensationTargets(whole, program, false));
      expectSameJobResult(r, whole);
    }
  }
}

/// The bytes a compensation job writes: program, targets CSV and JSON, report.
std::vector<std::string> jobBytes(OrientationMode mode, int threads) {
  const std::string program = test::sourceDir() + "/samples/emotor-housing/housing_kr120.src";
  api::CompensationJob job;
  job.allow_partial = true;
  job.options.mode = mode;
  job.job.threads = threads;
  api::CompensationResult r =
      api::compensateJob(test::sourceDir() + "/samples/cells/housing-kr120.xml", program, job);
  const std::string dir = test::tempDir("compensate_threads");
  const std::string out = dir + "/out_" + std::to_string(threads) + ".src";
  api::writeCompensatedProgram(r.context, out, {});
  return {test::readFile(out), api::compensationTargets(r, program, true),
          api::compensationTargets(r, program, false), api::compensationReport(r, program)};
}

TEST(CompensateThreads, JobOutputsAreTheSameBytes) {
  for (const OrientationMode mode :
       {OrientationMode::kKeep, OrientationMode::kFlipFree, OrientationMode::kStiffest}) {
    SCOPED_TRACE(orientationModeName(mode));
    const std::vector<std::string> ref = jobBytes(mode, 1);
    ASSERT_GT(ref[0].size(), 1000U);
    for (const int threads : {2, 3}) {
      const std::vector<std::string> got = jobBytes(mode, threads);
      for (size_t k = 0; k < ref.size(); ++k) {
        SCOPED_TRACE("output " + std::to_string(k) + ", threads " + std::to_string(threads));
        EXPECT_EQ(got[k].size(), ref[k].size());
        EXPECT_TRUE(got[k] == ref[k]);
      }
    }
  }
}

}  // namespace
}  // namespace roprec

namespace roprec {
namespace {

// Through the CLI, --threads 2 writes the corrected program, the targets CSV and the report at the
// same time: the same files and bytes as one thread, and still all or nothing (a failing output
// leaves every other one unwritten, whichever thread wrote it).
TEST(CompensateThreads, CliWritesTheOutputsTogetherAllOrNothing) {
  const std::string dir = test::tempDir("compensate_threads_cli");
  const std::string src = test::sourceDir() + "/samples/emotor-housing/housing_kr120.src";
  const std::string cell = test::sourceDir() + "/samples/cells/housing-kr120.xml";
  auto run = [&](const std::string& out, const std::string& targets, const std::string& report,
                 int threads) {
    return test::runRoprec("compensate --cell '" + cell + "' '" + src + "' --quiet -o '" + out +
                           "' --targets '" + targets + "' --report '" + report +
                           "' --orientation flip-free --threads " + std::to_string(threads));
  };
  for (const int t : {1, 2}) {
    const std::string k = dir + "/t" + std::to_string(t);
    ASSERT_EQ(run(k + ".src", k + ".csv", k + ".html", t).exit_code, 0) << t;
  }
  for (const char* ext : {".src", ".csv", ".html"}) {
    SCOPED_TRACE(ext);
    const std::string one = test::readFile(dir + "/t1" + ext);
    EXPECT_GT(one.size(), 1000U);
    EXPECT_TRUE(one == test::readFile(dir + "/t2" + ext));
  }
  // the program's folder is missing: the targets and the report (other threads) are not written
  const auto bad_program = run(dir + "/none/o.src", dir + "/f1.csv", dir + "/f1.html", 2);
  EXPECT_EQ(bad_program.exit_code, 2);
  EXPECT_NE(bad_program.err.find("none"), std::string::npos) << bad_program.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/f1.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/f1.html"));
  // the targets' folder is missing: the program and the report are not written
  const auto bad_targets = run(dir + "/f2.src", dir + "/none/t.csv", dir + "/f2.html", 2);
  EXPECT_EQ(bad_targets.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir + "/f2.src"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/f2.html"));
  for (const auto& e : std::filesystem::directory_iterator(dir))  // no temporaries left
    EXPECT_FALSE(isOutputTemporaryName(e.path().filename().string(), nullptr)) << e.path();
}

// Without --report the program and the targets are written as the holes are compensated, into
// temporaries: the same bytes as with the report, and still all or nothing.
TEST(CompensateThreads, CliStreamsTheProgramAndTargetsAllOrNothing) {
  const std::string dir = test::tempDir("compensate_threads_cli_stream");
  const std::string src = test::sourceDir() + "/samples/emotor-housing/housing_kr120.src";
  const std::string cell = test::sourceDir() + "/samples/cells/housing-kr120.xml";
  auto run = [&](const std::string& out, const std::string& targets, const std::string& extra) {
    return test::runRoprec("compensate --cell '" + cell + "' '" + src + "' --quiet -o '" + out +
                           "' --targets '" + targets + "' --orientation stiffest --threads 2" +
                           extra);
  };
  ASSERT_EQ(run(dir + "/w.src", dir + "/w.csv", " --report '" + dir + "/w.html'").exit_code, 0);
  ASSERT_EQ(run(dir + "/s.src", dir + "/s.csv", "").exit_code, 0);
  for (const char* ext : {".src", ".csv"}) {
    SCOPED_TRACE(ext);
    const std::string whole = test::readFile(dir + "/w" + ext);
    EXPECT_GT(whole.size(), 1000U);
    EXPECT_TRUE(whole == test::readFile(dir + "/s" + ext));
  }
  const auto bad_program = run(dir + "/none/o.src", dir + "/f1.csv", "");
  EXPECT_EQ(bad_program.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir + "/f1.csv"));
  const auto bad_targets = run(dir + "/f2.src", dir + "/none/t.csv", "");
  EXPECT_EQ(bad_targets.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir + "/f2.src"));
  for (const auto& e : std::filesystem::directory_iterator(dir))  // no temporaries left
    EXPECT_FALSE(isOutputTemporaryName(e.path().filename().string(), nullptr)) << e.path();
}

}  // namespace
}  // namespace roprec

namespace roprec {
namespace {

/// A KRL job of 43 holes with named targets: every cycle goes in and out through its approach
/// point (a target one hole uses twice), and after 40 holes with targets of their own, holes 3,
/// 20 and 7 are drilled a second time with the same targets (targets two holes use).
std::string sharedTargetJob(const std::string& dir) {
  std::string src =
      "DEF shared ( )\n$BASE = {FRAME: X 1350.000,Y 0.000,Z 300.000,A 0.000,B 0.000,C 0.000}\n"
      "$TOOL = {FRAME: X 0.000,Y 0.000,Z 320.000,A 0.000,B 0.000,C 0.000}\n";
  std::string dat = "DEFDAT shared\n";
  auto cycle = [&](int k) {
    const std::string n = std::to_string(k);
    src += "; H" + n + " drill D6.8 depth 16.0\n$VEL.CP = 0.25\nPTP XA" + n + " C_PTP\nLIN XS" + n +
           " C_DIS\n$VEL.CP = 0.02\nLIN XB" + n + "\nWAIT SEC 0.3\n$VEL.CP = 0.25\nLIN XA" + n +
           " C_DIS\n";
  };
  for (int k = 0; k < 40; ++k) {
    const double x = 60.0 + 2.5 * k;
    const double y = -30.0 + 1.5 * k;
    char buf[160];
    for (const auto& [name, z] : {std::pair{"XA", 300.0}, {"XS", 252.0}, {"XB", 234.0}}) {
      std::snprintf(buf, sizeof buf,
                    "DECL E6POS %s%d={X %.3f,Y %.3f,Z %.3f,A 0.000,B 0.000,C 180.000}\n", name, k,
                    x, y, z);
      dat += buf;
    }
    cycle(k);
  }
  for (const int k : {3, 20, 7}) cycle(k);  // drilled again: their targets move twice
  src += "END\n";
  dat += "ENDDAT\n";
  test::writeFile(dir + "/shared.src", src);
  test::writeFile(dir + "/shared.dat", dat);
  return dir + "/shared.src";
}

// Holes that share targets are edited in hole order (each reads what the one before wrote),
// the others on the workers: the program is the one of the plain sequential edit, target after
// target in hole order, for 1, 2 and 3 threads.
TEST(CompensateThreads, SharedTargetsAreEditedInHoleOrder) {
  const std::string dir = test::tempDir("compensate_threads_shared");
  const std::string program = sharedTargetJob(dir);
  const std::string cell = test::sourceDir() + "/samples/cells/housing-kr120.xml";
  std::vector<std::string> ref;
  for (const int threads : {1, 2, 3}) {
    SCOPED_TRACE(threads);
    api::CompensationJob job;
    job.options.mode = OrientationMode::kFlipFree;
    job.job.threads = threads;
    const api::CompensationResult r = api::compensateJob(cell, program, job);
    ASSERT_EQ(r.holes.size(), 43U);
    ASSERT_EQ(r.failed, 0);
    EXPECT_TRUE(r.refused.empty());
    const std::vector<char> shared = api::holesSharingTargets(
        r.context.job.sources, std::vector<char>(43, 1), r.context.job.program->targets().size());
    for (size_t i = 0; i < 43; ++i) {
      const bool again = i == 3 || i == 7 || i == 20 || i >= 40;
      EXPECT_EQ(shared[i] != 0, again) << i;
    }
    const std::vector<std::string> got = postproc::renderFiles(*r.context.job.program);
    if (ref.empty()) {
      // the reference: the program read again, every target of every hole replaced directly
      postproc::Program p = postproc::readProgram(program);
      p.position_min_decimals = 5;
      for (size_t i = 0; i < r.holes.size(); ++i) {
        const HoleCompensation& h = r.holes[i];
        const api::HoleSource& s = r.context.job.sources[i];
        for (const int t : s.targets) {
          const Pose T_W_t = s.T_W_frame * postproc::targetPose(p, p.targets()[size_t(t)]);
          const Pose T_new = h.delta * T_W_t * Pose(Eigen::AngleAxisd(h.psi, Vec3::UnitZ()));
          ASSERT_TRUE(postproc::replaceTargetPose(p, t, s.T_W_frame.inverse() * T_new).ok);
        }
      }
      postproc::markCompensated(p, "x");
      ref = postproc::renderFiles(p);
      ASSERT_EQ(ref.size(), 2U);
      EXPECT_NE(ref[1], test::readFile(dir + "/shared.dat"));
    }
    ASSERT_EQ(got.size(), ref.size());
    // the marker line differs (cell name, version): compare the .dat, where the targets are
    EXPECT_TRUE(got[1] == ref[1]);
  }
}

}  // namespace
}  // namespace roprec

namespace roprec {
namespace {

/// compensateStreamedProgram (the program read by windows, twice) against compensateJob on
/// the program read whole: the program's files, the targets CSV of the holes the sink gets and
/// the job's counters.
/// `block`: the holes compensated (and edited) at a time, 0: the default.
void expectStreamedLikeWhole(const std::string& program, OrientationMode mode, int threads,
                             size_t block = 0) {
  SCOPED_TRACE(program + " " + orientationModeName(mode) + " threads " + std::to_string(threads) +
               " block " + std::to_string(block));
  const std::string cell = test::sourceDir() + "/samples/cells/housing-kr120.xml";
  api::CompensationJob job;
  job.options.mode = mode;
  job.job.threads = threads;
  if (block > 0) job.options.block = block;
  const api::CompensationResult whole = api::compensateJob(cell, program, job);
  const std::vector<std::string> want = postproc::renderFiles(*whole.context.job.program);
  ASSERT_TRUE(api::compensationStreams(program, job));
  api::CompensationResult r = api::loadStreamedCompensationJob(cell, program, job);
  EXPECT_TRUE(r.context.job.streamed);
  std::string src, csv;
  std::optional<std::string> dat;
  api::CompensationTargetsStream rows(
      r.context, r.orientation, program, true, [&](std::string_view b) { csv.append(b); }, threads);
  size_t next = 0;
  api::compensateStreamedProgram(
      r, job, [&](std::string_view b) { src.append(b); }, dat,
      [&](size_t first, std::span<const HoleCompensation> holes, std::span<const HoleRequest> q) {
        EXPECT_EQ(first, next);
        next += holes.size();
        rows.holes(holes, q);
      });
  rows.finish();
  ASSERT_TRUE(r.writable);
  EXPECT_EQ(next, whole.holes.size());
  EXPECT_EQ(src.size(), want[0].size());
  EXPECT_TRUE(src == want[0]);
  ASSERT_EQ(dat.has_value(), want.size() > 1);
  if (dat) {
    EXPECT_TRUE(*dat == want[1]);
  }
  EXPECT_TRUE(csv == api::compensationTargets(whole, program, true));
  expectSameJobResult(r, whole);
}

// A KRL program is compensated reading it by windows: the bytes of the program read whole, for
// targets in the .dat shared by two holes, the sample job, and a program of several windows
// (holes whose cycles cross a window's end, targets edited in the window before).
TEST(CompensateThreads, StreamedProgramWritesTheBytesOfTheWholeJob) {
  const std::string dir = test::tempDir("compensate_threads_streamed_program");
  for (const std::string& program :
       {sharedTargetJob(dir), test::sourceDir() + "/samples/emotor-housing/housing_kr120.src"}) {
    for (const OrientationMode mode :
         {OrientationMode::kKeep, OrientationMode::kFlipFree, OrientationMode::kStiffest}) {
      for (const int threads : {1, 2}) expectStreamedLikeWhole(program, mode, threads);
    }
  }
  const std::string big = dir + "/big.src";
  test::writeFile(big, test::krlDrillCycles(9000, test::kHousingBase, true));
  ASSERT_GT(std::filesystem::file_size(big), 2 * postproc::ProgramStream::kWindowBytes);
  for (const int threads : {1, 2}) expectStreamedLikeWhole(big, OrientationMode::kKeep, threads);
  expectStreamedLikeWhole(big, OrientationMode::kFlipFree, 2);
  // a block of holes larger than the program (every window's holes edited in one block), and
  // blocks of a few holes (many blocks a window, one across each window's end)
  for (const size_t block : {size_t{16384}, size_t{100}})
    expectStreamedLikeWhole(big, OrientationMode::kKeep, 2, block);
  // a prologue of comments two windows long: the first window with holes holds a few dozen, so
  // the holes it foretells are far fewer than the program's and most requests go past the ones
  // the first reading reserved (kept in chunks of their own, moved in at the end, in hole order)
  std::string sparse = test::krlDrillCycles(9000, test::kHousingBase, true);
  std::string prologue;
  while (prologue.size() < 2 * postproc::ProgramStream::kWindowBytes - 20000)
    prologue += "; the cell's set-up sheet, one line of many ...........................\n";
  sparse.insert(sparse.find('\n', sparse.find("$TOOL")) + 1, prologue);
  const std::string late = dir + "/late_holes.src";
  test::writeFile(late, sparse);
  for (const int threads : {1, 2}) expectStreamedLikeWhole(late, OrientationMode::kKeep, threads);
}

// A program that carries the compensation marker, or a hole list, takes the whole-program path
// (it says where the marker is), and so does one whose .dat, held whole either way, is the larger
// file and above a window.
TEST(CompensateThreads, MarkedProgramsAndHoleListsAreNotStreamed) {
  const std::string dir = test::tempDir("compensate_threads_not_streamed");
  const std::string marked = dir + "/marked.src";
  test::writeFile(
      marked, test::krlDrillCycles(3, test::kHousingBase, false, ";roprec compensated: cell x\n"));
  api::CompensationJob job;
  EXPECT_FALSE(api::compensationStreams(marked, job));
  const std::string plain = dir + "/plain.src";
  test::writeFile(plain, test::krlDrillCycles(3));
  EXPECT_TRUE(api::compensationStreams(plain, job));
  // a large program's halves are searched on two threads: a marker across the middle, at the
  // start or at the end is found
  const std::string program = test::krlDrillCycles(3);
  std::string filler;
  while (filler.size() < (std::size_t{17} << 20U))
    filler += "; the cell's set-up sheet, one line of many ...........................\n";
  const std::string large =
      program.substr(0, program.find('\n') + 1) + filler + program.substr(program.find('\n') + 1);
  const std::string marker = "roprec compensated";
  for (const std::string_view where : {"middle", "start", "end", "none"}) {
    SCOPED_TRACE(std::string(where));
    std::string text = large;
    if (where == "middle") {
      const std::size_t q = (text.size() + marker.size()) / 2 - marker.size() / 2;
      ASSERT_NE(text[q - 1], '\n');
      text.insert(q, marker);
      ASSERT_LT(q, text.size() / 2);
      ASSERT_GT(q + marker.size(), text.size() / 2);
    } else if (where == "start") {
      text.insert(0, ";" + marker + "\n");
    } else if (where == "end") {
      text += ";" + marker;
    }
    const std::string path = dir + "/large.src";
    test::writeFile(path, text);
    EXPECT_EQ(api::compensationStreams(path, job), where == "none");
  }
  job.job.holes = test::sourceDir() + "/samples/emotor-housing/holes.csv";
  EXPECT_FALSE(api::compensationStreams(plain, job));
  job.job.holes.reset();
  std::string dat = "DEFDAT plain\n";
  while (dat.size() <= 2 * postproc::ProgramStream::kWindowBytes)
    dat += "DECL E6POS XP" + std::to_string(dat.size()) +
           "={X 1.000,Y 2.000,Z 3.000,A 0.000,B 0.000,C 180.000}\n";
  test::writeFile(dir + "/plain.dat", dat + "ENDDAT\n");
  EXPECT_FALSE(api::compensationStreams(plain, job));
}

// An error far into a streamed program (in its last cycle, windows after the first: an aggregate
// left open, which the read-ahead does not read, or a literal where a number belongs, whose
// target the read-ahead does not make) stops the CLI with exit 2 at that line before anything is
// written, on one thread and on two: no output, no temporary.
TEST(CompensateThreads, CliErrorLateInAStreamedProgramWritesNothing) {
  const std::string dir = test::tempDir("compensate_threads_late_error");
  const std::string cycles = test::krlDrillCycles(9000, test::kHousingBase, true);
  const size_t last = cycles.rfind("LIN {");
  std::string open = cycles;
  open.erase(open.find('}', last), 1);
  std::string literal = cycles;
  const size_t x = literal.find("X ", last) + 2;
  literal.replace(x, literal.find(',', x) - x, "'B01'");
  const int line = static_cast<int>(std::count(cycles.begin(), cycles.begin() + last, '\n')) + 1;
  const std::string cell = test::sourceDir() + "/samples/cells/housing-kr120.xml";
  for (const auto& [text, what] :
       {std::pair{open, "aggregate"}, std::pair{literal, "not a number"}}) {
    for (const int threads : {1, 2}) {
      SCOPED_TRACE(std::string(what) + " threads " + std::to_string(threads));
      const std::string src = dir + "/late.src";
      test::writeFile(src, text);
      ASSERT_GT(text.size(), 2 * postproc::ProgramStream::kWindowBytes);
      api::CompensationJob job;
      ASSERT_TRUE(api::compensationStreams(src, job));
      const auto r = test::runRoprec("compensate --cell '" + cell + "' '" + src + "' --quiet -o '" +
                                     dir + "/o.src' --targets '" + dir + "/o.csv' --threads " +
                                     std::to_string(threads));
      EXPECT_EQ(r.exit_code, 2);
      EXPECT_NE(r.err.find("late.src:" + std::to_string(line)), std::string::npos) << r.err;
      EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
      EXPECT_FALSE(std::filesystem::exists(dir + "/o.src"));
      EXPECT_FALSE(std::filesystem::exists(dir + "/o.csv"));
      for (const auto& e : std::filesystem::directory_iterator(dir))  // no temporaries left
        EXPECT_FALSE(isOutputTemporaryName(e.path().filename().string(), nullptr)) << e.path();
    }
  }
}

}  // namespace
}  // namespace roprec
