#include "plugin/cli/cli.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <ostream>
#include <sstream>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/c_format.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/platform.hpp"
#include "compensator/support/xml_node.hpp"
#include "plugin/api/job_options.hpp"

namespace roprec::cli {

Args::Args(std::vector<std::string> tokens)
    : tokens_(std::move(tokens)), used_(tokens_.size(), false) {}

std::optional<std::string> Args::option(const std::string& name) {
  std::optional<std::string> value;
  const std::string key = "--" + name;
  const std::string short_key = name.size() == 1 ? "-" + name : key;  // -o as well as --o
  const std::string long_key = name == "o" ? "--output" : key;        // -o is also --output
  for (size_t i = 0; i < tokens_.size(); ++i) {
    if (used_[i]) continue;
    if (tokens_[i] == key || tokens_[i] == short_key || tokens_[i] == long_key) {
      if (i + 1 >= tokens_.size()) throw UsageError("option " + key + " needs a value");
      used_[i] = used_[i + 1] = true;
      value = tokens_[i + 1];
      ++i;
    } else if (tokens_[i].rfind(key + "=", 0) == 0) {
      used_[i] = true;
      value = tokens_[i].substr(key.size() + 1);
    } else if (tokens_[i].rfind(long_key + "=", 0) == 0) {
      used_[i] = true;
      value = tokens_[i].substr(long_key.size() + 1);
    }
  }
  return value;
}

bool Args::flag(const std::string& name) {
  bool found = false;
  for (size_t i = 0; i < tokens_.size(); ++i) {
    if (!used_[i] && tokens_[i] == "--" + name) {
      used_[i] = true;
      found = true;
    }
  }
  return found;
}

std::vector<std::string> Args::positionals() {
  std::vector<std::string> out;
  for (size_t i = 0; i < tokens_.size(); ++i) {
    if (used_[i]) continue;
    if (tokens_[i].size() > 1 && tokens_[i][0] == '-' && tokens_[i] != "-") continue;
    used_[i] = true;
    out.push_back(tokens_[i]);
  }
  return out;
}

void Args::finish() {
  for (size_t i = 0; i < tokens_.size(); ++i) {
    if (!used_[i]) throw UsageError("unknown or unexpected argument '" + tokens_[i] + "'");
  }
}

Eigen::VectorXd parseNumberList(const std::string& text, int n, const std::string& what) {
  return api::numbersFromText(text, n, what);
}

Eigen::Matrix<double, 6, 1> parseJointsDeg(const std::string& text) {
  const Eigen::VectorXd deg = parseNumberList(text, 6, "--joints");
  // ten turns either way, as the URDF joint limits (a 1e300 would be printed with 300 digits)
  constexpr double kMaxJointDeg = 3600.0;
  for (int i = 0; i < 6; ++i) {
    if (std::abs(deg[i]) > kMaxJointDeg)
      throw UsageError("--joints: joint " + std::to_string(i + 1) + " = " + numberText(deg[i]) +
                       "° is beyond ten turns (±3600°); give joint angles in degrees");
  }
  return deg * kDeg;
}

Pose parsePoseQuat(const std::string& text) {
  const Eigen::VectorXd v = parseNumberList(text, 7, "--pose (x y z qw qx qy qz)");
  Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
  if (std::abs(q.norm() - 1.0) > 1e-6) {
    throw InputError(
        "", 0,
        "--pose: the quaternion is not a unit quaternion (norm " + numberText(q.norm(), 9) + ")");
  }
  Pose T = Pose::Identity();
  T.translation() = v.head<3>() * 1e-3;
  T.linear() = q.normalized().toRotationMatrix();
  return T;
}

Pose parsePoseXyzAbc(const std::string& text, const std::string& what) {
  return api::poseFromXyzAbcText(text, what);
}

std::vector<Command>& commandRegistry() {
  static std::vector<Command> registry;
  return registry;
}

CommandRegistration::CommandRegistration(Command c) { commandRegistry().push_back(std::move(c)); }

int writeStdout(std::string_view text) { return platform::writeStdout(text); }

void emit(CommandContext& ctx, const std::string& path, const std::string& text) {
  if (path.empty() || path == "-") {
    ctx.out << text;
    ctx.out.flush();
  } else {
    writeFileAtomic(path, text);
  }
}

Progress::Progress(CommandContext& ctx, const std::string& what, size_t total)
    : ctx_(ctx),
      what_(what),
      total_(total),
      active_(ctx.stderr_is_tty && !ctx.quiet),
      start_(std::chrono::steady_clock::now()) {
  if (const char* a = std::getenv("ROPREC_PROGRESS_AFTER_S")) {
    if (const auto v = parseNumber(a); v && *v >= 0) after_s_ = *v;
  }
}

void Progress::step(size_t done, size_t total) {
  if (total > 0) total_ = total;
  if (!active_ || total_ == 0) return;
  const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (t < after_s_ || (last_print_s_ >= 0 && t - last_print_s_ < 0.2 && done < total_)) return;
  last_print_s_ = t;
  std::string line = what_ + " " + std::to_string(done) + "/" + std::to_string(total_);
  if (done > 0 && t > 0) {
    const double rate = static_cast<double>(done) / t;
    line += " (" + cFixed(rate, 0) + "/s";
    if (done < total_)
      line += ", ETA " + cFixed(static_cast<double>(total_ - done) / rate, 0) + " s";
    line += ")";
  }
  const size_t pad = width_ > line.size() ? width_ - line.size() : 0;
  ctx_.err << "\r" << line << std::string(pad, ' ') << std::flush;
  width_ = line.size();
}

void Progress::finish() {
  if (active_ && width_ > 0) ctx_.err << "\r" << std::string(width_, ' ') << "\r" << std::flush;
  width_ = 0;
}

}  // namespace roprec::cli
