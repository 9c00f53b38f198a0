// The cell file (compensator/precision/cell.hpp): unknown elements and attributes are errors with
// a "did you mean" hint at their line; tool mass, inertia, poses and centre of mass, the process
// numbers and the uncertainty settings are range-checked with short numbers in the messages; the
// repository's own cells and cards (the positive corpus) load.
#include "compensator/precision/cell.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "compensator/robot/robot_card.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/xml_node.hpp"
#include "tests/support/input_errors.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

namespace fs = std::filesystem;

std::string q(const std::string& p) { return "'" + p + "'"; }
std::string sample(const std::string& rel) { return test::sourceDir() + "/samples/" + rel; }

std::string sampleCell() {
  return test::readFile(test::sourceDir() + "/samples/cells/housing-kr120.xml");
}

/// Writes `text` as a cell file and loads it; returns the error (or fails the test).
InputError cellError(const std::string& text, const std::string& tag) {
  const std::string path = test::tempDir(tag) + "/cell.xml";
  test::writeFile(path, text);
  try {
    (void)loadCell(path);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    return e;
  }
  ADD_FAILURE() << "accepted:\n" << text;
  return InputError("", 0, "");
}

// A 10 MB unknown name costs no more than a short one (candidates whose length differs by more
// than the distance allowed are skipped; a quadratic comparison of 50 such names would not end
// within the test's time limit), and the message echoes it cut to a readable length.
TEST(Cell, AHugeUnknownAttributeIsAnsweredAtOnceAndClippedInTheMessage) {
  const std::vector<std::string> known = {"mass_kg", "com_mm", "name", "diameter"};
  const std::string huge(10'000'000, 'm');
  for (int i = 0; i < 50; ++i) EXPECT_EQ(didYouMean(huge, known), "");
  const InputError e = cellError(
      test::replaced(sampleCell(), "<tool ", "<tool " + std::string(1'000'000, 'q') + "=\"1\" "),
      "strict-huge-attr");
  EXPECT_NE(e.message().find("unknown attribute '" + std::string(80, 'q') + "… (1000000 bytes)'"),
            std::string::npos)
      << e.message().substr(0, 300);
  EXPECT_LT(e.message().size(), 400u);
}

TEST(Cell, MisspeltToolMassIsAnErrorWithAHint) {
  const std::string text = test::replaced(sampleCell(), "mass_kg=", "mas_kg=");
  const InputError e = cellError(text, "strict-mas");
  EXPECT_EQ(e.line(), test::lineOf(text, "<tool "));
  EXPECT_EQ(e.message(), "unknown attribute 'mas_kg' on <tool> (did you mean 'mass_kg'?)");
}

TEST(Cell, MisspeltToleranceElementIsAnErrorWithAHint) {
  const std::string text = test::replaced(sampleCell(), "<tolerance ", "<tolerence ");
  const InputError e = cellError(text, "strict-tolerence");
  EXPECT_EQ(e.line(), test::lineOf(text, "<tolerence "));
  EXPECT_EQ(e.message(), "unknown element <tolerence> in <cell> (did you mean <tolerance>?)");
}

TEST(Cell, UnknownNamesEverywhereAreErrors) {
  const struct {
    std::string from, to, expect;
  } cases[] = {
      {"<tool name=", "<tool colour=\"red\" name=",
       "unknown attribute 'colour' on <tool> (known: name, xyz, rpy, mass_kg, com_mm, "
       "inertia_kgm2)"},
      {"com_mm=", "Com_MM=", "(did you mean 'com_mm'?)"},
      {"<robot ref=", "<robot rev=\"x\" ref=", "unknown attribute 'rev' on <robot>"},
      {"<workobject xyz=", "<workobject xzy=\"0 0 0\" xyz=", "(did you mean 'xyz'?)"},
      {"<controller gravity_compensated=",
       "<controller gravity_compensate=\"true\" "
       "gravity_compensated=",
       "(did you mean 'gravity_compensated'?)"},
      {"<uncertainty method=", "<uncertainty samlpes=\"100\" method=", "(did you mean 'samples'?)"},
      {"<capability mc_approach_s=", "<capability mc_aproach_s=\"3\" mc_approach_s=",
       "(did you mean 'mc_approach_s'?)"},
      {"<tolerance position_mm=", "<tolerance postion_mm=\"0.1\" position_mm=",
       "(did you mean 'position_mm'?)"},
      {"<cell name=", "<cell nmae=\"x\" name=", "(did you mean 'name'?)"},
      {"<drill diameter_mm=", "<drill diamter_mm=\"9\" diameter_mm=",
       "(did you mean 'diameter_mm'?)"},
      {"<capability ", "<capabilty/>\n  <capability ", "unknown element <capabilty> in <cell>"},
      {"<material ", "<materal name=\"x\"/>\n    <material ",
       "unknown element <materal> in <process>"},
      {"<tolerance ", "<tool name=\"t2\"/>\n  <tolerance ", "<tool> is given twice in <cell>"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.to);
    const std::string text = test::replaced(sampleCell(), c.from, c.to);
    const InputError e = cellError(text, "strict-unknown");
    EXPECT_NE(e.message().find(c.expect), std::string::npos) << e.message();
    EXPECT_GT(e.line(), 0);
  }
}

TEST(Cell, ToolMassAndInertiaMustBePhysical) {
  const struct {
    std::string from, to, expect;
  } cases[] = {
      {"mass_kg=\"25.8\"", "mass_kg=\"-25.8\"", "mass_kg must lie in [0, 5000] kg, got -25.8"},
      {"mass_kg=\"25.8\"", "mass_kg=\"1e300\"", "mass_kg must lie in [0, 5000] kg"},
      {"mass_kg=\"25.8\"", "mass_kg=\"nan\"", "not a finite number"},
      {"mass_kg=\"25.8\"", "mass_kg=\"inf\"", "not a finite number"},
      {"inertia_kgm2=\"0.35 0 0 0.33 0 0.08\"", "inertia_kgm2=\"-0.35 0 0 0.33 0 0.08\"",
       "inertia_kgm2: principal moments must be >= 0"},
      {"inertia_kgm2=\"0.35 0 0 0.33 0 0.08\"", "inertia_kgm2=\"0.35 0 0 0.33 0 nan\"",
       "not a finite number"},
  };
  const std::string base = sampleCell();
  for (const auto& c : cases) {
    SCOPED_TRACE(c.to);
    const std::string text = test::replaced(base, c.from, c.to);
    const InputError e = cellError(text, "strict-mass");
    EXPECT_NE(e.message().find(c.expect), std::string::npos) << e.message();
    EXPECT_EQ(e.line(), test::lineOf(text, "<tool "));
  }
}

TEST(Cell, CliRefusesAMisspeltCellWithExit2AndWritesNothing) {
  const std::string dir = test::tempDir("strict-cli");
  const std::string cell = dir + "/cell.xml";
  const std::string text = test::replaced(sampleCell(), "mass_kg=", "mas_kg=");
  test::writeFile(cell, text);
  const std::string src = test::sourceDir() + "/samples/emotor-housing/housing_kr120.src";
  const auto r = test::runRoprec("predict --cell '" + cell + "' '" + src + "' --json '" + dir +
                                 "/p.json' --report '" + dir + "/p.html'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(cell + ":" + std::to_string(test::lineOf(text, "<tool ")) +
                       ": unknown attribute 'mas_kg' on <tool> (did you mean 'mass_kg'?)"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir + "/p.json"));
  EXPECT_FALSE(fs::exists(dir + "/p.html"));
}

TEST(Cell, UncertaintySeedAndSamplesMustBeIntegersInRange) {
  const std::string dir = test::tempDir("strict-seed");
  const std::string src = test::sourceDir() + "/samples/emotor-housing/housing_kr120.src";
  for (const std::string bad : {"seed=\"-1\"", "seed=\"1e300\"", "seed=\"2.5\"",
                                "samples=\"1e300\"", "samples=\"100.5\""}) {
    SCOPED_TRACE(bad);
    const std::string text =
        test::replaced(sampleCell(), "<uncertainty method=", "<uncertainty " + bad + " method=");
    test::writeFile(dir + "/cell.xml", text);
    const auto r = test::runRoprec("predict --cell '" + dir + "/cell.xml' '" + src + "' --json '" +
                                   dir + "/p.json'");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(
        r.err.find(dir + "/cell.xml:" + std::to_string(test::lineOf(text, "<uncertainty ")) +
                   ": <uncertainty> " + bad.substr(0, bad.find('=')) + " must be an integer in"),
        std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir + "/p.json"));
  }
}

/// The sample cell with `from` replaced by `to`, loaded: its InputError text (or "(accepted)").
std::string cellLoadError(const std::string& from, const std::string& to) {
  std::string text = test::readFile(sample("cells/housing-kr120.xml"));
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  const std::string path = test::tempDir("cell-edited") + "/cell.xml";
  test::writeFile(path, text);
  return test::inputErrorText([&] { (void)loadCell(path); });
}

TEST(Cell, PosesAndCentreOfMassAreBoundedAndNamedInShortNumbers) {
  const std::string tool = cellLoadError("xyz=\"0 0 320\"", "xyz=\"0 0 1e300\"");
  EXPECT_NE(tool.find("cell.xml:9: <tool> xyz '0 0 1e300' is beyond 100 m (mm expected)"),
            std::string::npos)
      << tool;
  EXPECT_EQ(tool.find("00000000"), std::string::npos) << tool;
  EXPECT_NE(cellLoadError("<workobject xyz=\"1350 0 300\" rpy=\"0 0 0\"",
                          "<workobject xyz=\"1350 0 300\" rpy=\"0 1e300 0\"")
                .find("cell.xml:13: <workobject> rpy '0 1e300 0' is beyond 3600 deg"),
            std::string::npos);
  EXPECT_NE(cellLoadError("com_mm=\"0 0 120\"", "com_mm=\"0 0 -1e300\"")
                .find("cell.xml:9: <tool> com_mm '0 0 -1e300' is beyond 100 m"),
            std::string::npos);
  EXPECT_EQ(cellLoadError("xyz=\"0 0 320\"", "xyz=\"0 0 320\""), "(accepted)");
}

TEST(Cell, AbsurdDepthWebAndToleranceAreRefusedAtTheirLine) {
  EXPECT_NE(cellLoadError("depth_mm=\"20\"", "depth_mm=\"1e-300\"")
                .find("cell.xml:17: <cut> depth_mm = 1e-300 is outside the plausible range"),
            std::string::npos);
  EXPECT_NE(cellLoadError("web_mm=\"1.2\"", "web_mm=\"1e-300\"")
                .find("cell.xml:15: <drill> web_mm = 1e-300 is below 0.02 Dc"),
            std::string::npos);
  EXPECT_NE(cellLoadError("web_mm=\"1.2\"", "web_mm=\"1.2\"").find("(accepted)"),
            std::string::npos);
  const std::string tol = cellLoadError("position_mm=\"0.2\"", "position_mm=\"1e300\"");
  EXPECT_NE(tol.find("position_mm must lie in (0, 10] mm"), std::string::npos) << tol;
}

TEST(Cell, SpindleSpeedAndFeedArePlausible) {
  // spindle_rpm 1e300 / 1e-300 and a feed of 1e-300 are refused (the machining-centre time would
  // print as a 300-digit number)
  EXPECT_NE(cellLoadError("spindle_rpm=\"6000\"", "spindle_rpm=\"1e-300\"")
                .find("cell.xml:17: <cut> spindle_rpm = 1e-300 is outside the plausible range"),
            std::string::npos);
  EXPECT_NE(cellLoadError("spindle_rpm=\"6000\"", "spindle_rpm=\"1e300\"")
                .find("spindle_rpm = 1e+300 is outside the plausible range 10 .. 100000"),
            std::string::npos);
  EXPECT_NE(cellLoadError("feed_mm_per_rev=\"0.2\"", "feed_mm_per_rev=\"1e-300\"")
                .find("feed_mm_per_rev = 1e-300 is outside the plausible range"),
            std::string::npos);
}

// <uncertainty stiffness_rel="0"> must not silently drop the stiffness term of U_robot.
TEST(Cell, AZeroBudgetTermIsAnError) {
  const std::string dir = test::tempDir("cell-budget");
  std::string cell = test::readFile(sample("cells/housing-kr120.xml"));
  cell.replace(cell.find("stiffness_rel=\"0.10\""), 20, "stiffness_rel=\"0\"");
  test::writeFile(dir + "/cell.xml", cell);
  const auto r =
      test::runRoprec("predict --cell " + q(dir + "/cell.xml") + " " +
                      q(sample("emotor-housing/holes.csv")) + " --json " + q(dir + "/p.json"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("stiffness_rel = 0 must lie in [0.01, 1]"), std::string::npos) << r.err;
}

TEST(Cell, EveryCellAndCardInTheRepositoryLoads) {
  int cells = 0;
  int cards = 0;
  for (const char* sub : {"samples", "robots", "examples", "tests/data"}) {
    const fs::path root = fs::path(test::sourceDir()) / sub;
    if (!fs::exists(root)) continue;
    for (const auto& f : fs::recursive_directory_iterator(root)) {
      if (!f.is_regular_file() || f.path().extension() != ".xml") continue;
      const std::string text = test::readFile(f.path().string());
      SCOPED_TRACE(f.path().string());
      if (text.find("<cell") != std::string::npos) {
        EXPECT_NO_THROW((void)loadCell(f.path().string()));
        ++cells;
      } else if (text.find("<robot ") != std::string::npos) {
        EXPECT_NO_THROW((void)loadRobot({f.path().string(), "", ""}));
        ++cards;
      }
    }
  }
  EXPECT_GE(cells, 8);
  EXPECT_GE(cards, 5);
}

}  // namespace
}  // namespace roprec
