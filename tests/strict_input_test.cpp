// Strict cell and robot-card XML (issue 13 §1): unknown elements and attributes are errors with a
// "did you mean" hint, a card needs <repeatability>, masses and inertias are physical; the
// repository's own cells and cards (the positive corpus) still load.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <regex>

#include "compensator/precision/cell.hpp"
#include "compensator/robot/robot_card.hpp"
#include "compensator/robot/urdf_loader.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/xml_node.hpp"
#include "support/test_support.hpp"

namespace fs = std::filesystem;

namespace roprec {
namespace {

std::string sampleCell() {
  return test::readFile(test::sourceDir() + "/samples/cells/housing-kr120.xml");
}

/// 1-based line of the first occurrence of `needle` in `text`.
int lineOf(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  if (at == std::string::npos) return -1;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
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

std::string replaced(const std::string& text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  std::string out = text;
  if (at != std::string::npos) out.replace(at, from.size(), to);
  return out;
}

TEST(XmlNames, DidYouMeanFindsNearMissesOnly) {
  const std::vector<std::string> known = {"mass_kg", "com_mm", "name", "diameter"};
  EXPECT_EQ(didYouMean("mas_kg", known), " (did you mean 'mass_kg'?)");
  EXPECT_EQ(didYouMean("MASS_KG", known), " (did you mean 'mass_kg'?)");
  EXPECT_EQ(didYouMean("dia", known), " (did you mean 'diameter'?)");
  EXPECT_EQ(didYouMean("colour", known), "");
  EXPECT_EQ(didYouMean("tolerence", {"tolerance"}, "<", ">"), " (did you mean <tolerance>?)");
}

// A 10 MB unknown name costs no more than a short one (candidates whose length differs by more
// than the distance allowed are skipped), and the message echoes it cut to a readable length.
TEST(XmlNames, AHugeUnknownNameIsAnsweredAtOnceAndClippedInTheMessage) {
  const std::vector<std::string> known = {"mass_kg", "com_mm", "name", "diameter"};
  const std::string huge(10'000'000, 'm');
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < 50; ++i) EXPECT_EQ(didYouMean(huge, known), "");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);
  const InputError e = cellError(
      replaced(sampleCell(), "<tool ", "<tool " + std::string(1'000'000, 'q') + "=\"1\" "),
      "strict-huge-attr");
  EXPECT_NE(e.message().find("unknown attribute '" + std::string(80, 'q') + "… (1000000 bytes)'"),
            std::string::npos)
      << e.message().substr(0, 300);
  EXPECT_LT(e.message().size(), 400u);
}

TEST(StrictCell, MisspeltToolMassIsAnErrorWithAHint) {
  const std::string text = replaced(sampleCell(), "mass_kg=", "mas_kg=");
  const InputError e = cellError(text, "strict-mas");
  EXPECT_EQ(e.line(), lineOf(text, "<tool "));
  EXPECT_EQ(e.message(), "unknown attribute 'mas_kg' on <tool> (did you mean 'mass_kg'?)");
}

TEST(StrictCell, MisspeltToleranceElementIsAnErrorWithAHint) {
  const std::string text = replaced(sampleCell(), "<tolerance ", "<tolerence ");
  const InputError e = cellError(text, "strict-tolerence");
  EXPECT_EQ(e.line(), lineOf(text, "<tolerence "));
  EXPECT_EQ(e.message(), "unknown element <tolerence> in <cell> (did you mean <tolerance>?)");
}

TEST(StrictCell, UnknownNamesEverywhereAreErrors) {
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
    const std::string text = replaced(sampleCell(), c.from, c.to);
    const InputError e = cellError(text, "strict-unknown");
    EXPECT_NE(e.message().find(c.expect), std::string::npos) << e.message();
    EXPECT_GT(e.line(), 0);
  }
}

TEST(StrictCell, ToolMassAndInertiaMustBePhysical) {
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
    const std::string text = replaced(base, c.from, c.to);
    const InputError e = cellError(text, "strict-mass");
    EXPECT_NE(e.message().find(c.expect), std::string::npos) << e.message();
    EXPECT_EQ(e.line(), lineOf(text, "<tool "));
  }
}

TEST(StrictCell, CliRefusesAMisspeltCellWithExit2AndWritesNothing) {
  const std::string dir = test::tempDir("strict-cli");
  const std::string cell = dir + "/cell.xml";
  const std::string text = replaced(sampleCell(), "mass_kg=", "mas_kg=");
  test::writeFile(cell, text);
  const std::string src = test::sourceDir() + "/samples/emotor-housing/housing_kr120.src";
  const auto r = test::runRoprec("predict --cell '" + cell + "' '" + src + "' --json '" + dir +
                                 "/p.json' --report '" + dir + "/p.html'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(cell + ":" + std::to_string(lineOf(text, "<tool ")) +
                       ": unknown attribute 'mas_kg' on <tool> (did you mean 'mass_kg'?)"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir + "/p.json"));
  EXPECT_FALSE(fs::exists(dir + "/p.html"));
}

TEST(StrictCell, UncertaintySeedAndSamplesMustBeIntegersInRange) {
  const std::string dir = test::tempDir("strict-seed");
  const std::string src = test::sourceDir() + "/samples/emotor-housing/housing_kr120.src";
  for (const std::string bad : {"seed=\"-1\"", "seed=\"1e300\"", "seed=\"2.5\"",
                                "samples=\"1e300\"", "samples=\"100.5\""}) {
    SCOPED_TRACE(bad);
    const std::string text =
        replaced(sampleCell(), "<uncertainty method=", "<uncertainty " + bad + " method=");
    test::writeFile(dir + "/cell.xml", text);
    const auto r = test::runRoprec("predict --cell '" + dir + "/cell.xml' '" + src + "' --json '" +
                                   dir + "/p.json'");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(
        r.err.find(dir + "/cell.xml:" + std::to_string(lineOf(text, "<uncertainty ")) +
                   ": <uncertainty> " + bad.substr(0, bad.find('=')) + " must be an integer in"),
        std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir + "/p.json"));
  }
}

// ---------------------------------------------------------------- robot cards

std::string bundledCardDir() { return test::sourceDir() + "/robots/kuka-kr120-r2500-pro"; }

/// The bundled KR 120 card with an absolute URDF path, edited by `edit`, written into a temp dir.
std::string cardCopy(const std::string& tag, const std::string& from, const std::string& to) {
  std::string text = test::readFile(bundledCardDir() + "/robot.xml");
  text = std::regex_replace(text, std::regex("urdf=\"kr120r2500pro.urdf\""),
                            "urdf=\"" + bundledCardDir() + "/kr120r2500pro.urdf\"");
  if (!from.empty()) text = replaced(text, from, to);
  const std::string path = test::tempDir(tag) + "/robot.xml";
  test::writeFile(path, text);
  return path;
}

InputError cardError(const std::string& path) {
  try {
    (void)loadRobot({path, "", ""});
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    return e;
  }
  ADD_FAILURE() << "accepted " << path;
  return InputError("", 0, "");
}

TEST(StrictCard, TheUneditedCopyLoads) {
  EXPECT_NO_THROW((void)loadRobot({cardCopy("strict-card-ok", "", ""), "", ""}));
}

TEST(StrictCard, UnknownNamesAreErrorsWithAHint) {
  const struct {
    std::string from, to, expect, line_of;
  } cases[] = {
      {"<joint name=\"joint_a3\" stiffness=", "<joint name=\"joint_a3\" stifness=",
       "unknown attribute 'stifness' on <joint> (did you mean 'stiffness'?)", "stifness="},
      {"<repeatability rp_mm=", "<repeatability rp_nm=", "(did you mean 'rp_mm'?)", "rp_nm="},
      {"<repeatability ", "<repeatibility ",
       "unknown element <repeatibility> in <robot> (did you mean <repeatability>?)",
       "<repeatibility "},
      {"rated_payload_kg=", "rated_payload=", "(did you mean 'rated_payload_kg'?)",
       "<robot name="},  // an attribute error is reported at its element's start tag
      {"<controller ", "<controler/>\n  <controller ", "(did you mean <controller>?)",
       "<controler/>"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.to);
    const std::string path = cardCopy("strict-card", c.from, c.to);
    const InputError e = cardError(path);
    EXPECT_NE(e.message().find(c.expect), std::string::npos) << e.message();
    EXPECT_EQ(e.line(), lineOf(test::readFile(path), c.line_of)) << e.message();
  }
}

TEST(StrictCard, ACardWithoutRepeatabilityIsAnError) {
  std::string text = test::readFile(cardCopy("strict-card-rp", "", ""));
  const std::size_t a = text.find("  <repeatability");
  const std::size_t b = text.find("/>", a) + 3;
  text.erase(a, b - a);
  const std::string path = test::tempDir("strict-card-no-rp") + "/robot.xml";
  test::writeFile(path, text);
  const InputError e = cardError(path);
  EXPECT_NE(e.message().find("has no <repeatability"), std::string::npos) << e.message();
  EXPECT_EQ(e.line(), lineOf(text, "<robot "));
}

TEST(StrictCard, LinkMassesAndInertiasMustBePhysical) {
  const std::string link = "<controller ";
  const struct {
    std::string extra, expect;
  } cases[] = {
      {"<link name=\"link_3\" mass_kg=\"-30\" com_mm=\"0 0 0\" source=\"x\"/>",
       "mass_kg must be > 0, got -30"},
      {"<link name=\"link_3\" mass_kg=\"inf\" com_mm=\"0 0 0\" source=\"x\"/>",
       "not a finite number"},
      {"<link name=\"link_3\" mass_kg=\"30\" com_mm=\"0 0 0\" inertia_kgm2=\"1 0 0 -1 0 1\" "
       "source=\"x\"/>",
       "principal moments must be >= 0"},
      {"<link name=\"link_3\" mass_kg=\"30\" com_mm=\"0 0 0\" inertia_kgm2=\"1 0 0 1 0 5\" "
       "source=\"x\"/>",
       "triangle inequality"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.extra);
    const std::string path = cardCopy("strict-card-link", link, c.extra + "\n  " + link);
    const InputError e = cardError(path);
    EXPECT_NE(e.message().find(c.expect), std::string::npos) << e.message();
    EXPECT_EQ(e.line(), lineOf(test::readFile(path), "<link "));
  }
}

TEST(StrictCard, UrdfInertialsMustBePhysical) {
  const std::string urdf = test::readFile(bundledCardDir() + "/kr120r2500pro.urdf");
  const std::regex mass("<mass value=\"([0-9.eE+-]+)\"\\s*/>");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(urdf, m, mass));
  const std::string dir = test::tempDir("strict-urdf");
  for (const char* bad : {"-12", "nan"}) {
    SCOPED_TRACE(bad);
    std::string text = urdf;
    text.replace(static_cast<std::size_t>(m.position(1)), static_cast<std::size_t>(m.length(1)),
                 bad);
    test::writeFile(dir + "/r.urdf", text);
    EXPECT_THROW((void)loadUrdfChain(dir + "/r.urdf"), InputError);
  }
}

// ---------------------------------------------------------------- the positive corpus

TEST(StrictCorpus, EveryCellAndCardInTheRepositoryLoads) {
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
