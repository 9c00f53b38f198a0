// `roprec milling-stability` on the sample milling cell: the robot's six modes at the pose plus the
// tool mode in X and Y, a stable cut (exit 0), the lobe CSV and report; the limit of the tool mode
// alone scales exactly with its stiffness at fixed frequency (H ∝ 1/k: a cell with a 10 times
// softer tool has a 10 times lower limit, 1e-3) and that cut chatters (exit 1); a bad speed range
// exits 2.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using test::runRoprec;

std::string sampleCell() { return test::sourceDir() + "/samples/cells/alu-milling-7075.xml"; }

TEST(MillingStabilityCli, SampleCellModesLobesAndExitCodes) {
  const std::string dir = test::tempDir("milling-stability");
  const auto r = runRoprec("milling-stability --cell '" + sampleCell() +
                           "' --joints \"0 -60 100 0 50 0\" --csv '" + dir + "/l.csv' --report '" +
                           dir + "/l.html' --steps 50");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& modes = j["dynamics"]["modes"];
  ASSERT_EQ(modes.size(), 8u);
  for (size_t i = 0; i < 6; ++i) EXPECT_EQ(modes[i]["kind"], "robot");
  EXPECT_GT(modes[0]["frequency_Hz"].get<double>(), 5.0);
  EXPECT_LT(modes[0]["frequency_Hz"].get<double>(), 40.0);
  EXPECT_EQ(modes[6]["kind"], "tool");
  EXPECT_DOUBLE_EQ(modes[6]["frequency_Hz"].get<double>(), 2000.0);
  ASSERT_TRUE(j["stability"]["bounded"].get<bool>());
  EXPECT_GT(j["stability"]["ap_limit_mm"].get<double>(), 5.0);
  EXPECT_TRUE(j["stability"]["stable"].get<bool>());
  const std::string csv = test::readFile(dir + "/l.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "spindle_rpm,ap_limit_mm,chatter_Hz,lobe");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 51);
  EXPECT_NE(test::readFile(dir + "/l.html").find("<svg"), std::string::npos);

  // the tool mode alone, 20 and 2 N/um
  const auto stiff = runRoprec("milling-stability --cell '" + sampleCell() + "' --steps 2");
  ASSERT_EQ(stiff.exit_code, 0) << stiff.err;
  std::string text = test::readFile(sampleCell());
  const std::string stock = "<stock top_z_mm=\"0\"/>";
  ASSERT_NE(text.find(stock), std::string::npos);
  text.replace(text.find(stock), stock.size(), stock + "<dynamics tool_stiffness_N_per_um=\"2\"/>");
  test::writeFile(dir + "/soft.xml", text);
  const auto soft = runRoprec("milling-stability --cell '" + dir + "/soft.xml' --steps 2");
  EXPECT_EQ(soft.exit_code, 1) << soft.err;
  const double a20 = nlohmann::json::parse(stiff.out)["stability"]["ap_limit_mm"].get<double>();
  const double a2 = nlohmann::json::parse(soft.out)["stability"]["ap_limit_mm"].get<double>();
  EXPECT_NEAR(a2, a20 / 10, 1e-3 * a20 / 10);
  EXPECT_FALSE(nlohmann::json::parse(soft.out)["stability"]["stable"].get<bool>());

  const auto bad = runRoprec("milling-stability --cell '" + sampleCell() + "' --rpm \"5000 100\"");
  EXPECT_EQ(bad.exit_code, 2);
}

// A tool table of two mills: without --tool the command cannot tell which (exit 2); --tool 2 gives
// exactly what a cell with that mill alone gives (its geometry and own cut), --tool 9 is refused.
TEST(MillingStabilityCli, ToolSelectsTheMillOfTheTable) {
  const std::string dir = test::tempDir("milling-stability");
  std::string text = test::readFile(sampleCell());
  const size_t b = text.find("<mill ");
  const size_t e = text.find("/>", b) + 2;
  ASSERT_NE(b, std::string::npos);
  const std::string own = "<cut ae_mm=\"1\" fz_mm=\"0.06\"/>";
  std::string table = text;
  table.replace(b, e - b,
                "<mill tool=\"1\" diameter_mm=\"10\" teeth=\"3\"/>"
                "<mill tool=\"2\" diameter_mm=\"6\" teeth=\"4\">" +
                    own + "</mill>");
  std::string alone = text;
  alone.replace(b, e - b, "<mill diameter_mm=\"6\" teeth=\"4\">" + own + "</mill>");
  test::writeFile(dir + "/table.xml", table);
  test::writeFile(dir + "/alone.xml", alone);
  const std::string args = " --joints \"0 -60 100 0 50 0\" --steps 20";
  const auto which = runRoprec("milling-stability --cell '" + dir + "/table.xml'" + args);
  EXPECT_EQ(which.exit_code, 2);
  EXPECT_NE(which.err.find("which mill? Give --tool N"), std::string::npos) << which.err;
  const auto two = runRoprec("milling-stability --cell '" + dir + "/table.xml' --tool 2" + args);
  const auto ref = runRoprec("milling-stability --cell '" + dir + "/alone.xml'" + args);
  ASSERT_LT(two.exit_code, 2) << two.err;
  auto a = nlohmann::json::parse(two.out);
  auto r = nlohmann::json::parse(ref.out);
  a.erase("cell");
  r.erase("cell");
  EXPECT_EQ(a, r);
  EXPECT_EQ(runRoprec("milling-stability --cell '" + dir + "/table.xml' --tool 9" + args).exit_code,
            2);
}

}  // namespace
}  // namespace roprec
