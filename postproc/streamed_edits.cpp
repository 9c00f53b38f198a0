#include "postproc/streamed_edits.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>

#include "compensator/support/error.hpp"

namespace roprec::postproc {

StreamedEdits::StreamedEdits(ProgramStream& stream, ByteWriter write, std::string marker,
                             const SourceFile& style)
    : stream_(stream), write_(std::move(write)), marker_(std::move(marker)) {
  if (!stream_.windowed()) throw InternalError("StreamedEdits: not a windowed program");
  style_.bare_fractions = style.bare_fractions;
  style_.zero_fractions = style.zero_fractions;
  style_.significant9 = style.significant9;
  if (stream_.program().dialect == Dialect::kTp)
    tp_mark_.emplace(marker_, style.dominantLineEnd());  // the whole file's (a first reading's)
  out_.reserve(kOutBytes + 4096);
}

void StreamedEdits::installed() {
  if (stream_.windowCount() == installed_) return;  // no new window (a TP program's motions)
  installed_ = stream_.windowCount();
  Program& p = stream_.program();
  SourceFile& f = p.files[0];
  f.bare_fractions = style_.bare_fractions;
  f.zero_fractions = style_.zero_fractions;
  f.significant9 = style_.significant9;
  Window w;
  w.start = stream_.windowStart();  // a RAPID window may start inside the one before
  w.line_base = f.line_base;
  w.line_starts = f.line_starts;
  w.bytes = f.bytes;
  total_ = w.start + w.bytes.size();
  windows_.push_back(std::move(w));
  if (tp_mark_) {  // the marker's edits of every /MN line
    const Window& last = windows_.back();
    tp_mark_->window(f, last.start, queueMark());
    marked_ = tp_mark_->marked();
    return;
  }
  if (!marked_) {
    p.edits.clear();
    marked_ = markCompensated(p, marker_);
    for (auto& [key, e] : p.edits)
      put(false, 0, windows_.back().start + e.offset, e.length, std::move(e.text));
    p.edits.clear();
  }
}

TpMarkStream::Put StreamedEdits::queueMark() {
  return [this](std::uint64_t at, std::uint32_t length, std::string text) {
    put(false, 0, at, length, std::move(text));
  };
}

StreamedEdits::Window& StreamedEdits::windowOf(int line) {
  for (auto it = windows_.rbegin(); it != windows_.rend(); ++it) {
    if (line > it->line_base && line <= it->line_base + static_cast<int>(it->line_starts.size()))
      return *it;
  }
  throw InternalError("StreamedEdits: line " + std::to_string(line) + " is no longer held");
}

EditResult StreamedEdits::replaceTargetPose(int index, const Pose& T_frame_tcp,
                                            const std::optional<Configuration>& config) {
  Program& p = stream_.program();
  const Target& t = p.targets()[static_cast<std::size_t>(index)];
  Window* w = t.file == 0 ? &windowOf(t.line) : nullptr;
  // the target's offsets are its window's: edited in those bytes (the program's own may be a
  // later window's, or released at the end of the file)
  if (w != nullptr) std::swap(p.files[0].bytes, w->bytes);
  EditLog log;
  EditResult r;
  try {
    r = postproc::replaceTargetPose(p, index, T_frame_tcp, config, log);
  } catch (...) {
    if (w != nullptr) std::swap(p.files[0].bytes, w->bytes);
    throw;
  }
  if (w != nullptr) std::swap(p.files[0].bytes, w->bytes);
  for (EditLog::Op& op : log.ops) {
    if (op.edit.file == 0 && w == nullptr)
      throw InternalError("StreamedEdits: an edit of the first file for a target of another");
    const std::uint64_t base = op.edit.file == 0 ? w->start : 0;
    put(op.erase, op.edit.file, base + op.edit.offset, op.edit.length, std::move(op.edit.text));
  }
  return r;
}

void StreamedEdits::PendingEdits::put(std::uint64_t at, Pending&& p) {
  if (after(at)) {
    items_.emplace_back(at, std::move(p));
    return;
  }
  const auto it = lowerBound(at);
  if (it != items_.end() && it->first == at) {
    it->second = std::move(p);
  } else {
    items_.emplace(it, at, std::move(p));
  }
}

void StreamedEdits::PendingEdits::erase(std::uint64_t at) {
  const auto it = lowerBound(at);
  if (it != items_.end() && it->first == at) items_.erase(it);
}

std::deque<StreamedEdits::PendingEdits::Item>::iterator StreamedEdits::PendingEdits::lowerBound(
    std::uint64_t at) {
  return std::lower_bound(items_.begin(), items_.end(), at,
                          [](const Item& x, std::uint64_t a) { return x.first < a; });
}

void StreamedEdits::put(bool erase, int file, std::uint64_t at, std::uint32_t length,
                        std::string&& text) {
  if (file == 0 && at < written_)
    throw std::logic_error("overlapping edits in " + stream_.program().files[0].path);
  PendingEdits& edits = file == 0 ? edits_ : dat_edits_;
  if (erase) {
    if (!edits.after(at)) edits.erase(at);
  } else {
    edits.put(at, Pending{length, std::move(text)});
  }
}

void StreamedEdits::flush() {
  int line = std::numeric_limits<int>::max();
  for (const Target& t : stream_.program().target_list) {
    if (t.file == 0 && t.line >= 1) line = std::min(line, t.line);
  }
  flushBeforeLine(line);
}

void StreamedEdits::flushBeforeLine(int line) {
  if (!marked_) return;
  // never past the bytes the next window reads again (a RAPID statement carried over)
  std::uint64_t upto = std::min(total_, stream_.settledEnd());
  const Window* last = latestWindow();
  // a line not read yet (a robtarget declared further on) holds nothing read so far
  if (last != nullptr && line <= last->line_base + static_cast<int>(last->line_starts.size())) {
    const Window& w = windowOf(line);
    upto =
        std::min(upto, w.start + w.line_starts[static_cast<std::size_t>(line - 1 - w.line_base)]);
  }
  flushBefore(upto);
}

void StreamedEdits::emit(std::string_view b) {
  out_.append(b);
  if (out_.size() >= kOutBytes) {
    write_(out_);
    out_.clear();
  }
}

void StreamedEdits::emitBytes(std::uint64_t a, std::uint64_t b) {
  // the windows in file order; where two overlap (a RAPID carried line) the bytes are the same
  for (const Window& w : windows_) {
    const std::uint64_t e = w.start + w.bytes.size();
    if (e <= a || w.start >= b) continue;
    const std::uint64_t x = std::max(a, w.start);
    const std::uint64_t y = std::min(b, e);
    emit(std::string_view(w.bytes).substr(x - w.start, y - x));
    a = y;
  }
}

void StreamedEdits::flushBefore(std::uint64_t upto) {
  upto = std::min(upto, total_);
  if (upto <= written_) return;
  std::deque<PendingEdits::Item>& q = edits_.items();
  auto it = q.begin();
  for (; it != q.end() && it->first < upto; ++it) {
    if (it->first + it->second.length > upto) {
      upto = it->first;
      break;
    }
    emitBytes(written_, it->first);
    emit(it->second.text);
    written_ = it->first + it->second.length;
  }
  q.erase(q.begin(), it);
  if (upto > written_) {
    emitBytes(written_, upto);
    written_ = upto;
  }
  while (!windows_.empty() && windows_.front().start + windows_.front().bytes.size() <= written_)
    windows_.pop_front();
}

void StreamedEdits::finish() {
  if (tp_mark_) {
    tp_mark_->finish(queueMark());
  }
  flushBefore(total_);
  // an insertion at the very end of the file (offset == size) is not before it
  for (auto& [at, e] : edits_.items()) {
    if (at != written_ || e.length != 0)
      throw std::logic_error("overlapping edits in " + stream_.program().files[0].path);
    emit(e.text);
  }
  edits_.items().clear();
  if (!out_.empty()) write_(out_);
  out_.clear();
}

std::optional<std::string> StreamedEdits::dat() const {
  const Program& p = stream_.program();
  if (p.files.size() < 2) return std::nullopt;
  const std::string& b = p.files[1].bytes;
  std::string s;
  s.reserve(b.size() + 64);
  std::uint64_t pos = 0;
  for (const auto& [at, e] : dat_edits_.items()) {
    if (at < pos || at + e.length > b.size())
      throw std::logic_error("overlapping edits in " + p.files[1].path);
    s.append(b, pos, at - pos);
    s += e.text;
    pos = at + e.length;
  }
  s.append(b, pos, std::string::npos);
  return s;
}

}  // namespace roprec::postproc
