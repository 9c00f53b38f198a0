#include "plugin/api/outputs_together.hpp"

#include <exception>
#include <utility>

namespace roprec::api {

StagedOutputs stagedApart(const std::function<void()>& write) {
  return std::async(std::launch::async, [write] {
    auto set = std::make_unique<OutputSet>();
    const ScopedOutputSet scope(*set);
    write();
    return set;
  });
}

std::vector<std::string> writeOutputsTogether(
    int threads, bool distinct_paths, const std::function<std::vector<std::string>()>& program,
    const std::function<void()>& targets, const std::function<void()>& report,
    StagedOutputs targets_started) {
  if (!targets_started.valid() && (threads <= 1 || !distinct_paths || (!targets && !report))) {
    std::vector<std::string> written = program();
    if (targets) targets();
    if (report) report();
    return written;
  }
  StagedOutputs t = std::move(targets_started);
  StagedOutputs rep;
  if (targets && !t.valid()) t = stagedApart(targets);
  if (report) rep = stagedApart(report);
  std::vector<std::string> written;
  std::exception_ptr first;
  try {
    written = program();
  } catch (...) {
    first = std::current_exception();
  }
  for (StagedOutputs* f : {&t, &rep}) {
    if (!f->valid()) continue;
    try {
      std::unique_ptr<OutputSet> set = f->get();
      if (first) continue;  // its temporaries are removed with it
      if (OutputSet* active = activeOutputSet()) {
        active->adopt(std::move(*set));
      } else {
        set->commit();
      }
    } catch (...) {
      if (!first) first = std::current_exception();
    }
  }
  if (first) std::rethrow_exception(first);
  return written;
}

}  // namespace roprec::api
