/// KUKA KRL reader (`.src` + `.dat`), docs/programs.md §2.
#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <span>
#include <unordered_map>

#include "compensator/support/c_format.hpp"
#include "compensator/support/error.hpp"
#include "postproc/dialects.hpp"
#include "postproc/lexer.hpp"

namespace roprec::postproc {
namespace {

struct Component {
  std::string_view name;  // as written (compare with iequals)
  std::uint32_t begin{0};
  std::uint32_t end{0};
  enum Kind { kNumber, kLiteral, kString, kOther, kNested } kind{kOther};
  double value{0};
};

// An aggregate's components live in the reader's scratch vector (no allocation per aggregate):
// `comps` is valid until the next parseAggregate() call.
struct Aggregate {
  std::string_view type;  // as written, "" when untyped
  std::span<const Component> comps;
  std::uint32_t open{0};
  std::uint32_t close{0};
  [[nodiscard]] const Component* find(std::string_view n) const {
    for (const Component& c : comps) {
      if (iequals(c.name, n)) return &c;
    }
    return nullptr;
  }
};

std::optional<int> parseKrlLiteralInt(std::string_view s) {
  // 'B0101' binary, 'H1F' hex
  if (s.size() < 3 || s.front() != '\'' || s.back() != '\'') return std::nullopt;
  const char base = static_cast<char>(std::toupper(static_cast<unsigned char>(s[1])));
  const std::string_view d = s.substr(2, s.size() - 3);
  if (d.empty() || d.size() > 30) return std::nullopt;
  int v = 0;
  for (const char c : d) {
    int digit = -1;
    if (c >= '0' && c <= '9') digit = c - '0';
    if (c >= 'a' && c <= 'f') digit = c - 'a' + 10;
    if (c >= 'A' && c <= 'F') digit = c - 'A' + 10;
    if (base == 'B' && (digit < 0 || digit > 1)) return std::nullopt;
    if (base == 'H' && digit < 0) return std::nullopt;
    if (base != 'B' && base != 'H') return std::nullopt;
    v = v * (base == 'B' ? 2 : 16) + digit;
  }
  return v;
}

// ASCII case-insensitive prefix / substring tests (upper(s) and then rfind/find, no copy).
bool istartsWith(std::string_view s, std::string_view w) {
  return s.size() >= w.size() && iequals(s.substr(0, w.size()), w);
}

bool icontains(std::string_view s, std::string_view w) {
  if (w.empty()) return true;
  const char first = asciiUpper(w[0]);  // compared first: most places fail on it
  for (std::size_t i = 0; i + w.size() <= s.size(); ++i) {
    if (asciiUpper(s[i]) == first && iequals(s.substr(i, w.size()), w)) return true;
  }
  return false;
}

int sigDigits(std::string_view s) {
  int n = 0;
  bool nz = false;
  for (const char c : s) {
    if (c == 'e' || c == 'E') break;
    if (isDigit(c)) {
      if (c != '0') nz = true;
      if (nz) ++n;
    }
  }
  return n;
}

// The aggregate at c ('{'), its components appended to `comps` (a nested aggregate's own
// components are dropped again); Aggregate::comps is left to the caller. Reads only the tokens
// and bytes of c's file, so the reader and the read-ahead of a window (KrlStream::lexWindow)
// give the same aggregate. Throws InputError (failAt) where the reader stops.
Aggregate readComponents(TokenCursor& c, std::vector<Component>& comps) {
  const SourceFile& f = c.file();
  Aggregate a;
  const Token& open = c.next();  // '{'
  a.open = open.offset;
  if (c.isKind(TokenKind::kIdentifier) && c.isPunct(':', 1)) {
    a.type = c.text();
    c.next();
    c.next();
  }
  while (true) {
    if (c.done() || c.isKind(TokenKind::kNewline) || c.isKind(TokenKind::kComment)) {
      failAt(f, open.offset, "unterminated aggregate (missing '}')");
    }
    if (c.isPunct('}')) {
      a.close = c.next().offset;
      return a;
    }
    if (c.isPunct(',')) {
      c.next();
      continue;
    }
    Component comp;
    if (!c.isKind(TokenKind::kIdentifier))
      failAt(f, c.peek().offset, "expected a component name in aggregate");
    comp.name = c.text();
    c.next();
    if (c.isPunct('[')) {  // POINT2[]
      while (!c.done() && !c.isPunct(']') && !c.isKind(TokenKind::kNewline)) c.next();
      if (c.isPunct(']')) c.next();
    }
    if (c.isPunct('{')) {
      const std::size_t mark = comps.size();
      const Aggregate nested = readComponents(c, comps);
      comps.resize(mark);
      comp.kind = Component::kNested;
      comp.begin = nested.open;
      comp.end = nested.close + 1;
      comps.push_back(comp);
      continue;
    }
    const std::size_t start = c.index();
    while (!c.done() && !c.isPunct(',') && !c.isPunct('}') && !c.isKind(TokenKind::kNewline) &&
           !c.isKind(TokenKind::kComment)) {
      c.next();
    }
    const std::size_t stop = c.index();
    if (stop == start)
      failAt(f, c.peek().offset, "component " + upper(comp.name) + " has no value");
    const Token& t0 = f.tokens[start];
    const Token& tl = f.tokens[stop - 1];
    comp.begin = t0.offset;
    comp.end = tl.offset + tl.length;
    const bool signed_start =
        t0.kind == TokenKind::kPunct && (f.bytes[t0.offset] == '-' || f.bytes[t0.offset] == '+');
    if (t0.kind == TokenKind::kNumber || signed_start) {
      const bool one =
          (stop - start == 1 && !signed_start) ||
          (stop - start == 2 && signed_start && f.tokens[start + 1].kind == TokenKind::kNumber);
      const std::string_view txt =
          std::string_view(f.bytes).substr(comp.begin, comp.end - comp.begin);
      if (!one)
        failAt(f, comp.begin,
               "broken number '" + std::string(txt) + "' in component " + upper(comp.name));
      const auto v = parseNumber(txt);
      if (!v) failAt(f, comp.begin, "broken number '" + std::string(txt) + "'");
      comp.kind = Component::kNumber;
      comp.value = *v;
    } else if (t0.kind == TokenKind::kString) {
      const std::string_view s = f.text(t0);
      if (s.size() < 2 || s.back() != s.front()) failAt(f, t0.offset, "unterminated string");
      comp.kind = Component::kString;
      if (const auto v = parseKrlLiteralInt(s)) {
        comp.kind = Component::kLiteral;
        comp.value = *v;
      }
    } else {
      comp.kind = Component::kOther;
    }
    comps.push_back(comp);
  }
}

bool isApprox(std::string_view w) {
  return w.size() == 5 && (iequals(w, "C_DIS") || iequals(w, "C_PTP") || iequals(w, "C_VEL") ||
                           iequals(w, "C_ORI") || iequals(w, "C_SPL"));
}

bool isMotionKeyword(std::string_view w) {
  static constexpr std::string_view kw[] = {
      "PTP",     "LIN",      "CIRC",     "SPTP",     "SLIN",      "SCIRC", "PTP_REL",
      "LIN_REL", "CIRC_REL", "SPTP_REL", "SLIN_REL", "SCIRC_REL", "SPL"};
  if (w.size() < 3 || w.size() > 9) return false;
  const char c = asciiUpper(w[0]);  // most other lines start with none of these letters
  if (c != 'P' && c != 'L' && c != 'C' && c != 'S') return false;
  for (const std::string_view k : kw) {
    if (iequals(w, k)) return true;
  }
  return false;
}

// The byte of a one-byte punctuation token, else 0.
char punct1(const SourceFile& f, const Token& t) {
  return t.kind == TokenKind::kPunct && t.length == 1 ? f.bytes[t.offset] : '\0';
}

// A motion's target expressions, tokens [from, e) of f after its keyword: split into `exprs` at
// top-level ',' up to an approximation/WITH/CA/# keyword, whose token index it returns (e when
// there is none).
std::size_t splitTargets(const SourceFile& f, std::size_t from, std::size_t e,
                         std::vector<std::pair<std::size_t, std::size_t>>& exprs) {
  exprs.clear();
  std::size_t start = from;
  int depth = 0;
  std::size_t k = from;
  for (; k < e; ++k) {
    const Token& t = f.tokens[k];
    const char p = punct1(f, t);
    if (p == '{' || p == '(' || p == '[') ++depth;
    if (p == '}' || p == ')' || p == ']') --depth;
    if (depth > 0) continue;
    if (p == ',') {
      exprs.emplace_back(start, k);
      start = k + 1;
      continue;
    }
    if (p == '#') break;
    if (t.kind == TokenKind::kIdentifier) {
      const std::string_view tx = f.text(t);
      if (isApprox(tx) || iequals(tx, "WITH") || iequals(tx, "CA")) break;
    }
  }
  exprs.emplace_back(start, k);
  return k;
}

// Slot of a position component in a target: X Y Z A B C, S T, A1..A6, E1..E6 (kNone: other).
enum class Slot { kNone, kPos, kRot, kStatus, kTurn, kJoint, kExt };
struct SlotIndex {
  Slot slot{Slot::kNone};
  std::size_t k{0};
};
SlotIndex slotOf(std::string_view n) {
  if (n.size() == 1) {
    const char c = asciiUpper(n[0]);
    if (c >= 'X' && c <= 'Z') return {Slot::kPos, static_cast<std::size_t>(c - 'X')};
    if (c >= 'A' && c <= 'C') return {Slot::kRot, static_cast<std::size_t>(c - 'A')};
    if (c == 'S') return {Slot::kStatus, 0};
    if (c == 'T') return {Slot::kTurn, 0};
  } else if (n.size() == 2 && n[1] >= '1' && n[1] <= '6') {
    const char c = asciiUpper(n[0]);
    const auto k = static_cast<std::size_t>(n[1] - '1');
    if (c == 'A') return {Slot::kJoint, k};
    if (c == 'E') return {Slot::kExt, k};
  }
  return {};
}

// Stores component c (a number or a KRL literal) of file f (index `file`) in its slot of t.
void setComponent(const SourceFile& f, int file, Target& t, const Component& c, SlotIndex s) {
  if (c.kind == Component::kLiteral && s.slot != Slot::kStatus && s.slot != Slot::kTurn)
    failAt(f, c.begin, "component " + upper(c.name) + " is not a number");
  const NumberField n = tokenField(f, file, c.begin, c.end, c.value);
  switch (s.slot) {
    case Slot::kPos:
      t.pos[s.k] = n;
      break;
    case Slot::kRot:
      t.rot[s.k] = n;
      break;
    case Slot::kStatus:
    case Slot::kTurn:
      if (c.value < 0 || c.value != std::floor(c.value) || c.value > 1e6)
        failAt(f, c.begin, upper(c.name) + " must be a non-negative integer");
      (s.slot == Slot::kStatus ? t.statusField() : t.turnField()) = n;
      (s.slot == Slot::kStatus ? t.config.status : t.config.turn) = toInt(c.value);
      break;
    case Slot::kJoint:
      t.joints[s.k] = n;
      break;
    case Slot::kExt:
      t.ext[s.k] = n;
      break;
    case Slot::kNone:
      break;
  }
}

// The target of position aggregate `a` (of type `type`) of file f (index `file`), as the reader
// makes it: every member but its name, line and uses. Throws InputError (failAt) where the reader
// stops. `check9`: returns whether a Cartesian component is written with 9 significant digits
// (KSS style: SourceFile::significant9), else false.
bool fillTarget(const SourceFile& f, int file, const Aggregate& a, std::string_view type,
                bool check9, Target& t) {
  t.file = file;
  t.aggregate_end = a.close;
  t.config.vendor = Vendor::kKuka;
  const bool joint =
      iequals(type, "AXIS") || iequals(type, "E6AXIS") || (type.empty() && a.find("A1") != nullptr);
  t.kind = joint ? TargetKind::kJoint : TargetKind::kCartesian;
  t.orientation = joint ? Orientation::kNone : Orientation::kKukaAbc;
  for (const Component& c : a.comps) {
    const SlotIndex s = slotOf(c.name);
    if (c.kind != Component::kNumber && c.kind != Component::kLiteral) {
      if (s.slot != Slot::kNone)
        failAt(f, c.begin, "component " + upper(c.name) + " is not a number");
      continue;
    }
    setComponent(f, file, t, c, s);
  }
  if (joint || !check9) return false;
  for (const NumberField* n : {&t.pos[0], &t.pos[1], &t.pos[2], &t.rot[0], &t.rot[1], &t.rot[2]}) {
    if (n->present() && n->length >= 9 &&
        sigDigits(std::string_view(f.bytes).substr(n->offset, n->length)) >= 9)
      return true;
  }
  return false;
}

}  // namespace

/// The motion lines of a window read ahead: their target aggregates parsed (the aggregate whose
/// '{' is token `open_token` ends before token `after`; its components are comps[comp_begin,
/// comp_end), their names (and its type) as offsets into the window), the target each of them
/// makes (`target`: 1 + its index in `targets`; 0: none, the reader makes it and stops there with
/// its error) and each line's target expressions split (`motions`, in token order).
struct KrlAhead {
  struct Aggregate {
    std::uint32_t open_token{0};
    std::uint32_t after{0};
    std::uint32_t comp_begin{0};
    std::uint32_t comp_end{0};
    std::uint32_t type_offset{0};
    std::uint32_t type_length{0};
    std::uint32_t open{0};
    std::uint32_t close{0};
    std::uint32_t target{0};
    bool significant9{false};  ///< its target is written with 9 significant digits
  };
  struct Component {
    postproc::Component comp;  ///< its name left empty
    std::uint32_t name_offset{0};
    std::uint32_t name_length{0};
  };
  /// splitTargets of the motion whose keyword is token `keyword`, its line's tokens ending
  /// before `end`: it returned `split` and `count` expressions, the first two kept.
  struct Motion {
    std::uint32_t keyword{0};
    std::uint32_t end{0};
    std::uint32_t split{0};
    std::uint32_t count{0};
    std::array<std::pair<std::uint32_t, std::uint32_t>, 2> exprs{};
  };
  std::vector<Aggregate> aggregates;  ///< in token order
  std::vector<Component> comps;
  std::vector<Target> targets;                             ///< taken (moved from) by the reader
  std::vector<Motion> motions;                             ///< in token order
  std::vector<std::pair<std::size_t, std::size_t>> exprs;  ///< splitTargets' scratch
};

namespace {

std::uint32_t offsetIn(const SourceFile& f, std::string_view s) {
  return s.empty() ? 0 : static_cast<std::uint32_t>(s.data() - f.bytes.data());
}

// The aggregates of tokens [b, j) of f, one lexed line, into `out` when it is a motion: each
// '{' after the keyword read by readComponents up to the line's end (its trailing comments
// excluded) and the target it makes (fillTarget); one that does not read is left to the reader
// (which stops there with its error). readComponents looks at no token past the aggregate's '}',
// so the aggregate is the one the reader reads over any target expression that holds it
// (KrlReader::targetAggregate). The line's target expressions split as the reader splits them.
void readAheadLine(const SourceFile& f, std::size_t b, std::size_t j,
                   std::vector<Component>& scratch, KrlAhead& out) {
  std::size_t e = j;
  while (e > b && f.tokens[e - 1].kind == TokenKind::kComment) --e;
  std::size_t k = b;
  const auto ident = [&f](std::size_t i) { return f.tokens[i].kind == TokenKind::kIdentifier; };
  if (k < e && ident(k) && iequals(f.text(f.tokens[k]), "GLOBAL")) ++k;
  if (k >= e || !ident(k) || !isMotionKeyword(f.text(f.tokens[k]))) return;
  KrlAhead::Motion mo;
  mo.keyword = static_cast<std::uint32_t>(k);
  mo.end = static_cast<std::uint32_t>(e);
  mo.split = static_cast<std::uint32_t>(splitTargets(f, k + 1, e, out.exprs));
  mo.count = static_cast<std::uint32_t>(out.exprs.size());
  for (std::size_t x = 0; x < mo.exprs.size() && x < out.exprs.size(); ++x) {
    mo.exprs[x] = {static_cast<std::uint32_t>(out.exprs[x].first),
                   static_cast<std::uint32_t>(out.exprs[x].second)};
  }
  out.motions.push_back(mo);
  for (++k; k < e; ++k) {
    if (punct1(f, f.tokens[k]) != '{') continue;
    TokenCursor c(f, k, e);
    scratch.clear();
    Aggregate a;
    try {
      a = readComponents(c, scratch);
    } catch (const InputError&) {
      continue;
    }
    KrlAhead::Aggregate g;
    g.open_token = static_cast<std::uint32_t>(k);
    g.after = static_cast<std::uint32_t>(c.index());
    g.comp_begin = static_cast<std::uint32_t>(out.comps.size());
    for (const Component& comp : scratch) {
      KrlAhead::Component ac{comp, offsetIn(f, comp.name),
                             static_cast<std::uint32_t>(comp.name.size())};
      ac.comp.name = {};
      out.comps.push_back(ac);
    }
    g.comp_end = static_cast<std::uint32_t>(out.comps.size());
    g.type_offset = offsetIn(f, a.type);
    g.type_length = static_cast<std::uint32_t>(a.type.size());
    g.open = a.open;
    g.close = a.close;
    a.comps = scratch;
    Target& t = out.targets.emplace_back();
    try {
      g.significant9 = fillTarget(f, 0, a, a.type, true, t);
      g.target = static_cast<std::uint32_t>(out.targets.size());
    } catch (const InputError&) {
      out.targets.pop_back();
    }
    out.aggregates.push_back(g);
    k = c.index() - 1;  // on after the aggregate
  }
}

/// The tokenizer options of KRL (`;` comments, `&` header lines, quoted literals).
LexOptions krlLexOptions() {
  LexOptions o;
  o.comment = ';';
  o.header_amp = true;
  o.single_quote_string = true;
  return o;
}

class KrlReader {
 public:
  explicit KrlReader(Program& p) : p_(p) {}

  void run() {
    start(true);
    readSrcLines();
    finish();
  }

  /// Before the .src: the lexer's options, the .dat's declarations (p.files[1], read whole).
  /// `reserve`: the .src is read whole (its targets' vector sized once).
  void start(bool reserve) {
    lex_ = krlLexOptions();
    // the name tables grow by doubling: a reserve from the file size would touch (and keep
    // resident) tens of MB a .src without declarations never uses
    // every target is an aggregate: '{' bounds their count (no regrowth of the large Target
    // vector, whose copy would double the peak memory of a 100,000-hole program)
    if (reserve) {
      std::size_t aggregates = 16;
      for (const SourceFile& f : p_.files)
        aggregates += static_cast<std::size_t>(std::count(f.bytes.begin(), f.bytes.end(), '{'));
      p_.target_list.reserve(aggregates);
    }
    if (p_.files.size() > 1) readDat();
  }

  /// The motion the reader may still change (a SPLINE block's last segment), -1: none.
  [[nodiscard]] int heldMotion() const { return spline_.active ? spline_.last_motion : -1; }
  /// The window's motions [0, m) were dropped (ProgramStream::retire).
  void retired(std::size_t m) {
    if (spline_.last_motion >= 0) spline_.last_motion -= static_cast<int>(m);
  }

  /// The lines of the .src (p.files[0]: the whole file, or the window of it read now).
  void readSrcLines() {
    file_ = 0;
    forEachLine([&](std::size_t b, std::size_t e, std::size_t j) { srcLine(b, e, j); });
  }
  /// readSrcLines() over the window's tokens lexed already (KrlStream::lexWindow).
  void readLexedSrcLines(KrlAhead* ahead) {
    file_ = 0;
    ahead_ = ahead;
    ahead_next_ = 0;
    ahead_motion_ = 0;
    forEachLexedLine([&](std::size_t b, std::size_t e, std::size_t j) { srcLine(b, e, j); });
    ahead_ = nullptr;
  }

  /// After the .src's last line: its DEF ... END checked.
  void finish() {
    if (!any_def_) throw InputError(file().path, 1, "no DEF found: not a KRL .src");
    if (depth_ != 0) fail(file().bytes.size(), "truncated file: DEF without END");
  }

 private:
  Program& p_;
  LexOptions lex_;
  int file_{0};
  NameMap<int> targets_;  // name -> index
  struct Fdat {
    int tool{-1};
    int base{-1};
    bool tcp{false};
  };
  NameMap<Fdat> fdats_;
  NameMap<int> runtime_locals_;  // position variables declared without a value -> their line
  NameMap<double> ldat_vel_;     // m/s
  // FRAME declarations by name (value -1 - index into frame_decls_). POS/E6POS declarations are
  // named frames too: found in targets_ and read back from the target (namedFrameIndex), so a
  // 100,000-point .dat keeps no second copy of its poses and no second table entry.
  NameMap<int> named_frames_;
  std::vector<Component> comps_;  // parseAggregate's scratch (see Aggregate)
  std::string marker_;            // addMarker's buffer
  KrlAhead* ahead_{nullptr};      // the window's motion lines read ahead (readLexedSrcLines)
  std::size_t ahead_next_{0};     // the first of its aggregates not taken yet
  std::size_t ahead_motion_{0};   // the first of its motions not taken yet
  std::vector<Frame> frame_decls_;
  std::unordered_map<int, Frame> base_data_;
  std::unordered_map<int, Frame> tool_data_;
  std::unordered_map<std::string, bool> reported_;
  std::set<std::pair<bool, int>> missing_tables_;  // (base?, number) already passed to unresolved
  std::size_t line_index_{0};                      // lineAt(): line_starts index of the last line
  std::vector<std::pair<std::size_t, std::size_t>> exprs_;  // motion(): target expressions
  Frame tool_{"$TOOL", false, Pose::Identity(), -1, 0};
  Frame base_{"$BASE", false, Pose::Identity(), -1, 0};
  Fdat fdat_;
  double vel_cp_{-1};
  int vel_zero_line_{0};  ///< line of a $VEL.CP (or LDAT VEL) of zero or below in force (0: none)
  /// A SPLINE … ENDSPLINE block being read: its segments blend; `vel` its WITH speed (m/s, < 0:
  /// not known) when `with_speed`.
  struct SplineBlock {
    bool active{false};
    bool with_speed{false};
    double vel{-1};
    int last_motion{-1};
  } spline_;
  // the texts of the last few $VEL.CP values (a drill cycle alternates a rapid and a feed speed):
  // one printf per value, not one per motion; round robin, `next_speed_text_` the next to replace
  std::array<std::pair<double, TextId>, 4> speed_texts_{{{-1, {}}, {-1, {}}, {-1, {}}, {-1, {}}}};
  std::size_t next_speed_text_{0};
  bool ext_tcp_{false};
  int depth_{0};  ///< DEF ... END nesting of the .src so far
  bool any_def_{false};

  const SourceFile& file() const { return p_.files[static_cast<std::size_t>(file_)]; }

  [[noreturn]] void fail(std::size_t offset, const std::string& msg) const {
    failAt(file(), offset, msg);
  }

  void unresolved(const std::string& ref, std::size_t offset, const std::string& what) {
    std::string key = upper(ref);
    if (reported_.count(key) != 0) return;
    if (reported_.emplace(std::move(key), true).second) {
      p_.unresolved.push_back(Unresolved{ref, file_, file().lineOf(offset), what});
    }
  }

  // Lexes the current file line by line (file().tokens holds one line's tokens at a time, so the
  // reader never keeps an index of the whole file) and calls fn(b, e, j) per line: [b, e) the
  // logical line, comment tokens excluded at the end; j the newline token (or the line's end).
  template <class F>
  void forEachLine(F&& fn) {
    SourceFile& f = p_.files[static_cast<std::size_t>(file_)];
    std::size_t pos = 0;
    line_index_ = 0;
    while (pos < f.bytes.size()) {
      f.tokens.clear();
      pos = lexLine(f, lex_, pos, f.tokens);
      std::size_t j = f.tokens.size();
      if (j > 0 && f.tokens[j - 1].kind == TokenKind::kNewline) --j;
      std::size_t e = j;
      while (e > 0 && f.tokens[e - 1].kind == TokenKind::kComment) --e;
      fn(std::size_t{0}, e, j);
    }
    f.tokens.clear();
  }

  // forEachLine over the tokens of the whole window (lexed line by line ahead, the same tokens):
  // fn(b, e, j) with [b, e) the logical line and j its newline token (or the tokens' end), as
  // indices into f.tokens; the reader never looks before b or past j.
  template <class F>
  void forEachLexedLine(F&& fn) {
    SourceFile& f = p_.files[static_cast<std::size_t>(file_)];
    line_index_ = 0;
    const std::size_t n = f.tokens.size();
    for (std::size_t b = 0; b < n;) {
      std::size_t j = b;
      while (j < n && f.tokens[j].kind != TokenKind::kNewline) ++j;
      std::size_t e = j;
      while (e > b && f.tokens[e - 1].kind == TokenKind::kComment) --e;
      fn(b, e, j);
      b = j + 1;
    }
    f.tokens.clear();
  }

  // file().lineOf(offset) for offsets met in file order: the line cursor moves forward from the
  // last answer (no binary search over 100,000s of lines per target).
  int lineAt(std::size_t offset) {
    const std::vector<std::uint32_t>& s = file().line_starts;
    if (line_index_ >= s.size() || s[line_index_] > offset) return file().lineOf(offset);
    while (line_index_ + 1 < s.size() && s[line_index_ + 1] <= offset) ++line_index_;
    return file().line_base + static_cast<int>(line_index_ + 1);
  }

  Aggregate parseAggregate(TokenCursor& c) {
    comps_.clear();
    Aggregate a = readComponents(c, comps_);
    a.comps = comps_;
    return a;
  }

  // parseAggregate(c) of a motion's target expression [c.index(), e): the aggregate read ahead
  // there when there is one within it (readAheadLine: the same tokens read by the same
  // readComponents, which looks at no token past the aggregate's '}').
  Aggregate targetAggregate(TokenCursor& c, std::size_t e) {
    const KrlAhead::Aggregate* read = aggregateReadAhead(c, e);
    if (read == nullptr) return parseAggregate(c);
    const KrlAhead::Aggregate& g = *read;
    ++ahead_next_;
    const std::string_view bytes = file().bytes;
    comps_.clear();
    for (std::size_t k = g.comp_begin; k < g.comp_end; ++k) {
      const KrlAhead::Component& ac = ahead_->comps[k];
      comps_.push_back(ac.comp);
      comps_.back().name = bytes.substr(ac.name_offset, ac.name_length);
    }
    Aggregate a;
    a.type = bytes.substr(g.type_offset, g.type_length);
    a.open = g.open;
    a.close = g.close;
    a.comps = comps_;
    c.seek(g.after);
    return a;
  }

  // The aggregate read ahead whose '{' is token c.index(), ending within [c.index(), e); null
  // when there is none (the reader parses it).
  const KrlAhead::Aggregate* aggregateReadAhead(const TokenCursor& c, std::size_t e) {
    if (ahead_ == nullptr) return nullptr;
    const std::vector<KrlAhead::Aggregate>& list = ahead_->aggregates;
    while (ahead_next_ < list.size() && list[ahead_next_].open_token < c.index()) ++ahead_next_;
    if (ahead_next_ == list.size() || list[ahead_next_].open_token != c.index() ||
        list[ahead_next_].after > e)
      return nullptr;
    return &list[ahead_next_];
  }

  // The target the read-ahead made of aggregate g (makeTarget(a, "", a.type) of it), taken;
  // returns its index.
  int takeTarget(const KrlAhead::Aggregate& g) {
    p_.target_list.push_back(std::move(ahead_->targets[g.target - 1]));
    p_.target_list.back().line = lineAt(g.open);
    if (g.significant9) p_.files[static_cast<std::size_t>(file_)].significant9 = true;
    return static_cast<int>(p_.target_list.size() - 1);
  }

  // splitTargets of the motion whose keyword is token `keyword` (its expressions from token
  // `from`, its line's tokens ending before e): the read-ahead's split when it made one.
  std::size_t splitMotion(std::size_t keyword, std::size_t from, std::size_t e,
                          std::vector<std::pair<std::size_t, std::size_t>>& exprs) {
    if (ahead_ == nullptr) return splitTargets(file(), from, e, exprs);
    const std::vector<KrlAhead::Motion>& list = ahead_->motions;
    while (ahead_motion_ < list.size() && list[ahead_motion_].keyword < keyword) ++ahead_motion_;
    if (ahead_motion_ == list.size() || list[ahead_motion_].keyword != keyword ||
        list[ahead_motion_].end != e || from != keyword + 1)
      return splitTargets(file(), from, e, exprs);
    const KrlAhead::Motion& mo = list[ahead_motion_++];
    exprs.clear();
    for (std::size_t x = 0; x < mo.exprs.size() && x < mo.count; ++x)
      exprs.emplace_back(mo.exprs[x].first, mo.exprs[x].second);
    return mo.split;
  }

  // Builds a target from a position aggregate; returns its index.
  int makeTarget(const Aggregate& a, std::string_view name, std::string_view type) {
    Target& t = p_.target_list.emplace_back();
    t.name = std::string(name);
    t.line = lineAt(a.open);
    if (fillTarget(file(), file_, a, type, !file().significant9, t))
      p_.files[static_cast<std::size_t>(file_)].significant9 = true;
    const int idx = static_cast<int>(p_.target_list.size() - 1);
    if (!name.empty()) targets_[name] = idx;
    return idx;
  }

  // named_frames_ value of a declared name: a FRAME declaration, else a Cartesian target
  // declared by name (POS/E6POS: the named targets that are not AXIS/E6AXIS).
  std::optional<int> namedFrameIndex(std::string_view n) const {
    if (const int* v = named_frames_.find(n)) return *v;
    const int* t = targets_.find(n);
    if (t != nullptr && p_.target_list[static_cast<std::size_t>(*t)].kind == TargetKind::kCartesian)
      return *t;
    return std::nullopt;
  }

  // The frame a name declared (see named_frames_): a POS/E6POS target's pose is poseOf() of its
  // aggregate (X, Y, Z, A, B, C; absent components 0), declared on the target's line.
  Frame namedFrame(int v) const {
    if (v < 0) return frame_decls_[static_cast<std::size_t>(-v - 1)];
    const Target& t = p_.target_list[static_cast<std::size_t>(v)];
    Pose T = Pose::Identity();
    T.translation() = Vec3(t.pos[0].value, t.pos[1].value, t.pos[2].value) * 1e-3;
    T.linear() =
        rotationFromZyx(t.rot[0].value * kDeg, t.rot[1].value * kDeg, t.rot[2].value * kDeg);
    return Frame{t.name, true, T, t.file, t.line};
  }

  static Pose poseOf(const Aggregate& a) {
    auto v = [&](const char* n) {
      const Component* c = a.find(n);
      return c != nullptr && c->kind == Component::kNumber ? c->value : 0.0;
    };
    Pose T = Pose::Identity();
    T.translation() = Vec3(v("X"), v("Y"), v("Z")) * 1e-3;
    T.linear() = rotationFromZyx(v("A") * kDeg, v("B") * kDeg, v("C") * kDeg);
    return T;
  }

  static bool isPositionType(std::string_view t) {
    return iequals(t, "E6POS") || iequals(t, "POS") || iequals(t, "FRAME") ||
           iequals(t, "E6AXIS") || iequals(t, "AXIS");
  }

  // DECL [GLOBAL] [CONST] TYPE NAME[...] [= value]  (DECL optional for predefined types)
  bool tryDecl(TokenCursor& c) {
    const std::size_t save = c.index();
    bool decl = false;
    if (c.isIdent("DECL")) {
      c.next();
      decl = true;
    }
    while (c.isIdent("GLOBAL") || c.isIdent("CONST")) c.next();
    if (!c.isKind(TokenKind::kIdentifier) || !c.isKind(TokenKind::kIdentifier, 1)) {
      c.seek(save);
      return decl;
    }
    const std::string_view type = c.text();
    if (!decl && !isPositionType(type) && !iequals(type, "FDAT") && !iequals(type, "LDAT") &&
        !iequals(type, "PDAT")) {
      c.seek(save);
      return false;
    }
    c.next();
    const std::string_view name = c.text();
    const std::size_t name_off = c.peek().offset;
    c.next();
    if (c.isPunct('[')) return true;  // arrays: runtime values
    if (!c.isPunct('=')) {
      // `DECL POS xHole,xProfile`: variables set while the program runs (a .src's locals)
      if (isPositionType(type)) {
        runtimeLocal(name, name_off);
        while (c.isPunct(',') && c.isKind(TokenKind::kIdentifier, 1)) {
          c.next();
          runtimeLocal(c.text(), c.peek().offset);
          c.next();
        }
      }
      return true;
    }
    c.next();
    if (!c.isPunct('{')) return true;
    const Aggregate a = parseAggregate(c);
    if (iequals(type, "FRAME")) {
      frame_decls_.push_back(
          Frame{std::string(name), true, poseOf(a), file_, file().lineOf(name_off)});
      named_frames_[name] = -static_cast<int>(frame_decls_.size());
    } else if (isPositionType(type)) {
      makeTarget(a, name, type);  // POS/E6POS: a named frame too (namedFrameIndex)
    } else if (iequals(type, "FDAT")) {
      Fdat fd;
      if (const Component* t = a.find("TOOL_NO"); t != nullptr && t->kind == Component::kNumber)
        fd.tool = toInt(t->value);
      if (const Component* b = a.find("BASE_NO"); b != nullptr && b->kind == Component::kNumber)
        fd.base = toInt(b->value);
      if (const Component* ipo = a.find("IPO_FRAME")) {
        fd.tcp = icontains(std::string_view(file().bytes).substr(ipo->begin, ipo->end - ipo->begin),
                           "TCP");
      }
      fdats_[name] = fd;
    } else if (iequals(type, "LDAT")) {
      if (const Component* v = a.find("VEL"); v != nullptr && v->kind == Component::kNumber)
        ldat_vel_[name] = v->value;
    }
    return true;
  }

  /// A position variable declared without a value: its value is set at run time.
  void runtimeLocal(std::string_view name, std::size_t offset) {
    if (targets_.find(name) == nullptr) runtime_locals_[name] = file().lineOf(offset);
  }

  void readDat() {
    file_ = 1;
    bool defdat = false;
    bool enddat = false;
    std::size_t defdat_off = 0;
    forEachLine([&](std::size_t b, std::size_t e, std::size_t) {
      if (b >= e) return;
      TokenCursor c(file(), b, e);
      if (c.isIdent("DEFDAT")) {
        defdat = true;
        defdat_off = c.peek().offset;
        return;
      }
      if (c.isIdent("ENDDAT")) {
        enddat = true;
        return;
      }
      tryDecl(c);
    });
    if (defdat && !enddat) fail(file().bytes.size(), "truncated file: DEFDAT without ENDDAT");
    if (!defdat) fail(0, "no DEFDAT in the .dat file");
    (void)defdat_off;
  }

  Frame tableFrame(bool base, int n, std::size_t offset) {
    if (n == 0) return Frame{"$NULLFRAME", true, Pose::Identity(), -1, 0};
    auto& table = base ? base_data_ : tool_data_;
    const auto it = table.find(n);
    if (it != table.end()) return it->second;
    std::string ref = std::string(base ? "BASE_DATA[" : "TOOL_DATA[") + std::to_string(n) + "]";
    // reported once (a table entry assigned later is found above from then on)
    if (missing_tables_.insert({base, n}).second) {
      unresolved(ref, offset,
                 base ? "base frame defined outside the program ($config.dat)"
                      : "tool defined outside the program ($config.dat)");
    }
    return Frame{std::move(ref), false, Pose::Identity(), -1, 0};
  }

  // Evaluates a frame expression over tokens [b, e): terms joined by ':'.
  Frame evalFrame(std::size_t b, std::size_t e) {
    TokenCursor c(file(), b, e);
    Frame out{"", true, Pose::Identity(), file_, c.line()};
    std::string ref;
    int terms = 0;
    while (!c.done()) {
      Frame term{"", false, Pose::Identity(), file_, c.line()};
      const std::size_t off = c.peek().offset;
      if (c.isPunct('{')) {
        const Aggregate a = parseAggregate(c);
        term = Frame{"{...}", true, poseOf(a), file_, file().lineOf(a.open)};
      } else if (c.isKind(TokenKind::kIdentifier)) {
        const std::string n = upper(c.text());
        c.next();
        if ((n == "BASE_DATA" || n == "TOOL_DATA") && c.isPunct('[') &&
            c.isKind(TokenKind::kNumber, 1) && c.isPunct(']', 2)) {
          c.next();  // '['
          const int idx = toInt(parseNumber(c.text()).value_or(0), 0);
          c.next();  // number
          c.next();  // ']'
          term = tableFrame(n == "BASE_DATA", idx, off);
          term.ref = n + "[" + std::to_string(idx) + "]";
        } else if (n == "$NULLFRAME" || n == "$WORLD" || n == "$ROBROOT") {
          term = Frame{n, true, Pose::Identity(), -1, 0};
        } else if (n == "$BASE") {
          term = base_;
        } else if (n == "$TOOL") {
          term = tool_;
        } else if (const std::optional<int> nf = namedFrameIndex(n)) {
          term = namedFrame(*nf);
        } else {
          term = Frame{std::string(file().text(file().tokens[c.index() - 1])), false,
                       Pose::Identity(), -1, 0};
          unresolved(term.ref, off, "frame not defined in the program");
          while (!c.done() && !c.isPunct(':')) c.next();
        }
      } else {
        term = Frame{"expression", false, Pose::Identity(), -1, 0};
        unresolved(std::string(c.text()), off, "frame expression not understood");
        while (!c.done() && !c.isPunct(':')) c.next();
      }
      out.resolved = out.resolved && term.resolved;
      out.pose = out.pose * term.pose;
      if (!term.ref.empty()) ref += (ref.empty() ? "" : ":") + term.ref;
      ++terms;
      if (c.isPunct(':')) {
        c.next();
        continue;
      }
      if (!c.done()) {
        unresolved(std::string(c.text()), c.peek().offset, "frame expression not understood");
        out.resolved = false;
        break;
      }
    }
    (void)terms;
    out.ref = ref;
    if (!out.resolved) out.pose = Pose::Identity();
    return out;
  }

  void applyFdat(const Fdat& fd, std::size_t offset) {
    if (fd.tool >= 0) tool_ = tableFrame(false, fd.tool, offset);
    if (fd.base >= 0) base_ = tableFrame(true, fd.base, offset);
    if (fd.tcp && !ext_tcp_) {
      ext_tcp_ = true;
      p_.notes.push_back("IPO_FRAME #TCP (external TCP) at " + file().path + ":" +
                         std::to_string(file().lineOf(offset)) +
                         ": the robot carries the part; base and tool swap roles");
    }
  }

  Fdat fdatFromAggregate(const Aggregate& a) const {
    Fdat fd;
    if (const Component* t = a.find("TOOL_NO"); t != nullptr && t->kind == Component::kNumber)
      fd.tool = toInt(t->value);
    if (const Component* b = a.find("BASE_NO"); b != nullptr && b->kind == Component::kNumber)
      fd.base = toInt(b->value);
    return fd;
  }

  // Adds the marker a + b + c, built in a buffer kept from marker to marker (no allocation).
  void addMarker(std::string_view a, std::string_view b, std::string_view c = {}) {
    marker_.assign(a);
    marker_.append(b);
    marker_.append(c);
    p_.addMarker(marker_);
  }

  // Resolves one target expression [b, e) of a motion; returns the target index or -1.
  int motionTarget(std::size_t b, std::size_t e, Motion& m, bool relative) {
    const SourceFile& f = file();
    if (b >= e)
      fail(b < f.tokens.size() ? f.tokens[b].offset : f.bytes.size(), "motion without a target");
    const std::uint32_t s = f.tokens[b].offset;
    const std::uint32_t en = f.tokens[e - 1].offset + f.tokens[e - 1].length;
    TokenCursor c(f, b, e);
    const std::string_view text = std::string_view(f.bytes).substr(s, en - s);
    if (!c.isPunct('{')) m.target_text = p_.addUniqueText(text);  // literal targets: the text
    if (c.isPunct('{')) {
      // the target the read-ahead made, when the expression is the aggregate alone
      if (const KrlAhead::Aggregate* g = aggregateReadAhead(c, e);
          g != nullptr && g->target > 0 && g->after == e && !relative) {
        ++ahead_next_;
        c.seek(g->after);
        return takeTarget(*g);
      }
      const Aggregate a = targetAggregate(c, e);
      if (!c.done() || relative) {
        m.derivation = relative ? m.instruction : p_.addText(":");
        m.target_text = p_.addUniqueText(text);
        return -1;
      }
      return makeTarget(a, "", a.type);
    }
    if (e - b == 1 && c.isKind(TokenKind::kIdentifier)) {
      const std::string_view n = c.text();
      if (const int* it = targets_.find(n)) return *it;
      if (n[0] == '$') {
        m.derivation = p_.addText("system variable");
        return -1;
      }
      if (const int* local = runtime_locals_.find(n)) {
        m.derivation = p_.addText("runtime");
        unresolved(std::string(n), s,
                   "position variable declared without a value (" +
                       p_.files[static_cast<std::size_t>(file_)].path + ":" +
                       std::to_string(*local) +
                       "): set while the program runs, its pose is not known (not predicted, "
                       "not compensated)");
        return -1;
      }
      unresolved(std::string(n), s,
                 p_.files.size() < 2
                     ? "target declared neither in the .src nor in a .dat (no " + p_.dat_path +
                           "): a global of the controller's $config.dat (e.g. XHOME) or of "
                           "another module; its pose is not known (not predicted, not "
                           "compensated)"
                     : std::string("target not declared in the .src or .dat"));
      m.derivation = p_.addText("undeclared");
      return -1;
    }
    for (std::size_t k = b; k < e; ++k) {
      if (f.tokens[k].kind == TokenKind::kPunct && f.bytes[f.tokens[k].offset] == ':') {
        m.derivation = p_.addText(":");
        return -1;
      }
    }
    m.derivation = p_.addText("runtime");
    return -1;
  }

  // The motion's speed text for $VEL.CP = vel (m/s, > 0): "0.25 m/s", interned.
  TextId speedText(double vel) {
    for (const auto& [v, id] : speed_texts_) {
      if (v == vel) return id;
    }
    auto& slot = speed_texts_[next_speed_text_];
    next_speed_text_ = (next_speed_text_ + 1) % speed_texts_.size();
    slot = {vel, p_.addText(cGeneral(vel, 6) + " m/s")};
    return slot.second;
  }

  void motion(TokenCursor& c, std::size_t e) {
    const SourceFile& f = file();
    Motion m;
    const std::string_view kw = c.text();
    m.instruction = p_.addText(kw);
    const std::size_t kw_off = c.peek().offset;
    const std::size_t kw_token = c.index();
    c.next();
    m.file = file_;
    m.line = lineAt(kw_off);
    const bool relative = icontains(kw, "_REL");
    if (istartsWith(kw, "PTP") || iequals(kw, "SPTP")) {
      m.type = MotionType::kJoint;
    } else if (icontains(kw, "CIRC")) {
      m.type = MotionType::kCircular;
    } else {
      m.type = MotionType::kLinear;
    }
    m.config_honoured = m.type == MotionType::kJoint;
    std::vector<std::pair<std::size_t, std::size_t>>& exprs = exprs_;
    const std::size_t k = splitMotion(kw_token, c.index(), e, exprs);
    if (m.type == MotionType::kCircular && exprs.size() >= 2) {
      Motion aux_dummy = m;
      m.aux = motionTarget(exprs[0].first, exprs[0].second, aux_dummy, relative);
      m.target = motionTarget(exprs[1].first, exprs[1].second, m, relative);
    } else {
      m.target = motionTarget(exprs[0].first, exprs[0].second, m, relative);
    }
    // the approximation clause may follow a WITH list (`SPL P3 WITH $VEL.CP = 3.0 C_SPL`)
    std::string zone;
    double vel = spline_.active && spline_.with_speed ? spline_.vel : vel_cp_;
    int zdepth = 0;
    for (std::size_t j = k; j < e; ++j) {
      const Token& t = f.tokens[j];
      const std::string_view tx = f.text(t);
      if (t.kind == TokenKind::kPunct && (is1(tx, '(') || is1(tx, '{') || is1(tx, '['))) ++zdepth;
      if (t.kind == TokenKind::kPunct && (is1(tx, ')') || is1(tx, '}') || is1(tx, ']'))) --zdepth;
      if (zdepth == 0 && t.kind == TokenKind::kIdentifier && isApprox(tx))
        zone += (zone.empty() ? "" : " ") + std::string(tx);
      if (zdepth == 0 && t.kind == TokenKind::kIdentifier && iequals(tx, "WITH"))
        withList(j + 1, e, t.offset, vel);
    }
    m.zone_text = p_.addText(zone);
    // inside SPLINE ... ENDSPLINE the segments blend into one path: only the block's end stops
    m.fine = zone.empty() && !spline_.active;
    if (spline_.active) spline_.last_motion = static_cast<int>(p_.motions.size());
    if (m.type != MotionType::kJoint && vel <= 0 && vel_zero_line_ > 0 && vel == vel_cp_)
      zeroSpeed(vel_zero_line_, vel_cp_, m.line);
    if (m.type != MotionType::kJoint && vel > 0) {
      m.speed_mm_s = vel * 1000.0;
      m.speed_text = speedText(vel);
    }
    m.tool = internFrame(p_, tool_);
    m.base = internFrame(p_, base_);
    p_.motions.push_back(std::move(m));
    const int mi = static_cast<int>(p_.motions.size() - 1);
    const Motion& mm = p_.motions.back();
    if (mm.target >= 0) p_.target_list[static_cast<std::size_t>(mm.target)].uses.push_back(mi);
    if (mm.aux >= 0) p_.target_list[static_cast<std::size_t>(mm.aux)].uses.push_back(mi);
  }

  /// A WITH list `[b, e)` of a spline motion or a SPLINE block: `$VEL.CP = v` and
  /// `$VEL = SVEL_CP(v, …)` set the path speed `vel` (m/s) of that motion or block alone;
  /// STOOL2/SBASE/SFRAME(FPn) select its tool and base. Other parameters (`$APO.CDIS`,
  /// `$ACC`, …) are kept verbatim.
  /// True when the list states the speed.
  bool withList(std::size_t b, std::size_t e, std::uint32_t with_offset, double& vel) {
    const SourceFile& f = file();
    bool stated = false;
    for (std::size_t q = b; q < e; ++q) {
      const std::string_view w = f.text(f.tokens[q]);
      if (q + 2 < e && (iequals(w, "STOOL2") || iequals(w, "SBASE") || iequals(w, "SFRAME")) &&
          is1(f.text(f.tokens[q + 1]), '(')) {
        if (const Fdat* it = fdats_.find(f.text(f.tokens[q + 2]))) {
          Fdat fd = *it;
          if (iequals(w, "SBASE")) fd.tool = -1;
          if (iequals(w, "STOOL2")) fd.base = -1;
          applyFdat(fd, with_offset);
        }
      }
      std::size_t v = 0;  // first token of the speed value
      if (iequals(w, "$VEL") && q + 3 < e && is1(f.text(f.tokens[q + 1]), '.') &&
          iequals(f.text(f.tokens[q + 2]), "CP") && is1(f.text(f.tokens[q + 3]), '='))
        v = q + 4;
      if (iequals(w, "$VEL") && q + 4 < e && is1(f.text(f.tokens[q + 1]), '=') &&
          iequals(f.text(f.tokens[q + 2]), "SVEL_CP") && is1(f.text(f.tokens[q + 3]), '('))
        v = q + 4;
      if (v == 0 || v >= e) continue;
      std::size_t last = v;  // the value: up to ',' ')' or the approximation clause
      while (last < e && !isApprox(f.text(f.tokens[last])) && !is1(f.text(f.tokens[last]), ',') &&
             !is1(f.text(f.tokens[last]), ')'))
        ++last;
      if (last == v) continue;
      stated = true;
      const std::uint32_t vb = f.tokens[v].offset;
      const std::string_view text = std::string_view(f.bytes).substr(
          vb, f.tokens[last - 1].offset + f.tokens[last - 1].length - vb);
      const auto val = parseNumber(text);
      if (!val) {
        vel = -1;
        unresolved("$VEL.CP", vb,
                   "the path velocity '" + std::string(text) +
                       "' in a WITH list is not a number roprec can evaluate: that motion's "
                       "speed is unknown");
        continue;
      }
      if (*val <= 0) zeroSpeed(file().lineOf(vb), *val, 0);
      vel = *val;
    }
    return stated;
  }

  /// A path velocity of zero or below: no motion can run at it, and a drill feed would no
  /// longer be recognised (the depth silently the cell's). An input error at its line.
  [[noreturn]] void zeroSpeed(int line, double vel, int motion_line) const {
    throw InputError(file().path, line,
                     "$VEL.CP = " + numberText(vel) + " m/s is not a speed (" +
                         (motion_line > 0 ? "the motion at line " + std::to_string(motion_line)
                                          : std::string("the motion")) +
                         " would not move); hint: a path velocity is > 0 m/s, e.g. $VEL.CP = 0.02 "
                         "for a 20 mm/s feed");
  }

  void statement(std::size_t b, std::size_t e) {
    const SourceFile& f = file();
    TokenCursor c(f, b, e);
    const std::string_view w = c.text();
    if (c.isKind(TokenKind::kIdentifier) && isMotionKeyword(w)) {
      motion(c, e);
      return;
    }
    if (c.isIdent("DECL") || (c.isKind(TokenKind::kIdentifier) &&
                              c.isKind(TokenKind::kIdentifier, 1) && isPositionType(w))) {
      tryDecl(c);
      return;
    }
    if (c.isIdent("SPLINE") || c.isIdent("PTP_SPLINE")) {  // [WITH …]: blend up to ENDSPLINE
      spline_ = SplineBlock{true, false, -1, -1};
      for (std::size_t j = b; j < e; ++j) {
        if (f.tokens[j].kind == TokenKind::kIdentifier && iequals(f.text(f.tokens[j]), "WITH"))
          spline_.with_speed = withList(j + 1, e, f.tokens[j].offset, spline_.vel);
      }
      return;
    }
    if (c.isIdent("ENDSPLINE")) {  // the block stops at its end unless it is approximated
      bool approx = false;
      for (std::size_t j = b; j < e; ++j)
        approx =
            approx || (f.tokens[j].kind == TokenKind::kIdentifier && isApprox(f.text(f.tokens[j])));
      if (spline_.active && spline_.last_motion >= 0 && !approx)
        p_.motions[static_cast<std::size_t>(spline_.last_motion)].fine = true;
      spline_ = SplineBlock{};
      return;
    }
    if (c.isIdent("WAIT") && c.isIdent("SEC", 1)) {
      addMarker("dwell ", c.text(2), " s");
      return;
    }
    if (c.isIdent("BAS") && c.isPunct('(', 1) && c.isPunct('#', 2)) {
      const std::string what = upper(c.text(3));
      const std::size_t off = c.peek().offset;
      std::optional<double> arg;
      if (c.isPunct(',', 4) && c.isKind(TokenKind::kNumber, 5)) arg = parseNumber(c.text(5));
      if (what == "FRAMES" || what == "PTP_PARAMS" || what == "CP_PARAMS") applyFdat(fdat_, off);
      if (what == "TOOL" && arg) tool_ = tableFrame(false, toInt(*arg, 0), off);
      if (what == "BASE" && arg) base_ = tableFrame(true, toInt(*arg, 0), off);
      return;
    }
    if (c.isKind(TokenKind::kIdentifier)) {
      const auto n = [w](std::string_view u) { return iequals(w, u); };  // u upper case
      // assignments
      std::size_t eq = b;
      while (eq < e &&
             !(f.tokens[eq].kind == TokenKind::kPunct && f.bytes[f.tokens[eq].offset] == '='))
        ++eq;
      if (eq < e && eq + 1 < e) {
        const std::size_t off = f.tokens[b].offset;
        if (n("$BASE") && eq == b + 1) {
          base_ = evalFrame(eq + 1, e);
          if (base_.ref.empty() || base_.ref == "{...}") base_.ref = "$BASE";
          return;
        }
        if (n("$TOOL") && eq == b + 1) {
          tool_ = evalFrame(eq + 1, e);
          if (tool_.ref.empty() || tool_.ref == "{...}") tool_.ref = "$TOOL";
          return;
        }
        if ((n("BASE_DATA") || n("TOOL_DATA")) && eq == b + 4 && c.isKind(TokenKind::kNumber, 2)) {
          const int idx = toInt(parseNumber(c.text(2)).value_or(-1));
          Frame fr = evalFrame(eq + 1, e);
          fr.ref = upper(w) + "[" + std::to_string(idx) + "]";
          (n("BASE_DATA") ? base_data_ : tool_data_)[idx] = fr;
          reported_.erase(upper(fr.ref));
          return;
        }
        if (n("FDAT_ACT") && eq == b + 1) {
          TokenCursor v(f, eq + 1, e);
          if (v.isPunct('{')) {
            fdat_ = fdatFromAggregate(parseAggregate(v));
          } else if (v.isKind(TokenKind::kIdentifier)) {
            if (const Fdat* it = fdats_.find(v.text())) {
              fdat_ = *it;
            } else {
              fdat_ = Fdat{};
              unresolved(std::string(v.text()), off, "frame data set not declared");
            }
          }
          return;
        }
        if (n("LDAT_ACT") && eq == b + 1) {
          TokenCursor v(f, eq + 1, e);
          if (v.isKind(TokenKind::kIdentifier)) {
            if (const double* it = ldat_vel_.find(v.text())) vel_cp_ = *it;
          } else if (v.isPunct('{')) {
            const Aggregate a = parseAggregate(v);
            if (const Component* vel = a.find("VEL");
                vel != nullptr && vel->kind == Component::kNumber)
              vel_cp_ = vel->value;
          }
          vel_zero_line_ = vel_cp_ <= 0 && vel_cp_ != -1 ? file().lineOf(off) : 0;
          return;
        }
        if (n("$VEL") && c.isPunct('.', 1) && c.isIdent("CP", 2) && eq == b + 3) {
          TokenCursor v(f, eq + 1, e);
          const std::size_t vb = v.peek().offset;
          const Token& last = f.tokens[e - 1];
          const std::string_view text =
              std::string_view(f.bytes).substr(vb, last.offset + last.length - vb);
          if (const auto val = parseNumber(text)) {
            vel_cp_ = *val;
            vel_zero_line_ = *val <= 0 ? file().lineOf(vb) : 0;
          } else {
            // a variable, an expression or `inf`/`nan` (identifiers to KRL): the path velocity
            // is known only at run time, so the speeds of the motions after it are unknown (not
            // the previous value: a feed move would pass for an approach)
            vel_cp_ = -1;
            vel_zero_line_ = 0;
            unresolved("$VEL.CP", vb,
                       "the path velocity '" + std::string(text) +
                           "' is not a number roprec can evaluate: the speeds after it are "
                           "unknown (a drill feed there is not recognised by its speed)");
          }
          return;
        }
        if (eq == b + 1 || (c.isPunct('[', 1))) {
          // Other assignments may still hold aggregates: validate them (unterminated / broken
          // numbers).
          TokenCursor v(f, eq + 1, e);
          if (v.isPunct('{')) parseAggregate(v);
          return;
        }
      }
      if (c.isPunct('(', 1)) {
        const std::string name = upper(w);
        if (name.find("SPINDLE") != std::string::npos || name.find("DRILL") != std::string::npos)
          addMarker("call ", w);
      }
    }
  }

  /// One line of the .src: [b, e) its tokens before a trailing comment, j its newline token.
  void srcLine(std::size_t b, std::size_t e, std::size_t j) {
    const SourceFile& f = file();
    // comment markers on comment-only lines
    if (b == e) {
      for (std::size_t k = b; k < j; ++k) {
        if (f.tokens[k].kind != TokenKind::kComment) continue;
        const std::string_view u = f.text(f.tokens[k]);
        if (istartsWith(u, ";FOLD") || istartsWith(u, ";ENDFOLD") || istartsWith(u, "&")) continue;
        if (icontains(u, "PLUNGE") || icontains(u, "DRILL")) {
          addMarker("comment ", f.text(f.tokens[k]));
        }
      }
      return;
    }
    TokenCursor c(f, b, e);
    if (c.isIdent("GLOBAL")) c.next();
    if (c.isIdent("DEF") || c.isIdent("DEFFCT")) {
      ++depth_;
      any_def_ = true;
      return;
    }
    if (c.isIdent("END") || c.isIdent("ENDFCT")) {
      --depth_;
      return;
    }
    if (c.isIdent("DEFDAT")) fail(c.peek().offset, "DEFDAT in a .src file");
    statement(c.index(), e);
  }
};

}  // namespace

void parseKrl(Program& p) { KrlReader(p).run(); }

struct KrlStream::Reader : KrlReader {
  using KrlReader::KrlReader;
};

KrlStream::KrlStream(Program& p) : r_(std::make_unique<Reader>(p)) { r_->start(false); }
KrlStream::~KrlStream() = default;
void KrlStream::lines() { r_->readSrcLines(); }
void KrlStream::lexedLines(KrlAhead* ahead) { r_->readLexedSrcLines(ahead); }
void KrlStream::lexWindow(SourceFile& f, std::shared_ptr<KrlAhead>& ahead) {
  const LexOptions o = krlLexOptions();
  f.tokens.clear();
  f.tokens.reserve(f.bytes.size() / 3 + 16);
  if (!ahead) ahead = std::make_shared<KrlAhead>();
  ahead->aggregates.clear();
  ahead->comps.clear();
  ahead->targets.clear();
  ahead->motions.clear();
  std::vector<Component> scratch;
  for (std::size_t pos = 0; pos < f.bytes.size();) {
    const std::size_t b = f.tokens.size();
    pos = lexLine(f, o, pos, f.tokens);
    std::size_t j = f.tokens.size();
    if (j > b && f.tokens[j - 1].kind == TokenKind::kNewline) --j;
    readAheadLine(f, b, j, scratch, *ahead);
  }
}
std::size_t aggregatesReadAhead(const KrlAhead& a) { return a.aggregates.size(); }
std::size_t targetsReadAhead(const KrlAhead& a) {
  return static_cast<std::size_t>(std::count_if(a.aggregates.begin(), a.aggregates.end(),
                                                [](const auto& g) { return g.target > 0; }));
}
void KrlStream::finish() { r_->finish(); }
int KrlStream::heldMotion() const { return r_->heldMotion(); }
void KrlStream::retired(std::size_t m) { r_->retired(m); }

}  // namespace roprec::postproc
