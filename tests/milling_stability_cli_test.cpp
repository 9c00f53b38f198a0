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

}  // namespace
}  // namespace roprec
