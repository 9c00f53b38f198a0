// predictHoles over threads: the output is byte-identical to one thread (every hole's contract
// JSON compared as text, and the raw doubles bit for bit), for the linear and the Monte Carlo
// budget, and predicting in blocks with the continuity seed equals one call. The reference is
// the plain sequential loop of predictHole written here (each hole seeded by the previous
// admissible joints), not predictHoles itself.
#include <gtest/gtest.h>

#include "plugin/api/job.hpp"
#include "plugin/api/prediction_setup.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

api::PredictionContext load() {
  return api::loadPredictionContext(test::sourceDir() + "/samples/cells/housing-kr120.xml",
                                    test::sourceDir() + "/samples/emotor-housing/holes.csv",
                                    std::nullopt, "");
}

std::vector<HolePrediction> sequential(const PredictionModel& m,
                                       const std::vector<HoleRequest>& req) {
  PredictionData d(m);
  std::vector<HolePrediction> out;
  std::optional<Vec6> prev;
  for (const HoleRequest& h : req) {
    out.push_back(predictHole(m, d, h, prev ? &*prev : nullptr));
    if (out.back().status == HoleStatus::kOk) prev = out.back().joints;
  }
  return out;
}

void expectIdentical(const std::vector<HolePrediction>& a, const std::vector<HolePrediction>& b,
                     const std::vector<HoleRequest>& req) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE(req[i].id);
    EXPECT_EQ(api::holeJson(a[i], req[i]).dump(), api::holeJson(b[i], req[i]).dump());
    EXPECT_TRUE(test::sameBits(a[i].joints.data(), b[i].joints.data(), 6));
    EXPECT_TRUE(test::sameBits(a[i].d_work.data(), b[i].d_work.data(), 3));
    EXPECT_TRUE(test::sameBits(&a[i].U_work_exact, &b[i].U_work_exact));
    EXPECT_EQ(a[i].status, b[i].status);
    EXPECT_EQ(a[i].reason, b[i].reason);
  }
}

TEST(PredictThreads, TwoThreadsAreByteIdenticalToOne) {
  api::PredictionContext c = load();
  // 612 holes: the housing three times, the last copy shifted out of reach in part (unreachable
  // holes break the continuity chain)
  std::vector<HoleRequest> req;
  for (int k = 0; k < 3; ++k) {
    for (HoleRequest h : c.job.requests) {
      h.id += "_" + std::to_string(k);
      if (k == 2 && req.size() % 7 == 0) h.T_W_tcp.translation().x() += 3.0;
      req.push_back(h);
    }
  }
  const std::vector<HolePrediction> ref = sequential(c.model, req);
  int bad = 0;
  for (const auto& p : ref) bad += p.status != HoleStatus::kOk ? 1 : 0;
  EXPECT_GT(bad, 10);
  for (const int threads : {1, 2, 3}) {
    SCOPED_TRACE(threads);
    PredictOptions o;
    o.threads = threads;
    expectIdentical(predictHoles(c.model, req, o), ref, req);
  }
}

TEST(PredictThreads, MonteCarloBudgetIsThreadIndependent) {
  api::PredictionContext c = load();
  c.model.uncertainty.method = UncertaintyInputs::Method::kMonteCarlo;
  c.model.uncertainty.samples = 40;
  std::vector<HoleRequest> req(c.job.requests.begin(), c.job.requests.begin() + 60);
  const std::vector<HolePrediction> ref = sequential(c.model, req);
  PredictOptions o;
  o.threads = 2;
  expectIdentical(predictHoles(c.model, req, o), ref, req);
}

TEST(PredictThreads, BlocksWithTheContinuitySeedEqualOneCall) {
  api::PredictionContext c = load();
  const std::vector<HoleRequest>& req = c.job.requests;
  const std::vector<HolePrediction> ref = sequential(c.model, req);
  std::vector<HolePrediction> blocks;
  PredictOptions o;
  o.threads = 2;
  for (size_t b = 0; b < req.size(); b += 50) {
    const std::vector<HoleRequest> part(
        req.begin() + static_cast<long>(b),
        req.begin() + static_cast<long>(std::min(req.size(), b + 50)));
    const std::vector<HolePrediction> got = predictHoles(c.model, part, o);
    for (const HolePrediction& p : got) {
      if (p.status == HoleStatus::kOk) o.seed = p.joints;
    }
    blocks.insert(blocks.end(), got.begin(), got.end());
  }
  expectIdentical(blocks, ref, req);
}

/// The prediction JSON predictJobStreaming writes for `csv` with `threads` workers (blocks of holes
/// written on a task of their own while the next block is predicted when threads > 1): hole by
/// hole, or (`blocks`) a block at a time formatted on the workers, as `roprec predict` does.
std::string streamedJson(const std::string& csv, int threads, bool blocks,
                         std::vector<size_t>* sizes = nullptr) {
  api::JobOptions o;
  o.threads = threads;
  std::string out;
  std::optional<api::PredictionJsonStream> js;
  auto header = [&](const api::PredictionContext& c) {
    js.emplace(c, [&](std::string_view b) { out += b; });
  };
  const std::string cell = test::sourceDir() + "/samples/cells/housing-kr120.xml";
  size_t next = 0;  // the blocks come in order, each once
  const api::PredictionResult r =
      blocks ? api::predictJobStreaming(
                   cell, csv, o,
                   [&](size_t first, std::span<const HolePrediction> h,
                       std::span<const HoleRequest> q, int t) {
                     EXPECT_EQ(first, next);
                     EXPECT_EQ(t, threads);
                     next += h.size();
                     if (sizes) sizes->push_back(h.size());
                     js->holes(h, q, t);
                   },
                   header)
             : api::predictJobStreaming(
                   cell, csv, o,
                   [&](size_t, const HolePrediction& h, const HoleRequest& q) { js->hole(h, q); },
                   header);
  js->finish(r.summary);
  if (blocks) {
    EXPECT_EQ(next, static_cast<size_t>(r.summary.holes));
  }
  return out;
}

TEST(PredictThreads, StreamedJsonOfSeveralBlocksIsTheSameBytes) {
  // the housing's hole list 25 times (5,100 holes: six blocks of the streaming predict, 2,048
  // holes, then the last 3,052 in halves down to 256, so the last block's formatting, which
  // nothing overlaps, is short)
  const std::string src = test::readFile(test::sourceDir() + "/samples/emotor-housing/holes.csv");
  const size_t header_end = src.find("\nid,") + 1;
  const size_t rows = src.find('\n', header_end) + 1;
  std::string csv = src.substr(0, rows);
  for (int k = 0; k < 25; ++k) {
    // every row's id prefixed (ids stay unique)
    for (size_t at = rows; at < src.size();) {
      const size_t end = std::min(src.size(), src.find('\n', at) + 1);
      csv += "K" + std::to_string(k) + "_" + src.substr(at, end - at);
      at = end;
    }
  }
  const std::string path = test::tempDir("predict_threads") + "/holes.csv";
  test::writeFile(path, csv);
  const std::string ref = streamedJson(path, 1, false);
  ASSERT_NE(ref.find("\"K24_L048\""), std::string::npos);
  for (const int threads : {2, 3})
    EXPECT_TRUE(streamedJson(path, threads, false) == ref) << threads;
  for (const int threads : {1, 2, 3}) {
    std::vector<size_t> sizes;
    EXPECT_TRUE(streamedJson(path, threads, true, &sizes) == ref)
        << threads << " threads, by blocks";
    EXPECT_EQ(sizes, (std::vector<size_t>{2048, 1526, 763, 382, 256, 125}));
  }
}

}  // namespace
}  // namespace roprec
