// The hole-list reader (postproc/table.cpp) and --holes matching (plugin/api/hole_input.cpp):
// duplicate ids, unknown columns, absurd sizes, non-unit directions and files in metres are refused
// with FILE:LINE and exit 2; a --holes list that matches nothing is an error, a partial match is
// listed, holes off their hole-list axis are a warning; the matcher is the old greedy one, without
// its O(n m) scans.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <random>
#include <set>
#include <sstream>

#include "compensator/support/error.hpp"
#include "postproc/drill.hpp"
#include "postproc/program.hpp"
#include "support/test_support.hpp"

namespace fs = std::filesystem;

namespace roprec {
namespace {

InputError holeListError(const std::string& text) {
  try {
    (void)postproc::parseHoleList("h.csv", text);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "h.csv");
    return e;
  }
  ADD_FAILURE() << "accepted:\n" << text;
  return InputError("", 0, "");
}

const std::string kHeader = "id,x,y,z,i,j,k,diameter,depth,tolerance\n";

TEST(HoleListValidation, BadRowsAreRefusedWithTheirLine) {
  const struct {
    std::string rows;
    int line;
    std::string expect;
  } cases[] = {
      {"H1,0,0,0,0,0,-1,8,10,0.2\nH2,40,0,0,0,0,-1,8,10,0.2\nH1,80,0,0,0,0,-1,8,10,0.2\n", 4,
       "duplicate hole id 'H1' (first at line 2"},
      {"H1,0,0,0,0,0,-1,8,10,0.2\nh1,80,0,0,0,0,-1,8,10,0.2\n", 3, "duplicate hole id 'h1'"},
      {"H1,0,0,0,0,0,-1,0,10,0.2\n", 2, "hole H1: diameter 0 mm is outside 0.1..100 mm"},
      {"H1,0,0,0,0,0,-1,-8,10,0.2\n", 2, "diameter -8 mm is outside 0.1..100 mm"},
      {"H1,0,0,0,0,0,-1,1e300,10,0.2\n", 2, "diameter 1e+300 mm is outside 0.1..100 mm"},
      {"H1,0,0,0,0,0,-1,8,0,0.2\n", 2, "depth 0 mm is outside 0.05..2000 mm"},
      {"H1,0,0,0,0,0,-1,8,1e300,0.2\n", 2, "depth 1e+300 mm is outside 0.05..2000 mm"},
      {"H1,0,0,0,0,0,-1,8,10,0\n", 2, "tolerance 0 mm is outside 0.001..50 mm"},
      {"H1,0,0,0,0,0,-1,8,10,-0.2\n", 2, "tolerance -0.2 mm is outside 0.001..50 mm"},
      {"H1,0,0,0,0,0,-1,8,10,1e300\n", 2, "tolerance 1e+300 mm is outside 0.001..50 mm"},
      {"H1,0,0,0,0,0,0,8,10,0.2\n", 2, "hole H1: drilling direction i,j,k is zero"},
      {"H1,0,0,0,0,0,-2,8,10,0.2\n", 2, "drilling direction i,j,k has length 2, not 1"},
      {"H1,0,0,0,0.5,0,-0.5,8,10,0.2\n", 2, "has length 0.707107, not 1"},
      {"H1,0,0,1e300,0,0,-1,8,10,0.2\n", 2, "a coordinate is beyond 100000 mm"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.rows);
    const InputError e = holeListError(kHeader + c.rows);
    EXPECT_EQ(e.line(), c.line) << e.message();
    EXPECT_NE(e.message().find(c.expect), std::string::npos) << e.message();
  }
}

TEST(HoleListValidation, PerHoleToolFeedAndSpeedAreReadAndBounded) {
  const std::string header = "id,x,y,z,i,j,k,tool,feed,spindle_rpm\n";
  const std::vector<postproc::HoleSpec> ok = postproc::parseHoleList(
      "h.csv", header + "H1,0,0,0,0,0,-1,3,0.15,4500\nH2,40,0,0,0,0,-1,tDrill,,\n");
  ASSERT_EQ(ok.size(), 2U);
  EXPECT_EQ(ok[0].tool, "3");
  EXPECT_EQ(ok[0].feed_mm_per_rev, 0.15);
  EXPECT_EQ(ok[0].spindle_rpm, 4500.0);
  EXPECT_EQ(ok[1].tool, "tDrill");
  EXPECT_FALSE(ok[1].feed_mm_per_rev);
  EXPECT_FALSE(ok[1].spindle_rpm);
  const InputError feed = holeListError(header + "H1,0,0,0,0,0,-1,3,20,4500\n");
  EXPECT_EQ(feed.line(), 2);
  EXPECT_NE(feed.message().find("hole H1: feed 20 mm/rev is outside 0.001..10 mm/rev"),
            std::string::npos)
      << feed.message();
  const InputError rpm = holeListError(header + "H1,0,0,0,0,0,-1,3,0.1,0\n");
  EXPECT_NE(rpm.message().find("hole H1: spindle_rpm 0 1/min is outside 10..100000 1/min"),
            std::string::npos)
      << rpm.message();
}

TEST(HoleListValidation, UnknownAndRepeatedColumnsAreRefused) {
  const InputError dia = holeListError("id,x,y,z,i,j,k,dia\nH1,0,0,0,0,0,-1,8\n");
  EXPECT_EQ(dia.line(), 1);
  EXPECT_EQ(dia.message(), "unknown column 'dia' in the hole list (did you mean 'diameter'?)");
  const InputError tol = holeListError("id,x,y,z,i,j,k,tolerence_mm\nH1,0,0,0,0,0,-1,0.1\n");
  EXPECT_NE(tol.message().find("(did you mean 'tolerance'?)"), std::string::npos);
  const InputError other = holeListError("# c\nid,x,y,z,i,j,k,colour\nH1,0,0,0,0,0,-1,red\n");
  EXPECT_EQ(other.line(), 2);
  EXPECT_NE(other.message().find("a hole list has the columns id,x,y,z,i,j,k,diameter"),
            std::string::npos)
      << other.message();
  const InputError twice = holeListError("id,x,y,z,i,j,k,depth,depth_mm\nH1,0,0,0,0,0,-1,8,9\n");
  EXPECT_NE(twice.message().find("column 'depth' is given twice"), std::string::npos);
}

TEST(HoleListValidation, AFileInMetresIsRefused) {
  const InputError e = holeListError(kHeader +
                                     "H1,0.150,0.000,0.250,0,0,-1,6.8,16,0.2\n"
                                     "H2,0.145,0.039,0.250,0,0,-1,6.8,16,0.2\n"
                                     "H3,0.130,0.075,0.250,0,0,-1,6.8,16,0.2\n");
  EXPECT_EQ(e.line(), 2);
  EXPECT_NE(e.message().find("looks like metres"), std::string::npos) << e.message();
  EXPECT_NE(e.message().find("multiply by 1000"), std::string::npos) << e.message();
}

TEST(HoleListValidation, GoodListsStillLoad) {
  // a single hole at the origin, directions within 1e-3 of unit length (normalised), no sizes
  const auto one = postproc::parseHoleList("h.csv", kHeader + "H1,0,0,0,0,0,-1.0005,,,\n");
  ASSERT_EQ(one.size(), 1u);
  EXPECT_NEAR(one[0].direction.norm(), 1.0, 1e-15);
  EXPECT_FALSE(one[0].diameter_mm.has_value());
  const auto diag =
      postproc::parseHoleList("h.csv",
                              "id,x_mm,y_mm,z_mm,i,j,k,comment\n"
                              "A,1,2,3,0.7071,0,-0.7071,chamfer\nB,40,2,3,0,0,-1,top\n");
  EXPECT_EQ(diag.size(), 2u);
  for (const char* f :
       {"/samples/emotor-housing/holes.csv", "/samples/verification/test_kr120_holes.csv",
        "/tests/data/programs/holes.csv", "/tests/data/paper/holes.csv"}) {
    SCOPED_TRACE(f);
    EXPECT_NO_THROW((void)postproc::readHoleList(test::sourceDir() + f));
  }
}

// ---------------------------------------------------------------- CLI: exit 2, nothing written

const std::string kCell = "/samples/cells/housing-kr120.xml";
const std::string kSrc = "/samples/emotor-housing/housing_kr120.src";
const std::string kHoles = "/samples/emotor-housing/holes.csv";

TEST(HoleListValidation, CliRefusesABadListWithExit2AndWritesNothing) {
  const std::string dir = test::tempDir("holes-cli");
  test::writeFile(dir + "/bad.csv", kHeader +
                                        "T001,150,0,250,0,0,-1,6.8,16,0.2\n"
                                        "T002,144.889,38.823,250,0,0,-1,6.8,16,0.2\n"
                                        "T001,130,75,250,0,0,-1,6.8,16,0.2\n");
  test::writeFile(dir + "/dia.csv", "id,x,y,z,i,j,k,dia\nT001,150,0,250,0,0,-1,6.8\n");
  const std::string s = test::sourceDir();
  const std::string json = " --json '" + dir + "/p.json' --report '" + dir + "/p.html'";
  const struct {
    std::string args, expect;
  } cases[] = {
      {"predict --cell '" + s + kCell + "' '" + dir + "/bad.csv'" + json,
       dir + "/bad.csv:4: duplicate hole id 'T001' (first at line 2"},
      {"predict --cell '" + s + kCell + "' '" + s + kSrc + "' --holes '" + dir + "/dia.csv'" + json,
       dir + "/dia.csv:1: unknown column 'dia' in the hole list (did you mean 'diameter'?)"},
      {"compensate --cell '" + s + kCell + "' '" + s + kSrc + "' --holes '" + dir +
           "/dia.csv' -o '" + dir + "/o.src'",
       dir + "/dia.csv:1: unknown column 'dia'"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.args);
    const auto r = test::runRoprec(c.args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("roprec: error: " + c.expect), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/p.json"));
    EXPECT_FALSE(fs::exists(dir + "/p.html"));
    EXPECT_FALSE(fs::exists(dir + "/o.src"));
  }
}

// ---------------------------------------------------------------- --holes matching

/// The sample hole list with rows edited by `edit(id, line) -> line ("" drops the row)`.
template <class F>
std::string editedSampleList(const std::string& path, F edit) {
  std::istringstream in(test::readFile(test::sourceDir() + kHoles));
  std::string out;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] != '#' && line.rfind("id,", 0) != 0) {
      line = edit(line.substr(0, line.find(',')), line);
      if (line.empty()) continue;
    }
    out += line + "\n";
  }
  test::writeFile(path, out);
  return path;
}

TEST(HolesMatching, AListThatMatchesNoProgramHoleIsAnError) {
  const std::string dir = test::tempDir("holes-nomatch");
  const std::string list =
      editedSampleList(dir + "/other.csv", [](const std::string& id, const std::string& row) {
        // another part: other ids, 500 mm away
        std::string r = "Z" + row;
        const std::size_t a = r.find(',') + 1;
        const std::size_t b = r.find(',', a);
        r.replace(a, b - a, std::to_string(std::stod(r.substr(a, b - a)) + 500.0));
        (void)id;
        return r;
      });
  const std::string s = test::sourceDir();
  const auto r = test::runRoprec("predict --cell '" + s + kCell + "' '" + s + kSrc + "' --holes '" +
                                 list + "' --json '" + dir + "/p.json'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(list + ":3: --holes: none of the 204 entries of the hole list matches one "
                              "of the 204 holes of housing_kr120.src"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir + "/p.json"));
}

TEST(HolesMatching, PartialMatchesAreListedInTheNotes) {
  const std::string dir = test::tempDir("holes-partial");
  std::string list =
      editedSampleList(dir + "/part.csv", [](const std::string& id, const std::string& row) {
        return id == "T002" || id == "T003" ? std::string() : row;
      });
  test::writeFile(list, test::readFile(list) + "X900,9000,0,0,0,0,-1,6.8,16,0.2\n");
  const std::string s = test::sourceDir();
  const auto r = test::runRoprec("predict --cell '" + s + kCell + "' '" + s + kSrc + "' --holes '" +
                                 list + "' --quiet --json '" + dir + "/p.json'");
  ASSERT_LE(r.exit_code, 1) << r.err;
  const auto j = nlohmann::json::parse(test::readFile(dir + "/p.json"));
  std::string notes;
  for (const auto& n : j["notes"]) notes += n.get<std::string>() + "\n";
  EXPECT_NE(notes.find("--holes: 2 of 204 holes of housing_kr120.src have no entry in part.csv"),
            std::string::npos)
      << notes;
  EXPECT_NE(notes.find("--holes: 1 of 203 entries of part.csv match no hole of "
                       "housing_kr120.src: X900 (line 205)"),
            std::string::npos)
      << notes;
  // and on stderr, where the user running the command sees them (also with --quiet: they say
  // which holes the numbers are about)
  EXPECT_NE(r.err.find("roprec: note: --holes: 2 of 204 holes of housing_kr120.src have no entry"),
            std::string::npos)
      << r.err;
}

/// The matcher before the grid (O(H S)): the reference the new one must agree with.
std::vector<postproc::HoleMatch> bruteForceMatch(const std::vector<postproc::Hole>& holes,
                                                 const postproc::Program& p,
                                                 const std::vector<postproc::HoleSpec>& specs,
                                                 double tol_mm) {
  std::vector<postproc::HoleMatch> out;
  std::set<int> taken;
  auto iequal = [](std::string a, std::string b) {
    for (char& c : a) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    for (char& c : b) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return a == b;
  };
  for (std::size_t h = 0; h < holes.size(); ++h) {
    const postproc::Hole& hole = holes[h];
    int by_id = -1;
    for (std::size_t s = 0; s < specs.size() && by_id < 0; ++s)
      for (const int t : hole.targets)
        if (t >= 0 && iequal(p.target_list[static_cast<std::size_t>(t)].name, specs[s].id))
          by_id = static_cast<int>(s);
    if (by_id >= 0 && taken.count(by_id) == 0) {
      taken.insert(by_id);
      out.push_back({static_cast<int>(h), by_id, 0.0});
      continue;
    }
    const Vec3 bottom = hole.position * 1e3;
    const Vec3 entry = bottom - hole.axis * hole.depth * 1e3;
    int best = -1;
    double best_d = tol_mm;
    for (std::size_t s = 0; s < specs.size(); ++s) {
      if (taken.count(static_cast<int>(s)) != 0) continue;
      if (specs[s].direction.dot(hole.axis) < std::cos(1.0 * kDeg)) continue;
      const Vec3 q = specs[s].position_mm;
      const double depth = specs[s].depth_mm.value_or(0.0);
      const double t =
          std::clamp((q - entry).dot(hole.axis), -depth - 50.0, hole.depth * 1e3 + depth + 50.0);
      const double d = (entry + hole.axis * t - q).norm();
      if (d <= best_d) {
        best_d = d;
        best = static_cast<int>(s);
      }
    }
    if (best >= 0) {
      taken.insert(best);
      out.push_back({static_cast<int>(h), best, best_d});
    }
  }
  return out;
}

TEST(HolesMatching, TheFastMatcherAgreesWithTheBruteForceOne) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const double tol : {0.5, 3.0, 40.0}) {
    SCOPED_TRACE(tol);
    postproc::Program p;
    std::vector<postproc::Hole> holes;
    std::vector<postproc::HoleSpec> specs;
    const Vec3 axes[] = {-Vec3::UnitZ(), Vec3::UnitX(), Vec3(1, 1, -1).normalized()};
    for (int i = 0; i < 400; ++i) {
      postproc::Hole h;
      h.axis = axes[i % 3];
      h.position = Vec3(u(rng), u(rng), u(rng)) * 0.3;  // m, a 600 mm box: some near misses
      h.depth = 0.01 + 0.01 * std::abs(u(rng));
      postproc::Target t;
      t.name = i % 5 == 0 ? "h" + std::to_string(i) : "P" + std::to_string(i);
      p.target_list.push_back(t);
      h.targets = {static_cast<int>(p.target_list.size() - 1)};
      holes.push_back(h);
      postproc::HoleSpec s;
      s.id = "H" + std::to_string(i);
      // near its hole (on the axis, off by up to ~tol), sometimes on another hole's axis
      const postproc::Hole& on = holes[static_cast<std::size_t>(i % 7 == 0 ? i / 2 : i)];
      // within ~1.2 deg of the hole axis: some beyond the 1 deg limit
      s.direction = (on.axis + Vec3(u(rng), u(rng), u(rng)) * 0.012).normalized();
      s.position_mm = on.position * 1e3 - on.axis * 30.0 * std::abs(u(rng)) +
                      Vec3(u(rng), u(rng), u(rng)) * tol * 0.8;
      if (i % 4 == 0) s.depth_mm = 5 + 30 * std::abs(u(rng));
      specs.push_back(s);
    }
    const auto fast = postproc::matchHoles(holes, p, specs, tol);
    const auto slow = bruteForceMatch(holes, p, specs, tol);
    ASSERT_EQ(fast.size(), slow.size());
    for (std::size_t k = 0; k < fast.size(); ++k) {
      EXPECT_EQ(fast[k].hole, slow[k].hole);
      EXPECT_EQ(fast[k].spec, slow[k].spec);
      EXPECT_DOUBLE_EQ(fast[k].distance_mm, slow[k].distance_mm);
    }
    EXPECT_GT(fast.size(), 100u);
  }
}

// A header that is one 10 MB token is refused ("unknown column", the name cut to a readable
// length) with a message of bounded size; every parse step is linear (a quadratic step on 10 MB
// would not end within the test's time limit).
TEST(HoleListValidation, AHugeUnknownColumnIsRefusedFastWithAShortMessage) {
  const std::string token(10'000'000, 'w');
  const InputError e = holeListError(token + "\nH1,1,2,3,0,0,-1\n");
  EXPECT_NE(e.message().find("unknown column '" + std::string(80, 'w') + "… (10000000 bytes)'"),
            std::string::npos)
      << e.message().substr(0, 300);
  EXPECT_LT(e.message().size(), 500u);
  const std::string spaces = "id,x,y,z,i,j,k," + std::string(2'000'000, ' ') + "dia\n";
  (void)holeListError(spaces + "H1,1,2,3,0,0,-1,5\n");
}

// A hole-list diameter meets the same rules as the cell's drill diameter: the range 0.1 .. 100 mm,
// and the cell's feed <= 0.1 Dc (a 0.1 mm hole at 0.2 mm/rev would get 0 N and "conforms"): an
// error naming the hole's line.
TEST(HoleListValidation, AHoleTheCellsFeedCannotDrillIsAnError) {
  const std::string dir = test::tempDir("holes-feed");
  const std::string cell = test::sourceDir() + "/samples/cells/housing-kr120.xml";
  test::writeFile(
      dir + "/h.csv",
      kHeader + "T001,150,0,250,0,0,-1,6.8,16,0.2\nT002,144.889,38.823,250,0,0,-1,0.1,16,0.2\n");
  const auto r =
      test::runRoprec("predict --cell '" + cell + "' '" + dir + "/h.csv' --quiet --json -");
  EXPECT_EQ(r.exit_code, 2) << r.out.substr(0, 300);
  EXPECT_NE(
      r.err.find(dir + "/h.csv:3: hole T002: diameter 0.1 mm is too small for the cell's feed"),
      std::string::npos)
      << r.err;
  EXPECT_NE(holeListError(kHeader + "H1,1,2,3,0,0,-1,150,16,0.2\n").message().find("diameter"),
            std::string::npos);
}

std::string q(const std::string& p) { return "'" + p + "'"; }
std::string sample(const std::string& rel) { return test::sourceDir() + "/samples/" + rel; }

TEST(HoleListValidation, ADecimalCommaIsAnErrorAtItsRow) {
  const std::string dir = test::tempDir("hole-list-comma");
  std::string text = test::readFile(sample("emotor-housing/holes.csv"));
  const std::size_t at = text.find(",6.8,16.0,0.20");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 4, ",6,8");
  test::writeFile(dir + "/holes.csv", text);
  const auto r = test::runRoprec("predict --cell " + q(sample("cells/housing-kr120.xml")) + " " +
                                 q(dir + "/holes.csv") + " --json " + q(dir + "/p.json"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("holes.csv:3: this row has 11 cells but the header has 10 columns"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir + "/p.json"));
}

// A cell without its <workobject> with a program that states its own base frame and a hole list:
// every hole lies 1.3 m off its hole-list axis, which must not be matched by id without a word.
TEST(HolesMatching, ProgramHolesOffTheirHoleListAxisAreAWarning) {
  std::string text = test::readFile(sample("cells/housing-kr120.xml"));
  const std::size_t b = text.find("<workobject");
  const std::size_t e = text.find("/>", b) + 2;
  text.erase(b, e - b);
  const std::string dir = test::tempDir("holes-off-axis");
  test::writeFile(dir + "/cell.xml", text);
  const std::string args = " " + q(sample("emotor-housing/housing_kr120.src")) + " --holes " +
                           q(sample("emotor-housing/holes.csv")) + " --json " + q(dir + "/p.json");
  const auto bad = test::runRoprec("predict --cell " + q(dir + "/cell.xml") + args);
  EXPECT_NE(bad.err.find("warning: 204 of 204 drill points of the program lie off their "
                         "hole-list axis by more than --match-tol 0.5 mm"),
            std::string::npos)
      << bad.err;
  const auto good =
      test::runRoprec("predict --cell " + q(sample("cells/housing-kr120.xml")) + args);
  EXPECT_EQ(good.exit_code, 0) << good.err;
  EXPECT_EQ(good.err.find("off their hole-list axis"), std::string::npos) << good.err;
}

}  // namespace
}  // namespace roprec
