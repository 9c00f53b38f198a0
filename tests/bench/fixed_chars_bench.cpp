// Fixed-point number text: toFixedChars against std::to_chars (its reference) in the same binary,
// on the magnitudes and places of the prediction JSON (mm with 6 places, µm with 3, unit vectors
// with 9).
//   build/bin/roprec_bench --benchmark_filter=Fixed
#include <benchmark/benchmark.h>

#include <array>
#include <charconv>
#include <random>
#include <vector>

#include "compensator/support/fixed_chars.hpp"

namespace {

struct Sample {
  double v;
  int decimals;
};

std::vector<Sample> samples() {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> mm(-2000, 2000);
  std::uniform_real_distribution<double> um(-400, 400);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::vector<Sample> s;
  for (int i = 0; i < 4096; ++i) {
    s.push_back({mm(rng), 6});
    s.push_back({um(rng), 3});
    s.push_back({unit(rng), 9});
  }
  return s;
}

template <class Format>
void run(benchmark::State& state, const Format& format) {
  const std::vector<Sample> s = samples();
  std::array<char, 64> buf{};
  std::size_t i = 0;
  for (auto _ : state) {
    const Sample& x = s[i++ % s.size()];
    const auto r = format(buf.data(), buf.data() + buf.size(), x.v, x.decimals);
    benchmark::DoNotOptimize(r.ptr);
  }
}

void BM_FixedTextToChars(benchmark::State& state) {
  run(state, [](char* f, char* l, double v, int d) {
    return std::to_chars(f, l, v, std::chars_format::fixed, d);
  });
}
BENCHMARK(BM_FixedTextToChars);

void BM_FixedTextRoprec(benchmark::State& state) { run(state, roprec::toFixedChars); }
BENCHMARK(BM_FixedTextRoprec);

}  // namespace
