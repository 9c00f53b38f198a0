// `roprec compensate --report` with a milling cell: the report is written with the
// program, one row per linear path point, and agrees with the targets export.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <regex>
#include <string>

#include "plugin/api/job.hpp"
#include "plugin/report/milling_report.hpp"
#include "support/test_support.hpp"

namespace roprec {
namespace {

TEST(MillingReport, CompensateWritesItWithOneRowPerPathPoint) {
  const std::string dir = test::tempDir("milling-report");
  const std::string src = test::sourceDir();
  const test::RunResult r =
      test::runRoprec("compensate --cell '" + src + "/samples/cells/alu-milling-7075.xml' '" + src +
                      "/samples/milling/wall_pass.src' -o '" + dir + "/c.src' --targets '" + dir +
                      "/t.json' --report '" + dir + "/r.html'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("wrote " + dir + "/r.html"), std::string::npos) << r.out;
  const std::string html = test::readFile(dir + "/r.html");
  ASSERT_FALSE(html.empty());
  EXPECT_NE(html.find("<h1>Milling path compensation</h1>"), std::string::npos);
  const auto t = nlohmann::json::parse(test::readFile(dir + "/t.json"));
  const auto& points = t.at("points");
  const std::regex row("<tr(?: class=\"bad\")?><td>([0-9]+)</td><td>([^<]*)</td>");
  std::size_t rows = 0;
  int cutting = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), row); it != std::sregex_iterator();
       ++it, ++rows) {
    ASSERT_LT(rows, points.size());
    EXPECT_EQ((*it)[1].str(), std::to_string(rows + 1));
    EXPECT_EQ((*it)[2].str(), points[rows].at("target").get<std::string>());
    cutting += points[rows].at("cutting").get<bool>() ? 1 : 0;
  }
  EXPECT_EQ(rows, points.size());
  EXPECT_GT(cutting, 0);
  EXPECT_NE(html.find(std::to_string(cutting) + " cutting"), std::string::npos);
  EXPECT_EQ(html.find("nan"), std::string::npos);
  // all or nothing: a report into a missing folder leaves no program either
  const test::RunResult bad = test::runRoprec(
      "compensate --cell '" + src + "/samples/cells/alu-milling-7075.xml' '" + src +
      "/samples/milling/wall_pass.src' -o '" + dir + "/d.src' --report '" + dir + "/no/r.html'");
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/d.src"));
}

// The exports written as the path streams past in blocks of 4 points (compensateMillingJob with a
// sink: the targets export as CSV and JSON point by point, the report from its per-point summary
// and its rows replayed after the plots) are the bytes of the whole-path writers, on passes with a
// box stock (rows that change engagement) and on the wall pass.
TEST(MillingReport, ExportsWrittenBlockByBlockAreTheWholePathBytes) {
  const std::string src = test::sourceDir();
  const std::pair<std::string, std::string> jobs[] = {
      {src + "/samples/cells/alu-milling-7075.xml", src + "/samples/milling/wall_pass.src"},
      {src + "/samples/milling/box-stock-7075.xml", src + "/samples/milling/box_passes.src"}};
  for (const auto& [cell, prog] : jobs) {
    MillingPathOptions o;
    o.resolve_edges = false;
    o.block = 4;
    const api::MillingCompensationResult whole = api::compensateMillingJob(cell, prog, false, o);
    std::string csv, json, rows;
    api::MillingTargetsStream c(true, prog, [&csv](std::string_view v) { csv += v; });
    api::MillingTargetsStream j(false, prog, [&json](std::string_view v) { json += v; });
    api::MillingReportSummary sum;
    int blocks = 0;
    const api::MillingCompensationResult streamed = api::compensateMillingJob(
        cell, prog, false, o, [&](const api::MillingCompensationResult& blk) {
          ++blocks;
          EXPECT_LE(blk.points_comp.size(), o.block);
          c.points(blk);
          j.points(blk);
          api::addMillingReportPoints(sum, blk);
          api::writeMillingReportRows(blk, [&rows](std::string_view v) { rows += v; });
        });
    c.finish(streamed);
    j.finish(streamed);
    std::string report;
    api::writeMillingReport(
        sum, streamed, prog, [&rows](const api::ByteSink& sink) { sink(rows); },
        [&report](std::string_view v) { report += v; });
    EXPECT_TRUE(streamed.points_comp.empty());
    EXPECT_GT(blocks, 3) << prog;
    EXPECT_EQ(csv, api::millingTargetsCsv(whole)) << prog;
    EXPECT_EQ(json, api::millingTargetsJson(whole, prog)) << prog;
    EXPECT_EQ(report, api::millingCompensationReport(whole, prog)) << prog;
  }
}

}  // namespace
}  // namespace roprec
