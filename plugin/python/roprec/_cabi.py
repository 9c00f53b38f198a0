"""roprec over its C ABI (roprec.h) through ctypes: the stand-in for the compiled module ``_roprec``.

Pure Python (any CPython >= 3.7, numpy optional): used where no ``_roprec`` extension was built for
the interpreter — RoboDK's embedded Python on Windows, or with ROPREC_PYTHON_BACKEND=ctypes. It
loads ``roprec_c.dll`` / ``libroprec_c.so`` (found as :func:`library_candidates` says) and gives the
same names as ``_roprec``: the exceptions, ``version``, ``Session`` and the whole-job calls.
The Session calls take the hole's process as ``_roprec`` does and give its dicts value for value
(the C library's JSON answers print every number as the shortest text of the same double).
Differences: the per-hole dicts of ``predict``/``compensate`` come from the JSON documents, so their
numbers carry the JSON's rounding; ``compensate`` gives ``results`` only when ``targets`` is a JSON
export.
"""

import ctypes
import json
import math
import ntpath
import os
import posixpath
import re
import sys
import tempfile
import threading

try:
    import numpy as _np
except ImportError:  # numpy is optional: poses and vectors are then nested lists
    _np = None


class RoprecError(Exception):
    """Base class of roprec's errors. str(e) is the text the roprec CLI prints after 'roprec: error: '."""


class InputError(RoprecError):
    """Bad input in a file (cell, program, hole list): 'FILE:LINE: what is wrong'."""


class UsageError(RoprecError, ValueError):
    """A bad argument (wrong shape, not finite, non-rigid pose, unknown option). Also a ValueError."""


class ItemError(RoprecError):
    """A target or hole that could not be handled (unreachable, singular, not converged)."""


_LEN = 1 << 16
_ERROR_ITEM, _ERROR_INPUT, _ERROR_USAGE, _ERROR_MEMORY = 1, 2, 3, 4


def library_candidates(env=None, package_dir=None, platform=None):
    """Where roprec_c is looked for, in order: $ROPREC_C_LIB; beside this package; the install
    layout's bin/ (Windows) or lib/ (Linux) above it; then the bare name (the system's search).
    `platform` (default sys.platform) also chooses the path syntax (ntpath on Windows)."""
    env = os.environ if env is None else env
    package_dir = os.path.dirname(os.path.abspath(__file__)) if package_dir is None else package_dir
    windows = (sys.platform if platform is None else platform).startswith("win")
    path = ntpath if windows else posixpath  # os.path on the system itself
    names = ["roprec_c.dll"] if windows else ["libroprec_c.so.0", "libroprec_c.so"]
    found = []
    if env.get("ROPREC_C_LIB"):
        found.append(env["ROPREC_C_LIB"])
    up = package_dir
    for depth in range(5):  # <prefix>/python/roprec, <prefix>/lib/python3/dist-packages/roprec
        for sub in ([""] if depth == 0 else (["bin", ""] if windows else ["lib", ""])):
            for n in names:
                found.append(path.join(up, sub, n) if sub else path.join(up, n))
        up = path.dirname(up)
    found.extend(names)
    seen = []
    for f in found:
        if f not in seen:
            seen.append(f)
    return seen


def _load(candidates=None, system=os, cdll=ctypes.CDLL):
    """The first of `candidates` (default :func:`library_candidates`) that exists and loads. A path
    (one with a separator) that does not exist is skipped; a bare name is left to the system's
    search. On Windows (system.name "nt") the folder of an absolute path is first made a place
    where the DLLs it needs (roprec.dll, the GCC runtime, beside it) are found:
    os.add_dll_directory on Python >= 3.8, else (3.7: RoboDK's older builds) the front of PATH.
    `system` and `cdll` are the os module and ctypes.CDLL, replaced by the tests."""
    candidates = library_candidates() if candidates is None else candidates
    errors = []
    for path in candidates:
        if system.path.sep in path and not system.path.exists(path):
            continue
        try:
            if system.name == "nt" and system.path.isabs(path):
                folder = system.path.dirname(path)
                if hasattr(system, "add_dll_directory"):
                    _dll_directories.append(system.add_dll_directory(folder))
                else:
                    system.environ["PATH"] = folder + system.pathsep + system.environ.get("PATH", "")
            return cdll(path)
        except OSError as e:
            errors.append("%s: %s" % (path, e))
    raise ImportError("roprec: the C library roprec_c was not found (set ROPREC_C_LIB): " + "; ".join(errors))


_dll_directories = []  # the handles of os.add_dll_directory, kept for the process's lifetime


class _HoleProcess(ctypes.Structure):
    """roprec_hole_process (roprec.h): the hole's process, mm; 0 / NULL: the cell's."""
    _fields_ = [("tool", ctypes.c_char_p), ("diameter_mm", ctypes.c_double), ("depth_mm", ctypes.c_double),
                ("feed_mm_per_rev", ctypes.c_double), ("spindle_rpm", ctypes.c_double)]


_lib = _load()
_D = ctypes.POINTER(ctypes.c_double)
_P, _S, _I, _V = ctypes.c_char_p, ctypes.c_size_t, ctypes.c_int, ctypes.c_void_p
_H = ctypes.POINTER(_HoleProcess)
for _name, _args in {
    "roprec_open": [_P, ctypes.POINTER(_V), _P, _S],
    "roprec_filter_target": [_V, _D, _D, _D, _D, _P, _S],
    "roprec_predict_joints_json": [_V, _D, _P, _S, _P, _S],
    "roprec_filter_target_hole": [_V, _D, _D, _H, _D, _D, _V, _P, _S],
    "roprec_predict_joints_hole_json": [_V, _D, _H, _P, _S, _P, _S],
    "roprec_filter_target_hole_json": [_V, _D, _D, _H, _P, _S, _P, _S],
    "roprec_filter_targets_json": [_V, _S, _D, _D, _H, _P, _S, _P, _S],
    "roprec_session_info": [_V, _P, _S, _P, _S],
    "roprec_options_new": [ctypes.POINTER(_V), _P, _S],
    "roprec_options_set": [_V, _P, _P, _P, _S],
    "roprec_predict_file_ex": [_P, _P, _V, _P, _P, _S, _P, _S],
    "roprec_compensate_file_ex": [_P, _P, _V, _P, _P, _P, _S, _P, _S],
    "roprec_verify_file_ex": [_P, _P, _P, _P, _V, _P, _P, _P, _S, _P, _S],
    "roprec_plan_test_file": [_P, _D, _I, _P, _P, _S, _P, _S],
}.items():
    getattr(_lib, _name).argtypes = _args
    getattr(_lib, _name).restype = _I
_lib.roprec_close.argtypes = [_V]
_lib.roprec_options_free.argtypes = [_V]
_lib.roprec_version.restype = _P
_lib.roprec_error_kind.restype = _I


def version():
    """The library version, e.g. '0.2.0'."""
    return _lib.roprec_version().decode()


def _b(s):
    return None if s is None else os.fspath(s).encode("utf-8")


def _raise(rc, err):
    """The exception of a failed call (rc != 0), by the kind the library reports."""
    text = err.value.decode("utf-8", "replace")
    kind = _lib.roprec_error_kind()
    if kind == _ERROR_ITEM:
        raise ItemError(text)
    if kind == _ERROR_INPUT:
        raise InputError(text)
    if kind == _ERROR_USAGE:
        raise UsageError(text)
    if kind == _ERROR_MEMORY:
        raise MemoryError(text)
    raise RoprecError(text)


_NEEDED = re.compile(r"^json: the buffer holds \d+ bytes, (\d+) are needed")


def _call(f, *args, item_ok=False, size=_LEN):
    """Calls f(*args, out, size, err, size); returns (rc, out text, err text). A JSON answer larger
    than `size` is asked for once more with the size the library states."""
    out, err = ctypes.create_string_buffer(size), ctypes.create_string_buffer(_LEN)
    rc = f(*(args + (out, size, err, _LEN)))
    needed = _NEEDED.match(err.value.decode("utf-8", "replace")) if rc == 2 else None
    if needed and _lib.roprec_error_kind() == _ERROR_USAGE:
        size = int(needed.group(1))
        out = ctypes.create_string_buffer(size)
        rc = f(*(args + (out, size, err, _LEN)))
    if rc != 0 and not (item_ok and rc == 1):
        _raise(rc, err)
    return rc, out.value.decode("utf-8"), err.value.decode("utf-8", "replace")


def _numbers(x, n, name):
    if _np is not None:  # one conversion, no per-element Python work
        try:
            a = _np.ascontiguousarray(x, dtype=float).reshape(-1)
        except (TypeError, ValueError):
            raise UsageError("%s: %d numbers are expected" % (name, n))
        if a.size != n:
            raise UsageError("%s: %d numbers are expected" % (name, n))
        return a.ctypes.data_as(_D), a  # the array keeps the memory alive
    try:
        flat = [float(v) for row in x for v in (row if hasattr(row, "__iter__") else [row])]
    except TypeError:
        raise UsageError("%s: %d numbers are expected" % (name, n))
    if len(flat) != n:
        raise UsageError("%s: %d numbers are expected" % (name, n))
    return (ctypes.c_double * n)(*flat), None


def _array(values, shape=None):
    if _np is None:
        v = list(values)
        return [v[i * 4:(i + 1) * 4] for i in range(4)] if shape == (4, 4) else v
    a = _np.array(values, dtype=float)
    return a.reshape(shape) if shape else a


def _mat_mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


_PROCESS_KEYS = ("tool", "diameter_mm", "depth_mm", "feed_mm_per_rev", "spindle_rpm")


def _process_number(d, key):
    """A non-negative finite number of a hole dict (mm units), 0 when absent or None."""
    v = d.get(key)
    if v is None:
        return 0.0
    try:
        v = float(v)
    except (TypeError, ValueError):
        raise UsageError("hole %s must be a number" % key)
    if not math.isfinite(v) or v < 0:
        raise UsageError("hole %s must be finite and >= 0 (0: the cell's)" % key)
    return v


def _hole_process(d):
    """A hole dict {tool, diameter_mm, depth_mm, feed_mm_per_rev, spindle_rpm} (any subset; None:
    the cell's) as roprec_hole_process, or None when it gives nothing."""
    if d is None:
        return None
    if not isinstance(d, dict):
        raise UsageError("a hole's process is a dict or None")
    for k in d:
        if k not in _PROCESS_KEYS:
            raise UsageError("unknown hole key '%s' (%s)" % (k, ", ".join(_PROCESS_KEYS)))
    tool = d.get("tool")
    return _HoleProcess(None if tool is None else str(tool).encode("utf-8"), _process_number(d, "diameter_mm"),
                        _process_number(d, "depth_mm"), _process_number(d, "feed_mm_per_rev"),
                        _process_number(d, "spindle_rpm"))


def _process_args(tool, diameter_mm, depth_mm, feed_mm_per_rev, spindle_rpm):
    """The keyword arguments of one hole's process as roprec_hole_process (None: the cell's)."""
    return _hole_process({"tool": tool, "diameter_mm": diameter_mm, "depth_mm": depth_mm,
                          "feed_mm_per_rev": feed_mm_per_rev, "spindle_rpm": spindle_rpm})


def _floats(text):
    """A Session call's JSON answer: every number is a double (the JSON prints 20.0 as 20)."""
    return json.loads(text, parse_int=float)


def _ref(hole):
    return None if hole is None else ctypes.byref(hole)


def _arrays(d, shapes):
    """The lists of a JSON answer as arrays: `shapes` names the reshaped ones, the rest stay 1-D."""
    for k, v in d.items():
        if isinstance(v, list) and v and not isinstance(v[0], (dict, str, bool)) and v[0] is not None:
            d[k] = _array(v, shapes.get(k))
    return d


def _hole_frame(d):
    """The hole's TCP rotation (columns x, y, z) for drilling direction d (plugin/api holeFrame)."""
    n = sum(v * v for v in d) ** 0.5
    z = [v / n for v in d]
    ref = [1.0, 0.0, 0.0] if abs(z[0]) < 0.9 else [0.0, 1.0, 0.0]
    y = [z[1] * ref[2] - z[2] * ref[1], z[2] * ref[0] - z[0] * ref[2], z[0] * ref[1] - z[1] * ref[0]]
    m = sum(v * v for v in y) ** 0.5
    y = [v / m for v in y]
    x = [y[1] * z[2] - y[2] * z[1], y[2] * z[0] - y[0] * z[2], y[0] * z[1] - y[1] * z[0]]
    return [[x[i], y[i], z[i]] for i in range(3)]


class Session(object):
    """A cell loaded once for per-target calls (the RoboDK FilterTarget analogue); see roprec.Session.
    One Session may be shared by threads: its calls on the C session are serialised (roprec.h asks
    it of the caller; ctypes releases the GIL during a foreign call)."""

    def __init__(self, cell_path):
        self._lock = threading.Lock()
        self._s = _V()
        err = ctypes.create_string_buffer(_LEN)
        rc = _lib.roprec_open(_b(cell_path), ctypes.byref(self._s), err, _LEN)
        if rc:
            _raise(rc, err)
        self._info = json.loads(_call(_lib.roprec_session_info, self._s)[1])

    def __del__(self):
        if getattr(self, "_s", None):
            _lib.roprec_close(self._s)
            self._s = None

    def filter_target(self, pose_mm, seed_joints_deg=None, *, tool=None, diameter_mm=None, depth_mm=None,
                      feed_mm_per_rev=None, spindle_rpm=None, details=False):
        """(pose_mm, joints_deg): the pose to program and its joints, drilling with the hole's
        process (None: the cell's); details=True: a dict (pose_mm, joints_deg, config, residual_um,
        process). See roprec.Session."""
        hole = _process_args(tool, diameter_mm, depth_mm, feed_mm_per_rev, spindle_rpm)
        pose, keep = _numbers(pose_mm, 16, "pose_mm")
        seed, keep_seed = (None, None) if seed_joints_deg is None else _numbers(seed_joints_deg, 6, "seed_joints_deg")
        if details:
            with self._lock:
                text = _call(_lib.roprec_filter_target_hole_json, self._s, pose, seed, _ref(hole), size=8192)[1]
            return _arrays(_floats(text), {"pose_mm": (4, 4)})
        err = ctypes.create_string_buffer(1024)
        if _np is not None:
            out, joints = _np.empty((4, 4)), _np.empty(6)
            with self._lock:
                rc = _lib.roprec_filter_target_hole(self._s, pose, seed, _ref(hole), out.ctypes.data_as(_D),
                                                    joints.ctypes.data_as(_D), None, err, 1024)
        else:
            out, joints = (ctypes.c_double * 16)(), (ctypes.c_double * 6)()
            with self._lock:
                rc = _lib.roprec_filter_target_hole(self._s, pose, seed, _ref(hole), out, joints, None, err, 1024)
            out, joints = _array(out[:], (4, 4)), _array(joints[:])
        if rc:
            _raise(rc, err)
        return out, joints

    def filter_targets(self, poses_mm, seed_joints_deg=None, holes=None):
        """filter_target over a program's targets in order (RoboDK's FilterProgram): a dict with
        poses_mm (N x 4 x 4), joints_deg (N x 6, NaN where not filtered), ok, reasons and process
        (per target). See roprec.Session."""
        try:
            n = len(poses_mm)
        except TypeError:
            n = -1
        if n < 0 or (_np is not None and _np.ndim(poses_mm) != 3):
            raise UsageError("poses_mm: an array of 4x4 poses (N x 4 x 4) is expected")
        try:
            poses, keep = _numbers([v for p in poses_mm for row in p for v in row], 16 * n, "poses_mm")
        except (TypeError, UsageError):
            raise UsageError("poses_mm: an array of 4x4 poses (N x 4 x 4) is expected")
        seeds, keep_seeds = None, None
        if seed_joints_deg is not None:
            try:
                if len(seed_joints_deg) != n:
                    raise TypeError
                seeds, keep_seeds = _numbers([v for q in seed_joints_deg for v in q], 6 * n, "seed_joints_deg")
            except (TypeError, UsageError):
                raise UsageError("seed_joints_deg: None or N x 6 joints (deg) are expected")
        processes = None
        if holes is not None:
            given = [_hole_process(h) or _HoleProcess(None, 0.0, 0.0, 0.0, 0.0) for h in holes]
            if len(given) != n:
                raise UsageError("holes: None or one dict per pose is expected")
            processes = (_HoleProcess * n)(*given)
        with self._lock:
            rc, text, err = _call(_lib.roprec_filter_targets_json, self._s, n, poses, seeds, processes,
                                  item_ok=True, size=4096 + 2048 * n)
        d = _floats(text)
        nan = float("nan")
        joints = [[nan] * 6 if q is None else q for q in d["joints_deg"]]
        d["poses_mm"] = _array([v for p in d["poses_mm"] for v in p], (n, 4, 4)) if _np is not None else \
            [_array(p, (4, 4)) for p in d["poses_mm"]]
        d["joints_deg"] = _array([v for q in joints for v in q], (n, 6)) if _np is not None else joints
        d["ok"] = _np.array(d["ok"], dtype=bool) if _np is not None else d["ok"]
        return d

    def predict_joints(self, joints_deg, *, tool=None, diameter_mm=None, depth_mm=None, feed_mm_per_rev=None,
                       spindle_rpm=None):
        """The predicted TCP deviation at these joints drilling with the hole's process (None: the
        cell's), a dict; see roprec.Session."""
        hole = _process_args(tool, diameter_mm, depth_mm, feed_mm_per_rev, spindle_rpm)
        joints = _numbers(joints_deg, 6, "joints_deg")[0]
        with self._lock:
            text = _call(_lib.roprec_predict_joints_hole_json, self._s, joints, _ref(hole), size=8192)[1]
        return _arrays(_floats(text), {})

    def hole_pose(self, position_mm, direction):
        """The TCP pose roprec uses for a hole-list row (workobject frame); see roprec.Session."""
        p = [float(v) for v in _numbers(position_mm, 3, "position_mm")[0][:3]]
        d = [float(v) for v in _numbers(direction, 3, "direction")[0][:3]]
        if not sum(v * v for v in d) ** 0.5 > 1e-9:
            raise UsageError("direction: a non-zero vector is expected")
        R = _hole_frame(d)
        T = [R[0] + [p[0]], R[1] + [p[1]], R[2] + [p[2]], [0.0, 0.0, 0.0, 1.0]]
        w = self._info["workobject_pose_mm"]
        W = [w[i * 4:(i + 1) * 4] for i in range(4)]
        return _array([v for row in _mat_mul(W, T) for v in row], (4, 4))

    cell_path = property(lambda self: self._info["cell_path"], doc="The cell file this session was loaded from.")
    cell = property(lambda self: self._info["cell"], doc="The cell's name.")
    robot = property(lambda self: self._info["robot"], doc="The robot card's name.")
    process = property(lambda self: self._info["process"], doc="The cell's process.")
    tool_pose_mm = property(lambda self: _array(self._info["tool_pose_mm"], (4, 4)),
                            doc="The TCP in the flange frame (4x4, mm): the cell's <tool>.")
    workobject_pose_mm = property(lambda self: _array(self._info["workobject_pose_mm"], (4, 4)),
                                  doc="The cell's workobject frame in the robot base frame (4x4, mm).")


class _Options(object):
    def __init__(self, **values):
        self.o = _V()
        err = ctypes.create_string_buffer(_LEN)
        if _lib.roprec_options_new(ctypes.byref(self.o), err, _LEN):
            _raise(2, err)
        for key, value in values.items():
            if value is not None:
                rc = _lib.roprec_options_set(self.o, key.encode(), str(value).encode("utf-8"), err, _LEN)
                if rc:
                    _raise(rc, err)

    def __enter__(self):
        return self.o

    def __exit__(self, *exc):
        _lib.roprec_options_free(self.o)


def _dig(tree, dotted):
    for key in dotted.split("."):
        if not isinstance(tree, dict) or key not in tree:
            return None
        tree = tree[key]
    return _array(tree) if isinstance(tree, list) else tree


def _pose(position, quaternion):
    w, x, y, z = quaternion
    R = [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
         [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
         [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]
    return _array([v for i in range(3) for v in R[i] + [position[i]]] + [0.0, 0.0, 0.0, 1.0], (4, 4))


_HOLE_KEYS = {
    "id": "id", "line": "line", "verdict": "verdict", "reason": "reason",
    "nominal_position_mm": "nominal.position_mm", "nominal_quaternion_wxyz": "nominal.quaternion_wxyz",
    "axis": "nominal.axis", "diameter_mm": "diameter_mm", "depth_mm": "depth_mm", "tolerance_mm": "tolerance_mm",
    "mc_time_s": "mc_time_s", "joints_deg": "joints_deg", "controller_joints_deg": "controller_joints_deg",
    "config": "config", "branch": "branch", "deviation_um": "deviation_um.work",
    "robot_deviation_um": "deviation_um.robot", "mach_deviation_um": "deviation_um.mach",
    "rotation_urad": "deviation_um.robot_rotation_urad", "work_tool_xy_um": "deviation_um.work_tool_xy",
    "position_error_um": "deviation_um.position_error", "axis_tilt_urad": "deviation_um.axis_tilt_urad",
    "from_nominal_axis_um": "deviation_um.from_nominal_axis", "U_robot_um": "uncertainty_um.U_robot",
    "U_mach_um": "uncertainty_um.U_mach", "U_work_um": "uncertainty_um.U_work", "k": "uncertainty_um.k",
    "U_work_anisotropic_um": "uncertainty_um.U_work_anisotropic", "budget_um": "uncertainty_um.standard_per_axis",
    "process_share": "uncertainty_um.process_share", "process_force_share": "uncertainty_um.process_force_share",
    "process_force_N": "process_force_N", "equilibrium_converged": "equilibrium.converged",
    "equilibrium_iterations": "equilibrium.iterations",
    "drill_tool": "drill.tool", "feed_mm_per_rev": "drill.feed_mm_per_rev", "spindle_rpm": "drill.spindle_rpm",
}
_FAILED = ("unreachable", "singular", "not-converged")


def _hole(j):
    d = {k: _dig(j, path) for k, path in _HOLE_KEYS.items()}
    d["status"] = d["verdict"] if d["verdict"] in _FAILED else "ok"
    d["nominal_pose_mm"] = _pose(j["nominal"]["position_mm"], j["nominal"]["quaternion_wxyz"])
    return d


def _predict(cell, program, holes=None, json_out=None, frame=None, tool=None):
    with _Options(holes=holes, frame=frame, tool=tool) as o:
        tmp = None
        if json_out is None:
            fd, tmp = tempfile.mkstemp(suffix=".json", prefix="roprec-")
            os.close(fd)
        try:
            rc, summary, err = _call(_lib.roprec_predict_file_ex, _b(cell), _b(program), o,
                                     _b(json_out if tmp is None else tmp), item_ok=True)
            with open(json_out if tmp is None else tmp, encoding="utf-8") as f:
                doc = json.load(f)
        finally:
            if tmp is not None:
                os.remove(tmp)
    return {"holes": [_hole(h) for h in doc["holes"]], "summary_json": summary, "notes": doc.get("notes", []),
            "failures": err if rc == 1 else "", "robot": doc["robot"], "cell": doc["cell"],
            "process": doc.get("process", "")}


def _compensate(cell, program, out, orientation, targets=None, holes=None, frame=None, tool=None, force=False):
    with _Options(holes=holes, frame=frame, tool=tool, orientation=orientation, force="1" if force else None) as o:
        rc, summary, err = _call(_lib.roprec_compensate_file_ex, _b(cell), _b(program), o, _b(out), _b(targets),
                                 item_ok=True)
    r = {"summary_json": summary if rc == 0 else json.dumps({"written": []}), "problems": err if rc == 1 else ""}
    if rc == 0 and targets is not None and not str(targets).lower().endswith(".csv"):
        with open(targets, encoding="utf-8") as f:
            doc = json.load(f)
        if "holes" in doc:
            r["results"] = [_compensation(h) for h in doc["holes"]]
    return r


def _compensation(j):
    keys = {
        "id": "id", "status": "status", "reason": "reason", "nominal_position_mm": "nominal.position_mm",
        "nominal_quaternion_wxyz": "nominal.quaternion_wxyz", "before_deviation_um": "before.deviation_um.translation",
        "before_rotation_urad": "before.deviation_um.rotation_urad", "before_verdict": "before.verdict",
        "programmed_position_mm": "programmed.position_mm", "programmed_quaternion_wxyz": "programmed.quaternion_wxyz",
        "joints_deg": "programmed.joints_deg", "controller_joints_deg": "programmed.controller_joints_deg",
        "config": "programmed.config", "rotation_about_axis_deg": "rotation_about_axis_deg",
        "residual_um": "residual_um", "residual_vector_um": "residual_vector_um", "branch_changed": "branch_changed",
        "note": "note", "U_robot_um": "uncertainty_um.U_robot", "U_mach_um": "uncertainty_um.U_mach",
        "U_work_um": "uncertainty_um.U_work", "k": "uncertainty_um.k", "verdict": "verdict",
    }
    d = {k: _dig(j, path) for k, path in keys.items()}
    d["nominal_pose_mm"] = _pose(j["nominal"]["position_mm"], j["nominal"]["quaternion_wxyz"])
    p = j.get("programmed")
    d["programmed_pose_mm"] = _pose(p["position_mm"], p["quaternion_wxyz"]) if p else None
    return d


def _verify(cell, program, measured, holes=None, register="none", calibrate=None, json_out=None, write_cell=None,
            identify="all", date=None, folds=5, poses=None, u_rot=None):
    with _Options(holes=holes, write_cell=write_cell, identify=identify, date=date, folds=int(folds), poses=poses,
                  u_rot=None if u_rot is None else repr(float(u_rot))) as o:
        tmp = None
        if json_out is None:
            fd, tmp = tempfile.mkstemp(suffix=".json", prefix="roprec-")
            os.close(fd)
        try:
            rc, summary, err = _call(_lib.roprec_verify_file_ex, _b(cell), _b(program), _b(measured),
                                     _b(register), o, _b(json_out if tmp is None else tmp), _b(calibrate),
                                     item_ok=True)
            text = ""
            if rc == 0:
                with open(json_out if tmp is None else tmp, encoding="utf-8") as f:
                    text = f.read()
        finally:
            if tmp is not None and os.path.exists(tmp):
                os.remove(tmp)
    if rc == 0 and tmp is not None:  # the temporary document is not one of the caller's outputs
        s = json.loads(summary)
        s["written"] = [w for w in s.get("written", []) if os.path.abspath(w) != os.path.abspath(tmp)]
        summary = json.dumps(s)
    return {"json": text or "{}", "summary_json": summary or json.dumps({"written": []}),
            "problems": err if rc == 1 else ""}


def _plan_test(cell, region, count, out):
    if len(region) != 6:
        raise UsageError("region: give 6 numbers x0 y0 z0 x1 y1 z1 (mm)")
    return {"summary_json": _call(_lib.roprec_plan_test_file, _b(cell), (ctypes.c_double * 6)(*region), int(count),
                                  _b(out))[1]}
