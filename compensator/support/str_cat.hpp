#pragma once
/// \file str_cat.hpp
/// Strings built from several pieces with one allocation: `a + b + c` makes a temporary string
/// per `+` (clang-tidy performance-inefficient-string-concatenation), strCat(a, b, c) sizes the
/// result once and appends. For messages and lines built in loops (a writer's statements, the
/// checks of every joint).

#include <cstddef>
#include <string>
#include <string_view>

namespace roprec {

/// Appends every piece (anything a std::string_view is made from) to `s`, in order. No piece may
/// view `s` itself (its buffer may move).
template <class... Pieces>
void strAppend(std::string& s, const Pieces&... pieces) {
  if constexpr (sizeof...(Pieces) > 0) {
    const std::string_view views[] = {std::string_view(pieces)...};
    std::size_t n = s.size();
    for (const std::string_view v : views) n += v.size();
    s.reserve(n);
    for (const std::string_view v : views) s.append(v);
  }
}

/// The pieces one after the other.
template <class... Pieces>
std::string strCat(const Pieces&... pieces) {
  std::string s;
  strAppend(s, pieces...);
  return s;
}

}  // namespace roprec
