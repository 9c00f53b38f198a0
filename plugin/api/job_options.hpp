#pragma once
/// Text forms of the job options shared by every host: the CLI's `--frame`/`--tool`, the C ABI's
/// `roprec_options_set` and the Python module's keyword arguments parse through these, so a frame
/// or tool resolution means the same thing whichever host asks for it (docs/programs.md §15).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "compensator/support/rotation.hpp"
#include "plugin/api/job.hpp"

namespace roprec::api {

/// `n` finite numbers separated by blanks or commas. Throws InputError naming `what` when a token
/// is not a finite number or the count differs.
Eigen::VectorXd numbersFromText(const std::string& text, int n, const std::string& what);

/// "x y z a b c" (mm, deg, KUKA Z-Y'-X'' angles) -> SI pose. Throws InputError naming `what`.
Pose poseFromXyzAbcText(const std::string& text, const std::string& what);

/// "REF=x y z a b c[;REF=...]": frames by name. Throws UsageError without '=', InputError on a bad
/// pose.
std::vector<FrameDefinition> framesFromText(const std::string& text);

/// How controller-only base frames are resolved: "cell" (the cell's <workobject>), "x y z a b c"
/// (every such base frame, robot base frame) or "REF=x y z a b c[;REF=...]" (by name, base or
/// tool). Throws UsageError/InputError on any other text.
void applyFrameOption(JobOptions& options, const std::string& text);

/// How a program tool differing from the cell's is reconciled: "program" or "cell".
/// Throws UsageError on any other text.
void applyToolOption(JobOptions& options, const std::string& text);

/// Worker threads for the per-hole work: "0" (every core) or "1".."1024" (the output is the
/// same whatever the count). Throws UsageError on any other text.
void applyThreadsOption(JobOptions& options, const std::string& text);

}  // namespace roprec::api
