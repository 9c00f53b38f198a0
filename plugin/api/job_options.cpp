#include "plugin/api/job_options.hpp"

#include <sstream>
#include <vector>

#include "compensator/support/error.hpp"
#include "compensator/support/str_cat.hpp"
#include "compensator/support/xml_node.hpp"

namespace roprec::api {

Eigen::VectorXd numbersFromText(const std::string& text, int n, const std::string& what) {
  std::string blanks = text;
  for (char& c : blanks) c = (c == ',' ? ' ' : c);
  std::istringstream in(blanks);
  std::vector<double> v;
  std::string part;
  while (in >> part) {
    const auto x = parseNumber(part);
    if (!x) throw InputError("", 0, strCat(what, ": '", part, "' is not a finite number"));
    v.push_back(*x);
  }
  if (static_cast<int>(v.size()) != n) {
    throw InputError("", 0,
                     what + " needs " + std::to_string(n) + " numbers, got " +
                         std::to_string(v.size()) + ": \"" + text + "\"");
  }
  Eigen::VectorXd out(n);
  for (int i = 0; i < n; ++i) out[i] = v[static_cast<size_t>(i)];
  return out;
}

Pose poseFromXyzAbcText(const std::string& text, const std::string& what) {
  const Eigen::VectorXd v = numbersFromText(text, 6, what);
  Pose T = Pose::Identity();
  T.translation() = v.head<3>() * 1e-3;
  T.linear() = rotationFromZyx(v[3] * kDeg, v[4] * kDeg, v[5] * kDeg);
  return T;
}

std::vector<FrameDefinition> framesFromText(const std::string& text) {
  std::vector<FrameDefinition> frames;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ';')) {
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos) throw UsageError("--frame expects REF=\"x y z a b c\"[;REF=...]");
    frames.push_back({item.substr(0, eq),
                      poseFromXyzAbcText(item.substr(eq + 1),
                                         "--frame REF=\"x y z a b c\" (mm, deg, KUKA ABC)")});
  }
  return frames;
}

void applyFrameOption(JobOptions& options, const std::string& text) {
  if (text == "cell") {
    options.frame_cell = true;
  } else if (text.find('=') != std::string::npos) {
    options.frames = framesFromText(text);
  } else {
    options.frame_pose =
        poseFromXyzAbcText(text, "--frame \"x y z a b c\" (mm, deg, KUKA ABC) or cell");
  }
}

void applyToolOption(JobOptions& options, const std::string& text) {
  if (text != "program" && text != "cell") throw UsageError("--tool must be program or cell");
  options.tool = text;
}

void applyThreadsOption(JobOptions& options, const std::string& text) {
  const auto n = parseNumber(text);
  if (!n || !(*n >= 0 && *n <= 1024 && *n == static_cast<double>(static_cast<int>(*n))))
    throw UsageError("threads must be a whole number: 0 (every core) or 1..1024, not " + text);
  options.threads = static_cast<int>(*n);
}

}  // namespace roprec::api
