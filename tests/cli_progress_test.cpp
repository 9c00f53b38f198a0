// The progress line: on stderr only when it is a terminal and not --quiet, with
// holes done, rate and ETA, after the run has taken a second (ROPREC_PROGRESS_AFTER_S lowers that
// for the test). The terminal is a pseudo-terminal made by script(1).
#include <gtest/gtest.h>

#include <string>

#include "support/test_support.hpp"

namespace roprec {
namespace {

const std::string kCell = test::sourceDir() + "/samples/cells/housing-kr120.xml";
const std::string kProgram = test::sourceDir() + "/samples/emotor-housing/housing_kr120.src";

/// Runs `roprec ARGS` with stderr on a pseudo-terminal (stdout discarded); returns what the
/// terminal showed.
test::RunResult onTerminal(const std::string& env, const std::string& args) {
  const std::string inner = env + " '" + test::roprecBin() + "' " + args + " > /dev/null";
  return test::runCommand("script -qec \"" + inner + "\" /dev/null");
}

TEST(CliProgress, ATerminalSeesHolesRateAndEtaThenAClearedLine) {
  const test::RunResult r =
      onTerminal("ROPREC_PROGRESS_AFTER_S=0", "predict --cell '" + kCell + "' '" + kProgram + "'");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("predicting holes 204/204 ("), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("/s)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find('\r'), std::string::npos) << r.out;
}

TEST(CliProgress, QuietOrShortOrNotATerminalShowsNothing) {
  const test::RunResult quiet = onTerminal(
      "ROPREC_PROGRESS_AFTER_S=0", "predict --cell '" + kCell + "' '" + kProgram + "' --quiet");
  ASSERT_EQ(quiet.exit_code, 0) << quiet.out;
  EXPECT_EQ(quiet.out.find("predicting holes"), std::string::npos) << quiet.out;
  // The default: nothing for a run well under a second's threshold (the sample takes ~0.1 s).
  const test::RunResult quick =
      onTerminal("ROPREC_PROGRESS_AFTER_S=30", "predict --cell '" + kCell + "' '" + kProgram + "'");
  ASSERT_EQ(quick.exit_code, 0) << quick.out;
  EXPECT_EQ(quick.out.find("predicting holes"), std::string::npos) << quick.out;
  // stderr not a terminal (captured to a file): nothing.
  const test::RunResult piped =
      test::runCommand("ROPREC_PROGRESS_AFTER_S=0 '" + test::roprecBin() + "' predict --cell '" +
                       kCell + "' '" + kProgram + "'");
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_EQ(piped.err.find("predicting holes"), std::string::npos) << piped.err;
}

}  // namespace
}  // namespace roprec
