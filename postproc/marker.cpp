/// The "compensated by roprec" marker (docs/programs.md §15): a comment line in the dialect's own
/// comment syntax that `roprec compensate` adds to every program it writes, and the check that
/// refuses to compensate a marked program again.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <string_view>

#include "compensator/support/str_cat.hpp"
#include "postproc/program.hpp"

namespace roprec::postproc {

namespace {

constexpr std::string_view kMarker = "roprec compensated";

std::string upperCopy(std::string_view s) {
  std::string u(s);
  for (char& c : u) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return u;
}

std::string_view lineText(const SourceFile& f, std::size_t line) {  // 0-based, without terminator
  const std::size_t a = f.line_starts[line];
  std::size_t b = line + 1 < f.line_starts.size() ? f.line_starts[line + 1] : f.bytes.size();
  while (b > a && (f.bytes[b - 1] == '\n' || f.bytes[b - 1] == '\r')) --b;
  return std::string_view(f.bytes).substr(a, b - a);
}

std::string_view trimLeft(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  return s;
}

/// Offset of the start of the line after the first line whose upper-cased, left-trimmed text
/// starts with one of `keys`; nullopt when there is none.
std::optional<std::uint32_t> afterLineStarting(const SourceFile& f,
                                               std::initializer_list<std::string_view> keys,
                                               std::size_t* found_line = nullptr) {
  for (std::size_t l = 0; l < f.line_starts.size(); ++l) {
    const std::string u = upperCopy(trimLeft(lineText(f, l)));
    for (const std::string_view k : keys) {
      if (u.rfind(k, 0) == 0 &&
          (u.size() == k.size() || !std::isalnum(static_cast<unsigned char>(u[k.size()])))) {
        if (found_line) *found_line = l;
        if (l + 1 < f.line_starts.size()) return f.line_starts[l + 1];
        return static_cast<std::uint32_t>(f.bytes.size());
      }
    }
  }
  return std::nullopt;
}

std::string terminatorOf(const SourceFile& f, std::size_t line) {
  const std::string_view t = lineText(f, line);
  const std::size_t a = f.line_starts[line] + t.size();
  const std::size_t b = line + 1 < f.line_starts.size() ? f.line_starts[line + 1] : f.bytes.size();
  std::string e = f.bytes.substr(a, b - a);
  return e.empty() ? f.dominantLineEnd() : e;
}

/// The edit of a numbered /MN line `t`: its first `length` bytes replaced by `repl`, its number
/// gone up by one, with the remark line before it when `first`; false for a line with no number
/// (a circular motion's continuation line).
bool renumberTpLine(std::string_view t, bool first, const std::string& remark,
                    const std::string& eol, std::uint32_t& length, std::string& repl) {
  std::size_t k = 0;
  while (k < t.size() && t[k] == ' ') ++k;
  std::size_t d = k;
  while (d < t.size() && std::isdigit(static_cast<unsigned char>(t[d]))) ++d;
  if (d == k || d >= t.size() || t[d] != ':') return false;
  const int n = std::stoi(std::string(t.substr(k, d - k)));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%*d", static_cast<int>(d), n + 1);
  repl = buf;
  if (first) {
    char one[32];
    std::snprintf(one, sizeof one, "%*d", static_cast<int>(d), 1);
    repl = strCat(one, ":  !", remark, " ;", eol, repl);
  }
  length = static_cast<std::uint32_t>(d);
  return true;
}

/// `LINE_COUNT = n` (line text `t`): the offset and length of n in the line and n + 1; false when
/// the line has no such number.
bool lineCountEdit(std::string_view t, std::size_t& offset, std::size_t& length,
                   std::string& repl) {
  const std::size_t eq = t.find('=');
  if (eq == std::string_view::npos) return false;
  std::size_t a = eq + 1;
  while (a < t.size() && (t[a] == ' ' || t[a] == '\t')) ++a;
  std::size_t b = a;
  while (b < t.size() && std::isdigit(static_cast<unsigned char>(t[b]))) ++b;
  if (b == a) return false;
  offset = a;
  length = b - a;
  repl = std::to_string(std::stoi(std::string(t.substr(a, b - a))) + 1);
  return true;
}

bool isLineCount(std::string_view t) { return upperCopy(trimLeft(t)).rfind("LINE_COUNT", 0) == 0; }

/// FANUC TP: a remark as the new line 1 of /MN, every /MN line renumbered, LINE_COUNT + 1.
bool markTp(Program& p, const std::string& text) {
  const int fi = 0;
  const SourceFile& f = p.files[0];
  std::size_t mn = 0;
  if (!afterLineStarting(f, {"/MN"}, &mn)) return false;
  const std::string eol = f.dominantLineEnd();
  bool first = true;
  for (std::size_t l = mn + 1; l < f.line_starts.size(); ++l) {
    const std::string_view t = lineText(f, l);
    if (!t.empty() && t.front() == '/') break;
    std::uint32_t length = 0;
    std::string repl;
    if (!renumberTpLine(t, first, text, eol, length, repl)) continue;  // a C continuation line
    queueEdit(p, fi, f.line_starts[l], length, repl);
    first = false;
  }
  if (first) {  // empty /MN: the remark is the only line
    const std::uint32_t at = mn + 1 < f.line_starts.size()
                                 ? f.line_starts[mn + 1]
                                 : static_cast<std::uint32_t>(f.bytes.size());
    queueEdit(p, fi, at, 0, "   1:  !" + text + " ;" + eol);
  }
  // LINE_COUNT = n;
  for (std::size_t l = 0; l < mn; ++l) {
    const std::string_view t = lineText(f, l);
    if (!isLineCount(t)) continue;
    std::size_t offset = 0;
    std::size_t length = 0;
    std::string repl;
    if (lineCountEdit(t, offset, length, repl)) {
      queueEdit(p, fi, static_cast<std::uint32_t>(f.line_starts[l] + offset),
                static_cast<std::uint32_t>(length), repl);
    }
    break;
  }
  return true;
}

/// Whether `t` (a line's text) is the `/MN` line markTp anchors at.
bool isMnLine(std::string_view t) {
  const std::string u = upperCopy(trimLeft(t));
  return u.rfind("/MN", 0) == 0 &&
         (u.size() == 3 || !std::isalnum(static_cast<unsigned char>(u[3])));
}

}  // namespace

TpMarkStream::TpMarkStream(const std::string& what, std::string eol)
    : text_(std::string(kMarker) + ": " + what), eol_(std::move(eol)) {}

void TpMarkStream::window(const SourceFile& f, std::uint64_t start, const Put& put) {
  for (std::size_t l = 0; l < f.line_starts.size() && phase_ != Phase::kDone; ++l) {
    const std::uint64_t at = start + f.line_starts[l];
    const std::uint64_t next =
        start + (l + 1 < f.line_starts.size() ? f.line_starts[l + 1] : f.bytes.size());
    if (at < seen_) continue;  // a line read again (a record carried over)
    line(lineText(f, l), at, next, put);
  }
  seen_ = std::max(seen_, start + f.bytes.size());
}

void TpMarkStream::line(std::string_view t, std::uint64_t at, std::uint64_t next, const Put& put) {
  if (phase_ == Phase::kHeader) {
    if (isMnLine(t)) {
      phase_ = Phase::kMn;
      after_mn_ = next;
      if (line_count_) put(line_count_->at, line_count_->length, std::move(line_count_->text));
      line_count_.reset();
    } else if (!line_count_seen_ && isLineCount(t)) {
      line_count_seen_ = true;
      std::size_t offset = 0;
      std::size_t length = 0;
      std::string repl;
      if (lineCountEdit(t, offset, length, repl))
        line_count_ = Edit{at + offset, static_cast<std::uint32_t>(length), std::move(repl)};
    }
    return;
  }
  if (!t.empty() && t.front() == '/') {
    endMn(put);
    return;
  }
  std::uint32_t length = 0;
  std::string repl;
  if (!renumberTpLine(t, first_, text_, eol_, length, repl)) return;
  put(at, length, std::move(repl));
  first_ = false;
}

void TpMarkStream::endMn(const Put& put) {
  if (first_) put(after_mn_, 0, "   1:  !" + text_ + " ;" + eol_);
  first_ = false;
  phase_ = Phase::kDone;
}

void TpMarkStream::finish(const Put& put) {
  if (phase_ == Phase::kMn) endMn(put);
}

std::optional<MarkerLocation> findCompensationMarker(const Program& p) {
  for (std::size_t fi = 0; fi < p.files.size(); ++fi) {
    const SourceFile& f = p.files[fi];
    const std::size_t at = f.bytes.find(kMarker);
    if (at == std::string::npos) continue;
    MarkerLocation m;
    m.file = static_cast<int>(fi);
    m.line = f.lineOf(at);
    std::size_t e = f.bytes.find_first_of("\r\n", at);
    if (e == std::string::npos) e = f.bytes.size();
    m.text = f.bytes.substr(at, e - at);
    return m;
  }
  return std::nullopt;
}

bool markCompensated(Program& p, const std::string& what) {
  if (p.files.empty()) return false;
  const std::string text = std::string(kMarker) + ": " + what;
  const SourceFile& f = p.files[0];
  std::size_t line = 0;
  switch (p.dialect) {
    case Dialect::kKrl: {
      const auto at = afterLineStarting(f, {"DEF", "GLOBAL DEF"}, &line);
      if (!at) return false;
      queueEdit(p, 0, *at, 0, ";" + text + terminatorOf(f, line));
      return true;
    }
    case Dialect::kRapid: {
      const auto at = afterLineStarting(f, {"MODULE"}, &line);
      if (!at) return false;
      queueEdit(p, 0, *at, 0, "! " + text + terminatorOf(f, line));
      return true;
    }
    case Dialect::kTp:
      return markTp(p, text);
    case Dialect::kCsv:
    case Dialect::kHoleCsv: {
      const std::uint32_t at = f.bom ? 3U : 0U;
      queueEdit(p, 0, at, 0, "# " + text + f.dominantLineEnd());
      return true;
    }
    case Dialect::kJson:
      return false;
  }
  return false;
}

}  // namespace roprec::postproc
