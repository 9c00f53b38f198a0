/// ABB RAPID reader (`.mod`, `.prg`, `.sys`), docs/programs.md §3.
#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <functional>
#include <optional>
#include <unordered_map>

#include "compensator/support/error.hpp"
#include "postproc/dialects.hpp"
#include "postproc/lexer.hpp"

namespace roprec::postproc {
namespace {

struct Node {
  bool list{false};
  std::vector<Node> items;
  std::uint32_t begin{0};
  std::uint32_t end{0};
  bool number{false};
  double value{0};
  std::string_view ident;  // identifier leaves: the name as written (a view of the file)
  std::size_t tb{0};       // scalar leaves: token range [tb, te)
  std::size_t te{0};
};

struct ToolState {
  Pose pose{Pose::Identity()};
  bool resolved{false};
  bool stationary{false};  // robhold FALSE (tool) / TRUE (wobj): roles swap
  int line{0};
};

class RapidReader {
 public:
  /// `streamed`: p.files[0] holds one window of whole lines at a time (RapidStream).
  explicit RapidReader(Program& p, bool streamed = false)
      : p_(p), f_(p.files[0]), streamed_(streamed) {}

  void run() {
    start();
    lines(true);
    finish();
  }

  void start() {
    opt_.comment = '!';
    opt_.rapid_assign = true;
    opt_.percent_header = true;
    tools_["TOOL0"] = ToolState{Pose::Identity(), true, false, 0};
    wobjs_["WOBJ0"] = ToolState{Pose::Identity(), true, false, 0};
  }

  /// Reads the constructs of the window f_ holds (the whole file: `last`). Read by windows, a
  /// construct the window ends inside is left to the next window: carry() is then the offset of
  /// the line it starts on, its tokens before it (on that line) skipped there.
  void lines(bool last) {
    last_ = last;
    tok_.clear();
    next_line_ = 0;
    carry_ = f_.bytes.size();
    if (skip_ > 0 && !f_.bytes.empty()) {  // the carried line's tokens read before
      next_line_ = lexLine(f_, opt_, 0, tok_);
      std::size_t k = 0;
      while (k < tok_.size() && tok_[k].offset < skip_) ++k;
      tok_.erase(tok_.begin(), tok_.begin() + static_cast<std::ptrdiff_t>(k));
    }
    skip_ = 0;
    bool construct = false;
    try {
      std::size_t i = 0;
      if (!header_read_) {
        i = skipHeader();
        header_read_ = true;
      }
      while (has(i)) {
        if (tok_[i].kind == TokenKind::kNewline || tok_[i].kind == TokenKind::kComment) {
          ++i;
          continue;
        }
        tok_.erase(tok_.begin(), tok_.begin() + static_cast<std::ptrdiff_t>(i));
        construct = true;
        i = topLevel(n_);
        construct = false;
      }
    } catch (const MoreBytes&) {
      if (!header_read_) {  // the header again, with the next window's bytes
        carry_ = 0;
      } else if (construct) {  // tok_[0] starts it: its line again
        const std::uint32_t at = tok_[0].offset;
        const auto it = std::upper_bound(f_.line_starts.begin(), f_.line_starts.end(), at);
        carry_ = *(it - 1);
        skip_ = at - static_cast<std::uint32_t>(carry_);
      }
    }
  }

  /// The offset of the window's first byte the next window starts with (lines()).
  [[nodiscard]] std::size_t carry() const { return carry_; }

  /// After the last window: the module's structure checked.
  void finish() {
    if (!n_.any_module) throw InputError(f_.path, 1, "no MODULE found: not a RAPID module");
    if (n_.modules != 0) failAt(f_, f_.bytes.size(), "truncated file: MODULE without ENDMODULE");
    if (n_.routines != 0) failAt(f_, f_.bytes.size(), "truncated file: routine without its END");
  }

  /// The targets [begin, end) of p_ were dropped (none declared): the later ones shift down.
  void retiredTargets(std::size_t begin, std::size_t end) {
    const auto n = static_cast<int>(end - begin);
    targets_.forEachValue([&](int& idx) {
      if (idx >= static_cast<int>(end)) idx -= n;
    });
  }

 private:
  Program& p_;
  const SourceFile& f_;
  LexOptions opt_;
  /// Tokens from the current top-level construct on, lexed line by line as the reader needs them
  /// (the file never has a whole-file token index).
  std::vector<Token> tok_;
  std::size_t next_line_{0};  ///< byte offset of the first line not lexed yet
  /// Thrown by has() at the end of a window that is not the file's last (streamed_).
  struct MoreBytes {};
  bool streamed_{false};
  bool last_{true};                ///< no bytes after f_'s
  bool header_read_{false};        ///< skipHeader() done
  std::size_t carry_{0};           ///< lines(): where the next window starts in this one
  std::uint32_t skip_{0};          ///< the bytes of the first line read before (carried)
  std::deque<std::string> names_;  ///< streamed_: the declared names targets_ keys view

  struct Nesting {
    int modules{0};
    int routines{0};
    bool any_module{false};
  };
  Nesting n_;

  /// Whether tok_[k] exists, lexing further lines as needed.
  bool has(std::size_t k) {
    while (k >= tok_.size()) {
      if (next_line_ >= f_.bytes.size()) {
        if (streamed_ && !last_) throw MoreBytes{};
        return false;
      }
      next_line_ = lexLine(f_, opt_, next_line_, tok_);
    }
    return true;
  }

  bool isComment3(std::size_t k) const {
    return tok_[k].kind == TokenKind::kComment && f_.text(tok_[k]).rfind("%%%", 0) == 0;
  }

  /// S4-era header: %%% / VERSION:1 / LANGUAGE:ENGLISH / %%%. Returns the index after it.
  std::size_t skipHeader() {
    std::size_t i = 0;
    while (has(i) && tok_[i].kind == TokenKind::kNewline) ++i;
    if (has(i) && isComment3(i)) {
      ++i;
      while (has(i) && !isComment3(i)) ++i;
      if (!has(i)) failAt(f_, f_.bytes.size(), "truncated file: %%% header not closed");
      ++i;
    }
    return i;
  }

  /// Keywords whose whole line is skipped (module and routine structure, block ends).
  static bool lineKeyword(std::string_view w) {
    static const char* const kLineKw[] = {
        "MODULE",  "ENDMODULE", "PROC",     "FUNC",   "TRAP",     "ENDPROC",   "ENDFUNC",
        "ENDTRAP", "ENDIF",     "ELSE",     "ENDFOR", "ENDWHILE", "ENDTEST",   "DEFAULT",
        "ERROR",   "UNDO",      "BACKWARD", "CASE",   "RECORD",   "ENDRECORD", "TEST"};
    for (const char* kw : kLineKw)
      if (iequals(w, kw)) return true;
    return false;
  }

  static void count(Nesting& n, std::string_view w2) {
    if (iequals(w2, "MODULE")) {
      ++n.modules;
      n.any_module = true;
    } else if (iequals(w2, "ENDMODULE")) {
      --n.modules;
    } else if (iequals(w2, "PROC") || iequals(w2, "FUNC") || iequals(w2, "TRAP")) {
      ++n.routines;
    } else if (iequals(w2, "ENDPROC") || iequals(w2, "ENDFUNC") || iequals(w2, "ENDTRAP")) {
      --n.routines;
    }
  }

  /// The construct starting at tok_[0]: a structure line, a condition head or a statement.
  /// Returns the index after it.
  std::size_t topLevel(Nesting& n) {
    const std::string_view w = f_.text(tok_[0]);
    const std::size_t k = iequals(w, "LOCAL") || iequals(w, "TASK") ? 1 : 0;
    const std::string_view w2 = has(k) ? f_.text(tok_[k]) : std::string_view();
    if (lineKeyword(w2)) {
      std::size_t i = 0;
      while (has(i) && tok_[i].kind != TokenKind::kNewline) ++i;
      count(n, w2);
      return i;
    }
    if (const std::size_t after = labelOrPlaceholder(); after > 0) return after;
    if (iequals(w, "IF") || iequals(w, "WHILE") || iequals(w, "FOR") || iequals(w, "ELSEIF")) {
      std::size_t j = 0;
      while (has(j) && !(pc(j) == ';') &&
             !(tok_[j].kind == TokenKind::kIdentifier &&
               (iequals(f_.text(tok_[j]), "THEN") || iequals(f_.text(tok_[j]), "DO")))) {
        ++j;
      }
      return j + 1;
    }
    return statementAt();
  }

  /// A label `name:` (the target of a GOTO; it may stand before any statement, also before
  /// ENDPROC, IF, WHILE or TEST) or the FlexPendant's `<SMT>` placeholder of an empty routine
  /// body at tok_[0]: neither is a statement (no ';'). Returns the index after it, 0 for anything
  /// else.
  std::size_t labelOrPlaceholder() {
    if (tok_[0].kind == TokenKind::kIdentifier && has(1) && pc(1) == ':') return 2;
    if (pc(0) == '<' && has(2) && iequals(f_.text(tok_[1]), "SMT") && pc(2) == '>') return 3;
    return 0;
  }

  /// The statement at tok_[0] up to its ';'; returns the index after the ';'.
  std::size_t statementAt() {
    std::size_t j = 0;
    int depth = 0;
    std::size_t last = 0;  // last significant token of the statement so far
    while (has(j)) {
      const Token x = tok_[j];
      if (x.kind == TokenKind::kPunct && x.length == 1) {
        const char c = f_.bytes[x.offset];
        if (c == '[' || c == '(') ++depth;
        if (c == ']' || c == ')') --depth;
        if (c == ';') break;
      }
      if (x.kind == TokenKind::kNewline && depth == 0) missingSemicolon(last, j);
      if (x.kind != TokenKind::kNewline && x.kind != TokenKind::kComment) last = j;
      ++j;
    }
    if (!has(j)) failAt(f_, tok_[0].offset, "truncated file: statement without ';'");
    statement(0, j);
    return j + 1;
  }

  /// Declared targets: name (a view of the file, case-insensitive) -> index in p_.target_list;
  /// a later declaration of a name replaces the earlier one.
  NameMap<int> targets_;
  std::unordered_map<std::string, ToolState> tools_;
  std::unordered_map<std::string, ToolState> wobjs_;
  std::unordered_map<std::string, double> speeds_;
  std::unordered_map<std::string, double> nums_;  // num constants/variables of known value
  std::unordered_map<std::string, bool> reported_;
  bool conf_l_{true};
  bool conf_j_{true};

  [[noreturn]] void fail(std::size_t off, const std::string& m) const { failAt(f_, off, m); }

  /// A statement continues on the next line only after an operator, a comma, `:=` or inside
  /// brackets, or when the next line starts with an operator or an optional argument (`\WObj`).
  /// A line that ends in a complete argument and is followed by a line starting with a name is a
  /// missing `;` (it would otherwise swallow the next instruction, e.g. a hole's drill point).
  /// The punctuation character of tok_[k] (0 for any other token).
  char pc(std::size_t k) const {
    const Token& x = tok_[k];
    return x.kind == TokenKind::kPunct && x.length == 1 ? f_.bytes[x.offset] : '\0';
  }

  static bool isOperatorWord(std::string_view w) {
    for (const char* op : {"AND", "OR", "XOR", "NOT", "DIV", "MOD"})
      if (iequals(w, op)) return true;
    return false;
  }

  void missingSemicolon(std::size_t last, std::size_t nl) {
    const Token lt = tok_[last];
    if (lt.kind == TokenKind::kPunct) {
      const std::string_view x = f_.text(lt);
      if (x != "]" && x != ")") return;  // `,` `:=` `\` `+` ... continue the statement
    } else if (lt.kind != TokenKind::kIdentifier && lt.kind != TokenKind::kNumber &&
               lt.kind != TokenKind::kString) {
      return;
    }
    if (lt.kind == TokenKind::kIdentifier && isOperatorWord(f_.text(lt))) return;
    std::size_t k = nl;
    while (has(k) && (tok_[k].kind == TokenKind::kNewline || tok_[k].kind == TokenKind::kComment))
      ++k;
    if (!has(k) || tok_[k].kind != TokenKind::kIdentifier) return;
    if (isOperatorWord(f_.text(tok_[k]))) return;
    fail(lt.offset, "missing ';' at the end of the line (the next line, '" +
                        std::string(f_.text(tok_[k])) + "', would become part of this statement)");
  }

  void unresolved(const std::string& ref, std::size_t off, const std::string& what) {
    if (reported_.count(upper(ref)) != 0) return;
    if (reported_.emplace(upper(ref), true).second)
      p_.unresolved.push_back(Unresolved{ref, 0, f_.lineOf(off), what});
  }

  // Parses an expression element in [i, e); advances i.
  Node parseElement(std::size_t& i, std::size_t e) {
    const std::vector<Token>& t = tok_;
    while (i < e && (t[i].kind == TokenKind::kNewline || t[i].kind == TokenKind::kComment)) ++i;
    if (i >= e)
      fail(i < t.size() ? t[i].offset : f_.bytes.size(), "unterminated aggregate (missing ']')");
    Node n;
    n.begin = t[i].offset;
    if (pc(i) == '[') {
      const std::uint32_t open = t[i].offset;
      n.list = true;
      n.items.reserve(6);  // robtarget extax, jointtarget robax: one allocation per aggregate
      ++i;
      while (true) {
        while (i < e && (t[i].kind == TokenKind::kNewline || t[i].kind == TokenKind::kComment)) ++i;
        if (i >= e) fail(open, "unterminated aggregate (missing ']')");
        if (pc(i) == ']') {
          n.end = t[i].offset + 1;
          ++i;
          return n;
        }
        n.items.push_back(parseElement(i, e));
        while (i < e && (t[i].kind == TokenKind::kNewline || t[i].kind == TokenKind::kComment)) ++i;
        if (i < e && pc(i) == ',') {
          ++i;
        } else if (!(i < e && pc(i) == ']')) {
          if (i >= e) fail(open, "unterminated aggregate (missing ']')");
          fail(t[i].offset, "unexpected '" + std::string(f_.text(t[i])) + "' in aggregate");
        }
      }
    }
    // scalar: tokens until ',' or ']' at depth 0
    const std::size_t s = i;
    int depth = 0;
    while (i < e) {
      const char x = pc(i);
      if (x == '(' || x == '[') ++depth;
      if ((x == ')' || x == ']') && depth == 0) break;
      if (x == ')' || x == ']') --depth;
      if (x == ',' && depth == 0) break;
      if (t[i].kind == TokenKind::kNewline || t[i].kind == TokenKind::kComment) {
        if (i == s) {
          ++i;
          continue;
        }
        break;
      }
      ++i;
    }
    if (i == s) fail(t[s].offset, "empty element in aggregate");
    n.end = t[i - 1].offset + t[i - 1].length;
    n.tb = s;
    n.te = i;
    const bool sign = pc(s) == '-' || pc(s) == '+';
    if (t[s].kind == TokenKind::kNumber || sign) {
      const std::string_view txt = std::string_view(f_.bytes).substr(n.begin, n.end - n.begin);
      const bool one =
          (i - s == 1 && !sign) || (i - s == 2 && sign && t[s + 1].kind == TokenKind::kNumber);
      const std::size_t num = sign ? s + 1 : s;
      if (sign && num < i && (t[num].kind == TokenKind::kIdentifier || (pc(num) == '('))) {
        return n;  // a signed expression (`-Shift`, `-(a+5)`): evaluated where it is used
      }
      if (sign && (num >= i || t[num].kind != TokenKind::kNumber))
        fail(n.begin, "broken number '" + std::string(txt) + "'");
      if (!one) {
        // an expression unless the number runs straight into more number/identifier characters
        const Token& a = t[num];
        if (num + 1 < i && t[num + 1].offset == a.offset + a.length &&
            (t[num + 1].kind == TokenKind::kNumber || t[num + 1].kind == TokenKind::kIdentifier)) {
          fail(n.begin, "broken number '" + std::string(txt) + "'");
        }
        return n;
      }
      const auto v = parseNumber(txt);
      if (!v) fail(n.begin, "broken number '" + std::string(txt) + "'");
      n.number = true;
      n.value = *v;
    } else if (i - s == 1 && t[s].kind == TokenKind::kIdentifier) {
      n.ident = f_.text(t[s]);
    }
    return n;
  }

  Node parseValue(std::size_t b, std::size_t e) {
    std::size_t i = b;
    Node n = parseElement(i, e);
    while (i < e && (tok_[i].kind == TokenKind::kNewline || tok_[i].kind == TokenKind::kComment))
      ++i;
    if (i < e && n.list)
      fail(tok_[i].offset, "unexpected '" + std::string(f_.text(tok_[i])) + "' after aggregate");
    return n;
  }

  /// Value of the expression in tokens [b, e): numbers, `num` constants declared above, + - * /
  /// and parentheses; nullopt when anything else (a variable set at run time, a function call).
  std::optional<double> evaluate(std::size_t b, std::size_t e) const {
    std::vector<std::size_t> tk;
    for (std::size_t k = b; k < e; ++k) {
      const TokenKind kind = tok_[k].kind;
      if (kind != TokenKind::kNewline && kind != TokenKind::kComment) tk.push_back(k);
    }
    std::size_t pos = 0;
    bool ok = true;
    std::function<double()> expr;
    auto peek = [&]() -> std::string_view {
      return pos < tk.size() ? f_.text(tok_[tk[pos]]) : std::string_view();
    };
    std::function<double()> factor = [&]() -> double {
      if (pos >= tk.size()) {
        ok = false;
        return 0;
      }
      const Token& x = tok_[tk[pos]];
      const std::string_view s = f_.text(x);
      if (x.kind == TokenKind::kPunct && (s == "-" || s == "+")) {
        ++pos;
        const double v = factor();
        return s == "-" ? -v : v;
      }
      if (x.kind == TokenKind::kPunct && s == "(") {
        ++pos;
        const double v = expr();
        if (peek() != ")") ok = false;
        ++pos;
        return v;
      }
      ++pos;
      if (x.kind == TokenKind::kNumber) {
        const auto v = parseNumber(s);
        if (!v) ok = false;
        return v.value_or(0);
      }
      if (x.kind == TokenKind::kIdentifier) {
        const auto it = nums_.find(upper(s));
        if (it != nums_.end()) return it->second;
      }
      ok = false;
      return 0;
    };
    auto term = [&]() -> double {
      double v = factor();
      while (ok && (peek() == "*" || peek() == "/")) {
        const bool mul = peek() == "*";
        ++pos;
        const double w = factor();
        if (!mul && w == 0) ok = false;
        v = mul ? v * w : (w != 0 ? v / w : 0);
      }
      return v;
    };
    expr = [&]() -> double {
      double v = term();
      while (ok && (peek() == "+" || peek() == "-")) {
        const bool add = peek() == "+";
        ++pos;
        const double w = term();
        v = add ? v + w : v - w;
      }
      return v;
    };
    if (tk.empty()) return std::nullopt;
    const double v = expr();
    if (!ok || pos != tk.size() || !std::isfinite(v)) return std::nullopt;
    return v;
  }

  /// A target component: a number, or (RAPID allows it) a named constant or expression, kept
  /// verbatim; its value when roprec can evaluate it, else reported as unresolved.
  NumberField component(const Node& n, const char* what) {
    if (n.number || n.list) return field(n, what);
    NumberField f;
    p_.expressions.emplace_back(std::string_view(f_.bytes).substr(n.begin, n.end - n.begin));
    f.setExpression(static_cast<std::uint32_t>(p_.expressions.size()));
    const std::string& text = p_.expressions.back();
    if (const auto v = evaluate(n.tb, n.te)) {
      f.value = *v;
      f.expr_known = true;
    } else {
      unresolved(text, n.begin,
                 std::string(what) + " component '" + text +
                     "' is not a constant roprec can evaluate (set at run time); its value is "
                     "unknown");
    }
    return f;
  }

  NumberField field(const Node& n, const char* what) const {
    if (!n.number) fail(n.begin, std::string(what) + " is not a number");
    return tokenField(f_, 0, n.begin, n.end, n.value);
  }

  void shape(const Node& n, std::size_t count, const char* what) const {
    if (!n.list || n.items.size() != count) {
      fail(n.begin, std::string(what) + " needs " + std::to_string(count) + " elements");
    }
  }

  static Pose poseOf(const Node& n) {
    Pose T = Pose::Identity();
    T.translation() =
        Vec3(n.items[0].items[0].value, n.items[0].items[1].value, n.items[0].items[2].value) *
        1e-3;
    Eigen::Quaterniond q(n.items[1].items[0].value, n.items[1].items[1].value,
                         n.items[1].items[2].value, n.items[1].items[3].value);
    if (q.norm() > 0) q.normalize();
    T.linear() = q.toRotationMatrix();
    return T;
  }

  void checkPose(const Node& n, const char* what) const {
    shape(n, 2, what);
    shape(n.items[0], 3, what);
    shape(n.items[1], 4, what);
    for (const Node& a : n.items[0].items) field(a, what);
    for (const Node& a : n.items[1].items) field(a, what);
  }

  /// pc(k) for k < e, else 0.
  char pcIn(std::size_t k, std::size_t e) const { return k < e ? pc(k) : '\0'; }

  /// `[sign] number` at tok_[i] (i < e) as a field; advances i. False for anything else or a
  /// number parseNumber refuses.
  bool plainNumber(std::size_t& i, std::size_t e, NumberField& f) const {
    const std::size_t s = i;
    if (pcIn(i, e) == '-' || pcIn(i, e) == '+') ++i;
    if (i >= e || tok_[i].kind != TokenKind::kNumber) return false;
    const std::uint32_t end = tok_[i].offset + tok_[i].length;
    if (end - tok_[s].offset > NumberField::kMaxLength) return false;  // tokenField refuses it
    const auto v =
        parseNumber(std::string_view(f_.bytes).substr(tok_[s].offset, end - tok_[s].offset));
    if (!v) return false;
    f.file = 0;
    f.offset = tok_[s].offset;
    f.length = end - tok_[s].offset;
    f.value = *v;
    ++i;
    return true;
  }

  /// An inline robtarget written in plain numbers on one line, the OLP form
  /// `[[x,y,z],[q1,q2,q3,q4],[cf1,cf4,cf6,cfx],[eax_a,..,eax_f]]`, in tokens [b, e): the target
  /// makeRobtarget(parseValue(b, e), name) makes, without building the tree. -1 for any other
  /// text (names, expressions, comments, line breaks, malformed numbers): the general path then
  /// reads it and reports its errors.
  int plainRobtarget(std::size_t b, std::size_t e, std::string_view name) {
    static constexpr std::size_t kCount[4] = {3, 4, 4, 6};
    std::array<NumberField, 17> v;
    std::size_t i = b;
    if (pcIn(i++, e) != '[') return -1;
    std::size_t n = 0;
    for (std::size_t g = 0; g < 4; ++g) {
      if (g > 0 && pcIn(i++, e) != ',') return -1;
      if (pcIn(i++, e) != '[') return -1;
      for (std::size_t k = 0; k < kCount[g]; ++k) {
        if (k > 0 && pcIn(i++, e) != ',') return -1;
        if (!plainNumber(i, e, v[n++])) return -1;
      }
      if (pcIn(i++, e) != ']') return -1;
    }
    if (i + 1 != e || pcIn(i, e) != ']') return -1;
    Target t;
    t.name = name;
    t.file = 0;
    t.line = f_.lineOf(tok_[b].offset);
    t.kind = TargetKind::kCartesian;
    t.orientation = Orientation::kQuaternion;
    t.config.vendor = Vendor::kAbb;
    for (std::size_t k = 0; k < 3; ++k) t.pos[k] = v[k];
    for (std::size_t k = 0; k < 4; ++k) t.rot[k] = v[3 + k];
    for (std::size_t k = 0; k < 4; ++k) {
      t.cf_fields[k] = v[7 + k];
      t.config.cf[k] = toInt(std::round(v[7 + k].value), 0);
    }
    for (std::size_t k = 0; k < 6; ++k) t.ext[k] = v[11 + k];
    return add(std::move(t), name);
  }

  int makeRobtarget(const Node& n, std::string_view name) {
    shape(n, 4, "robtarget");
    shape(n.items[0], 3, "robtarget trans");
    shape(n.items[1], 4, "robtarget rot");
    shape(n.items[2], 4, "robtarget robconf");
    shape(n.items[3], 6, "robtarget extax");
    Target t;
    t.name = name;
    t.file = 0;
    t.line = f_.lineOf(n.begin);
    t.kind = TargetKind::kCartesian;
    t.orientation = Orientation::kQuaternion;
    t.config.vendor = Vendor::kAbb;
    for (std::size_t k = 0; k < 3; ++k)
      t.pos[k] = component(n.items[0].items[k], "robtarget trans");
    for (std::size_t k = 0; k < 4; ++k) t.rot[k] = component(n.items[1].items[k], "robtarget rot");
    for (std::size_t k = 0; k < 4; ++k) {
      t.cf_fields[k] = component(n.items[2].items[k], "robtarget robconf");
      t.config.cf[k] = toInt(std::round(t.cf_fields[k].value), 0);
    }
    // A robconf roprec cannot evaluate states no configuration: the branch is then chosen as
    // for a program without one, never from a placeholder 0.
    for (const NumberField& f : t.cf_fields)
      if (!f.known()) t.config.vendor = Vendor::kNone;
    for (std::size_t k = 0; k < 6; ++k)
      t.ext[k] = component(n.items[3].items[k], "robtarget extax");
    return add(std::move(t), name);
  }

  int makeJointtarget(const Node& n, std::string_view name) {
    shape(n, 2, "jointtarget");
    shape(n.items[0], 6, "jointtarget robax");
    shape(n.items[1], 6, "jointtarget extax");
    Target t;
    t.name = name;
    t.file = 0;
    t.line = f_.lineOf(n.begin);
    t.kind = TargetKind::kJoint;
    for (std::size_t k = 0; k < 6; ++k)
      t.joints[k] = component(n.items[0].items[k], "jointtarget robax");
    for (std::size_t k = 0; k < 6; ++k)
      t.ext[k] = component(n.items[1].items[k], "jointtarget extax");
    return add(std::move(t), name);
  }

  /// Appends t, declared as `name` (a view of the file; empty for inline targets).
  int add(Target t, std::string_view name) {
    p_.target_list.push_back(std::move(t));
    const int idx = static_cast<int>(p_.target_list.size() - 1);
    if (name.empty()) return idx;
    if (!streamed_) {
      targets_[name] = idx;
    } else if (targets_.find(name) != nullptr) {  // a later declaration replaces it
      targets_[name] = idx;
    } else {  // the window's bytes go: the key is a name of the reader's own
      targets_[std::string_view(names_.emplace_back(name))] = idx;
    }
    return idx;
  }

  ToolState toolFrom(const Node& n) {
    // [robhold, [[x,y,z],[q]], loaddata]
    if (!n.list || n.items.size() < 2) fail(n.begin, "tooldata needs [robhold, tframe, tload]");
    checkPose(n.items[1], "tooldata tframe");
    return ToolState{poseOf(n.items[1]), true, iequals(n.items[0].ident, "FALSE"),
                     f_.lineOf(n.begin)};
  }

  ToolState wobjFrom(const Node& n) {
    // [robhold, ufprog, ufmec, uframe, oframe]
    if (!n.list || n.items.size() != 5) fail(n.begin, "wobjdata needs 5 elements");
    checkPose(n.items[3], "wobjdata uframe");
    checkPose(n.items[4], "wobjdata oframe");
    const bool moving = iequals(n.items[0].ident, "TRUE") || iequals(n.items[1].ident, "FALSE");
    return ToolState{poseOf(n.items[3]) * poseOf(n.items[4]), true, moving, f_.lineOf(n.begin)};
  }

  void declaration(std::size_t b, std::size_t e) {
    ++tables_version_;
    const std::vector<Token>& t = tok_;
    std::size_t i = b;
    while (i < e && (iequals(f_.text(t[i]), "LOCAL") || iequals(f_.text(t[i]), "TASK"))) ++i;
    ++i;  // CONST/VAR/PERS
    if (i + 1 >= e) return;
    const std::string type = upper(f_.text(t[i]));
    const std::string_view name = f_.text(t[i + 1]);
    const std::size_t name_off = t[i + 1].offset;
    i += 2;
    if (i < e && is1(f_.text(t[i]), '{')) return;  // arrays: runtime
    const std::string key = upper(name);
    if (i >= e || f_.text(t[i]) != ":=") {
      if (type == "TOOLDATA")
        tools_[key] = ToolState{Pose::Identity(), false, false, f_.lineOf(name_off)};
      if (type == "WOBJDATA")
        wobjs_[key] = ToolState{Pose::Identity(), false, false, f_.lineOf(name_off)};
      return;
    }
    ++i;
    if (i >= e) fail(t[i - 1].offset, "declaration without a value");
    if (type == "NUM" || type == "DNUM") {
      if (const auto v = evaluate(i, e)) {
        nums_[key] = *v;
      } else {
        nums_.erase(key);
      }
      return;
    }
    if (f_.text(t[i]) != "[") return;  // expressions: runtime
    if (type == "ROBTARGET" && plainRobtarget(i, e, name) >= 0) return;
    const Node v = parseValue(i, e);
    if (type == "ROBTARGET") {
      makeRobtarget(v, name);
    } else if (type == "JOINTTARGET") {
      makeJointtarget(v, name);
    } else if (type == "TOOLDATA") {
      tools_[key] = toolFrom(v);
    } else if (type == "WOBJDATA") {
      wobjs_[key] = wobjFrom(v);
    } else if (type == "SPEEDDATA") {
      if (v.list && !v.items.empty() && v.items[0].number) speeds_[key] = v.items[0].value;
    }
  }

  void assignment(std::size_t b, std::size_t eq, std::size_t e) {
    ++tables_version_;
    const std::vector<Token>& t = tok_;
    const std::string name = upper(f_.text(t[b]));
    std::string member;
    for (std::size_t k = b + 1; k < eq; ++k) member += upper(f_.text(t[k]));
    if (member.empty() && nums_.count(name) != 0) {
      // a num variable set in the program flow: its value below is the assigned one when known
      if (const auto v = evaluate(eq + 1, e)) {
        nums_[name] = *v;
      } else {
        nums_.erase(name);
      }
      return;
    }
    if (eq + 1 >= e || f_.text(t[eq + 1]) != "[") return;
    const Node v = parseValue(eq + 1, e);
    if (member.empty()) {
      if (tools_.count(name) != 0) tools_[name] = toolFrom(v);
      if (wobjs_.count(name) != 0) wobjs_[name] = wobjFrom(v);
      if (speeds_.count(name) != 0 && v.list && !v.items.empty() && v.items[0].number)
        speeds_[name] = v.items[0].value;
      return;
    }
    if (member == ".TFRAME" && tools_.count(name) != 0) {
      checkPose(v, "tframe");
      tools_[name].pose = poseOf(v);
      tools_[name].resolved = true;
      tools_[name].line = f_.lineOf(t[b].offset);
    } else if ((member == ".UFRAME" || member == ".OFRAME") && wobjs_.count(name) != 0) {
      checkPose(v, member == ".UFRAME" ? "uframe" : "oframe");
      ToolState& w = wobjs_[name];
      // track uframe and oframe separately
      auto& parts = wobj_parts_[name];
      if (!parts.set) {
        parts.uframe = w.pose;
        parts.oframe = Pose::Identity();
        parts.set = true;
      }
      (member == ".UFRAME" ? parts.uframe : parts.oframe) = poseOf(v);
      w.pose = parts.uframe * parts.oframe;
      w.resolved = true;
      w.line = f_.lineOf(t[b].offset);
    }
  }

  struct WobjParts {
    bool set{false};
    Pose uframe{Pose::Identity()};
    Pose oframe{Pose::Identity()};
  };
  std::unordered_map<std::string, WobjParts> wobj_parts_;

  Frame frameOf(const std::unordered_map<std::string, ToolState>& table, const std::string& ref,
                std::size_t off, bool tool) {
    const auto it = table.find(upper(ref));
    if (it == table.end()) {
      unresolved(
          ref, off,
          tool ? "tooldata not declared in the module" : "wobjdata not declared in the module");
      return Frame{ref, false, Pose::Identity(), -1, 0};
    }
    if (!it->second.resolved)
      unresolved(
          ref, off,
          tool ? "tooldata has no value in the module" : "wobjdata has no value in the module");
    if (it->second.stationary && reported_.emplace("STATIONARY:" + upper(ref), true).second) {
      p_.notes.push_back(
          ref +
          (tool ? ": stationary tool (robhold FALSE)" : ": robot-held or moving work object") +
          " — base and tool swap roles; poses reported as written");
    }
    return Frame{ref, it->second.resolved, it->second.pose, 0, it->second.line};
  }

  struct Arg {
    std::size_t b{0};
    std::size_t e{0};
  };
  std::vector<Arg> pos_;                         ///< motion(): positional arguments (reused)
  std::vector<std::pair<std::string, Arg>> sw_;  ///< motion(): `\switch` arguments (reused)

  /// internFrame(frameOf(...)) with the last answer per role reused while the tool/wobj tables
  /// and p_.frames are unchanged (frameOf's reports are made once per name, so none is skipped).
  struct FrameMemo {
    std::string ref;
    std::uint64_t version{0};
    std::size_t frames{0};
    int index{-1};
  };
  FrameMemo tool_memo_, wobj_memo_;
  std::uint64_t tables_version_{1};  ///< bumped by every declaration and assignment

  int frameIndex(bool tool, const std::string& ref, std::size_t off) {
    FrameMemo& m = tool ? tool_memo_ : wobj_memo_;
    if (m.index >= 0 && m.version == tables_version_ && m.frames == p_.frames.size() &&
        m.ref == ref)
      return m.index;
    m.index = internFrame(p_, frameOf(tool ? tools_ : wobjs_, ref, off, tool));
    m.ref = ref;
    m.version = tables_version_;
    m.frames = p_.frames.size();
    return m.index;
  }

  int targetArg(const Arg& a, Motion& m, bool joint) {
    const std::vector<Token>& t = tok_;
    if (a.b >= a.e) fail(t[a.b > 0 ? a.b - 1 : 0].offset, "motion without a target");
    if (f_.text(t[a.b]) != "[") {  // literal targets: the target itself is the text
      m.target_text = p_.addUniqueText(std::string_view(f_.bytes).substr(
          t[a.b].offset, t[a.e - 1].offset + t[a.e - 1].length - t[a.b].offset));
    }
    if (is1(f_.text(t[a.b]), '[')) {
      if (!joint) {
        const int plain = plainRobtarget(a.b, a.e, {});
        if (plain >= 0) return plain;
      }
      const Node n = parseValue(a.b, a.e);
      return joint ? makeJointtarget(n, "") : makeRobtarget(n, "");
    }
    if (a.e - a.b == 1 && t[a.b].kind == TokenKind::kIdentifier) {
      if (const int* idx = targets_.find(f_.text(t[a.b]))) return *idx;
      unresolved(std::string(f_.text(t[a.b])), t[a.b].offset, "target not declared in the module");
      m.derivation = p_.addText("undeclared");
      return -1;
    }
    const std::string fn = upper(f_.text(t[a.b]));
    if ((fn == "OFFS" || fn == "RELTOOL") && a.e - a.b > 3 && is1(f_.text(t[a.b + 1]), '(') &&
        t[a.b + 2].kind == TokenKind::kIdentifier) {
      m.derivation = p_.addText(fn == "OFFS" ? "Offs" : "RelTool");
      const int* const idx = targets_.find(f_.text(t[a.b + 2]));
      if (idx == nullptr) {
        unresolved(std::string(f_.text(t[a.b + 2])), t[a.b + 2].offset,
                   "target not declared in the module");
        return -1;
      }
      // literal displacements dx, dy, dz [\Rx:=..][\Ry:=..][\Rz:=..]
      std::vector<double> d;
      std::array<double, 3> r{0, 0, 0};
      bool literal = true;
      std::size_t k = a.b + 3;
      while (k < a.e && literal) {
        if (is1(f_.text(t[k]), ',') || is1(f_.text(t[k]), ')')) {
          ++k;
          continue;
        }
        if (f_.text(t[k]) == "\\" && k + 3 < a.e && f_.text(t[k + 2]) == ":=") {
          const std::string sw = upper(f_.text(t[k + 1]));
          std::size_t s = k + 3;
          std::size_t q = s;
          while (q < a.e && f_.text(t[q]) != "," && f_.text(t[q]) != ")" && f_.text(t[q]) != "\\")
            ++q;
          const auto v = q > s ? parseNumber(std::string_view(f_.bytes).substr(
                                     t[s].offset, t[q - 1].offset + t[q - 1].length - t[s].offset))
                               : std::nullopt;
          if (!v) literal = false;
          if (v && sw == "RX") r[0] = *v;
          if (v && sw == "RY") r[1] = *v;
          if (v && sw == "RZ") r[2] = *v;
          k = q;
          continue;
        }
        std::size_t q = k;
        while (q < a.e && f_.text(t[q]) != "," && f_.text(t[q]) != ")" && f_.text(t[q]) != "\\")
          ++q;
        const auto v = q > k ? parseNumber(std::string_view(f_.bytes).substr(
                                   t[k].offset, t[q - 1].offset + t[q - 1].length - t[k].offset))
                             : std::nullopt;
        if (!v) literal = false;
        if (v) d.push_back(*v);
        k = q;
      }
      if (literal && d.size() == 3) {
        m.has_offset = true;
        m.offset_in_tool = fn == "RELTOOL";
        Pose offset = Pose::Identity();
        offset.translation() = Vec3(d[0], d[1], d[2]) * 1e-3;
        offset.linear() = (Eigen::AngleAxisd(r[0] * kDeg, Vec3::UnitX()) *
                           Eigen::AngleAxisd(r[1] * kDeg, Vec3::UnitY()) *
                           Eigen::AngleAxisd(r[2] * kDeg, Vec3::UnitZ()))
                              .toRotationMatrix();
        m.offset.set(offset);
      }
      return *idx;
    }
    m.derivation = p_.addText("runtime");
    return -1;
  }

  void motion(std::size_t b, std::size_t e) {
    const std::vector<Token>& t = tok_;
    Motion m;
    m.instruction = p_.addText(f_.text(t[b]));
    const std::string kw = upper(f_.text(t[b]));
    m.file = 0;
    m.line = f_.lineOf(t[b].offset);
    const bool absj = kw.rfind("MOVEABSJ", 0) == 0;
    const bool circ = kw.rfind("MOVEC", 0) == 0 || kw == "TRIGGC";
    m.type = absj || kw.rfind("MOVEJ", 0) == 0 || kw == "TRIGGJ" ? MotionType::kJoint
             : circ                                              ? MotionType::kCircular
                                                                 : MotionType::kLinear;
    m.config_honoured = m.type == MotionType::kJoint ? conf_j_ : conf_l_;
    // split arguments
    std::vector<Arg>& pos = pos_;
    std::vector<std::pair<std::string, Arg>>& sw = sw_;
    pos.clear();
    sw.clear();
    std::size_t i = b + 1;
    int depth = 0;
    std::size_t s = i;
    bool in_switch = false;
    std::string sw_name;
    auto close = [&](std::size_t k) {
      if (in_switch) {
        std::size_t vb = s;
        if (vb < k && f_.text(t[vb]) == ":=") ++vb;
        sw.emplace_back(sw_name, Arg{vb, k});
      } else if (k > s) {
        pos.push_back(Arg{s, k});
      }
      in_switch = false;
    };
    for (; i < e; ++i) {
      const char x = pc(i);
      if (x == '[' || x == '(') ++depth;
      if (x == ']' || x == ')') --depth;
      if (depth != 0) continue;
      if (x == ',') {
        close(i);
        s = i + 1;
      } else if (x == '\\') {
        close(i);
        in_switch = true;
        sw_name = i + 1 < e ? upper(f_.text(t[i + 1])) : "";
        s = i + 2;
        ++i;
      }
    }
    close(e);
    // drop leading/trailing newline tokens inside args
    auto trim = [&](Arg a) {
      while (a.b < a.e &&
             (t[a.b].kind == TokenKind::kNewline || t[a.b].kind == TokenKind::kComment))
        ++a.b;
      while (a.e > a.b &&
             (t[a.e - 1].kind == TokenKind::kNewline || t[a.e - 1].kind == TokenKind::kComment))
        --a.e;
      return a;
    };
    for (Arg& a : pos) a = trim(a);
    std::size_t ip = 0;
    if (circ) ip = 1;
    std::size_t speed_i = ip + 1;
    std::size_t zone_i = ip + 2;
    std::size_t tool_i = ip + 3;
    if (kw == "TRIGGL" || kw == "TRIGGJ" || kw == "TRIGGC") {
      zone_i = ip + 3;
      tool_i = ip + 4;
    }
    if (kw == "SEARCHL" || kw == "SEARCHJ") {
      ip = 2;
      speed_i = 3;
      zone_i = 99;
      tool_i = 4;
    }
    if (pos.size() <= ip) fail(t[b].offset, std::string(f_.text(t[b])) + " without a target");
    if (circ) {
      Motion aux = m;
      m.aux = targetArg(pos[0], aux, false);
    }
    m.target = targetArg(pos[ip], m, absj);
    auto argText = [&](const Arg& a) {
      return a.b < a.e ? f_.bytes.substr(t[a.b].offset,
                                         t[a.e - 1].offset + t[a.e - 1].length - t[a.b].offset)
                       : std::string();
    };
    if (speed_i < pos.size()) {
      const std::string speed = argText(pos[speed_i]);
      m.speed_text = p_.addText(speed);
      const std::string u = upper(speed);
      if (u.size() > 1 && u[0] == 'V' && isDigit(u[1])) {
        m.speed_mm_s = parseNumber(u.substr(1)).value_or(-1.0);
      } else if (speeds_.count(u) != 0) {
        m.speed_mm_s = speeds_[u];
      } else if (!u.empty() && u[0] == '[') {
        const Node n = parseValue(pos[speed_i].b, pos[speed_i].e);
        if (n.list && !n.items.empty() && n.items[0].number) m.speed_mm_s = n.items[0].value;
      }
    }
    if (zone_i < pos.size()) {
      const std::string zone = argText(pos[zone_i]);
      m.zone_text = p_.addText(zone);
      m.fine = iequals(zone, "fine");
    }
    std::string tool = tool_i < pos.size() ? argText(pos[tool_i]) : "tool0";
    std::string wobj = "wobj0";
    for (const auto& [name, a] : sw) {
      if (name == "WOBJ") wobj = argText(trim(a));
      if (name == "V") m.speed_mm_s = parseNumber(argText(trim(a))).value_or(m.speed_mm_s);
    }
    if (m.speed_mm_s < 0 && m.speed_mm_s != -1.0) {
      // a speeddata whose v_tcp is below zero (-1 is "not stated", Motion's default)
      fail(t[b].offset, std::string(f_.text(t[b])) + ": speed " + p_.text(m.speed_text) + " is " +
                            numberText(m.speed_mm_s) +
                            " mm/s: no motion runs at it; hint: v_tcp is > 0 mm/s");
    }
    const std::size_t off = t[b].offset;
    m.tool = frameIndex(true, tool, off);
    m.base = frameIndex(false, wobj, off);
    p_.motions.push_back(std::move(m));
    const int mi = static_cast<int>(p_.motions.size() - 1);
    const Motion& mm = p_.motions.back();
    if (mm.target >= 0) p_.target_list[static_cast<std::size_t>(mm.target)].uses.push_back(mi);
    if (mm.aux >= 0) p_.target_list[static_cast<std::size_t>(mm.aux)].uses.push_back(mi);
  }

  void statement(std::size_t b, std::size_t e) {
    const std::vector<Token>& t = tok_;
    const std::string_view w = f_.text(t[b]);
    if (iequals(w, "LOCAL") || iequals(w, "TASK") || iequals(w, "CONST") || iequals(w, "VAR") ||
        iequals(w, "PERS")) {
      declaration(b, e);
      return;
    }
    if (iequals(w.substr(0, 4), "MOVE") || iequals(w, "TRIGGL") || iequals(w, "TRIGGJ") ||
        iequals(w, "TRIGGC") || iequals(w, "SEARCHL") || iequals(w, "SEARCHJ")) {
      if (!iequals(w, "MOVEEXTJ")) {
        motion(b, e);
        return;
      }
    }
    if ((iequals(w, "CONFL") || iequals(w, "CONFJ")) && b + 2 < e) {
      const bool on = iequals(f_.text(t[b + 2]), "On");
      (iequals(w, "CONFL") ? conf_l_ : conf_j_) = on;
      return;
    }
    if (iequals(w, "WAITTIME") && b + 1 < e) {
      p_.addMarker("dwell " + std::string(f_.text(t[e - 1])) + " s");
      return;
    }
    for (std::size_t k = b; k < e; ++k) {
      if (f_.text(t[k]) == ":=" && t[k].kind == TokenKind::kPunct) {
        assignment(b, k, e);
        return;
      }
    }
    const std::string uw = upper(w);
    if (t[b].kind == TokenKind::kIdentifier &&
        (uw.find("SPINDLE") != std::string::npos || uw.find("DRILL") != std::string::npos)) {
      p_.addMarker("call " + std::string(f_.text(t[b])));
    }
    // other statements: kept verbatim; aggregates in them still validated
    for (std::size_t k = b; k < e; ++k) {
      if (is1(f_.text(t[k]), '[') && t[k].kind == TokenKind::kPunct) {
        std::size_t q = k;
        parseElement(q, e);
        k = q > k ? q - 1 : k;
      }
    }
  }
};

}  // namespace

void parseRapid(Program& p) { RapidReader(p).run(); }

struct RapidStream::Reader : RapidReader {
  using RapidReader::RapidReader;
};

RapidStream::RapidStream(Program& p) : r_(std::make_unique<Reader>(p, true)) { r_->start(); }
RapidStream::~RapidStream() = default;
void RapidStream::lines(bool last) { r_->lines(last); }
std::size_t RapidStream::carry() const { return r_->carry(); }
void RapidStream::finish() { r_->finish(); }
void RapidStream::retiredTargets(std::size_t begin, std::size_t end) {
  r_->retiredTargets(begin, end);
}

}  // namespace roprec::postproc
