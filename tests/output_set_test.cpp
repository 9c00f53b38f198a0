/// All-or-nothing outputs: OutputSet stages every output to a temporary file
/// in its target folder and renames all of them only when all were staged. What needs POSIX to
/// set up (fork and kill, flock, FIFOs, links, rlimits, devices) is in output_set_posix_test.cpp.
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "plugin/c/roprec.h"
#include "tests/support/file_checks.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

namespace fs = std::filesystem;

using test::listDir;
using test::temporariesIn;

TEST(OutputSet, CommitWritesAllAndLeavesNoTemporaries) {
  const std::string dir = test::tempDir("outset-commit");
  OutputSet set;
  set.stage(dir + "/a.src", "A");
  set.stage(dir + "/a.dat", "D");
  set.stage(dir + "/r.html", "R");
  EXPECT_FALSE(fs::exists(dir + "/a.src"));  // nothing visible before commit
  EXPECT_EQ(temporariesIn(dir), 3);
  const auto written = set.commit();
  EXPECT_EQ(written.size(), 3u);
  EXPECT_EQ(test::readFile(dir + "/a.src"), "A");
  EXPECT_EQ(test::readFile(dir + "/a.dat"), "D");
  EXPECT_EQ(test::readFile(dir + "/r.html"), "R");
  EXPECT_EQ(temporariesIn(dir), 0);
}

TEST(OutputSet, ErrorInTheMiddleLeavesOldSetAndNoTemporaries) {
  const std::string dir = test::tempDir("outset-rollback");
  test::writeFile(dir + "/a.src", "old A");
  {
    OutputSet set;
    set.stage(dir + "/a.src", "new A");
    EXPECT_THROW(set.stage(dir + "/missing-folder/b.dat", "x"), InputError);
  }  // destructor rolls back
  EXPECT_EQ(test::readFile(dir + "/a.src"), "old A");
  EXPECT_EQ(temporariesIn(dir), 0);
}

TEST(OutputSet, ScopedSetMakesWriteFileAtomicAllOrNothing) {
  const std::string dir = test::tempDir("outset-scope");
  try {
    OutputSet set;
    const ScopedOutputSet scope(set);
    writeFileAtomic(dir + "/one.json", "1");
    writeFileAtomic(dir + "/two.html", "2");
    throw std::runtime_error("the command failed after writing two outputs");
  } catch (const std::runtime_error&) {
  }
  EXPECT_TRUE(listDir(dir).empty());
}

TEST(OutputSet, CannotWriteSaysWhy) {
  try {
    writeFileAtomic("/nonexistent-folder-roprec/x.json", "x");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "cannot write output file: the folder /nonexistent-folder-roprec does not "
                  "exist (roprec does not create folders: mkdir -p /nonexistent-folder-roprec)"),
              std::string::npos)
        << e.what();
  }
  // A file where the folder should be.
  const std::string dir = test::tempDir("outset-notdir");
  test::writeFile(dir + "/f", "x");
  try {
    writeFileAtomic(dir + "/f/x.json", "x");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(dir + "/f is not a folder"), std::string::npos)
        << e.what();
  }
}

TEST(OutputSet, NamesNearTheNameMaxLimitWork) {
  const std::string dir = test::tempDir("outset-long");
  for (const size_t len : {200u, 240u, 250u, 255u}) {
    const std::string name = std::string(len - 5, 'h') + ".json";
    ASSERT_EQ(name.size(), len);
    const std::string tmp = outputTemporaryPath(dir + "/" + name, 4194304);
    EXPECT_LE(fs::path(tmp).filename().string().size(), 255u);
    EXPECT_TRUE(isOutputTemporaryName(fs::path(tmp).filename().string()));
    OutputSet set;
    set.stage(dir + "/" + name, "long " + std::to_string(len));
    set.stage(dir + "/" + std::string(len - 5, 'h') + ".html", "html");
    set.commit();
    EXPECT_EQ(test::readFile(dir + "/" + name), "long " + std::to_string(len));
  }
  EXPECT_EQ(temporariesIn(dir), 0);
}

TEST(OutputSet, CliMultiOutputCommandWritesNothingWhenOneOutputFails) {
  // roprec forces --csv OK --json into a missing folder: exit 2, the CSV is not written either.
  const std::string dir = test::tempDir("outset-cli");
  const auto r = test::runRoprec("forces --cell '" + test::sourceDir() +
                                 "/samples/cells/alu-drilling-6061.xml' --csv '" + dir +
                                 "/d.csv' --json '" + dir + "/missing/f.json'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("cannot write output file: the folder " + dir + "/missing does not exist"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(listDir(dir).empty());
}

TEST(OutputSet, CApiCompensateWritesNothingWhenTheTargetsExportFails) {
  // program + .dat + targets through the C ABI: the targets' folder does not exist, so neither
  // the corrected program nor its .dat may appear.
  const std::string dir = test::tempDir("outset-capi");
  const std::string src = test::sourceDir();
  char err[4096];
  const int rc =
      roprec_compensate_file((src + "/samples/cells/housing-kr120.xml").c_str(),
                             (src + "/samples/emotor-housing/housing_kr120.src").c_str(), nullptr,
                             (dir + "/c.src").c_str(), "keep", (dir + "/missing/t.json").c_str(),
                             nullptr, 0, err, sizeof err);
  EXPECT_EQ(rc, ROPREC_BAD_INPUT);
  EXPECT_NE(std::string(err).find("the folder " + dir + "/missing does not exist"),
            std::string::npos)
      << err;
  EXPECT_TRUE(listDir(dir).empty());
}

// The CLI: an output equal to the program, the cell, the hole list or another output is exit 2
// naming both files, and nothing is written (the program keeps its bytes).
TEST(OutputSet, CliOutputsNeverReplaceAnInputOrEachOther) {
  const std::string dir = test::tempDir("outset-cli-same");
  const std::string src = test::sourceDir();
  const std::string program = dir + "/y.src";
  const std::string cell = dir + "/cell.xml";
  const std::string holes = dir + "/holes.csv";
  const std::string program_bytes =
      test::readFile(src + "/samples/emotor-housing/housing_kr120.src");
  const std::string cell_bytes = test::readFile(src + "/samples/cells/housing-kr120.xml");
  const std::string holes_bytes = test::readFile(src + "/samples/emotor-housing/holes.csv");
  test::writeFile(program, program_bytes);
  test::writeFile(cell, cell_bytes);
  test::writeFile(holes, holes_bytes);
  const std::string base = "--cell '" + cell + "' '" + program + "' ";
  struct Case {
    std::string args;
    std::string first;
    std::string second;
  };
  const std::vector<Case> cases{
      {"predict " + base + "--json '" + program + "'", program, program},
      {"predict " + base + "--json '" + cell + "'", cell, cell},
      {"predict " + base + "--holes '" + holes + "' --json '" + holes + "'", holes, holes},
      {"predict " + base + "--report '" + dir + "/./y.src'", dir + "/./y.src", program},
      {"compensate " + base + "-o '" + dir + "/c.src' --targets '" + cell + "'", cell, cell},
      {"compensate " + base + "-o '" + dir + "/c.src' --report '" + cell + "'", cell, cell},
      {"compensate " + base + "-o '" + dir + "/z.src' --targets '" + dir + "/z.src'",
       dir + "/z.src", dir + "/z.src"},
  };
  for (const Case& c : cases) {
    const auto r = test::runRoprec(c.args + " --quiet");
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.first), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.second), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(r.out.find("wrote"), std::string::npos) << r.out;
    EXPECT_TRUE(test::readFile(program) == program_bytes) << c.args;
    EXPECT_TRUE(test::readFile(cell) == cell_bytes) << c.args;
    EXPECT_TRUE(test::readFile(holes) == holes_bytes) << c.args;
    EXPECT_FALSE(fs::exists(dir + "/z.src")) << c.args;
    EXPECT_FALSE(fs::exists(dir + "/c.src")) << c.args;
    EXPECT_EQ(temporariesIn(dir), 0) << c.args;
  }
}

// Two threads of one process writing the same path: every call succeeds and the file always holds
// one call's bytes whole (temporary names are unique per thread).
TEST(OutputSet, ThreadsWritingTheSamePathNeverFailOrMix) {
  const std::string dir = test::tempDir("outset-threads");
  const std::string path = dir + "/same.json";
  std::atomic<int> failures{0};
  auto body = [&](int t) {
    const std::string bytes(4096 + t, static_cast<char>('a' + t));
    for (int i = 0; i < 150; ++i) {
      try {
        writeFileAtomic(path, bytes);
      } catch (const std::exception&) {
        ++failures;
      }
    }
  };
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) threads.emplace_back(body, t);
  for (auto& th : threads) th.join();
  EXPECT_EQ(failures.load(), 0);
  const std::string got = test::readFile(path);
  ASSERT_GE(got.size(), 4096u);
  const int t = got[0] - 'a';
  EXPECT_EQ(got, std::string(4096 + static_cast<std::size_t>(t), got[0]));
  EXPECT_EQ(temporariesIn(dir), 0);
}

// The same through the CLI: compensate killed after renaming the program; the next roprec run
// writing there finishes the set (the targets appear) and prints a note.
TEST(OutputSet, CliCommitKilledBetweenRenamesIsFinishedByTheNextRun) {
  const std::string dir = test::tempDir("outset-cli-kill");
  const std::string src = test::sourceDir();
  const auto killed =
      test::runCommand(std::string(kFaultKillAfterRenamesEnv) + "=1 '" + test::roprecBin() +
                       "' compensate --cell '" + src + "/samples/cells/housing-kr120.xml' '" + src +
                       "/samples/emotor-housing/housing_kr120.src' -o '" + dir +
                       "/c.src' --targets '" + dir + "/t.json' --quiet");
  EXPECT_NE(killed.exit_code, 0);
  EXPECT_FALSE(fs::exists(dir + "/t.json"));
  const auto next = test::runRoprec(
      "fk --robot kuka-kr120-r2500-pro --joints \"0 -90 90 0 0 0\" -o '" + dir + "/fk.json'");
  EXPECT_EQ(next.exit_code, 0) << next.err;
  EXPECT_NE(next.err.find("roprec: note: finished the output commit of an earlier run"),
            std::string::npos)
      << next.err;
  EXPECT_TRUE(fs::exists(dir + "/c.src"));
  EXPECT_TRUE(fs::exists(dir + "/t.json"));
  EXPECT_EQ(temporariesIn(dir), 0);
}

}  // namespace
}  // namespace roprec

namespace roprec {
namespace {

// readFileBytes reads every byte as it is (NUL, CR LF, no newline at the end), for an empty file,
// a small one and one of several read buffers; a missing file is an InputError naming it (a pipe:
// output_set_posix_test.cpp).
TEST(ReadFileBytes, EveryByteOfFilesOfAnySize) {
  const std::string dir = test::tempDir("read_file_bytes");
  std::string big;
  // 64-bit arithmetic: i * 7919 passes 2^31 (a 32-bit long on Windows would overflow)
  for (std::int64_t i = 0; i < 300000; ++i) big += static_cast<char>((i * 7919) % 251);
  for (const std::string& text : {std::string(), std::string("a\0b\r\nc", 6), big}) {
    const std::string path = dir + "/f" + std::to_string(text.size());
    test::writeFile(path, text);
    EXPECT_TRUE(readFileBytes(path) == text) << text.size();
  }
  try {
    readFileBytes(dir + "/missing.src");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.src"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace roprec
