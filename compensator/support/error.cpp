#include "compensator/support/error.hpp"

#include <utility>

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

InputError::InputError(std::string file, int line, std::string message, int column)
    : std::runtime_error(compose(file, line, column, message)),
      file_(std::move(file)),
      line_(line),
      column_(column),
      message_(std::move(message)) {}

std::string formatInputError(const InputError& e) { return e.what(); }

}  // namespace roprec
