// The drill of each hole (plugin/api/hole_input.hpp, docs/process.md §8 tool table): the program's
// tool selects the drill of the cell's tool table, a hole list's tool column or diameter does,
// a single-drill cell drills every hole and says so, and a job that changes tools with a
// single-drill cell, or uses a tool the table does not have, is refused at its line. The same
// holes drilled from the program with tool changes and from the hole list agree per hole.
#include "plugin/api/hole_input.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "compensator/support/error.hpp"
#include "plugin/api/job.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

const std::string kCell = test::sourceDir() + "/samples/cells/housing-kr120.xml";
const std::string kToolsCell = test::sourceDir() + "/samples/cells/housing-kr120-tools.xml";
const std::string kToolsProgram =
    test::sourceDir() + "/samples/emotor-housing/housing_kr120_tools.src";
const std::string kProgram = test::sourceDir() + "/samples/emotor-housing/housing_kr120.src";
const std::string kHoles = test::sourceDir() + "/samples/emotor-housing/holes.csv";

/// The line of `needle`'s first occurrence in `path` (1-based), 0 when absent.
int lineOf(const std::string& path, const std::string& needle) {
  const std::string text = test::readFile(path);
  const size_t at = text.find(needle);
  if (at == std::string::npos) return 0;
  int line = 1;
  for (size_t i = 0; i < at; ++i) line += text[i] == '\n' ? 1 : 0;
  return line;
}

TEST(HoleInput, ProgramToolKeysAreTheToolTableKeys) {
  EXPECT_EQ(api::programToolKey("TOOL_DATA[3]"), "3");
  EXPECT_EQ(api::programToolKey("UTOOL[12]"), "12");
  EXPECT_EQ(api::programToolKey("tDrill68"), "tDrill68");
  EXPECT_EQ(api::programToolKey("$TOOL"), "$TOOL");
}

TEST(HoleInput, ProgramToolChangesSelectTheDrillsOfTheToolTable) {
  const api::PredictionContext c =
      api::loadPredictionContext(kToolsCell, kToolsProgram, std::nullopt, "");
  ASSERT_EQ(c.job.requests.size(), 204U);
  std::map<std::string, int> holes_per_tool;
  for (const HoleRequest& r : c.job.requests) {
    ASSERT_GE(r.drill, 0) << r.id;
    ++holes_per_tool[r.tool];
    // tool n is drill n-1 of the table (document order)
    EXPECT_EQ(std::to_string(r.drill + 1), r.tool) << r.id;
  }
  // the sample's diameters: 72 × 6.8, 56 × 8.5, 60 × 10.2, 16 × 12
  EXPECT_EQ(holes_per_tool,
            (std::map<std::string, int>{{"1", 72}, {"2", 56}, {"3", 60}, {"4", 16}}));
  const api::PredictionResult r = api::predictJob(kToolsCell, kToolsProgram);
  for (const HolePrediction& h : r.holes) {
    const HoleRequest& q = r.context.job.requests[&h - r.holes.data()];
    const DrillingSpec& d = r.context.process->drills[static_cast<size_t>(q.drill)];
    EXPECT_EQ(h.diameter, d.geometry.diameter) << h.id;
    EXPECT_EQ(h.feed, d.feed) << h.id;
    EXPECT_EQ(h.spindle_rpm, d.spindle_rpm) << h.id;
  }
  // no "single drill" note: every hole states its drill
  for (const std::string& n : r.context.job.notes) EXPECT_NE(n.rfind("drill: ", 0), 0U) << n;
}

/// `text` with every `from` in the lines of the holes whose comment line contains `marker` (up to
/// the next comment line starting with `comment`) replaced by `to`.
std::string inHolesOf(const std::string& text, const std::string& marker,
                      const std::string& comment, const std::string& from, const std::string& to) {
  std::string out;
  bool in = false;
  size_t b = 0;
  while (b < text.size()) {
    size_t e = text.find('\n', b);
    e = e == std::string::npos ? text.size() : e + 1;
    std::string line = text.substr(b, e - b);
    const size_t first = line.find_first_not_of(' ');
    if (first != std::string::npos && line.compare(first, comment.size(), comment) == 0)
      in = line.find(marker) != std::string::npos;
    for (size_t at = 0; in && (at = line.find(from, at)) != std::string::npos; at += to.size())
      line.replace(at, from.size(), to);
    out += line;
    b = e;
  }
  return out;
}

/// The sample cell `name` with its drill replaced by a table of two: key_a (its 8.5 mm drill)
/// and key_b (a 12 mm drill).
std::string twoDrillCell(const std::string& name, const std::string& key_a,
                         const std::string& key_b) {
  std::string cell = test::readFile(test::sourceDir() + "/samples/cells/" + name);
  const size_t at = cell.find("<drill diameter_mm=\"8.5\"");
  EXPECT_NE(at, std::string::npos);
  cell.insert(at, "<drill tool=\"" + key_b +
                      "\" diameter_mm=\"12\" point_angle_deg=\"140\" stickout_mm=\"45\"/>\n    ");
  cell.insert(at + cell.substr(at).find("<drill diameter_mm") + 7, "tool=\"" + key_a + "\" ");
  return cell;
}

TEST(HoleInput, RapidToolDataArgumentSelectsTheDrill) {
  const std::string dir = test::tempDir("hole-input-rapid");
  std::string mod =
      test::readFile(test::sourceDir() + "/samples/emotor-housing/housing_irb6640.mod");
  mod = inHolesOf(mod, "drill D12.0", "!", "tSpindle", "tDrill12");
  const size_t decl = mod.find("  PERS wobjdata");
  mod.insert(decl,
             "  PERS tooldata tDrill12:=[TRUE,[[0,0,320],[1,0,0,0]],[25.8,[0,0,120],[1,0,0,0],"
             "0.35,0.33,0.08]];\n");
  test::writeFile(dir + "/h.mod", mod);
  test::writeFile(dir + "/cell.xml", twoDrillCell("housing-irb6640.xml", "tSpindle", "TDRILL12"));
  const api::PredictionContext c =
      api::loadPredictionContext(dir + "/cell.xml", dir + "/h.mod", std::nullopt, "");
  ASSERT_EQ(c.job.requests.size(), 204U);
  int twelve = 0;
  for (const HoleRequest& r : c.job.requests) {
    twelve += r.drill == 0;
    EXPECT_EQ(r.tool, r.drill == 0 ? "TDRILL12" : "tSpindle") << r.id;
  }
  EXPECT_EQ(twelve, 16);
}

TEST(HoleInput, FanucUtoolNumAndThePositionsToolSelectTheDrill) {
  const std::string dir = test::tempDir("hole-input-tp");
  const std::string ls =
      test::readFile(test::sourceDir() + "/samples/emotor-housing/housing_r2000.ls");
  // the positions of the 12 mm holes (the motions after their comment) get UT : 2
  std::vector<std::string> positions;
  bool in = false;
  for (size_t b = 0, e = 0; b < ls.size(); b = e + 1) {
    e = ls.find('\n', b);
    if (e == std::string::npos) e = ls.size();
    const std::string line = ls.substr(b, e - b);
    if (line.find("/POS") == 0) break;
    if (line.find("!") != std::string::npos) in = line.find("drill D12.0") != std::string::npos;
    const size_t p = line.find(" P[");
    if (in && p != std::string::npos) {
      const std::string pos = line.substr(p + 1, line.find(']', p) - p);
      if (std::find(positions.begin(), positions.end(), pos) == positions.end())
        positions.push_back(pos);
    }
  }
  ASSERT_EQ(positions.size(), 16U * 3U);  // approach, entry, bottom of each hole
  // the program selects tool 2 for them as a controller needs (UTOOL_NUM=2, back to 1 after):
  // the comment line where the tool changes becomes the UTOOL_NUM line
  std::string out;
  int active = 1;
  for (size_t b = 0, e = 0; b < ls.size(); b = e + 1) {
    e = ls.find('\n', b);
    if (e == std::string::npos) e = ls.size();
    std::string line = ls.substr(b, e - b);
    const size_t bang = line.find("  !");
    if (line.find("/POS") == 0) active = 0;
    const int want = line.find("drill D12.0") != std::string::npos ? 2 : 1;
    if (active > 0 && bang != std::string::npos && line.find(" drill D") != std::string::npos &&
        want != active) {
      line = line.substr(0, bang) + "  UTOOL_NUM=" + std::to_string(want) + " ;" +
             (line.back() == '\r' ? "\r" : "");
      active = want;
    }
    out += line + (e < ls.size() ? "\n" : "");
  }
  for (const std::string& pos : positions) {
    const size_t rec = out.find("\n" + pos + "{");
    ASSERT_NE(rec, std::string::npos) << pos;
    const size_t ut = out.find("UT : 1", rec);
    out.replace(ut, 6, "UT : 2");
  }
  test::writeFile(dir + "/h.ls", out);
  test::writeFile(dir + "/cell.xml", twoDrillCell("housing-r2000.xml", "1", "2"));
  api::JobOptions o;
  o.frame_cell = true;
  o.tool = "cell";
  const api::PredictionResult r = api::predictJob(dir + "/cell.xml", dir + "/h.ls", o);
  ASSERT_EQ(r.holes.size(), 204U);
  int twelve = 0;
  for (size_t i = 0; i < r.holes.size(); ++i) {
    const HoleRequest& q = r.context.job.requests[i];
    twelve += q.drill == 0;
    EXPECT_EQ(q.tool, q.drill == 0 ? "2" : "1");
    EXPECT_DOUBLE_EQ(r.holes[i].diameter, q.drill == 0 ? 12e-3 : 8.5e-3);
  }
  EXPECT_EQ(twelve, 16);
}

TEST(HoleInput, ProgramThatChangesToolsWithASingleDrillCellIsRefusedAtTheSecondTool) {
  const test::RunResult r =
      test::runRoprec("predict --cell '" + kCell + "' '" + kToolsProgram + "' --quiet");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  // the first hole of tool 2: its drill point's motion (the feed LIN after the first D8.5 comment)
  const int first_d85 = lineOf(kToolsProgram, "drill D8.5 depth");
  const std::string where = kToolsProgram + ":" + std::to_string(first_d85 + 5) + ": ";
  EXPECT_NE(r.err.find(where + "the job changes tools (TOOL_DATA[1] at "), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("then TOOL_DATA[2]) but the cell has a single drill"), std::string::npos);
  EXPECT_NE(r.err.find("hint: give the cell a tool table"), std::string::npos) << r.err;
}

TEST(HoleInput, ToolTheTableDoesNotHaveIsRefusedAtTheHole) {
  const std::string dir = test::tempDir("hole-input-tools");
  std::string cell = test::readFile(kToolsCell);
  // drop tool 4 (the 12 mm drill) from the table
  const size_t b = cell.find("    <drill tool=\"4\"");
  const size_t e = cell.find("</drill>", b) + std::string("</drill>\n").size();
  ASSERT_NE(b, std::string::npos);
  cell.erase(b, e - b);
  test::writeFile(dir + "/cell.xml", cell);
  const test::RunResult r =
      test::runRoprec("predict --cell '" + dir + "/cell.xml' '" + kToolsProgram + "' --quiet");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const int first_d12 = lineOf(kToolsProgram, "drill D12.0 depth");
  EXPECT_NE(r.err.find(kToolsProgram + ":" + std::to_string(first_d12 + 5) +
                       ": hole H189 is "
                       "drilled with tool "
                       "TOOL_DATA[4], "
                       "which the cell's "
                       "tool table does "
                       "not have (tools: "
                       "1 (Ø6.8 mm), 2 "
                       "(Ø8.5 mm), 3 "
                       "(Ø10.2 mm))"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("hint: add <drill tool=\"4\" .../>"), std::string::npos) << r.err;
}

TEST(HoleInput, HoleListSelectsTheDrillByToolColumnElseByDiameter) {
  const std::string dir = test::tempDir("hole-input-list");
  test::writeFile(dir + "/h.csv",
                  "id,x,y,z,i,j,k,diameter,depth,tool,feed,spindle_rpm\n"
                  "A,150,0,250,0,0,-1,6.8,16,,,\n"
                  "B,144.889,38.823,250,0,0,-1,7,16,tool4,,\n"
                  "C,129.904,75,250,0,0,-1,12,16,,0.3,4000\n");
  // tool names compare without regard to case; "tool4" is not in the table
  const test::RunResult bad =
      test::runRoprec("predict --cell '" + kToolsCell + "' '" + dir + "/h.csv' --quiet");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find(dir + "/h.csv:3: hole B is drilled with tool tool4, which the cell's "
                               "tool table does not have"),
            std::string::npos)
      << bad.err;
  test::writeFile(dir + "/h.csv",
                  "id,x,y,z,i,j,k,diameter,depth,tool,feed,spindle_rpm\n"
                  "A,150,0,250,0,0,-1,6.8,16,,,\n"
                  "B,144.889,38.823,250,0,0,-1,7,16,4,,\n"
                  "C,129.904,75,250,0,0,-1,12,16,,0.3,4000\n");
  const api::PredictionContext c =
      api::loadPredictionContext(kToolsCell, dir + "/h.csv", std::nullopt, "");
  ASSERT_EQ(c.job.requests.size(), 3U);
  EXPECT_EQ(c.job.requests[0].drill, 0);  // by its diameter
  EXPECT_EQ(c.job.requests[1].drill, 3);  // by its tool column (a 7 mm hole with the 12 mm drill)
  EXPECT_EQ(c.job.requests[2].drill, 3);  // by its diameter, with its own feed and speed
  EXPECT_DOUBLE_EQ(c.job.requests[2].feed, 0.3e-3);
  EXPECT_DOUBLE_EQ(c.job.requests[2].spindle_rpm, 4000.0);
  // a diameter no drill has, and no tool: nothing says which drill
  test::writeFile(dir + "/h.csv",
                  "id,x,y,z,i,j,k,diameter\n"
                  "A,150,0,250,0,0,-1,7\n");
  const test::RunResult none =
      test::runRoprec("predict --cell '" + kToolsCell + "' '" + dir + "/h.csv' --quiet");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find(dir + "/h.csv:2: hole A: nothing says which drill of the cell's tool "
                                "table drills it"),
            std::string::npos)
      << none.err;
}

TEST(HoleInput, SingleDrillCellSaysWhichHolesItDrillsWithoutADiameter) {
  const api::PredictionContext c = api::loadPredictionContext(kCell, kProgram, std::nullopt, "");
  int notes = 0;
  for (const std::string& n : c.job.notes) {
    if (n.rfind("drill: ", 0) != 0) continue;
    ++notes;
    EXPECT_EQ(n.rfind("drill: 204 of 204 holes (the first H1) state no drill or diameter: drilled "
                      "with the cell's single drill Ø8.5 mm",
                      0),
              0U)
        << n;
  }
  EXPECT_EQ(notes, 1);
  // a hole list with diameters says which: no note
  const api::PredictionContext l = api::loadPredictionContext(kCell, kHoles, std::nullopt, "");
  for (const std::string& n : l.job.notes) EXPECT_NE(n.rfind("drill: ", 0), 0U) << n;
}

TEST(HoleInput, ProgramToolChangesAndHoleListGiveEachHoleTheSameDrill) {
  // the program drilled tool by tool, alone (its tools select the drills) and with the hole list
  // (matched by position: ids, diameters, depths and tolerances from the list): the same drill,
  // diameter and deviation per hole; only the depth is the list's
  const api::PredictionResult prog = api::predictJob(kToolsCell, kToolsProgram);
  api::JobOptions o;
  o.holes = kHoles;
  const api::PredictionResult listed = api::predictJob(kToolsCell, kToolsProgram, o);
  ASSERT_EQ(prog.holes.size(), 204U);
  ASSERT_EQ(listed.holes.size(), 204U);
  for (size_t i = 0; i < prog.holes.size(); ++i) {
    const HolePrediction& a = prog.holes[i];
    const HolePrediction& b = listed.holes[i];
    SCOPED_TRACE(a.id + " / " + b.id);
    EXPECT_EQ(prog.context.job.requests[i].drill, listed.context.job.requests[i].drill);
    EXPECT_EQ(a.diameter, b.diameter);
    EXPECT_EQ(a.feed, b.feed);
    // the program's depth runs from the feed start 2 mm above the surface (its coordinates are
    // printed to 0.001 mm)
    EXPECT_NEAR(a.depth, b.depth + 2e-3, 1e-6);
    EXPECT_EQ(a.d_robot, b.d_robot);
    EXPECT_EQ(a.d_mach, b.d_mach);
    EXPECT_EQ(a.U_work_exact, b.U_work_exact);
  }
}

TEST(HoleInput, ToolTableDrillsGiveTheSameHoleAsTheSingleDrillAtItsDiameter) {
  // a 12 mm hole drilled with the table's 12 mm drill at the single drill's cut data is the
  // single 8.5 mm drill scaled to 12 mm only in the diameter's geometry: its own drill (web,
  // stick-out, feed 0.25) predicts a larger thrust than the scaled one
  const api::PredictionResult single = api::predictJob(kCell, kHoles);
  const api::PredictionResult table = api::predictJob(kToolsCell, kHoles);
  ASSERT_EQ(single.holes.size(), table.holes.size());
  int bigger = 0;
  int same = 0;
  for (size_t i = 0; i < single.holes.size(); ++i) {
    const HolePrediction& a = single.holes[i];
    const HolePrediction& b = table.holes[i];
    ASSERT_EQ(a.diameter, b.diameter);
    if (std::abs(a.diameter - 12e-3) < 1e-9) bigger += b.force_base.norm() > a.force_base.norm();
    if (std::abs(a.diameter - 8.5e-3) < 1e-9) same += (a.d_robot - b.d_robot).norm() < 1e-12;
  }
  EXPECT_EQ(bigger, 16);
  EXPECT_EQ(same, 56);  // the 8.5 mm drill is the single cell's drill, same cut
}

// ---- each drill's own TCP (<drill><tcp/>)

/// A one- or two-drill KR120 housing cell: `tool` is the cell's <tool>, `drills` its <drill>s.
std::string housingCell(const std::string& tool, const std::string& drills) {
  return "<cell name=\"tcp\">\n  <robot ref=\"kuka-kr120-r2500-pro\"/>\n  " + tool +
         "\n  <controller gravity_compensated=\"true\" calibration_load=\"tool\"/>\n"
         "  <workobject xyz=\"1350 0 300\" rpy=\"0 0 0\"/>\n  <process type=\"drilling\">\n" +
         drills +
         "    <cut feed_mm_per_rev=\"0.2\" spindle_rpm=\"6000\" depth_mm=\"20\"/>\n"
         "    <material name=\"AlSi9Cu3\"/>\n  </process>\n</cell>\n";
}

const std::string kSpindle =
    "<tool name=\"spindle\" xyz=\"0 0 320\" rpy=\"0 0 0\" mass_kg=\"25.8\" com_mm=\"0 0 120\" "
    "inertia_kgm2=\"0.35 0 0 0.33 0 0.08\"/>";
const std::string kDrill1 =
    "diameter_mm=\"6.8\" point_angle_deg=\"140\" web_mm=\"0.95\" stickout_mm=\"30\"";
const std::string kDrill2 =
    "diameter_mm=\"8.5\" point_angle_deg=\"140\" web_mm=\"1.2\" stickout_mm=\"34\"";
// drill 2 is a longer, heavier tool: its own mass data
const std::string kTool2Mass =
    "mass_kg=\"27.1\" com_mm=\"0 0 135\" inertia_kgm2=\"0.4 0 0 0.38 0 0.08\"";

/// The sample program drilled tool by tool, with its tools 1 and 2 at TCP z 300 and 340 mm;
/// `only`: just the holes of that tool (1 or 2), else those of tools 1 and 2.
std::string twoTcpProgram(int only) {
  std::string src = test::readFile(kToolsProgram);
  auto replace = [&](const std::string& a, const std::string& b) {
    const size_t at = src.find(a);
    ASSERT_NE(at, std::string::npos) << a;
    src.replace(at, a.size(), b);
  };
  replace("TOOL_DATA[1] = {X 0.000,Y 0.000,Z 320.000", "TOOL_DATA[1] = {X 0.000,Y 0.000,Z 300.000");
  replace("TOOL_DATA[2] = {X 0.000,Y 0.000,Z 320.000", "TOOL_DATA[2] = {X 0.000,Y 0.000,Z 340.000");
  const size_t t1 = src.find("; tool change: tool 1");
  const size_t t2 = src.find("; tool change: tool 2");
  const size_t t3 = src.find("; tool change: tool 3");
  const std::string head = src.substr(0, t1);
  const std::string body = only == 1   ? src.substr(t1, t2 - t1)
                           : only == 2 ? src.substr(t2, t3 - t2)
                                       : src.substr(t1, t3 - t1);
  return head + body + "SPINDLE_OFF()\nEND\n";
}

TEST(HoleInput, EachDrillsOwnTcpCompensatesAsASingleDrillCellWithThatTcp) {
  const std::string dir = test::tempDir("hole-input-tcp");
  // the tool table: tool 1 at z 300 with the spindle's mass data, tool 2 at z 340 with its own
  test::writeFile(
      dir + "/table.xml",
      housingCell(kSpindle, "    <drill tool=\"1\" " + kDrill1 +
                                ">\n      <tcp xyz=\"0 0 300\" rpy=\"0 0 0\"/>\n"
                                "    </drill>\n    <drill tool=\"2\" " +
                                kDrill2 + ">\n      <tcp xyz=\"0 0 340\" rpy=\"0 0 0\" " +
                                kTool2Mass + "/>\n    </drill>\n"));
  // the oracles: one single-drill cell per drill, its <tool> at that drill's TCP and mass
  test::writeFile(
      dir + "/one.xml",
      housingCell("<tool name=\"spindle\" xyz=\"0 0 300\" rpy=\"0 0 0\" mass_kg=\"25.8\" "
                  "com_mm=\"0 0 120\" inertia_kgm2=\"0.35 0 0 0.33 0 0.08\"/>",
                  "    <drill " + kDrill1 + "/>\n"));
  test::writeFile(
      dir + "/two.xml",
      housingCell("<tool name=\"spindle\" xyz=\"0 0 340\" rpy=\"0 0 0\" " + kTool2Mass + "/>",
                  "    <drill " + kDrill2 + "/>\n"));
  test::writeFile(dir + "/both.src", twoTcpProgram(0));
  test::writeFile(dir + "/one.src", twoTcpProgram(1));
  test::writeFile(dir + "/two.src", twoTcpProgram(2));
  const api::CompensationResult both = api::compensateJob(dir + "/table.xml", dir + "/both.src");
  const api::CompensationResult one = api::compensateJob(dir + "/one.xml", dir + "/one.src");
  const api::CompensationResult two = api::compensateJob(dir + "/two.xml", dir + "/two.src");
  ASSERT_EQ(one.holes.size(), 72U);
  ASSERT_EQ(two.holes.size(), 56U);
  ASSERT_EQ(both.holes.size(), one.holes.size() + two.holes.size());
  // the same table without <tcp>s (every drill at the cell's <tool>, the program's tools taken
  // as its TCP): a compensation the per-drill TCPs visibly change
  test::writeFile(dir + "/flat.xml",
                  housingCell(kSpindle, "    <drill tool=\"1\" " + kDrill1 +
                                            "/>\n    <drill tool=\"2\" " + kDrill2 + "/>\n"));
  api::CompensationJob flat_job;
  flat_job.job.tool = "cell";
  const api::CompensationResult flat =
      api::compensateJob(dir + "/flat.xml", dir + "/both.src", flat_job);
  ASSERT_EQ(flat.holes.size(), both.holes.size());
  double worst = 0;
  double worst_rot = 0;
  double moved = 0;
  for (size_t i = 0; i < both.holes.size(); ++i) {
    const HoleCompensation& h = both.holes[i];
    const HoleCompensation& o = i < 72 ? one.holes[i] : two.holes[i - 72];
    ASSERT_TRUE(h.ok && o.ok) << h.id << " " << h.reason << o.reason;
    worst = std::max(worst, (h.T_programmed.translation() - o.T_programmed.translation()).norm());
    worst_rot = std::max(
        worst_rot,
        Eigen::AngleAxisd(h.T_programmed.linear().transpose() * o.T_programmed.linear()).angle());
    moved = std::max(moved, (h.delta.translation() - flat.holes[i].delta.translation()).norm());
  }
  EXPECT_LE(worst, 1e-9);
  EXPECT_LE(worst_rot, 1e-9);
  EXPECT_GT(moved, 1e-6);
}

TEST(HoleInput, ProgramToolIsCheckedAgainstItsOwnDrillsTcp) {
  const std::string dir = test::tempDir("hole-input-tcp-check");
  test::writeFile(dir + "/both.src", twoTcpProgram(0));
  // tool 2's <tcp> says z 330, the program's TOOL_DATA[2] z 340: an error where it is selected
  test::writeFile(dir + "/table.xml",
                  housingCell(kSpindle, "    <drill tool=\"1\" " + kDrill1 +
                                            ">\n      <tcp xyz=\"0 0 300\"/>\n    </drill>\n"
                                            "    <drill tool=\"2\" " +
                                            kDrill2 +
                                            ">\n      <tcp xyz=\"0 0 330\"/>\n"
                                            "    </drill>\n"));
  const test::RunResult r =
      test::runRoprec("predict --cell '" + dir + "/table.xml' '" + dir + "/both.src' --quiet");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(
      r.err.find("both.src:" + std::to_string(lineOf(dir + "/both.src", "$TOOL = TOOL_DATA[2]")) +
                 ": the program's tool TOOL_DATA[2]"),
      std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("differs from the cell's drill 2 <tcp>"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("Correct the drill's <tcp> in"), std::string::npos) << r.err;
  // tool 1 matches its own <tcp> (z 300) though the cell's <tool> is at z 320: no error for it
  EXPECT_EQ(r.err.find("TOOL_DATA[1]"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace roprec
