#pragma once
/// \file error.hpp
/// Errors that reach the user. An InputError names the file, the line (1-based, 0 = unknown)
/// and optionally the column of what is wrong; the CLI prints
/// `roprec: error: FILE:LINE[:COL]: message` and exits with code 2 (docs/contract.md §3).

#include <stdexcept>
#include <string>

namespace roprec {

/// Bad input in a file (or on the command line when `file` is empty).
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, int line, std::string message, int column = 0);

  const std::string& file() const { return file_; }
  int line() const { return line_; }
  int column() const { return column_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  int line_{0};
  int column_{0};
  std::string message_;
};

/// Bad command-line usage (unknown option, missing argument). Exit code 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A bug in roprec caught before it could write a wrong answer (e.g. a non-finite number reaching
/// an output). The CLI prints `roprec: internal error: ...` and exits with code 2.
class InternalError : public std::logic_error {
 public:
  explicit InternalError(const std::string& what) : std::logic_error(what) {}
};

/// Formats `FILE:LINE[:COL]: message` (the part after `roprec: error: `).
std::string formatInputError(const InputError& e);

/// A number for a message: at most `significant` significant digits (%g style, "C" locale, so
/// never 300 digits), and words instead of "nan"/"inf" ("not a number", "infinite",
/// "-infinite").
std::string numberText(double v, int significant = 6);

}  // namespace roprec
