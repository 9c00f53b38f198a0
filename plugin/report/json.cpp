#include "plugin/report/json.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "compensator/support/error.hpp"
#include "compensator/support/fixed_chars.hpp"
#include "compensator/support/utf8.hpp"

namespace roprec::api {

Json Json::object() {
  Json j;
  j.kind_ = Kind::kObject;
  return j;
}
Json Json::array() {
  Json j;
  j.kind_ = Kind::kArray;
  return j;
}
Json Json::str(std::string s) {
  Json j;
  j.kind_ = Kind::kString;
  j.string_ = std::move(s);
  return j;
}
Json Json::boolean(bool b) {
  Json j;
  j.kind_ = Kind::kBool;
  j.bool_ = b;
  return j;
}
Json Json::number(double v, int decimals) {
  Json j;
  j.kind_ = Kind::kNumber;
  j.number_ = v;
  j.decimals_ = decimals;
  return j;
}
Json Json::integer(std::int64_t v) {
  Json j;
  j.kind_ = Kind::kNumber;
  j.is_integer_ = true;
  j.integer_ = v;
  return j;
}
Json Json::vector(const Eigen::Ref<const Eigen::VectorXd>& v, int decimals) {
  Json j = array();
  for (Eigen::Index i = 0; i < v.size(); ++i) j.push(number(v[i], decimals));
  return j;
}

Json& Json::set(const std::string& key, Json value) {
  for (size_t i = 0; i < keys_.size(); ++i) {
    if (keys_[i] == key) {
      items_[i] = std::move(value);
      return items_[i];
    }
  }
  keys_.push_back(key);
  items_.push_back(std::move(value));
  return items_.back();
}

Json& Json::push(Json value) {
  items_.push_back(std::move(value));
  return items_.back();
}

bool Json::finite() const {
  if (kind_ == Kind::kNumber) return is_integer_ || std::isfinite(number_);
  for (const Json& i : items_) {
    if (!i.finite()) return false;
  }
  return true;
}

namespace {
/// The bytes appendJsonEscaped does not copy as they are: '"', '\\', control characters and
/// the bytes of non-ASCII characters (checked as UTF-8).
constexpr std::array<bool, 256> kNeedsEscape = [] {
  std::array<bool, 256> t{};
  for (std::size_t c = 0; c < 256; ++c) t[c] = c < 0x20 || c >= 0x80 || c == '"' || c == '\\';
  return t;
}();

bool needsEscape(char c) { return kNeedsEscape[static_cast<unsigned char>(c)]; }

void appendEscapedChar(std::string& o, char c) {
  switch (c) {
    case '"':
      o += "\\\"";
      break;
    case '\\':
      o += "\\\\";
      break;
    case '\n':
      o += "\\n";
      break;
    case '\r':
      o += "\\r";
      break;
    case '\t':
      o += "\\t";
      break;
    default: {
      // a control character, or a byte that is not valid UTF-8 (its Latin-1 character, utf8.hpp)
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x",
                    static_cast<unsigned>(static_cast<unsigned char>(c)));
      o += buf;
    }
  }
}
}  // namespace

void appendJsonEscaped(std::string& o, std::string_view s) {
  // runs without a character to escape are appended whole (ids, keys, notes: nearly everything)
  size_t i = 0;
  while (i < s.size()) {
    size_t run = i;
    while (run < s.size() && !needsEscape(s[run])) ++run;
    o.append(s.data() + i, run - i);
    if (run == s.size()) break;
    const size_t n = static_cast<unsigned char>(s[run]) >= 0x80 ? utf8SequenceLength(s, run) : 0;
    if (n > 0) {  // valid UTF-8 passes through
      o.append(s.data() + run, n);
      i = run + n;
    } else {
      appendEscapedChar(o, s[run]);
      i = run + 1;
    }
  }
}

std::string jsonEscape(const std::string& s) {
  std::string o;
  o.reserve(s.size() + 2);
  appendJsonEscaped(o, s);
  return o;
}

void appendNumber(std::string& out, double v, int decimals) {
  // toFixedChars / std::to_chars: the "C" format whatever the host's locale (a comma-decimal
  // LC_NUMERIC must not change a byte of the output).
  if (decimals >= 0) {
    if (!std::isfinite(v)) {
      out += numberText(v);
      return;
    }
    appendFixed(out, v, decimals);  // "-0.000" -> "0.000"
    return;
  }
  char buf[400];
  if (v == 0.0) {
    out += '0';
    return;
  }
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, static_cast<size_t>(r.ptr - buf));
}

std::string formatNumber(double v, int decimals) {
  if (!std::isfinite(v)) return numberText(v);  // never "nan"/"inf"/"null" (Json::dump throws)
  std::string s;
  appendNumber(s, v, decimals);
  return s;
}

namespace {
/// Thrown inside Json::write for a non-finite number; every level adds its key or index.
struct NonFiniteAt {
  std::string where;
};
}  // namespace

void Json::write(std::string& out, int indent, int level) const {
  const std::string pad =
      indent > 0 ? std::string(static_cast<size_t>(indent * (level + 1)), ' ') : "";
  const std::string pad_end =
      indent > 0 ? std::string(static_cast<size_t>(indent * level), ' ') : "";
  const char* nl = indent > 0 ? "\n" : "";
  switch (kind_) {
    case Kind::kNull:
      out += "null";
      break;
    case Kind::kBool:
      out += bool_ ? "true" : "false";
      break;
    case Kind::kNumber:
      if (!is_integer_ && !std::isfinite(number_)) throw NonFiniteAt{""};
      out += is_integer_ ? std::to_string(integer_) : formatNumber(number_, decimals_);
      break;
    case Kind::kString:
      out += '"';
      appendJsonEscaped(out, string_);
      out += '"';
      break;
    case Kind::kArray: {
      bool scalars = true;
      for (const auto& i : items_) {
        if (i.kind_ == Kind::kArray || i.kind_ == Kind::kObject) scalars = false;
      }
      if (items_.empty()) {
        out += "[]";
        break;
      }
      if (scalars) {  // short arrays of numbers on one line
        out += "[";
        for (size_t i = 0; i < items_.size(); ++i) {
          if (i) out += ", ";
          try {
            items_[i].write(out, indent, level + 1);
          } catch (NonFiniteAt& e) {
            e.where = "[" + std::to_string(i) + "]" + e.where;
            throw;
          }
        }
        out += "]";
        break;
      }
      out += "[";
      out += nl;
      for (size_t i = 0; i < items_.size(); ++i) {
        out += pad;
        try {
          items_[i].write(out, indent, level + 1);
        } catch (NonFiniteAt& e) {
          e.where = "[" + std::to_string(i) + "]" + e.where;
          throw;
        }
        if (i + 1 < items_.size()) out += ",";
        out += nl;
      }
      out += pad_end + "]";
      break;
    }
    case Kind::kObject: {
      if (items_.empty()) {
        out += "{}";
        break;
      }
      out += "{";
      out += nl;
      for (size_t i = 0; i < items_.size(); ++i) {
        out += pad + "\"" + jsonEscape(keys_[i]) + "\":" + (indent > 0 ? " " : "");
        try {
          items_[i].write(out, indent, level + 1);
        } catch (NonFiniteAt& e) {
          e.where = "." + keys_[i] + e.where;
          throw;
        }
        if (i + 1 < items_.size()) out += ",";
        out += nl;
      }
      out += pad_end + "}";
      break;
    }
  }
}

std::string Json::dump(int indent) const {
  std::string out;
  try {
    write(out, indent, 0);
  } catch (const NonFiniteAt& e) {
    throw InternalError("a non-finite number reached the JSON output at $" + e.where +
                        " (it is never written as null; please report this input)");
  }
  if (indent > 0) out += "\n";
  return out;
}

// ---- JsonWriter (the bytes of Json::dump(2), streamed)

JsonNonFinite::JsonNonFinite(const std::string& w)
    : InternalError("a non-finite number reached the JSON output at " + w +
                    " (it is never written as null; please report this input)"),
      where(w) {}

void JsonWriter::pad(size_t n) { out_.append(2 * n, ' '); }

std::string JsonWriter::where(std::string_view tail) const {
  std::string w = "$";
  for (const Frame& f : stack_) {
    if (f.object) {
      w += ".";
      w += f.key;
    } else if (f.count > 0) {
      w += '[';
      w += std::to_string(f.count - 1);
      w += ']';
    }
  }
  w += tail;
  return w;
}

void JsonWriter::beforeValue() {
  if (stack_.empty() || stack_.back().object) return;  // top level, or after key()
  Frame& f = stack_.back();
  newLine(f.count > 0);
  ++f.count;
}

void JsonWriter::newLine(bool comma) {
  // ",\n" or "\n" and two spaces a level, in one append
  const size_t n = 2 * stack_.size();
  const std::string_view kSpaces = ",\n                                ";  // 32 spaces
  if (n + 2 <= kSpaces.size()) {
    out_.append(comma ? kSpaces.data() : kSpaces.data() + 1, n + (comma ? 2 : 1));
    return;
  }
  out_.append(comma ? ",\n" : "\n", comma ? 2 : 1);
  pad(stack_.size());
}

void JsonWriter::key(std::string_view k) {
  Frame& f = stack_.back();
  newLine(f.count > 0);
  out_ += '"';
  appendJsonEscaped(out_, k);
  out_ += "\": ";
  f.key = k;
  ++f.count;
}

void JsonWriter::beginObject() {
  beforeValue();
  out_ += '{';
  stack_.push_back({true, 0, {}});
}

void JsonWriter::beginArray() {
  beforeValue();
  out_ += '[';
  stack_.push_back({false, 0, {}});
}

void JsonWriter::endObject() {
  const size_t n = stack_.back().count;
  stack_.pop_back();
  if (n) {
    out_ += '\n';
    pad(stack_.size());
  }
  out_ += '}';
}

void JsonWriter::endArray() {
  const size_t n = stack_.back().count;
  stack_.pop_back();
  if (n) {
    out_ += '\n';
    pad(stack_.size());
  }
  out_ += ']';
}

void JsonWriter::str(std::string_view s) {
  beforeValue();
  out_ += '"';
  appendJsonEscaped(out_, s);
  out_ += '"';
}

void JsonWriter::number(double v, int decimals) {
  if (!std::isfinite(v)) throw JsonNonFinite(where());
  beforeValue();
  appendNumber(out_, v, decimals);
}

void JsonWriter::integer(std::int64_t v) {
  beforeValue();
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out_.append(buf, r.ptr);
}

void JsonWriter::boolean(bool b) {
  beforeValue();
  out_ += b ? "true" : "false";
}

void JsonWriter::null() {
  beforeValue();
  out_ += "null";
}

void JsonWriter::numbers(const Eigen::Ref<const Eigen::VectorXd>& v, int decimals) {
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) throw JsonNonFinite(where("[" + std::to_string(i) + "]"));
  }
  beforeValue();
  out_ += '[';
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (i) out_ += ", ";
    appendNumber(out_, v[i], decimals);
  }
  out_ += ']';
}

void JsonWriter::strings(const std::vector<std::string>& v) {
  beforeValue();
  out_ += '[';
  for (size_t i = 0; i < v.size(); ++i) {
    if (i) out_ += ", ";
    out_ += '"';
    appendJsonEscaped(out_, v[i]);
    out_ += '"';
  }
  out_ += ']';
}

void JsonWriter::value(const Json& j) {
  const Mark m = mark();
  beforeValue();
  try {
    j.write(out_, 2, static_cast<int>(stack_.size()));
  } catch (const NonFiniteAt& e) {
    const std::string w = where(e.where);
    rewind(m);
    throw JsonNonFinite(w);
  }
}

void JsonWriter::finish() { out_ += '\n'; }

JsonWriter::Mark JsonWriter::mark() const {
  return {out_.size(), stack_.size(), stack_.empty() ? 0 : stack_.back().count};
}

void JsonWriter::rewind(const Mark& m) {
  out_.resize(m.size);
  stack_.resize(m.depth);
  if (!stack_.empty()) stack_.back().count = m.count;
}

JsonWriter JsonWriter::itemWriter(size_t k) const {
  if (stack_.empty() || stack_.back().object)
    throw InternalError("JsonWriter::itemWriter outside an array at " + where());
  JsonWriter w;
  w.stack_ = stack_;
  w.stack_.back().count += k;
  return w;
}

void JsonWriter::appendItems(std::string_view text, size_t n) {
  if (stack_.empty() || stack_.back().object)
    throw InternalError("JsonWriter::appendItems outside an array at " + where());
  out_ += text;
  stack_.back().count += n;
}

void JsonWriter::take(std::string& to) {
  to.swap(out_);
  out_.clear();
}

}  // namespace roprec::api
