// Predicting a program's holes while it is read (plugin/api/lookahead.hpp):
//  - postproc::HoleRecognizer advanced over a program as it grows gives recognizeHoles' holes
//    (every prefix of the motions of the samples and the corpus programs, every dialect);
//  - readProgram's progress hook is called every kReadProgressLines lines of a KRL .src;
//  - predictJobStreaming with the lookahead writes the bytes of predictJob on one thread, takes
//    the predictions made ahead when the job's requests are the same, none when the job sets
//    them up differently after the read (a base frame given with --frame), and reports the
//    program's own error when the program is broken after the holes predicted ahead;
//  - sameRequest tells apart requests that differ in any field.
#include <gtest/gtest.h>

#include <cstdio>

#include "plugin/api/job.hpp"
#include "plugin/api/lookahead.hpp"
#include "plugin/api/prediction_setup.hpp"
#include "postproc/drill.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

std::string cellPath() { return test::sourceDir() + "/samples/cells/housing-kr120.xml"; }

/// `n` drill cycles with a drilling marker each (7 lines a cycle after 3 header lines).
std::string drillProgram(int n, const std::string& base, const std::string& tail = "") {
  return test::krlDrillCycles(n, base, true, tail);
}

void expectSameHoles(const std::vector<postproc::Hole>& a, const std::vector<postproc::Hole>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(a[i].id, b[i].id);
    EXPECT_EQ(a[i].entry_motion, b[i].entry_motion);
    EXPECT_EQ(a[i].bottom_motion, b[i].bottom_motion);
    EXPECT_EQ(a[i].surface_motion, b[i].surface_motion);
    EXPECT_EQ(a[i].targets, b[i].targets);
    EXPECT_EQ(a[i].position, b[i].position);
    EXPECT_EQ(a[i].axis, b[i].axis);
    EXPECT_EQ(a[i].surface, b[i].surface);
    EXPECT_EQ(a[i].depth, b[i].depth);
    EXPECT_EQ(a[i].base, b[i].base);
    EXPECT_EQ(a[i].tool, b[i].tool);
    EXPECT_EQ(a[i].slower_feed, b[i].slower_feed);
    EXPECT_EQ(a[i].all_markers, b[i].all_markers);
    EXPECT_EQ(a[i].marker_begin, b[i].marker_begin);
    EXPECT_EQ(a[i].marker_end, b[i].marker_end);
  }
}

TEST(Lookahead, RecognisingAsTheProgramGrowsGivesTheHolesOfTheWholeProgram) {
  std::vector<std::string> programs;
  for (const char* f : {"housing_kr120.src", "housing_irb6640.mod", "housing_r2000.ls"})
    programs.push_back(test::sourceDir() + "/samples/emotor-housing/" + f);
  const std::string dir = test::tempDir("lookahead_recognise");
  test::writeFile(dir + "/big.src", drillProgram(120, test::kHousingBase));
  programs.push_back(dir + "/big.src");
  if (const std::string corpus = test::corpusDir(); !corpus.empty()) {
    for (const char* f : {"DRILLR30IA.LS", "DrillIRC5.mod", "DrillKRC2DAT.src", "DrillKRC4.src"})
      programs.push_back(corpus + "/robodk/" + f);
  }
  for (const std::string& path : programs) {
    SCOPED_TRACE(path);
    postproc::Program p = postproc::readProgram(path);
    const std::vector<postproc::Hole> whole = postproc::recognizeHoles(p);
    ASSERT_FALSE(whole.empty());
    // the motions come back one at a time; the recogniser advances after each
    std::vector<postproc::Motion> motions = std::move(p.motions);
    p.motions.clear();
    postproc::HoleRecognizer r;
    size_t seen = 0;
    for (postproc::Motion& m : motions) {
      r.advance(p, false);
      EXPECT_GE(r.holes().size(), seen);  // a hole once recognised stays
      seen = r.holes().size();
      p.motions.push_back(std::move(m));
    }
    r.advance(p, true);
    expectSameHoles(r.holes(), whole);
  }
}

TEST(Lookahead, TheReadCallsItsHookEveryBlockOfLinesAndRecognisesAlong) {
  const std::string dir = test::tempDir("lookahead_hook");
  test::writeFile(dir + "/big.src", drillProgram(800, test::kHousingBase));  // 5,603 lines
  postproc::HoleRecognizer r;
  int calls = 0;
  size_t holes_at_last_call = 0;
  postproc::Program p = postproc::readProgram(dir + "/big.src", [&](const postproc::Program& q) {
    ++calls;
    r.advance(q, false);
    holes_at_last_call = r.holes().size();
  });
  EXPECT_EQ(calls, static_cast<int>(5603 / postproc::kReadProgressLines));
  // the last call at line 4,096: the cycles before it but the one it cuts
  EXPECT_EQ(holes_at_last_call, (2 * postproc::kReadProgressLines - 3) / 7);
  r.advance(p, true);
  expectSameHoles(r.holes(), postproc::recognizeHoles(p));
  EXPECT_EQ(r.holes().size(), 800U);
}

/// predictJobStreaming's JSON, what it predicted ahead and how many texts of holes it handed to
/// the sink.
struct Streamed {
  std::string json;
  size_t ahead{0};
  size_t texts{0};
};

/// `format_ahead`: the lookahead also formats the holes it predicts (as `roprec predict` has it).
Streamed streamed(const std::string& program, const api::JobOptions& opt,
                  bool format_ahead = true) {
  Streamed s;
  std::optional<api::PredictionJsonStream> js;
  const api::PredictionResult r = api::predictJobStreaming(
      cellPath(), program, opt,
      [&](size_t, std::span<const HolePrediction> h, std::span<const HoleRequest> q,
          std::span<const std::string> x, int t) {
        s.texts += x.size();
        js->holes(h, q, t, x);
      },
      [&](const api::PredictionContext& c) {
        js.emplace(c, [&](std::string_view b) { s.json += b; });
      },
      {}, format_ahead ? &api::PredictionJsonStream::itemFormat : api::HoleFormatFactory());
  js->finish(r.summary);
  s.ahead = r.predicted_ahead;
  return s;
}

TEST(Lookahead, HolesPredictedWhileTheProgramIsReadGiveTheBytesOfTheJob) {
  const std::string dir = test::tempDir("lookahead_job");
  // 2,100 cycles, 14,703 lines: the hook sees about 2,000 of them before the read ends; the job
  // predicts them in two blocks
  test::writeFile(dir + "/big.src", drillProgram(2100, test::kHousingBase));
  // the same with its base frame in the controller (BASE_DATA[1], given by --frame 2 mm off the
  // cell's workobject, which the read takes for it): the job moves each request into that frame
  // after the read, so none predicted ahead is the job's
  test::writeFile(dir + "/bd.src", drillProgram(2100, "$BASE = BASE_DATA[1]"));
  for (const std::string name : {"big.src", "bd.src"}) {
    SCOPED_TRACE(name);
    const std::string path = (dir + "/").append(name);
    api::JobOptions opt;
    if (name == "bd.src")
      opt.frames.push_back({"BASE_DATA[1]", Pose(Eigen::Translation3d(1.35, 0.002, 0.3))});
    opt.threads = 1;
    const std::string one = api::predictionJson(api::predictJob(cellPath(), path, opt)).dump();
    for (const int threads : {2, 3}) {
      opt.threads = threads;
      opt.lookahead = api::JobOptions::Lookahead::kComplete;
      for (const bool format_ahead : {true, false}) {
        const Streamed s = streamed(path, opt, format_ahead);
        EXPECT_TRUE(s.json == one) << threads << " threads, format ahead " << format_ahead;
        EXPECT_EQ(s.texts, format_ahead ? s.ahead : 0U);
        if (name == "big.src") {
          EXPECT_GT(s.ahead, 1900U);
          EXPECT_LT(s.ahead, 2100U);
        } else {
          EXPECT_EQ(s.ahead, 0U);
        }
      }
      opt.lookahead = api::JobOptions::Lookahead::kOff;
      const Streamed off = streamed(path, opt);
      EXPECT_TRUE(off.json == one);
      EXPECT_EQ(off.ahead, 0U);
    }
  }
}

TEST(Lookahead, AProgramBrokenAfterTheHolesPredictedAheadGivesItsOwnError) {
  const std::string dir = test::tempDir("lookahead_error");
  test::writeFile(dir + "/bad.src", drillProgram(2100, test::kHousingBase, "LIN {X 1.0,Y\n"));
  std::string expected;
  try {
    api::JobOptions opt;
    (void)api::predictJob(cellPath(), dir + "/bad.src", opt);
  } catch (const InputError& e) {
    expected = e.what();
  }
  ASSERT_NE(expected.find("bad.src:14704"), std::string::npos) << expected;
  api::JobOptions opt;
  opt.threads = 2;
  opt.lookahead = api::JobOptions::Lookahead::kComplete;
  try {
    (void)streamed(dir + "/bad.src", opt);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), expected);
  }
}

TEST(Lookahead, SameRequestTellsApartEveryField) {
  HoleRequest a;
  a.id = "H1";
  a.T_W_tcp = Pose(Eigen::Translation3d(1.2, 0.1, 0.4));
  a.tolerance = 2e-4;
  a.diameter = 6.8e-3;
  a.depth = 0.016;
  a.config = VendorConfig{};
  a.written_config = VendorConfig{};
  a.line = 12;
  a.surface_W = Vec3(1.2, 0.1, 0.42);
  a.nominal_axis = std::make_pair(Vec3(1.2, 0.1, 0.4), Vec3(0, 0, -1));
  a.ik_seed = Vec6::Zero();
  EXPECT_TRUE(api::sameRequest(a, a));
  const std::vector<std::pair<const char*, void (*)(HoleRequest&)>> changes = {
      {"id", [](HoleRequest& r) { r.id = "H2"; }},
      {"pose", [](HoleRequest& r) { r.T_W_tcp.translation().x() += 1e-15; }},
      {"rotation", [](HoleRequest& r) { r.T_W_tcp.linear()(0, 1) = -0.0; }},
      {"tolerance", [](HoleRequest& r) { r.tolerance = 1e-4; }},
      {"diameter", [](HoleRequest& r) { r.diameter = 0; }},
      {"depth", [](HoleRequest& r) { r.depth = 0.02; }},
      {"config", [](HoleRequest& r) { r.config->kuka.status = 2; }},
      {"no config", [](HoleRequest& r) { r.config.reset(); }},
      {"written config", [](HoleRequest& r) { r.written_config->fanuc.turns[2] = 1; }},
      {"line", [](HoleRequest& r) { r.line = 13; }},
      {"surface", [](HoleRequest& r) { r.surface_W->z() = 0.43; }},
      {"no surface", [](HoleRequest& r) { r.surface_W.reset(); }},
      {"nominal axis", [](HoleRequest& r) { r.nominal_axis->second.z() = 1; }},
      {"seed", [](HoleRequest& r) { (*r.ik_seed)[5] = -0.0; }},
      {"no seed", [](HoleRequest& r) { r.ik_seed.reset(); }},
      {"evidence", [](HoleRequest& r) { r.evidence = "on the hole list"; }},
  };
  for (const auto& [what, change] : changes) {
    HoleRequest b = a;
    change(b);
    EXPECT_FALSE(api::sameRequest(a, b)) << what;
    EXPECT_FALSE(api::sameRequest(b, a)) << what;
  }
  // a field added to HoleRequest must be compared by sameRequest (and changed above)
  EXPECT_EQ(sizeof(HoleRequest), 496U);
}

}  // namespace
}  // namespace roprec
