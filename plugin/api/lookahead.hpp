#pragma once
/// \file lookahead.hpp
/// Predicting a program's holes while the program is still being read (issue 15).
///
/// `roprec predict` on a KRL program spends about a third of its time reading the program and
/// recognising its drill cycles, on one thread. With more than one thread, a HoleLookahead uses
/// that time: postproc::readProgram calls its hook every kReadProgressLines lines (on the
/// reading thread), the hook recognises the cycles complete so far (postproc::HoleRecognizer)
/// and sets up their requests (setUpRecognizedHole), and a worker thread predicts them in order,
/// each seeded with the previous admissible solution, as predictJobStreaming does, and (given a
/// HoleFormat) formats each one as the job's output will (the prediction JSON's item: as much
/// work again as the prediction, done while the reading thread is the one the job waits for).
///
/// The job itself is then loaded, checked and set up exactly as without it (the same errors,
/// notes, frames and requests); it finishes the hook's recognizer instead of recognising the
/// whole program again (the same holes: HoleRecognizer only takes a cycle once the motion after
/// it is read, and a KRL reader never changes a motion once the next one exists). What was
/// predicted ahead is only a guess of the job's first
/// predictions: take(k, request) hands hole k's prediction over only when the job's request k
/// equals, bit for bit, the one it was predicted from, and every hole before it was handed over
/// the same way. A prediction depends only on the model, the request and the seed (the previous
/// admissible solution), and its text only on the prediction, the request, its index and the
/// job's robot card, so the bytes are those of a job predicted without a lookahead. A hole
/// set up differently once the whole program is known (a base frame the job resolves after the
/// read, say) ends the lookahead there; the rest is predicted as usual.
///
/// Memory: at most `cap` requests, predictions and texts (~4 kB a hole) and kRecognizeAhead
/// recognised cycles (~250 B each) are held while the program is read, on top of the read's own
/// peak; loadPredictionContext starts no lookahead for programs over kLookaheadProgramBytes.

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "compensator/precision/cell.hpp"
#include "compensator/precision/prediction.hpp"
#include "plugin/api/hole_input.hpp"
#include "plugin/api/prediction_setup.hpp"
#include "postproc/drill.hpp"
#include "postproc/program.hpp"

namespace roprec::api {

/// Two requests are the same bit for bit: every field, doubles by their bits (so that a
/// prediction from one is the prediction from the other).
bool sameRequest(const HoleRequest& a, const HoleRequest& b);

class HoleLookahead {
 public:
  /// Cycles the hook recognises at most (~250 B each; the job recognises the rest after the
  /// read, when the program's bytes are released).
  static constexpr std::size_t kRecognizeAhead = 16384;
  /// `model`: the model the job predicts with (a copy: the job may go on changing its own);
  /// `cell`, `robot`: the job's, referenced by the hook only (while the program is read);
  /// `format` (may be empty): what the worker makes of each hole it predicts. Starts the worker.
  HoleLookahead(PredictionModel model, const CellSpec& cell, const Robot& robot, std::size_t cap,
                HoleFormat format = {});
  ~HoleLookahead();  ///< stops and joins the worker
  HoleLookahead(const HoleLookahead&) = delete;
  HoleLookahead& operator=(const HoleLookahead&) = delete;
  HoleLookahead(HoleLookahead&&) = delete;
  HoleLookahead& operator=(HoleLookahead&&) = delete;

  /// The hook for postproc::readProgram. Never throws: a cycle it cannot set up ends the
  /// lookahead (the job's own setup reports it).
  [[nodiscard]] postproc::ReadProgress hook();
  /// The recognizer the hook advanced (it recognised every complete cycle read so far), for the
  /// job to finish (HoleRecognizer::advance(p, true)) instead of recognising the whole program
  /// again; null when the hook failed.
  postproc::HoleRecognizer* recognizer();
  /// Stops the worker and joins it: after the hole it is predicting, or (`finish_handed`, for
  /// tests) after every hole handed to it.
  void stop(bool finish_handed = false);
  /// After stop(), for k = 0, 1, … in order: moves hole k's prediction into `out` (and, with a
  /// HoleFormat, its text into `text`) when it was predicted from a request equal to
  /// `job_request` (sameRequest) and every hole before it was taken; false from the first hole
  /// that was not (and for every hole after it).
  bool take(std::size_t k, const HoleRequest& job_request, HolePrediction& out, std::string& text);
  /// Whether the holes taken come with their text (a HoleFormat was given).
  [[nodiscard]] bool formats() const { return static_cast<bool>(format_); }

 private:
  void onRead(const postproc::Program& p);
  void work();

  const PredictionModel model_;
  const CellSpec& cell_;
  const Robot& robot_;
  const std::size_t cap_;
  const HoleFormat format_;
  // reading thread
  postproc::HoleRecognizer recognizer_;  // the cycles recognised so far
  std::size_t handed_{0};
  bool failed_{false};
  // shared. The requests and predictions are reserved for `cap` at the start and never
  // reallocated (no large block freed while the program is read, which would make the
  // allocator keep the program's growing tables in memory it cannot give back): the reading
  // thread appends set-up requests under m_, the worker predicts those below the count it read
  // under m_ (complete, never written again).
  std::mutex m_;
  std::condition_variable cv_;
  std::vector<HoleRequest> req_;
  bool stopping_{false};
  bool finish_handed_{false};
  std::atomic<bool> halt_{false};  // stop after the current hole
  // worker (read by the job after stop())
  std::vector<HolePrediction> pred_;
  std::vector<std::string> text_;  // with format_: pred_[k]'s text
  std::size_t next_take_{0};
  bool taking_{true};
  std::thread worker_;
};

}  // namespace roprec::api
