#include "postproc/lexer.hpp"

#include <cctype>

namespace roprec::postproc {

namespace {
inline char asciiUpper(char c) {
  return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
}
}  // namespace

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (asciiUpper(a[i]) != asciiUpper(b[i])) return false;
  }
  return true;
}

std::string upper(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = asciiUpper(c);
  return r;
}

void lex(SourceFile& f, const LexOptions& o) {
  f.tokens.clear();
  f.tokens.reserve(f.bytes.size() / 4 + 16);
  std::size_t i = f.bom ? 3 : 0;
  while (i < f.bytes.size()) i = lexLine(f, o, i, f.tokens);
}

std::size_t lexLine(const SourceFile& f, const LexOptions& o, std::size_t from,
                    std::vector<Token>& out) {
  const std::string& b = f.bytes;
  const std::size_t n = b.size();
  std::size_t i = from == 0 && f.bom ? 3 : from;
  bool line_start = true;
  auto push = [&](std::size_t start, std::size_t end, TokenKind k) {
    out.push_back(
        Token{static_cast<std::uint32_t>(start), static_cast<std::uint32_t>(end - start), k});
  };
  while (i < n) {
    const char c = b[i];
    if (c == '\n' || c == '\r') {
      std::size_t j = i;
      while (j < n && b[j] == '\r') ++j;
      if (j < n && b[j] == '\n') {
        ++j;
      } else if (j > i + 1) {
        j = i + 1;  // lone CRs: one line end each
      }
      if (j == i) j = i + 1;
      push(i, j, TokenKind::kNewline);
      return j;
    }
    if (c == ' ' || c == '\t' || c == '\f' || c == '\v') {
      ++i;
      continue;
    }
    const bool at_line_start = line_start;
    line_start = false;
    if ((o.header_amp && at_line_start && c == '&') ||
        (o.percent_header && at_line_start && c == '%' && i + 2 < n && b[i + 1] == '%' &&
         b[i + 2] == '%') ||
        (o.comment != 0 && c == o.comment)) {
      std::size_t j = i;
      while (j < n && b[j] != '\n' && b[j] != '\r') ++j;
      push(i, j, TokenKind::kComment);
      i = j;
      continue;
    }
    if (isDigit(c) || (c == '.' && i + 1 < n && isDigit(b[i + 1]))) {
      std::size_t j = i;
      while (j < n && isDigit(b[j])) ++j;
      if (j < n && b[j] == '.') {
        ++j;
        while (j < n && isDigit(b[j])) ++j;
      }
      if (j < n && (b[j] == 'e' || b[j] == 'E')) {
        std::size_t k = j + 1;
        if (k < n && (b[k] == '+' || b[k] == '-')) ++k;
        if (k < n && isDigit(b[k])) {
          while (k < n && isDigit(b[k])) ++k;
          j = k;
        }
      }
      push(i, j, TokenKind::kNumber);
      i = j;
      continue;
    }
    if (isIdentStart(c)) {
      std::size_t j = i + 1;
      while (j < n && isIdentChar(b[j])) ++j;
      push(i, j, TokenKind::kIdentifier);
      i = j;
      continue;
    }
    if (c == '"' || (o.single_quote_string && c == '\'')) {
      std::size_t j = i + 1;
      while (j < n && b[j] != c && b[j] != '\n' && b[j] != '\r') ++j;
      if (j < n && b[j] == c) ++j;  // unterminated strings end at the line end; readers check
      push(i, j, TokenKind::kString);
      i = j;
      continue;
    }
    if (static_cast<unsigned char>(c) >= 0x80 || c < 0x20) {
      std::size_t j = i + 1;
      while (j < n && (static_cast<unsigned char>(b[j]) >= 0x80)) ++j;
      push(i, j, TokenKind::kOther);
      i = j;
      continue;
    }
    if (o.rapid_assign && c == ':' && i + 1 < n && b[i + 1] == '=') {
      push(i, i + 2, TokenKind::kPunct);
      i += 2;
      continue;
    }
    push(i, i + 1, TokenKind::kPunct);
    ++i;
  }
  return n;
}

const Token& TokenCursor::peek(std::size_t k) const {
  static const Token kEnd{0, 0, TokenKind::kNewline};
  return i_ + k < end_ ? f_.tokens[i_ + k] : kEnd;
}

std::string_view TokenCursor::text(std::size_t k) const {
  if (i_ + k >= end_) return {};
  return f_.text(f_.tokens[i_ + k]);
}

bool TokenCursor::isPunct(char c, std::size_t k) const {
  if (i_ + k >= end_) return false;
  const Token& t = f_.tokens[i_ + k];
  return t.kind == TokenKind::kPunct && t.length == 1 && f_.bytes[t.offset] == c;
}

bool TokenCursor::isIdent(std::string_view word, std::size_t k) const {
  if (i_ + k >= end_) return false;
  const Token& t = f_.tokens[i_ + k];
  return t.kind == TokenKind::kIdentifier && iequals(f_.text(t), word);
}

bool TokenCursor::isKind(TokenKind kind, std::size_t k) const {
  return i_ + k < end_ && f_.tokens[i_ + k].kind == kind;
}

const Token& TokenCursor::next() {
  const Token& t = peek();
  if (i_ < end_) ++i_;
  return t;
}

int TokenCursor::line() const {
  if (i_ < end_) return f_.lineOf(f_.tokens[i_].offset);
  if (end_ > 0 && end_ <= f_.tokens.size()) return f_.lineOf(f_.tokens[end_ - 1].offset);
  return static_cast<int>(f_.line_starts.size());
}

}  // namespace roprec::postproc
