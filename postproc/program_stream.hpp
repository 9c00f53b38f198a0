#pragma once
/// \file program_stream.hpp
/// A program read a window at a time, for a job that writes no program (`roprec predict`): it
/// needs the motions in order, never the whole model. A KUKA KRL `.src` is read by windows of
/// whole lines (about `window_bytes` each) through one reader that keeps its state from window to
/// window; its `.dat` is read whole first (declarations before the lines that use them). The
/// window Program holds the motions and targets read since the last retire() (every target of
/// the `.dat` and every named target stays), and the frames, notes and unresolved references of
/// everything read so far; its `.src` SourceFile holds the window's bytes (lineOf() gives the
/// file's line: SourceFile::line_base). With `rapid`, an ABB RAPID module is read by windows of
/// whole lines too (RapidStream: a statement a window ends inside is read again from its line at
/// the start of the next window); its targets declared by name stay, its inline targets go with
/// their motions. With `rapid` too, a FANUC TP program is read by windows of whole lines by two
/// readers (TpStream): a scan of the whole file in order (a /POS record a window ends inside is
/// read again from its line), whose windows are program().files[0], and a second reading of /MN
/// behind it, from a window of its own, that makes the motions; they are bound to the records in
/// order as both come, and a record goes once no motion to come names it (a home position named
/// again at the end stays until then; records far out of the motions' order hold the records
/// between). The other dialects are read whole, as one window.
///
/// Errors are those readProgram gives, in the same order: a reader's error where it is met, a
/// value out of range (checkValueRanges) once the whole program is read without one (RAPID: the
/// first target's, else frame's, else motion's, as checkValueRanges orders them; within a kind the
/// first met, which is the whole read's unless a robtarget declared early is out of range and
/// first used after another target out of range; TP: unless a position record out of range is
/// first used after another out of range that follows it in /POS).
///
///   ProgramStream s(path);
///   HoleRecognizer rec;
///   while (s.next()) { rec.advance(s.program(), false); ...; s.retire(m); }
///   rec.advance(s.program(), true);

#include <cstddef>
#include <cstdint>
#include <exception>
#include <future>
#include <memory>
#include <string>
#include <vector>

#include "compensator/support/platform.hpp"
#include "postproc/program.hpp"
#include "postproc/value_ranges.hpp"

namespace roprec::postproc {

class KrlStream;
class RapidStream;
class TpStream;
class HoleRecognizer;
struct KrlAhead;

/// What retire() dropped: motions [0, motions) and targets [target_begin, target_end) of the
/// window; the indices after them shift down by as many.
struct Retired {
  std::size_t motions{0};
  std::size_t target_begin{0};
  std::size_t target_end{0};
};

class ProgramStream {
 public:
  static constexpr std::size_t kWindowBytes = std::size_t{1} << 20U;
  /// Opens `path` as readProgram does (a KRL `.dat` reads its `.src`; the same InputErrors).
  /// `read_ahead`: a KRL .src's next window is read, indexed and lexed on a task of its own
  /// while the reader reads the window before (the same windows, tokens and errors, in the same
  /// order; for a caller with a second core).
  /// `rapid`: a RAPID module or a TP program is read by windows as well (read_ahead does not
  /// apply to them).
  explicit ProgramStream(const std::string& path, std::size_t window_bytes = kWindowBytes,
                         bool read_ahead = false, bool rapid = false);
  ~ProgramStream();
  ProgramStream(const ProgramStream&) = delete;
  ProgramStream& operator=(const ProgramStream&) = delete;

  /// Reads the next window into program(); false (program() unchanged) once the whole program
  /// was read: the end-of-file checks are then done and a value out of range thrown.
  bool next();
  [[nodiscard]] Program& program() { return p_; }
  [[nodiscard]] const Program& program() const { return p_; }
  /// A reading of a program read (and checked) whole before: next() checks no value range any
  /// more (checkValueRanges), the reader's errors stay.
  void skipValueRanges() { skip_ranges_ = true; }
  /// Whether the program is read by windows (KRL; RAPID and TP with `rapid`); false: next() reads
  /// it whole once.
  [[nodiscard]] bool windowed() const {
    return krl_ != nullptr || rapid_ != nullptr || tp_ != nullptr;
  }
  /// The window's motions [0, settledMotions()) the reader will not change any more: all of them
  /// but from the held segment of a SPLINE block being read (every one once the program is read).
  [[nodiscard]] std::size_t settledMotions() const;
  /// Drops the window's motions before `m` (fewer when the reader may still change one of them;
  /// the last motion always stays: a marker after it belongs to it) and the unnamed targets only
  /// they use, their texts released. A whole-read program drops nothing.
  Retired retire(std::size_t m);
  /// The byte of the file (the KRL `.src`, the RAPID module) program().files[0] starts at: the
  /// window's first byte. A RAPID window starts with the line of a statement the window before
  /// ended inside, so windows may overlap there; the targets read on that line before the window
  /// changed are moved to the new window's offsets (the same bytes).
  [[nodiscard]] std::uint64_t windowStart() const { return window_start_; }
  /// The byte of the file the next window starts at: the end of the bytes no later window reads
  /// again (a RAPID window's carried line; the end of a KRL window).
  [[nodiscard]] std::uint64_t settledEnd() const;
  /// Windows of the first file read so far: next() may return without a new one (a TP program's
  /// motions are read from a second window of their own).
  [[nodiscard]] std::uint64_t windowCount() const { return window_count_; }

 private:
  /// next() of a TP program: the scan's next window or the motions' (TpStream::wantsMotions()).
  bool nextTp();
  /// The next window's bytes of whole lines of `file` into `buf` (empty at the end of the file),
  /// the bytes read after its last line kept in `rest`.
  void readLines(platform::File& file, std::string& rest, bool& eof, std::size_t& read,
                 std::string& buf) const;
  /// Fills p_.files[0].bytes with the next window of whole lines; false at the end of the file.
  bool readWindow();
  /// readWindow() of a RAPID module or a TP program: the window starts with the reader's carry.
  bool readCarriedWindow();
  /// The offset in the window the next window starts at (a RAPID statement, a TP position
  /// record the window ended inside); the window's size when none.
  [[nodiscard]] std::size_t carry() const;
  /// The first file's targets on line `line`, read in the window before from byte `cut` of it on,
  /// moved to the offsets of the window that starts with that line (windowStart()).
  void moveCarriedTargets(int line, std::uint32_t cut);
  /// Opens the file the windows are read from (readInputFile's errors).
  void openWindows(const std::string& path);
  /// The next window's bytes of whole lines into `buf` (empty at the end of the file).
  void readWindowBytes(std::string& buf);
  /// A window read, indexed and lexed ahead, with what KrlStream::lexWindow read of it.
  struct Ahead {
    SourceFile file;
    std::shared_ptr<KrlAhead> read;
  };
  /// The memory of a window done with (its capacity kept), for the window read after it: no
  /// new pages per window.
  struct Spare {
    std::string bytes;
    std::vector<std::uint32_t> line_starts;
    std::vector<LineEnd> line_ends;
    std::vector<Token> tokens;
    std::shared_ptr<KrlAhead> read;
  };
  /// A SourceFile for the next window, on the spare's memory (taken).
  static SourceFile fromSpare(Spare& s);
  /// Makes `w` (the bytes, line index and tokens of the window after the last one) p_.files[0];
  /// the line ends of the first `lines_done` lines of the window before are counted as earlier
  /// lines' (SourceFile::earlier_ends; the others are read again).
  void installWindow(SourceFile&& w, std::size_t lines_done = SIZE_MAX);
  /// checkValueRanges of the window: its first error kept for the end.
  void checkRanges();
  /// Starts reading, indexing and lexing the next window on a task of its own (read_ahead).
  void startAhead();

  std::string path_;
  std::string src_;  ///< the KRL .src's path
  std::size_t window_bytes_;
  Program p_;
  std::unique_ptr<KrlStream> krl_;
  std::unique_ptr<RapidStream> rapid_;
  std::unique_ptr<TpStream> tp_;
  platform::File mn_file_;  ///< TP: the file again, for the motions' reader (TpStream)
  std::string mn_rest_;
  bool mn_eof_{false};
  std::size_t mn_read_{0};
  bool tp_done_{false};  ///< TP: the scan read the whole file
  std::uint64_t window_count_{0};
  platform::File file_;
  std::string rest_;               ///< bytes read after the window's last line
  std::size_t read_{0};            ///< bytes of the .src read so far
  std::uint64_t window_start_{0};  ///< windowStart()
  bool eof_{false};
  bool whole_read_{false};
  bool finished_{false};
  bool pending_{false};    ///< the window the constructor read is not parsed yet
  std::size_t pinned_{0};  ///< targets that always stay (the .dat's)
  std::exception_ptr range_error_;
  RangeErrors rapid_ranges_;  ///< RAPID: the first value out of range of each kind
  Spare spare_;  ///< the window before the one p_ holds (read_ahead: taken by the next task)
  bool read_ahead_{false};
  bool skip_ranges_{false};
  std::future<Ahead> ahead_;  ///< the next window (read_ahead); last: joined first
};

}  // namespace roprec::postproc
