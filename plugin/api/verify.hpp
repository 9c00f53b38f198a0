#pragma once
/// \file verify.hpp
/// `roprec verify` as a host-facing job: a cell + the drilled program + the CMM's
/// measured holes in; per hole the measured deviation against the predicted one, the statistics,
/// optionally the part registration and the re-identified joint stiffness, and the texts a host
/// writes (JSON, HTML report, the calibrated robot card). No parsing of arguments, no printing.
///
/// Frames and units: SI inside every struct (m, rad, N·m/rad). The measured file holds hole
/// positions in the cell's **workobject** frame in mm (postproc/measured.hpp); they are taken to
/// the robot base frame with the cell's T_base_wobj (and its <part_registration>, partMotion). Per
/// hole the in-plane axes (e₁, e₂) are those of the nominal hole pose (the hole list's when --holes
/// is given, else the program's drill point), z = the drilling direction
/// (compensator/precision/identification.hpp). The commanded joints of a hole are the prediction's
/// (rigid IK of the programmed target).
///
/// Errors: bad input (cell, program, hole list, measured file: missing column, non-number,
/// duplicate id, a file in metres, no hole matching) throws roprec::InputError (`FILE:LINE:
/// what`); bad arguments throw UsageError. Measured ids the program does not have and program
/// holes that were not measured are notes. A measured hole whose prediction failed (unreachable,
/// singular) is listed in VerifyResult::failed (CLI exit 1). Deterministic: identical inputs give
/// identical results and byte-identical texts.

#include <optional>
#include <string>
#include <vector>

#include "compensator/precision/fit_validation.hpp"
#include "compensator/precision/identification.hpp"
#include "plugin/api/job.hpp"
#include "postproc/measured.hpp"
#include "postproc/measured_poses.hpp"

namespace roprec::api {

/// `hole ID (PROGRAM:LINE)` (`hole ID` when the line is not known): how every host names a hole
/// in messages.
std::string holeWhere(const std::string& id, int line, const std::string& program);

struct VerifyJob {
  JobOptions job;        ///< hole list, match tolerance, uncertainty method
  std::string measured;  ///< the CMM file (roprec CSV, PC-DMIS CSV or DMIS), workobject mm
  /// Measured TCP poses (laser tracker / CMM, postproc/measured_poses.hpp), identified together
  /// with the holes: 3 equations per pose, 6 when the row has its orientation (rx,ry,rz). With
  /// poses, the program and `measured` are optional.
  std::string poses;
  Registration registration{Registration::kNone};  ///< part registration estimated jointly
  bool calibrate{false};  ///< re-identify the joint stiffness (identification.hpp)
  /// Also identify the tool's mass and centre of mass (prior: the cell's <tool>, σ 2 kg and
  /// 20 mm); reported, the cell is not rewritten.
  bool identify_tool{false};
  double u_measurement_um{5.0};  ///< σ per axis of a measured position when the file has no `u`
  /// σ per axis of a measured pose orientation (rx,ry,rz) when the row has no `u_rot`, µrad: a
  /// 6-DoF tracker probe's stated orientation accuracy is 0.01° ≈ 175 µrad (2σ).
  double u_rotation_urad{100.0};
  IdentifySet identify{IdentifySet::kAll};  ///< which robot parameters --calibrate may move
  /// k of the k-fold held-out validation run with calibrate (fit_validation.hpp); 0: none (the
  /// card is then written without a held-out check, and the result says so).
  int folds{5};
  /// The calibration's `date` (YYYY-MM-DD); empty: calibrationDate()'s rule.
  std::string date;
};

/// The date written into a calibration: `date` when given (YYYY-MM-DD, checked), else the UTC day
/// of SOURCE_DATE_EPOCH when set, else the UTC day of `measured_file`'s modification time (the
/// day the measurement was saved). Never empty; the same inputs give the same day.
std::string calibrationDate(const std::string& date, const std::string& measured_file);

struct VerifyResult {
  PredictionResult prediction;  ///< the program predicted with the cell's card
  std::string date;             ///< of the calibration (calibrationDate), with calibrate
  postproc::MeasuredHoles measured;
  postproc::MeasuredPoses poses;  ///< empty without a pose file
  postproc::MeasuredMatch match;
  Registration registration{Registration::kNone};
  bool calibrate{false};
  std::string cell_path, program_path;
  std::vector<std::string> notes;  ///< unknown ids, unmeasured holes, job notes
  std::vector<std::string>
      failed;  ///< "hole ID (FILE:LINE): verdict: reason" (measured, unpredicted)
  /// Verified holes in program order: the request index and the measured index of each.
  std::vector<int> request_of, measured_of;
  std::vector<HoleVerification> holes;
  std::vector<Pose> nominal;    ///< nominal hole pose of each verified hole (base frame)
  VerificationSummary summary;  ///< correlations along the workobject axes
  /// Run when calibrate or registration ≠ none.
  std::optional<IdentificationResult> identification;
  /// Per-hole residual |measured − predicted| ⊥ axis after identification (m), holes order.
  std::vector<double> residual_identified;
  /// The observations identified from (the verified holes in order, then the poses); kept for
  /// the validation and the checks.
  std::vector<IdentificationHole> observations;
  /// With calibrate: the χ² check of the fit and the held-out validation (k-fold; absent with
  /// folds = 0 or fewer observations than folds, with a note).
  std::optional<FitCheck> fit_check;
  std::optional<HeldOutValidation> validation;
  /// Why the calibrated card must not be written (empty: it may): its held-out error is not
  /// below the original card's.
  std::string card_refused;
};

/// Predicts the job, reads and matches the measured holes, identifies (when asked) and verifies
/// every measured hole (registration removed from the measured positions when estimated).
/// Throws InputError/UsageError (see the file comment).
VerifyResult verifyJob(const std::string& cell_path, const std::string& program_path,
                       const VerifyJob& job, const ProgressFn& progress = {});

// The JSON texts: plugin/report/verify_json.hpp.

// The HTML report: plugin/report/verify_report.hpp.

/// The new robot card (card_writer.hpp): the cell's card with each identified joint's stiffness
/// and source replaced (`identified: N holes from MEASURED_FILE_NAME by roprec verify (σ = …)`);
/// unidentifiable joints keep the prior. When `card_out_path` is given and the card's URDF is not
/// next to it, the card's `urdf` attribute is rewritten to the URDF's path relative to the new
/// card's folder, so the new card loads where it is written. Throws UsageError when the result
/// has no identification (calibrate was not asked), InputError for a malformed card.
std::string calibratedCardText(const VerifyResult& r, const std::string& measured_file_name,
                               const std::string& card_out_path = "");

/// The cell for the next job (cell.hpp format): the cell file's text with the registration as
/// `<part_registration xyz_mm rpy_mrad source>` — F = [R(ω), t], composed as F_cell · F with the
/// cell's own when it has one; none with Registration::kNone; the workobject kept — and, when
/// `card_path` is given, `<robot file="…"/>` pointing to
/// that card (relative to the new cell's folder); otherwise a `file=`/`urdf=` reference is made
/// relative to the new cell's folder. Nothing else changes. Throws UsageError when the result
/// has no identification, InputError(cell, line, …) when the cell's `<robot>`/`<part_registration>`
/// element cannot be rewritten (not a single empty-element tag).
std::string calibratedCellText(const VerifyResult& r, const std::string& cell_out_path,
                               const std::string& card_path);

}  // namespace roprec::api
