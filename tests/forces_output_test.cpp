// The forces JSON of a milling --program written as the path's blocks arrive (ForcesJsonStream)
// is the whole result's JSON byte for byte, whatever the block size and the thread count.
#include "plugin/report/forces_output.hpp"

#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

struct MillingCase {
  const char* cell;
  const char* program;
  bool one_thread;  ///< also streamed on one thread (not only on 2)
};

std::string samplePath(const std::string& name) { return test::sourceDir() + "/samples/" + name; }

api::ForcesRequest programRequest(const MillingCase& c) {
  api::ForcesRequest req;
  req.cell = samplePath(c.cell);
  req.program = samplePath(c.program);
  return req;
}

/// The streamed JSON and result; checks that every block is at most `block` points, in order.
std::string streamedJson(api::ForcesRequest req, std::size_t block, int threads,
                         api::ForcesResult& result, std::string& csv) {
  req.block = block;
  req.threads = threads;
  std::string bytes;
  api::ForcesJsonStream json([&](std::string_view v) { bytes.append(v); });
  std::size_t next = 0;
  api::ForcesPathSink sink;
  sink.head = [&](const api::ForcesResult& head) { csv = json.head(head); };
  sink.points = [&](const api::MillingCompensationResult& b) {
    EXPECT_EQ(b.first, next);
    EXPECT_GE(b.points_comp.size(), 1u);
    EXPECT_LE(b.points_comp.size(), block);
    next = b.first + b.points_comp.size();
    json.points(b);
  };
  result = api::processForces(req, sink);
  json.finish();
  EXPECT_EQ(next, result.milling->path->pointCount());  // every point handed over
  EXPECT_TRUE(result.milling->path->points_comp.empty());
  return bytes;
}

TEST(ForcesJsonStream, MillingProgramStreamedEqualsTheWholeResultBytes) {
  // the writer does not depend on the cell: the blocks of a one-pass and a four-pass program (the
  // box stock's engagement across blocks: MillingCompensation.PipelinedBlocks...)
  const MillingCase cases[] = {{"cells/alu-milling-7075.xml", "milling/wall_pass.src", true},
                               {"cells/alu-milling-7075.xml", "milling/box_passes.src", false}};
  for (const MillingCase& c : cases) {
    const api::ForcesRequest req = programRequest(c);
    const api::ForcesResult whole = api::processForces(req);
    const api::ForcesOutput o = api::forcesOutput(whole);
    const std::string expected = o.json.dump();
    ASSERT_GT(whole.milling->path->points_comp.size(), 7u) << c.program;  // several blocks of 3
    for (const int threads : {1, 2}) {
      if (threads == 1 && !c.one_thread) continue;
      api::ForcesResult r;
      std::string csv;
      const std::string got = streamedJson(req, 3, threads, r, csv);
      EXPECT_EQ(got, expected) << c.cell << " " << c.program << " threads " << threads;
      EXPECT_EQ(csv, o.curve_csv) << c.program;
      EXPECT_EQ(r.converged, whole.converged) << c.program;
      EXPECT_EQ(r.unstable, whole.unstable) << c.program;
    }
  }
}

TEST(ForcesJsonStream, HeadRefusesAResultThatIsNotAMillingPathHead) {
  api::ForcesRequest req;
  req.cell = samplePath("cells/alu-drilling-6061.xml");
  const api::ForcesResult drilling = api::processForces(req);
  api::ForcesJsonStream json([](std::string_view) {});
  EXPECT_THROW((void)json.head(drilling), InternalError);
}

}  // namespace
}  // namespace roprec
