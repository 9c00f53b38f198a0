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

/// Formats `FILE:LINE[:COL]: message` (the part after `roprec: error: `).
std::string formatInputError(const InputError& e);

}  // namespace roprec
