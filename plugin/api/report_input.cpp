/// \file report_input.cpp
/// The part frame and the δrobot split of the hole report (see report_input.hpp).
#include "plugin/api/report_input.hpp"

#include <algorithm>
#include <stdexcept>

#include "plugin/api/deviation_split.hpp"
#include "plugin/api/prediction_setup.hpp"

namespace roprec::api {

void setPartFrame(ReportInput& in, const PredictionContext& c, const SharedFrame& frames) {
  // the part frame: the frame all holes' targets are given in, if they share one
  in.T_W_part = c.cell.T_base_wobj;
  in.part_frame = "cell workobject";
  if (const HoleSource* s0 = frames.shared()) {
    in.T_W_part = s0->T_W_frame;
    if (!s0->frame_ref.empty()) in.part_frame = s0->frame_ref;
  }
}

void addPartFrameAndSplit(ReportInput& in, const PredictionContext& c, int threads,
                          bool process_alone) {
  const JobHoles& job = c.job;
  if (in.holes.size() != job.requests.size())
    throw std::invalid_argument("addPartFrameAndSplit: one report hole per request expected");
  SharedFrame frames;
  for (const HoleSource& s : job.sources) frames.add(s);
  setPartFrame(in, c, frames);
  std::vector<const HolePrediction*> preds;
  preds.reserve(in.holes.size());
  for (const ReportHole& h : in.holes) preds.push_back(h.prediction);
  const auto splits =
      splitRobotDeviations(c.model, c.tool, job.requests, preds, threads, process_alone);
  for (size_t i = 0; i < in.holes.size(); ++i) in.holes[i].split = splits[i];
}

}  // namespace roprec::api
