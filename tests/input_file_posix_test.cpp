/// The loader of input files (compensator/support/input_file.hpp) where POSIX is needed to make
/// the input: character devices and FIFOs are refused without reading them (library and CLI), and
/// the size limits follow the environment (setenv). Built on Linux only
/// (tests/windows/posix_only_tests.txt); the portable cases are in input_file_test.cpp.
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "compensator/support/error.hpp"
#include "compensator/support/input_file.hpp"
#include "tests/support/file_checks.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

std::string errorOf(const std::string& path, InputKind kind) {
  return test::inputErrorOf(path, kind);
}

TEST(InputFile, FoldersDevicesAndFifosAreRefusedSayingWhatTheyAre) {
  const std::string dir = test::tempDir("input-kinds");
  EXPECT_NE(errorOf(dir, InputKind::kCell).find(dir + ": is a directory; give a cell file"),
            std::string::npos)
      << errorOf(dir, InputKind::kCell);
  // devices and FIFOs are refused before any read (reading /dev/zero would not end)
  EXPECT_NE(errorOf("/dev/zero", InputKind::kCell).find("is not a regular file"),
            std::string::npos);
  EXPECT_NE(errorOf("/dev/urandom", InputKind::kProgram).find("is not a regular file"),
            std::string::npos);
  const std::string fifo = dir + "/pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(errorOf(fifo, InputKind::kHoleList).find("is not a regular file"), std::string::npos);
  EXPECT_NE(errorOf(dir + "/missing.xml", InputKind::kCell).find("cannot open file"),
            std::string::npos);
  const auto zero = test::runRoprec("predict --cell /dev/zero '" + dir + "' --json -");
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_NE(zero.err.find("/dev/zero: is not a regular file"), std::string::npos) << zero.err;
}

TEST(InputFile, EachKindHasASizeLimitThatTheEnvironmentRaises) {
  EXPECT_EQ(inputSizeLimit(InputKind::kCell), std::size_t{64} << 20U);
  EXPECT_EQ(inputSizeLimit(InputKind::kProgram), std::size_t{2048} << 20U);
  const std::string dir = test::tempDir("input-limit");
  std::string big = "id,x,y,z,i,j,k\n";
  while (big.size() < (std::size_t{3} << 20U)) big += "H1,1,2,3,0,0,-1\n";
  test::writeFile(dir + "/big.csv", big);
  ::setenv("ROPREC_MAX_INPUT_MB", "2", 1);
  const std::string e = errorOf(dir + "/big.csv", InputKind::kHoleList);
  EXPECT_NE(e.find("MB, more than the 2 MB allowed for a hole list (set the "
                   "environment variable ROPREC_MAX_INPUT_MB to raise the limit)"),
            std::string::npos)
      << e;
  ::setenv("ROPREC_MAX_INPUT_MB", "4", 1);
  EXPECT_EQ(readInputFile(dir + "/big.csv", InputKind::kHoleList).size(), big.size());
  ::unsetenv("ROPREC_MAX_INPUT_MB");
}

}  // namespace
}  // namespace roprec
