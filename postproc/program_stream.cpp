#include "postproc/program_stream.hpp"

#include <algorithm>
#include <filesystem>
#include <utility>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/input_file.hpp"
#include "postproc/dialects.hpp"
#include "postproc/value_ranges.hpp"

namespace roprec::postproc {

namespace fs = std::filesystem;

ProgramStream::ProgramStream(const std::string& path, std::size_t window_bytes, bool read_ahead,
                             bool rapid)
    : path_(path), window_bytes_(std::max<std::size_t>(window_bytes, 1)), read_ahead_(read_ahead) {
  // a file that cannot be read in windows (missing, not a regular file, above the size limit)
  // gets readInputFile's error
  const auto refuse = [&](const std::string& p) {
    (void)readInputFile(p, InputKind::kProgram);
    throw InputError(p, 0, "cannot open file");  // not reached: readInputFile threw
  };
  std::string head;
  {
    platform::File f;
    if (f.openRead(path) != 0) refuse(path);
    const platform::Status st = f.status();
    if (st.kind != platform::Kind::kRegular || st.size > inputSizeLimit(InputKind::kProgram))
      refuse(path);
    head.resize(4096);
    int e = 0;
    const long long n = f.read(head.data(), head.size(), &e);
    if (n < 0) refuse(path);
    head.resize(static_cast<std::size_t>(n));
  }
  const Dialect dialect = detectDialect(path, head);
  if ((dialect == Dialect::kRapid || dialect == Dialect::kTp) && rapid) {
    p_.dialect = dialect;
    openWindows(path);
    SourceFile s;
    s.path = path;
    p_.files.push_back(std::move(s));
    noteInputFile(path);
    if (!readWindow()) {  // an empty module: read whole, as readProgram does
      file_.close();
      whole_read_ = true;
      p_ = Program{};
      return;
    }
    checkInputText(p_.files[0].bytes, path);
    read_ahead_ = false;
    if (dialect == Dialect::kTp) {
      tp_ = std::make_unique<TpStream>(p_);
    } else {
      rapid_ = std::make_unique<RapidStream>(p_);
    }
    pending_ = true;
    return;
  }
  if (dialect != Dialect::kKrl) {
    whole_read_ = true;
    return;
  }
  const auto [src, dat] = krlFiles(path);
  p_.dialect = Dialect::kKrl;
  p_.dat_path = dat.empty() ? fs::path(src).replace_extension(".dat").string() : dat;
  openWindows(src);
  SourceFile s;
  s.path = src;
  p_.files.push_back(std::move(s));
  if (!dat.empty()) {
    SourceFile d;
    d.path = dat;
    d.bytes = readInputFile(dat, InputKind::kProgram);
    d.indexLines();
    p_.files.push_back(std::move(d));
  }
  noteInputFile(src);
  if (!readWindow()) {  // an empty .src: read whole, as readProgram does
    file_.close();
    whole_read_ = true;
    p_ = Program{};
    return;
  }
  checkInputText(p_.files[0].bytes, src);
  krl_ = std::make_unique<KrlStream>(p_);  // reads the .dat
  pinned_ = p_.target_list.size();
  pending_ = true;
}

void ProgramStream::openWindows(const std::string& path) {
  const auto refuse = [&] {
    (void)readInputFile(path, InputKind::kProgram);
    throw InputError(path, 0, "cannot open file");  // not reached: readInputFile threw
  };
  if (file_.openRead(path) != 0) refuse();
  const platform::Status st = file_.status();
  if (st.kind != platform::Kind::kRegular || st.size > inputSizeLimit(InputKind::kProgram))
    refuse();
  src_ = path;
}

ProgramStream::~ProgramStream() {
  if (ahead_.valid()) ahead_.wait();  // its errors are no one's any more
}

SourceFile ProgramStream::fromSpare(Spare& s) {
  SourceFile w;
  w.bytes = std::move(s.bytes);
  w.line_starts = std::move(s.line_starts);
  w.line_ends = std::move(s.line_ends);
  w.tokens = std::move(s.tokens);
  w.tokens.clear();
  return w;
}

bool ProgramStream::readWindow() {
  SourceFile w = fromSpare(spare_);
  readWindowBytes(w.bytes);
  if (w.bytes.empty()) return false;
  w.indexLines();
  installWindow(std::move(w));
  return true;
}

std::size_t ProgramStream::carry() const {
  if (rapid_) return rapid_->carry();
  if (tp_) return tp_->carry();
  return p_.files[0].bytes.size();
}

bool ProgramStream::readCarriedWindow() {
  SourceFile& f = p_.files[0];
  const std::size_t cut = carry();
  int base = f.line_base + static_cast<int>(f.line_starts.size());
  const std::size_t carried = cut < f.bytes.size() ? f.bytes.size() - cut : 0;
  if (carried > 0) {  // a construct the window ended inside: from its line again
    const auto it = std::upper_bound(f.line_starts.begin(), f.line_starts.end(),
                                     static_cast<std::uint32_t>(cut));
    base = f.line_base + static_cast<int>(it - f.line_starts.begin()) - 1;
    rest_.insert(0, f.bytes, cut, std::string::npos);
  }
  SourceFile w = fromSpare(spare_);
  readWindowBytes(w.bytes);
  if (w.bytes.empty()) return false;
  w.indexLines();
  installWindow(std::move(w), static_cast<std::size_t>(base - f.line_base));
  f.line_base = base;
  if (carried > 0) {
    window_start_ -= carried;
    moveCarriedTargets(base + 1, static_cast<std::uint32_t>(cut));
  }
  return true;
}

namespace {

/// A field of a token of the first file `shift` bytes earlier in its new window.
void shiftField(NumberField& f, std::uint32_t shift) {
  if (f.file == 0) f.offset -= shift;
}

template <std::size_t N>
void shiftFields(FieldBlock<N>& b, std::uint32_t shift) {
  if (!b.stored()) return;
  for (std::size_t i = 0; i < N; ++i) shiftField(b[i], shift);
}

}  // namespace

void ProgramStream::moveCarriedTargets(int line, std::uint32_t cut) {
  for (Target& t : p_.target_list) {
    if (t.file != 0 || t.line != line) continue;
    for (NumberField& f : t.pos) shiftField(f, cut);
    for (NumberField& f : t.rot) shiftField(f, cut);
    shiftFields(t.joints, cut);
    shiftFields(t.ext, cut);
    shiftFields(t.cf_fields, cut);
    shiftFields(t.config_fields, cut);
    if (t.aggregate_end >= cut) t.aggregate_end -= cut;
  }
}

std::uint64_t ProgramStream::settledEnd() const { return window_start_ + carry(); }

void ProgramStream::installWindow(SourceFile&& w, std::size_t lines_done) {
  SourceFile& f = p_.files[0];
  const bool first = f.line_starts.empty();
  ++window_count_;
  lines_done = std::min(lines_done, f.line_ends.size());
  for (std::size_t l = 0; l < lines_done; ++l)
    ++f.earlier_ends[static_cast<std::size_t>(f.line_ends[l])];
  const int lines = first ? 0 : f.line_base + static_cast<int>(f.line_starts.size());
  if (!first) window_start_ += f.bytes.size();
  // the window's memory in, the previous window's out to the spare
  std::swap(f.bytes, w.bytes);
  std::swap(f.line_starts, w.line_starts);
  std::swap(f.line_ends, w.line_ends);
  std::swap(f.tokens, w.tokens);
  f.bare_fractions = f.bare_fractions || w.bare_fractions;  // the flags of the file so far
  f.zero_fractions = f.zero_fractions || w.zero_fractions;
  f.bom = first && w.bom;
  f.line_base = lines;
  spare_.bytes = std::move(w.bytes);
  spare_.line_starts = std::move(w.line_starts);
  spare_.line_ends = std::move(w.line_ends);
  spare_.tokens = std::move(w.tokens);
}

void ProgramStream::startAhead() {
  Ahead a;  // on the spare's memory, taken here (the reader refills the spare meanwhile)
  a.file = fromSpare(spare_);
  a.read = std::move(spare_.read);
  ahead_ = std::async(std::launch::async, [this, a = std::move(a)]() mutable {
    SourceFile& w = a.file;
    readWindowBytes(w.bytes);
    if (w.bytes.empty()) return std::move(a);
    w.indexLines();
    w.bom = false;  // not the file's first bytes
    KrlStream::lexWindow(w, a.read);
    return std::move(a);
  });
}

void ProgramStream::readWindowBytes(std::string& buf) { readLines(file_, rest_, eof_, read_, buf); }

void ProgramStream::readLines(platform::File& file, std::string& rest, bool& eof, std::size_t& read,
                              std::string& buf) const {
  const std::string& path = src_;  // not p_ (the reader may change it meanwhile)
  buf.assign(rest);                // into buf's own memory (a spare window's)
  rest.clear();
  std::size_t cut = std::string::npos;
  while (!eof) {  // whole lines: up to the last line end, more when the window has none
    const std::size_t old = buf.size();
    buf.resize(old + window_bytes_);
    int e = 0;
    const long long n = file.read(buf.data() + old, window_bytes_, &e);
    if (n < 0) (void)readInputFile(path, InputKind::kProgram);  // its read error
    buf.resize(old + static_cast<std::size_t>(std::max(0LL, n)));
    if (n <= 0) eof = true;
    read += static_cast<std::size_t>(std::max(0LL, n));
    if (read > inputSizeLimit(InputKind::kProgram))  // a file grown past the limit as it is read
      (void)readInputFile(path, InputKind::kProgram);
    if (buf.find('\0', old) != std::string::npos)
      (void)readInputFile(path, InputKind::kProgram);  // the NUL byte at its line and column
    for (std::size_t k = buf.size(); k > old; --k) {   // the bytes read before have none
      if (buf[k - 1] == '\n') {
        cut = k - 1;
        break;
      }
    }
    if (cut != std::string::npos) break;
  }
  if (!buf.empty() && !eof && cut != std::string::npos) {
    rest.assign(buf, cut + 1, std::string::npos);
    buf.resize(cut + 1);
  }
}

bool ProgramStream::next() {
  if (finished_) return false;
  if (tp_) return nextTp();
  if (rapid_) {
    if (pending_) {
      pending_ = false;
    } else if (!readCarriedWindow()) {
      finished_ = true;
      rapid_->finish();
      rapid_ranges_.rethrow();
      std::string().swap(p_.files[0].bytes);
      return false;
    }
    rapid_->lines(eof_ && rest_.empty());
    checkRanges();
    return true;
  }
  if (whole_read_) {
    if (!p_.files.empty()) {
      finished_ = true;
      return false;
    }
    p_ = readProgram(path_, readInputFile(path_, InputKind::kProgram));
    return true;
  }
  bool more = true;
  bool lexed = false;
  std::shared_ptr<KrlAhead> read;  // what the read-ahead read of the window
  if (pending_) {                  // the constructor's window
    pending_ = false;
  } else if (read_ahead_) {
    more = ahead_.valid();  // none after the window that ended the file
    if (more) {
      Ahead w = ahead_.get();  // its read error, where readWindow() would throw it
      more = lexed = !w.file.bytes.empty();
      if (more) installWindow(std::move(w.file));
      read = std::move(w.read);
    }
  } else {
    more = readWindow();
  }
  if (!more) {
    finished_ = true;
    krl_->finish();
    if (range_error_) std::rethrow_exception(range_error_);
    std::string().swap(p_.files[0].bytes);
    return false;
  }
  if (read_ahead_ && !eof_) startAhead();  // the window after, while this one is read
  if (lexed) {
    krl_->lexedLines(read.get());
    spare_.read = std::move(read);  // refilled by the window after next
  } else {
    krl_->lines();
  }
  checkRanges();
  return true;
}

bool ProgramStream::nextTp() {
  if (pending_ || (!tp_done_ && !tp_->wantsMotions())) {  // the scan's next window
    if (std::exchange(pending_, false) || readCarriedWindow()) {
      tp_->lines(eof_ && rest_.empty());
    } else {
      tp_done_ = true;
      tp_->finish();
    }
    checkRanges();
    return true;
  }
  if (!tp_->motionsRead()) {  // the motions' next window
    if (!mn_file_.isOpen()) {
      if (mn_file_.openRead(src_) != 0) (void)readInputFile(src_, InputKind::kProgram);
    }
    SourceFile& f = tp_->motionFile();
    f.line_base += static_cast<int>(f.line_starts.size());
    readLines(mn_file_, mn_rest_, mn_eof_, mn_read_, f.bytes);
    f.indexLines();
    tp_->motionLines(f.bytes.empty() || (mn_eof_ && mn_rest_.empty()));
    checkRanges();
    return true;
  }
  finished_ = true;  // both read: the rest bound (positions not in /POS)
  tp_->end();
  checkRanges();
  rapid_ranges_.rethrow();
  std::string().swap(p_.files[0].bytes);
  return false;
}

void ProgramStream::checkRanges() {
  // RAPID and TP: the first error of each kind, thrown in the whole read's order
  if ((rapid_ || tp_) && !skip_ranges_) {
    checkValueRanges(p_, rapid_ranges_);
    return;
  }
  if (range_error_ || skip_ranges_) return;
  try {
    checkValueRanges(p_);
  } catch (const InputError&) {
    range_error_ = std::current_exception();
  }
}

std::size_t ProgramStream::settledMotions() const {
  if (tp_ && !finished_) return tp_->settled();
  if (!krl_ || finished_) return p_.motions.size();
  const int held = krl_->heldMotion();
  return held >= 0 ? std::min(p_.motions.size(), static_cast<std::size_t>(held))
                   : p_.motions.size();
}

Retired ProgramStream::retire(std::size_t m) {
  Program& p = p_;
  if ((!krl_ && !rapid_ && !tp_) || p.motions.empty()) return {};
  m = std::min(m, p.motions.size() - 1);
  if (krl_ || tp_) {
    m = std::min(m, settledMotions());  // not the motions the reader may still change
  } else {
    // RAPID: the targets declared by name before the first one that may go stay for good (the
    // reader finds them by name); those declared after wait until the ones before them went
    while (pinned_ < p.target_list.size() && !p.target_list[pinned_].name.empty()) ++pinned_;
  }
  if (m == 0) return {};
  // the unnamed targets after the pinned ones that no remaining motion uses (TP: from the first
  // one no motion not bound yet names; a home position named again at the end stays before them)
  std::size_t t0 = pinned_;
  if (tp_) {
    while (t0 < p.target_list.size() && tp_->needed(t0)) ++t0;
  }
  std::size_t t1 = p.target_list.size();
  auto lowest = [&](int t) {
    if (t >= 0 && static_cast<std::size_t>(t) >= t0) t1 = std::min(t1, static_cast<std::size_t>(t));
  };
  for (std::size_t k = m; k < p.motions.size(); ++k) {
    lowest(p.motions[k].target);
    lowest(p.motions[k].aux);
  }
  // TP: a position a motion not bound yet names stays; RAPID, KRL: a target declared by name
  for (std::size_t t = t0; t < t1; ++t) {
    if (tp_ ? tp_->needed(t) : !p.target_list[t].name.empty()) {
      t1 = t;
      break;
    }
  }
  t1 = std::max(t1, t0);
  // the targets whose uses change: those of every motion of the window that stay
  std::vector<int> touched;
  for (const Motion& mo : p.motions) {
    for (const int t : {mo.target, mo.aux}) {
      if (t < 0) continue;
      const auto u = static_cast<std::size_t>(t);
      if (u >= t0 && u < t1) continue;
      touched.push_back(static_cast<int>(u >= t1 ? u - (t1 - t0) : u));
    }
  }
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  dropFirstMotions(p, m);
  p.target_list.erase(p.target_list.begin() + static_cast<std::ptrdiff_t>(t0),
                      p.target_list.begin() + static_cast<std::ptrdiff_t>(t1));
  const auto shift = static_cast<int>(t1 - t0);
  for (Motion& mo : p.motions) {
    if (mo.target >= static_cast<int>(t1)) mo.target -= shift;
    if (mo.aux >= static_cast<int>(t1)) mo.aux -= shift;
  }
  for (const int t : touched) {
    Target& tg = p.target_list[static_cast<std::size_t>(t)];
    IndexList uses;
    for (const int u : tg.uses) {
      if (u >= static_cast<int>(m)) uses.push_back(u - static_cast<int>(m));
    }
    tg.uses = std::move(uses);
  }
  if (krl_) krl_->retired(m);
  if (rapid_ && t1 > t0) rapid_->retiredTargets(t0, t1);
  if (tp_) {
    if (t1 > t0) tp_->retiredTargets(t0, t1);
    tp_->retired(m);
  }
  return {m, t0, t1};
}

}  // namespace roprec::postproc
