"""The Python module `roprec` against the CLI and the C ABI (through ctypes) on the sample job:
predict and compensate keep give the same numbers (the CLI's JSON rounds; the Python dicts carry
full precision and are compared at the JSON's printed decimals, within 1e-9 relative); the same
files byte for byte; Session.filter_target / predict_joints equal roprec_filter_target /
roprec_predict_joints; the per-hole Session calls give the CLI's per-hole numbers and the same
dicts under both backends (the compiled module and the ctypes one over the C ABI); errors are
roprec.RoprecError subclasses with the CLI's text; docstrings.

Run by ctest with PYTHONPATH = the build tree's python/ folder, ROPREC_BIN = the CLI and
ROPREC_C_LIB = libroprec_c.so.
"""

import ctypes
import glob
import importlib.util
import json
import math
import os
import random
import shutil
import subprocess
import tempfile
import threading
import time
import unittest
from pathlib import Path

import numpy as np

import roprec

SRC = Path(__file__).resolve().parents[1]
CELL = str(SRC / "samples" / "cells" / "housing-kr120.xml")
TOOLS_CELL = str(SRC / "samples" / "cells" / "housing-kr120-tools.xml")
PROGRAM = str(SRC / "samples" / "emotor-housing" / "housing_kr120.src")
HOLES = str(SRC / "samples" / "emotor-housing" / "holes.csv")
ROPREC_BIN = os.environ["ROPREC_BIN"]
REL = 1e-9


def cli(*args):
    return subprocess.run([ROPREC_BIN] + [str(a) for a in args], capture_output=True, text=True, timeout=600)


def cli_error_text(r):
    """The CLI's error message without 'roprec: error: '."""
    text = r.stderr.strip()
    return text[len("roprec: error: "):] if text.startswith("roprec: error: ") else text


class Num(float):
    """A JSON number that remembers how it was printed."""

    def __new__(cls, text):
        n = float.__new__(cls, float(text))
        n.text = text
        return n


def load_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f, parse_float=Num, parse_int=Num)


def same_number(py_value, token, what):
    """py_value (full precision) printed like `token` (a JSON number) is `token`, within REL."""
    text = token.text
    if "." in text and "e" not in text.lower():
        decimals = len(text.split(".")[1])
        printed = float("%.*f" % (decimals, float(py_value)))
    else:
        printed = float(py_value)
    ref = float(token)
    assert abs(printed - ref) <= REL * max(abs(printed), abs(ref)), "%s: %r (python) vs %s (CLI)" % (what, py_value, text)


def compare_value(py_value, ref, what):
    if isinstance(ref, Num):
        same_number(py_value, ref, what)
    elif isinstance(ref, list):
        values = list(np.asarray(py_value, dtype=float).ravel())
        assert len(values) == len(ref), "%s: %d vs %d values" % (what, len(values), len(ref))
        for k, (v, t) in enumerate(zip(values, ref)):
            same_number(v, t, "%s[%d]" % (what, k))
    else:
        assert py_value == ref, "%s: %r vs %r" % (what, py_value, ref)


def compare_trees(a, b, path=""):
    """Two parsed JSON documents: same structure and strings, numbers within REL."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and list(a) == list(b), "%s: keys %s vs %s" % (path, list(a), list(b))
        for k in a:
            compare_trees(a[k], b[k], path + "/" + k)
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), "%s: lengths" % path
        for i, (x, y) in enumerate(zip(a, b)):
            compare_trees(x, y, "%s/%d" % (path, i))
    elif isinstance(a, float) and isinstance(b, float):
        assert abs(a - b) <= REL * max(abs(a), abs(b)), "%s: %r vs %r" % (path, a, b)
    else:
        assert a == b, "%s: %r vs %r" % (path, a, b)


def dig(tree, dotted):
    for key in dotted.split("."):
        tree = tree[key]
    return tree


# Python per-hole key -> the prediction JSON's key (docs/contract.md "Prediction output").
PREDICT_KEYS = {
    "id": "id", "verdict": "verdict", "nominal_position_mm": "nominal.position_mm",
    "nominal_quaternion_wxyz": "nominal.quaternion_wxyz", "axis": "nominal.axis", "diameter_mm": "diameter_mm",
    "depth_mm": "depth_mm", "tolerance_mm": "tolerance_mm", "mc_time_s": "mc_time_s", "joints_deg": "joints_deg",
    "config": "config", "branch": "branch", "deviation_um": "deviation_um.work",
    "robot_deviation_um": "deviation_um.robot", "mach_deviation_um": "deviation_um.mach",
    "rotation_urad": "deviation_um.robot_rotation_urad", "work_tool_xy_um": "deviation_um.work_tool_xy",
    "position_error_um": "deviation_um.position_error", "axis_tilt_urad": "deviation_um.axis_tilt_urad",
    "from_nominal_axis_um": "deviation_um.from_nominal_axis", "U_robot_um": "uncertainty_um.U_robot",
    "U_mach_um": "uncertainty_um.U_mach", "U_work_um": "uncertainty_um.U_work", "k": "uncertainty_um.k",
    "U_work_anisotropic_um": "uncertainty_um.U_work_anisotropic", "process_share": "uncertainty_um.process_share",
    "process_force_share": "uncertainty_um.process_force_share", "process_force_N": "process_force_N",
    "equilibrium_converged": "equilibrium.converged", "equilibrium_iterations": "equilibrium.iterations",
    "line": "line", "reason": "reason", "drill_tool": "drill.tool", "feed_mm_per_rev": "drill.feed_mm_per_rev",
    "spindle_rpm": "drill.spindle_rpm",
}

# Python per-hole compensation key -> the corrected-target export's key.
COMPENSATE_KEYS = {
    "id": "id", "status": "status", "reason": "reason", "nominal_position_mm": "nominal.position_mm",
    "nominal_quaternion_wxyz": "nominal.quaternion_wxyz", "before_deviation_um": "before.deviation_um.translation",
    "before_rotation_urad": "before.deviation_um.rotation_urad", "before_verdict": "before.verdict",
    "programmed_position_mm": "programmed.position_mm", "programmed_quaternion_wxyz": "programmed.quaternion_wxyz",
    "joints_deg": "programmed.joints_deg", "config": "programmed.config",
    "rotation_about_axis_deg": "rotation_about_axis_deg", "residual_um": "residual_um",
    "residual_vector_um": "residual_vector_um", "branch_changed": "branch_changed", "note": "note",
    "U_robot_um": "uncertainty_um.U_robot", "U_mach_um": "uncertainty_um.U_mach",
    "U_work_um": "uncertainty_um.U_work", "k": "uncertainty_um.k", "verdict": "verdict",
}


def compare_hole(py, ref, mapping, what):
    """Every key of `mapping` the JSON has is in the dict with the same value; absent ones are None."""
    for py_key, json_key in mapping.items():
        try:
            value = dig(ref, json_key)
        except KeyError:
            assert py[py_key] is None, "%s: %s is %r, the JSON has no %s" % (what, py_key, py[py_key], json_key)
            continue
        compare_value(py[py_key], value, "%s %s" % (what, py_key))


class HoleProcess(ctypes.Structure):
    _fields_ = [("tool", ctypes.c_char_p), ("diameter_mm", ctypes.c_double), ("depth_mm", ctypes.c_double),
                ("feed_mm_per_rev", ctypes.c_double), ("spindle_rpm", ctypes.c_double)]


class ProcessUsed(ctypes.Structure):
    _fields_ = [("tool", ctypes.c_char * 64), ("diameter_mm", ctypes.c_double), ("depth_mm", ctypes.c_double),
                ("feed_mm_per_rev", ctypes.c_double), ("spindle_rpm", ctypes.c_double), ("from_cell", ctypes.c_int)]


class CApi(object):
    """libroprec_c through ctypes."""

    def __init__(self, path):
        lib = ctypes.CDLL(path)
        D, P, S, I = ctypes.POINTER(ctypes.c_double), ctypes.c_char_p, ctypes.c_size_t, ctypes.c_int
        lib.roprec_version.restype = P
        lib.roprec_open.argtypes = [P, ctypes.POINTER(ctypes.c_void_p), P, S]
        lib.roprec_close.argtypes = [ctypes.c_void_p]
        lib.roprec_filter_target.argtypes = [ctypes.c_void_p, D, D, D, D, P, S]
        lib.roprec_predict_joints.argtypes = [ctypes.c_void_p, D, D, D, P, S]
        lib.roprec_predict_file.argtypes = [P, P, P, P, P, S, P, S]
        lib.roprec_compensate_file.argtypes = [P, P, P, P, P, P, P, S, P, S]
        lib.roprec_predict_joints_hole.argtypes = [ctypes.c_void_p, D, ctypes.POINTER(HoleProcess), D, D,
                                                   ctypes.POINTER(ProcessUsed), P, S]
        lib.roprec_filter_targets.argtypes = [ctypes.c_void_p, S, D, D, ctypes.POINTER(HoleProcess), D, D,
                                              ctypes.POINTER(I), P, S]
        for f in (lib.roprec_open, lib.roprec_filter_target, lib.roprec_predict_joints, lib.roprec_predict_file,
                  lib.roprec_compensate_file, lib.roprec_predict_joints_hole, lib.roprec_filter_targets):
            f.restype = I
        self.lib = lib

    @staticmethod
    def b(s):
        return None if s is None else str(s).encode()

    def version(self):
        return self.lib.roprec_version().decode()

    def predict_file(self, cell, program, holes, json_out):
        summary, err = ctypes.create_string_buffer(4096), ctypes.create_string_buffer(4096)
        rc = self.lib.roprec_predict_file(self.b(cell), self.b(program), self.b(holes), self.b(json_out), summary, 4096,
                                          err, 4096)
        return rc, json.loads(summary.value.decode()) if rc != 2 else None, err.value.decode()

    def compensate_file(self, cell, program, holes, out, orientation, targets):
        summary, err = ctypes.create_string_buffer(4096), ctypes.create_string_buffer(4096)
        rc = self.lib.roprec_compensate_file(self.b(cell), self.b(program), self.b(holes), self.b(out),
                                             self.b(orientation), self.b(targets), summary, 4096, err, 4096)
        return rc, json.loads(summary.value.decode()) if rc == 0 else None, err.value.decode()

    def open(self, cell):
        s, err = ctypes.c_void_p(), ctypes.create_string_buffer(1024)
        rc = self.lib.roprec_open(self.b(cell), ctypes.byref(s), err, 1024)
        if rc:
            raise RuntimeError(err.value.decode())
        return s

    def filter_target(self, s, pose, seed):
        arr = lambda a, n: (ctypes.c_double * n)(*[float(x) for x in np.ravel(a)])
        out, joints, err = (ctypes.c_double * 16)(), (ctypes.c_double * 6)(), ctypes.create_string_buffer(1024)
        rc = self.lib.roprec_filter_target(s, arr(pose, 16), None if seed is None else arr(seed, 6), out, joints, err, 1024)
        return rc, np.array(out[:]).reshape(4, 4), np.array(joints[:]), err.value.decode()

    def predict_joints(self, s, joints):
        dev, U, err = (ctypes.c_double * 6)(), ctypes.c_double(), ctypes.create_string_buffer(1024)
        rc = self.lib.roprec_predict_joints(s, (ctypes.c_double * 6)(*joints), dev, ctypes.byref(U), err, 1024)
        return rc, np.array(dev[:]), U.value


    def predict_joints_hole(self, s, joints, tool, diameter_mm, depth_mm):
        dev, U, err, used = (ctypes.c_double * 6)(), ctypes.c_double(), ctypes.create_string_buffer(1024), ProcessUsed()
        hp = HoleProcess(self.b(tool), diameter_mm, depth_mm, 0.0, 0.0)
        rc = self.lib.roprec_predict_joints_hole(s, (ctypes.c_double * 6)(*joints), ctypes.byref(hp), dev,
                                                 ctypes.byref(U), ctypes.byref(used), err, 1024)
        return rc, np.array(dev[:]), U.value, used, err.value.decode()

    def filter_targets(self, s, poses, holes):
        n = len(poses)
        flat = (ctypes.c_double * (16 * n))(*[float(x) for x in np.ravel(poses)])
        hp = (HoleProcess * n)(*[HoleProcess(self.b(h.get("tool")), h.get("diameter_mm", 0.0), h.get("depth_mm", 0.0),
                                             0.0, 0.0) for h in holes])
        out, joints = (ctypes.c_double * (16 * n))(), (ctypes.c_double * (6 * n))()
        status, err = (ctypes.c_int * n)(), ctypes.create_string_buffer(4096)
        rc = self.lib.roprec_filter_targets(s, n, flat, None, hp, out, joints, status, err, 4096)
        return rc, np.array(out[:]).reshape(n, 4, 4), np.array(joints[:]).reshape(n, 6), list(status), err.value.decode()


C = CApi(os.environ["ROPREC_C_LIB"])


def other_backend():
    """The backend roprec is not using: the ctypes one (roprec/_cabi.py) or the compiled module of
    the build (loaded under its own name, beside the package's)."""
    if not roprec._roprec.__name__.endswith("_cabi"):
        from roprec import _cabi
        return _cabi
    found = glob.glob(os.path.join(os.path.dirname(roprec.__file__), "_roprec*.so"))
    assert found, "the build's compiled module _roprec is missing"
    spec = importlib.util.spec_from_file_location("_roprec", found[0])
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def compare_exactly(a, b, what):
    """Same keys, types of container and values (arrays equal, NaN where NaN)."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and sorted(a) == sorted(b), "%s: keys %s vs %s" % (what, sorted(a), sorted(b))
        for k in a:
            compare_exactly(a[k], b[k], "%s.%s" % (what, k))
    elif isinstance(a, np.ndarray):
        assert isinstance(b, np.ndarray), "%s: an array vs %r" % (what, type(b))
        assert a.dtype == b.dtype, "%s: %s vs %s" % (what, a.dtype, b.dtype)
        np.testing.assert_array_equal(a, b, err_msg=what)
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), what
        for i, (x, y) in enumerate(zip(a, b)):
            compare_exactly(x, y, "%s[%d]" % (what, i))
    else:
        assert type(a) is type(b) and a == b, "%s: %r vs %r" % (what, a, b)


class PythonApiTest(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="roprec-pytest-"))

    def tearDown(self):
        shutil.rmtree(self.tmp)

    def test_version_and_docstrings(self):
        self.assertEqual(roprec.__version__, C.version())
        self.assertRegex(roprec.__version__, r"^\d+\.\d+\.\d+$")
        self.assertTrue(issubclass(roprec.RoprecError, Exception))
        for cls in (roprec.InputError, roprec.UsageError, roprec.ItemError):
            self.assertTrue(issubclass(cls, roprec.RoprecError))
        self.assertTrue(issubclass(roprec.UsageError, ValueError))
        public = [roprec, roprec.Session, roprec.predict, roprec.compensate, roprec.Prediction, roprec.RoprecError,
                  roprec.InputError, roprec.UsageError, roprec.ItemError]
        public += [getattr(roprec.Session, n) for n in ("filter_target", "filter_targets", "predict_joints",
                                                        "hole_pose", "cell_path",
                                                        "cell", "robot", "tool_pose_mm", "workobject_pose_mm",
                                                        "process")]
        for obj in public:
            self.assertTrue((obj.__doc__ or "").strip(), obj)
        self.assertEqual(sorted(roprec.__all__), sorted(["__version__", "Session", "predict", "compensate", "verify", "plan_test", "Prediction",
                                                         "RoprecError", "InputError", "UsageError", "ItemError"]))

    def test_a_folder_given_as_an_input_is_a_directory_not_a_memory_error(self):
        with self.assertRaises(roprec.InputError) as e:
            roprec.predict(CELL, str(self.tmp))
        self.assertIn(str(self.tmp) + ": is a directory", str(e.exception))
        with self.assertRaises(roprec.InputError) as e:
            roprec.predict(str(self.tmp), PROGRAM)
        self.assertIn("is a directory; give a cell file", str(e.exception))

    def test_an_output_that_is_an_input_is_refused_and_the_input_kept(self):
        program = self.tmp / "p.src"
        shutil.copy(PROGRAM, program)
        before = program.read_bytes()
        with self.assertRaises(roprec.UsageError) as e:
            roprec.predict(CELL, str(program), json_out=str(program))
        self.assertIn("is the input file", str(e.exception))
        self.assertEqual(program.read_bytes(), before)

    def test_predict_gives_the_cli_and_c_numbers(self):
        r = cli("predict", "--cell", CELL, PROGRAM, "--holes", HOLES, "--json", self.tmp / "cli.json", "--quiet")
        self.assertLessEqual(r.returncode, 1, r.stderr)
        p = roprec.predict(CELL, PROGRAM, holes=HOLES, json_out=self.tmp / "py.json")
        rc, c_summary, err = C.predict_file(CELL, PROGRAM, HOLES, self.tmp / "c.json")
        self.assertEqual(rc, r.returncode, err)
        ref = load_json(self.tmp / "cli.json")
        # The same document from all three.
        compare_trees(ref, load_json(self.tmp / "py.json"))
        compare_trees(ref, load_json(self.tmp / "c.json"))
        self.assertEqual((self.tmp / "py.json").read_bytes(), (self.tmp / "cli.json").read_bytes())
        # The dicts: every number of the JSON, at full precision.
        self.assertIsInstance(p, list)
        self.assertEqual(len(p), len(ref["holes"]))
        self.assertEqual(len(p), 204)
        for h, j in zip(p, ref["holes"]):
            compare_hole(h, j, PREDICT_KEYS, h["id"])
            budget = dig(j, "uncertainty_um.standard_per_axis") if "uncertainty_um" in j else None
            if budget is not None:
                self.assertEqual(list(h["budget_um"]), list(budget))
                for name, tok in budget.items():
                    same_number(h["budget_um"][name], tok, h["id"] + " budget " + name)
            np.testing.assert_allclose(h["nominal_pose_mm"][:3, 3], h["nominal_position_mm"], rtol=0, atol=0)
        self.assertEqual(p.robot, ref["robot"])
        self.assertEqual(p.notes, ref["notes"])
        summary = dict(p.summary)
        self.assertEqual(summary.pop("failed"), len(p.failed))
        compare_trees(ref["summary"], summary)
        compare_trees(p.summary, c_summary)
        self.assertEqual(p.failures == "", not p.failed)

    def test_compensate_keep_gives_the_cli_and_c_numbers_and_bytes(self):
        r = cli("compensate", "--cell", CELL, PROGRAM, "--holes", HOLES, "--orientation", "keep",
                "-o", self.tmp / "cli.src", "--targets", self.tmp / "cli.json", "--quiet")
        self.assertEqual(r.returncode, 0, r.stderr)
        res = roprec.compensate(CELL, PROGRAM, self.tmp / "py.src", orientation="keep", targets=self.tmp / "py.json",
                                holes=HOLES)
        rc, c_summary, err = C.compensate_file(CELL, PROGRAM, HOLES, self.tmp / "c.src", "keep", self.tmp / "c.json")
        self.assertEqual(rc, 0, err)
        for stem in ("py", "c"):   # the sample keeps its points inline: no .dat
            self.assertEqual((self.tmp / (stem + ".src")).read_bytes(), (self.tmp / "cli.src").read_bytes())
        ref = load_json(self.tmp / "cli.json")
        compare_trees(ref, load_json(self.tmp / "py.json"))
        compare_trees(ref, load_json(self.tmp / "c.json"))
        self.assertEqual(len(res["results"]), 204)
        for h, j in zip(res["results"], ref["holes"]):
            compare_hole(h, j, COMPENSATE_KEYS, h["id"])
            np.testing.assert_allclose(h["programmed_pose_mm"][:3, 3], h["programmed_position_mm"], rtol=0, atol=0)
            # keep: the programmed orientation is the nominal one
            np.testing.assert_array_equal(h["programmed_pose_mm"][:3, :3], h["nominal_pose_mm"][:3, :3])
        self.assertEqual(res["written"], [str(self.tmp / "py.src"), str(self.tmp / "py.json")])
        self.assertEqual(c_summary["written"], [str(self.tmp / "c.src"), str(self.tmp / "c.json")])
        summary = {k: v for k, v in res.items() if k not in ("results", "written")}
        compare_trees(summary, {k: v for k, v in c_summary.items() if k != "written"})
        self.assertEqual((summary["orientation"], summary["holes"], summary["compensated"], summary["failed"]),
                         ("keep", 204, 204, 0))

    def test_milling_cell_compensates_path_points_like_the_cli(self):
        cell = str(SRC / "samples" / "cells" / "alu-milling-7075.xml")
        program = str(SRC / "samples" / "milling" / "wall_pass.src")
        for ext in (".json", ".csv"):  # the export's format by its name, as the CLI's
            r = cli("compensate", "--cell", cell, program, "-o", self.tmp / "cli.src", "--targets",
                    self.tmp / ("cli" + ext), "--quiet")
            self.assertEqual(r.returncode, 0, r.stderr)
            res = roprec.compensate(cell, program, self.tmp / "py.src", targets=self.tmp / ("py" + ext))
            rc, c_summary, err = C.compensate_file(cell, program, None, self.tmp / "c.src", None,
                                                   self.tmp / ("c" + ext))
            self.assertEqual(rc, 0, err)
            for stem in ("py", "c"):
                for e in (".src", ext):
                    self.assertEqual((self.tmp / (stem + e)).read_bytes(), (self.tmp / ("cli" + e)).read_bytes())
        self.assertFalse((self.tmp / "cli.csv").read_text().startswith("{"))
        self.assertEqual((res["process"], res["failed"]), ("milling", 0))
        self.assertEqual(res["points"], len(load_json(self.tmp / "cli.json")["points"]))
        compare_trees({k: v for k, v in res.items() if k != "written"},
                      {k: v for k, v in c_summary.items() if k != "written"})

    def test_session_equals_the_c_session(self):
        s = roprec.Session(CELL)
        cs = C.open(CELL)
        try:
            p = roprec.predict(CELL, HOLES)
            for h in p[::17]:
                wanted = h["nominal_pose_mm"]
                for seed in (None, h["controller_joints_deg"]):
                    pose, joints = s.filter_target(wanted, seed)
                    rc, cpose, cjoints, err = C.filter_target(cs, wanted, seed)
                    self.assertEqual(rc, 0, err)
                    np.testing.assert_array_equal(pose, cpose)
                    np.testing.assert_array_equal(joints, cjoints)
                    np.testing.assert_array_equal(pose[:3, :3], wanted[:3, :3])   # orientation kept
                    d = s.predict_joints(joints)
                    rc, cdev, cU = C.predict_joints(cs, joints)
                    self.assertEqual(rc, 0)
                    np.testing.assert_array_equal(d["deviation_um"], cdev[:3])
                    np.testing.assert_array_equal(d["rotation_urad"], cdev[3:])
                    self.assertEqual(d["U_work_um"], cU)
                    real = pose[:3, 3] + d["deviation_um"] * 1e-3
                    self.assertLess(np.linalg.norm(real - wanted[:3, 3]) * 1e3, 0.1)
            # hole_pose is the hole list's pose (the cell's workobject x the hole frame).
            np.testing.assert_allclose(s.hole_pose([150, 0, 250], [0, 0, -1]), p[0]["nominal_pose_mm"], rtol=0, atol=1e-12)
            self.assertEqual(s.robot, p.robot)
            self.assertEqual(s.cell_path, CELL)
        finally:
            C.lib.roprec_close(cs)

    def test_both_backends_give_the_same_per_hole_dicts(self):
        """The Session calls with a hole's process give the same dicts, value for value, from the
        compiled module and from the ctypes one over the C ABI (its JSON answers)."""
        this, other = roprec._roprec, other_backend()
        p = roprec.predict(TOOLS_CELL, HOLES)[::23]
        a, b = this.Session(TOOLS_CELL), other.Session(TOOLS_CELL)
        holes = [dict(tool=h["drill_tool"], diameter_mm=h["diameter_mm"], depth_mm=h["depth_mm"]) for h in p]
        holes[0] = dict(tool=3, feed_mm_per_rev=0.15, spindle_rpm=4000.0)  # a number as the tool, own cut data
        holes[1] = {}                                                      # the cell's drill
        for h, args in zip(p, holes):
            compare_exactly(a.predict_joints(h["controller_joints_deg"], **args),
                            b.predict_joints(h["controller_joints_deg"], **args), "predict_joints")
            compare_exactly(a.filter_target(h["nominal_pose_mm"], h["controller_joints_deg"], details=True, **args),
                            b.filter_target(h["nominal_pose_mm"], h["controller_joints_deg"], details=True, **args),
                            "filter_target details")
            plain = (s.filter_target(h["nominal_pose_mm"], **args) for s in (a, b))
            for x, y in zip(*plain):
                np.testing.assert_array_equal(x, y)
        d = a.predict_joints(p[0]["controller_joints_deg"], **holes[0])["process"]
        self.assertEqual((d["tool"], d["feed_mm_per_rev"], d["spindle_rpm"], d["from_cell"]),
                         ("3", 0.15, 4000.0, False))
        self.assertTrue(a.predict_joints(p[1]["controller_joints_deg"])["process"]["from_cell"])
        poses = np.array([h["nominal_pose_mm"] for h in p])
        poses[2, 0, 3] = 9000.0  # unreachable: kept, NaN joints, its reason
        batch = a.filter_targets(poses, holes=holes)
        compare_exactly(batch, b.filter_targets(poses, holes=holes), "filter_targets")
        self.assertEqual(list(batch["ok"]), [i != 2 for i in range(len(p))])
        self.assertTrue(np.isnan(batch["joints_deg"][2]).all())
        np.testing.assert_array_equal(batch["poses_mm"][2], poses[2])
        self.assertIn("unreachable", batch["reasons"][2])
        seeds = np.array([h["controller_joints_deg"] for h in p])
        compare_exactly(a.filter_targets(poses, seeds), b.filter_targets(poses, seeds), "filter_targets seeded")
        for s in (a, b):  # the same refusals
            for call, error in ((lambda: s.filter_target(poses[0], tool="9"), this.InputError),
                                (lambda: s.predict_joints([0, -90, 90, 0, 0, 400], tool="2"), this.InputError),
                                (lambda: s.predict_joints(seeds[0], diameter_mm=-1.0), this.UsageError),
                                (lambda: s.filter_targets(poses, holes=[{"drill": "1"}] * len(p)), this.UsageError),
                                (lambda: s.filter_targets(poses, holes=holes[:1]), this.UsageError),
                                (lambda: s.filter_targets(poses[0]), this.UsageError)):
                with self.assertRaises(Exception) as e:
                    call()
                self.assertEqual(type(e.exception).__name__, error.__name__, str(e.exception))

    def test_host_calls_take_the_hole_and_agree_with_the_cli_per_hole(self):
        """predict_joints / filter_targets with each hole's drill, diameter and depth (C and Python)
        give the CLI's `predict --holes` deviations and `compensate` targets per hole, to 1e-9 m."""
        out = self.tmp / "p.json"
        r = cli("predict", "--cell", TOOLS_CELL, HOLES, "--json", out, "--quiet")
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out, encoding="utf-8") as f:
            holes = json.load(f)["holes"]
        r = cli("compensate", "--cell", TOOLS_CELL, HOLES, "--orientation", "keep", "-o", self.tmp / "c.csv",
                "--targets", self.tmp / "t.json", "--quiet")
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(self.tmp / "t.json", encoding="utf-8") as f:
            targets = json.load(f)["holes"]
        s = roprec.Session(TOOLS_CELL)
        cs = C.open(TOOLS_CELL)
        try:
            p = roprec.predict(TOOLS_CELL, HOLES)
            hole_args = []
            for h, ph in zip(holes, p):
                self.assertEqual(h["id"], ph["id"])
                args = dict(tool=h["drill"]["tool"], diameter_mm=h["diameter_mm"], depth_mm=h["depth_mm"])
                hole_args.append(args)
                d = s.predict_joints(ph["controller_joints_deg"], **args)
                rc, cdev, cU, used, err = C.predict_joints_hole(cs, ph["controller_joints_deg"], **args)
                self.assertEqual(rc, 0, err)
                np.testing.assert_array_equal(d["deviation_um"], cdev[:3])
                for k in range(3):   # the JSON's µm with 3 decimals: 1e-9 m
                    self.assertAlmostEqual(d["deviation_um"][k], h["deviation_um"]["robot"][k], delta=1e-3)
                self.assertAlmostEqual(d["U_work_um"], h["uncertainty_um"]["U_work_anisotropic"], delta=1e-3)
                self.assertEqual(d["process"]["tool"], h["drill"]["tool"])
                self.assertEqual(used.tool.decode(), h["drill"]["tool"])
                self.assertAlmostEqual(used.feed_mm_per_rev, h["drill"]["feed_mm_per_rev"], delta=1e-9)
                self.assertAlmostEqual(d["process"]["spindle_rpm"], h["drill"]["spindle_rpm"], delta=1e-9)
                self.assertAlmostEqual(used.diameter_mm, h["diameter_mm"], delta=1e-9)
                self.assertEqual(used.from_cell, 0)
                self.assertFalse(d["process"]["from_cell"])
                self.assertAlmostEqual(d["process"]["depth_mm"], h["depth_mm"], delta=1e-9)
            wanted = np.array([ph["nominal_pose_mm"] for ph in p])
            batch = s.filter_targets(wanted, holes=hole_args)
            rc, cposes, cjoints, status, err = C.filter_targets(cs, wanted, hole_args)
            self.assertEqual(rc, 0, err)
            self.assertTrue(all(batch["ok"]))
            np.testing.assert_array_equal(batch["poses_mm"], cposes)
            np.testing.assert_array_equal(batch["joints_deg"], cjoints)
            for i, t in enumerate(targets):   # the export's mm with 6 decimals: 1e-9 m
                np.testing.assert_allclose(cposes[i][:3, 3], t["programmed"]["position_mm"], rtol=0, atol=0.5e-6 + 1e-9)
                self.assertEqual(batch["process"][i]["tool"], holes[i]["drill"]["tool"])
                self.assertEqual(batch["reasons"][i], None)
            # a joint outside the limits is bad input (2), as in the CLI
            rc, _, _, _, err = C.predict_joints_hole(cs, [0, -90, 90, 0, 0, 400], None, 0.0, 0.0)
            self.assertEqual(rc, 2, err)
            self.assertIn("outside the joint limits", err)
            with self.assertRaises(roprec.InputError):
                s.predict_joints([0, -90, 90, 0, 0, 400])
            with self.assertRaises(roprec.InputError):
                s.filter_target(wanted[0], tool="9")
            # the old call: the cell's (first) drill, stated in the details
            det = s.filter_target(wanted[0], details=True)
            self.assertTrue(det["process"]["from_cell"])
            self.assertEqual(det["process"]["tool"], "1")
        finally:
            C.lib.roprec_close(cs)

    def test_errors_carry_the_cli_text(self):
        missing = str(SRC / "samples" / "cells" / "no-such-cell.xml")
        with self.assertRaises(roprec.InputError) as e:
            roprec.Session(missing)
        self.assertEqual(str(e.exception), cli_error_text(cli("predict", "--cell", missing, PROGRAM)))
        self.assertIsInstance(e.exception, roprec.RoprecError)
        no_program = self.tmp / "no-such-program.src"
        with self.assertRaises(roprec.InputError) as e:
            roprec.compensate(CELL, no_program, self.tmp / "o.src")
        r = cli("compensate", "--cell", CELL, no_program, "-o", self.tmp / "o.src", "--quiet")
        self.assertEqual(r.returncode, 2)
        self.assertEqual(str(e.exception), cli_error_text(r))
        self.assertFalse((self.tmp / "o.src").exists())
        with self.assertRaises(roprec.UsageError):
            roprec.compensate(CELL, PROGRAM, self.tmp / "o.src", orientation="sideways")
        s = roprec.Session(CELL)
        with self.assertRaises(roprec.UsageError):
            s.filter_target(np.eye(3))
        with self.assertRaises(ValueError):
            s.filter_target(np.diag([1.0, 1.0, 2.0, 1.0]))                  # not a rotation
        with self.assertRaises(roprec.UsageError):
            s.predict_joints([0, -90, 90, 0, float("nan"), 0])
        far = np.eye(4)
        far[0, 3] = 9000.0
        with self.assertRaises(roprec.ItemError) as e:
            s.filter_target(far)
        self.assertIn("target not filtered", str(e.exception))

    def test_frame_tool_and_force_as_the_cli(self):
        fcell = str(SRC / "samples" / "cells" / "housing-r2000.xml")
        fprog = str(SRC / "samples" / "emotor-housing" / "housing_r2000.ls")
        # Controller-only UFRAME/UTOOL: an error without frame/tool, with the CLI's text.
        with self.assertRaises(roprec.InputError) as e:
            roprec.predict(fcell, fprog)
        self.assertEqual(str(e.exception), cli_error_text(cli("predict", "--cell", fcell, fprog)))
        with self.assertRaises(roprec.UsageError):
            roprec.predict(fcell, fprog, frame="cell", tool="flange")
        r = cli("predict", "--cell", fcell, fprog, "--frame", "cell", "--tool", "cell", "--json",
                self.tmp / "cli.json", "--quiet")
        self.assertLessEqual(r.returncode, 1, r.stderr)
        p = roprec.predict(fcell, fprog, json_out=self.tmp / "py.json", frame="cell", tool="cell")
        self.assertEqual((self.tmp / "py.json").read_bytes(), (self.tmp / "cli.json").read_bytes())
        self.assertTrue(any(n.startswith("resolution: ") for n in p.notes), p.notes)
        # force: a compensated program is refused again unless force=True.
        once = self.tmp / "once.ls"
        roprec.compensate(fcell, fprog, once, frame="cell", tool="cell")
        twice = self.tmp / "twice.ls"
        with self.assertRaises(roprec.InputError) as e:
            roprec.compensate(fcell, once, twice, frame="cell", tool="cell")
        self.assertIn("--force", str(e.exception))
        self.assertFalse(twice.exists())
        roprec.compensate(fcell, once, twice, frame="cell", tool="cell", force=True)
        self.assertTrue(twice.exists())

    @unittest.skipIf(roprec._roprec.__name__.endswith("_cabi"),
                     "the C ABI gives no summary or per-hole results for a compensation it refused")
    def test_compensate_with_a_failed_hole_writes_nothing(self):
        s = roprec.Session(CELL)
        wobj = s.workobject_pose_mm
        targets = []
        for k, (p, d) in enumerate((([150, 0, 250], [0, 0, -1]), ([4000, 0, 250], [0, 0, -1]))):
            pose = np.linalg.inv(wobj) @ s.hole_pose(p, d)
            for name, depth, speed in (("A", -20.0, 250), ("", 0.0, 10)):
                pp = pose[:3, 3] + depth * pose[:3, 2]
                targets.append({"id": "H%d%s" % (k + 1, name), "motion": "L", "frame": "wobj", "speed_mm_s": speed,
                                "position_mm": pp.tolist(), "quaternion_wxyz": [0.0, 1.0, 0.0, 0.0]})
        program = self.tmp / "two_holes.json"
        program.write_text(json.dumps({"frames": [{"name": "wobj", "position_mm": wobj[:3, 3].tolist(),
                                                   "quaternion_wxyz": [1, 0, 0, 0]}], "targets": targets}))
        with self.assertRaises(roprec.ItemError) as e:
            roprec.compensate(CELL, program, self.tmp / "out.json", targets=self.tmp / "t.json")
        self.assertIn("not compensated", str(e.exception))
        self.assertEqual(e.exception.result["failed"], 1)
        self.assertEqual(e.exception.result["written"], [])
        self.assertEqual([h["status"] for h in e.exception.result["results"]], ["compensated", "original-kept"])
        self.assertFalse((self.tmp / "out.json").exists())
        self.assertFalse((self.tmp / "t.json").exists())
        rc, _, err = C.compensate_file(CELL, program, None, self.tmp / "out.json", None, None)
        self.assertEqual(rc, 1)
        self.assertIn("not compensated", err)
        self.assertFalse((self.tmp / "out.json").exists())

    def tracker_poses_with_orientation(self, count=24):
        """A tracker pose file with rx,ry,rz: the sample program's commanded joints, measured at the
        programmed TCP (workobject frame; its axes are the base's) with a seeded ±0.3 mrad error per
        angle, so the fit trades the orientations against the positions by their σ."""
        r = cli("predict", "--cell", CELL, PROGRAM, "--holes", HOLES, "--quiet", "--json", self.tmp / "p.json")
        self.assertEqual(r.returncode, 0, r.stderr)
        wobj = (1350.0, 0.0, 300.0)  # mm, the cell's <workobject>
        rng = random.Random(7)
        rows = ["id,j1,j2,j3,j4,j5,j6,x,y,z,rx,ry,rz"]
        for h in load_json(self.tmp / "p.json")["holes"][:count]:
            w, x, y, z = (float(v) for v in h["nominal"]["quaternion_wxyz"])
            R = [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                 [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                 [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]
            rpy = (math.atan2(R[2][1], R[2][2]), math.asin(-R[2][0]), math.atan2(R[1][0], R[0][0]))  # fixed X-Y-Z
            xyz = ",".join("%.4f" % (float(h["nominal"]["position_mm"][a]) - wobj[a]) for a in range(3))
            angles = ",".join("%.7f" % math.degrees(a + rng.uniform(-3e-4, 3e-4)) for a in rpy)
            joints = ",".join("%.9f" % float(q) for q in h["controller_joints_deg"])
            rows.append("%s,%s,%s,%s" % (h["id"], joints, xyz, angles))
        path = self.tmp / "poses.csv"
        path.write_text("\n".join(rows) + "\n")
        return path

    def test_verify_u_rot_gives_the_cli_rotation_residuals(self):
        # verify(poses=..., u_rot=...) as `roprec verify --poses ... --u-rot ...`: the same JSON (each
        # pose's rotation_residual_identified_urad within 1e-9 relative); u_rot weighs the orientations
        # against the positions in the rigid registration, so another σ gives other residuals
        poses = self.tracker_poses_with_orientation()
        r = cli("verify", "--cell", CELL, "--poses", poses, "--register", "rigid", "--u-rot", "20", "--quiet", "--json",
                self.tmp / "cli.json")
        self.assertEqual(r.returncode, 0, r.stderr)
        ref = json.loads((self.tmp / "cli.json").read_text())
        got = roprec.verify(CELL, None, None, poses=poses, register="rigid", u_rot=20)
        self.assertEqual(got.pop("written"), [])
        compare_trees(got, ref)
        rot = [p["rotation_residual_identified_urad"] for p in got["poses"]["poses"]]
        self.assertEqual(len(rot), 24)
        self.assertGreater(max(max(abs(v) for v in p) for p in rot), 1.0)  # µrad: the orientations were fitted
        default = roprec.verify(CELL, None, None, poses=poses, register="rigid")
        other = [p["rotation_residual_identified_urad"] for p in default["poses"]["poses"]]
        self.assertGreater(max(abs(a - b) for p, q in zip(rot, other) for a, b in zip(p, q)), 1e-3)
        with self.assertRaises(roprec.UsageError):
            roprec.verify(CELL, None, None, poses=poses, register="rigid", u_rot=0)

    def test_filter_target_of_a_registered_cell_aims_at_the_registered_part(self):
        # as CApi.FilterTargetOfARegisteredCellAimsAtTheRegisteredPart: a cell with a
        # <part_registration> F (about the workobject W) programs a wanted pose T of the nominal
        # part as the plain cell programs G·T, G = W·F⁻¹·W⁻¹ (the real part), to 1e-6 mm and 1e-9 rad,
        # and the part moved the program by ≥ 0.1 mm
        text = Path(CELL).read_text()
        at = text.index("/>", text.index("<workobject ")) + 2
        registered = self.tmp / "registered.xml"
        registered.write_text(text[:at] + '\n  <part_registration xyz_mm="0.35 -0.2 0.25" rpy_mrad="0.5 -0.4 0.6" '
                              'source="test"/>' + text[at:])

        def rot(axis, a):
            c, s = np.cos(a), np.sin(a)
            i, j = (axis + 1) % 3, (axis + 2) % 3
            R = np.eye(3)
            R[i, i], R[i, j], R[j, i], R[j, j] = c, -s, s, c
            return R

        F = np.eye(4)  # the registration by hand: URDF rpy, R = Rz · Ry · Rx; mm
        F[:3, :3] = rot(2, 0.6e-3) @ rot(1, -0.4e-3) @ rot(0, 0.5e-3)
        F[:3, 3] = [0.35, -0.2, 0.25]
        s, plain = roprec.Session(str(registered)), roprec.Session(CELL)
        W = np.asarray(plain.workobject_pose_mm)
        np.testing.assert_array_equal(np.asarray(s.workobject_pose_mm), W)  # the workobject stays
        G = W @ np.linalg.inv(F) @ np.linalg.inv(W)
        rows = [r.split(",") for r in Path(HOLES).read_text().splitlines() if r and not r.startswith("#")]
        head = rows[0]
        for row in rows[1:13]:
            v = dict(zip(head, row))
            want = np.asarray(plain.hole_pose([float(v[k]) for k in "xyz"], [float(v[k]) for k in "ijk"]))
            prog = s.filter_target(want)[0]
            hand = plain.filter_target(G @ want)[0]
            prog, hand = np.asarray(prog), np.asarray(hand)
            self.assertLessEqual(np.linalg.norm(prog[:3, 3] - hand[:3, 3]), 1e-6, v["id"])
            D = prog[:3, :3].T @ hand[:3, :3]  # the small rotation between them: its vee part, rad
            self.assertLessEqual(np.linalg.norm([D[2, 1] - D[1, 2], D[0, 2] - D[2, 0], D[1, 0] - D[0, 1]]) / 2, 1e-9)
            self.assertGreaterEqual(np.linalg.norm(prog[:3, 3] - want[:3, 3]), 0.1, v["id"])

    def test_sessions_on_threads(self):
        holes = roprec.predict(CELL, HOLES)[:30]
        serial = [roprec.Session(CELL).filter_target(h["nominal_pose_mm"])[0] for h in holes]
        results = [None] * len(holes)

        def work(part):
            s = roprec.Session(CELL)
            for i in range(part, len(holes), 2):
                results[i] = s.filter_target(holes[i]["nominal_pose_mm"])[0]

        shared = roprec.Session(CELL)   # one session shared by threads: calls are serialised
        shared_results = [None] * len(holes)

        def work_shared(part):
            for i in range(part, len(holes), 2):
                shared_results[i] = shared.filter_target(holes[i]["nominal_pose_mm"])[0]

        threads = [threading.Thread(target=f, args=(k,)) for f in (work, work_shared) for k in (0, 1)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        for a, b, c in zip(serial, results, shared_results):
            np.testing.assert_array_equal(a, b)
            np.testing.assert_array_equal(a, c)


    def test_a_ctypes_session_shared_by_threads_serialises_its_calls(self):
        """The ctypes backend's Session over one C session (which must not be used by two threads at
        once, roprec.h): four threads calling filter_target, filter_targets and predict_joints on
        it, each C call held 2 ms by a counting stand-in for the library, are never inside the
        library together, and give the answers of calls made one after the other."""
        from roprec import _cabi

        class Counting(object):
            def __init__(self, lib):
                self.lib, self.inside, self.most, self.count = lib, 0, 0, threading.Lock()

            def __getattr__(self, name):
                f = getattr(self.lib, name)
                if name not in ("roprec_filter_target_hole", "roprec_filter_targets_json",
                                "roprec_predict_joints_hole_json"):
                    return f

                def held(*args):
                    with self.count:
                        self.inside += 1
                        self.most = max(self.most, self.inside)
                    try:
                        time.sleep(0.002)
                        return f(*args)
                    finally:
                        with self.count:
                            self.inside -= 1
                return held

        holes = roprec.predict(CELL, HOLES)[:8]
        poses = [h["nominal_pose_mm"] for h in holes]
        one = _cabi.Session(CELL)
        want = [(one.filter_target(p)[0], one.filter_targets(np.asarray([p]))["poses_mm"][0],
                 one.predict_joints(h["controller_joints_deg"])["deviation_um"]) for p, h in zip(poses, holes)]
        shared = _cabi.Session(CELL)
        got = [[None] * len(holes) for _ in range(4)]
        real, _cabi._lib = _cabi._lib, Counting(_cabi._lib)
        try:
            def work(k):
                for i in range(len(holes)):
                    got[k][i] = (shared.filter_target(poses[i])[0],
                                 shared.filter_targets(np.asarray([poses[i]]))["poses_mm"][0],
                                 shared.predict_joints(holes[i]["controller_joints_deg"])["deviation_um"])
            threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
            for t in threads:
                t.start()
            for t in threads:
                t.join()
            most = _cabi._lib.most
        finally:
            _cabi._lib = real
        self.assertEqual(most, 1)
        for k in range(4):
            for i in range(len(holes)):
                for a, b in zip(want[i], got[k][i]):
                    np.testing.assert_array_equal(np.asarray(a), np.asarray(b))


if __name__ == "__main__":
    unittest.main(verbosity=2)
