#pragma once
/// \file parallel.hpp
/// Work over holes on a few worker threads (issue 15): `parallelFor(n, threads, work)` runs
/// work(worker, i) for every i in [0, n) on min(threads, n) workers, the calling thread being
/// worker 0, in chunks of kParallelChunk indices taken from a shared counter. Each index runs
/// exactly once; `worker` ∈ [0, threads) selects the caller's per-thread scratch. The order in
/// which indices run is not fixed, so work(w, i) must write only to slot i (and to scratch w):
/// then the result does not depend on the thread count. The first exception of a worker (lowest
/// worker index) is rethrown after every worker joined.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace roprec {

constexpr std::size_t kParallelChunk = 16;

template <class Work>
void parallelFor(std::size_t n, int threads, const Work& work) {
  const std::size_t cap = static_cast<std::size_t>(std::max(1, threads));
  const int t = static_cast<int>(std::min(cap, n));
  if (t <= 1) {
    for (std::size_t i = 0; i < n; ++i) work(0, i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(t));
  auto run = [&](int w) {
    try {
      for (std::size_t b = next.fetch_add(kParallelChunk); b < n;
           b = next.fetch_add(kParallelChunk)) {
        for (std::size_t i = b; i < std::min(n, b + kParallelChunk); ++i) work(w, i);
      }
    } catch (...) {
      errors[static_cast<std::size_t>(w)] = std::current_exception();
      next.store(n);
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(static_cast<std::size_t>(t - 1));
  for (int w = 1; w < t; ++w) pool.emplace_back(run, w);
  run(0);
  for (std::thread& th : pool) th.join();
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace roprec
