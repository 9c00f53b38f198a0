#pragma once
/// \file long_words.hpp
/// Messages stay readable whatever the input echoes into them: the CLI's stderr lines and every
/// InputError pass through clipLongWords (docs/contract.md §4a).

#include <string>
#include <string_view>

namespace roprec {

/// `message` with every run of non-blank bytes longer than 1000 bytes (a 1 MB name or value echoed
/// by whatever message) cut by clipForMessage (input_file.hpp) to its first 200 bytes and
/// "… (N bytes)". Linear in the message.
std::string clipLongWords(std::string_view message);

}  // namespace roprec
