#include "postproc/lexer.hpp"

#include <array>
#include <cctype>

namespace roprec::postproc {

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

namespace {

// Byte classes of the tokenizer (one table look-up per byte instead of a chain of compares).
enum ByteClass : std::uint8_t { kSpace, kLineEnd, kDigit, kIdent, kPunctByte, kRaw };

constexpr std::array<std::uint8_t, 256> kByteClass = [] {
  std::array<std::uint8_t, 256> t{};
  for (int c = 0; c < 256; ++c) {
    const char ch = static_cast<char>(c);
    t[static_cast<std::size_t>(c)] = c >= 0x80 || c < 0x20 ? kRaw : kPunctByte;
    if (isDigit(ch)) t[static_cast<std::size_t>(c)] = kDigit;
    if (isIdentStart(ch)) t[static_cast<std::size_t>(c)] = kIdent;
  }
  t[' '] = t['\t'] = t['\f'] = t['\v'] = kSpace;
  t['\n'] = t['\r'] = kLineEnd;
  return t;
}();

ByteClass classOf(char c) {
  return static_cast<ByteClass>(kByteClass[static_cast<unsigned char>(c)]);
}

// End of the line terminator starting at b[i]: LF, CR LF, CR CR LF; lone CRs one each.
std::size_t lineEndFrom(const std::string& b, std::size_t i) {
  const std::size_t n = b.size();
  std::size_t j = i;
  while (j < n && b[j] == '\r') ++j;
  if (j < n && b[j] == '\n') {
    ++j;
  } else if (j > i + 1) {
    j = i + 1;  // lone CRs: one line end each
  }
  return j == i ? i + 1 : j;
}

// End of the number starting at b[i]: digits [. digits] [e|E [+|-] digits].
std::size_t numberEnd(const std::string& b, std::size_t i) {
  const std::size_t n = b.size();
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
  return j;
}

// Whether b[i] starts a token that runs to the end of the line (comment, KRL `&` header, RAPID
// `%%%`).
bool startsComment(const std::string& b, std::size_t i, bool line_start, const LexOptions& o) {
  const char c = b[i];
  if (o.comment != 0 && c == o.comment) return true;
  if (!line_start) return false;
  return (o.header_amp && c == '&') ||
         (o.percent_header && c == '%' && i + 2 < b.size() && b[i + 1] == '%' && b[i + 2] == '%');
}

// End of the token starting at b[i] that is not a line end, space, comment, number or name.
std::size_t otherEnd(const std::string& b, std::size_t i, const LexOptions& o, TokenKind& kind) {
  const std::size_t n = b.size();
  const char c = b[i];
  std::size_t j = i + 1;
  if (c == '"' || (o.single_quote_string && c == '\'')) {
    while (j < n && b[j] != c && b[j] != '\n' && b[j] != '\r') ++j;
    if (j < n && b[j] == c) ++j;  // unterminated strings end at the line end; readers check
    kind = TokenKind::kString;
  } else if (classOf(c) == kRaw) {
    while (j < n && (static_cast<unsigned char>(b[j]) >= 0x80)) ++j;
    kind = TokenKind::kOther;
  } else {
    if (o.rapid_assign && c == ':' && j < n && b[j] == '=') ++j;
    kind = TokenKind::kPunct;
  }
  return j;
}

}  // namespace

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
    const ByteClass cls = classOf(b[i]);
    if (cls == kSpace) {
      ++i;
      continue;
    }
    if (cls == kLineEnd) {
      const std::size_t j = lineEndFrom(b, i);
      push(i, j, TokenKind::kNewline);
      return j;
    }
    std::size_t j = i + 1;
    TokenKind kind = TokenKind::kIdentifier;
    if (startsComment(b, i, line_start, o)) {
      while (j < n && b[j] != '\n' && b[j] != '\r') ++j;
      kind = TokenKind::kComment;
    } else if (cls == kDigit || (b[i] == '.' && j < n && isDigit(b[j]))) {
      j = numberEnd(b, i);
      kind = TokenKind::kNumber;
    } else if (cls == kIdent) {
      while (j < n && (classOf(b[j]) == kIdent || classOf(b[j]) == kDigit)) ++j;
    } else {
      j = otherEnd(b, i, o, kind);
    }
    line_start = false;
    push(i, j, kind);
    i = j;
  }
  return n;
}

int TokenCursor::line() const {
  if (i_ < end_) return f_.lineOf(f_.tokens[i_].offset);
  if (end_ > 0 && end_ <= f_.tokens.size()) return f_.lineOf(f_.tokens[end_ - 1].offset);
  return static_cast<int>(f_.line_starts.size());
}

}  // namespace roprec::postproc
