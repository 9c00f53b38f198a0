#pragma once
/// \file verify_json.hpp
/// The JSON texts of `roprec verify` (the result: plugin/api/verify.hpp): the verification JSON
/// and the one-line summary host interfaces return.

#include <string>
#include <vector>

#include "plugin/api/verify.hpp"
#include "plugin/report/json.hpp"

namespace roprec::api {

/// The verification JSON: measured file, registration, summary, identification (parameters,
/// covariance, condition number, identifiability), per-hole records. µm, µrad, mm.
Json verifyJson(const VerifyResult& r);

/// The one-line summary host interfaces return (C ABI, Python): holes, matched, failed, RMS of
/// measured/predicted/residual (µm), explained, coverage, registration, identified stiffness,
/// condition number, and `written` (the paths given).
Json verifySummaryJson(const VerifyResult& r, const std::vector<std::string>& written);

}  // namespace roprec::api
