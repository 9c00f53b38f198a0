#include "postproc/program.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/c_format.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/input_file.hpp"
#include "postproc/dialects.hpp"
#include "postproc/lexer.hpp"
#include "postproc/value_ranges.hpp"

namespace roprec::postproc {

namespace fs = std::filesystem;

std::string dialectName(Dialect d) {
  switch (d) {
    case Dialect::kKrl:
      return "krl";
    case Dialect::kRapid:
      return "rapid";
    case Dialect::kTp:
      return "tp";
    case Dialect::kCsv:
      return "csv";
    case Dialect::kJson:
      return "json";
    case Dialect::kHoleCsv:
      return "holes";
  }
  return "unknown";
}

// ---------------------------------------------------------------- source files

namespace {

// Bytes indexLines() stops at: line terminators and '.' (fraction style).
constexpr std::array<bool, 256> kLineScanStops = [] {
  std::array<bool, 256> t{};
  t['\n'] = t['\r'] = t['.'] = true;
  return t;
}();

// Records the fraction style of the '.' at bytes[i] (followed by a digit) in f's flags.
void noteFraction(SourceFile& f, std::size_t i) {
  const std::string& b = f.bytes;
  const std::size_t n = b.size();
  if (i == 0 || (!isDigit(b[i - 1]) && !isIdentChar(b[i - 1]))) {
    f.bare_fractions = true;
  } else if (b[i - 1] == '0' && (i < 2 || (!isDigit(b[i - 2]) && !isIdentChar(b[i - 2])))) {
    // `0.044` is evidence of leading zeros; an exact `0.000` is not (FANUC prints zero so)
    for (std::size_t k = i + 1; k < n && isDigit(b[k]); ++k) {
      if (b[k] != '0') {
        f.zero_fractions = true;
        break;
      }
    }
  }
}

// Terminator of the line end at bytes[i] ('\n' or '\r'); j moves to its last byte.
LineEnd lineEndAt(const std::string& b, std::size_t& j) {
  if (b[j] != '\r') return LineEnd::kLf;
  const std::size_t n = b.size();
  if (j + 1 < n && b[j + 1] == '\n') {
    j += 1;
    return LineEnd::kCrLf;
  }
  if (j + 2 < n && b[j + 1] == '\r' && b[j + 2] == '\n') {
    j += 2;
    return LineEnd::kCrCrLf;
  }
  return LineEnd::kCr;
}

}  // namespace

void SourceFile::indexLines() {
  const std::size_t n = bytes.size();
  line_starts.clear();
  line_ends.clear();
  bom = n >= 3 && static_cast<unsigned char>(bytes[0]) == 0xEF &&
        static_cast<unsigned char>(bytes[1]) == 0xBB &&
        static_cast<unsigned char>(bytes[2]) == 0xBF;
  line_starts.push_back(0);
  const char* const data = bytes.data();
  for (std::size_t i = 0; i < n; ++i) {
    while (i < n && !kLineScanStops[static_cast<unsigned char>(data[i])]) ++i;
    if (i >= n) break;
    if (data[i] == '.') {
      if (i + 1 < n && isDigit(data[i + 1]) && !(bare_fractions && zero_fractions))
        noteFraction(*this, i);
      continue;
    }
    std::size_t j = i;
    line_ends.push_back(lineEndAt(bytes, j));
    i = j;
    if (i + 1 <= n) line_starts.push_back(static_cast<std::uint32_t>(i + 1));
  }
  if (line_starts.size() > line_ends.size()) {
    if (line_starts.back() == n && n > 0) {
      line_starts.pop_back();
    } else {
      line_ends.push_back(LineEnd::kNone);
    }
  }
}

int SourceFile::lineOf(std::size_t offset) const {
  const auto it =
      std::upper_bound(line_starts.begin(), line_starts.end(), static_cast<std::uint32_t>(offset));
  return line_base + static_cast<int>(it - line_starts.begin());
}

std::string SourceFile::dominantLineEnd() const {
  std::array<std::uint64_t, 5> count = earlier_ends;
  for (const LineEnd e : line_ends) ++count[static_cast<std::size_t>(e)];
  const std::size_t best =
      static_cast<std::size_t>(std::max_element(count.begin() + 1, count.end()) - count.begin());
  if (count[best] == 0) return "\n";
  switch (static_cast<LineEnd>(best)) {
    case LineEnd::kCrLf:
      return "\r\n";
    case LineEnd::kCr:
      return "\r";
    case LineEnd::kCrCrLf:
      return "\r\r\n";
    default:
      return "\n";
  }
}

// ---------------------------------------------------------------- texts

TextId TextTable::add(std::string_view s) {
  if (s.empty()) return TextId{};
  if (s.size() > kSharedMax) return append(s);
  std::uint32_t& recent = recent_[recentSlot(s)];
  if (recent != 0 && texts_[recent] == s) return TextId{recent};
  if (const auto it = index_.find(s); it != index_.end()) {
    recent = it->second;
    return TextId{recent};
  }
  recent = static_cast<std::uint32_t>(texts_.size());
  index_.emplace(std::string_view(texts_.emplace_back(s)), recent);
  return TextId{recent};
}

TextId TextTable::append(std::string_view s) {
  if (s.empty()) return TextId{};
  if (!free_.empty()) {
    const std::uint32_t id = free_.back();
    free_.pop_back();
    texts_[id].assign(s);
    return TextId{id};
  }
  texts_.emplace_back(s);
  return TextId{static_cast<std::uint32_t>(texts_.size() - 1)};
}

void TextTable::release(TextId id) {
  if (id.empty() || id.index >= texts_.size()) return;
  std::string& t = texts_[id.index];
  if (t.empty()) return;  // released already
  if (t.size() <= kSharedMax) {
    const auto it = index_.find(std::string_view(t));
    if (it != index_.end() && it->second == id.index) return;  // shared
  }
  std::string().swap(t);
  free_.push_back(id.index);
}

void TextTable::reindex() {
  index_.clear();
  for (std::size_t i = texts_.size(); i-- > 1;) {  // the first of equal texts wins
    const std::string& t = texts_[i];
    if (t.size() <= kSharedMax) index_[std::string_view(t)] = static_cast<std::uint32_t>(i);
  }
}

void Program::addMarker(std::string_view marker) {
  if (motions.empty()) return;
  Motion& m = motions.back();
  if (m.marker_count == 0) m.marker_begin = static_cast<std::uint32_t>(marker_texts.size());
  marker_texts.push_back(texts.add(marker));
  ++m.marker_count;
}

void dropFirstMotions(Program& p, std::size_t n) {
  n = std::min(n, p.motions.size());
  if (n == 0) return;
  std::size_t marker_cut = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const Motion& mo = p.motions[k];
    p.texts.release(mo.target_text);
    for (std::uint32_t j = 0; j < mo.marker_count; ++j)
      p.texts.release(p.marker_texts[mo.marker_begin + j]);
    if (mo.marker_count > 0) marker_cut = mo.marker_begin + mo.marker_count;
  }
  p.marker_texts.erase(p.marker_texts.begin(),
                       p.marker_texts.begin() + static_cast<std::ptrdiff_t>(marker_cut));
  p.motions.erase(p.motions.begin(), p.motions.begin() + static_cast<std::ptrdiff_t>(n));
  for (Motion& mo : p.motions)
    if (mo.marker_count > 0) mo.marker_begin -= static_cast<std::uint32_t>(marker_cut);
}

void failAt(const SourceFile& f, std::size_t offset, const std::string& msg) {
  throw InputError(f.path, f.lineOf(offset), msg);
}

int internFrame(Program& p, const Frame& f) {
  const std::size_t n = p.frames.size();
  for (std::size_t k = n; k > 0 && k + 4 > n; --k) {
    const Frame& g = p.frames[k - 1];
    if (g.ref == f.ref && g.resolved == f.resolved && g.pose.matrix() == f.pose.matrix()) {
      return static_cast<int>(k - 1);
    }
  }
  p.frames.push_back(f);
  return static_cast<int>(p.frames.size() - 1);
}

// ---------------------------------------------------------------- numbers

namespace {

// `digits[.digits]` with at most 15 significant digits and 22 decimals, exactly as
// std::from_chars rounds it: the mantissa m < 10^15 < 2^53 and 10^d (d <= 22) are exact doubles,
// so m / 10^d is one correctly rounded operation (Clinger's fast path). nullopt for any other form
// (exponent, more digits), which from_chars then reads.
std::optional<double> parseDecimalExact(std::string_view s) {
  static constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                      1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                      1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  std::uint64_t m = 0;
  int digits = 0;  // significant (after leading zeros)
  int decimals = -1;
  bool any = false;
  for (const char c : s) {
    if (c == '.' && decimals < 0) {
      decimals = 0;
      continue;
    }
    if (!isDigit(c)) return std::nullopt;
    any = true;
    if (decimals >= 0) ++decimals;
    if (m == 0 && c == '0') continue;
    if (++digits > 15) return std::nullopt;
    m = m * 10 + static_cast<std::uint64_t>(c - '0');
  }
  if (!any || decimals > 22) return std::nullopt;
  return static_cast<double>(m) / kPow10[std::max(decimals, 0)];
}

}  // namespace

std::optional<double> parseNumber(std::string_view s) {
  std::size_t k = 0;
  bool neg = false;
  if (k < s.size() && (s[k] == '-' || s[k] == '+')) {
    neg = s[k] == '-';
    ++k;
    while (k < s.size() && (s[k] == ' ' || s[k] == '\t')) ++k;
  }
  if (k >= s.size()) return std::nullopt;
  if (!isDigit(s[k]) && s[k] != '.') return std::nullopt;
  if (const auto fast = parseDecimalExact(s.substr(k))) return neg ? -*fast : *fast;
  double v = 0;
  const char* b = s.data() + k;
  const char* e = s.data() + s.size();
  const auto r = std::from_chars(b, e, v, std::chars_format::general);
  if (r.ec != std::errc() || r.ptr != e) return std::nullopt;
  if (!std::isfinite(v)) return std::nullopt;
  return neg ? -v : v;
}

NumberField tokenField(const SourceFile& sf, int file, std::uint32_t begin, std::uint32_t end,
                       double value) {
  if (end - begin > NumberField::kMaxLength) {
    failAt(sf, begin,
           "a number of " + std::to_string(end - begin) + " characters (at most " +
               std::to_string(NumberField::kMaxLength) + ")");
  }
  NumberField f;
  f.file = static_cast<std::int8_t>(file);
  f.offset = begin;
  f.length = static_cast<std::uint16_t>(end - begin);
  f.value = value;
  return f;
}

NumberField numberField(const Program& p, int file, std::uint32_t begin, std::uint32_t end) {
  const SourceFile& f = p.files[static_cast<std::size_t>(file)];
  const std::string_view t = std::string_view(f.bytes).substr(begin, end - begin);
  const auto v = parseNumber(t);
  if (!v) failAt(f, begin, "broken number '" + std::string(t) + "'");
  return tokenField(f, file, begin, end, *v);
}

namespace {

struct NumStyle {
  bool neg{false};
  bool plus{false};
  bool bare{false};  // `.5`
  bool has_point{false};
  int frac{0};
  int sig{0};
  bool exp{false};
  bool exp_lower{false};
};

NumStyle styleOf(std::string_view s) {
  NumStyle st;
  std::size_t k = 0;
  if (k < s.size() && (s[k] == '-' || s[k] == '+')) {
    st.neg = s[k] == '-';
    st.plus = s[k] == '+';
    ++k;
  }
  while (k < s.size() && (s[k] == ' ' || s[k] == '\t')) ++k;
  st.bare = k < s.size() && s[k] == '.';
  bool seen_nonzero = false;
  for (; k < s.size(); ++k) {
    const char c = s[k];
    if (isDigit(c)) {
      if (c != '0') seen_nonzero = true;
      if (seen_nonzero) ++st.sig;
      if (st.has_point) ++st.frac;
    } else if (c == '.') {
      st.has_point = true;
    } else if (c == 'e' || c == 'E') {
      st.exp = true;
      st.exp_lower = c == 'e';
      break;
    }
  }
  return st;
}

bool allZeroDigits(const std::string& t) {
  for (const char c : t) {
    if (c == 'e' || c == 'E') break;
    if (isDigit(c) && c != '0') return false;
  }
  return true;
}

}  // namespace

namespace {

/// The places of the fixed notation formatLike writes a number of style `st` with, whatever its
/// value; -1 when they depend on the value (exponent notation, nine significant digits).
int fixedPlaces(const NumStyle& st, const NumberHints& h) {
  if (st.exp || h.significant9) return -1;
  return std::clamp(std::max(st.has_point ? st.frac : 0, h.min_decimals), 0, 20);
}

/// formatLike of a number written in the style `st`.
std::string formatStyled(const NumStyle& st, double value, const NumberHints& h) {
  // printf's %.*f / %.*g / %.*G in the "C" locale whatever the host's locale (std::to_chars)
  auto print = [](char kind, int prec, double v) {
    std::string s = kind == 'f' ? cFixed(v, prec) : cGeneral(v, prec);
    if (kind == 'G') std::replace(s.begin(), s.end(), 'e', 'E');
    return s;
  };
  std::string t;
  if (st.exp) {
    int prec = std::clamp(st.sig, 6, 17);
    if (h.min_decimals >= 9) prec = std::max(prec, 9);
    t = print(st.exp_lower ? 'g' : 'G', prec, value);
  } else {
    int d = st.has_point ? st.frac : 0;
    if (h.significant9) {
      const double a = std::fabs(value);
      const int int_digits = a < 1.0 ? 0 : static_cast<int>(std::floor(std::log10(a))) + 1;
      d = std::clamp(9 - int_digits, 1, 9);
    }
    d = std::clamp(std::max(d, h.min_decimals), 0, 20);
    t = print('f', d, value);
  }
  if (allZeroDigits(t)) {
    if (!t.empty() && t[0] == '-') t.erase(0, 1);
    if (st.bare && t.rfind("0.", 0) == 0) t.erase(0, 1);
    if (st.neg) t.insert(0, "-");
    return t;
  }
  const bool drop = st.bare || (h.drop_leading_zero && !st.exp);
  if (drop) {
    if (t.rfind("0.", 0) == 0) {
      t.erase(0, 1);
    } else if (t.rfind("-0.", 0) == 0) {
      t.erase(1, 1);
    }
  }
  if (st.plus && value >= 0) t.insert(0, "+");
  return t;
}

}  // namespace

std::string formatLike(std::string_view original, double value, const NumberHints& h) {
  return formatStyled(styleOf(original), value, h);
}

void EditQueue::put(int file, std::uint32_t offset, std::uint32_t length, std::string text) {
  Edit e{file, offset, length, std::move(text)};
  if (map_) {
    // edits come in file order mostly (target after target): the hint makes those O(1)
    map_->insert_or_assign(map_->end(), {file, offset}, std::move(e));
  } else {
    log_->ops.push_back(EditLog::Op{false, std::move(e)});
  }
}

void EditQueue::erase(int file, std::uint32_t offset) {
  if (map_) {
    // a key past the last pending edit has none to drop (no tree search): edits come in file
    // order mostly, and most erases are of numbers an edit leaves as they were written
    const std::pair<int, std::uint32_t> key{file, offset};
    if (!map_->empty() && !(map_->rbegin()->first < key)) map_->erase(key);
  } else {
    log_->ops.push_back(EditLog::Op{true, Edit{file, offset, 0, {}}});
  }
}

void applyEdits(Program& p, EditLog&& log) {
  EditQueue q(p);
  for (EditLog::Op& op : log.ops) {
    if (op.erase) {
      q.erase(op.edit.file, op.edit.offset);
    } else {
      q.put(op.edit.file, op.edit.offset, op.edit.length, std::move(op.edit.text));
    }
  }
  log.ops.clear();
}

void queueEdit(Program& p, int file, std::uint32_t offset, std::uint32_t length, std::string text) {
  EditQueue(p).put(file, offset, length, std::move(text));
}

void setNumber(Program& p, NumberField& f, double value, const NumberHints& h) {
  EditQueue q(p);
  setNumber(p, q, f, value, h);
}

void setNumber(const Program& p, EditQueue& q, NumberField& f, double value, const NumberHints& h) {
  const SourceFile& sf = p.files[static_cast<std::size_t>(f.file)];
  const std::string_view orig = std::string_view(sf.bytes).substr(f.offset, f.length);
  const double orig_value = parseNumber(orig).value_or(0.0);
  const NumStyle st = styleOf(orig);
  std::string b = formatStyled(st, value, h);
  f.value = value;
  const std::uint32_t start = f.offset - f.pad;
  // Values more than two units of the last place apart round to numbers more than one unit
  // apart: their texts differ (every step after the rounding keeps the number the text reads),
  // and the original's is not written.
  static constexpr std::array<double, 21> kPlace{1.0,   1e-1,  1e-2,  1e-3,  1e-4,  1e-5,  1e-6,
                                                 1e-7,  1e-8,  1e-9,  1e-10, 1e-11, 1e-12, 1e-13,
                                                 1e-14, 1e-15, 1e-16, 1e-17, 1e-18, 1e-19, 1e-20};
  const int d = fixedPlaces(st, h);
  const bool apart = d >= 0 && std::isfinite(value) && std::isfinite(orig_value) &&
                     std::fabs(value - orig_value) > 2.0 * kPlace[static_cast<std::size_t>(d)];
  if (!apart && formatStyled(st, orig_value, h) == b) {
    q.erase(f.file, start);
    return;
  }
  if (f.pad > 0) {
    const std::size_t width = f.pad + f.length;
    b = b.size() < width ? std::string(width - b.size(), ' ') + b : " " + b;
  }
  q.put(f.file, start, f.pad + f.length, std::move(b));
}

NumberHints hintsFor(const Program& p, const NumberField& f, bool quaternion) {
  NumberHints h;
  const SourceFile& sf = p.files[static_cast<std::size_t>(f.file)];
  h.min_decimals = quaternion ? 9 : 3;
  h.significant9 = sf.significant9 && !quaternion;
  h.drop_leading_zero = sf.bare_fractions && !sf.zero_fractions;
  return h;
}

// ---------------------------------------------------------------- configuration

bool Configuration::present() const {
  switch (vendor) {
    case Vendor::kKuka:
      return status >= 0 || turn >= 0;
    case Vendor::kAbb:
      return true;
    case Vendor::kFanuc:
      return flip != 0;
    case Vendor::kNone:
      return false;
  }
  return false;
}

std::optional<int> Configuration::branch() const {
  switch (vendor) {
    case Vendor::kKuka:
      if (status < 0) return std::nullopt;
      return 4 * (status & 1) + 2 * (((status >> 1) & 1) != 0 ? 0 : 1) + ((status >> 2) & 1);
    case Vendor::kAbb:
      if (cf[3] < 0 || cf[3] > 7) return std::nullopt;
      return cf[3];
    case Vendor::kFanuc:
      if (flip == 0) return std::nullopt;
      return 4 * (front == 'B' ? 1 : 0) + 2 * (elbow == 'D' ? 1 : 0) + (flip == 'N' ? 1 : 0);
    case Vendor::kNone:
      return std::nullopt;
  }
  return std::nullopt;
}

std::string Configuration::text() const {
  switch (vendor) {
    case Vendor::kKuka: {
      std::string s;
      if (status >= 0) s += "S " + std::to_string(status);
      if (turn >= 0) s += (s.empty() ? "T " : " T ") + std::to_string(turn);
      return s;
    }
    case Vendor::kAbb:
      return "[" + std::to_string(cf[0]) + "," + std::to_string(cf[1]) + "," +
             std::to_string(cf[2]) + "," + std::to_string(cf[3]) + "]";
    case Vendor::kFanuc:
      if (flip == 0) return "";
      return std::string(1, flip) + " " + elbow + " " + front + ", " + std::to_string(turns[0]) +
             ", " + std::to_string(turns[1]) + ", " + std::to_string(turns[2]);
    case Vendor::kNone:
      return "";
  }
  return "";
}

Configuration configurationFromBranch(Vendor v, int branch) {
  Configuration c;
  c.vendor = v;
  const int s = (branch >> 2) & 1;
  const int e = (branch >> 1) & 1;
  const int w = branch & 1;
  switch (v) {
    case Vendor::kKuka:
      c.status = s | ((e == 0 ? 1 : 0) << 1) | (w << 2);
      c.turn = 0;
      break;
    case Vendor::kAbb:
      c.cf = {0, 0, 0, branch & 7};
      break;
    case Vendor::kFanuc:
      c.flip = w ? 'N' : 'F';
      c.elbow = e ? 'D' : 'U';
      c.front = s ? 'B' : 'T';
      break;
    case Vendor::kNone:
      break;
  }
  return c;
}

Configuration parseConfigurationText(const std::string& text) {
  Configuration c;
  const std::string u = upper(text);
  std::vector<int> nums;
  std::string letters;
  for (std::size_t i = 0; i < u.size(); ++i) {
    if (isDigit(u[i]) || (u[i] == '-' && i + 1 < u.size() && isDigit(u[i + 1]))) {
      std::size_t j = i + 1;
      while (j < u.size() && isDigit(u[j])) ++j;
      nums.push_back(j - i > 9 ? 0 : std::atoi(u.substr(i, j - i).c_str()));
      i = j - 1;
    } else if (std::isalpha(static_cast<unsigned char>(u[i]))) {
      letters += u[i];
    }
  }
  if (u.find('[') != std::string::npos && nums.size() == 4) {
    c.vendor = Vendor::kAbb;
    for (std::size_t k = 0; k < 4; ++k) c.cf[k] = nums[k];
  } else if ((letters == "ST" || letters == "S" || letters == "T") && !nums.empty()) {
    c.vendor = Vendor::kKuka;
    std::size_t k = 0;
    if (letters.find('S') != std::string::npos) c.status = nums[k++];
    if (letters.find('T') != std::string::npos && k < nums.size()) c.turn = nums[k];
  } else if (letters.size() == 3 && nums.size() == 3) {
    c.vendor = Vendor::kFanuc;
    c.flip = letters[0];
    c.elbow = letters[1];
    c.front = letters[2];
    for (std::size_t k = 0; k < 3; ++k) c.turns[k] = nums[k];
    if ((c.flip != 'F' && c.flip != 'N') || (c.elbow != 'U' && c.elbow != 'D') ||
        (c.front != 'T' && c.front != 'B')) {
      return Configuration{};
    }
  }
  return c;
}

// ---------------------------------------------------------------- targets

bool targetComplete(const Target& t) {
  if (t.kind != TargetKind::kCartesian) return false;
  for (const NumberField& f : t.pos) {
    if (!f.known()) return false;
  }
  const int n = t.orientation == Orientation::kQuaternion ? 4 : 3;
  for (int i = 0; i < n; ++i) {
    if (!t.rot[static_cast<std::size_t>(i)].known()) return false;
  }
  return t.orientation != Orientation::kNone;
}

namespace {

Mat3 axisFrame(const Vec3& z_in) {
  const Vec3 z = z_in.norm() > 0 ? z_in.normalized() : Vec3::UnitZ();
  const Vec3 ref = std::fabs(z.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 y = z.cross(ref).normalized();
  const Vec3 x = y.cross(z);
  Mat3 R;
  R.col(0) = x;
  R.col(1) = y;
  R.col(2) = z;
  return R;
}

}  // namespace

const Pose& SparsePose::get() const {
  static const Pose kIdentity = Pose::Identity();
  return p_ ? *p_ : kIdentity;
}

Pose targetPose(const Program& /*p*/, const Target& t) {
  Pose T = Pose::Identity();
  if (t.kind != TargetKind::kCartesian) return T;
  T.translation() = Vec3(t.pos[0].value, t.pos[1].value, t.pos[2].value) * 1e-3;
  switch (t.orientation) {
    case Orientation::kKukaAbc:
      T.linear() =
          rotationFromZyx(t.rot[0].value * kDeg, t.rot[1].value * kDeg, t.rot[2].value * kDeg);
      break;
    case Orientation::kFanucWpr:
      T.linear() =
          rotationFromZyx(t.rot[2].value * kDeg, t.rot[1].value * kDeg, t.rot[0].value * kDeg);
      break;
    case Orientation::kQuaternion: {
      Eigen::Quaterniond q(t.rot[0].value, t.rot[1].value, t.rot[2].value, t.rot[3].value);
      if (q.norm() > 0) q.normalize();
      T.linear() = q.toRotationMatrix();
      break;
    }
    case Orientation::kXyzIntrinsic:
      T.linear() = (Eigen::AngleAxisd(t.rot[0].value * kDeg, Vec3::UnitX()) *
                    Eigen::AngleAxisd(t.rot[1].value * kDeg, Vec3::UnitY()) *
                    Eigen::AngleAxisd(t.rot[2].value * kDeg, Vec3::UnitZ()))
                       .toRotationMatrix();
      break;
    case Orientation::kAxis:
      T.linear() = axisFrame(Vec3(t.rot[0].value, t.rot[1].value, t.rot[2].value));
      break;
    case Orientation::kNone:
      break;
  }
  return T;
}

std::optional<Pose> motionPose(const Program& p, const Motion& m) {
  if (m.target < 0 || (!m.derivation.empty() && !m.has_offset)) return std::nullopt;
  const Target& t = p.target_list[static_cast<std::size_t>(m.target)];
  if (!targetComplete(t)) return std::nullopt;
  const Pose T = targetPose(p, t);
  if (!m.has_offset) return T;
  return m.offset_in_tool ? Pose(T * m.offset.get()) : Pose(m.offset.get() * T);
}

std::vector<double> targetJointsDeg(const Target& t) {
  std::vector<double> j;
  for (const NumberField& f : t.joints) {
    if (f.known()) j.push_back(f.value);
  }
  return j;
}

const Frame* targetBase(const Program& p, const Target& t) {
  if (t.uses.empty()) return nullptr;
  const int b = p.motions[static_cast<std::size_t>(t.uses.front())].base;
  return b >= 0 ? &p.frames[static_cast<std::size_t>(b)] : nullptr;
}

const Frame* targetTool(const Program& p, const Target& t) {
  if (t.uses.empty()) return nullptr;
  const int b = p.motions[static_cast<std::size_t>(t.uses.front())].tool;
  return b >= 0 ? &p.frames[static_cast<std::size_t>(b)] : nullptr;
}

bool sameFrame(const Program& p, int a, int b) {
  if (a == b) return true;
  if (a < 0 || b < 0) return false;
  const Frame& fa = p.frames[static_cast<std::size_t>(a)];
  const Frame& fb = p.frames[static_cast<std::size_t>(b)];
  return iequals(fa.ref, fb.ref) && fa.resolved == fb.resolved &&
         fa.pose.matrix() == fb.pose.matrix();
}

namespace {

Vendor vendorOf(Dialect d) {
  switch (d) {
    case Dialect::kKrl:
      return Vendor::kKuka;
    case Dialect::kRapid:
      return Vendor::kAbb;
    case Dialect::kTp:
      return Vendor::kFanuc;
    default:
      return Vendor::kNone;
  }
}

}  // namespace

namespace {

// (A, B, C) of R = Rz(A)Ry(B)Rx(C) closest (wrapped, per angle) to `old`; at B = ±90° (gimbal)
// C keeps its old value and A takes the rest (docs/programs.md §6).
Vec3 nearAbc(const Mat3& R, const Vec3& old) {
  auto wrapNear = [&](const Vec3& v) {
    Vec3 o;
    for (int i = 0; i < 3; ++i) o[i] = old[i] + wrapAngle(v[i] - old[i]);
    return o;
  };
  const Vec3 p = zyxFromRotation(R);
  if (std::hypot(R(0, 0), R(1, 0)) < 1e-9) {
    const double c = old[2];
    const Mat3 M = R * Eigen::AngleAxisd(-c, Vec3::UnitX()).toRotationMatrix() *
                   Eigen::AngleAxisd(-p[1], Vec3::UnitY()).toRotationMatrix();
    return wrapNear(Vec3(std::atan2(M(1, 0), M(0, 0)), p[1], c));
  }
  const Vec3 a = wrapNear(p);
  const Vec3 b = wrapNear(Vec3(p[0] + kPi, kPi - p[1], p[2] + kPi));
  return (b - old).squaredNorm() < (a - old).squaredNorm() ? b : a;
}

}  // namespace

bool targetFramesConsistent(const Program& p, const Target& t) {
  for (std::size_t k = 1; k < t.uses.size(); ++k) {
    const Motion& a = p.motions[static_cast<std::size_t>(t.uses[0])];
    const Motion& b = p.motions[static_cast<std::size_t>(t.uses[k])];
    if (!sameFrame(p, a.tool, b.tool) || !sameFrame(p, a.base, b.base)) return false;
  }
  return true;
}

namespace {

/// replaceTargetPose of target `t` of `p`, its edits queued into `q`.
EditResult replaceTarget(const Program& p, EditQueue& queue, Target& t, const Pose& T,
                         const std::optional<Configuration>& config) {
  EditResult r;
  auto who = [&] {  // built only for a refusal
    return (t.name.empty() ? std::string("inline target") : "target " + t.name) + " (" +
           p.files[static_cast<std::size_t>(t.file)].path + ":" + std::to_string(t.line) + ")";
  };
  if (t.kind != TargetKind::kCartesian) {
    r.reason = who() + " is a joint target; only Cartesian targets can take a pose";
    return r;
  }
  {
    std::string named;
    for (const NumberField& f : t.pos)
      if (f.named()) named += (named.empty() ? "" : ", ") + p.exprText(f);
    for (const NumberField& f : t.rot)
      if (f.named()) named += (named.empty() ? "" : ", ") + p.exprText(f);
    if (config)
      for (const NumberField& f : t.cf_fields)
        if (f.named()) named += (named.empty() ? "" : ", ") + p.exprText(f);
    if (!named.empty()) {
      r.reason = who() + " states components by name or expression (" + named +
                 "); they are not rewritten: not edited";
      return r;
    }
  }
  if (!targetComplete(t)) {
    r.reason =
        who() +
        " omits pose components (the controller takes them from the start point); not edited";
    return r;
  }
  if (!targetFramesConsistent(p, t)) {
    r.reason =
        who() +
        " is used by motions with different tools or frames; edit refused (clone it per use)";
    return r;
  }
  if (config && config->vendor != Vendor::kNone) {
    const bool table = vendorOf(p.dialect) == Vendor::kNone;
    if (table && config->text() == t.config.text() && config->vendor == t.config.vendor) {
      // unchanged configuration cell of a target list
    } else if (table) {
      r.reason = who() + ": rewriting the configuration cell of a target list is not supported";
      return r;
    } else if (config->vendor != vendorOf(p.dialect)) {
      r.reason = who() + ": configuration of another vendor given";
      return r;
    } else {
      r = writeConfiguration(p, queue, t, *config);
      if (!r.ok) {
        r.reason = who() + ": " + r.reason;
        return r;
      }
    }
  }
  const Vec3 xyz = T.translation() * 1e3;
  for (int i = 0; i < 3; ++i) {
    NumberField& f = t.pos[static_cast<std::size_t>(i)];
    NumberHints h = hintsFor(p, f, false);
    h.min_decimals = std::max(h.min_decimals, p.position_min_decimals);
    setNumber(p, queue, f, xyz[i], h);
  }
  const Mat3 R = T.linear();
  switch (t.orientation) {
    case Orientation::kKukaAbc: {
      const Vec3 old(t.rot[0].value * kDeg, t.rot[1].value * kDeg, t.rot[2].value * kDeg);
      const Vec3 abc = nearAbc(R, old) / kDeg;
      for (int i = 0; i < 3; ++i) {
        NumberField& f = t.rot[static_cast<std::size_t>(i)];
        setNumber(p, queue, f, abc[i], hintsFor(p, f, false));
      }
      break;
    }
    case Orientation::kFanucWpr: {
      const Vec3 old(t.rot[2].value * kDeg, t.rot[1].value * kDeg, t.rot[0].value * kDeg);
      const Vec3 abc = nearAbc(R, old) / kDeg;
      const std::array<double, 3> wpr{abc[2], abc[1], abc[0]};
      for (int i = 0; i < 3; ++i) {
        NumberField& f = t.rot[static_cast<std::size_t>(i)];
        setNumber(p, queue, f, wpr[static_cast<std::size_t>(i)], hintsFor(p, f, false));
      }
      break;
    }
    case Orientation::kQuaternion: {
      Eigen::Quaterniond q = quaternionFromRotation(R);
      const double dot = q.w() * t.rot[0].value + q.x() * t.rot[1].value + q.y() * t.rot[2].value +
                         q.z() * t.rot[3].value;
      if (dot < 0) q.coeffs() = -q.coeffs();
      const std::array<double, 4> v{q.w(), q.x(), q.y(), q.z()};
      for (int i = 0; i < 4; ++i) {
        NumberField& f = t.rot[static_cast<std::size_t>(i)];
        setNumber(p, queue, f, v[static_cast<std::size_t>(i)], hintsFor(p, f, true));
      }
      break;
    }
    case Orientation::kXyzIntrinsic: {
      // R = Rx(a)Ry(b)Rz(c): r13 = sb, r23 = -sa cb, r33 = ca cb, r12 = -cb sc, r11 = cb cc
      const Vec3 old(t.rot[0].value * kDeg, t.rot[1].value * kDeg, t.rot[2].value * kDeg);
      const double cb = std::hypot(R(0, 0), R(0, 1));
      Vec3 abc(std::atan2(-R(1, 2), R(2, 2)), std::atan2(R(0, 2), cb),
               std::atan2(-R(0, 1), R(0, 0)));
      if (cb < 1e-9) abc = Vec3(std::atan2(R(2, 1), R(1, 1)), std::atan2(R(0, 2), cb), 0.0);
      const Vec3 alt(abc[0] + kPi, kPi - abc[1], abc[2] + kPi);
      auto near = [&](const Vec3& v) {
        Vec3 o;
        for (int i = 0; i < 3; ++i) o[i] = old[i] + wrapAngle(v[i] - old[i]);
        return o;
      };
      const Vec3 a1 = near(abc);
      const Vec3 a2 = near(alt);
      const Vec3 best =
          (a2 - old).squaredNorm() + 1e-18 < (a1 - old).squaredNorm() && cb >= 1e-9 ? a2 : a1;
      for (int i = 0; i < 3; ++i) {
        NumberField& f = t.rot[static_cast<std::size_t>(i)];
        setNumber(p, queue, f, best[i] / kDeg, hintsFor(p, f, false));
      }
      break;
    }
    case Orientation::kAxis: {
      const Vec3 z = R.col(2);
      for (int i = 0; i < 3; ++i) {
        NumberField& f = t.rot[static_cast<std::size_t>(i)];
        NumberHints h = hintsFor(p, f, false);
        h.min_decimals = 6;
        setNumber(p, queue, f, z[i], h);
      }
      break;
    }
    case Orientation::kNone:
      break;
  }
  r.ok = true;
  r.reason.clear();
  return r;
}

/// replaceTarget of target `index` of `p`, or the reason there is none.
EditResult replaceAt(Program& p, int index, const Pose& T,
                     const std::optional<Configuration>& config, EditQueue queue) {
  if (index < 0 || static_cast<std::size_t>(index) >= p.target_list.size()) {
    EditResult r;
    r.reason = "no target with index " + std::to_string(index);
    return r;
  }
  return replaceTarget(p, queue, p.target_list[static_cast<std::size_t>(index)], T, config);
}

}  // namespace

EditResult replaceTargetPose(Program& p, int index, const Pose& T,
                             const std::optional<Configuration>& config) {
  return replaceAt(p, index, T, config, EditQueue(p));
}

EditResult replaceTargetPose(Program& p, int index, const Pose& T,
                             const std::optional<Configuration>& config, EditLog& log) {
  return replaceAt(p, index, T, config, EditQueue(log));
}

int resolveFrame(Program& p, const std::string& ref, const Pose& pose) {
  int n = 0;
  for (Frame& f : p.frames) {
    if (!f.resolved && iequals(f.ref, ref)) {
      f.resolved = true;
      f.pose = pose;
      ++n;
    }
  }
  p.unresolved.erase(std::remove_if(p.unresolved.begin(), p.unresolved.end(),
                                    [&](const Unresolved& u) { return iequals(u.ref, ref); }),
                     p.unresolved.end());
  return n;
}

// ---------------------------------------------------------------- output

std::vector<std::string> renderFiles(const Program& p) {
  std::vector<std::string> out;
  out.reserve(p.files.size());
  auto it = p.edits.begin();
  for (std::size_t fi = 0; fi < p.files.size(); ++fi) {
    const std::string& b = p.files[fi].bytes;
    std::string s;
    s.reserve(b.size() + 64);
    std::size_t pos = 0;
    for (; it != p.edits.end() && it->first.first == static_cast<int>(fi); ++it) {
      const Edit& e = it->second;
      if (e.offset < pos || e.offset + e.length > b.size()) {
        throw std::logic_error("overlapping edits in " + p.files[fi].path);
      }
      s.append(b, pos, e.offset - pos);
      s += e.text;
      pos = e.offset + e.length;
    }
    s.append(b, pos, std::string::npos);
    out.push_back(std::move(s));
  }
  return out;
}

std::vector<std::string> outputPaths(const Program& p, const std::string& out_path) {
  std::vector<std::string> paths{out_path};
  if (p.dialect == Dialect::kKrl && p.files.size() > 1) {
    const fs::path o(out_path);
    const std::string ext = o.extension().string();
    const bool src_ext = iequals(ext, ".src");
    const std::string dat_ext = fs::path(p.files[1].path).extension().string();
    std::string stem = src_ext ? (o.parent_path() / o.stem()).string() : out_path;
    if (src_ext && o.parent_path().empty()) stem = o.stem().string();
    const bool upper_ext = src_ext && ext == ".SRC";
    paths.push_back(
        stem + (dat_ext.empty() ? (upper_ext ? ".DAT" : ".dat") : (upper_ext ? ".DAT" : dat_ext)));
  }
  return paths;
}

void writeProgram(const Program& p, const std::string& out_path) {
  const std::vector<std::string> bytes = renderFiles(p);
  const std::vector<std::string> paths = outputPaths(p, out_path);
  for (std::size_t i = 0; i < paths.size() && i < bytes.size(); ++i)
    writeFileAtomic(paths[i], bytes[i]);
}

// ---------------------------------------------------------------- reading

Dialect detectDialect(const std::string& path, const std::string& bytes) {
  const std::string ext = upper(fs::path(path).extension().string());
  if (ext == ".SRC" || ext == ".DAT") return Dialect::kKrl;
  if (ext == ".MOD" || ext == ".PRG" || ext == ".SYS" || ext == ".MODX") return Dialect::kRapid;
  if (ext == ".LS") return Dialect::kTp;
  if (ext == ".JSON") return Dialect::kJson;
  if (ext == ".CSV" || ext == ".TXT") return Dialect::kCsv;
  const std::string head = upper(std::string_view(bytes).substr(0, 4096));
  if (head.find("/PROG") != std::string::npos) return Dialect::kTp;
  if (head.find("MODULE") != std::string::npos) return Dialect::kRapid;
  if (head.find("DEF ") != std::string::npos || head.find("&ACCESS") != std::string::npos)
    return Dialect::kKrl;
  throw InputError(path, 0,
                   "unknown program dialect (expected .src, .mod/.prg/.sys, .ls, .csv or .json)");
}

Program parseProgram(Dialect d, const std::string& path, std::string bytes,
                     std::optional<std::string> dat_bytes, const std::string& dat_path) {
  Program p;
  p.dialect = d;
  SourceFile f;
  f.path = path;
  f.bytes = std::move(bytes);
  f.indexLines();
  p.files.push_back(std::move(f));
  p.dat_path = dat_path;
  if (d == Dialect::kKrl && dat_bytes) {
    SourceFile g;
    g.path = dat_path;
    g.bytes = std::move(*dat_bytes);
    g.indexLines();
    p.files.push_back(std::move(g));
  }
  // Upper bound of targets and motions in the line-based dialects: one array of each, built in
  // place (pages never written are never resident).
  std::size_t lines = 0;
  for (const SourceFile& sf : p.files) lines += sf.line_starts.size();
  p.target_list.reserve(lines + 16);
  p.motions.reserve(lines + 16);
  switch (d) {
    case Dialect::kKrl:
      parseKrl(p);
      break;
    case Dialect::kRapid:
      parseRapid(p);
      break;
    case Dialect::kTp:
      parseTp(p);
      break;
    case Dialect::kCsv:
    case Dialect::kHoleCsv:
      parseCsv(p);
      break;
    case Dialect::kJson:
      parseJson(p);
      break;
  }
  checkValueRanges(p);
  for (SourceFile& sf : p.files) std::vector<Token>().swap(sf.tokens);  // the readers' index only
  return p;
}

Program readProgram(const std::string& path) {
  if (!fs::exists(path)) throw InputError(path, 0, "cannot open file");
  return readProgram(path, readInputFile(path, InputKind::kProgram));
}

std::pair<std::string, std::string> krlFiles(const std::string& path) {
  std::string src = path;
  const fs::path pp(path);
  if (iequals(pp.extension().string(), ".dat")) {
    for (const char* e : {".src", ".SRC", ".Src"}) {
      const fs::path s = fs::path(pp).replace_extension(e);
      if (fs::exists(s)) {
        src = s.string();
        break;
      }
    }
    if (src == path) throw InputError(path, 0, "a KRL .dat needs its .src beside it");
  }
  for (const char* e : {".dat", ".DAT", ".Dat"}) {
    const fs::path s = fs::path(src).replace_extension(e);
    if (fs::exists(s)) return {src, s.string()};
  }
  return {src, ""};
}

Program readProgram(const std::string& path, std::string bytes) {
  const Dialect d = detectDialect(path, bytes);
  if (d != Dialect::kKrl) return parseProgram(d, path, std::move(bytes), std::nullopt, "");
  const auto [src_path, dat_path] = krlFiles(path);
  if (src_path != path) bytes = readInputFile(src_path, InputKind::kProgram);
  std::optional<std::string> dat;
  if (!dat_path.empty()) dat = readInputFile(dat_path, InputKind::kProgram);
  return parseProgram(
      Dialect::kKrl, src_path, std::move(bytes), std::move(dat),
      dat_path.empty() ? fs::path(src_path).replace_extension(".dat").string() : dat_path);
}

}  // namespace roprec::postproc
