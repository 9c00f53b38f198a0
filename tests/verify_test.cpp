// `roprec verify` (plugin/api/verify.hpp) on damaged measured files: two holes leave the
// correlation per workobject axis undefined (no JSON key, "undefined" in the text and the report,
// never NaN); a hole whose y and z were swapped is refused before the identification, at its line.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>

#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using nlohmann::json;

std::string q(const std::string& p) { return "'" + p + "'"; }
std::string sample(const std::string& rel) { return test::sourceDir() + "/samples/" + rel; }

TEST(Verify, TwoMeasuredHolesGiveAnUndefinedCorrelationNotANaN) {
  const std::string dir = test::tempDir("verify-two-holes");
  // The sample's measured file cut after its second hole.
  const std::string full = test::readFile(sample("verification/measured.csv"));
  std::string cut;
  int holes = 0;
  for (std::size_t at = 0; at < full.size();) {
    const std::size_t end = full.find('\n', at);
    const std::string line = full.substr(at, end == std::string::npos ? end : end - at + 1);
    at = end == std::string::npos ? full.size() : end + 1;
    if (line.rfind("V", 0) == 0 && ++holes > 2) break;
    cut += line;
  }
  ASSERT_EQ(holes, 3);
  test::writeFile(dir + "/m.csv", cut);
  const auto r = test::runRoprec("verify --cell " + q(sample("cells/housing-kr120.xml")) + " " +
                                 q(sample("verification/test_kr120.src")) + " --holes " +
                                 q(sample("verification/test_kr120_holes.csv")) + " --measured " +
                                 q(dir + "/m.csv") + " --json " + q(dir + "/v.json") +
                                 " --report " + q(dir + "/v.html"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("correlation x y z undefined"), std::string::npos) << r.out;
  const json j = json::parse(test::readFile(dir + "/v.json"));
  EXPECT_EQ(j["summary"]["holes"], 2);
  EXPECT_FALSE(j["summary"].contains("correlation_workobject_xyz"));
  const std::string html = test::readFile(dir + "/v.html");
  EXPECT_EQ(html.find(">nan"), std::string::npos);
  EXPECT_NE(html.find("undefined"), std::string::npos);
}

TEST(Verify, MeasuredColumnsSwappedAreRefusedBeforeTheIdentification) {
  const std::string dir = test::tempDir("verify-swap");
  std::string text = test::readFile(sample("verification/measured.csv"));
  // swap the y and z cells of the first hole
  const size_t row = text.find("\nV01,") + 1;
  const size_t y = text.find(',', row + 4) + 1, z = text.find(',', y) + 1, u = text.find(',', z);
  text = text.substr(0, row + 4) + text.substr(z, u - z) + "," + text.substr(y, z - 1 - y) +
         text.substr(u);
  test::writeFile(dir + "/m.csv", text);
  const auto r = test::runRoprec("verify --cell " + q(sample("cells/housing-kr120.xml")) + " " +
                                 q(sample("verification/test_kr120.src")) + " --holes " +
                                 q(sample("verification/test_kr120_holes.csv")) + " --measured " +
                                 q(dir + "/m.csv") + " --register rigid --calibrate " +
                                 q(dir + "/card.xml") + " --json " + q(dir + "/v.json"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("m.csv:5: measured hole V01 lies "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("more than any drilling deviation"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace roprec
