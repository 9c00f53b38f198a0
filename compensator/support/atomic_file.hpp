#pragma once
/// \file atomic_file.hpp
/// Outputs are written all-or-nothing (docs/contract.md §4). Every output of a command is staged
/// to a temporary file in its target folder (`.NAME.roprec-tmp.PID.N`, N unique in the process
/// whatever the thread; shortened with a hash when the name would exceed NAME_MAX), fsynced, and
/// renamed onto its target only when every output of the command was staged; on any error the
/// temporaries are removed. Temporaries left by a killed run are recognised by their name and
/// removed by the next run that writes to the folder.
/// Before anything is renamed, every output is compared with every other output and with every
/// input file read while the set was active (same file by device and inode after resolving
/// links, or the same resolved path for a file not yet there): UsageError naming both.
/// The renames of one set happen under an exclusive lock (flock) on each output folder, so two
/// runs never interleave their sets; a set of several files first writes a commit journal
/// (`.roprec-commit.PID.N` in its first folder) that the next run writing to that folder uses
/// to finish the renames of a run killed during them (then removes it).
/// A target that is a symbolic link, a FIFO, a device or a folder is refused, never replaced;
/// the null device (/dev/null) is accepted and its output discarded (produced, not staged).

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace roprec {

/// Appends bytes to a streamed output (see OutputSet::stageStream).
using ByteWriter = std::function<void(std::string_view)>;

/// A set of output files written all-or-nothing: stage() each, then commit() (rename all) or
/// rollback() (remove the temporaries; also done by the destructor when not committed).
class OutputSet {
 public:
  OutputSet() = default;
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  /// Writes `bytes` to a temporary file beside `path` and fsyncs it. Staging the same path again
  /// replaces the earlier bytes. Throws InputError(path, 0, "cannot write output file: <why>").
  void stage(const std::string& path, const std::string& bytes);
  /// Like stage(), with the bytes given piece by piece: `produce` is called once with a writer
  /// that appends to the temporary (constant memory for large outputs). If `produce` throws, the
  /// temporary is removed and the exception passes on (the target is untouched).
  void stageStream(const std::string& path, const std::function<void(const ByteWriter&)>& produce);
  /// Renames every staged temporary onto its target (then fsyncs the folders); returns the paths
  /// in staging order. Throws InputError when a rename fails (the remaining temporaries are
  /// removed).
  std::vector<std::string> commit();
  /// Removes every staged temporary; the targets keep their old contents.
  void rollback() noexcept;
  /// Takes over the staged temporaries (and noted inputs) of `other` (e.g. staged on another
  /// thread) after this set's own: commit() renames them too, in that order; `other` is left empty.
  void adopt(OutputSet&& other);
  /// Records an input file of the run: commit() refuses an output that is the same file.
  void noteInput(const std::string& path);
  /// Renames all staged temporaries that the commit journal of a killed run in `dir` names,
  /// under the folder lock (done by staging into a folder; public for the tests).
  void recoverFolder(const std::string& dir);

  [[nodiscard]] const std::vector<std::string>& paths() const { return paths_; }
  [[nodiscard]] bool empty() const { return paths_.empty(); }
  /// "finished the interrupted commit of an earlier run (pid N): A, B" for each journal of a
  /// killed run that staging into a folder found and completed.
  [[nodiscard]] const std::vector<std::string>& notes() const { return notes_; }

 private:
  void checkSameFiles() const;
  std::vector<std::string> paths_;
  std::vector<std::string> temps_;
  std::vector<std::string> inputs_;
  std::vector<std::string> cleaned_dirs_;
  std::vector<std::string> notes_;
};

/// While alive, writeFileAtomic() stages into `set` instead of writing at once, so code that
/// writes several files through writeFileAtomic (program + .dat, JSON + HTML + targets) becomes
/// all-or-nothing when its caller wraps it in a scope and commits the set afterwards. Scopes nest
/// (the innermost wins); one per thread.
class ScopedOutputSet {
 public:
  explicit ScopedOutputSet(OutputSet& set);
  ~ScopedOutputSet();
  ScopedOutputSet(const ScopedOutputSet&) = delete;
  ScopedOutputSet& operator=(const ScopedOutputSet&) = delete;

 private:
  OutputSet* previous_;
};

/// The set writeFileAtomic() stages into on the calling thread (nullptr: none).
OutputSet* activeOutputSet();

/// Writes one output: staged into the active ScopedOutputSet if there is one, else written
/// at once (temporary + fsync + rename). Throws InputError on failure.
void writeFileAtomic(const std::string& path, const std::string& bytes);
/// writeFileAtomic with the bytes produced piece by piece (OutputSet::stageStream).
void writeFileAtomicStream(const std::string& path,
                           const std::function<void(const ByteWriter&)>& produce);

/// Reads a whole file as bytes. Throws InputError(path, 0, "cannot open file: <why>").
std::string readFileBytes(const std::string& path);

/// Notes `path` as an input of the set active on this thread (if any): see OutputSet::noteInput.
void noteInputFile(const std::string& path);

/// The temporary file name used for `path` by process `pid`, staging number `seq` (same folder;
/// the file name part is at most NAME_MAX bytes).
std::string outputTemporaryPath(const std::string& path, long pid, unsigned long seq = 0);
/// True when `file_name` (no folder) is an output temporary; sets *pid to its writer's process.
bool isOutputTemporaryName(const std::string& file_name, long* pid = nullptr);
/// Removes the output temporaries in `dir` whose writing process no longer exists.
void removeStaleOutputTemporaries(const std::string& dir);

/// Test hook: called by OutputSet::commit() after every output was staged and before the first
/// rename (the tests kill the process there). nullptr disables it.
void setOutputCommitHookForTesting(void (*hook)());
/// Fault injection for the tests: with the environment variable ROPREC_FAULT_KILL_AFTER_RENAMES=N,
/// OutputSet::commit() kills its own process (SIGKILL) after the N-th rename of a set.
inline constexpr const char* kFaultKillAfterRenamesEnv = "ROPREC_FAULT_KILL_AFTER_RENAMES";

}  // namespace roprec
