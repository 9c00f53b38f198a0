#pragma once
/// The report of a compensated milling path (`roprec compensate --report` with a milling cell):
/// one self-contained HTML page (no external resources) with the deviation of every linear path
/// point before compensation (the coupled force, docs/process.md) and the predicted residual
/// after it, in µm, drawn along the path, and a table per point: program target and line,
/// whether it cuts and why, the converged force, the before/after deviation, the coupled
/// solver's status, iterations and loop gain, the configuration written.
#include <string>

#include "plugin/api/job.hpp"

namespace roprec::api {

/// Throws InputError when a number to be shown is not finite (nothing is written then).
std::string millingCompensationReport(const MillingCompensationResult& r,
                                      const std::string& program_path);
/// The same bytes handed to `sink` in pieces of about 64 KiB (no whole-document string).
void writeMillingCompensationReport(const MillingCompensationResult& r,
                                    const std::string& program_path, const ByteSink& sink);

}  // namespace roprec::api
