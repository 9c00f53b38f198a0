#pragma once
/// \file dialects.hpp
/// Internal interface between the generic program model (program.cpp), the dialect readers and
/// drill-cycle recognition (drill.cpp).

#include <memory>
#include <string>
#include <utility>

#include "postproc/program.hpp"

namespace roprec::postproc {

/// Readers fill p.target_list/motions/frames/unresolved from p.files (already loaded, lines
/// indexed). They throw InputError(file, line, message) on real errors.
void parseKrl(Program& p);
void parseRapid(Program& p);
void parseTp(Program& p);
void parseCsv(Program& p);
void parseJson(Program& p);

/// The `.src` of a KRL program path (a `.dat` names the `.src` beside it: InputError when there is
/// none) and its `.dat` ("" when there is none beside it).
std::pair<std::string, std::string> krlFiles(const std::string& path);

/// What KrlStream::lexWindow() reads of a window besides its tokens: the target aggregates of
/// its motion lines and the targets they make, parsed as the reader parses them, and the lines'
/// target expressions split as the reader splits them (defined in krl.cpp).
struct KrlAhead;
/// The target aggregates a KrlAhead holds.
std::size_t aggregatesReadAhead(const KrlAhead& a);
/// The targets those aggregates made (not taken yet).
std::size_t targetsReadAhead(const KrlAhead& a);

/// The KRL reader a window of the .src at a time (ProgramStream): constructed once p.files holds
/// the .src's first window and the .dat (read then); lines() reads the lines of the window
/// p.files[0] holds now, finish() checks the .src's end after the last window.
class KrlStream {
 public:
  explicit KrlStream(Program& p);
  ~KrlStream();
  KrlStream(const KrlStream&) = delete;
  KrlStream& operator=(const KrlStream&) = delete;
  void lines();
  /// lines() of a window whose tokens lexWindow() put in p.files[0].tokens already; `ahead`:
  /// what lexWindow() returned for them (its aggregates, targets and splits are taken instead of
  /// read again; its targets are moved from).
  void lexedLines(KrlAhead* ahead = nullptr);
  void finish();
  /// Lexes a window of whole lines of a .src (not its first: no byte-order mark) into f.tokens
  /// as lines() would, line after line, and reads its motion lines (their target aggregates,
  /// the targets they make, their target expressions) into `ahead` (made when null, else
  /// refilled: its memory is reused): lexedLines() then takes them (this may run on another
  /// thread, ahead of the reader).
  static void lexWindow(SourceFile& f, std::shared_ptr<KrlAhead>& ahead);
  /// The motion the reader may still change (the last segment of a SPLINE block being read),
  /// -1 when none: motions from it on may not be retired.
  [[nodiscard]] int heldMotion() const;
  /// Motions [0, m) of the window were dropped (their indices shift by m).
  void retired(std::size_t m);

 private:
  struct Reader;
  std::unique_ptr<Reader> r_;
};

/// The RAPID reader a window of whole lines of the module at a time (ProgramStream): constructed
/// once p.files holds the first window; lines() reads the constructs of the window p.files[0]
/// holds now (`last`: no bytes follow it) up to one the window ends inside, whose line (from
/// carry(), its tokens before it skipped) starts the next window (a construct longer than a window
/// grows the next one until it holds it; the module's header likewise); finish() checks the
/// module's end after the last window. The reader's state (declarations, tools, work objects,
/// numbers, nesting) is that of the whole read at the same point: the same targets, motions,
/// frames, notes and errors, in the same order.
class RapidStream {
 public:
  explicit RapidStream(Program& p);
  ~RapidStream();
  RapidStream(const RapidStream&) = delete;
  RapidStream& operator=(const RapidStream&) = delete;
  void lines(bool last);
  /// The offset in p.files[0] (a line start) the next window starts with; its size when none.
  [[nodiscard]] std::size_t carry() const;
  void finish();
  /// Targets [begin, end) of p.target_list were dropped (none of them declared by name).
  void retiredTargets(std::size_t begin, std::size_t end);

 private:
  struct Reader;
  std::unique_ptr<Reader> r_;
};

/// The FANUC TP reader a window of whole lines at a time (ProgramStream), as two readers over the
/// same file: a scan, constructed once p.files holds the first window, reads the windows of
/// p.files[0] in order (lines(); `last`: no bytes follow it) up to a /POS record a window ends
/// inside, whose line (carry()) starts the next window: its errors, notes and unresolved
/// references, and the records; the motions it reads in /MN it drops, counting the references to
/// each position. Once it has read /MN, a second reader reads /MN again by windows of
/// motionFile() (motionLines()), behind it, and makes the motions; the scan binds them to the
/// records in order as both come (settled()), with the whole read's unresolved entries, frames and
/// uses in the same order. wantsMotions() says which reader reads next: the motions' while none
/// waits for a record. finish() checks the file's end after the scan's last window, end() binds
/// the rest once both are read (positions not in /POS). A record goes once no motion to come
/// names it (needed()).
class TpStream {
 public:
  explicit TpStream(Program& p);
  ~TpStream();
  TpStream(const TpStream&) = delete;
  TpStream& operator=(const TpStream&) = delete;
  void lines(bool last);
  /// The offset in p.files[0] (a line start) the next window starts with; its size when none.
  [[nodiscard]] std::size_t carry() const;
  void finish();
  /// Whether the motions' reader reads its next window now.
  [[nodiscard]] bool wantsMotions() const;
  /// The motions' reader's window (its path set; the caller fills its bytes and lines).
  SourceFile& motionFile();
  void motionLines(bool last);
  /// Whether the motions' reader has read /MN whole.
  [[nodiscard]] bool motionsRead() const;
  void end();
  /// Motions [0, settled()) are bound (the reader changes them no more).
  [[nodiscard]] std::size_t settled() const;
  /// Whether target `target`'s position is named by a motion not bound yet (it must stay).
  [[nodiscard]] bool needed(std::size_t target) const;
  /// Motions [0, m) were dropped.
  void retired(std::size_t m);
  /// Targets [begin, end) were dropped.
  void retiredTargets(std::size_t begin, std::size_t end);

 private:
  struct Reader;
  std::unique_ptr<Reader> r_;
};

/// Where the edit functions queue their edits: Program::edits, or an EditLog replayed later.
class EditQueue {
 public:
  explicit EditQueue(Program& p) : map_(&p.edits) {}
  explicit EditQueue(EditLog& log) : log_(&log) {}
  /// Replaces the pending edit at (file, offset).
  void put(int file, std::uint32_t offset, std::uint32_t length, std::string text);
  /// Drops the pending edit at (file, offset), if any.
  void erase(int file, std::uint32_t offset);

 private:
  std::map<std::pair<int, std::uint32_t>, Edit>* map_{nullptr};
  EditLog* log_{nullptr};
};

/// setNumber with its edit queued into `q`; reads `p` (the token's text and the file's style).
void setNumber(const Program& p, EditQueue& q, NumberField& f, double value, const NumberHints& h);

/// Writes a configuration change into the target's tokens (dialect specific), queued into `q`.
EditResult writeConfiguration(const Program& p, EditQueue& q, Target& t, const Configuration& c);

/// Number-style hints for a field of a program (file-level style detection).
NumberHints hintsFor(const Program& p, const NumberField& f, bool quaternion);

/// A parsed number as an int; `fallback` when not finite or beyond ±1e9 (never UB on huge input).
inline int toInt(double v, int fallback = -1) {
  return (v == v && v > -1e9 && v < 1e9) ? static_cast<int>(v) : fallback;
}

/// A JSON string literal of `s` (quotes and backslashes escaped) for the target-list writers.
inline std::string jsonStr(const std::string& s) {
  std::string r = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') r += '\\';
    r += c;
  }
  return r + "\"";
}

/// Throws InputError at the token's line.
[[noreturn]] void failAt(const SourceFile& f, std::size_t offset, const std::string& msg);

/// Adds a frame snapshot unless identical to the last one; returns its index.
int internFrame(Program& p, const Frame& f);

/// Frames a and b of p (indices into p.frames, -1: none) are the same frame: the same reference
/// (case-insensitive), resolution and pose.
bool sameFrame(const Program& p, int a, int b);

/// Number field of the token [begin, end) of `sf`, file `file` (index into p.files), whose value
/// the reader has already parsed. Throws InputError for a number longer than
/// NumberField::kMaxLength bytes.
NumberField tokenField(const SourceFile& sf, int file, std::uint32_t begin, std::uint32_t end,
                       double value);

/// Number field from a token span [begin, end) whose text parses as a number; throws a
/// "broken number" InputError otherwise. `file` is the index into p.files.
NumberField numberField(const Program& p, int file, std::uint32_t begin, std::uint32_t end);

}  // namespace roprec::postproc
