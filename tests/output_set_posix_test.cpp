/// All-or-nothing outputs (OutputSet) where POSIX is needed to set the case up: runs killed by
/// SIGKILL (fork), a full disk (RLIMIT_FSIZE), symbolic and hard links, FIFOs, devices, the folder
/// lock (flock). Built on Linux only (tests/windows/posix_only_tests.txt); the portable cases are
/// in output_set_test.cpp.
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "tests/support/file_checks.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

namespace fs = std::filesystem;

using test::listDir;
using test::temporariesIn;

void killSelf() { ::raise(SIGKILL); }

TEST(OutputSet, SymlinkAndFifoTargetsAreRefusedNotReplaced) {
  const std::string dir = test::tempDir("outset-special");
  test::writeFile(dir + "/real.txt", "real");
  ASSERT_EQ(::symlink("real.txt", (dir + "/link.txt").c_str()), 0);
  ASSERT_EQ(::mkfifo((dir + "/fifo.txt").c_str(), 0644), 0);
  try {
    writeFileAtomic(dir + "/link.txt", "new");
    FAIL() << "symlink replaced";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("symbolic link"), std::string::npos) << e.what();
  }
  try {
    writeFileAtomic(dir + "/fifo.txt", "new");
    FAIL() << "FIFO replaced";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("FIFO"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_symlink(dir + "/link.txt"));
  EXPECT_TRUE(fs::is_fifo(dir + "/fifo.txt"));
  EXPECT_EQ(test::readFile(dir + "/real.txt"), "real");
  EXPECT_EQ(temporariesIn(dir), 0);
}

TEST(OutputSet, TheNullDeviceDiscardsAndOtherDevicesAreRefused) {
  // /dev/null: produced (the producer's error still counts) and discarded, nothing staged
  OutputSet set;
  bool produced = false;
  set.stageStream("/dev/null", [&](const ByteWriter& w) {
    w("bytes");
    produced = true;
  });
  EXPECT_TRUE(produced);
  EXPECT_TRUE(set.empty());
  EXPECT_TRUE(set.commit().empty());
  EXPECT_THROW(
      set.stageStream("/dev/null", [](const ByteWriter&) { throw InputError("x", 1, "y"); }),
      InputError);
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  // another character device is refused, not written
  try {
    writeFileAtomic("/dev/zero", "new");
    FAIL() << "device written";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
  }
}

TEST(OutputSet, KillBetweenStagingAndCommitLeavesOldSetAndNextRunCleansUp) {
  const std::string dir = test::tempDir("outset-kill");
  test::writeFile(dir + "/p.src", "old src");
  test::writeFile(dir + "/p.dat", "old dat");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    setOutputCommitHookForTesting(&killSelf);  // SIGKILL after staging, before the renames
    OutputSet set;
    set.stage(dir + "/p.src", "new src");
    set.stage(dir + "/p.dat", "new dat");
    set.stage(dir + "/p.json", "new json");
    set.commit();
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGKILL);
  // the old set, untouched; the killed run's temporaries are recognisable
  EXPECT_EQ(test::readFile(dir + "/p.src"), "old src");
  EXPECT_EQ(test::readFile(dir + "/p.dat"), "old dat");
  EXPECT_FALSE(fs::exists(dir + "/p.json"));
  EXPECT_EQ(temporariesIn(dir), 3);
  // the next run writing to the folder removes them
  OutputSet next;
  next.stage(dir + "/q.txt", "q");
  next.commit();
  EXPECT_EQ(temporariesIn(dir), 0);
  EXPECT_EQ(listDir(dir), (std::vector<std::string>{"p.dat", "p.src", "q.txt"}));
}

TEST(OutputSet, KillAfterCommitLeavesTheNewSet) {
  const std::string dir = test::tempDir("outset-kill-after");
  test::writeFile(dir + "/p.src", "old src");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    OutputSet set;
    set.stage(dir + "/p.src", "new src");
    set.stage(dir + "/p.dat", "new dat");
    set.commit();
    ::raise(SIGKILL);
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_EQ(test::readFile(dir + "/p.src"), "new src");
  EXPECT_EQ(test::readFile(dir + "/p.dat"), "new dat");
  EXPECT_EQ(temporariesIn(dir), 0);
}

TEST(OutputSet, FullDiskLeavesNothingNew) {
  // RLIMIT_FSIZE in a forked child: the second output does not fit (EFBIG), so the first one is
  // not published either and no temporary is left.
  const std::string dir = test::tempDir("outset-full");
  test::writeFile(dir + "/big.src", "old");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::signal(SIGXFSZ, SIG_IGN);
    struct rlimit rl {};
    rl.rlim_cur = rl.rlim_max = 4096;
    if (::setrlimit(RLIMIT_FSIZE, &rl) != 0) ::_exit(3);
    try {
      OutputSet set;
      set.stage(dir + "/big.src", "small new program");
      set.stage(dir + "/big.dat", std::string(100000, 'x'));
      set.commit();
    } catch (const InputError& e) {
      const std::string what = e.what();
      ::_exit(what.find("File too large") != std::string::npos ? 42 : 4);
    }
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 42);
  EXPECT_EQ(test::readFile(dir + "/big.src"), "old");
  EXPECT_EQ(listDir(dir), (std::vector<std::string>{"big.src"}));
}

TEST(OutputSet, CliRefusesASymlinkOutput) {
  const std::string dir = test::tempDir("outset-cli-link");
  test::writeFile(dir + "/target.json", "keep");
  ASSERT_EQ(::symlink("target.json", (dir + "/out.json").c_str()), 0);
  const auto r = test::runRoprec(
      "fk --robot kuka-kr120-r2500-pro --joints \"0 -90 90 0 0 0\" -o '" + dir + "/out.json'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("symbolic link"), std::string::npos) << r.err;
  EXPECT_EQ(test::readFile(dir + "/target.json"), "keep");
  EXPECT_TRUE(fs::is_symlink(dir + "/out.json"));
}

// Every output is compared with every other output and every input of the set before anything is
// renamed: the same file by device and inode (a link, a "./" path) or by resolved path (a file not
// there yet). Nothing is written, no temporary is left.
TEST(OutputSet, AnOutputThatIsAnInputOrAnotherOutputIsRefusedBeforeAnyRename) {
  const std::string dir = test::tempDir("outset-same");
  test::writeFile(dir + "/in.src", "the input");
  ASSERT_EQ(::symlink("in.src", (dir + "/link.src").c_str()), 0);
  {
    OutputSet set;
    set.noteInput(dir + "/link.src");
    set.stage(dir + "/other.json", "json");
    set.stage(dir + "/./in.src", "would clobber the input");
    try {
      set.commit();
      ADD_FAILURE() << "an output equal to an input was committed";
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find("is the input file " + dir + "/link.src"),
                std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find("output " + dir + "/./in.src"), std::string::npos)
          << e.what();
    }
  }
  EXPECT_EQ(test::readFile(dir + "/in.src"), "the input");
  EXPECT_FALSE(fs::exists(dir + "/other.json"));
  EXPECT_EQ(temporariesIn(dir), 0);
  // two outputs naming one file (not there yet: by resolved path; there: by inode)
  for (const std::string& second : {dir + "/sub/../new.json", dir + "/./new.json"}) {
    fs::create_directories(dir + "/sub");
    OutputSet set;
    set.stage(dir + "/new.json", "one");
    try {
      set.stage(second, "two");
      ADD_FAILURE() << "two outputs naming one file were staged: " << second;
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find("are the same file"), std::string::npos) << e.what();
    }
  }
  EXPECT_FALSE(fs::exists(dir + "/new.json"));
  ASSERT_EQ(::link((dir + "/in.src").c_str(), (dir + "/hard.src").c_str()), 0);
  OutputSet set;
  set.stage(dir + "/in.src", "a");
  EXPECT_THROW(set.stage(dir + "/hard.src", "b"), UsageError);
}

// Sets committed concurrently never interleave: a reader holding the folder lock (what a commit
// holds during its renames) always sees the program and the targets of one and the same set.
TEST(OutputSet, ConcurrentSetsAreCommittedWhole) {
  const std::string dir = test::tempDir("outset-concurrent");
  std::atomic<bool> done{false};
  std::atomic<int> mixed{0};
  std::atomic<int> failures{0};
  auto writer = [&](char tag) {
    for (int i = 0; i < 150; ++i) {
      try {
        OutputSet set;
        const std::string v = std::string(1, tag) + std::to_string(i);
        set.stage(dir + "/p.src", v);
        set.stage(dir + "/p.json", v);
        set.stage(dir + "/p.html", v);
        set.commit();
      } catch (const std::exception&) {
        ++failures;
      }
    }
  };
  std::thread reader([&] {
    while (!done) {
      const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
      ASSERT_GE(fd, 0);
      ASSERT_EQ(::flock(fd, LOCK_EX), 0);
      if (fs::exists(dir + "/p.html")) {
        const std::string a = test::readFile(dir + "/p.src");
        if (a != test::readFile(dir + "/p.json") || a != test::readFile(dir + "/p.html")) ++mixed;
      }
      ::close(fd);
    }
  });
  std::thread w1(writer, 'a');
  std::thread w2(writer, 'b');
  w1.join();
  w2.join();
  done = true;
  reader.join();
  EXPECT_EQ(failures.load(), 0);
  EXPECT_EQ(mixed.load(), 0);
  EXPECT_EQ(temporariesIn(dir), 0);
}

// Two spellings of one folder ("d" and "d/sub/..") are locked once: the commit neither waits for
// itself nor fails (run in a child that the test kills after 10 s).
TEST(OutputSet, OneFolderSpelledTwoWaysIsLockedOnce) {
  const std::string dir = test::tempDir("outset-two-spellings");
  fs::create_directories(dir + "/sub");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    OutputSet set;
    set.stage(dir + "/a.json", "a");
    set.stage(dir + "/sub/../b.json", "b");
    set.commit();
    ::_exit(0);
  }
  int status = 0;
  pid_t done = 0;
  for (int i = 0; i < 1000 && done == 0; ++i) {
    done = ::waitpid(child, &status, WNOHANG);
    if (done == 0) ::usleep(10000);
  }
  if (done == 0) {
    ::kill(child, SIGKILL);
    ::waitpid(child, &status, 0);
    FAIL() << "the commit did not finish within 10 s";
  }
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(test::readFile(dir + "/a.json"), "a");
  EXPECT_EQ(test::readFile(dir + "/b.json"), "b");
}

// A run killed between the renames of its set (fault injection: ROPREC_FAULT_KILL_AFTER_RENAMES)
// leaves a mixed set and its commit journal; the next run writing to the folder finishes the
// renames, says so, and removes the journal.
TEST(OutputSet, ACommitKilledBetweenRenamesIsFinishedByTheNextRun) {
  const std::string dir = test::tempDir("outset-kill-mid");
  test::writeFile(dir + "/p.src", "old src");
  test::writeFile(dir + "/p.dat", "old dat");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::setenv(kFaultKillAfterRenamesEnv, "1", 1);
    OutputSet set;
    set.stage(dir + "/p.src", "new src");
    set.stage(dir + "/p.dat", "new dat");
    set.stage(dir + "/p.json", "new json");
    set.commit();
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status));
  // the mixed set the kill left, and its journal
  EXPECT_EQ(test::readFile(dir + "/p.src"), "new src");
  EXPECT_EQ(test::readFile(dir + "/p.dat"), "old dat");
  int journals = 0;
  for (const auto& name : listDir(dir)) journals += name.rfind(".roprec-commit.", 0) == 0 ? 1 : 0;
  EXPECT_EQ(journals, 1);
  OutputSet next;
  next.stage(dir + "/q.txt", "q");
  next.commit();
  EXPECT_EQ(test::readFile(dir + "/p.src"), "new src");
  EXPECT_EQ(test::readFile(dir + "/p.dat"), "new dat");
  EXPECT_EQ(test::readFile(dir + "/p.json"), "new json");
  ASSERT_EQ(next.notes().size(), 1u);
  EXPECT_NE(next.notes()[0].find("killed during it: " + dir + "/p.dat, " + dir + "/p.json"),
            std::string::npos)
      << next.notes()[0];
  EXPECT_EQ(listDir(dir), (std::vector<std::string>{"p.dat", "p.json", "p.src", "q.txt"}));
}

// readFileBytes reads a pipe (no size known beforehand) whole.
TEST(ReadFileBytes, EveryByteOfAPipe) {
  const std::string dir = test::tempDir("read_file_bytes_pipe");
  std::string big;
  for (long i = 0; i < 300000; ++i) big += static_cast<char>((i * 7919) % 251);
  const std::string fifo = dir + "/pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::thread writer([&] { test::writeFile(fifo, big); });
  const std::string got = readFileBytes(fifo);
  writer.join();
  EXPECT_TRUE(got == big);
}

}  // namespace
}  // namespace roprec
