#include "compensator/support/platform.hpp"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#ifdef _WIN32
#ifndef NOMINMAX
#define NOMINMAX
#endif
#ifndef WIN32_LEAN_AND_MEAN
#define WIN32_LEAN_AND_MEAN
#endif
#include <windows.h>
// after windows.h
#include <fcntl.h>
#include <io.h>
#include <shellapi.h>
#include <sys/stat.h>

#include <cwchar>
#include <cwctype>
#else
#include <dirent.h>
#include <dlfcn.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <csignal>
#endif

namespace roprec::platform {

namespace {

#ifdef _WIN32
std::wstring wide(std::string_view utf8) {
  if (utf8.empty()) return {};
  const int n =
      ::MultiByteToWideChar(CP_UTF8, 0, utf8.data(), static_cast<int>(utf8.size()), nullptr, 0);
  std::wstring w(static_cast<std::size_t>(n), L'\0');
  ::MultiByteToWideChar(CP_UTF8, 0, utf8.data(), static_cast<int>(utf8.size()), w.data(), n);
  return w;
}

std::string narrow(std::wstring_view w) {
  if (w.empty()) return {};
  const int n = ::WideCharToMultiByte(CP_UTF8, 0, w.data(), static_cast<int>(w.size()), nullptr, 0,
                                      nullptr, nullptr);
  std::string s(static_cast<std::size_t>(n), '\0');
  ::WideCharToMultiByte(CP_UTF8, 0, w.data(), static_cast<int>(w.size()), s.data(), n, nullptr,
                        nullptr);
  return s;
}

/// errno for the common Windows errors (the same message as on Linux), else -code.
int fromWindowsError(DWORD code) {
  switch (code) {
    case ERROR_FILE_NOT_FOUND:
    case ERROR_PATH_NOT_FOUND:
    case ERROR_INVALID_NAME:
      return ENOENT;
    case ERROR_ACCESS_DENIED:
    case ERROR_SHARING_VIOLATION:
    case ERROR_LOCK_VIOLATION:
      return EACCES;
    case ERROR_FILE_EXISTS:
    case ERROR_ALREADY_EXISTS:
      return EEXIST;
    case ERROR_DISK_FULL:
    case ERROR_HANDLE_DISK_FULL:
      return ENOSPC;
    case ERROR_WRITE_PROTECT:
      return EROFS;
    case ERROR_NOT_SAME_DEVICE:
      return EXDEV;
    default:
      return -static_cast<int>(code);
  }
}

bool isNullDeviceName(const std::string& path) {
  std::string n = path;
  for (char& c : n) c = static_cast<char>(c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c);
  // "/dev/null" too: a command line written for a POSIX shell means the null device by it
  return n == "NUL" || n == "\\\\.\\NUL" || n == "//./NUL" || n == "/DEV/NULL";
}

Status fromHandleInfo(HANDLE h) {
  Status s;
  BY_HANDLE_FILE_INFORMATION info{};
  if (!::GetFileInformationByHandle(h, &info)) {
    s.kind = Kind::kError;
    s.error = fromWindowsError(::GetLastError());
    return s;
  }
  s.kind = (info.dwFileAttributes & FILE_ATTRIBUTE_DIRECTORY) != 0 ? Kind::kFolder : Kind::kRegular;
  s.device = info.dwVolumeSerialNumber;
  s.inode = (static_cast<std::uint64_t>(info.nFileIndexHigh) << 32U) | info.nFileIndexLow;
  s.size = (static_cast<std::uint64_t>(info.nFileSizeHigh) << 32U) | info.nFileSizeLow;
  return s;
}
#else
Status fromStat(const struct stat& st) {
  Status s;
  s.device = static_cast<std::uint64_t>(st.st_dev);
  s.inode = static_cast<std::uint64_t>(st.st_ino);
  s.size = static_cast<std::uint64_t>(st.st_size);
  if (S_ISREG(st.st_mode)) {
    s.kind = Kind::kRegular;
  } else if (S_ISDIR(st.st_mode)) {
    s.kind = Kind::kFolder;
  } else if (S_ISLNK(st.st_mode)) {
    s.kind = Kind::kSymlink;
  } else if (S_ISFIFO(st.st_mode)) {
    s.kind = Kind::kFifo;
#ifdef __linux__
  } else if (S_ISCHR(st.st_mode) && major(st.st_rdev) == 1 && minor(st.st_rdev) == 3) {
    s.kind = Kind::kNullDevice;  // /dev/null, or any name for character device 1:3
#endif
  } else {
    s.kind = Kind::kOther;
  }
  return s;
}

Status failedStatus(int e) {
  Status s;
  s.error = e;
  s.kind = e == ENOENT || e == ENOTDIR ? Kind::kMissing : Kind::kError;
  return s;
}
#endif

}  // namespace

std::string errorText(int error) {
#ifdef _WIN32
  if (error < 0) {
    wchar_t* text = nullptr;
    const DWORD n = ::FormatMessageW(
        FORMAT_MESSAGE_ALLOCATE_BUFFER | FORMAT_MESSAGE_FROM_SYSTEM | FORMAT_MESSAGE_IGNORE_INSERTS,
        nullptr, static_cast<DWORD>(-error), MAKELANGID(LANG_ENGLISH, SUBLANG_DEFAULT),
        reinterpret_cast<LPWSTR>(&text), 0, nullptr);
    std::string s = n > 0 ? narrow(std::wstring_view(text, n)) : std::string();
    if (text != nullptr) ::LocalFree(text);
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == '.')) s.pop_back();
    return s.empty() ? "Windows error " + std::to_string(-error) : s;
  }
#endif
  return std::strerror(error);
}

#ifdef _WIN32

std::filesystem::path fromUtf8(std::string_view utf8) { return {wide(utf8)}; }
std::string toUtf8(const std::filesystem::path& path) { return narrow(path.native()); }

std::vector<std::string> utf8Arguments(int argc, char** argv) {
  int n = 0;
  wchar_t** w = ::CommandLineToArgvW(::GetCommandLineW(), &n);
  if (w == nullptr) return {argv, argv + argc};
  std::vector<std::string> out;
  out.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) out.push_back(narrow(w[i]));
  ::LocalFree(w);
  return out;
}

void setUpStdio() {
  (void)::_setmode(0, _O_BINARY);
  (void)::_setmode(1, _O_BINARY);
  (void)::_setmode(2, _O_BINARY);
}

int writeStdout(std::string_view bytes) {
  const char* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const unsigned chunk = left > (1U << 30U) ? (1U << 30U) : static_cast<unsigned>(left);
    const int n = ::_write(1, p, chunk);
    if (n < 0) return errno;
    if (n == 0) return EIO;
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return 0;
}

bool stderrIsTerminal() { return ::_isatty(2) != 0; }

Status linkStatus(const std::string& path) {
  Status s;
  if (isNullDeviceName(path)) {
    s.kind = Kind::kNullDevice;
    return s;
  }
  const std::wstring w = wide(path);
  const DWORD attrs = ::GetFileAttributesW(w.c_str());
  if (attrs == INVALID_FILE_ATTRIBUTES) {
    const DWORD e = ::GetLastError();
    s.error = fromWindowsError(e);
    s.kind = s.error == ENOENT ? Kind::kMissing : Kind::kError;
    return s;
  }
  if ((attrs & FILE_ATTRIBUTE_REPARSE_POINT) != 0) {
    s.kind = Kind::kSymlink;
    return s;
  }
  const Status f = fileStatus(path);
  return f.kind == Kind::kError ? s : f;
}

Status fileStatus(const std::string& path) {
  if (isNullDeviceName(path)) {
    Status s;
    s.kind = Kind::kNullDevice;
    return s;
  }
  const std::wstring w = wide(path);
  HANDLE h = ::CreateFileW(w.c_str(), 0, FILE_SHARE_READ | FILE_SHARE_WRITE | FILE_SHARE_DELETE,
                           nullptr, OPEN_EXISTING, FILE_FLAG_BACKUP_SEMANTICS, nullptr);
  if (h == INVALID_HANDLE_VALUE) {
    Status s;
    s.error = fromWindowsError(::GetLastError());
    s.kind = s.error == ENOENT ? Kind::kMissing : Kind::kError;
    return s;
  }
  const Status s = fromHandleInfo(h);
  ::CloseHandle(h);
  return s;
}

File::~File() {
  if (fd_ >= 0) ::_close(fd_);
}

int File::openRead(const std::string& path) {
  // CreateFileW, not _wopen: FILE_FLAG_BACKUP_SEMANTICS opens a folder too (status() then says
  // kFolder instead of _wopen's EACCES), and FILE_SHARE_DELETE lets another writer rename its
  // file over this one while it is read (as on POSIX); the handle is not inherited
  const HANDLE h = ::CreateFileW(wide(path).c_str(), GENERIC_READ,
                                 FILE_SHARE_READ | FILE_SHARE_WRITE | FILE_SHARE_DELETE, nullptr,
                                 OPEN_EXISTING, FILE_FLAG_BACKUP_SEMANTICS, nullptr);
  if (h == INVALID_HANDLE_VALUE) return fromWindowsError(::GetLastError());
  fd_ = ::_open_osfhandle(reinterpret_cast<intptr_t>(h), _O_RDONLY | _O_BINARY);
  if (fd_ < 0) {
    const int e = errno;
    ::CloseHandle(h);
    return e;
  }
  return 0;
}

int File::createNew(const std::string& path) {
  fd_ = ::_wopen(wide(path).c_str(), _O_WRONLY | _O_CREAT | _O_EXCL | _O_BINARY | _O_NOINHERIT,
                 _S_IREAD | _S_IWRITE);
  return fd_ < 0 ? errno : 0;
}

Status File::status() const {
  const auto h = reinterpret_cast<HANDLE>(::_get_osfhandle(fd_));
  if (h == INVALID_HANDLE_VALUE) {
    Status s;
    s.kind = Kind::kError;
    s.error = EBADF;
    return s;
  }
  const DWORD type = ::GetFileType(h);
  if (type == FILE_TYPE_PIPE) {
    Status s;
    s.kind = Kind::kFifo;
    return s;
  }
  if (type == FILE_TYPE_CHAR) {
    Status s;
    s.kind = Kind::kOther;
    return s;
  }
  return fromHandleInfo(h);
}

long long File::read(char* into, std::size_t n, int* error) {
  const unsigned chunk = n > (1U << 30U) ? (1U << 30U) : static_cast<unsigned>(n);
  const int r = ::_read(fd_, into, chunk);
  if (r < 0) *error = errno;
  return r;
}

int File::writeAll(std::string_view bytes) {
  const char* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const unsigned chunk = left > (1U << 30U) ? (1U << 30U) : static_cast<unsigned>(left);
    const int n = ::_write(fd_, p, chunk);
    if (n < 0) return errno;
    if (n == 0) return EIO;
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return 0;
}

void File::startWriteBack(std::uint64_t /*offset*/, std::uint64_t /*length*/) {}

int File::sync() {
  const auto h = reinterpret_cast<HANDLE>(::_get_osfhandle(fd_));
  return ::FlushFileBuffers(h) ? 0 : fromWindowsError(::GetLastError());
}

int File::close() {
  const int fd = fd_;
  fd_ = -1;
  return ::_close(fd) == 0 ? 0 : errno;
}

int replaceFile(const std::string& from, const std::string& to) {
  const std::wstring f = wide(from);
  const std::wstring t = wide(to);
  // Windows refuses the rename while another process or thread has `to` open without
  // FILE_SHARE_DELETE or is renaming onto it (ERROR_ACCESS_DENIED / ERROR_SHARING_VIOLATION),
  // where POSIX rename replaces it at once: retried for up to about 2 s, then the error
  DWORD e = 0;
  for (int attempt = 0; attempt < 200; ++attempt) {
    if (::MoveFileExW(f.c_str(), t.c_str(), MOVEFILE_REPLACE_EXISTING | MOVEFILE_WRITE_THROUGH))
      return 0;
    e = ::GetLastError();
    if (e != ERROR_ACCESS_DENIED && e != ERROR_SHARING_VIOLATION) break;
    const DWORD attrs = ::GetFileAttributesW(t.c_str());  // refused for good: no retry
    if (attrs != INVALID_FILE_ATTRIBUTES &&
        (attrs & (FILE_ATTRIBUTE_DIRECTORY | FILE_ATTRIBUTE_READONLY)) != 0)
      break;
    ::Sleep(attempt < 10 ? 1 : 10);
  }
  return fromWindowsError(e);
}

void removeFile(const std::string& path) { (void)::DeleteFileW(wide(path).c_str()); }

void syncFolder(const std::string& /*dir*/) {}

std::vector<std::string> folderEntries(const std::string& dir) {
  std::vector<std::string> names;
  WIN32_FIND_DATAW found{};
  HANDLE h = ::FindFirstFileW(wide(dir + "/*").c_str(), &found);
  if (h == INVALID_HANDLE_VALUE) return names;
  do {
    names.push_back(narrow(found.cFileName));
  } while (::FindNextFileW(h, &found));
  ::FindClose(h);
  return names;
}

FolderLock::FolderLock(FolderLock&& other) noexcept : handle_(other.handle_) { other.handle_ = -1; }

FolderLock::~FolderLock() {
  if (handle_ == -1) return;
  const auto h = reinterpret_cast<HANDLE>(handle_);
  ::ReleaseMutex(h);
  ::CloseHandle(h);
}

bool FolderLock::acquire(const std::string& dir, bool wait) {
  std::error_code ec;
  const std::filesystem::path real = std::filesystem::canonical(fromUtf8(dir), ec);
  if (ec) return false;
  std::wstring key = real.native();
  for (wchar_t& c : key) c = c == L'/' ? L'\\' : static_cast<wchar_t>(::towupper(c));
  std::uint64_t h = 1469598103934665603ULL;  // FNV-1a of the folder's resolved path
  for (const wchar_t c : key) {
    h ^= static_cast<std::uint64_t>(c);
    h *= 1099511628211ULL;
  }
  wchar_t name[64];
  std::swprintf(name, 64, L"Local\\roprec-folder-%016llx", static_cast<unsigned long long>(h));
  HANDLE m = ::CreateMutexW(nullptr, FALSE, name);
  if (m == nullptr) return false;
  const DWORD r = ::WaitForSingleObject(m, wait ? INFINITE : 0);
  if (r != WAIT_OBJECT_0 && r != WAIT_ABANDONED) {
    ::CloseHandle(m);
    return false;
  }
  handle_ = reinterpret_cast<std::intptr_t>(m);
  return true;
}

long processId() { return static_cast<long>(::GetCurrentProcessId()); }

bool processGone(long pid) {
  if (pid <= 0) return false;
  HANDLE h = ::OpenProcess(PROCESS_QUERY_LIMITED_INFORMATION, FALSE, static_cast<DWORD>(pid));
  if (h == nullptr) return ::GetLastError() == ERROR_INVALID_PARAMETER;
  DWORD code = 0;
  const bool exited = ::GetExitCodeProcess(h, &code) && code != STILL_ACTIVE;
  ::CloseHandle(h);
  return exited;
}

void killThisProcess() {
  ::TerminateProcess(::GetCurrentProcess(), 137);
  std::abort();
}

std::string loadedModulePath() {
  HMODULE module = nullptr;
  if (!::GetModuleHandleExW(
          GET_MODULE_HANDLE_EX_FLAG_FROM_ADDRESS | GET_MODULE_HANDLE_EX_FLAG_UNCHANGED_REFCOUNT,
          reinterpret_cast<LPCWSTR>(&loadedModulePath), &module)) {
    return {};
  }
  std::wstring path(MAX_PATH, L'\0');
  while (true) {
    const DWORD n = ::GetModuleFileNameW(module, path.data(), static_cast<DWORD>(path.size()));
    if (n == 0) return {};
    if (n < path.size()) {
      path.resize(n);
      return narrow(path);
    }
    path.resize(path.size() * 2);
  }
}

#else  // POSIX

std::filesystem::path fromUtf8(std::string_view utf8) { return {std::string(utf8)}; }
std::string toUtf8(const std::filesystem::path& path) { return path.string(); }

std::vector<std::string> utf8Arguments(int argc, char** argv) { return {argv, argv + argc}; }

void setUpStdio() { std::signal(SIGPIPE, SIG_IGN); }

int writeStdout(std::string_view bytes) {
  const char* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(1, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    if (n == 0) return EIO;
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return 0;
}

bool stderrIsTerminal() { return ::isatty(2) != 0; }

Status linkStatus(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return failedStatus(errno);
  return fromStat(st);
}

Status fileStatus(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return failedStatus(errno);
  return fromStat(st);
}

File::~File() {
  if (fd_ >= 0) ::close(fd_);
}

int File::openRead(const std::string& path) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  return fd_ < 0 ? errno : 0;
}

int File::createNew(const std::string& path) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
  return fd_ < 0 ? errno : 0;
}

Status File::status() const {
  struct stat st {};
  if (::fstat(fd_, &st) != 0) {
    Status s;
    s.kind = Kind::kError;
    s.error = errno;
    return s;
  }
  return fromStat(st);
}

long long File::read(char* into, std::size_t n, int* error) {
  while (true) {
    const ssize_t r = ::read(fd_, into, n);
    if (r >= 0) return r;
    if (errno == EINTR) continue;
    *error = errno;
    return -1;
  }
}

int File::writeAll(std::string_view bytes) {
  const char* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return 0;
}

void File::startWriteBack(std::uint64_t offset, std::uint64_t length) {
#ifdef __linux__
  (void)::sync_file_range(fd_, static_cast<off_t>(offset), static_cast<off_t>(length),
                          SYNC_FILE_RANGE_WRITE);
#else
  (void)offset;
  (void)length;
#endif
}

int File::sync() { return ::fsync(fd_) == 0 ? 0 : errno; }

int File::close() {
  const int fd = fd_;
  fd_ = -1;
  return ::close(fd) == 0 ? 0 : errno;
}

int replaceFile(const std::string& from, const std::string& to) {
  return ::rename(from.c_str(), to.c_str()) == 0 ? 0 : errno;
}

void removeFile(const std::string& path) { ::unlink(path.c_str()); }

void syncFolder(const std::string& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  (void)::fsync(fd);
  ::close(fd);
}

std::vector<std::string> folderEntries(const std::string& dir) {
  std::vector<std::string> names;
  DIR* d = ::opendir(dir.c_str());
  if (d == nullptr) return names;
  while (const dirent* e = ::readdir(d)) names.emplace_back(e->d_name);
  ::closedir(d);
  return names;
}

FolderLock::FolderLock(FolderLock&& other) noexcept : handle_(other.handle_) { other.handle_ = -1; }

FolderLock::~FolderLock() {
  if (handle_ >= 0) ::close(static_cast<int>(handle_));
}

bool FolderLock::acquire(const std::string& dir, bool wait) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return false;
  while (::flock(fd, wait ? LOCK_EX : LOCK_EX | LOCK_NB) != 0) {
    if (!wait || errno != EINTR) {
      ::close(fd);
      return false;
    }
  }
  handle_ = fd;
  return true;
}

long processId() { return static_cast<long>(::getpid()); }

bool processGone(long pid) {
  return pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

void killThisProcess() {
  ::raise(SIGKILL);
  std::abort();
}

std::string loadedModulePath() {
  Dl_info info{};
  if (::dladdr(reinterpret_cast<const void*>(&loadedModulePath), &info) == 0 ||
      info.dli_fname == nullptr) {
    return {};
  }
  return info.dli_fname;
}

#endif

}  // namespace roprec::platform
