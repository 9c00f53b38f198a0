/// \file report_input.cpp
/// The part frame and the δrobot split of the hole report (see report_input.hpp).
#include "plugin/api/report_input.hpp"

#include <algorithm>
#include <stdexcept>

#include "plugin/api/deviation_split.hpp"
#include "plugin/api/prediction_setup.hpp"

namespace roprec::api {

void addPartFrameAndSplit(ReportInput& in, const PredictionContext& c, int threads) {
  const JobHoles& job = c.job;
  if (in.holes.size() != job.requests.size())
    throw std::invalid_argument("addPartFrameAndSplit: one report hole per request expected");
  // the part frame: the frame all holes' targets are given in, if they share one
  in.T_W_part = c.cell.T_base_wobj;
  in.part_frame = "cell workobject";
  if (!job.sources.empty()) {
    const HoleSource& s0 = job.sources.front();
    const bool shared =
        std::all_of(job.sources.begin(), job.sources.end(), [&](const HoleSource& s) {
          return s.frame_ref == s0.frame_ref && s.T_W_frame.isApprox(s0.T_W_frame, 1e-12);
        });
    if (shared) {
      in.T_W_part = s0.T_W_frame;
      if (!s0.frame_ref.empty()) in.part_frame = s0.frame_ref;
    }
  }
  std::vector<const HolePrediction*> preds;
  preds.reserve(in.holes.size());
  for (const ReportHole& h : in.holes) preds.push_back(h.prediction);
  const auto splits = splitRobotDeviations(c.model, c.tool, job.requests, preds, threads);
  for (size_t i = 0; i < in.holes.size(); ++i) in.holes[i].split = splits[i];
}

}  // namespace roprec::api
