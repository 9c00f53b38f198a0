/* roprec.h — the C interface of roprec (libroprec_c).
 *
 * roprec predicts where an industrial robot really drills (deflection under link weight, tool
 * weight and the drilling forces) and pre-offsets the targets so that the real hole lands on the
 * nominal one. This header is the stable C ABI for hosts (OLP tools, C#/Delphi/Python ctypes …):
 * plain C types only; no C++ exception ever crosses it.
 *
 * Installed as  P/include/roprec/roprec.h ; link with  -lroprec_c  (P/lib/libroprec_c.so), or in
 * CMake:  find_package(roprec)  then  target_link_libraries(app PRIVATE roprec::roprec_c).
 *
 * ---------------------------------------------------------------------------------------------
 * Units and frames
 *   - Lengths in mm, angles in degrees, deviations in µm (translation) and µrad (rotation).
 *   - Poses are 4x4 homogeneous matrices, row-major (pose[4*r + c]): rotation in the upper-left
 *     3x3, translation (mm) in pose[3], pose[7], pose[11], last row 0 0 0 1. A pose passed in
 *     must be rigid: orthonormal rotation (to 1e-6), last row 0 0 0 1 (to 1e-9), finite values.
 *   - Poses are the TCP in the robot BASE frame: the robot card's base link (for FANUC, the
 *     controller's World frame at J2 height). TCP = flange x the cell's <tool>.
 *   - Joints are in the robot controller's convention (signs, zeros, FANUC J2/J3 coupling as the
 *     teach pendant shows them), degrees.
 *   - File paths are UTF-8 (as the operating system takes them); relative paths are relative to
 *     the process's working directory.
 *
 * Return codes (every int function)
 *   ROPREC_OK           0  done.
 *   ROPREC_ITEM_FAILED  1  the call was valid but some item (a target, a hole) could not be handled
 *                          (unreachable, singular, equilibrium not converged); `err` says which
 *                          and why. See each function for what is still written.
 *   ROPREC_BAD_INPUT    2  bad input (unreadable or invalid file — the text then reads
 *                          `FILE:LINE: what is wrong`, exactly as the roprec CLI prints it after
 *                          `roprec: error: ` —, NULL or non-finite argument, non-rigid pose, bad
 *                          option, output buffer too small) or the call could not be completed
 *                          (out of memory, internal error). Nothing is written.
 *
 * Error text
 *   Every function that can fail takes `char* err, size_t err_len`: a caller-owned buffer that
 *   receives the message (UTF-8). It is truncated to fit and always NUL-terminated when
 *   err_len > 0; on success it is set to "" . `err` may be NULL when err_len == 0.
 *
 * Memory and ownership
 *   All output buffers are owned by the caller. The library allocates only the session
 *   (roprec_open), which the caller releases with roprec_close, and the job options
 *   (roprec_options_new), released with roprec_options_free. roprec_version returns a static
 *   string.
 *
 * Thread safety
 *   The library keeps no global mutable state. Distinct sessions, and the whole-job calls, may
 *   run concurrently on distinct threads. One session must not be used by two threads at the
 *   same time (serialise the calls on it).
 * ------------------------------------------------------------------------------------------- */
#ifndef ROPREC_ROPREC_H
#define ROPREC_ROPREC_H

#include <stddef.h>

#if defined(_WIN32)
#if defined(ROPREC_C_BUILDING)
#define ROPREC_API __declspec(dllexport)
#else
#define ROPREC_API __declspec(dllimport)
#endif
#elif defined(__GNUC__)
#define ROPREC_API __attribute__((visibility("default")))
#else
#define ROPREC_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

#define ROPREC_OK 0
#define ROPREC_ITEM_FAILED 1
#define ROPREC_BAD_INPUT 2

/* A buffer of this size always holds the summary JSON of roprec_predict_file,
 * roprec_compensate_file, roprec_verify_file and roprec_plan_test_file (apart from the paths and
 * ids they list; see there). */
#define ROPREC_SUMMARY_LEN 4096

/* A cell (robot, tool, process load, controller) loaded once, for per-target calls. */
typedef struct roprec_session roprec_session;

/* The library version, e.g. "0.2.0" (static string; never NULL). */
ROPREC_API const char* roprec_version(void);

/* ---------------------------------------------------------------- one target at a time */

/* Loads the cell file `cell_path` (XML: robot, tool, workobject, process, controller).
 * On success *out receives a new session (release it with roprec_close) and 0 is returned;
 * otherwise *out is set to NULL and 2 is returned with the reason in `err`. */
ROPREC_API int roprec_open(const char* cell_path, roprec_session** out, char* err, size_t err_len);

/* Releases a session. NULL is allowed (no-op). */
ROPREC_API void roprec_close(roprec_session* s);

/* The RoboDK FilterTarget analogue.
 *   pose_mm           the TCP pose wanted (where the drill must really be), base frame, row-major.
 *   seed_joints_deg   6 controller joints (deg) whose IK branch and turns the result should keep
 *                     (the nearest admissible solution is taken), or NULL: the robot's reference
 *                     pose (KUKA {0,-90,90,0,0,0}, ABB/FANUC all zero).
 * Returns in out_pose_mm the pose to program (base frame, row-major) and in out_joints_deg its
 * joints (controller convention, deg) so that the predicted real TCP lands on `pose_mm` under the
 * cell's gravity, tool weight and process load (the cell's drill at its steady thrust).
 * Orientation is kept ("keep" mode): out_pose_mm has the rotation of pose_mm, bit for bit; only the
 * position is pre-offset, so the real drill axis keeps its small predicted tilt.
 * 1: the target cannot be filtered (unreachable, singular, not converged; reason in err);
 * the outputs are then left unchanged. out_pose_mm may alias pose_mm. */
ROPREC_API int roprec_filter_target(roprec_session* s, const double pose_mm[16],
                                    const double* seed_joints_deg, double out_pose_mm[16],
                                    double out_joints_deg[6], char* err, size_t err_len);

/* The predicted TCP deviation when the robot is commanded to `joints_deg` (controller convention,
 * deg) under the cell's gravity, tool weight and process load:
 *   deviation[0..2]  real − commanded TCP position, µm, base frame;
 *   deviation[3..5]  real TCP rotation relative to the commanded one (rotation vector), µrad,
 *                    base frame.
 * The predicted real TCP position is FK(joints) + deviation[0..2]. U_work_um (may be NULL)
 * receives the expanded uncertainty of a hole drilled there: the exact 95 % radius of the
 * anisotropic in-plane distribution (U_work_anisotropic, the radius the verdict uses), µm.
 * 1: no prediction at these joints (singular, not converged; reason in err); outputs unchanged.
 * 2: a joint outside the robot's limits (as the roprec CLI), or bad input.
 */
ROPREC_API int roprec_predict_joints(roprec_session* s, const double joints_deg[6],
                                     double deviation[6], double* U_work_um, char* err,
                                     size_t err_len);

/* ---------------------------------------------------------------- the hole's process */

/* The process of one hole (docs/process.md §1.5): which drill of the cell's tool table drills it
 * and the hole's own size and cut data. A zero (or NULL / "") field takes the cell's value. */
typedef struct roprec_hole_process {
  const char* tool;       /* the controller's tool number or name, as the cell's <drill tool="...">
                             keys it ("3", "tDrill68"); NULL or "": the cell's (first) drill */
  double diameter_mm;     /* hole diameter; 0: the drill's */
  double depth_mm;        /* hole depth; 0: the cell's <cut depth_mm> (else 2 x diameter) */
  double feed_mm_per_rev; /* 0: the drill's <cut feed_mm_per_rev> */
  double spindle_rpm;     /* 0: the drill's <cut spindle_rpm> */
} roprec_hole_process;

/* The process a call used, every value resolved (the cell's where the caller gave none). */
typedef struct roprec_process_used {
  char tool[64]; /* the drill's <drill tool> ("" for a single drill without one),
                    NUL-terminated (truncated to 63 bytes) */
  double diameter_mm;
  double depth_mm;
  double feed_mm_per_rev; /* 0 when the cell's process is not drilling */
  double spindle_rpm;
  int from_cell; /* 1: the caller gave no value: all of it is the cell's */
} roprec_process_used;

/* roprec_filter_target for a hole drilled with `process` (NULL: the cell's drill): the process
 * load is that drill's at the hole's diameter, feed and speed. `used` (may be NULL) receives the
 * process used. 2 also for a tool the cell's tool table does not have, a diameter outside
 * 0.1 .. 100 mm, a feed above 0.1 x the diameter, or a second tool with a single-drill cell. */
ROPREC_API int roprec_filter_target_hole(roprec_session* s, const double pose_mm[16],
                                         const double* seed_joints_deg,
                                         const roprec_hole_process* process, double out_pose_mm[16],
                                         double out_joints_deg[6], roprec_process_used* used,
                                         char* err, size_t err_len);

/* roprec_predict_joints for a hole drilled with `process` (NULL: the cell's drill); `used` (may be
 * NULL) receives the process used. */
ROPREC_API int roprec_predict_joints_hole(roprec_session* s, const double joints_deg[6],
                                          const roprec_hole_process* process, double deviation[6],
                                          double* U_work_um, roprec_process_used* used, char* err,
                                          size_t err_len);

/* The batch of roprec_filter_target_hole for a program's `count` targets in order (RoboDK's
 * FilterProgram): poses_mm holds count row-major 4x4 poses (16 * count doubles);
 * seed_joints_deg NULL (target i is then seeded with the IK choice of the previous target that
 * could be filtered — the continuity of `roprec compensate`; the first with the reference pose)
 * or 6 * count joints; processes NULL (the cell's drill) or count entries. out_poses_mm (16 *
 * count) and out_joints_deg (6 * count) receive each filtered target; status (NULL or count ints)
 * receives 0 (filtered) or 1 (not: its outputs are left unchanged) per target.
 * Returns 0 when every target was filtered, 1 when some were not (err lists them, `target I:
 * reason`), 2 for bad input (nothing written). */
ROPREC_API int roprec_filter_targets(roprec_session* s, size_t count, const double* poses_mm,
                                     const double* seed_joints_deg,
                                     const roprec_hole_process* processes, double* out_poses_mm,
                                     double* out_joints_deg, int* status, char* err,
                                     size_t err_len);

/* roprec_predict_joints_hole with every figure of the prediction, as a one-line JSON object:
 * the keys of roprec_predict_joints_json plus "process", the process used: {"tool", "drill" (its
 * label, e.g. "tool 3 'D6.8' (Ø6.8 mm)"), "diameter_mm", "depth_mm", "feed_mm_per_rev",
 * "spindle_rpm", "from_cell" (true: the caller gave no value)}. Numbers are the shortest text that
 * reads back as the same double (the Python module's predict_joints dict, value for value).
 * ROPREC_SUMMARY_LEN bytes suffice unless the tool names are long; too small gives 2.
 * 1: no prediction at these joints (reason in err). 2: a joint outside the robot's limits (as the
 * roprec CLI; roprec_error_kind gives ROPREC_ERROR_INPUT), a tool the cell does not have, or bad
 * input. */
ROPREC_API int roprec_predict_joints_hole_json(roprec_session* s, const double joints_deg[6],
                                               const roprec_hole_process* process, char* json,
                                               size_t json_len, char* err, size_t err_len);

/* roprec_filter_target_hole with the details, as a one-line JSON object (numbers as in
 * roprec_predict_joints_hole_json): "pose_mm" (16, the pose to program, row-major), "joints_deg"
 * (6, controller convention), "config" (the vendor's configuration flags of those joints),
 * "residual_um" (|predicted real TCP - wanted|) and "process" (as
 * roprec_predict_joints_hole_json's). ROPREC_SUMMARY_LEN bytes suffice unless the tool names are
 * long; too small gives 2. 1: the target cannot be filtered (reason in err); 2 as
 * roprec_filter_target_hole. */
ROPREC_API int roprec_filter_target_hole_json(roprec_session* s, const double pose_mm[16],
                                              const double* seed_joints_deg,
                                              const roprec_hole_process* process, char* json,
                                              size_t json_len, char* err, size_t err_len);

/* roprec_filter_targets with the process used per target, as a one-line JSON object (numbers as in
 * roprec_predict_joints_hole_json): "poses_mm" (count arrays of 16; a target not filtered keeps its
 * wanted pose), "joints_deg" (count arrays of 6, or null where not filtered), "ok" (count
 * booleans), "reasons" (null or why not, per target) and "process" (count objects, as
 * roprec_predict_joints_hole_json's). A buffer too small gives 2 and the bytes needed in err
 * (about 1 kB per target suffices unless the tool names are long).
 * Returns 0 when every target was filtered, 1 when some were not (the JSON is still written; err
 * lists them, `target I: reason`), 2 for bad input (nothing written). */
ROPREC_API int roprec_filter_targets_json(roprec_session* s, size_t count, const double* poses_mm,
                                          const double* seed_joints_deg,
                                          const roprec_hole_process* processes, char* json,
                                          size_t json_len, char* err, size_t err_len);

/* ---------------------------------------------------------------- whole programs (by file) */

/* `roprec predict --cell CELL PROGRAM [--holes HOLES] [--json JSON_OUT]`:
 * predicts every hole of `program_path` (KUKA .src, ABB .mod/.prg/.sys, FANUC .ls, CSV/JSON target
 * list, or a hole-list CSV). `holes_path` (or NULL) is a hole-list CSV whose ids, diameters,
 * depths and tolerances are matched to the program's holes (by id, else by position within
 * 0.5 mm).
 *   json_out_path     NULL, or where the full prediction JSON is written (atomically) — the same
 *                     document, byte for byte, as `roprec predict ... --json`.
 *   summary_json      NULL (then summary_len must be 0), or a buffer that receives (on 0 and 1;
 *                     "" on 2) a one-line JSON object: the "summary" object of the prediction JSON
 *                     ("holes", "verdicts" {conforms, conforms-after-compensation,
 *                     not-capable, unreachable, singular, not-converged}, "robot_can_take",
 *                     "mc_time_taken_s", "mc_time_total_s", "process_share_mean",
 *                     "process_share_max") plus "failed" (holes not predicted).
 *                     ROPREC_SUMMARY_LEN bytes suffice; a smaller buffer that cannot hold it gives
 *                     2 and nothing is written.
 * Returns 0, or 1 when some holes could not be predicted (the JSON is still written, those holes
 * carry their verdict and reason; err lists them as `hole ID (FILE:LINE): verdict: reason`), or 2.
 */
ROPREC_API int roprec_predict_file(const char* cell_path, const char* program_path,
                                   const char* holes_path, const char* json_out_path,
                                   char* summary_json, size_t summary_len, char* err,
                                   size_t err_len);

/* `roprec compensate --cell CELL PROGRAM -o OUT_PROGRAM --orientation MODE [--holes HOLES]
 *  [--targets TARGETS_OUT]`: pre-offsets every hole of a drilling program so the predicted real
 * holes land on the nominal ones (every target of a drill cycle moves with its drill point) and
 * writes the corrected program in its own dialect (only the compensated targets' bytes change; a
 * KUKA .src whose points live in its .dat gets the .dat written beside the new .src).
 *   orientation       "keep" (or NULL): positions only; "flip-free": the rotation about each drill
 *                     axis chosen so axes 4/6 do not flip; "stiffest": the stiffest rotation.
 *   holes_path        NULL, or a hole-list CSV matched to the program's holes (as for predict).
 *   targets_out_path  NULL, or the corrected-target export: CSV when the name ends in ".csv", else
 *                     JSON — the same document as `roprec compensate ... --targets`.
 *   summary_json      NULL (summary_len 0), or a buffer that receives (on 0; "" otherwise) a
 *                     one-line JSON object: {"orientation", "holes", "compensated", "failed",
 *                     "error_before_um": {"mean", "max"}, "residual_after_um": {"mean", "max"},
 *                     "conform_before", "conform_after", "jumps_before", "jumps_after",
 *                     "written": [paths]}.
 *                     ROPREC_SUMMARY_LEN bytes suffice unless the paths are long; too small gives 2
 *                     and nothing is written.
 * All outputs are written together (each atomically) and only when every hole was compensated and
 * the writer accepted every edit; otherwise 1 is returned, nothing is written and err lists the
 * holes/edits. A milling cell compensates every linear path point instead (summary: "process",
 * "points", "failed", "deviation_before_um", "residual_after_um", "written"; orientation and
 * holes_path are ignored; the export is CSV or JSON by its name as above; the job is that of
 * `roprec compensate`: a KRL program, a RAPID module or a TP program is read by windows and
 * written as its points come, in memory that does not grow with them).
 * The program may be any file roprec_predict_file reads (a hole-list CSV is rewritten as such).
 * 2: bad input (unreadable program, program without holes, bad orientation). */
ROPREC_API int roprec_compensate_file(const char* cell_path, const char* program_path,
                                      const char* holes_path, const char* out_program_path,
                                      const char* orientation, const char* targets_out_path,
                                      char* summary_json, size_t summary_len, char* err,
                                      size_t err_len);

/* ---------------------------------------------------------------- job options */

/* Job options for roprec_predict_file_ex and roprec_compensate_file_ex: what the CLI's predict and
 * compensate options say, for hosts that need more than the plain calls above (a program whose
 * frames or tool only the controller defines, a program compensated before).
 * A new options object holds the defaults of the plain calls; release it with
 * roprec_options_free. One options object may be shared by calls on several threads once it is
 * no longer being set. */
typedef struct roprec_options roprec_options;

/* *out receives a new options object (0), or NULL (2: out of memory, out NULL). */
ROPREC_API int roprec_options_new(roprec_options** out, char* err, size_t err_len);

/* Releases an options object. NULL is allowed (no-op). */
ROPREC_API void roprec_options_free(roprec_options* options);

/* Sets one option from its text (UTF-8); on 2 (unknown key, bad value) the object is unchanged.
 *   "holes"         hole-list CSV matched to the program's holes ("" = none)     --holes
 *   "match_tol_mm"  position match when ids differ, mm (> 0; default 0.5)        --match-tol
 *   "uncertainty"   "linear" or "montecarlo" ("" = the cell's)                   --uncertainty
 *   "frame"         how base frames only the controller defines are resolved:    --frame
 *                   "cell" (the cell's <workobject>), "x y z a b c" (mm, deg, KUKA ABC, robot
 *                   base frame: every such frame) or "REF=x y z a b c[;REF=...]" (by name)
 *   "tool"          a program tool that differs from the cell's, or only the      --tool
 *                   controller defines: "program" (the program's TCP is the real one) or "cell"
 *   "threads"       worker threads for the per-hole work (a milling path's two    --threads
 *                   pipelined chains): "0" (every core) or "1".."1024" (default "1"); the
 *                   outputs are the same bytes whatever the count
 *   "orientation"   "keep" (default), "flip-free" or "stiffest" (compensate only) --orientation
 *   "force"         "1": compensate a program that carries roprec's compensation   --force
 *                   marker again (with a note); "0" (default): such a program is refused (2)
 * roprec_verify_file_ex only:
 *   "write_cell"    where the cell the next job runs with is written ("" = none):  --write-cell
 *                   its <part_registration> (workobject kept), its robot the new card
 *   "poses"         measured TCP poses (laser tracker / CMM CSV) identified with   --poses
 *                   the holes ("" = none); with poses, program and measured may be NULL
 *   "identify"      "stiffness", "geometry" or "all" (default): what the new card  --identify
 *                   may move
 *   "folds"         k of the held-out validation, "0".."100" (default "5")        --folds
 *   "date"          the written calibration's date, YYYY-MM-DD ("" = the rule of  --date
 *                   docs/cards.md: SOURCE_DATE_EPOCH, else the measured file's day)
 *   "u_rot"         σ per axis of a measured pose orientation (rx,ry,rz) when the --u-rot
 *                   row has no u_rot, µrad, > 0 ("" = the default 100)
 * Without "frame"/"tool", a controller-only frame or a differing tool is an error (2) naming the
 * frame or tool and these options. How they were resolved is stated in the prediction JSON's
 * notes and in the report header. */
ROPREC_API int roprec_options_set(roprec_options* options, const char* key, const char* value,
                                  char* err, size_t err_len);

/* roprec_predict_file with the job options (the holes list comes from "holes"). */
ROPREC_API int roprec_predict_file_ex(const char* cell_path, const char* program_path,
                                      const roprec_options* options, const char* json_out_path,
                                      char* summary_json, size_t summary_len, char* err,
                                      size_t err_len);

/* roprec_compensate_file with the job options ("holes", "orientation", "force", "frame", "tool").
 */
ROPREC_API int roprec_compensate_file_ex(const char* cell_path, const char* program_path,
                                         const roprec_options* options,
                                         const char* out_program_path, const char* targets_out_path,
                                         char* summary_json, size_t summary_len, char* err,
                                         size_t err_len);

/* `roprec verify --cell CELL PROGRAM --measured MEASURED [--holes HOLES] [--register REG]
 *  [--json JSON_OUT] [--calibrate NEW_CARD_OUT]`: compares the holes a CMM measured on a part
 * drilled with `program_path` against the prediction. measured_path     roprec CSV
 * (id,x,y,z[,i,j,k][,u]), PC-DMIS CSV or DMIS output; positions in the cell's workobject frame, mm;
 * u (µm) the standard measurement uncertainty per axis (5 µm when absent). Holes are matched by id.
 *   holes_path        NULL, or a hole-list CSV matched to the program's holes (nominal holes).
 *   registration      NULL or "none", "translation", "rigid": a part registration estimated jointly
 *                     with the joint stiffness and removed before the comparison.
 *   json_out_path     NULL, or the verification JSON — byte for byte `roprec verify ... --json`.
 *   new_card_out_path NULL, or where the re-identified robot card is written (the identification
 *                     then runs): `roprec verify ... --calibrate`.
 *   summary_json      NULL (summary_len 0), or a buffer that receives (on 0; "" otherwise) a
 *                     one-line JSON object: "holes", "matched", "failed", "rms_measured_um",
 *                     "rms_predicted_um", "rms_residual_um", "explained", "coverage",
 *                     "registration" {"kind"[, "frame", "translation_um", "translation_sigma_um",
 *                     "rotation_urad", "rotation_sigma_urad"]}, "identification" (when run)
 *                     {"converged", "condition_number", "rms_prior_um", "rms_final_um", "joints":
 *                     [{"joint", "k_card", "k", "k_sigma", "identified"}]}, "written": [paths].
 *                     ROPREC_SUMMARY_LEN bytes suffice unless the paths are long.
 * Outputs are written together and only when every measured hole was predicted; otherwise 1 is
 * returned (err lists the holes) and nothing is written. 2: bad input (a measured file with a
 * missing column, a non-number, a duplicate id or in metres: `FILE:LINE: what`). */
ROPREC_API int roprec_verify_file(const char* cell_path, const char* program_path,
                                  const char* measured_path, const char* holes_path,
                                  const char* registration, const char* json_out_path,
                                  const char* new_card_out_path, char* summary_json,
                                  size_t summary_len, char* err, size_t err_len);

/* roprec_verify_file with the job options: "holes", "match_tol_mm", "uncertainty", "frame",
 * "tool", "threads" and the verify keys "write_cell", "poses", "identify", "folds", "date",
 * "u_rot" (see roprec_options_set). measured_path and program_path may be NULL when "poses" is set.
 * Every file written (JSON, card, cell) is byte for byte what `roprec verify` writes with the same
 * options; the summary's "written" lists them. The cell is not written when the held-out validation
 * refused the card. 2 also for "write_cell" without a registration or a new card. */
ROPREC_API int roprec_verify_file_ex(const char* cell_path, const char* program_path,
                                     const char* measured_path, const char* registration,
                                     const roprec_options* options, const char* json_out_path,
                                     const char* new_card_out_path, char* summary_json,
                                     size_t summary_len, char* err, size_t err_len);

/* `roprec plan-test --cell CELL --region "x0 y0 z0 x1 y1 z1" --count N -o OUT_PATH`: a D-optimal
 * drilling test program for re-identifying the joint stiffness. Candidate drill points on a 4 x 4 x
 * 4 grid over the region (workobject frame, mm; region_mm = {x0, y0, z0, x1, y1, z1}), drilled
 * along -z of the workobject, rotations 0 and 90 deg about the drill axis; `count` holes are
 * chosen. OUT_PATH is written in the cell robot's dialect (KRL .src + .dat, RAPID .mod, TP .ls) or
 * as a hole list when it ends in ".csv". summary_json      NULL (summary_len 0), or a buffer that
 * receives (on 0) a one-line JSON object: "holes", "candidates", "rejected", "log_det", "joints":
 * [{"joint", "k_card", "prior_sigma_rel", "expected_sigma_rel", "expected_sigma_k"}], "ids",
 *                     "written".
 * 2: bad input (region, count, fewer admissible candidates than count). */
ROPREC_API int roprec_plan_test_file(const char* cell_path, const double region_mm[6], int count,
                                     const char* out_path, char* summary_json, size_t summary_len,
                                     char* err, size_t err_len);

/* ---------------------------------------------------------------- for bindings */

/* The kind of the error the last call on this thread returned (ROPREC_OK: none), for bindings that
 * map it to their own exceptions: an item that could not be handled (the call returned 1), a bad
 * input file (`FILE:LINE: ...`), a bad argument or option, out of memory, an internal error. */
#define ROPREC_ERROR_NONE 0
#define ROPREC_ERROR_ITEM 1
#define ROPREC_ERROR_INPUT 2
#define ROPREC_ERROR_USAGE 3
#define ROPREC_ERROR_MEMORY 4
#define ROPREC_ERROR_INTERNAL 5
ROPREC_API int roprec_error_kind(void);

/* The session's cell as a one-line JSON object: "cell_path", "cell" (its name), "robot" (the robot
 * card's name), "process" (as the prediction JSON describes it), "tool_pose_mm" (the TCP in the
 * flange frame: the cell's <tool>) and "workobject_pose_mm" (the workobject frame in the robot
 * base frame), each 16 numbers of a 4x4 pose, row-major. Numbers are the shortest text that reads
 * back as the same double. ROPREC_SUMMARY_LEN bytes suffice unless the names are long; too small
 * gives 2. */
ROPREC_API int roprec_session_info(roprec_session* s, char* json, size_t json_len, char* err,
                                   size_t err_len);

/* roprec_predict_joints with every figure of the prediction, as a one-line JSON object (numbers
 * as in roprec_session_info): "deviation_um", "rotation_urad" (3 each, as deviation[]),
 * "U_work_um", "U_robot_um", "U_mach_um", "k", "work_deviation_um" (3: deviation_um + the
 * machining deviation), "position_error_um", "axis_tilt_urad" (w.r.t. the commanded TCP z axis),
 * "tolerance_mm", "verdict", "config", "joints_deg" (6, the joints predicted, radians converted
 * as the JSON exports do), "process_force_N" (3, base frame). ROPREC_SUMMARY_LEN bytes suffice.
 * 1: no prediction at these joints (reason in err). */
ROPREC_API int roprec_predict_joints_json(roprec_session* s, const double joints_deg[6], char* json,
                                          size_t json_len, char* err, size_t err_len);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* ROPREC_ROPREC_H */
