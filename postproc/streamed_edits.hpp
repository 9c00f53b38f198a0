#pragma once
/// \file streamed_edits.hpp
/// The target edits of a KRL program, a RAPID module or a TP program read by windows
/// (ProgramStream) and written out as they become final: the first file's windows are kept from the
/// first byte not written yet, an edit of a target is made in the bytes of the window that holds it
/// and queued at its byte of the file, and the bytes before the line of the earliest target the
/// stream's program still holds (no later edit can reach them) go to the writer. The `.dat` is held
/// whole (ProgramStream) and its edits applied at the end. The bytes are those writeProgram gives
/// of the program read whole with the same edits and the same compensation marker.
///
///   ProgramStream s(path);
///   StreamedEdits e(s, write, marker, style);
///   while (s.next()) { e.installed(); ...; e.replaceTargetPose(t, T, cfg); ...; e.flush(); }
///   e.finish();  const std::optional<std::string> dat = e.dat();

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "compensator/support/atomic_file.hpp"
#include "postproc/program.hpp"
#include "postproc/program_stream.hpp"

namespace roprec::postproc {

class StreamedEdits {
 public:
  /// A window of the first file: its first byte in the file, its lines and bytes.
  struct Window {
    std::uint64_t start{0};
    int line_base{0};
    std::vector<std::uint32_t> line_starts;
    std::string bytes;
  };

  /// `stream` read by windows (windowed()), before its first next(); `write` receives the first
  /// file's bytes in order; `marker` (markCompensated) is queued once the window with the DEF
  /// line is installed; `style`: the first file's number style read over the whole file (a first
  /// reading's SourceFile).
  StreamedEdits(ProgramStream& stream, ByteWriter write, std::string marker,
                const SourceFile& style);
  /// After each next() of the stream that returned true: keeps the window's bytes (when it read
  /// one).
  void installed();
  /// replaceTargetPose of target `index` of the stream's program, made in the bytes of the window
  /// that holds it and queued (the target must still be in the stream's program).
  EditResult replaceTargetPose(int index, const Pose& T_frame_tcp,
                               const std::optional<Configuration>& config);
  /// Writes the first file's bytes before the line of the earliest target of file 0 the stream's
  /// program holds (an edit reaching past it waits), and drops the windows written.
  void flush();
  /// flush() for a caller that knows where the next edit can be: the first file's bytes before
  /// line `line` (a line not read yet, e.g. INT_MAX: every byte read whose line no later window
  /// reads again).
  void flushBeforeLine(int line);
  /// Once the stream is read to its end (next() returned false) and every edit made: the rest of
  /// the first file.
  void finish();
  /// The `.dat` with its edits, nullopt for a program without one.
  [[nodiscard]] std::optional<std::string> dat() const;

  /// For a caller that makes the edits itself (an EditLog in a window's bytes, e.g. on workers):
  /// the window that holds line `line` of the first file (1-based), the latest window installed,
  /// and the queueing of one edit at byte `at` of file `file` (0: the first file, offsets in the
  /// whole file; erase: drop the edit queued there).
  Window& windowOf(int line);
  Window* latestWindow() { return windows_.empty() ? nullptr : &windows_.back(); }
  void put(bool erase, int file, std::uint64_t at, std::uint32_t length, std::string&& text);

 private:
  static constexpr std::size_t kOutBytes = std::size_t{1} << 20U;
  struct Pending {
    std::uint32_t length{0};
    std::string text;
  };
  /// A file's pending edits by their first byte, in order: a map's put and erase on a deque (the
  /// edits come in file order almost always: appended, and written from the front).
  class PendingEdits {
   public:
    using Item = std::pair<std::uint64_t, Pending>;
    /// The edit at `at` (replacing one there).
    void put(std::uint64_t at, Pending&& p);
    /// Drops the edit at `at`, if any.
    void erase(std::uint64_t at);
    /// Whether `at` lies after every pending edit.
    [[nodiscard]] bool after(std::uint64_t at) const {
      return items_.empty() || at > items_.back().first;
    }
    std::deque<Item>& items() { return items_; }
    [[nodiscard]] const std::deque<Item>& items() const { return items_; }

   private:
    std::deque<Item>::iterator lowerBound(std::uint64_t at);
    std::deque<Item> items_;
  };
  /// The TP marker's edits queued in the first file.
  TpMarkStream::Put queueMark();
  void emit(std::string_view b);
  void emitBytes(std::uint64_t a, std::uint64_t b);
  void flushBefore(std::uint64_t upto);

  ProgramStream& stream_;
  ByteWriter write_;
  std::string marker_;
  SourceFile style_;
  bool marked_{false};
  std::uint64_t installed_{0};  ///< ProgramStream::windowCount() when installed() last kept one
  std::optional<TpMarkStream> tp_mark_;  ///< a TP program's marker, window by window
  std::deque<Window> windows_;
  std::uint64_t total_{0};    ///< bytes of the first file read
  std::uint64_t written_{0};  ///< bytes of the first file written (edits applied)
  PendingEdits edits_;
  PendingEdits dat_edits_;
  std::string out_;
};

}  // namespace roprec::postproc
