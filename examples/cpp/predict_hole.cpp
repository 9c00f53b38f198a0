// predict_hole — a C++ host of libroprec (plugin/api/job.hpp).
//
//   predict_hole CELL.xml PROGRAM [HOLE_ID]
//
// Loads the cell, predicts every hole of PROGRAM (a KRL/RAPID/FANUC program or a hole-list CSV)
// and prints one hole (HOLE_ID, else the first): its ISO 14253-1 verdict, the position error
// ⊥ the hole axis, the expanded uncertainty U_work and the deviation δwork (base frame), in µm.
// Exit code: 0 done; 1 the hole was not found or could not be predicted; 2 bad usage or input.
#include <cstdio>
#include <exception>
#include <string>

#include <roprec/plugin/api/job.hpp>

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: %s CELL.xml PROGRAM [HOLE_ID]\n", argv[0]);
    return 2;
  }
  try {
    const roprec::api::PredictionResult r = roprec::api::predictJob(argv[1], argv[2]);
    std::printf("roprec %s: %zu holes, %d not predicted\n", roprec::api::version(), r.holes.size(),
                r.failed());
    for (const roprec::HolePrediction& h : r.holes) {
      if (argc == 4 && h.id != argv[3]) continue;
      std::printf("hole %s: %s\n", h.id.c_str(), roprec::verdictName(h.verdict));
      if (h.status != roprec::HoleStatus::kOk) {
        std::printf("  not predicted: %s\n", h.reason.c_str());
        return 1;
      }
      std::printf("  position error  %8.1f um\n", h.position_error * 1e6);
      std::printf("  U_work (95 %%)   %8.1f um\n", h.U_work * 1e6);
      std::printf("  d_work (base)   %8.1f %8.1f %8.1f um\n", h.d_work.x() * 1e6,
                  h.d_work.y() * 1e6, h.d_work.z() * 1e6);
      return 0;
    }
    std::fprintf(stderr, "predict_hole: no hole %s\n", argc == 4 ? argv[3] : "in the program");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "predict_hole: error: %s\n", e.what());
    return 2;
  }
}
