/// FANUC TP ASCII reader (`.ls`), docs/programs.md §4.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <deque>
#include <iterator>
#include <unordered_map>

#include "compensator/support/error.hpp"
#include "postproc/dialects.hpp"
#include "postproc/lexer.hpp"

namespace roprec::postproc {
namespace {

class TpReader {
 public:
  /// How the reader reads. kWhole: the whole file, once. Read by windows of whole lines
  /// (TpStream) by two readers over the same file: kScan reads every line in order (p.files[0]):
  /// its errors, notes and unresolved references, the position records, and the references of /MN
  /// counted (the motions it reads there are dropped); kMotions reads /MN again, behind it, and
  /// makes the motions, which the scan binds to the records in order as both come.
  enum class Mode { kWhole, kScan, kMotions };

  TpReader(Program& p, const SourceFile& f, Mode mode) : p_(p), f_(f), mode_(mode) {}
  explicit TpReader(Program& p) : TpReader(p, p.files[0], Mode::kWhole) {}

  /// The whole file.
  void run() {
    lines(true);
    finish();
  }

  /// A kScan reader's kMotions reader (and the other way round).
  void pair(TpReader& motions) {
    motions_ = &motions;
    motions.binder_ = this;
  }

  /// The lines of the window f_ holds (`last`: no bytes follow it) up to a /POS record the window
  /// ends inside, whose line starts the next window (carry()); kMotions: up to the end of /MN.
  void lines(bool last) {
    opt_.comment = 0;
    opt_.single_quote_string = true;
    last_ = last;
    next_line_ = 0;
    carry_ = f_.bytes.size();
    tok_.clear();
    bool pending = false;  // tok_ holds the rest of the line where /POS stopped
    if (sec_ == Section::kPos && mode_ != Mode::kMotions) {
      pending = positions();
      if (!pending) {
        windowEnd();
        return;
      }
    }
    while (!(mode_ == Mode::kMotions && mn_done_)) {
      if (!pending) {
        tok_.clear();
        if (!lexMore()) break;
      }
      pending = false;
      std::size_t j = 0;
      while (j < tok_.size() && tok_[j].kind != TokenKind::kNewline) ++j;
      // line [0, j)
      if (j > 0 && punct(0, '/') && 1 < j && tok_[1].offset == tok_[0].offset + 1 &&
          tok_[1].kind == TokenKind::kIdentifier && atLineStart(tok_[0].offset)) {
        section(tx(1));
        if (sec_ == Section::kPos && mode_ != Mode::kMotions) {
          tok_.clear();
          pending = positions();
          if (!pending) break;
        }
        continue;
      }
      if (sec_ == Section::kMn && j > 0) mnLine(0, j);
    }
    if (mode_ == Mode::kMotions && last) mn_done_ = true;  // a file that ends in /MN
    windowEnd();
  }

  /// After the last window: the file's end checked; kWhole: every motion bound.
  void finish() {
    if (!seen_prog_) throw InputError(f_.path, 1, "no /PROG header: not a FANUC TP .ls file");
    if (sec_ != Section::kEnd) failAt(f_, f_.bytes.size(), "truncated file: no /END");
    finished_ = true;
    bindSettled(mode_ == Mode::kWhole);
  }
  /// kScan, once both readers read their last window: the motions left bound (positions not in
  /// /POS unresolved).
  void end() { bindSettled(true); }

  /// The offset in f_ (a line start) the next window starts with; its size when none.
  [[nodiscard]] std::size_t carry() const { return carry_; }
  /// kScan: the kMotions reader is to read its next window: /MN was read here, the motions read
  /// there are all bound (or the first waits for its continuation line) and it has not read /MN
  /// whole.
  [[nodiscard]] bool wantsMotions() const {
    if (!mn_done_ || motions_ == nullptr || motions_->mn_done_) return false;
    // none waits, or the first waits for its end point (a circular motion's next line)
    return pending_.empty() || pending_.front().motion == motions_->last_motion_line_;
  }
  /// Whether /MN was read whole.
  [[nodiscard]] bool mnRead() const { return mn_done_; }
  /// Motions [0, settled()) are bound to their positions (the reader changes them no more).
  [[nodiscard]] std::size_t settled() const {
    if (mode_ == Mode::kScan && !mn_done_) return 0;  // the scan's own motions: dropped
    return pending_.empty() ? p_.motions.size() : static_cast<std::size_t>(pending_.front().motion);
  }
  /// Whether a motion not bound yet names target `t`'s position (kScan: every reference of /MN
  /// counted, so a position named again later stays until then).
  [[nodiscard]] bool needed(std::size_t t) const {
    if (!mn_done_) return true;
    return t < numbers_.size() && refs_.count(numbers_[t]) != 0U;
  }
  /// Motions [0, m) were dropped.
  void retired(std::size_t m) {
    const auto shift = static_cast<int>(m);
    for (Pending& pd : pending_) pd.motion -= shift;
    TpReader& open = motions_ != nullptr ? *motions_ : *this;
    if (open.last_motion_line_ >= 0) open.last_motion_line_ -= shift;
  }
  /// Targets [begin, end) were dropped: their numbers are found no more.
  void retiredTargets(std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end && t < numbers_.size(); ++t) by_number_.erase(numbers_[t]);
    numbers_.erase(numbers_.begin() + static_cast<std::ptrdiff_t>(begin),
                   numbers_.begin() + static_cast<std::ptrdiff_t>(std::min(end, numbers_.size())));
    const auto shift = static_cast<int>(end - begin);
    for (auto& [number, target] : by_number_) {
      if (target >= static_cast<int>(end)) target -= shift;
    }
  }

 private:
  enum class Section { kNone, kProg, kAttr, kAppl, kMn, kPos, kEnd };
  Program& p_;
  const SourceFile& f_;
  Mode mode_{Mode::kWhole};
  TpReader* binder_{this};      ///< the reader whose pending_ a motion joins (kMotions: the scan)
  TpReader* motions_{nullptr};  ///< kScan: the reader that makes the motions
  bool finished_{false};        ///< the file's end was read
  bool started_{false};         ///< kMotions: a window was read
  bool last_{true};             ///< no bytes follow the window
  std::size_t carry_{0};        ///< carry()
  Section sec_{Section::kNone};
  bool seen_prog_{false};
  bool mn_done_{false};  ///< a section after /MN began: every motion is read (kMotions: made)
  LexOptions opt_;
  std::vector<Token> tok_;    ///< tokens of the current line (/MN) or position record (/POS)
  std::size_t next_line_{0};  ///< byte offset of the first line not lexed yet

  /// Appends the next line's tokens to tok_; false at the end of the file.
  bool lexMore() {
    if (next_line_ >= f_.bytes.size()) return false;
    const std::size_t from = tok_.size();
    next_line_ = lexLine(f_, opt_, next_line_, tok_);
    quotesInBrackets(from);
    return true;
  }

  /// An apostrophe inside brackets (a position comment `P[101:1-0']`) is text, not the start of
  /// a string: the lexer read it as a string running to the line end, so the line's tokens from
  /// tok_[from] on are re-lexed after the bracket that closes the comment.
  void quotesInBrackets(std::size_t from) {
    int depth = 0;
    for (std::size_t k = from; k < tok_.size(); ++k) {
      if (punct(k, '[')) ++depth;
      if (punct(k, ']') && depth > 0) --depth;
      if (depth == 0 || tok_[k].kind != TokenKind::kString || f_.bytes[tok_[k].offset] != '\'')
        continue;
      const std::size_t close = f_.bytes.find(']', tok_[k].offset);
      const std::size_t eol = f_.bytes.find_first_of("\r\n", tok_[k].offset);
      if (close == std::string::npos || close > eol) return;  // unterminated: reference() says so
      std::vector<Token> rest;
      lexLine(f_, opt_, close, rest);
      tok_[k].kind = TokenKind::kOther;  // the comment text from the apostrophe on
      tok_[k].length = static_cast<std::uint32_t>(close - tok_[k].offset);
      std::size_t end = k + 1;  // the tokens of this line the string swallowed or followed
      while (end < tok_.size() && tok_[end - 1].kind != TokenKind::kNewline) ++end;
      tok_.erase(tok_.begin() + static_cast<std::ptrdiff_t>(k + 1),
                 tok_.begin() + static_cast<std::ptrdiff_t>(end));
      tok_.insert(tok_.begin() + static_cast<std::ptrdiff_t>(k + 1), rest.begin(), rest.end());
    }
  }
  /// A section header `/NAME` at a line start.
  void section(std::string_view s) {
    const Section before = sec_;
    if (iequals(s, "PROG")) {
      sec_ = Section::kProg;
      seen_prog_ = true;
    } else if (iequals(s, "ATTR")) {
      sec_ = Section::kAttr;
    } else if (iequals(s, "APPL")) {
      sec_ = Section::kAppl;
    } else if (iequals(s, "MN")) {
      sec_ = Section::kMn;
    } else if (iequals(s, "POS")) {
      sec_ = Section::kPos;
    } else if (iequals(s, "END")) {
      sec_ = Section::kEnd;
    }
    if (before == Section::kMn && sec_ != Section::kMn) mn_done_ = true;
  }
  bool atLineStart(std::uint32_t offset) const {
    const int line = f_.lineOf(offset) - f_.line_base;  // in the window
    return line != 0 && f_.line_starts[static_cast<std::size_t>(line - 1)] == offset;
  }
  std::unordered_map<int, int> by_number_;  // P number -> target
  /// kScan: the P number of each target (target_list order), and per P number the references of
  /// /MN not bound yet (refs_).
  std::deque<int> numbers_;
  /// Counts by P number: a 32-bit count per number below 2^24, a map for the others.
  class Counts {
   public:
    void add(int n) {
      if (n >= 0 && n < kDense) {
        const auto k = static_cast<std::size_t>(n);
        if (k >= dense_.size()) dense_.resize(std::max<std::size_t>(k + 1, 2 * dense_.size()));
        ++dense_[k];
      } else {
        ++sparse_[n];
      }
    }
    void remove(int n) {
      if (n >= 0 && n < kDense) {
        const auto k = static_cast<std::size_t>(n);
        if (k < dense_.size() && dense_[k] > 0) --dense_[k];
      } else if (const auto it = sparse_.find(n); it != sparse_.end() && --it->second == 0) {
        sparse_.erase(it);
      }
    }
    [[nodiscard]] std::uint32_t count(int n) const {
      if (n >= 0 && n < kDense) {
        const auto k = static_cast<std::size_t>(n);
        return k < dense_.size() ? dense_[k] : 0U;
      }
      const auto it = sparse_.find(n);
      return it == sparse_.end() ? 0U : it->second;
    }

   private:
    static constexpr int kDense = 1 << 24;
    std::vector<std::uint32_t> dense_;
    std::unordered_map<int, std::uint32_t> sparse_;
  };
  Counts refs_;
  /// The records read by P number (a record read twice is an error, also once the first was
  /// dropped).
  Counts defined_;
  /// P number -> line of a record never taught (negated once a motion to it is reported)
  std::unordered_map<int, int> untaught_;
  bool other_config_noted_{false};
  struct Pending {
    int motion;
    int number;
    int aux_number;
    int utool;       ///< the UTOOL_NUM active at the motion (-1: none, -2: a register)
    int utool_line;  ///< its line
  };
  std::deque<Pending> pending_;  ///< motions not bound yet, in order
  int uframe_{-1};
  int utool_{-1};
  int utool_line_{0};
  bool utool_register_noted_{false};
  int last_motion_line_{-1};
  std::array<TextId, 100> uframe_names_{}, utool_names_{};  ///< UF/UT number -> its text
  struct Memo {
    TextId ref;
    std::size_t frames{0};  ///< p_.frames.size() when `index` was found
    int index{-1};
  };
  Memo base_memo_, tool_memo_;

  [[noreturn]] void fail(std::size_t off, const std::string& m) const { failAt(f_, off, m); }
  std::string_view tx(std::size_t k) const { return f_.text(tok_[k]); }
  /// The source text of tokens [k, after).
  std::string_view spanText(std::size_t k, std::size_t after) const {
    return std::string_view(f_.bytes).substr(
        tok_[k].offset, tok_[after - 1].offset + tok_[after - 1].length - tok_[k].offset);
  }
  bool punct(std::size_t k, char c) const {
    return tok_[k].kind == TokenKind::kPunct && tok_[k].length == 1 &&
           f_.bytes[tok_[k].offset] == c;
  }

  // P[n(:comment)] / PR[n(:comment)] at k; returns index after ']' and the number (-1 indirect).
  std::size_t reference(std::size_t k, std::size_t e, int& number) const {
    number = -1;
    if (k + 1 >= e || !punct(k + 1, '[')) return k + 1;
    std::size_t q = k + 2;
    if (q < e && tok_[q].kind == TokenKind::kNumber)
      number = toInt(parseNumber(tx(q)).value_or(-1));
    int depth = 1;
    for (q = k + 2; q < e && depth > 0; ++q) {
      if (punct(q, '[')) ++depth;
      if (punct(q, ']')) --depth;
    }
    if (depth != 0) fail(tok_[k].offset, "unterminated position reference '['");
    return q;
  }

  void marker(const std::string& m) { p_.addMarker(m); }

  void mnLine(std::size_t b, std::size_t e) {
    std::size_t k = b;
    const bool numbered = tok_[k].kind == TokenKind::kNumber && k + 1 < e && punct(k + 1, ':');
    if (numbered) {
      k += 2;
    } else if (punct(k, ':') && last_motion_line_ >= 0 && k + 1 < e &&
               (iequals(tx(k + 1), "P") || iequals(tx(k + 1), "PR"))) {
      continuation(k + 1, e);
      return;
    } else if (punct(k, ':')) {
      k += 1;
    } else if (last_motion_line_ >= 0 && (iequals(tx(k), "P") || iequals(tx(k), "PR"))) {
      // continuation line of a C/A motion: the end point
      continuation(k, e);
      return;
    } else if (subBlockEnd(k, e)) {
      return;
    } else {
      // a program line starts with its number (`12:`): anything else is a damaged line, never
      // dropped in silence (it may be a motion)
      fail(tok_[k].offset, "a /MN line starts with its line number ('12:  L P[3] ...'), got '" +
                               std::string(tx(k).substr(0, 40)) + "'");
    }
    if (k >= e) return;
    last_motion_line_ = -1;
    // motion letter directly after ':'
    const Token& lt = tok_[k];
    const std::string_view letter = tx(k);
    const bool attached = lt.offset == tok_[k - 1].offset + 1;
    if (attached && lt.kind == TokenKind::kIdentifier && letter.size() == 1 &&
        (letter == "J" || letter == "L" || letter == "C" || letter == "A" || letter == "S")) {
      motion(k, e);
      return;
    }
    const std::string w = upper(letter);
    if (w == "UFRAME_NUM" || w == "UTOOL_NUM") {
      int& selected = w == "UFRAME_NUM" ? uframe_ : utool_;
      if (k + 2 < e && punct(k + 1, '=') && tok_[k + 2].kind == TokenKind::kNumber) {
        selected = toInt(parseNumber(tx(k + 2)).value_or(-1));
        if (selected > 99) selected = -2;  // not a frame number: as unknown as a register
      } else {
        selected = -2;  // register: runtime
      }
      if (w == "UTOOL_NUM") {
        utool_line_ = f_.lineOf(tok_[k].offset);
        if (selected == -2) utoolFromRegister(k, e);
      }
      return;
    }
    if (w == "WAIT" && k + 1 < e && tok_[k + 1].kind == TokenKind::kNumber) {
      marker("dwell " + std::string(tx(k + 1)) + " s");
      return;
    }
    if (w == "CALL" && k + 1 < e) {
      marker("call " + std::string(tx(k + 1)));
      return;
    }
    if (punct(k, '!')) {
      const std::string u = upper(
          std::string_view(f_.bytes).substr(tok_[k].offset, tok_[e - 1].offset - tok_[k].offset));
      if (u.find("DRILL") != std::string::npos || u.find("PLUNGE") != std::string::npos) {
        marker("comment " +
               std::string(std::string_view(f_.bytes).substr(
                   tok_[k].offset, tok_[e - 1].offset + tok_[e - 1].length - tok_[k].offset)));
      }
    }
  }

  /// `------ ;`: the line that closes the point-logic sub-block of a motion (its own numbered
  /// lines `1:  CALL ... ;` follow the motion line; TB/TA/DB logic).
  bool subBlockEnd(std::size_t k, std::size_t e) const {
    std::size_t q = k;
    while (q < e && punct(q, '-')) ++q;
    return q > k && q + 1 == e && punct(q, ';');
  }

  void tail(Motion& m, std::size_t k, std::size_t e) {
    // speed, termination, options
    std::string speed;
    std::size_t q = k;
    for (; q < e; ++q) {
      const std::string_view u = tx(q);
      if (iequals(u, "FINE") || iequals(u.substr(0, 3), "CNT") || punct(q, ';')) break;
      speed += tx(q);
    }
    m.speed_text = p_.addText(speed);
    std::size_t digits = 0;  // the number the speed starts with
    while (digits < speed.size() && (isDigit(speed[digits]) || speed[digits] == '.')) ++digits;
    const std::optional<double> num =
        digits > 0 ? parseNumber(speed.substr(0, digits)) : std::nullopt;
    // the linear units, mm/s = number · mul / div
    struct LinearUnit {
      const char* name;
      double mul;
      double div;
    };
    static constexpr LinearUnit kUnits[] = {
        {"MM/SEC", 1.0, 1.0}, {"CM/MIN", 10.0, 60.0}, {"INCH/MIN", 25.4, 60.0}};
    const std::string su = upper(speed);
    const bool linear_unit = std::any_of(std::begin(kUnits), std::end(kUnits), [&](const auto& u) {
      return su.find(u.name) != std::string::npos;
    });
    const bool by_register = su.rfind("R[", 0) == 0 || su.rfind("AR[", 0) == 0;
    // the unit right after the number: `1e300mm/sec` is not 1 mm/sec
    const std::string unit = su.substr(digits);
    const auto* const follows = std::find_if(std::begin(kUnits), std::end(kUnits),
                                             [&](const auto& u) { return unit == u.name; });
    const bool unit_follows = follows != std::end(kUnits);
    if (linear_unit && !by_register && (!num || !unit_follows)) {
      // a damaged number (`nanmm/sec`) would leave the move without a speed: the drill feed
      // is recognised from it
      fail(tok_[k].offset, "speed '" + speed.substr(0, 40) +
                               "' is not a number with its unit (e.g. 20mm/sec) or a register");
    }
    if (num && unit_follows) m.speed_mm_s = *num * follows->mul / follows->div;
    if (q < e && !punct(q, ';')) {
      std::string zone(tx(q));
      if (iequals(zone, "CNT") && q + 1 < e) zone += std::string(tx(q + 1));
      m.fine = iequals(zone, "FINE");
      m.zone_text = p_.addText(zone);
    }
    for (std::size_t r = q; r < e; ++r) {
      const std::string_view u = tx(r);
      if (iequals(u, "OFFSET") || iequals(u, "TOOL_OFFSET")) {
        m.derivation = p_.addText(iequals(u, "OFFSET") ? "Offset" : "Tool_Offset");
      }
      if (iequals(u, "INC")) m.derivation = p_.addText("INC");
    }
  }

  void motion(std::size_t k, std::size_t e) {
    Motion m;
    m.instruction = p_.addText(tx(k));
    m.file = 0;
    m.line = f_.lineOf(tok_[k].offset);
    const char c = tx(k)[0];
    m.type = c == 'J'                 ? MotionType::kJoint
             : (c == 'C' || c == 'A') ? MotionType::kCircular
                                      : MotionType::kLinear;
    m.config_honoured = m.type == MotionType::kJoint;
    std::size_t q = k + 1;
    if (q >= e) fail(tok_[k].offset, "motion without a target");
    const std::string_view ref = tx(q);
    int number = -1;
    const std::size_t after = reference(q, e, number);
    m.target_text = p_.addUniqueText(spanText(q, after));
    int pnum = -1;
    if (iequals(ref, "P") && number >= 0) {
      pnum = number;
    } else {
      m.derivation = p_.addText(iequals(ref, "PR") ? "PR" : "runtime");
      runtimePosition(q, after, m.line);
    }
    m.base = -1;
    m.tool = -1;
    if (m.type == MotionType::kCircular) {
      // C P[aux] [speed...] ; then the end point on the continuation line
      tail(m, after, e);
      p_.motions.push_back(std::move(m));
      addPending(Pending{static_cast<int>(p_.motions.size() - 1), -1, pnum, utool_, utool_line_});
      last_motion_line_ = static_cast<int>(p_.motions.size() - 1);
      return;
    }
    tail(m, after, e);
    p_.motions.push_back(std::move(m));
    addPending(Pending{static_cast<int>(p_.motions.size() - 1), pnum, -1, utool_, utool_line_});
    optionCalls(after, e);
  }

  /// `UTOOL_NUM=R[i]` (tokens [k, e)): the tool is known only at run time; noted once, each
  /// position's own UT is then its tool.
  void utoolFromRegister(std::size_t k, std::size_t e) {
    if (utool_register_noted_ || mode_ == Mode::kMotions) return;  // the scan reported it
    utool_register_noted_ = true;
    p_.unresolved.push_back(Unresolved{
        std::string(spanText(k, e)), 0, utool_line_,
        "the tool number comes from a register: known only at run time (each position's UT is "
        "taken as its tool)"});
  }

  /// Point-logic calls on the motion line (`TB .50sec,CALL SPINDLE_ON`, `DB 10.0mm,CALL DRILL`):
  /// markers of that motion, as a CALL on its own line after it.
  void optionCalls(std::size_t k, std::size_t e) {
    for (std::size_t q = k; q + 1 < e; ++q) {
      if (iequals(tx(q), "CALL") && tok_[q + 1].kind == TokenKind::kIdentifier)
        marker("call " + std::string(tx(q + 1)));
    }
  }

  void continuation(std::size_t k, std::size_t e) {
    Motion& m = p_.motions[static_cast<std::size_t>(last_motion_line_)];
    int number = -1;
    const std::string_view ref = tx(k);
    const std::size_t after = reference(k, e, number);
    tail(m, after, e);
    optionCalls(after, e);
    if (iequals(ref, "P") && number >= 0) {
      if (mode_ == Mode::kScan) {
        reference(number);
      } else {
        binder_->pending_.back().number = number;
      }
    } else {
      if (iequals(ref, "PR")) m.derivation = p_.addText("PR");
      runtimePosition(k, after, f_.lineOf(tok_[k].offset));
    }
    last_motion_line_ = -1;
  }

  /// A motion to a position roprec cannot know (tokens [k, after)): a position register `PR[i]`,
  /// or `P[...]` whose index is not a number (`P[R[4]]`, a typo): reported as unresolved, with
  /// its line, so the holes it belongs to are not dropped without a word.
  void runtimePosition(std::size_t k, std::size_t after, int line) {
    if (mode_ == Mode::kMotions) return;  // the scan reported it
    const std::string ref(spanText(k, after));
    p_.unresolved.push_back(Unresolved{
        ref, 0, line,
        iequals(tx(k), "PR")
            ? "a position register: its value lives in the controller, so the motion's pose is "
              "not known (not predicted, not compensated)"
            : "the position's index is not a number (a register or an expression): the pose is "
              "known only at run time (not predicted, not compensated)"});
  }

  NumberField signedNumber(std::size_t& q, std::size_t e, std::size_t eq_end) {
    const std::size_t s = q;
    if (q < e && (punct(q, '-') || punct(q, '+'))) ++q;
    if (q >= e || tok_[q].kind != TokenKind::kNumber) {
      fail(tok_[std::min(q, e - 1)].offset, "broken number in position record");
    }
    const Token& nt = tok_[q];
    if (q + 1 < e && tok_[q + 1].offset == nt.offset + nt.length &&
        (tok_[q + 1].kind == TokenKind::kNumber || punct(q + 1, '.'))) {
      fail(nt.offset, "broken number '" + std::string(tx(q)) + std::string(tx(q + 1)) + "'");
    }
    NumberField f = numberField(p_, 0, tok_[s].offset, nt.offset + nt.length);
    // right-aligned field: the spaces between '=' and the number belong to it
    std::uint32_t pad = 0;
    std::uint32_t o = f.offset;
    while (o > eq_end && f_.bytes[o - 1] == ' ') {
      --o;
      ++pad;
    }
    if (o == eq_end) f.pad = static_cast<std::uint8_t>(std::min<std::uint32_t>(pad, 255));
    ++q;
    return f;
  }

  /// Lexes lines onto tok_ until it holds a `}` or a `/END`; false when the window ended first.
  bool bufferRecord() {
    std::size_t k = 0;
    while (true) {
      for (; k < tok_.size(); ++k) {
        if (punct(k, '}')) return true;
        if (punct(k, '/') && k + 1 < tok_.size() && iequals(tx(k + 1), "END")) return true;
      }
      if (!lexMore()) return false;
      if (k > 0 && punct(k - 1, '/')) --k;  // `/` was the last token: look at it again
    }
  }

  /// Reads the /POS records, lexing one record at a time. Returns true when it stopped at a
  /// `/END` (tok_ then holds the rest of that line, from the `/`), false at the end of the
  /// window (a record the window ends inside, not the file's last: carry() is its line).
  bool positions() {
    std::size_t i = 0;
    while (true) {
      if (i >= tok_.size()) {
        tok_.clear();
        i = 0;
        if (!lexMore()) return false;
        continue;
      }
      if (tok_[i].kind == TokenKind::kNewline) {
        ++i;
        continue;
      }
      tok_.erase(tok_.begin(), tok_.begin() + static_cast<std::ptrdiff_t>(i));
      if (!bufferRecord() && !last_) {
        const int line = f_.lineOf(tok_[0].offset);
        carry_ = f_.line_starts[static_cast<std::size_t>(line - 1 - f_.line_base)];
        tok_.clear();
        return false;
      }
      // '/END' ends the section
      if (punct(0, '/') && 1 < tok_.size() && iequals(tx(1), "END")) return true;
      i = positionRecord();
    }
  }

  /// The position record at tok_[0]; returns the index after it.
  std::size_t positionRecord() {
    const std::vector<Token>& t = tok_;
    std::size_t i = 0;
    if (!iequals(tx(i), "P") || i + 1 >= t.size() || !punct(i + 1, '[')) {
      fail(t[i].offset, "expected a position record P[n]{...}; in /POS");
    }
    const std::size_t rec = i;
    int number = -1;
    i = reference(i, t.size(), number);
    if (number < 0) fail(t[rec].offset, "position record without a number");
    if (i >= t.size()) fail(t[rec].offset, "truncated position record");
    // skip to '{'
    while (i < t.size() && t[i].kind == TokenKind::kNewline) ++i;
    if (i >= t.size() || !punct(i, '{'))
      fail(t[rec].offset, "expected '{' after P[" + std::to_string(number) + "]");
    // find the closing '};'
    std::size_t e = i + 1;
    while (e < t.size() && !punct(e, '}')) {
      if (punct(e, '/') && e + 1 < t.size() && iequals(tx(e + 1), "END"))
        e = t.size();
      else
        ++e;
    }
    if (e >= t.size())
      fail(t[rec].offset,
           "unterminated position record P[" + std::to_string(number) + "] (missing '};')");
    record(rec, number, i + 1, e);
    i = e + 1;
    if (i < t.size() && punct(i, ';')) ++i;
    return i;
  }

  void record(std::size_t rec, int number, std::size_t b, std::size_t e) {
    Target t;
    t.name = "P[" + std::to_string(number) + "]";
    t.file = 0;
    t.line = f_.lineOf(tok_[rec].offset);
    t.config.vendor = Vendor::kFanuc;
    bool gp1 = false;
    bool untaught = false;
    bool cart = false;
    bool joint = false;
    int group = 0;
    std::size_t q = b;
    while (q < e) {
      const Token& tk = tok_[q];
      if (tk.kind != TokenKind::kIdentifier) {
        ++q;
        continue;
      }
      const std::string_view n = tx(q);
      if (n.size() >= 3 && iequals(n.substr(0, 2), "GP") && q + 1 < e && punct(q + 1, ':')) {
        group = toInt(parseNumber(n.substr(2)).value_or(0), 0);
        gp1 = gp1 || group == 1;
        q += 2;
        continue;
      }
      if (group != 1) {
        ++q;
        continue;
      }
      const bool uf = iequals(n, "UF");
      if ((uf || iequals(n, "UT")) && q + 2 < e && punct(q + 1, ':') && iequals(tx(q + 2), "F")) {
        untaught = true;  // `UF : F`: the controller's mark of a position never taught
        q += 3;
        continue;
      }
      if ((uf || iequals(n, "UT")) && q + 2 < e && punct(q + 1, ':')) {
        std::size_t r = q + 2;
        const NumberField v = signedNumber(r, e, tok_[q + 1].offset + 1);
        // frame numbers are small integers (UF 0..61, UT 1..61 on current controllers)
        if (!(v.value >= 0 && v.value <= 99 && v.value == std::floor(v.value))) {
          fail(tok_[q].offset, upper(n) + " : " + numberText(v.value) +
                                   " is not a frame number (an integer 0 .. 99)");
        }
        (uf ? t.frame_ref : t.tool_ref) = frameName(uf, toInt(v.value));
        q = r;
        continue;
      }
      if (iequals(n, "CONFIG") && q + 2 < e && punct(q + 1, ':') &&
          tok_[q + 2].kind == TokenKind::kString) {
        const Token& s = tok_[q + 2];
        const std::string_view sv = f_.text(s);
        if (sv.size() < 2 || sv.back() != '\'') fail(s.offset, "unterminated CONFIG string");
        if (s.length - 2 > NumberField::kMaxLength) fail(s.offset, "CONFIG string too long");
        const std::string_view text = sv.substr(1, sv.size() - 2);
        if (parseConfig(text, t.config)) {
          NumberField& config = t.fanucConfig();
          config.file = 0;
          config.offset = s.offset + 1;
          config.length = static_cast<std::uint16_t>(s.length - 2);
        } else if (!untaught) {
          otherConfig(t, text, s.offset);
        }
        q += 3;
        continue;
      }
      if (q + 2 < e && punct(q + 1, '=') && punct(q + 2, '*')) {
        untaught = true;  // `X = ********  mm`: a value never taught
        q += 2;
        while (q < e && punct(q, '*')) ++q;
        continue;
      }
      if (q + 1 < e && punct(q + 1, '=')) {
        std::size_t r = q + 2;
        const NumberField v = signedNumber(r, e, tok_[q + 1].offset + 1);
        positionField(n, v, t, cart, joint);
        q = r;
        continue;
      }
      ++q;
    }
    if (!gp1) p_.notes.push_back(t.name + ": no GP1 group; kept verbatim");
    if (defined_.count(number) != 0U)
      fail(tok_[rec].offset, "position P[" + std::to_string(number) + "] defined twice");
    defined_.add(number);
    if (untaught) {
      // a record the controller wrote for a position never taught: kept verbatim, no target;
      // a motion to it is unresolved (finish()), an error only where a job needs its pose
      untaught_[number] = t.line;
      p_.notes.push_back(t.name + " (" + f_.path + ":" + std::to_string(t.line) +
                         "): never taught (UF : F / ********), kept verbatim; a motion to it has "
                         "no known position");
      return;
    }
    t.kind = joint && !cart ? TargetKind::kJoint : TargetKind::kCartesian;
    t.orientation = t.kind == TargetKind::kCartesian ? Orientation::kFanucWpr : Orientation::kNone;
    p_.target_list.push_back(std::move(t));
    by_number_[number] = static_cast<int>(p_.target_list.size() - 1);
    if (mode_ == Mode::kScan) numbers_.push_back(number);
  }

  /// A 6-axis arm's CONFIG `F|N U|D T|B, t1, t2, t3` into c; false (c unchanged) for any other
  /// text the controller writes (a SCARA's `'L, 0, 0, 0'`, an untaught `''`).
  static bool parseConfig(std::string_view s, Configuration& c) {
    Configuration r = c;
    int turn = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      const char ch = static_cast<char>(std::toupper(static_cast<unsigned char>(s[i])));
      if (ch == 'F' || ch == 'N')
        r.flip = ch;
      else if (ch == 'U' || ch == 'D')
        r.elbow = ch;
      else if (ch == 'T' || ch == 'B')
        r.front = ch;
      else if (isDigit(ch) || ch == '-') {
        std::size_t j = i + 1;
        while (j < s.size() && isDigit(s[j])) ++j;
        const auto v = parseNumber(s.substr(i, j - i));
        if (!v || turn >= 3) return false;
        r.turns[static_cast<std::size_t>(turn++)] = toInt(*v, 0);
        i = j - 1;
      } else if (ch != ' ' && ch != ',') {
        return false;
      }
    }
    if (r.flip == 0 || r.elbow == 0 || r.front == 0) return false;
    c = r;
    return true;
  }

  /// A CONFIG that is not a 6-axis arm's (a SCARA's `'L, 0, 0, 0'`): kept as text (the bytes stay
  /// as they are), the target states no configuration; noted once.
  void otherConfig(Target& t, std::string_view text, std::size_t off) {
    t.config.vendor = Vendor::kNone;
    if (other_config_noted_) return;
    other_config_noted_ = true;
    p_.notes.push_back("CONFIG '" + std::string(text.substr(0, 40)) + "' (" + f_.path + ":" +
                       std::to_string(f_.lineOf(off)) +
                       ") is not a 6-axis arm's configuration (F|N U|D T|B, e.g. a SCARA's): kept "
                       "as text; roprec predicts 6-axis arms only");
  }

  /// X Y Z W P R J1..J6 E1..E6 of a position record into the target.
  static void positionField(std::string_view n, const NumberField& v, Target& t, bool& cart,
                            bool& joint) {
    const char c =
        n.size() <= 2 ? static_cast<char>(std::toupper(static_cast<unsigned char>(n[0]))) : '\0';
    if (n.size() == 1) {
      const char* const kPose = "XYZWPR";
      const char* const at = std::strchr(kPose, c);
      if (c == 0 || at == nullptr) return;
      const auto k = static_cast<std::size_t>(at - kPose);
      (k < 3 ? t.pos[k] : t.rot[k - 3]) = v;
      cart = cart || k < 3;
    } else if (n.size() == 2 && n[1] >= '1' && n[1] <= '6' && (c == 'J' || c == 'E')) {
      const auto k = static_cast<std::size_t>(n[1] - '1');
      (c == 'J' ? t.joints[k] : t.ext[k]) = v;
      joint = joint || c == 'J';
    }
  }

  /// The text id of `UFRAME[n]` / `UTOOL[n]` (n in 0..99, checked), made once per number.
  TextId frameName(bool uframe, int n) {
    TextId& id = (uframe ? uframe_names_ : utool_names_)[static_cast<std::size_t>(n)];
    if (id.empty()) id = p_.addText((uframe ? "UFRAME[" : "UTOOL[") + std::to_string(n) + "]");
    return id;
  }

  /// internFrame(frameFor(ref)); the last answer for the same text reused while no frame was
  /// added (frameFor's unresolved entry exists by then, so nothing is skipped).
  int frameIndex(TextId ref, bool tool) {
    Memo& m = tool ? tool_memo_ : base_memo_;
    if (m.index >= 0 && m.ref.index == ref.index && m.frames == p_.frames.size()) return m.index;
    m.index = internFrame(p_, frameFor(p_.text(ref), tool));
    m.ref = ref;
    m.frames = p_.frames.size();
    return m.index;
  }

  Frame frameFor(const std::string& ref, bool tool) {
    const bool zero = ref == "UFRAME[0]" || ref == "UTOOL[0]";
    if (zero) return Frame{ref, true, Pose::Identity(), -1, 0};
    bool seen = false;
    for (const Unresolved& u : p_.unresolved) seen = seen || u.ref == ref;
    if (!seen) {
      p_.unresolved.push_back(Unresolved{ref, 0, 0,
                                         tool ? "tool frame lives in the controller (UTOOL)"
                                              : "user frame lives in the controller (UFRAME)"});
    }
    return Frame{ref, false, Pose::Identity(), -1, 0};
  }

  /// The tool UTOOL_NUM selected for motion `m` (pd.utool): its tool when its position names
  /// none; a position taught in another tool is a ToolConflict (the position's UT stays its tool).
  void selectedTool(const Pending& pd, Motion& m) {
    if (pd.utool < 0) return;
    const int active = frameIndex(frameName(false, pd.utool), true);
    if (m.tool < 0) {
      m.tool = active;
    } else if (m.tool != active) {
      p_.tool_conflicts.push_back(ToolConflict{pd.motion, pd.utool_line,
                                               p_.frames[static_cast<std::size_t>(active)].ref,
                                               p_.frames[static_cast<std::size_t>(m.tool)].ref});
    }
  }

  /// A motion's positions to bind: kScan counts its references (the motion is dropped), kMotions
  /// queues it on the scan, kWhole on itself.
  void addPending(const Pending& pd) {
    if (mode_ == Mode::kScan) {
      reference(pd.number);
      reference(pd.aux_number);
    } else {
      binder_->pending_.push_back(pd);
    }
  }
  /// /MN names position `number` once more (kScan: its record stays until that motion is bound).
  void reference(int number) {
    if (mode_ == Mode::kScan && number >= 0) refs_.add(number);
  }
  void unreference(int number) {
    if (mode_ != Mode::kScan || number < 0) return;
    refs_.remove(number);
  }
  /// Whether position `number` (-1: none) is bound as the whole read binds it: its record read,
  /// or none to come.
  bool known(int number) const {
    return number < 0 || finished_ || by_number_.count(number) != 0 || untaught_.count(number) != 0;
  }

  /// kScan: its own motions (read to check /MN, count its references and report what it
  /// reports) dropped but the last one (`keep_last`: a continuation line may follow).
  void dropScanMotions(bool keep_last) {
    const std::size_t n = p_.motions.size() - (keep_last && !p_.motions.empty() ? 1 : 0);
    dropFirstMotions(p_, n);
    last_motion_line_ =
        last_motion_line_ >= static_cast<int>(n) ? last_motion_line_ - static_cast<int>(n) : -1;
  }

  /// The end of a window's lines: the scan's motions dropped, what can be bound bound.
  void windowEnd() {
    if (mode_ == Mode::kScan && p_.motions.size() > 0 && (!motions_ || !motions_->started_)) {
      dropScanMotions(!mn_done_);
      if (mn_done_) last_motion_line_ = -1;
    }
    if (mode_ == Mode::kMotions) {
      started_ = true;
      binder_->bindSettled(false);
      return;
    }
    bindSettled(false);
  }

  /// Binds the motions not bound yet, in order, while their positions are known (`all`: every
  /// one, those not in /POS unresolved): not before /MN is read whole, as the whole read binds
  /// them after it (the same unresolved entries, frames and uses in the same order).
  void bindSettled(bool all) {
    if (!all && !mn_done_) return;
    // a circular motion whose end point the next line may give
    const TpReader& maker = motions_ != nullptr ? *motions_ : *this;
    const int open = motions_ != nullptr && motions_->mn_done_ ? -1 : maker.last_motion_line_;
    while (!pending_.empty()) {
      const Pending& pd = pending_.front();
      if (!all && (pd.motion == open || !known(pd.number) || !known(pd.aux_number))) break;
      bind(pd);
      unreference(pd.number);
      unreference(pd.aux_number);
      pending_.pop_front();
    }
  }

  /// Motion pd.motion bound to its positions, frames and tool.
  void bind(const Pending& pd) {
    Motion& m = p_.motions[static_cast<std::size_t>(pd.motion)];
    auto bindNumber = [&](int number) -> int {
      if (number < 0) return -1;
      if (auto u = untaught_.find(number); u != untaught_.end()) {
        m.derivation = p_.addText("untaught");
        if (u->second < 0) return -1;  // reported at its first motion
        p_.unresolved.push_back(Unresolved{
            "P[" + std::to_string(number) + "]", 0, m.line,
            "position never taught (UF : F / ******** at line " + std::to_string(u->second) +
                "): its pose is not known (not predicted, not compensated)"});
        u->second = -u->second;
        return -1;
      }
      const auto it = by_number_.find(number);
      if (it == by_number_.end()) {
        p_.unresolved.push_back(
            Unresolved{"P[" + std::to_string(number) + "]", 0, m.line, "position not in /POS"});
        return -1;
      }
      return it->second;
    };
    m.target = bindNumber(pd.number);
    m.aux = bindNumber(pd.aux_number);
    const int ti = m.target >= 0 ? m.target : m.aux;
    if (ti >= 0) {
      const Target& t = p_.target_list[static_cast<std::size_t>(ti)];
      if (!t.frame_ref.empty()) m.base = frameIndex(t.frame_ref, false);
      if (!t.tool_ref.empty()) m.tool = frameIndex(t.tool_ref, true);
    }
    selectedTool(pd, m);
    if (m.target >= 0) p_.target_list[static_cast<std::size_t>(m.target)].uses.push_back(pd.motion);
    if (m.aux >= 0) p_.target_list[static_cast<std::size_t>(m.aux)].uses.push_back(pd.motion);
  }
};

}  // namespace

void parseTp(Program& p) { TpReader(p).run(); }

struct TpStream::Reader {
  explicit Reader(Program& p)
      : scan(p, p.files[0], TpReader::Mode::kScan), motions(p, mn, TpReader::Mode::kMotions) {
    mn.path = p.files[0].path;
    scan.pair(motions);
  }
  SourceFile mn;  ///< the window of /MN the motions are read from
  TpReader scan;
  TpReader motions;
};

TpStream::TpStream(Program& p) : r_(std::make_unique<Reader>(p)) {}
TpStream::~TpStream() = default;
void TpStream::lines(bool last) { r_->scan.lines(last); }
std::size_t TpStream::carry() const { return r_->scan.carry(); }
void TpStream::finish() { r_->scan.finish(); }
bool TpStream::wantsMotions() const { return r_->scan.wantsMotions(); }
SourceFile& TpStream::motionFile() { return r_->mn; }
void TpStream::motionLines(bool last) { r_->motions.lines(last); }
bool TpStream::motionsRead() const { return r_->motions.mnRead(); }
void TpStream::end() { r_->scan.end(); }
std::size_t TpStream::settled() const { return r_->scan.settled(); }
bool TpStream::needed(std::size_t target) const { return r_->scan.needed(target); }
void TpStream::retired(std::size_t m) { r_->scan.retired(m); }
void TpStream::retiredTargets(std::size_t begin, std::size_t end) {
  r_->scan.retiredTargets(begin, end);
}

}  // namespace roprec::postproc
