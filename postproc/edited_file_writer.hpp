#pragma once
/// \file edited_file_writer.hpp
/// One file of a program written out while its edits are still being made (`roprec compensate`
/// of a large program): the bytes before a point that no later edit reaches are written with the
/// pending edits among them applied, and those edits are dropped from Program::edits, so the
/// queued edits and the written text never hold the whole program. Once every edit is made and
/// finish() called, the bytes written are renderFiles(p)[file].
///
///   EditedFileWriter out(p, 0, write);
///   for each block of holes: edit their targets; out.flushBefore(first offset a later edit may
///   touch); out.finish();

#include <cstddef>
#include <string>

#include "compensator/support/atomic_file.hpp"
#include "postproc/program.hpp"

namespace roprec::postproc {

class EditedFileWriter {
 public:
  /// Writes file `file` of `p` to `write` (pieces of about kBufferBytes).
  EditedFileWriter(Program& p, int file, ByteWriter write);
  /// Writes the file's bytes before `offset` with the pending edits among them, and drops those
  /// edits from p.edits; a pending edit that starts before `offset` and ends after it stays, with
  /// the bytes from its start. No edit may be queued before the bytes written since (logic_error
  /// "overlapping edits", as renderFiles).
  void flushBefore(std::size_t offset);
  /// Writes the rest of the file with every pending edit of it.
  void finish();

 private:
  static constexpr std::size_t kBufferBytes = std::size_t{1} << 20U;
  void emit(std::string_view bytes);
  Program& p_;
  int file_;
  ByteWriter write_;
  std::size_t pos_{0};  ///< bytes of the file written (edits applied)
  std::string buf_;
};

}  // namespace roprec::postproc
