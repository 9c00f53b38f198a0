/// \file roprec_python.cpp
/// The extension module `roprec._roprec` (pybind11) over the host-facing job API
/// (plugin/api/job.hpp). The package `roprec` (roprec/__init__.py) re-exports it; see there for
/// the public API. Units at this boundary: mm, degrees, µm, µrad; poses are 4x4 numpy arrays
/// (TCP in the robot base frame unless said otherwise).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "plugin/api/hole_input.hpp"
#include "plugin/api/job.hpp"
#include "plugin/api/job_options.hpp"
#include "plugin/api/plan_test.hpp"
#include "plugin/api/verify.hpp"
#include "plugin/c/host_common.hpp"
#include "plugin/report/plan_test_json.hpp"
#include "plugin/report/verify_json.hpp"

namespace py = pybind11;

namespace roprec::python {
namespace {

/// Runs `write` (which writes through writeFileAtomic) so that its outputs appear all or none
/// (compensator/support/atomic_file.hpp).
template <class F>
void writeAllOrNone(F&& write) {
  if (activeOutputSet() != nullptr) {  // inside a RunScope: its commit writes them
    write();
    return;
  }
  OutputSet outputs;
  {
    const ScopedOutputSet scope(outputs);
    write();
  }
  outputs.commit();
}

/// The outputs of one call, staged from its start: the input files the call reads are noted in
/// it, so that no output can replace one (atomic_file.hpp); commit() at the end of the call.
class RunScope {
 public:
  void commit() { set_.commit(); }

 private:
  OutputSet set_;
  ScopedOutputSet scope_{set_};
};

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// A target or hole that could not be handled (raised as roprec.ItemError).
class ItemFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The exception classes, created once when the module is imported (extension modules are never
/// unloaded, so the references stay valid for the life of the process).
struct ErrorClasses {
  PyObject* base{nullptr};
  PyObject* input{nullptr};
  PyObject* usage{nullptr};
  PyObject* item{nullptr};
};
ErrorClasses& errorClasses() {
  static ErrorClasses classes;
  return classes;
}

// ---------------------------------------------------------------- conversions

py::array_t<double> poseArray(const Pose& T) {
  py::array_t<double> a({4, 4});
  host::poseToRowMajorMm(T, a.mutable_data());
  return a;
}

template <class V>
py::array_t<double> vectorArray(const V& v, double scale = 1.0) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  double* d = a.mutable_data();
  for (Eigen::Index i = 0; i < v.size(); ++i) d[i] = v[i] * scale;
  return a;
}

/// Radians -> degrees, divided as the JSON exports do (bit-identical numbers).
py::array_t<double> degreesArray(const Vec6& v) {
  py::array_t<double> a(6);
  double* d = a.mutable_data();
  for (int i = 0; i < 6; ++i) d[i] = v[i] / kDeg;
  return a;
}

py::array_t<double> quaternionArray(const Mat3& R) {
  const Eigen::Quaterniond q = quaternionFromRotation(R);
  return vectorArray(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()));
}

Pose poseArg(const py::handle& h, const char* name) {
  const Array a = Array::ensure(h);
  if (!a || a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4) {
    throw UsageError(std::string(name) + ": a 4x4 pose (array-like of numbers) is expected");
  }
  return host::poseFromRowMajorMm(a.data(), name);
}

template <int N>
Eigen::Matrix<double, N, 1> vectorArg(const py::handle& h, const char* name) {
  const Array a = Array::ensure(h);
  if (!a || a.ndim() != 1 || a.shape(0) != N) {
    throw UsageError(std::string(name) + ": " + std::to_string(N) + " numbers are expected");
  }
  Eigen::Matrix<double, N, 1> v;
  for (int i = 0; i < N; ++i) {
    v[i] = a.data()[i];
    if (!std::isfinite(v[i]))
      throw UsageError(std::string(name) + ": element " + std::to_string(i) + " is not finite");
  }
  return v;
}

const char* statusName(HoleStatus s) {
  switch (s) {
    case HoleStatus::kOk:
      return "ok";
    case HoleStatus::kUnreachable:
      return "unreachable";
    case HoleStatus::kSingular:
      return "singular";
    case HoleStatus::kNotConverged:
      return "not-converged";
  }
  return "?";
}

py::object textOrNone(std::string_view s) {
  return s.empty() ? py::object(py::none()) : py::object(py::str(s.data(), s.size()));
}

// ---------------------------------------------------------------- result dictionaries

/// One hole of a prediction: the keys of the prediction JSON, flattened, at full precision.
py::dict holeDict(const HolePrediction& h, const HoleRequest& r, const RobotCard& card) {
  py::dict d;
  d["id"] = h.id;
  d["line"] = r.line > 0 ? py::object(py::int_(r.line)) : py::object(py::none());
  d["status"] = statusName(h.status);
  d["verdict"] = verdictName(h.verdict);
  d["reason"] = textOrNone(h.reason);
  d["nominal_pose_mm"] = poseArray(r.T_W_tcp);
  d["nominal_position_mm"] = vectorArray(r.T_W_tcp.translation(), 1e3);
  d["nominal_quaternion_wxyz"] = quaternionArray(r.T_W_tcp.linear());
  d["axis"] = vectorArray(Vec3(r.T_W_tcp.linear().col(2)));
  d["diameter_mm"] = h.diameter * 1e3;
  d["depth_mm"] = h.depth * 1e3;
  d["tolerance_mm"] = h.tolerance * 1e3;
  // the hole's own drill (a tool table's, or its own feed/speed), as the JSON's "drill"
  const bool own = api::statesOwnProcess(r);
  d["drill_tool"] = own && !r.tool.empty() ? py::object(py::str(r.tool)) : py::object(py::none());
  d["feed_mm_per_rev"] = own ? py::object(py::float_(h.feed * 1e3)) : py::object(py::none());
  d["spindle_rpm"] = own ? py::object(py::float_(h.spindle_rpm)) : py::object(py::none());
  d["mc_time_s"] = h.mc_time;
  const bool has_joints = h.status == HoleStatus::kOk || h.status == HoleStatus::kNotConverged ||
                          h.status == HoleStatus::kSingular;
  d["joints_deg"] = has_joints ? py::object(degreesArray(h.joints)) : py::object(py::none());
  d["controller_joints_deg"] = has_joints
                                   ? py::object(degreesArray(toControllerJoints(card, h.joints)))
                                   : py::object(py::none());
  d["config"] = has_joints ? textOrNone(h.config) : py::object(py::none());
  d["branch"] = has_joints ? py::object(py::int_(h.branch)) : py::object(py::none());
  const bool ok = h.status == HoleStatus::kOk;
  auto when_ok = [&](auto&& make) { return ok ? py::object(make()) : py::object(py::none()); };
  d["deviation_um"] = when_ok([&] { return vectorArray(h.d_work, 1e6); });
  d["robot_deviation_um"] = when_ok([&] { return vectorArray(h.d_robot, 1e6); });
  d["mach_deviation_um"] = when_ok([&] { return vectorArray(h.d_mach, 1e6); });
  d["rotation_urad"] = when_ok([&] { return vectorArray(h.d_rot, 1e6); });
  d["work_tool_xy_um"] = when_ok([&] { return vectorArray(h.e_tool, 1e6); });
  d["position_error_um"] = when_ok([&] { return py::float_(h.position_error * 1e6); });
  d["axis_tilt_urad"] = when_ok([&] { return py::float_(h.axis_tilt * 1e6); });
  d["from_nominal_axis_um"] = ok && h.nominal_axis_error
                                  ? py::object(py::float_(*h.nominal_axis_error * 1e6))
                                  : py::object(py::none());
  d["U_robot_um"] = when_ok([&] { return py::float_(h.U_robot * 1e6); });
  d["U_mach_um"] = when_ok([&] { return py::float_(h.U_mach * 1e6); });
  d["U_work_um"] = when_ok([&] { return py::float_(h.U_work * 1e6); });
  d["k"] = when_ok([&] { return py::float_(h.k); });
  d["U_work_anisotropic_um"] = when_ok([&] { return py::float_(h.U_work_exact * 1e6); });
  d["budget_um"] = when_ok([&] {
    py::dict b;
    for (const BudgetTerm& t : h.budget) b[t.name] = t.u * 1e6;
    return b;
  });
  d["process_share"] = when_ok([&] { return py::float_(h.process_share); });
  d["process_force_share"] = when_ok([&] { return py::float_(h.process_force_share); });
  d["process_force_N"] = when_ok([&] { return vectorArray(h.force_base); });
  d["equilibrium_converged"] = when_ok([&] { return py::bool_(h.deflection.converged); });
  d["equilibrium_iterations"] = when_ok([&] { return py::int_(h.deflection.iterations); });
  return d;
}

/// One hole of a compensation: the keys of the corrected-target export, flattened.
py::dict compensationDict(const api::CompensationResult& r, size_t i) {
  const HoleCompensation& h = r.holes[i];
  const RobotCard& card = r.context.robot.card;
  const Pose& N = h.ok ? h.T_nominal : r.context.job.requests[i].T_W_tcp;
  py::dict d;
  d["id"] = h.id;
  d["status"] = h.ok ? "compensated" : "original-kept";
  d["reason"] = textOrNone(h.reason);
  d["nominal_pose_mm"] = poseArray(N);
  d["nominal_position_mm"] = vectorArray(N.translation(), 1e3);
  d["nominal_quaternion_wxyz"] = quaternionArray(N.linear());
  d["before_deviation_um"] = vectorArray(h.before.d_work, 1e6);
  d["before_rotation_urad"] = vectorArray(h.before.d_rot, 1e6);
  d["before_verdict"] = verdictName(h.before.verdict);
  auto when_ok = [&](auto&& make) { return h.ok ? py::object(make()) : py::object(py::none()); };
  d["programmed_pose_mm"] = when_ok([&] { return poseArray(h.T_programmed); });
  d["programmed_position_mm"] =
      when_ok([&] { return vectorArray(h.T_programmed.translation(), 1e3); });
  d["programmed_quaternion_wxyz"] =
      when_ok([&] { return quaternionArray(h.T_programmed.linear()); });
  d["joints_deg"] = when_ok([&] { return degreesArray(h.theta_cmd); });
  d["controller_joints_deg"] =
      when_ok([&] { return degreesArray(toControllerJoints(card, h.theta_cmd)); });
  d["config"] = when_ok([&] { return py::str(h.config_text); });
  d["rotation_about_axis_deg"] = when_ok([&] { return py::float_(h.psi / kDeg); });
  const Vec3 a = N.linear().col(2);
  d["residual_um"] =
      when_ok([&] { return py::float_((h.residual - h.residual.dot(a) * a).norm() * 1e6); });
  d["residual_vector_um"] = when_ok([&] { return vectorArray(h.residual, 1e6); });
  d["branch_changed"] = when_ok([&] { return py::bool_(h.branch_changed); });
  d["note"] = textOrNone(h.note);
  const HolePrediction& u = h.ok ? h.after : h.before;
  d["U_robot_um"] = u.U_robot * 1e6;
  d["U_mach_um"] = u.U_mach * 1e6;
  d["U_work_um"] = u.U_work * 1e6;
  d["k"] = u.k;
  d["verdict"] = verdictName(u.verdict);
  return d;
}

// ---------------------------------------------------------------- Session

/// The process a call used (api::ProcessUsed) as a dict in mm, mm/rev and 1/min.
py::dict processDict(const api::ProcessUsed& u) {
  py::dict d;
  d["tool"] = u.tool;
  d["drill"] = u.drill;
  d["diameter_mm"] = u.diameter * 1e3;
  d["depth_mm"] = u.depth * 1e3;
  d["feed_mm_per_rev"] = u.feed * 1e3;
  d["spindle_rpm"] = u.spindle_rpm;
  d["from_cell"] = u.from_cell;
  return d;
}

py::dict filteredDict(const api::Session::Filtered& f) {
  py::dict d;
  d["pose_mm"] = poseArray(f.T_programmed);
  d["joints_deg"] = degreesArray(f.joints_controller);
  d["config"] = f.config;
  d["residual_um"] = f.residual * 1e6;
  d["process"] = processDict(f.process);
  return d;
}

/// A non-negative finite number of a hole dict (mm units), 0 when absent or None.
double processNumber(const py::dict& d, const char* key, double scale) {
  if (!d.contains(key) || d[key].is_none()) return 0.0;
  const double v = d[key].cast<double>();
  if (!std::isfinite(v) || v < 0)
    throw UsageError(std::string("hole ") + key + " must be finite and >= 0 (0: the cell's)");
  return v * scale;
}

/// A hole dict {tool, diameter_mm, depth_mm, feed_mm_per_rev, spindle_rpm} (any subset).
api::HoleProcess holeProcessOf(const py::handle& h) {
  if (h.is_none()) return {};
  if (!py::isinstance<py::dict>(h)) throw UsageError("a hole's process is a dict or None");
  const py::dict d = py::reinterpret_borrow<py::dict>(h);
  for (const auto& item : d) {
    const std::string k = py::str(item.first);
    if (k != "tool" && k != "diameter_mm" && k != "depth_mm" && k != "feed_mm_per_rev" &&
        k != "spindle_rpm")
      throw UsageError("unknown hole key '" + k +
                       "' (tool, diameter_mm, depth_mm, feed_mm_per_rev, spindle_rpm)");
  }
  api::HoleProcess p;
  if (d.contains("tool") && !d["tool"].is_none()) p.tool = py::str(d["tool"]);
  p.diameter = processNumber(d, "diameter_mm", 1e-3);
  p.depth = processNumber(d, "depth_mm", 1e-3);
  p.feed = processNumber(d, "feed_mm_per_rev", 1e-3);
  p.spindle_rpm = processNumber(d, "spindle_rpm", 1.0);
  return p;
}

/// The keyword arguments of one hole's process (None: the cell's).
api::HoleProcess holeProcessArgs(const py::object& tool, const py::object& diameter_mm,
                                 const py::object& depth_mm, const py::object& feed_mm_per_rev,
                                 const py::object& spindle_rpm) {
  py::dict d;
  d["tool"] = tool;
  d["diameter_mm"] = diameter_mm;
  d["depth_mm"] = depth_mm;
  d["feed_mm_per_rev"] = feed_mm_per_rev;
  d["spindle_rpm"] = spindle_rpm;
  return holeProcessOf(d);
}

/// api::Session behind a mutex: one Python Session may be shared by threads (calls on it are
/// serialised); distinct sessions run in parallel with the GIL released.
class PySession {
 public:
  explicit PySession(std::string cell_path) : cell_path_(std::move(cell_path)) {
    py::gil_scoped_release release;
    session_ = std::make_unique<api::Session>(cell_path_);
  }

  py::object filterTarget(const py::handle& pose, const py::handle& seed,
                          const api::HoleProcess& hole, bool details) {
    const Pose T = poseArg(pose, "pose_mm");
    std::optional<Vec6> q;
    if (!seed.is_none()) q = vectorArg<6>(seed, "seed_joints_deg") * kDeg;
    api::Session::Filtered f;
    {
      py::gil_scoped_release release;
      const std::lock_guard<std::mutex> lock(mutex_);
      f = session_->filterTarget(T, q ? &*q : nullptr, hole);
    }
    if (!f.ok) throw ItemFailure("target not filtered: " + f.reason);
    if (!details)
      return py::make_tuple(poseArray(f.T_programmed), degreesArray(f.joints_controller));
    return filteredDict(f);
  }

  py::dict filterTargets(const py::handle& poses, const py::handle& seeds,
                         const py::handle& holes) {
    const Array a = Array::ensure(poses);
    if (!a || a.ndim() != 3 || a.shape(1) != 4 || a.shape(2) != 4)
      throw UsageError("poses_mm: an array of 4x4 poses (N x 4 x 4) is expected");
    const auto n = static_cast<size_t>(a.shape(0));
    std::vector<Pose> T;
    T.reserve(n);
    for (size_t i = 0; i < n; ++i)
      T.push_back(
          host::poseFromRowMajorMm(a.data() + 16 * i, "poses_mm[" + std::to_string(i) + "]"));
    std::vector<Vec6> q;
    if (!seeds.is_none()) {
      const Array s = Array::ensure(seeds);
      if (!s || s.ndim() != 2 || static_cast<size_t>(s.shape(0)) != n || s.shape(1) != 6)
        throw UsageError("seed_joints_deg: None or N x 6 joints (deg) are expected");
      for (size_t i = 0; i < n; ++i)
        q.push_back(host::jointsFromDeg(s.data() + 6 * i, "seed_joints_deg"));
    }
    std::vector<api::HoleProcess> hp;
    if (!holes.is_none()) {
      for (const py::handle h : holes) hp.push_back(holeProcessOf(h));
      if (hp.size() != n) throw UsageError("holes: None or one dict per pose is expected");
    }
    std::vector<api::Session::Filtered> f;
    {
      py::gil_scoped_release release;
      const std::lock_guard<std::mutex> lock(mutex_);
      f = session_->filterTargets(T, q, hp);
    }
    py::array_t<double> out_poses({static_cast<py::ssize_t>(n), py::ssize_t{4}, py::ssize_t{4}});
    py::array_t<double> out_joints({static_cast<py::ssize_t>(n), py::ssize_t{6}});
    py::array_t<bool> ok(static_cast<py::ssize_t>(n));
    py::list reasons;
    py::list process;
    for (size_t i = 0; i < n; ++i) {
      host::poseToRowMajorMm(f[i].ok ? f[i].T_programmed : T[i], out_poses.mutable_data() + 16 * i);
      for (int j = 0; j < 6; ++j)
        out_joints.mutable_data()[6 * i + static_cast<size_t>(j)] =
            f[i].ok ? f[i].joints_controller[j] / kDeg : std::nan("");
      ok.mutable_data()[i] = f[i].ok;
      reasons.append(f[i].ok ? py::object(py::none()) : py::object(py::str(f[i].reason)));
      process.append(processDict(f[i].process));
    }
    py::dict d;
    d["poses_mm"] = out_poses;
    d["joints_deg"] = out_joints;
    d["ok"] = ok;
    d["reasons"] = reasons;
    d["process"] = process;
    return d;
  }

  py::dict predictJoints(const py::handle& joints, const api::HoleProcess& hole) {
    const Vec6 q = vectorArg<6>(joints, "joints_deg") * kDeg;
    api::Session::JointPrediction p;
    {
      py::gil_scoped_release release;
      const std::lock_guard<std::mutex> lock(mutex_);
      p = session_->predictJoints(q, hole);
    }
    if (!p.ok) throw ItemFailure("no prediction at these joints: " + p.reason);
    const HolePrediction& h = p.prediction;
    py::dict d;
    d["deviation_um"] = vectorArray(p.d_translation, 1e6);
    d["rotation_urad"] = vectorArray(p.d_rotation, 1e6);
    d["U_work_um"] = p.U_work * 1e6;
    d["U_robot_um"] = h.U_robot * 1e6;
    d["U_mach_um"] = h.U_mach * 1e6;
    d["k"] = h.k;
    d["work_deviation_um"] = vectorArray(h.d_work, 1e6);
    d["position_error_um"] = h.position_error * 1e6;
    d["axis_tilt_urad"] = h.axis_tilt * 1e6;
    d["tolerance_mm"] = h.tolerance * 1e3;
    d["verdict"] = verdictName(h.verdict);
    d["config"] = h.config;
    d["joints_deg"] = degreesArray(q);
    d["process_force_N"] = vectorArray(h.force_base);
    d["process"] = processDict(p.process);
    return d;
  }

  py::array_t<double> holePose(const py::handle& position, const py::handle& direction) const {
    const Vec3 p = vectorArg<3>(position, "position_mm") * 1e-3;
    const Vec3 dir = vectorArg<3>(direction, "direction");
    if (!(dir.norm() > 1e-9)) throw UsageError("direction: a non-zero vector is expected");
    Pose T_wobj_tcp = Pose::Identity();
    T_wobj_tcp.translation() = p;
    T_wobj_tcp.linear() = api::holeFrame(dir);
    return poseArray(context().cell.T_base_wobj * T_wobj_tcp);
  }

  const api::PredictionContext& context() const { return session_->context(); }
  const std::string& cellPath() const { return cell_path_; }

 private:
  std::string cell_path_;
  std::unique_ptr<api::Session> session_;
  std::mutex mutex_;
};

// ---------------------------------------------------------------- whole jobs

/// The frame and tool resolution of a job (docs/programs.md §15), as the CLI's --frame/--tool.
void applyFrameTool(api::JobOptions& options, const std::optional<std::string>& frame,
                    const std::optional<std::string>& tool) {
  if (frame) api::applyFrameOption(options, *frame);
  if (tool) api::applyToolOption(options, *tool);
}

py::dict predict(const std::string& cell, const std::string& program,
                 const std::optional<std::string>& holes,
                 const std::optional<std::string>& json_out,
                 const std::optional<std::string>& frame, const std::optional<std::string>& tool) {
  api::JobOptions options;
  options.holes = holes;
  applyFrameTool(options, frame, tool);
  std::optional<api::PredictionResult> r;
  std::string summary;
  {
    py::gil_scoped_release release;
    RunScope run;
    r = api::predictJob(cell, program, options);
    summary = host::predictionSummary(*r).dump(0);
    if (json_out) writeFileAtomic(*json_out, api::predictionJson(*r).dump());
    run.commit();
  }
  py::list hs;
  for (size_t i = 0; i < r->holes.size(); ++i)
    hs.append(holeDict(r->holes[i], r->context.job.requests[i], r->context.robot.card));
  py::list notes;
  for (const auto& n : r->context.job.notes) notes.append(n);
  py::dict d;
  d["holes"] = hs;
  d["summary_json"] = summary;
  d["notes"] = notes;
  d["failures"] = host::joinLines(host::predictionFailures(*r, program));
  d["robot"] = r->context.robot.card.name;
  d["cell"] = r->context.cell.name;
  d["process"] = r->context.process_description;
  return d;
}

py::dict compensate(const std::string& cell, const std::string& program, const std::string& out,
                    const std::string& orientation, const std::optional<std::string>& targets,
                    const std::optional<std::string>& holes,
                    const std::optional<std::string>& frame, const std::optional<std::string>& tool,
                    bool force) {
  api::CompensationJob job;
  job.options.mode = host::orientationMode(orientation);
  job.job.holes = holes;
  job.force = force;
  applyFrameTool(job.job, frame, tool);
  const std::string targets_path = targets.value_or("");
  py::dict d;
  std::string problems;
  std::string summary;
  if (api::cellIsMilling(cell)) {
    py::gil_scoped_release release;
    RunScope run;
    api::MillingFilesJob files;
    files.cell = cell;
    files.program = program;
    files.out = out;
    files.targets = targets;
    files.force = force;
    const api::MillingFilesResult r = api::compensateMillingFiles(files);
    problems = host::millingProblems(r);
    summary = host::millingSummary(r).dump(0);
    run.commit();
  } else {
    std::optional<api::CompensationResult> r;
    {
      py::gil_scoped_release release;
      RunScope run;
      r = api::compensateJob(cell, program, job);
      problems = host::compensationProblems(*r, program);
      const bool write = problems.empty();
      summary = host::compensationSummary(
                    *r, write ? host::compensationPaths(r->context, out, targets_path)
                              : std::vector<std::string>{})
                    .dump(0);
      if (write) {
        std::vector<std::pair<std::string, std::string>> extra;
        if (targets)
          extra.emplace_back(*targets,
                             api::compensationTargets(*r, program, host::isCsvPath(*targets)));
        writeAllOrNone([&] { api::writeCompensatedProgram(r->context, out, extra); });
      }
      run.commit();
    }
    py::list results;
    for (size_t i = 0; i < r->holes.size(); ++i) results.append(compensationDict(*r, i));
    d["results"] = results;
  }
  d["summary_json"] = summary;
  d["problems"] = problems;
  return d;
}

py::dict verify(const std::string& cell, const std::optional<std::string>& program,
                const std::optional<std::string>& measured, const std::optional<std::string>& holes,
                const std::string& registration, const std::optional<std::string>& calibrate,
                const std::optional<std::string>& json_out,
                const std::optional<std::string>& write_cell, const std::string& identify,
                const std::optional<std::string>& date, int folds,
                const std::optional<std::string>& poses, const std::optional<double>& u_rot) {
  api::VerifyJob job;
  job.measured = measured.value_or("");
  job.poses = poses.value_or("");
  if (job.measured.empty() && job.poses.empty())
    throw UsageError("give measured and/or poses (tracker poses)");
  if (!job.measured.empty() && !program)
    throw UsageError("program is None (a measured file needs its program)");
  if (u_rot) {
    if (!(*u_rot > 0)) throw UsageError("u_rot must be > 0 µrad");
    job.u_rotation_urad = *u_rot;
  }
  job.job.holes = holes;
  job.registration = host::registration(registration);
  job.calibrate = calibrate.has_value();
  const auto set = identifySetFromName(identify);
  if (!set || *set == IdentifySet::kNone)
    throw UsageError("identify must be stiffness, geometry or all, not '" + identify + "'");
  job.identify = *set;
  if (date) job.date = *date;
  if (folds < 0 || folds > 100) throw UsageError("folds must lie in 0..100");
  job.folds = folds;
  std::string json;
  std::string summary;
  std::string problems;
  {
    py::gil_scoped_release release;
    RunScope run;
    const api::VerifyResult r = api::verifyJob(cell, program.value_or(""), job);
    json = api::verifyJson(r).dump();
    const auto out = host::verifyOutputs(r, job, json_out.value_or(""), calibrate.value_or(""),
                                         write_cell.value_or(""));
    std::vector<std::string> paths;
    paths.reserve(out.size());
    for (const auto& o : out) paths.push_back(o.first);
    if (!r.failed.empty()) {
      problems = host::joinLines(r.failed) + "\nnothing written";
      paths.clear();
    }
    summary = api::verifySummaryJson(r, paths).dump(0);
    if (problems.empty()) {
      writeAllOrNone([&] {
        for (const auto& [path, text] : out) writeFileAtomic(path, text);
      });
    }
    run.commit();
  }
  py::dict d;
  d["json"] = json;
  d["summary_json"] = summary;
  d["problems"] = problems;
  return d;
}

py::dict planTest(const std::string& cell, const std::vector<double>& region, int count,
                  const std::string& out) {
  if (region.size() != 6) throw UsageError("region: give 6 numbers x0 y0 z0 x1 y1 z1 (mm)");
  std::string summary;
  {
    py::gil_scoped_release release;
    RunScope run;
    const api::PlanTestResult r = api::planTestJob(cell, Vec3(region[0], region[1], region[2]),
                                                   Vec3(region[3], region[4], region[5]), count);
    const postproc::DrillProgramText t = api::planTestProgram(r, out);
    summary = api::planTestSummaryJson(r, postproc::drillProgramPaths(t, out)).dump(0);
    postproc::saveDrillProgram(t, out);
    run.commit();
  }
  py::dict d;
  d["summary_json"] = summary;
  return d;
}

void raise(PyObject* cls, const char* what) { PyErr_SetString(cls, what); }

PyObject* newError(py::module_& m, const char* name, const char* doc, PyObject* bases) {
  const std::string qualified = std::string("roprec.") + name;
  PyObject* cls = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases, nullptr);
  if (cls == nullptr) throw py::error_already_set();
  m.add_object(name, py::reinterpret_borrow<py::object>(cls));  // the module keeps a reference too
  return cls;  // the reference PyErr_NewExceptionWithDoc returned is kept for the process
}

}  // namespace
}  // namespace roprec::python

PYBIND11_MODULE(_roprec, m) {
  using namespace roprec::python;  // NOLINT(google-build-using-namespace)
  m.doc() =
      "roprec extension module: use the package `roprec` (roprec/__init__.py), which re-exports "
      "it.";

  ErrorClasses& e = errorClasses();
  e.base =
      newError(m, "RoprecError",
               "Base class of roprec's errors. str(e) is the same text the roprec CLI prints after "
               "'roprec: error: ' (for a bad file: 'FILE:LINE: what is wrong').",
               PyExc_Exception);
  e.input = newError(m, "InputError",
                     "Bad input in a file (cell, program, hole list): 'FILE:LINE: what is wrong'.",
                     e.base);
  {
    py::tuple bases = py::make_tuple(py::handle(e.base), py::handle(PyExc_ValueError));
    e.usage = newError(m, "UsageError",
                       "A bad argument (wrong shape, not finite, non-rigid pose, unknown option). "
                       "Also a ValueError.",
                       bases.ptr());
  }
  e.item = newError(
      m, "ItemError",
      "A target or hole that could not be handled (unreachable, singular, not converged), or a "
      "compensation that was not written because some holes failed.",
      e.base);
  // pybind11 takes a plain function pointer, void(*)(std::exception_ptr)
  // NOLINTNEXTLINE(performance-unnecessary-value-param)
  py::register_exception_translator([](std::exception_ptr p) {
    const ErrorClasses& c = errorClasses();
    try {
      if (p) std::rethrow_exception(p);
    } catch (const py::error_already_set&) {
      throw;
    } catch (const py::builtin_exception&) {
      throw;
    } catch (const roprec::InputError& x) {
      raise(c.input, x.what());
    } catch (const roprec::UsageError& x) {
      raise(c.usage, x.what());
    } catch (const ItemFailure& x) {
      raise(c.item, x.what());
    } catch (const std::bad_alloc&) {
      throw;  // MemoryError
    } catch (const std::exception& x) {
      raise(c.base, (std::string("internal error: ") + x.what()).c_str());
    }
  });

  m.def(
      "version", [] { return std::string(roprec::api::version()); },
      "The library version, e.g. '0.2.0'.");

  py::class_<PySession>(
      m, "Session",
      "A cell loaded once for per-target calls (the RoboDK FilterTarget analogue).\n\n"
      "Session(cell_path) loads the cell XML (robot, tool, workobject, process, controller);\n"
      "raises roprec.InputError for a bad cell. Poses are 4x4 arrays in mm: the TCP\n"
      "(flange x the cell's tool) in the robot base frame. Joints are in the controller's\n"
      "convention, degrees. A session may be shared by threads (its calls are serialised);\n"
      "distinct sessions run in parallel (the GIL is released while computing).")
      .def(py::init([](const py::object& path) {
             // str or os.PathLike (pathlib.Path)
             return std::make_unique<PySession>(
                 py::str(py::module_::import("os").attr("fspath")(path)));
           }),
           py::arg("cell_path"))
      .def(
          "filter_target",
          [](PySession& s, const py::handle& pose, const py::handle& seed, const py::object& tool,
             const py::object& diameter, const py::object& depth, const py::object& feed,
             const py::object& rpm, bool details) {
            return s.filterTarget(pose, seed, holeProcessArgs(tool, diameter, depth, feed, rpm),
                                  details);
          },
          py::arg("pose_mm"), py::arg("seed_joints_deg") = py::none(), py::kw_only(),
          py::arg("tool") = py::none(), py::arg("diameter_mm") = py::none(),
          py::arg("depth_mm") = py::none(), py::arg("feed_mm_per_rev") = py::none(),
          py::arg("spindle_rpm") = py::none(), py::arg("details") = false,
          "filter_target(pose_mm, seed_joints_deg=None, *, tool=None, diameter_mm=None,\n"
          "              depth_mm=None, feed_mm_per_rev=None, spindle_rpm=None, details=False)\n"
          "    -> (pose_mm, joints_deg)\n\n"
          "The pose to program (4x4, mm, base frame) and its joints (6, controller convention,\n"
          "deg) so that the predicted real TCP lands on `pose_mm` under the cell's gravity, tool\n"
          "weight and the hole's process load. Orientation is kept: only the position is\n"
          "pre-offset. seed_joints_deg: joints whose IK branch/turns to keep (the nearest\n"
          "solution is taken); None: the robot's reference pose. The hole's process: tool (the\n"
          "controller's tool number or name in the cell's tool table), diameter_mm, depth_mm,\n"
          "feed_mm_per_rev, spindle_rpm; None: the cell's. details=True returns a dict instead:\n"
          "pose_mm, joints_deg, config, residual_um and process (the values used: tool, drill,\n"
          "diameter_mm, depth_mm, feed_mm_per_rev, spindle_rpm, from_cell). Raises\n"
          "roprec.ItemError when the target cannot be filtered (unreachable, singular),\n"
          "roprec.UsageError for a non-rigid pose, roprec.InputError for a tool the cell does\n"
          "not have.")
      .def("filter_targets", &PySession::filterTargets, py::arg("poses_mm"),
           py::arg("seed_joints_deg") = py::none(), py::arg("holes") = py::none(),
           "filter_targets(poses_mm, seed_joints_deg=None, holes=None) -> dict\n\n"
           "filter_target over a program's targets in order (RoboDK's FilterProgram): poses_mm\n"
           "N x 4 x 4; seed_joints_deg None (each target seeded with the previous target's IK\n"
           "choice, as roprec compensate) or N x 6; holes None or one dict per target with any of\n"
           "tool, diameter_mm, depth_mm, feed_mm_per_rev, spindle_rpm. Keys: poses_mm (N x 4 x\n"
           "4; a target not filtered keeps its pose), joints_deg (N x 6; NaN where not\n"
           "filtered), ok (N bools), reasons (None or why not, per target), process (the values\n"
           "used, per target).")
      .def(
          "predict_joints",
          [](PySession& s, const py::handle& joints, const py::object& tool,
             const py::object& diameter, const py::object& depth, const py::object& feed,
             const py::object& rpm) {
            return s.predictJoints(joints, holeProcessArgs(tool, diameter, depth, feed, rpm));
          },
          py::arg("joints_deg"), py::kw_only(), py::arg("tool") = py::none(),
          py::arg("diameter_mm") = py::none(), py::arg("depth_mm") = py::none(),
          py::arg("feed_mm_per_rev") = py::none(), py::arg("spindle_rpm") = py::none(),
          "predict_joints(joints_deg, *, tool=None, diameter_mm=None, depth_mm=None,\n"
          "               feed_mm_per_rev=None, spindle_rpm=None) -> dict\n\n"
          "The predicted TCP deviation when the robot is commanded to `joints_deg` (controller\n"
          "convention, deg) under the cell's loads. Keys: deviation_um (real - commanded TCP\n"
          "position, base frame, 3), rotation_urad (rotation vector, base frame, 3), U_work_um\n"
          "(expanded 95 % uncertainty of a hole there), U_robot_um, U_mach_um, k,\n"
          "work_deviation_um (deviation_um + the machining deviation), position_error_um and\n"
          "axis_tilt_urad (w.r.t. the commanded TCP z axis), tolerance_mm, verdict, config,\n"
          "joints_deg, process_force_N, process (the hole's process used, as filter_target's).\n"
          "The hole's process as for filter_target. Raises roprec.ItemError when no prediction\n"
          "exists, roprec.InputError for joints outside the limits.")
      .def(
          "hole_pose", &PySession::holePose, py::arg("position_mm"), py::arg("direction"),
          "hole_pose(position_mm, direction) -> pose_mm\n\n"
          "The TCP pose (4x4, mm, base frame) roprec uses for a hole-list row: the hole at\n"
          "`position_mm` in the cell's workobject frame, drilled along `direction` (TCP z); TCP x\n"
          "is the workobject x axis projected perpendicular to z (the y axis when the direction "
          "is\n"
          "within 26 deg of x).")
      .def_property_readonly("cell_path", &PySession::cellPath,
                             "The cell file this session was loaded from.")
      .def_property_readonly(
          "cell", [](const PySession& s) { return s.context().cell.name; }, "The cell's name.")
      .def_property_readonly(
          "robot", [](const PySession& s) { return s.context().robot.card.name; },
          "The robot card's name.")
      .def_property_readonly(
          "tool_pose_mm",
          [](const PySession& s) { return poseArray(s.context().tool.T_flange_tcp); },
          "The TCP in the flange frame (4x4, mm): the cell's <tool>.")
      .def_property_readonly(
          "workobject_pose_mm",
          [](const PySession& s) { return poseArray(s.context().cell.T_base_wobj); },
          "The cell's workobject frame in the robot base frame (4x4, mm).")
      .def_property_readonly(
          "process", [](const PySession& s) { return s.context().process_description; },
          "The cell's process, as the prediction JSON describes it.");

  m.def("_predict", &predict, py::arg("cell"), py::arg("program"), py::arg("holes") = py::none(),
        py::arg("json_out") = py::none(), py::arg("frame") = py::none(),
        py::arg("tool") = py::none(), "Internal: see roprec.predict.");
  m.def("_compensate", &compensate, py::arg("cell"), py::arg("program"), py::arg("out"),
        py::arg("orientation"), py::arg("targets") = py::none(), py::arg("holes") = py::none(),
        py::arg("frame") = py::none(), py::arg("tool") = py::none(), py::arg("force") = false,
        "Internal: see roprec.compensate.");
  m.def("_verify", &verify, py::arg("cell"), py::arg("program"), py::arg("measured"),
        py::arg("holes") = py::none(), py::arg("register") = "none",
        py::arg("calibrate") = py::none(), py::arg("json_out") = py::none(),
        py::arg("write_cell") = py::none(), py::arg("identify") = "all",
        py::arg("date") = py::none(), py::arg("folds") = 5, py::arg("poses") = py::none(),
        py::arg("u_rot") = py::none(), "Internal: see roprec.verify.");
  m.def("_plan_test", &planTest, py::arg("cell"), py::arg("region"), py::arg("count"),
        py::arg("out"), "Internal: see roprec.plan_test.");
}
