#pragma once
/// \file platform.hpp
/// The operating-system layer: the few file, folder, process and module calls that POSIX and
/// Windows spell differently, behind one interface (platform.cpp holds both implementations;
/// nothing else in roprec includes a POSIX or Windows header). Paths are UTF-8 strings
/// everywhere in roprec; on Windows they reach the wide-character API (Linux: the bytes as given).
/// Errors are errno values (std::strerror texts, the same words on both systems); a Windows error
/// without an errno equivalent is negative (-GetLastError()), and errorText() gives its text.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace roprec::platform {

/// The characters that end a folder's name in a path: "/" (Windows: "/" and "\\").
#ifdef _WIN32
inline constexpr const char* kPathSeparators = "/\\";
#else
inline constexpr const char* kPathSeparators = "/";
#endif

/// A path from UTF-8 bytes (Linux: the bytes unchanged) and back.
std::filesystem::path fromUtf8(std::string_view utf8);
std::string toUtf8(const std::filesystem::path& path);

/// The program's arguments as UTF-8 (Windows: from the wide command line, whatever the code page;
/// Linux: argv as given).
std::vector<std::string> utf8Arguments(int argc, char** argv);
/// Standard input/output/error pass bytes unchanged (Windows: no "\n" -> "\r\n" translation),
/// and a write to a closed pipe fails with EPIPE instead of ending the process (SIGPIPE ignored).
void setUpStdio();
/// Writes all of `bytes` to standard output (file descriptor 1): 0 or an errno value.
int writeStdout(std::string_view bytes);
/// True when standard error is a terminal.
bool stderrIsTerminal();

/// What a path is. kMissing: it does not exist (error ENOENT) or a folder of its path is a file
/// (ENOTDIR); kError: it could not be examined (error says why).
enum class Kind { kMissing, kError, kRegular, kFolder, kSymlink, kFifo, kNullDevice, kOther };
struct Status {
  Kind kind{Kind::kMissing};
  int error{0};
  std::uint64_t device{0};  ///< with inode: the file's identity (same file <=> same pair)
  std::uint64_t inode{0};
  std::uint64_t size{0};
};
/// The path itself (a symbolic link is kSymlink: lstat).
Status linkStatus(const std::string& path);
/// What the path resolves to (links followed: stat).
Status fileStatus(const std::string& path);
/// The text of an error value (std::strerror for errno values).
std::string errorText(int error);

/// An open file (a descriptor). Every call returns 0 or an error value.
class File {
 public:
  File() = default;
  File(const File&) = delete;
  File& operator=(const File&) = delete;
  ~File();
  /// For reading (does not block on a FIFO; not inherited by child processes).
  int openRead(const std::string& path);
  /// A new file for writing: fails with EEXIST if `path` exists (never follows a link there).
  int createNew(const std::string& path);
  [[nodiscard]] bool isOpen() const { return fd_ >= 0; }
  [[nodiscard]] Status status() const;
  /// Reads up to `n` bytes into `into`; the count (0 at the end) or -1 with *error set.
  long long read(char* into, std::size_t n, int* error);
  int writeAll(std::string_view bytes);
  /// Starts the disk write of bytes [offset, offset + length) without waiting (Linux; a hint).
  void startWriteBack(std::uint64_t offset, std::uint64_t length);
  /// Flushes the file's data to the disk (fsync / FlushFileBuffers).
  int sync();
  int close();

 private:
  int fd_{-1};
};

/// Renames `from` onto `to`, replacing `to` atomically (rename / MoveFileExW with
/// MOVEFILE_REPLACE_EXISTING | MOVEFILE_WRITE_THROUGH): 0 or an error value.
int replaceFile(const std::string& from, const std::string& to);
/// Removes a file (errors ignored).
void removeFile(const std::string& path);
/// Makes a folder's entries durable (fsync on the folder; Windows: the renames are write-through).
void syncFolder(const std::string& dir);
/// The names in a folder ("." and ".." may be among them); empty when it cannot be read.
std::vector<std::string> folderEntries(const std::string& dir);

/// An exclusive lock on a folder between processes and threads (flock on the folder; Windows:
/// a named mutex of the folder's resolved path), released by the destructor.
class FolderLock {
 public:
  FolderLock() = default;
  FolderLock(FolderLock&& other) noexcept;
  FolderLock& operator=(FolderLock&& other) = delete;
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  ~FolderLock();
  /// Locks `dir`, waiting for another holder when `wait`; false when not locked (held by another
  /// and !wait, or the folder cannot be opened).
  bool acquire(const std::string& dir, bool wait);

 private:
  std::intptr_t handle_{-1};
};

/// This process's id.
long processId();
/// True when no process `pid` exists any more.
bool processGone(long pid);
/// Ends this process at once, as a kill would (SIGKILL / TerminateProcess): fault injection.
[[noreturn]] void killThisProcess();

/// The file of the loaded module (shared library or executable) that holds roprec's code
/// (dladdr / GetModuleFileNameW); empty when unknown.
std::string loadedModulePath();

}  // namespace roprec::platform
