/// Locale independence: a host process that sets a comma-decimal locale (the C
/// locale through setlocale and the global C++ locale) must not change a byte of roprec's results,
/// and numbers must still parse.
#include <unistd.h>

#include <clocale>
#include <cstdlib>
#include <filesystem>
#include <locale>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "compensator/robot/robot_card.hpp"
#include "compensator/support/xml_node.hpp"
#include "plugin/api/job.hpp"
#include "plugin/api/robot_setup.hpp"
#include "plugin/api/robots.hpp"
#include "plugin/report/exports.hpp"
#include "plugin/report/json.hpp"
#include "plugin/report/robots_output.hpp"
#include "postproc/program.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

namespace fs = std::filesystem;

/// German-style numbers for the C++ locale: 1.234.567,5.
struct CommaNumpunct : std::numpunct<char> {
  char do_decimal_point() const override { return ','; }
  char do_thousands_sep() const override { return '.'; }
  std::string do_grouping() const override { return "\3"; }
};

/// Sets a comma-decimal C locale: de_DE.UTF-8 when installed, else one compiled with localedef
/// from the `locales` package's sources into the build tree (LOCPATH). Returns false when neither
/// is possible (the C++-locale part of the test still runs).
bool setCommaCLocale() {
  for (const char* name : {"de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8"}) {
    if (std::setlocale(LC_ALL, name) != nullptr) return true;
  }
  const std::string dir =
      fs::path(test::tempDir("locale")).parent_path().string() + "/roprec-test-locales";
  const std::string loc = dir + "/de_DE.UTF-8";
  if (!fs::exists(loc + "/LC_NUMERIC")) {
    // compiled beside, then renamed: tests running in parallel never see a half-written locale
    fs::create_directories(dir);
    const std::string part = loc + ".part." + std::to_string(::getpid());
    const std::string cmd = "localedef -i de_DE -f UTF-8 '" + part + "' >/dev/null 2>&1";
    if (std::system(cmd.c_str()) != 0 || !fs::exists(part + "/LC_NUMERIC")) return false;
    std::error_code ec;
    fs::rename(part, loc, ec);  // fails when another test was faster: its copy is used
    fs::remove_all(part, ec);
  }
  ::setenv("LOCPATH", dir.c_str(), 1);
  const bool ok = std::setlocale(LC_ALL, "de_DE.UTF-8") != nullptr;
  ::unsetenv("LOCPATH");
  return ok;
}

class HostLocale {
 public:
  HostLocale() : cxx_(std::locale()) {
    c_ = std::setlocale(LC_ALL, nullptr);
    c_comma_ = setCommaCLocale();
    std::locale::global(std::locale(std::locale::classic(), new CommaNumpunct));
  }
  ~HostLocale() {
    std::locale::global(cxx_);
    std::setlocale(LC_ALL, c_.c_str());
  }
  bool cComma() const { return c_comma_; }

 private:
  std::locale cxx_;
  std::string c_;
  bool c_comma_{false};
};

struct Outputs {
  std::string json;
  std::string report;
};

Outputs predictSample() {
  const std::string v = test::sourceDir() + "/samples/verification/";
  api::JobOptions opt;
  opt.holes = v + "test_kr120_holes.csv";
  const api::PredictionResult r = api::predictJob(
      test::sourceDir() + "/samples/cells/housing-kr120.xml", v + "test_kr120.src", opt);
  return {api::predictionJson(r).dump(), api::predictionReport(r)};
}

TEST(Locale, CommaDecimalHostLocaleGivesByteIdenticalPrediction) {
  const Outputs classic = predictSample();
  ASSERT_NE(classic.json.find("\"holes\""), std::string::npos);
  Outputs comma;
  bool c_comma = false;
  {
    const HostLocale host;
    c_comma = host.cComma();
    if (c_comma) {  // the C locale really is comma-decimal now
      char buf[16];
      std::snprintf(buf, sizeof buf, "%.1f", 1.5);
      EXPECT_STREQ(buf, "1,5");
    }
    std::ostringstream probe;
    probe << 1.5;
    EXPECT_EQ(probe.str(), "1,5");  // and so is the C++ global locale
    comma = predictSample();
  }
  if (!c_comma) std::cerr << "note: no comma-decimal C locale available; C++ locale only\n";
  EXPECT_EQ(comma.json, classic.json);
  EXPECT_EQ(comma.report, classic.report);
}

TEST(Locale, NumbersParseAndFormatInTheCFormatWhateverTheLocale) {
  const HostLocale host;
  ASSERT_TRUE(parseNumber("1.5").has_value());
  EXPECT_DOUBLE_EQ(*parseNumber("1.5"), 1.5);
  EXPECT_DOUBLE_EQ(*parseNumber(" -2.25e3 "), -2250.0);
  EXPECT_DOUBLE_EQ(*parseNumber("+4"), 4.0);
  EXPECT_FALSE(parseNumber("1,5").has_value());
  EXPECT_FALSE(parseNumber("nan").has_value());
  EXPECT_FALSE(parseNumber("inf").has_value());
  EXPECT_FALSE(parseNumber("1e400").has_value());
  EXPECT_EQ(api::formatNumber(1234567.5, 3), "1234567.500");
  EXPECT_EQ(api::formatNumber(-0.0001, 2), "0.00");
  EXPECT_EQ(api::formatNumber(0.1, -1), "0.1");
}

// The program writer keeps each number's written style with printf semantics, but in the "C"
// format: a comma-decimal host must not turn a compensated `X 1234.5` into `X 1234,500`.
TEST(Locale, ProgramNumbersAreWrittenWithADecimalPointWhateverTheLocale) {
  const postproc::NumberHints h{};
  const std::vector<std::pair<std::string, double>> cases{
      {"1200.000", 1234.5}, {"-5.2", -19.10055}, {"1.5E+03", 1234.5e3}, {"1.5e-3", 0.00125}};
  std::vector<std::string> classic;
  for (const auto& [text, v] : cases) classic.push_back(postproc::formatLike(text, v, h));
  EXPECT_EQ(classic[0], "1234.500");
  const HostLocale host;
  if (!host.cComma()) GTEST_SKIP() << "no comma-decimal C locale could be set up";
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::string t = postproc::formatLike(cases[i].first, cases[i].second, h);
    EXPECT_EQ(t, classic[i]);
    EXPECT_EQ(t.find(','), std::string::npos) << t;
  }
}

TEST(Locale, RobotListingAndLimitMessagesAreLocaleFree) {
  const Robot robot = loadRobot({"kuka-kr120-r2500-pro", "", ""});
  nc::Vec6 q = nc::Vec6::Zero();
  q[0] = 4.0;  // beyond A1's limit
  const std::string text = api::robotCardText(robot.card);
  const std::vector<std::string> limits = api::limitViolations(robot.chain, q);
  ASSERT_EQ(limits.size(), 1u);
  const HostLocale host;
  EXPECT_EQ(api::robotCardText(robot.card), text);
  EXPECT_EQ(api::limitViolations(robot.chain, q), limits);
  EXPECT_NE(limits[0].find("229.183 deg"), std::string::npos) << limits[0];
}

}  // namespace
}  // namespace roprec
