#pragma once
/// \file outputs_together.hpp
/// A job's output files written by writers that only read its result, on tasks of their own when
/// there are threads to spare, committed as one thread would (the active OutputSet's
/// all-or-nothing commit, compensator/support/atomic_file.hpp).

#include <functional>
#include <future>
#include <memory>
#include <string>
#include <vector>

#include "compensator/support/atomic_file.hpp"

namespace roprec::api {

/// What a writer on a task of its own staged (stagedApart).
using StagedOutputs = std::future<std::unique_ptr<OutputSet>>;

/// Runs `write` on a task of its own, staging into a set of its own (see writeOutputsTogether).
StagedOutputs stagedApart(const std::function<void()>& write);

/// Runs `program` (which returns the paths it wrote) and the optional `targets` and `report`
/// writers: one after the other with one thread (or when two outputs share a path), else at the
/// same time — they only read the result. A writer on another thread stages into a set of its
/// own, handed to the caller's set (ScopedOutputSet, the all-or-nothing commit) after the
/// program's outputs, so the files, their bytes and the commit order are those of one thread.
/// Waits for every writer before rethrowing the first error (program, targets, report).
/// `targets_started`: the targets writer already started by stagedApart (then `targets` is not
/// run again).
std::vector<std::string> writeOutputsTogether(
    int threads, bool distinct_paths, const std::function<std::vector<std::string>()>& program,
    const std::function<void()>& targets, const std::function<void()>& report,
    StagedOutputs targets_started = {});

}  // namespace roprec::api
