#pragma once
/// \file xml_escape.hpp
/// Escaping text for XML and HTML output (robot cards, reports): one rule everywhere.

#include <string>
#include <string_view>

namespace roprec {

/// `&`, `<`, `>` become entities; quotes become `&quot;` / `&#39;` — both when `quote` is 0 (text
/// and attributes of either kind), else only the quote that delimits the attribute (`"` or `'`;
/// the other is kept as it is). Control characters other than `\n` and `\t` become spaces (they
/// are not allowed in XML 1.0). A byte that is not part of valid UTF-8 becomes `&#xXX;`, its
/// Latin-1 character (utf8.hpp), so the output is always UTF-8.
std::string escapeXml(std::string_view s, char quote = 0);

}  // namespace roprec
