#include "plugin/api/lookahead.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>

namespace roprec::api {

namespace {

bool sameBits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

template <class M>
bool sameBits(const M& a, const M& b) {
  for (Eigen::Index k = 0; k < a.size(); ++k) {
    if (!sameBits(a.data()[k], b.data()[k])) return false;
  }
  return true;
}

bool sameConfig(const VendorConfig& a, const VendorConfig& b) {
  return a.vendor == b.vendor && a.kuka.status == b.kuka.status && a.kuka.turn == b.kuka.turn &&
         a.abb.cf1 == b.abb.cf1 && a.abb.cf4 == b.abb.cf4 && a.abb.cf6 == b.abb.cf6 &&
         a.abb.cfx == b.abb.cfx && a.fanuc.flip == b.fanuc.flip && a.fanuc.up == b.fanuc.up &&
         a.fanuc.top == b.fanuc.top && a.fanuc.turns == b.fanuc.turns && a.branch == b.branch;
}

template <class T, class Same>
bool sameOptional(const std::optional<T>& a, const std::optional<T>& b, const Same& same) {
  if (a.has_value() != b.has_value()) return false;
  return !a || same(*a, *b);
}

}  // namespace

bool sameRequest(const HoleRequest& a, const HoleRequest& b) {
  const auto cfg = [](const VendorConfig& x, const VendorConfig& y) { return sameConfig(x, y); };
  const auto vec = [](const auto& x, const auto& y) { return sameBits(x, y); };
  const auto axis = [](const std::pair<Vec3, Vec3>& x, const std::pair<Vec3, Vec3>& y) {
    return sameBits(x.first, y.first) && sameBits(x.second, y.second);
  };
  return a.id == b.id && sameBits(a.T_W_tcp.matrix(), b.T_W_tcp.matrix()) &&
         sameBits(a.tolerance, b.tolerance) && sameBits(a.diameter, b.diameter) &&
         sameBits(a.depth, b.depth) && sameOptional(a.config, b.config, cfg) &&
         sameOptional(a.written_config, b.written_config, cfg) && a.line == b.line &&
         sameOptional(a.surface_W, b.surface_W, vec) &&
         sameOptional(a.nominal_axis, b.nominal_axis, axis) &&
         sameOptional(a.ik_seed, b.ik_seed, vec) && a.evidence == b.evidence &&
         a.drill == b.drill && sameBits(a.feed, b.feed) && sameBits(a.spindle_rpm, b.spindle_rpm) &&
         a.tool == b.tool;
}

HoleLookahead::HoleLookahead(PredictionModel model, const CellSpec& cell, const Robot& robot,
                             std::size_t cap, HoleFormat format)
    : model_(std::move(model)), cell_(cell), robot_(robot), cap_(cap), format_(std::move(format)) {
  req_.reserve(cap_);
  pred_.reserve(cap_);
  if (format_) text_.reserve(cap_);
  worker_ = std::thread([this] { work(); });
}

HoleLookahead::~HoleLookahead() { stop(); }

postproc::ReadProgress HoleLookahead::hook() {
  return [this](const postproc::Program& p) { onRead(p); };
}

postproc::HoleRecognizer* HoleLookahead::recognizer() { return failed_ ? nullptr : &recognizer_; }

void HoleLookahead::onRead(const postproc::Program& p) {
  if (failed_) return;
  size_t handed = 0;
  try {
    // the cycles are recognised while the program is read as long as they are few (their
    // memory would add to the read's peak); the job recognises the rest once the program's
    // bytes are released
    if (recognizer_.holes().size() < kRecognizeAhead) recognizer_.advance(p, false);
    const std::vector<postproc::Hole>& rec = recognizer_.holes();
    for (size_t i = handed_; i < std::min(rec.size(), cap_); ++i) {
      HoleRequest r;
      HoleSource src;
      setUpRecognizedHole(rec, p, cell_, robot_, i, r, src);
      const std::lock_guard<std::mutex> lock(m_);
      req_.push_back(std::move(r));  // within the capacity reserved: no element moves
      handed = ++handed_;
    }
  } catch (...) {
    // what is wrong is the job's own to say; the lookahead ends here (and so does its
    // recognizer: the job recognises the program's holes itself)
    failed_ = true;
  }
  if (handed > 0) cv_.notify_one();
}

void HoleLookahead::work() {
  PredictionData d(model_);
  std::optional<Vec6> prev;
  std::string text;  // the format's scratch: each hole keeps a copy of its own size
  for (;;) {
    size_t handed = 0;
    const HoleRequest* req = nullptr;
    {
      std::unique_lock<std::mutex> lock(m_);
      cv_.wait(lock, [&] { return stopping_ || req_.size() > pred_.size(); });
      handed = req_.size();
      req = req_.data();  // the reserved array: it does not move while the reader appends
      if (handed == pred_.size() || (stopping_ && !finish_handed_)) return;
    }
    // requests below `handed` are complete and never written again (read through `req`: the
    // vector's size is the reader's to change meanwhile)
    while (pred_.size() < handed) {
      if (halt_.load(std::memory_order_relaxed)) return;
      const std::size_t k = pred_.size();
      HolePrediction h;
      try {
        predictHole(model_, d, req[k], prev ? &*prev : nullptr, h);
        if (format_) format_(k, h, req[k], text);
      } catch (...) {
        halt_ = true;  // the job's own prediction of this hole meets (and reports) the same
        return;
      }
      if (h.status == HoleStatus::kOk) prev = h.joints;
      if (format_) text_.emplace_back(text);
      pred_.push_back(std::move(h));
    }
  }
}

void HoleLookahead::stop(bool finish_handed) {
  if (!worker_.joinable()) return;
  {
    const std::lock_guard<std::mutex> lock(m_);
    stopping_ = true;
    finish_handed_ = finish_handed;
  }
  if (!finish_handed) halt_ = true;
  cv_.notify_one();
  worker_.join();
}

bool HoleLookahead::take(std::size_t k, const HoleRequest& job_request, HolePrediction& out,
                         std::string& text) {
  if (worker_.joinable() || !taking_ || k != next_take_ || k >= pred_.size() ||
      !sameRequest(req_[k], job_request)) {
    taking_ = false;
    return false;
  }
  out = std::move(pred_[k]);
  if (format_) text = std::move(text_[k]);
  ++next_take_;
  return true;
}

}  // namespace roprec::api
