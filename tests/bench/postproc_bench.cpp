// Read + write throughput of the robot-program readers/writers on generated 100,000-target
// programs (goal: >= 100 MB/s). Bytes counted = input bytes (src + dat for KRL); the rate
// is per CPU second (Google Benchmark's default), so a loaded machine inflates the wall time only.
//   build-pp/bin/roprec_bench --benchmark_filter=ReadWrite
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <random>
#include <string>

#include "postproc/program.hpp"

namespace {

using roprec::postproc::Dialect;

constexpr int kTargets = 100000;

struct Generated {
  std::string main;
  std::optional<std::string> dat;
};

Generated generate(Dialect d) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1500, 1500);
  std::uniform_real_distribution<double> a(-180, 180);
  Generated g;
  char buf[512];
  switch (d) {
    case Dialect::kKrl: {
      g.main = "&ACCESS RVP\r\n&REL 1\r\nDEF big( )\r\nBAS(#INITMOV,0)\r\n";
      std::string dat = "&ACCESS RVP\r\nDEFDAT big\r\n";
      for (int i = 1; i <= kTargets; ++i) {
        std::snprintf(buf, sizeof buf,
                      "$VEL.CP=0.2\r\nFDAT_ACT=FP%d\r\nBAS(#CP_PARAMS,0.2)\r\nLIN XP%d C_DIS\r\n",
                      i, i);
        g.main += buf;
        std::snprintf(buf, sizeof buf,
                      "DECL E6POS XP%d={X %.5f,Y %.5f,Z %.5f,A %.6f,B %.6f,C %.6f,S 'B010',T 35,E1 "
                      "0.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0}\r\n"
                      "DECL FDAT FP%d={TOOL_NO 1,BASE_NO 1,IPO_FRAME #BASE,POINT2[] \" \",TQ_STATE "
                      "FALSE}\r\n",
                      i, u(rng), u(rng), u(rng), a(rng), a(rng) / 2, a(rng), i);
        dat += buf;
      }
      g.main += "END\r\n";
      g.dat = dat + "ENDDAT\r\n";
      break;
    }
    case Dialect::kRapid:
      g.main = "MODULE big\n  PROC main()\n";
      for (int i = 0; i < kTargets; ++i) {
        std::snprintf(buf, sizeof buf,
                      "    MoveL "
                      "[[%.3f,%.3f,%.3f],[%.8f,%.8f,%.8f,%.8f],[0,0,-2,0],[9E+09,9E+09,9E+09,9E+09,"
                      "9E+09,9E+09]],v100,z1,tool0\\WObj:=wobj0;\n",
                      u(rng), u(rng), u(rng), 0.5, 0.5, 0.5, 0.5);
        g.main += buf;
      }
      g.main += "  ENDPROC\nENDMODULE\n";
      break;
    case Dialect::kTp: {
      g.main = "/PROG  BIG\n/ATTR\nOWNER\t\t= MNEDITOR;\n/MN\n";
      std::string pos = "/POS\n";
      for (int i = 1; i <= kTargets; ++i) {
        std::snprintf(buf, sizeof buf, "%4d:L P[%d] 250mm/sec CNT100 ;\n", i, i);
        g.main += buf;
        std::snprintf(buf, sizeof buf,
                      "P[%d]{\n   GP1:\n\tUF : 1, UT : 1,\t\tCONFIG : 'N U T, 0, 0, 0',\n\tX = "
                      "%9.3f  mm,\tY = %9.3f  mm,\tZ = %9.3f  mm,\n"
                      "\tW = %9.3f deg,\tP = %9.3f deg,\tR = %9.3f deg\n};\n",
                      i, u(rng), u(rng), u(rng), a(rng), a(rng) / 2, a(rng));
        pos += buf;
      }
      g.main += pos + "/END\n";
      break;
    }
    case Dialect::kCsv:
    case Dialect::kHoleCsv:
      g.main = "id,x,y,z,a,b,c,frame,tool,conf\n";
      for (int i = 0; i < kTargets; ++i) {
        std::snprintf(buf, sizeof buf, "T%d,%.4f,%.4f,%.4f,%.5f,%.5f,%.5f,base,spindle,S 2 T 35\n",
                      i, u(rng), u(rng), u(rng), a(rng), a(rng) / 2, a(rng));
        g.main += buf;
      }
      break;
    case Dialect::kJson:
      g.main = "{\n  \"targets\": [\n";
      for (int i = 0; i < kTargets; ++i) {
        std::snprintf(buf, sizeof buf,
                      "    {\"id\": \"T%d\", \"motion\": \"L\", \"position_mm\": [%.6f, %.6f, "
                      "%.6f], \"quaternion_wxyz\": [0.5, 0.5, 0.5, 0.5]}%s\n",
                      i, u(rng), u(rng), u(rng), i + 1 < kTargets ? "," : "");
        g.main += buf;
      }
      g.main += "  ]\n}\n";
      break;
  }
  return g;
}

const Generated& cached(Dialect d) {
  static std::map<Dialect, Generated> cache;
  auto it = cache.find(d);
  if (it == cache.end()) it = cache.emplace(d, generate(d)).first;
  return it->second;
}

void BM_ReadWrite(benchmark::State& state) {
  const auto d = static_cast<Dialect>(state.range(0));
  const Generated& g = cached(d);
  const std::size_t bytes = g.main.size() + (g.dat ? g.dat->size() : 0);
  for (auto _ : state) {
    const roprec::postproc::Program p =
        roprec::postproc::parseProgram(d, "big", g.main, g.dat, "big.dat");
    const std::vector<std::string> out = roprec::postproc::renderFiles(p);
    if (out[0].size() != g.main.size() ||
        p.targets().size() != static_cast<std::size_t>(kTargets)) {
      state.SkipWithError("round trip mismatch");
    }
    benchmark::DoNotOptimize(out);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(bytes));
  state.SetLabel(roprec::postproc::dialectName(d) + " " + std::to_string(bytes / 1000000) + " MB");
}

BENCHMARK(BM_ReadWrite)
    ->Arg(static_cast<int>(Dialect::kKrl))
    ->Arg(static_cast<int>(Dialect::kRapid))
    ->Arg(static_cast<int>(Dialect::kTp))
    ->Arg(static_cast<int>(Dialect::kCsv))
    ->Arg(static_cast<int>(Dialect::kJson))
    ->Unit(benchmark::kMillisecond);

}  // namespace
