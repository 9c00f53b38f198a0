#pragma once
/// \file utf8.hpp
/// UTF-8 validity, for the outputs that must be UTF-8 (JSON, HTML). roprec keeps the bytes of its
/// inputs as they are (a program's Latin-1 comment passes through unchanged); a byte that is not
/// part of a valid UTF-8 sequence is written to JSON as `\u00XX` and to HTML as `&#xXX;`, the
/// character of that byte in Latin-1 (ISO 8859-1), so `Geh\xE4use` reads "Gehäuse"
/// (docs/contract.md "Text encodings").

#include <cstddef>
#include <string_view>

namespace roprec {

/// The length (1..4) of the valid UTF-8 sequence starting at s[i], or 0 when the byte there does
/// not start one (a stray continuation byte, an overlong form, a surrogate, beyond U+10FFFF, or
/// cut by the end of `s`).
std::size_t utf8SequenceLength(std::string_view s, std::size_t i);

}  // namespace roprec
