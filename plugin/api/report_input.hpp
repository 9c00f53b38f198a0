#pragma once
/// \file report_input.hpp
/// What the hole report (plugin/report/hole_report.hpp) derives from the job before it is drawn.

#include "plugin/report/hole_report.hpp"

namespace roprec::api {

struct PredictionContext;

class SharedFrame;

/// The report's part frame: the frame every hole's targets share (`frames`), named after it, else
/// the cell's <workobject>.
void setPartFrame(ReportInput& in, const PredictionContext& c, const SharedFrame& frames);

/// Fills what the report derives from the job: the part frame (the program frame every hole
/// shares, else the cell's <workobject>, named after it) and each predicted hole's δrobot split
/// (splitRobotDeviations with the context's model and tool). Call after `in.holes` has one entry
/// per context.job.requests entry, in that order. Throws std::invalid_argument otherwise. The
/// split runs on `threads` workers (the same bytes); `process_alone`: DeviationSplitter's.
void addPartFrameAndSplit(ReportInput& in, const PredictionContext& c, int threads = 1,
                          bool process_alone = true);

}  // namespace roprec::api
