#pragma once
/// Running a program from the tests without a shell, the same on Linux and Windows: the program
/// is started directly (posix_spawn / CreateProcessW) with standard input empty and standard
/// output and error captured, so no POSIX shell syntax is needed (under Wine, std::system would
/// run cmd.exe).
#include <string>
#include <string_view>
#include <vector>

namespace roprec::test {

/// The words of a command line written with POSIX shell quoting: blanks separate words, '...'
/// keeps everything, "..." keeps everything but \" \\ \$ \`, a backslash outside quotes keeps the
/// next character. Nothing is expanded. Throws std::invalid_argument on an unclosed quote.
std::vector<std::string> shellWords(std::string_view line);

/// True when a word is a shell operator the helper does not run (|, >, <, &&, ;, 2>&1, ...).
bool isShellOperator(const std::string& word);

struct ProcessResult {
  int exit_code{0};  ///< the exit status; 128 + signal when a signal ended it (POSIX)
  std::string out;
  std::string err;
};

/// Runs argv[0] (a path) with the arguments argv[1..], the environment of this process plus
/// `env` ("NAME=VALUE" each; a bare "NAME" removes it), in the current folder; waits for it and
/// returns its exit status and captured output.
ProcessResult runProcess(const std::vector<std::string>& argv,
                         const std::vector<std::string>& env = {});

}  // namespace roprec::test
