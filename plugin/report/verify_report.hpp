#pragma once
/// \file verify_report.hpp
/// The HTML report of `roprec verify` (the result: plugin/api/verify.hpp).

#include <string>

#include "plugin/api/verify.hpp"

namespace roprec::api {

/// The self-contained HTML report (inline SVG; deterministic bytes): measured vs predicted
/// arrows per face, residual map, statistics, identified parameters with their uncertainties.
std::string verifyReport(const VerifyResult& r);

}  // namespace roprec::api
