#pragma once
/// \file program.hpp
/// One model for robot programs of every supported dialect (docs/programs.md): KUKA KRL
/// (`.src` + `.dat`), ABB RAPID (`.mod`/`.prg`/`.sys`), FANUC TP ASCII (`.ls`), CSV/JSON target
/// lists and the contract's hole-list CSV.
///
/// Storage rule (docs/programs.md §1): a program is its files' bytes, kept verbatim, plus an
/// index of the tokens the readers found (byte offset, length, kind) and of every line's
/// terminator. Targets point at the exact byte spans of their numeric fields. An edit replaces
/// only the bytes of the numeric tokens whose printed value changes, printed in the style of the
/// token it replaces (decimals or significant digits, leading zero, exponent style, padding).
/// Writing a program that was not edited reproduces the input byte for byte.
///
/// Library API used by `roprec inspect/convert` and later by `predict/compensate`:
/// ```
///   Program p = readProgram("job.src");              // throws InputError(file, line, msg)
///   for (const Target& t : p.targets()) ...          // pose via targetPose(t) (SI, frame-local)
///   std::vector<Hole> holes = recognizeHoles(p);     // drill.hpp
///   EditResult r = replaceTargetPose(p, i, T_frame_tcp, config);   // r.ok or r.reason
///   writeProgram(p, "out.src");                      // atomic; KRL writes out.src + out.dat
/// ```
/// Units: poses handed in and out of the API are SI (m, rad) with the rotation as a matrix;
/// the files hold mm and degrees (or quaternions). Frames: a target's pose is T_frame_tcp, the
/// TCP in the frame the program expresses it in (KUKA $BASE, ABB wobj uframe·oframe, FANUC
/// UFRAME); the base-frame pose is T_base_frame · T_frame_tcp when the frame resolves.

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "compensator/support/rotation.hpp"

namespace roprec::postproc {

enum class Dialect { kKrl, kRapid, kTp, kCsv, kJson, kHoleCsv };
/// "krl", "rapid", "tp", "csv", "json", "holes".
std::string dialectName(Dialect d);

enum class LineEnd : std::uint8_t { kNone, kLf, kCrLf, kCr, kCrCrLf };

enum class TokenKind : std::uint8_t {
  kNumber,
  kIdentifier,
  kString,
  kPunct,
  kComment,
  kNewline,
  kOther
};

struct Token {
  std::uint32_t offset{0};
  std::uint32_t length{0};
  TokenKind kind{TokenKind::kOther};
};

/// One input file kept verbatim.
struct SourceFile {
  std::string path;
  std::string bytes;
  bool bom{false};                         ///< starts with a UTF-8 byte-order mark (kept)
  std::vector<std::uint32_t> line_starts;  ///< byte offset of every line
  std::vector<LineEnd> line_ends;          ///< terminator of every line, as found
  std::vector<Token> tokens;               ///< the reader's token index
  bool bare_fractions{false};  ///< numbers such as `.044` occur (FANUC controller style)
  bool zero_fractions{false};  ///< numbers such as `0.044` occur
  bool significant9{false};    ///< KSS style: positions written with 9 significant digits
  /// Lines of the file before `bytes`: a file read a window at a time (ProgramStream) holds one
  /// window of whole lines; offsets are the window's, lineOf() the file's line.
  int line_base{0};
  /// A window's file: the line ends of the lines before `bytes`, by kind (LineEnd).
  std::array<std::uint64_t, 5> earlier_ends{};

  /// Builds line_starts/line_ends and the fraction-style flags.
  void indexLines();
  /// 1-based line of a byte offset (in the file: line_base + the line in `bytes`).
  [[nodiscard]] int lineOf(std::size_t offset) const;
  [[nodiscard]] std::string_view text(const Token& t) const {
    return std::string_view(bytes.data() + t.offset, t.length);  // tokens lie inside bytes
  }
  /// The most frequent line terminator ("\n" when the file has none); a window's file counts the
  /// lines before it too (earlier_ends).
  [[nodiscard]] std::string dominantLineEnd() const;
};

/// A number in a file: value plus the span of its token (sign included). `pad` counts the
/// whitespace bytes before `offset` that belong to a right-aligned field (FANUC `%9.3f`).
/// 16 bytes (a 100,000-hole program holds millions of them): a token is at most kMaxLength bytes
/// (the readers refuse a longer number) and its padding at most 255 bytes.
struct NumberField {
  static constexpr std::uint32_t kMaxLength = 65535;
  double value{0.0};
  /// Byte offset of the token in its file. A component stated by a name or an expression (RAPID
  /// `Shift_Track`, `-d/2`: no token of its own, file = -1, kept verbatim and never re-printed)
  /// keeps its text's number here instead: Program::expressions[offset - 1] (setExpression()).
  std::uint32_t offset{0};
  std::uint16_t length{0};
  std::uint8_t pad{0};          ///< right-alignment whitespace before `offset`
  std::int8_t file : 6 {-1};    ///< index into Program::files (-1: no token of its own)
  bool expr_known : 1 {false};  ///< named(): `value` holds the expression's value
  bool named_ : 1 {false};
  [[nodiscard]] bool present() const { return file >= 0; }
  /// A value is known: a numeric token, or an expression roprec could evaluate.
  [[nodiscard]] bool known() const { return file >= 0 || expr_known; }
  /// Stated by a name or expression (known or not).
  [[nodiscard]] bool named() const { return named_; }
  /// States the component by expression number `index` (1-based into Program::expressions).
  void setExpression(std::uint32_t index) {
    file = -1;
    named_ = true;
    offset = index;
  }
};
static_assert(sizeof(NumberField) == 16, "a program holds ~25 NumberFields per target");

/// N fields most targets leave empty (the joints of a Cartesian target, external axes, ABB cf
/// digits): 8 bytes while empty, the N fields on the heap from the first write. Element access as
/// std::array: reading an empty block sees N absent fields; the non-const operator[] allocates
/// (read through a const reference where nothing is written).
template <std::size_t N>
class FieldBlock {
 public:
  FieldBlock() = default;
  FieldBlock(const FieldBlock& o) : p_(o.p_ ? std::make_unique<Fields>(*o.p_) : nullptr) {}
  FieldBlock(FieldBlock&&) noexcept = default;
  FieldBlock& operator=(const FieldBlock& o) {
    if (this != &o) p_ = o.p_ ? std::make_unique<Fields>(*o.p_) : nullptr;
    return *this;
  }
  FieldBlock& operator=(FieldBlock&&) noexcept = default;
  ~FieldBlock() = default;

  [[nodiscard]] const NumberField& operator[](std::size_t i) const { return all()[i]; }
  NumberField& operator[](std::size_t i) {
    if (!p_) p_ = std::make_unique<Fields>();
    return (*p_)[i];
  }
  [[nodiscard]] const NumberField* begin() const { return all().data(); }
  [[nodiscard]] const NumberField* end() const { return all().data() + N; }
  [[nodiscard]] static constexpr std::size_t size() { return N; }
  /// Whether any field was written.
  [[nodiscard]] bool stored() const { return p_ != nullptr; }

 private:
  using Fields = std::array<NumberField, N>;
  [[nodiscard]] const Fields& all() const {
    static const Fields kEmpty{};
    return p_ ? *p_ : kEmpty;
  }
  std::unique_ptr<Fields> p_;
};

/// Indices in insertion order with the interface of a read-only std::vector<int> plus push_back:
/// the first kept inline (most targets are used by one motion), the others on the heap. 16 bytes
/// and no allocation for a single index.
class IndexList {
 public:
  class const_iterator {
   public:
    const_iterator(const IndexList* l, std::size_t k) : l_(l), k_(k) {}
    int operator*() const { return (*l_)[k_]; }
    const_iterator& operator++() {
      ++k_;
      return *this;
    }
    bool operator!=(const const_iterator& o) const { return k_ != o.k_; }
    bool operator==(const const_iterator& o) const { return k_ == o.k_; }

   private:
    const IndexList* l_;
    std::size_t k_;
  };

  IndexList() = default;
  IndexList(const IndexList& o)
      : first_(o.first_), more_(o.more_ ? std::make_unique<std::vector<int>>(*o.more_) : nullptr) {}
  IndexList(IndexList&&) noexcept = default;
  IndexList& operator=(const IndexList& o) {
    if (this != &o) *this = IndexList(o);
    return *this;
  }
  IndexList& operator=(IndexList&&) noexcept = default;
  ~IndexList() = default;

  void push_back(int v) {
    if (first_ < 0) {
      first_ = v;
      return;
    }
    if (!more_) more_ = std::make_unique<std::vector<int>>();
    more_->push_back(v);
  }
  [[nodiscard]] bool empty() const { return first_ < 0; }
  [[nodiscard]] std::size_t size() const {
    return first_ < 0 ? 0 : 1 + (more_ ? more_->size() : 0);
  }
  [[nodiscard]] int front() const { return first_; }
  [[nodiscard]] int operator[](std::size_t k) const { return k == 0 ? first_ : (*more_)[k - 1]; }
  [[nodiscard]] const_iterator begin() const { return {this, 0}; }
  [[nodiscard]] const_iterator end() const { return {this, size()}; }

 private:
  int first_{-1};  ///< -1: empty (indices are >= 0)
  std::unique_ptr<std::vector<int>> more_;
};

enum class Vendor : std::uint8_t { kNone, kKuka, kAbb, kFanuc };

/// Raw vendor configuration exactly as the program states it (docs/programs.md §2.4, §3.3, §4.5).
struct Configuration {
  // the one-byte members first: 40 bytes, no padding (a program holds one per target)
  Vendor vendor{Vendor::kNone};
  char flip{0};                       ///< FANUC 'F'|'N'
  char elbow{0};                      ///< FANUC 'U'|'D'
  char front{0};                      ///< FANUC 'T'|'B'
  int status{-1};                     ///< KUKA S (-1 = absent)
  int turn{-1};                       ///< KUKA T (-1 = absent)
  std::array<int, 4> cf{0, 0, 0, 0};  ///< ABB cf1, cf4, cf6, cfx
  std::array<int, 3> turns{0, 0, 0};  ///< FANUC turn digits t1, t2, t3

  [[nodiscard]] bool present() const;
  /// Branch b = 4s + 2e + w of docs/programs.md §7.1 (s = shoulder back, e = elbow down,
  /// w = θ5 < 0). KUKA uses the table's bit-1 = elbow-up reading (§9 item 2, documented).
  [[nodiscard]] std::optional<int> branch() const;
  /// Human-readable: `S 2 T 35`, `[0,0,-2,0]`, `N U T, 0, 0, 0`.
  [[nodiscard]] std::string text() const;
};

/// Vendor flags for branch b (0..7) from the §7.1 table; turns/quadrants are zero (KUKA T = 0,
/// ABB cf1 = cf4 = cf6 = 0, FANUC turns 0) — callers carry turns separately where they can.
Configuration configurationFromBranch(Vendor v, int branch);
/// Parses Configuration::text() forms: `S 2 T 35`, `[0,0,-2,0]`, `N U T, 0, 0, 0`; vendor kNone
/// when empty or not understood.
Configuration parseConfigurationText(const std::string& text);

enum class TargetKind : std::uint8_t { kCartesian, kJoint };
/// kKukaAbc: R = Rz(A)Ry(B)Rx(C); kFanucWpr: R = Rz(R)Ry(P)Rx(W); kQuaternion: [w,x,y,z];
/// kXyzIntrinsic: R = Rx(rx)Ry(ry)Rz(rz) (RoboDK TxyzRxyz); kAxis: hole-list drilling direction
/// i,j,k = TCP z (the rotation about it is free, built deterministically).
enum class Orientation : std::uint8_t {
  kNone,
  kKukaAbc,
  kQuaternion,
  kFanucWpr,
  kXyzIntrinsic,
  kAxis
};

/// A text of a program stored once in its TextTable (Program::text(id)); 0 is "". Not a number:
/// motions and targets hold 4 bytes per text instead of a std::string each.
struct TextId {
  std::uint32_t index{0};
  [[nodiscard]] bool empty() const { return index == 0; }
};

/// The texts of a program's motions and targets (instructions, speeds, zones, derivations,
/// markers, frame names), each stored once. A 100,000-hole program repeats a handful of them
/// (`LIN`, `C_DIS`, `0.25 m/s`): 4 bytes per use instead of a 32-byte std::string. Texts of up
/// to kSharedMax bytes are looked up and shared; longer ones (comment markers, target
/// expressions: unique in practice) are appended without a look-up. Ids are stable; text(0) = "".
class TextTable {
 public:
  static constexpr std::size_t kSharedMax = 24;
  TextTable() { texts_.emplace_back(); }
  TextTable(const TextTable& o) : recent_(o.recent_), texts_(o.texts_) { reindex(); }
  TextTable(TextTable&&) noexcept = default;
  TextTable& operator=(const TextTable& o) {
    if (this != &o) {
      recent_ = o.recent_;
      texts_ = o.texts_;
      reindex();
    }
    return *this;
  }
  TextTable& operator=(TextTable&&) noexcept = default;
  ~TextTable() = default;

  /// The id of `s` (0 for ""), stored when new.
  TextId add(std::string_view s);
  /// Stores `s` without looking it up (texts unique in practice: a motion's target expression).
  TextId append(std::string_view s);
  [[nodiscard]] const std::string& operator[](TextId id) const { return texts_[id.index]; }
  [[nodiscard]] std::size_t size() const { return texts_.size(); }
  /// Frees a text that append() stored (a read window's motions retired: ProgramStream); its id
  /// is given to a later append(). Shared texts (add() of up to kSharedMax bytes) stay.
  void release(TextId id);

 private:
  void reindex();
  /// Slot of `s` in recent_: a cheap hash of its size and end bytes.
  static std::size_t recentSlot(std::string_view s) {
    return (s.size() * 31 + static_cast<std::size_t>(static_cast<unsigned char>(s.front())) * 7 +
            static_cast<unsigned char>(s.back())) &
           (kRecent - 1);
  }
  static constexpr std::size_t kRecent = 64;
  std::array<std::uint32_t, kRecent> recent_{};  ///< last shared id per slot (0: none): most
                                                 ///< look-ups repeat a recent text
  std::deque<std::string> texts_;  ///< a deque: the index's views stay valid as it grows
  std::unordered_map<std::string_view, std::uint32_t> index_;  ///< shared texts -> index
  std::vector<std::uint32_t> free_;                            ///< released ids, reused by append()
};

struct Target {
  // the 8-byte members first, then the 4-byte ones, then the bytes: 256 bytes, no padding
  // between members (a 100,000-hole program holds ~400,000 targets)
  std::string name;  ///< as declared (`XP2`, `pHole1`, `P[2]`, hole id); empty for inline targets
  std::array<NumberField, 3> pos;  ///< x, y, z mm
  std::array<NumberField, 4> rot;  ///< A,B,C deg | q1..q4 | W,P,R deg | i,j,k
  FieldBlock<6> joints;            ///< A1..A6 / J1..J6 (deg or mm)
  FieldBlock<6> ext;               ///< E1..E6 / eax_a..eax_f
  FieldBlock<4> cf_fields;         ///< ABB cf1, cf4, cf6, cfx
  IndexList uses;                  ///< indices of the motions that use this target
  /// KUKA S and T tokens (may be 'B...' literals) and the FANUC span of the CONFIG string's
  /// contents (value unused): 8 bytes while the target states none of them (inline targets).
  FieldBlock<3> config_fields;
  int file{-1};
  int line{0};
  Configuration config;
  std::uint32_t aggregate_end{0};  ///< KRL: offset of the closing `}` (S/T insertion)
  TextId frame_ref;  ///< frame the target itself declares (FANUC `UF`, CSV `frame`): Program::text
  TextId tool_ref;   ///< tool the target itself declares (FANUC `UT`, CSV `tool`): Program::text
  TargetKind kind{TargetKind::kCartesian};
  Orientation orientation{Orientation::kNone};

  [[nodiscard]] const NumberField& statusField() const { return config_fields[0]; }
  [[nodiscard]] const NumberField& turnField() const { return config_fields[1]; }
  [[nodiscard]] const NumberField& fanucConfig() const { return config_fields[2]; }
  /// Writable fields (allocate the block: read through a const Target where nothing is written).
  NumberField& statusField() { return config_fields[0]; }
  NumberField& turnField() { return config_fields[1]; }
  NumberField& fanucConfig() { return config_fields[2]; }
};

enum class MotionType : std::uint8_t { kJoint, kLinear, kCircular };

/// A resolved (or unresolved) frame: tool, base, work object, user frame.
struct Frame {
  std::string ref;  ///< as the program names it: `BASE_DATA[1]`, `$BASE`, `rdkWObj`, `UFRAME[1]`
  bool resolved{false};
  Pose pose{Pose::Identity()};  ///< SI; base: T_base_frame, tool: T_flange_tcp
  int file{-1};
  int line{0};  ///< where its value was set (0 = predefined)
};

/// A pose kept on the heap only when set (most motions have no offset): 8 bytes instead of 128;
/// reads identity until set.
class SparsePose {
 public:
  SparsePose() = default;
  SparsePose(const SparsePose& o) : p_(o.p_ ? std::make_unique<Pose>(*o.p_) : nullptr) {}
  SparsePose(SparsePose&&) noexcept = default;
  SparsePose& operator=(const SparsePose& o) {
    if (this != &o) p_ = o.p_ ? std::make_unique<Pose>(*o.p_) : nullptr;
    return *this;
  }
  SparsePose& operator=(SparsePose&&) noexcept = default;
  ~SparsePose() = default;
  [[nodiscard]] const Pose& get() const;
  /// Stores `pose`.
  void set(const Pose& pose) { p_ = std::make_unique<Pose>(pose); }

 private:
  std::unique_ptr<Pose> p_;
};

/// One motion instruction. Its texts are TextIds into Program::texts (read them with
/// Program::text); its markers are Program::markers(m). 96 bytes (a 100,000-hole KRL job holds
/// 400,000).
struct Motion {
  TextId instruction;  ///< as written: `LIN`, `MoveL`, `L`
  MotionType type{MotionType::kLinear};
  bool fine{false};            ///< exact stop at the point
  bool config_honoured{true};  ///< KUKA PTP / ABB ConfJ,ConfL \On / FANUC J: configuration taken
  bool has_offset{false};      ///< target = T_target · offset (tool) or offset · T_target (frame)
  bool offset_in_tool{false};
  int file{-1};
  int line{0};
  int target{-1};           ///< index into targets (-1: runtime target, see target_text)
  int aux{-1};              ///< CIRC/MoveC auxiliary point
  TextId target_text;       ///< source text of the target expression
  TextId derivation;        ///< "" plain; else `Offs`, `RelTool`, `LIN_REL`, `PR`, `:`, `Offset`,
                            ///< `Tool_Offset`...
  int tool{-1};             ///< index into frames
  int base{-1};             ///< index into frames
  double speed_mm_s{-1.0};  ///< linear speed when known, else < 0
  TextId speed_text;        ///< as written: `10mm/sec`, `rdkSpeed`, `0.01 m/s`
  TextId zone_text;         ///< `FINE`, `CNT50`, `z1`, `C_DIS`...
  /// Dwell, spindle, drill-call, comment markers after this motion: Program::marker_texts
  /// [marker_begin, marker_begin + marker_count) (see Program::markers / addMarker).
  std::uint32_t marker_begin{0};
  std::uint32_t marker_count{0};
  SparsePose offset;  ///< SI; RAPID Offs/RelTool, TP Offset/Tool_Offset with known values
};

/// The marker texts of one motion, iterated as `const std::string&`.
class MarkerRange {
 public:
  class const_iterator {
   public:
    const_iterator(const TextTable* t, const TextId* p) : t_(t), p_(p) {}
    const std::string& operator*() const { return (*t_)[*p_]; }
    const_iterator& operator++() {
      ++p_;
      return *this;
    }
    bool operator!=(const const_iterator& o) const { return p_ != o.p_; }
    bool operator==(const const_iterator& o) const { return p_ == o.p_; }

   private:
    const TextTable* t_;
    const TextId* p_;
  };
  MarkerRange(const TextTable& t, const TextId* b, const TextId* e) : t_(&t), b_(b), e_(e) {}
  [[nodiscard]] const_iterator begin() const { return {t_, b_}; }
  [[nodiscard]] const_iterator end() const { return {t_, e_}; }
  [[nodiscard]] bool empty() const { return b_ == e_; }
  [[nodiscard]] std::size_t size() const { return static_cast<std::size_t>(e_ - b_); }

 private:
  const TextTable* t_;
  const TextId* b_;
  const TextId* e_;
};

struct Unresolved {
  std::string ref;
  int file{-1};
  int line{0};
  std::string what;
};

/// A motion whose position was taught in another tool than the one the program selected before
/// it (FANUC `UTOOL_NUM=1`, then `P[5]` with `UT : 2`): the controller stops there. The readers
/// list it; predict and compensate refuse it (docs/programs.md §15).
struct ToolConflict {
  int motion{-1};        ///< index into Program::motions
  int selected_line{0};  ///< the line that selected the active tool (same file)
  std::string selected;  ///< the active tool (`UTOOL[1]`)
  std::string taught;    ///< the position's tool (`UTOOL[2]`)
};

struct Edit {
  int file{-1};
  std::uint32_t offset{0};
  std::uint32_t length{0};
  std::string text;
};

/// Notes of a Program that say how a file was read (a guess the user must be able to check)
/// start with this prefix; hosts show them (the CLI on stderr).
inline constexpr const char* kReadingNotePrefix = "reading: ";

struct Program {
  Dialect dialect{Dialect::kKrl};
  std::vector<SourceFile> files;  ///< KRL: [src, dat] (dat may be absent); others: one
  std::string dat_path;           ///< KRL: the `.dat` that belongs to the `.src` (may not exist)
  std::vector<Target> target_list;
  std::vector<Motion> motions;
  std::vector<Frame> frames;
  std::vector<Unresolved> unresolved;
  std::vector<ToolConflict> tool_conflicts;
  std::vector<std::string> notes;
  /// Texts of the target components stated by name or expression (NumberField::setExpression).
  std::vector<std::string> expressions;
  TextTable texts;                   ///< the motions' and targets' texts (TextId)
  std::vector<TextId> marker_texts;  ///< the motions' markers, motion after motion
  std::map<std::pair<int, std::uint32_t>, Edit> edits;  ///< pending edits by (file, offset)
  /// FANUC `$SCR_GRP[1].$TURN_AXIS[1..3]` (1-based joint numbers) when known (docs/programs.md §9.1
  /// item 1).
  std::optional<std::array<int, 3>> fanuc_turn_axes;
  /// Fewest decimals (mm) a changed position is printed with. 3 keeps the usual OLP style (1 µm);
  /// `roprec compensate` raises it to 5 (0.01 µm) so the written target carries the compensation
  /// to well below its 0.1 µm residual (the controllers parse any number of decimals).
  int position_min_decimals{3};

  [[nodiscard]] const std::vector<Target>& targets() const { return target_list; }
  /// A motion's or target's text.
  [[nodiscard]] const std::string& text(TextId id) const { return texts[id]; }
  /// The id of `s` in texts (stored when new).
  TextId addText(std::string_view s) { return texts.add(s); }
  /// Same without the look-up, for texts that rarely repeat (TextTable::append).
  TextId addUniqueText(std::string_view s) { return texts.append(s); }
  /// The markers of motion m.
  [[nodiscard]] MarkerRange markers(const Motion& m) const {
    const TextId* b = marker_texts.data() + m.marker_begin;
    return {texts, b, b + m.marker_count};
  }
  /// Appends a marker to the last motion (none: ignored). Markers go to the last motion only, so
  /// each motion's markers are one run of marker_texts.
  void addMarker(std::string_view marker);
  /// The name or expression a component states ("" for a number).
  [[nodiscard]] const std::string& exprText(const NumberField& f) const {
    static const std::string kNone;
    return f.named() ? expressions[f.offset - 1] : kNone;
  }
};

/// Reads a program; the dialect comes from the extension and the content. KRL: `x.src` reads
/// `x.dat` beside it when present. Throws InputError(file, line, message) on real errors.
Program readProgram(const std::string& path);
/// The same with `path`'s bytes already read (`bytes`: what readFileBytes(path) gives; a KRL
/// .src's .dat is still read from beside it).
Program readProgram(const std::string& path, std::string bytes);
/// Same from bytes already in memory (`dat_bytes` only for KRL; nullopt = no .dat).
Program parseProgram(Dialect d, const std::string& path, std::string bytes,
                     std::optional<std::string> dat_bytes = std::nullopt,
                     const std::string& dat_path = "");
/// Dialect from a path (extension, then content); throws InputError when unknown.
Dialect detectDialect(const std::string& path, const std::string& bytes);

/// Pose of a Cartesian target in its own frame (SI). Missing components read as 0 (see complete()).
Pose targetPose(const Program& p, const Target& t);
/// Whether the target states all six pose components.
bool targetComplete(const Target& t);
/// Pose the motion moves to in its base frame's coordinates (target pose with any known
/// offset applied); nullopt for joint or runtime targets.
std::optional<Pose> motionPose(const Program& p, const Motion& m);
/// Joint values in degrees (or mm) of a joint target.
std::vector<double> targetJointsDeg(const Target& t);
/// Base frame / tool frame of the first motion that uses the target (or the target's own
/// declaration); nullptr when unknown.
const Frame* targetBase(const Program& p, const Target& t);
const Frame* targetTool(const Program& p, const Target& t);
/// Whether every motion that uses the target shares one tool and one base.
bool targetFramesConsistent(const Program& p, const Target& t);

struct EditResult {
  bool ok{false};
  std::string reason;  ///< why the edit was refused (nothing changed then)
};

/// Replaces target `index`'s pose by T_frame_tcp (SI, same frame as the target) and, when given,
/// its configuration (raw flags of the target's vendor). Only changed numeric tokens are
/// re-printed. Refuses (ok = false, program unchanged) rather than guess (docs/programs.md §9):
/// joint targets, targets missing pose components, targets shared by motions with different
/// tools/frames, FANUC turn digits changed while $TURN_AXIS is unknown, a configuration of
/// another vendor.
EditResult replaceTargetPose(Program& p, int index, const Pose& T_frame_tcp,
                             const std::optional<Configuration>& config = std::nullopt);

/// Edits queued away from Program::edits, in the order they were made: a put replaces the
/// pending edit at (edit.file, edit.offset), an erase drops it (edit.text unused).
struct EditLog {
  struct Op {
    bool erase{false};
    Edit edit;
  };
  std::vector<Op> ops;
};

/// replaceTargetPose with its edits queued into `log` instead of p.edits; applyEdits(p, log)
/// queues them later. It reads `p` and writes only target `index` (its values and flags), so
/// several threads may prepare the targets of one program at once as long as no two of them
/// touch the same target (roprec compensate --threads). Applying the logs in the order
/// the calls would have run gives the bytes of the direct calls.
EditResult replaceTargetPose(Program& p, int index, const Pose& T_frame_tcp,
                             const std::optional<Configuration>& config, EditLog& log);
/// Replays `log` into p.edits, in order (the edits' texts are moved out of it).
void applyEdits(Program& p, EditLog&& log);

/// Defines a frame the program refers to but does not define (e.g. `UFRAME[1]` of a TP
/// program, `BASE_DATA[3]` of a KRL program from $config.dat). Returns how many uses resolved.
int resolveFrame(Program& p, const std::string& ref, const Pose& pose);

/// Drops motions [0, n) of `p` (a program read by windows), their target texts and their markers
/// (the motions after them keep theirs); targets and uses are the caller's.
void dropFirstMotions(Program& p, std::size_t n);

/// The "roprec compensated" marker (docs/programs.md §15) found in a program's files.
struct MarkerLocation {
  int file{-1};
  int line{0};       ///< 1-based
  std::string text;  ///< from "roprec compensated" to the end of its line
};
/// The first marker line in the program, nullopt when it has none.
std::optional<MarkerLocation> findCompensationMarker(const Program& p);
/// Queues the marker line "roprec compensated: `what`" in the dialect's comment syntax: KRL `;`
/// after the `DEF` line, RAPID `!` after the `MODULE` line, FANUC TP a `!` remark as /MN line 1
/// (the lines after it renumbered, `LINE_COUNT` + 1), CSV `#` as the first line. Returns false
/// when the dialect has no comment syntax (JSON) or the anchor line is missing.
bool markCompensated(Program& p, const std::string& what);

/// markCompensated of a FANUC TP program read by windows of whole lines (StreamedEdits): fed each
/// window in file order, it gives the edits markCompensated gives of the whole file that fall in
/// that window or before it (the remark, the /MN lines renumbered, `LINE_COUNT` + 1 once /MN is
/// found), each as (byte of the file, length replaced, text).
class TpMarkStream {
 public:
  using Put = std::function<void(std::uint64_t at, std::uint32_t length, std::string text)>;
  /// `eol`: the whole file's dominant line end (the remark's).
  TpMarkStream(const std::string& what, std::string eol);
  /// The edits of window `f`, whose first byte is byte `start` of the file; its lines that start
  /// before the end of the windows fed before (a line read again) are not looked at again.
  void window(const SourceFile& f, std::uint64_t start, const Put& put);
  /// After the last window: the remark of a /MN with no numbered line that the file ends in.
  void finish(const Put& put);
  /// Whether the /MN line was found: the marker is made.
  [[nodiscard]] bool marked() const { return phase_ != Phase::kHeader; }

 private:
  enum class Phase { kHeader, kMn, kDone };
  /// A line's text `t`, its first byte `at` in the file and the byte after it `next`.
  void line(std::string_view text, std::uint64_t at, std::uint64_t next, const Put& put);
  void endMn(const Put& put);
  std::string text_;
  std::string eol_;
  Phase phase_{Phase::kHeader};
  std::uint64_t seen_{0};      ///< the bytes of the file looked at
  bool first_{true};           ///< no numbered /MN line yet
  std::uint64_t after_mn_{0};  ///< the byte after the /MN line
  struct Edit {
    std::uint64_t at{0};
    std::uint32_t length{0};
    std::string text;
  };
  std::optional<Edit> line_count_;  ///< `LINE_COUNT = n` + 1, put once /MN is found
  bool line_count_seen_{false};
};

/// The program's files after the pending edits: (path suffix role, bytes). KRL: [.src, .dat].
std::vector<std::string> renderFiles(const Program& p);
/// Writes the program atomically. KRL: `out_path` names the `.src`; the `.dat` goes beside it
/// (same stem) when the program has one.
void writeProgram(const Program& p, const std::string& out_path);
/// The paths writeProgram(p, out_path) writes.
std::vector<std::string> outputPaths(const Program& p, const std::string& out_path);

// ---- number style (docs/programs.md §2.9, §3.8, §4.8)

struct NumberHints {
  int min_decimals{3};  ///< absolute resolution kept for changed values (mm/deg: 3, quaternions: 9)
  bool significant9{false};       ///< KSS style: 9 significant digits, trailing zeros kept
  bool drop_leading_zero{false};  ///< file writes `.044` (FANUC controller)
};

/// Prints `value` in the style of `original` (a token's text, sign included).
std::string formatLike(std::string_view original, double value, const NumberHints& h);
/// Parses a number token (sign, decimals, exponent); nullopt when malformed.
std::optional<double> parseNumber(std::string_view text);

/// Queues a replacement of a numeric field when its printed value changes; updates f.value.
void setNumber(Program& p, NumberField& f, double value, const NumberHints& h);
/// Queues an arbitrary span replacement (used by dialect writers for non-numeric spans).
void queueEdit(Program& p, int file, std::uint32_t offset, std::uint32_t length, std::string text);

}  // namespace roprec::postproc
