// parallelFor and pipelinedFor (compensator/precision/parallel.hpp): every index runs once, the
// ordered pass sees each block after its work and in block order, one block at a time, and the
// first error is rethrown once nothing runs any more — for 1, 2 and 3 threads and block sizes
// that do and do not divide the count.
#include "compensator/precision/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <utility>
#include <vector>

namespace roprec {
namespace {

TEST(ParallelFor, EveryIndexRunsOnceOnAWorkerOfItsOwn) {
  for (const int threads : {1, 2, 3}) {
    for (const std::size_t n :
         {std::size_t{0}, std::size_t{1}, std::size_t{17}, std::size_t{1000}}) {
      SCOPED_TRACE(std::to_string(threads) + " threads, n = " + std::to_string(n));
      std::vector<std::atomic<int>> runs(n);
      std::atomic<int> bad_worker{0};
      parallelFor(n, threads, [&](int w, std::size_t i) {
        if (w < 0 || w >= threads) ++bad_worker;
        ++runs[i];
      });
      for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(runs[i].load(), 1) << i;
      EXPECT_EQ(bad_worker.load(), 0);
    }
  }
}

TEST(PipelinedFor, ThenSeesEachFinishedBlockInOrder) {
  for (const int threads : {1, 2, 3}) {
    for (const std::size_t block : {std::size_t{1}, std::size_t{7}, std::size_t{64}}) {
      const std::size_t n = 1000;
      SCOPED_TRACE(std::to_string(threads) + " threads, block " + std::to_string(block));
      std::vector<std::atomic<int>> done(n);
      std::vector<std::pair<std::size_t, std::size_t>> seen;
      std::atomic<int> inside{0};  // `then` calls running at this moment
      bool overlapped = false;
      bool unfinished = false;
      long carried = 0;  // a sequential pass: the running sum of the work's values
      pipelinedFor(
          n, block, threads, [&](int, std::size_t i) { done[i].store(static_cast<int>(i) + 1); },
          [&](std::size_t b, std::size_t e) {
            overlapped |= ++inside > 1;
            for (std::size_t i = b; i < e; ++i) {
              unfinished |= done[i].load() != static_cast<int>(i) + 1;
              carried += done[i].load();
            }
            seen.emplace_back(b, e);
            --inside;
          });
      EXPECT_FALSE(overlapped);
      EXPECT_FALSE(unfinished);
      EXPECT_EQ(carried, static_cast<long>(n * (n + 1) / 2));
      ASSERT_EQ(seen.size(), (n + block - 1) / block);
      for (std::size_t k = 0; k < seen.size(); ++k) {
        EXPECT_EQ(seen[k].first, k * block);
        EXPECT_EQ(seen[k].second, std::min(n, (k + 1) * block));
      }
    }
  }
}

TEST(PipelinedFor, AnErrorOfTheWorkOrOfThenIsRethrownAndStopsTheBlocksAfter) {
  for (const int threads : {1, 2, 3}) {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    std::size_t last_then = 0;
    EXPECT_THROW(pipelinedFor(
                     100, 10, threads,
                     [](int, std::size_t i) {
                       if (i == 35) throw std::runtime_error("work");
                     },
                     [&](std::size_t b, std::size_t) { last_then = b; }),
                 std::runtime_error);
    EXPECT_EQ(last_then, 20u);  // blocks 0..2 finished; block 3 failed
    last_then = 0;
    try {
      pipelinedFor(
          100, 10, threads, [](int, std::size_t) {},
          [&](std::size_t b, std::size_t) {
            last_then = b;
            if (b == 40) throw std::logic_error("then");
          });
      ADD_FAILURE() << "no error";
    } catch (const std::logic_error& e) {
      EXPECT_STREQ(e.what(), "then");
    }
    EXPECT_EQ(last_then, 40u);
  }
}

}  // namespace
}  // namespace roprec
