#pragma once
/// \file text_lines.hpp
/// Line splitting and trimming for the line-oriented measurement files (measured holes, tracker
/// poses): physical lines with their 1-based numbers, blanks and tabs trimmed.

#include <string_view>
#include <vector>

namespace roprec::postproc {

struct TextLine {
  std::string_view text;  ///< without its terminator
  int number{0};          ///< 1-based
};

/// Physical lines (LF, CRLF or CR terminated); a leading UTF-8 byte-order mark is dropped.
std::vector<TextLine> splitTextLines(std::string_view text);

/// `s` without leading and trailing blanks and tabs.
std::string_view trimBlanks(std::string_view s);

/// True for an empty line, a line of blanks, or a `#` comment line.
bool isBlankOrComment(std::string_view line);

}  // namespace roprec::postproc
