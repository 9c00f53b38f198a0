#pragma once
/// \file exports.hpp
/// The texts a job writes (docs/contract.md): the prediction JSON and HTML report, the
/// corrected-target export (CSV or JSON), the compensation report, the milling path export.
/// Pure functions of a job result; deterministic bytes for identical inputs.

#include <string>

#include "plugin/api/job.hpp"

namespace roprec::api {

/// The prediction JSON of the file contract (docs/contract.md "Prediction output").
Json predictionJson(const PredictionResult& r);
/// The self-contained HTML report of a prediction.
std::string predictionReport(const PredictionResult& r);

/// The corrected-target export: CSV when `csv`, else JSON (docs/contract.md "Corrected targets").
std::string compensationTargets(const CompensationResult& r, const std::string& program_path,
                                bool csv);
/// The compensation report (before/after maps).
std::string compensationReport(const CompensationResult& r, const std::string& program_path);

/// The milling path export: per point the nominal and programmed pose, force, coupling iterations.
std::string millingTargetsJson(const MillingCompensationResult& r, const std::string& program_path);

}  // namespace roprec::api
