#include "compensator/support/xml_escape.hpp"

#include <cstdio>

#include "compensator/support/utf8.hpp"

namespace roprec {

std::string escapeXml(std::string_view s, char quote) {
  std::string o;
  o.reserve(s.size() + 8);
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (static_cast<unsigned char>(c) >= 0x80) {
      const std::size_t n = utf8SequenceLength(s, i);
      if (n == 0) {  // not UTF-8: the byte's Latin-1 character (utf8.hpp)
        char buf[8];
        std::snprintf(buf, sizeof buf, "&#x%02X;",
                      static_cast<unsigned>(static_cast<unsigned char>(c)));
        o += buf;
      } else {
        o.append(s.data() + i, n);
        i += n - 1;
      }
      continue;
    }
    switch (c) {
      case '&':
        o += "&amp;";
        break;
      case '<':
        o += "&lt;";
        break;
      case '>':
        o += "&gt;";
        break;
      case '"':
        o += quote == '\'' ? "\"" : "&quot;";
        break;
      case '\'':
        o += quote == '"' ? "'" : "&#39;";
        break;
      default:
        o += static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t' ? ' ' : c;
    }
  }
  return o;
}

}  // namespace roprec
