#pragma once
/// \file parallel.hpp
/// Work over holes on a few worker threads: `parallelFor(n, threads, work)` runs
/// work(worker, i) for every i in [0, n) on min(threads, n) workers, the calling thread being
/// worker 0, in chunks of kParallelChunk indices taken from a shared counter. Each index runs
/// exactly once; `worker` ∈ [0, threads) selects the caller's per-thread scratch. The order in
/// which indices run is not fixed, so work(w, i) must write only to slot i (and to scratch w):
/// then the result does not depend on the thread count. The first exception of a worker (lowest
/// worker index) is rethrown after every worker joined.
///
/// `pipelinedFor(n, block, threads, work, then)` adds an ordered pass: work over block k of
/// `block` indices as above, then `then(b, e)` over that block [b, e), in block order, on a task
/// of its own while the workers run block k + 1 (inline with one thread). `then` carries what
/// goes from index to index (a seed, a dynamic program's last row); it runs on one thread at a
/// time, so it needs no lock, but work(·, i) of the next block runs meanwhile: the two must not
/// write the same data. Errors: the first exception of a block's workers or of a `then` is
/// rethrown once nothing runs any more.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <future>
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

template <class Work, class Then>
void pipelinedFor(std::size_t n, std::size_t block, int threads, const Work& work,
                  const Then& then) {
  std::future<void> pending;  // `then` of the block before
  for (std::size_t b = 0; b < n; b += block) {
    const std::size_t e = std::min(n, b + block);
    try {
      parallelFor(e - b, threads, [&](int w, std::size_t k) { work(w, b + k); });
    } catch (...) {
      if (pending.valid()) pending.wait();
      throw;
    }
    if (pending.valid()) pending.get();
    if (threads > 1) {
      pending = std::async(std::launch::async, [&then, b, e] { then(b, e); });
    } else {
      then(b, e);
    }
  }
  if (pending.valid()) pending.get();
}

}  // namespace roprec
