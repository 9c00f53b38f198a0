// U_mach is one number per tool and cut, whichever command prints it:
// `roprec forces` (the process alone) and `roprec predict` (the per-hole budget) give
// the same U_mach with the same 2-D radial coverage factor, at the drill's own diameter and — with
// a <machining_deviation diameter_mm> override — at another diameter of the hole list.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using test::runRoprec;

std::string writeCell(const std::string& dir, const std::string& name, const std::string& drill,
                      const std::string& extra) {
  const std::string path = dir + "/" + name;
  test::writeFile(path,
                  "<cell name=\"umach\">\n"
                  "  <robot ref=\"kuka-kr120-r2500-pro\"/>\n"
                  "  <tool name=\"spindle\" xyz=\"0 0 350\" rpy=\"0 0 0\" mass_kg=\"25\" "
                  "com_mm=\"0 0 150\"/>\n"
                  "  <workobject xyz=\"1600 0 400\" rpy=\"0 0 0\"/>\n"
                  "  <process type=\"drilling\">\n"
                  "    " +
                      drill +
                      "\n"
                      "    <cut feed_mm_per_rev=\"0.2\" spindle_rpm=\"3000\" depth_mm=\"12\"/>\n"
                      "    <material name=\"Al 6061-T6\"/>\n"
                      "    " +
                      extra +
                      "\n"
                      "  </process>\n"
                      "  <tolerance position_mm=\"0.2\"/>\n"
                      "</cell>\n");
  return path;
}

double forcesUmach(const std::string& cell) {
  const auto r = runRoprec("forces --cell '" + cell + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["machining_deviation"]["k"].get<double>(), 2.45, 0.005);
  return j["machining_deviation"]["U_mach_um"].get<double>();
}

TEST(UmachConsistency, ForcesAndPredictAgreeAtEveryDiameter) {
  const std::string dir = test::tempDir("umach");
  const std::string extra = "<machining_deviation diameter_mm=\"8\" stickout_mm=\"40\"/>";
  const std::string cell =
      writeCell(dir, "c10.xml",
                "<drill diameter_mm=\"10\" tool_material=\"carbide\" stickout_mm=\"30\"/>", extra);
  // the same tool as a cell of its own: Dc 8 with the 40 mm stick-out the override names
  const std::string cell8 = writeCell(
      dir, "c8.xml", "<drill diameter_mm=\"8\" tool_material=\"carbide\" stickout_mm=\"40\"/>", "");
  const std::string holes = dir + "/holes.csv";
  test::writeFile(holes,
                  "id,x,y,z,i,j,k,diameter,depth,tolerance\n"
                  "A,0,0,0,0,0,-1,10,12,0.2\n"
                  "B,50,0,0,0,0,-1,8,12,0.2\n");
  const auto r =
      runRoprec("predict --cell '" + cell + "' '" + holes + "' --json '" + dir + "/p.json'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto p = nlohmann::json::parse(test::readFile(dir + "/p.json"));
  ASSERT_EQ(p["holes"].size(), 2u);
  const double u10 = p["holes"][0]["uncertainty_um"]["U_mach"].get<double>();
  const double u8 = p["holes"][1]["uncertainty_um"]["U_mach"].get<double>();
  EXPECT_NEAR(u10, forcesUmach(cell), 0.01);
  EXPECT_NEAR(u8, forcesUmach(cell8), 0.01);
  EXPECT_NE(u8, u10);
}

}  // namespace
}  // namespace roprec
