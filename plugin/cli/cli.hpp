#pragma once
/// \file cli.hpp
/// Command-line plumbing: option parsing and the command registry. Every `plugin/cmd_*.cpp`
/// registers one command with a static `CommandRegistration`, so commands are added without
/// touching a shared table.

#include <Eigen/Core>
#include <chrono>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "compensator/support/error.hpp"
#include "compensator/support/rotation.hpp"

namespace roprec::api {}
namespace roprec::cli {

// The CLI is parsing and printing over the host-facing job API.
using namespace roprec::api;  // NOLINT(google-build-using-namespace)

/// Options are consumed as commands ask for them; `finish()` rejects anything left over.
class Args {
 public:
  explicit Args(std::vector<std::string> tokens);

  /// `--name VALUE` or `--name=VALUE`; the last occurrence wins.
  std::optional<std::string> option(const std::string& name);
  /// `--name` present.
  bool flag(const std::string& name);
  /// Remaining non-option tokens, in order (call after every option/flag was read).
  std::vector<std::string> positionals();
  /// Throws UsageError naming the first unknown option.
  void finish();

 private:
  std::vector<std::string> tokens_;
  std::vector<bool> used_;
};

/// Parses n whitespace-separated finite numbers; UsageError names `what` on failure.
Eigen::VectorXd parseNumberList(const std::string& text, int n, const std::string& what);
/// `--joints "j1 .. j6"` (deg) -> rad.
Eigen::Matrix<double, 6, 1> parseJointsDeg(const std::string& text);
/// `--pose "x y z qw qx qy qz"` (mm, unit quaternion) -> SI pose. The quaternion must be
/// unit within 1e-6 (it is then normalised).
Pose parsePoseQuat(const std::string& text);
/// `--xyzabc "x y z a b c"` (mm, deg, KUKA Z-Y'-X'') -> SI pose; `what` names the option in errors.
Pose parsePoseXyzAbc(const std::string& text, const std::string& what = "--xyzabc (x y z a b c)");

/// Keeps `value` until the process exits and never destroys it: a command's job result (100,000
/// holes: ~10^6 heap blocks and ~0.1 s of frees) goes back to the operating system with the whole
/// process instead of block by block. It stays reachable from a static, so leak
/// checkers do not report it. For the CLI's commands only (one job per process).
template <class T>
void keepUntilExit(T&& value) {
  // never deleted, on purpose (see above)
  static auto* const kept = new std::vector<std::shared_ptr<void>>();  // NOLINT
  kept->push_back(std::make_shared<std::decay_t<T>>(std::forward<T>(value)));
}

struct CommandContext {
  std::ostream& out;
  std::ostream& err;
  bool quiet{false};
  bool stderr_is_tty{false};
};

struct Command {
  std::string name;
  std::string summary;  ///< one line for `roprec --help`
  std::string usage;    ///< full text for `roprec NAME --help`
  int order{100};       ///< position in the help listing
  std::function<int(Args&, CommandContext&)> run;
};

/// Writes a progress line to stderr when it is a terminal and not --quiet.
class Progress {
 public:
  /// `total` 0: given with each step. The line appears once the run has taken `after_s`
  /// (default 1 s; the environment variable ROPREC_PROGRESS_AFTER_S overrides it) and is
  /// refreshed at most 5 times a second: "what done/total (rate/s, ETA n s)".
  Progress(CommandContext& ctx, const std::string& what, size_t total);
  void step(size_t done, size_t total = 0);
  void finish();

 private:
  CommandContext& ctx_;
  std::string what_;
  size_t total_;
  bool active_;
  double after_s_{1.0};
  std::chrono::steady_clock::time_point start_;
  double last_print_s_{-1.0};
  size_t width_{0};  ///< length of the last line written (0: none)
};

std::vector<Command>& commandRegistry();

struct CommandRegistration {
  explicit CommandRegistration(Command c);
};

/// `--threads N` of predict and compensate: worker threads for the per-hole work, 0 = every core,
/// default 1 (JobOptions::threads; outputs are byte-identical for any N). Throws UsageError
/// unless N is a whole number in [0, 1024].
inline int parseThreadsOption(Args& args) {
  const std::optional<std::string> t = args.option("threads");
  if (!t) return 1;
  const double n = parseNumberList(*t, 1, "--threads")[0];
  if (!(n >= 0 && n <= 1024 && n == static_cast<double>(static_cast<int>(n))))
    throw UsageError("--threads must be a whole number: 0 (every core) or 1..1024, not " + *t);
  return static_cast<int>(n);
}

/// Writes all of `text` to standard output (file descriptor 1) now, past ctx.out (which main
/// prints once the command succeeded); 0, or the errno of a failed write (a full disk, a closed
/// pipe: SIGPIPE is ignored so that it is reported, not fatal).
int writeStdout(std::string_view text);

/// Writes `text` to `path` atomically, or to ctx.out when path is "-" or empty.
void emit(CommandContext& ctx, const std::string& path, const std::string& text);

}  // namespace roprec::cli
