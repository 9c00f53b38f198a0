#include "plugin/cli/cli.hpp"

#include <cmath>
#include <ostream>
#include <sstream>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/xml_node.hpp"
#include "plugin/api/job_options.hpp"

namespace roprec::cli {

Args::Args(std::vector<std::string> tokens)
    : tokens_(std::move(tokens)), used_(tokens_.size(), false) {}

std::optional<std::string> Args::option(const std::string& name) {
  std::optional<std::string> value;
  const std::string key = "--" + name;
  const std::string short_key = name.size() == 1 ? "-" + name : key;  // -o as well as --o
  for (size_t i = 0; i < tokens_.size(); ++i) {
    if (used_[i]) continue;
    if (tokens_[i] == key || tokens_[i] == short_key) {
      if (i + 1 >= tokens_.size()) throw UsageError("option " + key + " needs a value");
      used_[i] = used_[i + 1] = true;
      value = tokens_[i + 1];
      ++i;
    } else if (tokens_[i].rfind(key + "=", 0) == 0) {
      used_[i] = true;
      value = tokens_[i].substr(key.size() + 1);
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
  return parseNumberList(text, 6, "--joints") * kDeg;
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

void emit(CommandContext& ctx, const std::string& path, const std::string& text) {
  if (path.empty() || path == "-") {
    ctx.out << text;
    ctx.out.flush();
  } else {
    writeFileAtomic(path, text);
  }
}

Progress::Progress(CommandContext& ctx, const std::string& what, size_t total)
    : ctx_(ctx), what_(what), total_(total), active_(ctx.stderr_is_tty && !ctx.quiet) {}

void Progress::step(size_t done, size_t total) {
  if (total > 0) total_ = total;
  if (!active_ || total_ < 50 || (done - last_ < total_ / 50 && done != total_)) return;
  last_ = done;
  ctx_.err << "\r" << what_ << " " << done << "/" << total_ << std::flush;
}

void Progress::finish() {
  if (active_ && last_ > 0)
    ctx_.err << "\r" << std::string(what_.size() + 24, ' ') << "\r" << std::flush;
}

}  // namespace roprec::cli
