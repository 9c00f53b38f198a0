#include "compensator/support/error.hpp"

#include <charconv>
#include <cmath>
#include <utility>

#include "compensator/support/long_words.hpp"

namespace roprec {

namespace {
std::string compose(const std::string& file, int line, int column, const std::string& message) {
  std::string s;
  if (!file.empty()) {
    s += file;
    if (line > 0) {
      s += ":" + std::to_string(line);
      if (column > 0) s += ":" + std::to_string(column);
    }
    s += ": ";
  }
  s += message;
  return s;
}
}  // namespace

// A 1 MB name or value echoed into a message is cut to a readable length (clipLongWords).
InputError::InputError(std::string file, int line, std::string message, int column)
    : std::runtime_error(compose(file, line, column, clipLongWords(message))),
      file_(std::move(file)),
      line_(line),
      column_(column),
      message_(clipLongWords(message)) {}

std::string formatInputError(const InputError& e) { return e.what(); }

std::string numberText(double v, int significant) {
  if (std::isnan(v)) return "not a number";
  if (std::isinf(v)) return v > 0 ? "infinite" : "-infinite";
  if (v == 0.0) return "0";
  char buf[64];
  const int p = significant < 1 ? 1 : (significant > 17 ? 17 : significant);
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, p);
  return std::string(buf, r.ptr);
}

}  // namespace roprec
