#include "compensator/support/atomic_file.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "compensator/support/error.hpp"

namespace roprec {

namespace {

constexpr const char* kTmpTag = ".roprec-tmp.";
constexpr std::size_t kNameMax = 255;  // NAME_MAX on Linux file systems

thread_local OutputSet* g_active = nullptr;
void (*g_commit_hook)() = nullptr;

std::string errnoText(int e) { return std::strerror(e); }

std::string dirOf(const std::string& path) {
  const std::size_t s = path.find_last_of('/');
  if (s == std::string::npos) return ".";
  if (s == 0) return "/";
  return path.substr(0, s);
}

std::string nameOf(const std::string& path) {
  const std::size_t s = path.find_last_of('/');
  return s == std::string::npos ? path : path.substr(s + 1);
}

std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 1469598103934665603ULL;
  for (const unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return h;
}

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw InputError(path, 0, "cannot write output file: " + why);
}

/// The null device (/dev/null, or any name for character device 1:3): what is written to it is
/// discarded, so nothing is staged or replaced.
bool isNullDevice(const std::string& path) {
#ifdef __linux__
  struct stat st {};
  return ::lstat(path.c_str(), &st) == 0 && S_ISCHR(st.st_mode) && major(st.st_rdev) == 1 &&
         minor(st.st_rdev) == 3;
#else
  (void)path;
  return false;
#endif
}

/// Refuses targets that are not regular files (symbolic links, FIFOs, devices, folders).
void checkTarget(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) {
    const int e = errno;
    if (e != ENOENT && e != ENOTDIR) fail(path, errnoText(e));
    const std::string dir = dirOf(path);
    struct stat ds {};
    if (::stat(dir.c_str(), &ds) != 0) {
      fail(path, "the folder " + dir + " does not exist (roprec does not create folders)");
    }
    if (!S_ISDIR(ds.st_mode)) fail(path, dir + " is not a folder");
    if (e == ENOTDIR) fail(path, errnoText(e));
    return;
  }
  if (S_ISLNK(st.st_mode)) {
    fail(path, "it is a symbolic link; roprec does not replace links (give the real path)");
  }
  if (S_ISDIR(st.st_mode)) fail(path, "it is a folder");
  if (S_ISFIFO(st.st_mode)) fail(path, "it is a FIFO (named pipe), not a regular file");
  if (!S_ISREG(st.st_mode)) fail(path, "it is not a regular file (a device or socket)");
}

void fsyncDir(const std::string& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  (void)::fsync(fd);
  ::close(fd);
}

/// An open temporary: written, fsynced and closed, or removed on any failure.
class TempFile {
 public:
  TempFile(const std::string& path, const std::string& tmp) : path_(path), tmp_(tmp) {
    fd_ = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd_ < 0 && errno == EEXIST) {  // our own earlier staging of the same path, or a reused pid
      ::unlink(tmp.c_str());
      fd_ = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    }
    if (fd_ < 0) fail(path, errnoText(errno));
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  ~TempFile() {
    if (fd_ >= 0) {
      ::close(fd_);
      ::unlink(tmp_.c_str());
    }
  }
  void write(std::string_view bytes) {
    const char* p = bytes.data();
    std::size_t left = bytes.size();
    while (left > 0) {
      const ssize_t n = ::write(fd_, p, left);
      if (n < 0) {
        if (errno == EINTR) continue;
        failAndRemove(errno);
      }
      p += n;
      left -= static_cast<std::size_t>(n);
    }
    written_ += bytes.size();
    writeBehind();
  }
  void close() {
    if (::fsync(fd_) != 0) failAndRemove(errno);
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) {
      const int e = errno;
      ::unlink(tmp_.c_str());
      fail(path_, errnoText(e));
    }
  }

 private:
  [[noreturn]] void failAndRemove(int e) {
    ::close(fd_);
    fd_ = -1;
    ::unlink(tmp_.c_str());
    fail(path_, errnoText(e));
  }
  /// Starts the disk write of every kWriteBehind bytes written (Linux: sync_file_range, which
  /// does not wait), so that close()'s fsync waits for the last part only, not for an 18 MB
  /// file written in one go at the end. Durability is fsync's, as before.
  void writeBehind() {
#ifdef __linux__
    constexpr std::size_t kWriteBehind = std::size_t{1} << 20U;
    if (written_ - started_ < kWriteBehind) return;
    (void)::sync_file_range(fd_, static_cast<off_t>(started_),
                            static_cast<off_t>(written_ - started_), SYNC_FILE_RANGE_WRITE);
    started_ = written_;
#endif
  }
  std::string path_;
  std::string tmp_;
  int fd_{-1};
  std::size_t written_{0};  ///< bytes written
  std::size_t started_{0};  ///< bytes whose disk write writeBehind() started
};

void writeAll(const std::string& path, const std::string& tmp,
              const std::function<void(const ByteWriter&)>& produce) {
  TempFile f(path, tmp);
  produce([&](std::string_view bytes) { f.write(bytes); });
  f.close();
}

}  // namespace

std::string outputTemporaryPath(const std::string& path, long pid) {
  const std::string dir = dirOf(path);
  const std::string name = nameOf(path);
  const std::string tail = std::string(kTmpTag) + std::to_string(pid);
  std::string file = "." + name + tail;
  if (file.size() > kNameMax) {
    char hash[24];
    std::snprintf(hash, sizeof hash, "~%016llx", static_cast<unsigned long long>(fnv1a(name)));
    std::size_t keep = kNameMax - 1 - std::strlen(hash) - tail.size();
    // do not cut a UTF-8 sequence
    while (keep > 0 && keep < name.size() &&
           (static_cast<unsigned char>(name[keep]) & 0xC0U) == 0x80U) {
      --keep;
    }
    file = "." + name.substr(0, keep) + hash + tail;
  }
  const std::size_t s = path.find_last_of('/');
  return s == std::string::npos ? file : path.substr(0, s + 1) + file;
}

bool isOutputTemporaryName(const std::string& file_name, long* pid) {
  if (file_name.size() < 2 || file_name[0] != '.') return false;
  const std::size_t t = file_name.rfind(kTmpTag);
  if (t == std::string::npos || t < 2) return false;
  const std::string digits = file_name.substr(t + std::strlen(kTmpTag));
  if (digits.empty() || digits.size() > 18) return false;
  if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return false;
  if (pid) *pid = std::stol(digits);
  return true;
}

void removeStaleOutputTemporaries(const std::string& dir) {
  DIR* d = ::opendir(dir.c_str());
  if (d == nullptr) return;
  const long self = static_cast<long>(::getpid());
  while (const dirent* e = ::readdir(d)) {
    long pid = 0;
    const std::string name = e->d_name;
    if (!isOutputTemporaryName(name, &pid) || pid == self || pid <= 0) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // still running
    std::string full = dir == "/" ? "/" : dir + "/";
    full += name;
    struct stat st {};
    if (::lstat(full.c_str(), &st) == 0 && S_ISREG(st.st_mode)) ::unlink(full.c_str());
  }
  ::closedir(d);
}

OutputSet::~OutputSet() { rollback(); }

void OutputSet::stage(const std::string& path, const std::string& bytes) {
  stageStream(path, [&](const ByteWriter& write) { write(bytes); });
}

void OutputSet::stageStream(const std::string& path,
                            const std::function<void(const ByteWriter&)>& produce) {
  if (path.empty()) fail(path, "empty output path");
  if (nameOf(path).empty() || nameOf(path) == "." || nameOf(path) == "..")
    fail(path, "the path names a folder, not a file");
  if (isNullDevice(path)) {  // discarded: the bytes are still produced (and their errors thrown)
    produce([](std::string_view) {});
    return;
  }
  checkTarget(path);
  const std::string dir = dirOf(path);
  if (std::find(cleaned_dirs_.begin(), cleaned_dirs_.end(), dir) == cleaned_dirs_.end()) {
    removeStaleOutputTemporaries(dir);
    cleaned_dirs_.push_back(dir);
  }
  const std::string tmp = outputTemporaryPath(path, static_cast<long>(::getpid()));
  const auto it = std::find(paths_.begin(), paths_.end(), path);
  if (it != paths_.end()) {  // staged again: the new bytes replace the old ones
    const auto i = static_cast<std::size_t>(it - paths_.begin());
    ::unlink(temps_[i].c_str());
    paths_.erase(it);
    temps_.erase(temps_.begin() + static_cast<std::ptrdiff_t>(i));
  }
  writeAll(path, tmp, produce);
  paths_.push_back(path);
  temps_.push_back(tmp);
}

std::vector<std::string> OutputSet::commit() {
  if (g_commit_hook && !paths_.empty()) g_commit_hook();
  // Re-check the targets right before replacing them (a link or FIFO made meanwhile).
  try {
    for (const std::string& p : paths_) checkTarget(p);
  } catch (...) {
    rollback();
    throw;
  }
  std::vector<std::string> dirs;
  for (std::size_t i = 0; i < paths_.size(); ++i) {
    if (::rename(temps_[i].c_str(), paths_[i].c_str()) != 0) {
      const int e = errno;
      const std::string path = paths_[i];
      for (std::size_t j = i; j < temps_.size(); ++j) ::unlink(temps_[j].c_str());
      paths_.clear();
      temps_.clear();
      fail(path, errnoText(e));
    }
    const std::string dir = dirOf(paths_[i]);
    if (std::find(dirs.begin(), dirs.end(), dir) == dirs.end()) dirs.push_back(dir);
  }
  for (const std::string& d : dirs) fsyncDir(d);
  std::vector<std::string> written;
  written.swap(paths_);
  temps_.clear();
  return written;
}

void OutputSet::rollback() noexcept {
  for (const std::string& t : temps_) ::unlink(t.c_str());
  temps_.clear();
  paths_.clear();
}

void OutputSet::adopt(OutputSet&& other) {
  paths_.insert(paths_.end(), other.paths_.begin(), other.paths_.end());
  temps_.insert(temps_.end(), other.temps_.begin(), other.temps_.end());
  for (const std::string& d : other.cleaned_dirs_) {
    if (std::find(cleaned_dirs_.begin(), cleaned_dirs_.end(), d) == cleaned_dirs_.end())
      cleaned_dirs_.push_back(d);
  }
  other.paths_.clear();
  other.temps_.clear();
}

OutputSet* activeOutputSet() { return g_active; }

ScopedOutputSet::ScopedOutputSet(OutputSet& set) : previous_(g_active) { g_active = &set; }
ScopedOutputSet::~ScopedOutputSet() { g_active = previous_; }

void writeFileAtomic(const std::string& path, const std::string& bytes) {
  if (g_active != nullptr) {
    g_active->stage(path, bytes);
    return;
  }
  OutputSet one;
  one.stage(path, bytes);
  one.commit();
}

void writeFileAtomicStream(const std::string& path,
                           const std::function<void(const ByteWriter&)>& produce) {
  if (g_active != nullptr) {
    g_active->stageStream(path, produce);
    return;
  }
  OutputSet one;
  one.stageStream(path, produce);
  one.commit();
}

std::string readFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int e = errno;
    throw InputError(path, 0, "cannot open file" + (e ? ": " + errnoText(e) : std::string()));
  }
  // one read into a string of the file's size (a 36 MB program: no growing buffer, one copy);
  // whatever the size did not foresee (a file still growing, a pipe) is read after it
  std::string bytes;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0, std::ios::beg);
  if (size > 0 && in) {
    bytes.resize(static_cast<std::size_t>(size));
    in.read(bytes.data(), size);
    bytes.resize(static_cast<std::size_t>(in.gcount()));
  }
  in.clear();
  char buf[65536];
  while (in.read(buf, sizeof buf) || in.gcount() > 0)
    bytes.append(buf, static_cast<std::size_t>(in.gcount()));
  if (in.bad()) throw InputError(path, 0, "cannot read file");
  return bytes;
}

void setOutputCommitHookForTesting(void (*hook)()) { g_commit_hook = hook; }

}  // namespace roprec
