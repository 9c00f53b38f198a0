#pragma once
/// \file input_file.hpp
/// The one loader of roprec's input files (cells, robot cards, URDFs, programs, hole lists,
/// measured holes; docs/contract.md "Input files"). Before any reader sees the bytes it refuses:
/// a folder ("is a directory"), anything but a regular file (devices, FIFOs, sockets: no command
/// reads a stream), a file above the size limit of its kind (the environment variable
/// ROPREC_MAX_INPUT_MB raises every limit), a UTF-16 or UTF-32 file ("this file is UTF-16; save
/// it as UTF-8") and a NUL byte (at its FILE:LINE:COL). A UTF-8 byte-order mark is accepted.
/// Bytes that are not valid UTF-8 are kept (a controller's Latin-1 comment passes through a
/// program unchanged); JSON and HTML outputs escape them (docs/contract.md).
/// The file is noted as an input of the active output set (atomic_file.hpp), so no output of the
/// run can replace it.

#include <cstddef>
#include <string>
#include <string_view>

namespace roprec {

/// What an input file is: names it in messages and sets its size limit.
enum class InputKind {
  kCell,       ///< cell XML: 64 MB
  kRobotCard,  ///< robot card XML: 64 MB
  kUrdf,       ///< URDF: 64 MB
  kXml,        ///< any other XML: 64 MB
  kProgram,    ///< robot program (and KRL .dat): 2048 MB
  kHoleList,   ///< hole list CSV: 2048 MB
  kMeasured,   ///< measured holes CSV: 2048 MB
};

/// The size limit of `kind` in bytes (ROPREC_MAX_INPUT_MB, a whole number of MB, overrides it).
std::size_t inputSizeLimit(InputKind kind);

/// Reads an input file whole after the checks above. Throws InputError naming the file.
std::string readInputFile(const std::string& path, InputKind kind);

/// The encoding checks alone (UTF-16/32, NUL) on text read from `file`: InputError at FILE:LINE.
void checkInputText(std::string_view bytes, const std::string& file);

/// `name` for a message: whole when it is at most `max_bytes` long, else its first bytes (not
/// cutting a UTF-8 sequence) and "… (N bytes)".
std::string clipForMessage(std::string_view name, std::size_t max_bytes = 80);

}  // namespace roprec
