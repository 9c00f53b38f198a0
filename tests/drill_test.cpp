// postproc/drill.hpp: drill-cycle recognition advanced over a program as it grows
// (HoleRecognizer) gives recognizeHoles' holes: every prefix of the motions of the samples and the
// corpus programs, every dialect.
#include <gtest/gtest.h>

#include "postproc/drill.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

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

TEST(HoleRecognizer, AdvancingAsTheProgramGrowsGivesTheHolesOfTheWholeProgram) {
  std::vector<std::string> programs;
  for (const char* f : {"housing_kr120.src", "housing_irb6640.mod", "housing_r2000.ls"})
    programs.push_back(test::sourceDir() + "/samples/emotor-housing/" + f);
  const std::string dir = test::tempDir("recognise_growing");
  test::writeFile(dir + "/big.src", test::krlDrillCycles(120, test::kHousingBase, true));
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

}  // namespace
}  // namespace roprec
