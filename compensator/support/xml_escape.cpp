#include "compensator/support/xml_escape.hpp"

namespace roprec {

std::string escapeXml(std::string_view s, char quote) {
  std::string o;
  o.reserve(s.size() + 8);
  for (const char c : s) {
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
