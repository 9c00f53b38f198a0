#include "compensator/support/atomic_file.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>

#include "compensator/support/error.hpp"
#include "compensator/support/platform.hpp"

namespace roprec {

namespace {

constexpr const char* kTmpTag = ".roprec-tmp.";
constexpr const char* kJournalTag = ".roprec-commit.";
constexpr const char* kJournalEnd = "roprec-commit-end";
constexpr std::size_t kNameMax = 255;  // NAME_MAX on Linux file systems

thread_local OutputSet* g_active = nullptr;
void (*g_commit_hook)() = nullptr;
std::atomic<unsigned long> g_seq{0};  ///< staging number: temporary names unique per thread

std::string errnoText(int e) { return platform::errorText(e); }

std::string dirOf(const std::string& path) {
  const std::size_t s = path.find_last_of(platform::kPathSeparators);
  if (s == std::string::npos) return ".";
  if (s == 0) return "/";
  return path.substr(0, s);
}

std::string nameOf(const std::string& path) {
  const std::size_t s = path.find_last_of(platform::kPathSeparators);
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
  return platform::linkStatus(path).kind == platform::Kind::kNullDevice;
}

/// Refuses targets that are not regular files (symbolic links, FIFOs, devices, folders).
void checkTarget(const std::string& path) {
  using platform::Kind;
  const platform::Status st = platform::linkStatus(path);
  if (st.kind == Kind::kError) fail(path, errnoText(st.error));
  if (st.kind == Kind::kMissing) {
    const std::string dir = dirOf(path);
    const platform::Status ds = platform::fileStatus(dir);
    if (ds.kind == Kind::kMissing || ds.kind == Kind::kError) {
      fail(path, "the folder " + dir +
                     " does not exist (roprec does not create folders: mkdir -p " + dir + ")");
    }
    if (ds.kind != Kind::kFolder) fail(path, dir + " is not a folder");
    if (st.error != ENOENT) fail(path, errnoText(st.error));
    return;
  }
  if (st.kind == Kind::kSymlink) {
    fail(path, "it is a symbolic link; roprec does not replace links (give the real path)");
  }
  if (st.kind == Kind::kFolder) fail(path, "it is a folder");
  if (st.kind == Kind::kFifo) fail(path, "it is a FIFO (named pipe), not a regular file");
  if (st.kind != Kind::kRegular) fail(path, "it is not a regular file (a device or socket)");
}

/// What a path names, for the same-file checks: device and inode of the file it resolves to
/// (links followed) when it exists, else its resolved absolute path.
struct FileIdentity {
  bool exists{false};
  std::uint64_t dev{};
  std::uint64_t ino{};
  std::string resolved;
};

FileIdentity identify(const std::string& path) {
  FileIdentity id;
  const platform::Status st = platform::fileStatus(path);
  if (st.kind != platform::Kind::kMissing && st.kind != platform::Kind::kError) {
    id.exists = true;
    id.dev = st.device;
    id.ino = st.inode;
  }
  std::error_code e;
  id.resolved = platform::toUtf8(
      std::filesystem::weakly_canonical(std::filesystem::absolute(platform::fromUtf8(path), e), e));
  if (e) id.resolved = path;
  return id;
}

bool sameIdentity(const FileIdentity& a, const FileIdentity& b) {
  if (a.exists && b.exists) return a.dev == b.dev && a.ino == b.ino;
  return a.resolved == b.resolved;
}

/// Exclusive locks on folders (platform::FolderLock: flock() on POSIX, where the lock belongs to
/// the open file description, so two threads of one process exclude each other as two processes
/// do), released by the destructor.
class FolderLocks {
 public:
  FolderLocks() = default;
  FolderLocks(const FolderLocks&) = delete;
  FolderLocks& operator=(const FolderLocks&) = delete;
  ~FolderLocks() = default;
  /// Locks `dir` (blocking). A folder that cannot be opened for locking is not locked (the
  /// staging or rename in it reports its own error).
  void lock(const std::string& dir) { take(dir, true); }
  /// Locks `dir` unless another holds it; false then.
  bool tryLock(const std::string& dir) { return take(dir, false); }

 private:
  bool take(const std::string& dir, bool wait) {
    platform::FolderLock l;
    if (!l.acquire(dir, wait)) return false;
    locks_.push_back(std::move(l));
    return true;
  }
  std::vector<platform::FolderLock> locks_;
};

/// `dirs` once each by identity (device and inode: "out" and "./out" are one folder, and a
/// second flock on it from this thread would wait for ever), in one order for every run (device,
/// inode), so that runs locking several folders never wait for each other in a cycle. A folder
/// that cannot be stat'ed is left out (its staging or rename reports the error).
std::vector<std::string> uniqueFolders(const std::vector<std::string>& dirs) {
  std::vector<std::tuple<std::uint64_t, std::uint64_t, std::string>> ids;
  for (const std::string& d : dirs) {
    const platform::Status st = platform::fileStatus(d);
    if (st.kind == platform::Kind::kMissing || st.kind == platform::Kind::kError) continue;
    const bool seen = std::any_of(ids.begin(), ids.end(), [&](const auto& x) {
      return std::get<0>(x) == st.device && std::get<1>(x) == st.inode;
    });
    if (!seen) ids.emplace_back(st.device, st.inode, d);
  }
  std::sort(ids.begin(), ids.end());
  std::vector<std::string> out;
  out.reserve(ids.size());
  for (auto& x : ids) out.push_back(std::move(std::get<2>(x)));
  return out;
}

/// "PID" or "PID.N" (digits): the writing process.
bool parseOwner(const std::string& digits, long* pid) {
  if (digits.empty() || digits.size() > 40) return false;
  const std::size_t dot = digits.find('.');
  const std::string p = digits.substr(0, dot);
  const std::string n = dot == std::string::npos ? std::string() : digits.substr(dot + 1);
  const auto all_digits = [](const std::string& x) {
    return std::all_of(x.begin(), x.end(), [](char c) { return c >= '0' && c <= '9'; });
  };
  if (p.empty() || p.size() > 18 || !all_digits(p)) return false;
  if (dot != std::string::npos && (n.empty() || n.size() > 20 || !all_digits(n))) return false;
  if (pid) *pid = std::stol(p);
  return true;
}

bool isJournalName(const std::string& name, long* pid) {
  const std::size_t t = std::strlen(kJournalTag);
  return name.size() > t && name.compare(0, t, kJournalTag) == 0 && parseOwner(name.substr(t), pid);
}

/// The commit journal: "tmp\0target\0" per output, then the end marker (absent: the run was killed
/// while writing the journal, before any rename).
struct Journal {
  std::vector<std::pair<std::string, std::string>> renames;
  bool complete{false};
};

Journal readJournal(const std::string& path) {
  Journal j;
  std::ifstream in(platform::fromUtf8(path), std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::string> parts;
  std::size_t b = 0;
  for (std::size_t e = text.find('\0'); e != std::string::npos; e = text.find('\0', b)) {
    parts.push_back(text.substr(b, e - b));
    b = e + 1;
  }
  if (!parts.empty() && parts.back() == kJournalEnd) {
    j.complete = true;
    parts.pop_back();
  }
  for (std::size_t i = 0; i + 1 < parts.size(); i += 2)
    j.renames.emplace_back(parts[i], parts[i + 1]);
  return j;
}

/// Writes the journal of a set's renames (fsynced, and its folder) before the first rename.
std::string writeJournal(const std::string& dir, const std::vector<std::string>& temps,
                         const std::vector<std::string>& paths) {
  std::string text;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    std::error_code e;
    const std::string t =
        platform::toUtf8(std::filesystem::absolute(platform::fromUtf8(temps[i]), e));
    const std::string p =
        platform::toUtf8(std::filesystem::absolute(platform::fromUtf8(paths[i]), e));
    text += t;
    text += '\0';
    text += p;
    text += '\0';
  }
  text += kJournalEnd;
  text += '\0';
  const std::string name = std::string(kJournalTag) + std::to_string(platform::processId()) + "." +
                           std::to_string(g_seq.fetch_add(1));
  const std::string path = dir == "/" ? "/" + name : dir + "/" + name;
  platform::File f;
  if (f.createNew(path) != 0) return "";  // no journal: the commit still happens, without recovery
  bool ok = f.writeAll(text) == 0;
  ok = ok && f.sync() == 0;
  (void)f.close();
  if (!ok) {
    platform::removeFile(path);
    return "";
  }
  platform::syncFolder(dir);
  return path;
}

/// An open temporary: written, fsynced and closed, or removed on any failure.
class TempFile {
 public:
  TempFile(const std::string& path, const std::string& tmp) : path_(path), tmp_(tmp) {
    int e = file_.createNew(tmp);
    if (e == EEXIST) {  // our own earlier staging of the same path, or a reused pid
      platform::removeFile(tmp);
      e = file_.createNew(tmp);
    }
    if (e != 0) fail(path, errnoText(e));
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  ~TempFile() {
    if (file_.isOpen()) {
      (void)file_.close();
      platform::removeFile(tmp_);
    }
  }
  void write(std::string_view bytes) {
    if (const int e = file_.writeAll(bytes); e != 0) failAndRemove(e);
    written_ += bytes.size();
    writeBehind();
  }
  void close() {
    if (const int e = file_.sync(); e != 0) failAndRemove(e);
    if (const int e = file_.close(); e != 0) {
      platform::removeFile(tmp_);
      fail(path_, errnoText(e));
    }
  }

 private:
  [[noreturn]] void failAndRemove(int e) {
    (void)file_.close();
    platform::removeFile(tmp_);
    fail(path_, errnoText(e));
  }
  /// Starts the disk write of every kWriteBehind bytes written (Linux: sync_file_range, which
  /// does not wait), so that close()'s fsync waits for the last part only, not for an 18 MB
  /// file written in one go at the end. Durability is fsync's, as before.
  void writeBehind() {
    constexpr std::size_t kWriteBehind = std::size_t{1} << 20U;
    if (written_ - started_ < kWriteBehind) return;
    file_.startWriteBack(started_, written_ - started_);
    started_ = written_;
  }
  std::string path_;
  std::string tmp_;
  platform::File file_;
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

std::string outputTemporaryPath(const std::string& path, long pid, unsigned long seq) {
  const std::string dir = dirOf(path);
  const std::string name = nameOf(path);
  const std::string tail = std::string(kTmpTag) + std::to_string(pid) + "." + std::to_string(seq);
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
  const std::size_t s = path.find_last_of(platform::kPathSeparators);
  return s == std::string::npos ? file : path.substr(0, s + 1) + file;
}

bool isOutputTemporaryName(const std::string& file_name, long* pid) {
  if (file_name.size() < 2 || file_name[0] != '.') return false;
  const std::size_t t = file_name.rfind(kTmpTag);
  if (t == std::string::npos || t < 2) return false;
  return parseOwner(file_name.substr(t + std::strlen(kTmpTag)), pid);
}

void removeStaleOutputTemporaries(const std::string& dir) {
  const long self = platform::processId();
  for (const std::string& name : platform::folderEntries(dir)) {
    long pid = 0;
    if (!isOutputTemporaryName(name, &pid) || pid == self || pid <= 0) continue;
    if (!platform::processGone(pid)) continue;  // still running
    std::string full = dir == "/" ? "/" : dir + "/";
    full += name;
    if (platform::linkStatus(full).kind == platform::Kind::kRegular) platform::removeFile(full);
  }
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
  const FileIdentity id = identify(path);
  for (const std::string& p : paths_) {
    if (sameIdentity(identify(p), id))
      throw UsageError("output " + path + " and output " + p +
                       " are the same file; give each output its own file (nothing written)");
  }
  const std::string dir = dirOf(path);
  if (std::find(cleaned_dirs_.begin(), cleaned_dirs_.end(), dir) == cleaned_dirs_.end()) {
    recoverFolder(dir);
    cleaned_dirs_.push_back(dir);
  }
  const std::string tmp = outputTemporaryPath(path, platform::processId(), g_seq++);
  writeAll(path, tmp, produce);
  paths_.push_back(path);
  temps_.push_back(tmp);
}

void OutputSet::noteInput(const std::string& path) {
  if (std::find(inputs_.begin(), inputs_.end(), path) == inputs_.end()) inputs_.push_back(path);
}

void OutputSet::checkSameFiles() const {
  std::vector<FileIdentity> outs;
  outs.reserve(paths_.size());
  for (const std::string& p : paths_) outs.push_back(identify(p));
  for (std::size_t i = 0; i < outs.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (sameIdentity(outs[i], outs[j]))
        throw UsageError("output " + paths_[i] + " and output " + paths_[j] +
                         " are the same file; give each output its own file (nothing written)");
    }
  }
  for (const std::string& in : inputs_) {
    const FileIdentity iid = identify(in);
    for (std::size_t i = 0; i < outs.size(); ++i) {
      if (sameIdentity(outs[i], iid))
        throw UsageError("output " + paths_[i] + " is the input file " + in +
                         "; write the output to another file (nothing written)");
    }
  }
}

void OutputSet::recoverFolder(const std::string& dir) {
  FolderLocks locks;
  locks.lock(dir);
  std::vector<std::pair<std::string, long>> journals;
  for (const std::string& name : platform::folderEntries(dir)) {
    long pid = 0;
    if (isJournalName(name, &pid) && platform::processGone(pid)) journals.emplace_back(name, pid);
  }
  std::sort(journals.begin(), journals.end());
  for (const auto& [name, pid] : journals) {
    const std::string path = dir == "/" ? "/" + name : dir + "/" + name;
    const Journal j = readJournal(path);
    if (j.complete) {
      // the other folders of that set are locked too (skipped if a live run holds one now)
      FolderLocks others;
      std::vector<std::string> folders{dir};
      for (const auto& r : j.renames) folders.push_back(dirOf(r.second));
      folders = uniqueFolders(folders);
      bool all = true;
      for (const std::string& od : folders) {
        std::error_code e;
        if (!std::filesystem::equivalent(platform::fromUtf8(od), platform::fromUtf8(dir), e))
          all = all && others.tryLock(od);
      }
      if (!all) continue;
      std::string done;
      for (const auto& [tmp, target] : j.renames) {
        if (platform::linkStatus(tmp).kind != platform::Kind::kRegular) continue;  // renamed before
        if (platform::replaceFile(tmp, target) == 0) done += (done.empty() ? "" : ", ") + target;
      }
      for (const auto& r : j.renames) platform::syncFolder(dirOf(r.second));
      if (!done.empty())
        notes_.push_back("finished the output commit of an earlier run (pid " +
                         std::to_string(pid) + ") that was killed during it: " + done);
    }
    platform::removeFile(path);
    platform::syncFolder(dir);
  }
  removeStaleOutputTemporaries(dir);
}

std::vector<std::string> OutputSet::commit() {
  if (g_commit_hook && !paths_.empty()) g_commit_hook();
  // Re-check the targets right before replacing them (a link or FIFO made meanwhile), and that no
  // output is another output or an input of the run.
  try {
    checkSameFiles();
    for (const std::string& p : paths_) checkTarget(p);
  } catch (...) {
    rollback();
    throw;
  }
  std::vector<std::string> dirs;
  for (const std::string& p : paths_) {
    const std::string dir = dirOf(p);
    if (std::find(dirs.begin(), dirs.end(), dir) == dirs.end()) dirs.push_back(dir);
  }
  const std::vector<std::string> lock_order = uniqueFolders(dirs);
  FolderLocks locks;
  for (const std::string& d : lock_order) locks.lock(d);
  const std::string journal = paths_.size() > 1 && !lock_order.empty()
                                  ? writeJournal(lock_order.front(), temps_, paths_)
                                  : std::string();
  long kill_after = -1;
  if (const char* k = std::getenv(kFaultKillAfterRenamesEnv)) kill_after = std::atol(k);
  for (std::size_t i = 0; i < paths_.size(); ++i) {
    if (kill_after >= 0 && static_cast<long>(i) == kill_after) platform::killThisProcess();
    if (const int e = platform::replaceFile(temps_[i], paths_[i]); e != 0) {
      const std::string path = paths_[i];
      for (std::size_t j = i; j < temps_.size(); ++j) platform::removeFile(temps_[j]);
      paths_.clear();
      temps_.clear();
      if (!journal.empty()) platform::removeFile(journal);
      fail(path, errnoText(e));
    }
  }
  for (const std::string& d : dirs) platform::syncFolder(d);
  if (!journal.empty()) {
    platform::removeFile(journal);
    platform::syncFolder(lock_order.front());
  }
  std::vector<std::string> written;
  written.swap(paths_);
  temps_.clear();
  return written;
}

void OutputSet::rollback() noexcept {
  for (const std::string& t : temps_) platform::removeFile(t);
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
  for (const std::string& in : other.inputs_) noteInput(in);
  notes_.insert(notes_.end(), other.notes_.begin(), other.notes_.end());
  other.paths_.clear();
  other.temps_.clear();
  other.inputs_.clear();
  other.notes_.clear();
}

void noteInputFile(const std::string& path) {
  if (g_active != nullptr) g_active->noteInput(path);
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
  std::ifstream in(platform::fromUtf8(path), std::ios::binary);
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
