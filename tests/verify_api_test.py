"""`roprec verify` and `roprec plan-test`: the CLI, the C ABI (ctypes) and the Python
module give identical numbers on the shipped sample (samples/verification/): identical JSON and
card bytes, and every number of the summaries equal within 1e-9 relative.

Run by ctest with PYTHONPATH = the build tree's python/ folder, ROPREC_BIN = the CLI and
ROPREC_C_LIB = libroprec_c.so.
"""

import ctypes
import json
import math
import os
import re
import random
import subprocess
import tempfile
import unittest
from pathlib import Path

import roprec

SRC = Path(__file__).resolve().parents[1]
CELL = str(SRC / "samples" / "cells" / "housing-kr120.xml")
PROGRAM = str(SRC / "samples" / "verification" / "test_kr120.src")
MEASURED = str(SRC / "samples" / "verification" / "measured.csv")
HOLES = str(SRC / "samples" / "verification" / "test_kr120_holes.csv")  # names the holes V01…
REL = 1e-9


def cli(*args):
    return subprocess.run([os.environ["ROPREC_BIN"]] + [str(a) for a in args], capture_output=True, text=True,
                          timeout=600)


def close(a, b, what):
    if isinstance(a, dict):
        assert set(a) == set(b), what
        for k in a:
            close(a[k], b[k], what + "." + k)
    elif isinstance(a, list):
        assert len(a) == len(b), what
        for i, (x, y) in enumerate(zip(a, b)):
            close(x, y, "%s[%d]" % (what, i))
    elif isinstance(a, float) or isinstance(b, float):
        assert abs(a - b) <= REL * max(abs(a), abs(b)), "%s: %r != %r" % (what, a, b)
    else:
        assert a == b, "%s: %r != %r" % (what, a, b)


class C(object):
    def __init__(self):
        lib = ctypes.CDLL(os.environ["ROPREC_C_LIB"])
        P, S, I = ctypes.c_char_p, ctypes.c_size_t, ctypes.c_int
        lib.roprec_verify_file.argtypes = [P, P, P, P, P, P, P, P, S, P, S]
        lib.roprec_plan_test_file.argtypes = [P, ctypes.POINTER(ctypes.c_double), I, P, P, S, P, S]
        lib.roprec_verify_file.restype = I
        lib.roprec_plan_test_file.restype = I
        self.lib = lib

    def verify(self, measured, registration, json_out, card_out):
        b = lambda s: None if s is None else str(s).encode()
        summary, err = ctypes.create_string_buffer(4096), ctypes.create_string_buffer(4096)
        rc = self.lib.roprec_verify_file(b(CELL), b(PROGRAM), b(measured), b(HOLES), b(registration), b(json_out),
                                         b(card_out), summary, 4096, err, 4096)
        return rc, summary.value.decode(), err.value.decode()

    def verify_ex(self, program, measured, registration, json_out, card_out, options):
        b = lambda s: None if s is None else str(s).encode()
        lib, P, S = self.lib, ctypes.c_char_p, ctypes.c_size_t
        lib.roprec_options_new.argtypes = [ctypes.POINTER(ctypes.c_void_p), P, S]
        lib.roprec_options_set.argtypes = [ctypes.c_void_p, P, P, P, S]
        lib.roprec_options_free.argtypes = [ctypes.c_void_p]
        lib.roprec_verify_file_ex.argtypes = [P, P, P, P, ctypes.c_void_p, P, P, P, S, P, S]
        summary, err = ctypes.create_string_buffer(4096), ctypes.create_string_buffer(4096)
        opt = ctypes.c_void_p()
        assert lib.roprec_options_new(ctypes.byref(opt), err, 4096) == 0, err.value
        try:
            for k, v in options.items():
                assert lib.roprec_options_set(opt, b(k), b(v), err, 4096) == 0, err.value
            rc = lib.roprec_verify_file_ex(b(CELL), b(program), b(measured), b(registration), opt, b(json_out),
                                           b(card_out), summary, 4096, err, 4096)
        finally:
            lib.roprec_options_free(opt)
        return rc, summary.value.decode(), err.value.decode()

    def plan_test(self, region, count, out):
        arr = (ctypes.c_double * 6)(*region)
        summary, err = ctypes.create_string_buffer(4096), ctypes.create_string_buffer(4096)
        rc = self.lib.roprec_plan_test_file(CELL.encode(), arr, count, str(out).encode(), summary, 4096, err, 4096)
        return rc, summary.value.decode(), err.value.decode()


class VerifyAcrossInterfaces(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory()
        self.tmp = Path(self._tmp.name)

    def tearDown(self):
        self._tmp.cleanup()

    def test_verify_cli_c_python_identical(self):
        t = self.tmp
        r = cli("verify", "--cell", CELL, PROGRAM, "--holes", HOLES, "--measured", MEASURED, "--register", "translation",
                "--json", t / "cli.json", "--calibrate", t / "cli.xml", "--quiet")
        self.assertEqual(r.returncode, 0, r.stderr)
        rc, summary, err = C().verify(MEASURED, "translation", t / "c.json", t / "c.xml")
        self.assertEqual(rc, 0, err)
        py = roprec.verify(CELL, PROGRAM, MEASURED, holes=HOLES, register="translation", calibrate=t / "py.xml",
                           json_out=t / "py.json")
        cli_json = (t / "cli.json").read_bytes()
        self.assertEqual(cli_json, (t / "c.json").read_bytes())
        self.assertEqual(cli_json, (t / "py.json").read_bytes())
        self.assertEqual((t / "cli.xml").read_bytes(), (t / "c.xml").read_bytes())
        self.assertEqual((t / "cli.xml").read_bytes(), (t / "py.xml").read_bytes())
        doc = json.loads(cli_json)
        self.assertEqual(py.pop("written"), [str(t / "py.json"), str(t / "py.xml")])
        close(py, doc, "python vs CLI")
        s = json.loads(summary)
        self.assertEqual(s["holes"], doc["summary"]["holes"])
        close(s["rms_residual_um"], doc["summary"]["residual_um"]["rms"], "rms residual")
        close(s["explained"], doc["summary"]["explained"], "explained")
        close(s["identification"]["joints"], doc["identification"]["joints"], "joints")
        self.assertGreater(doc["summary"]["explained"], 0.0)

    def test_calibration_date_identify_and_folds_alike_in_cli_c_python(self):
        # the geometry test part of README's loop, calibrated with the geometry alone
        t, v = self.tmp, SRC / "samples" / "verification"
        prog, holes, measured = v / "geometry_kr120.src", v / "geometry_kr120_holes.csv", v / "measured_geometry.csv"
        r = cli("verify", "--cell", CELL, prog, "--holes", holes, "--measured", measured, "--register", "none",
                "--calibrate", t / "cli.xml", "--json", t / "cli.json", "--quiet", "--identify", "geometry",
                "--date", "2025-03-04", "--folds", "3")
        self.assertEqual(r.returncode, 0, r.stderr)
        rc, _, err = C().verify_ex(prog, measured, "none", t / "c.json", t / "c.xml",
                                   {"holes": holes, "identify": "geometry", "date": "2025-03-04", "folds": "3"})
        self.assertEqual(rc, 0, err)
        py = roprec.verify(CELL, prog, measured, holes=holes, register="none", calibrate=t / "py.xml",
                           json_out=t / "py.json", identify="geometry", date="2025-03-04", folds=3)
        card = (t / "cli.xml").read_bytes()
        self.assertEqual(card, (t / "c.xml").read_bytes())
        self.assertEqual(card, (t / "py.xml").read_bytes())
        self.assertEqual((t / "cli.json").read_bytes(), (t / "py.json").read_bytes())
        self.assertEqual((t / "cli.json").read_bytes(), (t / "c.json").read_bytes())
        self.assertIn(b'date="2025-03-04"', card)
        ident = py["identification"]
        self.assertEqual(ident["validation"]["folds"], 3)
        # identify="geometry": the joint compliances keep the card's values
        self.assertEqual([p["identifiable"] for p in ident["parameters"][:6]], [False] * 6)
        self.assertTrue(any(p["identifiable"] for p in ident["parameters"] if p["name"].startswith("j2_")))
        # the defaults (identify all, 5 folds, the date rule) give another card
        roprec.verify(CELL, prog, measured, holes=holes, calibrate=t / "all.xml", date="2024-12-31")
        self.assertIn(b'date="2024-12-31"', (t / "all.xml").read_bytes())
        for bad in ({"identify": "everything"}, {"date": "4 March 2025"}, {"folds": 101}):
            with self.assertRaises(roprec.UsageError):
                roprec.verify(CELL, prog, measured, holes=holes, calibrate=t / "x.xml", **bad)
        self.assertFalse((t / "x.xml").exists())

    def test_a_card_no_better_on_held_out_holes_is_refused_and_a_residual_above_the_noise_exits_1(self):
        t = self.tmp
        # holes "drilled" exactly as the card predicts (+ 5 um noise): a geometry fitted to them fits
        # the noise, the cross-validation finds it worse than the card, and it is not written
        r = cli("predict", "--cell", CELL, PROGRAM, "--holes", HOLES, "--quiet", "--json", t / "p.json")
        self.assertEqual(r.returncode, 0, r.stderr)
        wobj = (1350.0, 0.0, 300.0)  # samples/cells/housing-kr120.xml, axes = the base's
        rng = random.Random(5)
        lines = ["id,x,y,z"]
        for h in json.loads((t / "p.json").read_text())["holes"]:
            p = [h["nominal"]["position_mm"][a] - wobj[a] + h["deviation_um"]["work"][a] * 1e-3 + rng.gauss(0, 0.005)
                 for a in range(3)]
            lines.append("%s,%.4f,%.4f,%.4f" % (h["id"], p[0], p[1], p[2]))
        (t / "self.csv").write_text("\n".join(lines) + "\n")
        r = cli("verify", "--cell", CELL, PROGRAM, "--holes", HOLES, "--measured", t / "self.csv", "--register", "none",
                "--identify", "geometry", "--calibrate", t / "cli.xml", "--write-cell", t / "cell.xml", "--date",
                "2026-01-01")
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
        self.assertIn("the calibrated card is not written", r.stderr)
        self.assertFalse((t / "cli.xml").exists() or (t / "cell.xml").exists())
        py = roprec.verify(CELL, PROGRAM, t / "self.csv", holes=HOLES, calibrate=t / "py.xml", identify="geometry",
                           date="2026-01-01")
        self.assertEqual(py["written"], [])
        self.assertIn("not below the original card", py["identification"]["card_refused"])
        self.assertFalse(py["identification"]["validation"]["better"])
        # the shipped held-out holes come from a truth with geometric errors: the joint stiffness alone
        # cannot explain them, the χ² check says so and the run exits 1 (Python: fit_check.consistent)
        r = cli("verify", "--cell", CELL, PROGRAM, "--holes", HOLES, "--measured", MEASURED, "--register", "none",
                "--identify", "stiffness", "--calibrate", t / "k.xml", "--date", "2026-01-01")
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
        self.assertIn("times the measurement σ", r.stderr)
        py = roprec.verify(CELL, PROGRAM, MEASURED, holes=HOLES, calibrate=t / "k2.xml", identify="stiffness",
                           date="2026-01-01")
        self.assertFalse(py["identification"]["fit_check"]["consistent"])
        self.assertGreater(py["identification"]["fit_check"]["rms_normalized"], 2.0)

    def test_plan_test_names_what_one_drilling_direction_leaves_unobservable(self):
        # planning for geometry + compliances + registration: one drilling direction leaves more of
        # the robot unobservable (named in the warning) than three directions with two rotations about
        # the drill axis; both print the expected σ per group and the accuracy before -> after
        def plan(directions, psi):
            r = cli("plan-test", "--cell", CELL, "--region", "-200 -200 0 200 200 300", "--directions", directions,
                    "--psi", psi, "--per-axis", 3, "--count", 20, "--register", "rigid", "-o", self.tmp / "p.csv")
            self.assertEqual(r.returncode, 0, r.stderr)
            m = re.search(r"leave (\d+) robot parameters unobservable \(they keep their prior\): ([^;]*);", r.stderr)
            self.assertIsNotNone(m, r.stderr)
            self.assertIn("expected geometry uncertainty", r.stdout)
            self.assertIn("expected joint stiffness uncertainty", r.stdout)
            acc = re.search(r"predicted accuracy .*: ([0-9.]+) µm before calibration -> ([0-9.]+) µm after", r.stdout)
            self.assertIsNotNone(acc, r.stdout)
            self.assertLess(float(acc.group(2)), 0.01 * float(acc.group(1)))
            return int(m.group(1)), m.group(2).split(", ")
        one, names_one = plan("0 0 -1", "0")
        three, names_three = plan("0 0 -1, 0 1 0, 0.7071 0 -0.7071", "0 90")
        self.assertEqual(one, len(names_one))
        self.assertGreater(one, three)
        self.assertIn("j1_x", names_three)  # joint 1's origin is the registration's, whatever the plan
        self.assertTrue(set(names_three) <= set(names_one), (names_one, names_three))

    def test_tracker_poses_may_name_the_programs_targets_instead_of_joints(self):
        # the same tracker poses given once with the commanded joints and once as the program's
        # targets (j1..j6 empty): the same observations, the same fit; a known tracker offset is
        # recovered (as VerifyCli.PosesAloneCalibrateAndRecoverATrackerOffset)
        t = self.tmp
        r = cli("predict", "--cell", CELL, PROGRAM, "--holes", HOLES, "--quiet", "--json", t / "p.json")
        self.assertEqual(r.returncode, 0, r.stderr)
        wobj, offset = (1350.0, 0.0, 300.0), (0.120, -0.080, 0.060)  # mm
        with_joints, targets = ["id,j1,j2,j3,j4,j5,j6,x,y,z"], ["id,j1,j2,j3,j4,j5,j6,x,y,z"]
        for h in json.loads((t / "p.json").read_text())["holes"]:
            xyz = ",".join("%.4f" % (h["nominal"]["position_mm"][a] - wobj[a] + offset[a]) for a in range(3))
            with_joints.append(h["id"] + "," + ",".join("%.9f" % q for q in h["controller_joints_deg"]) + "," + xyz)
            targets.append(h["id"] + ",,,,,," + "," + xyz)
        (t / "joints.csv").write_text("\n".join(with_joints) + "\n")
        (t / "targets.csv").write_text("\n".join(targets) + "\n")
        common = ("--register", "translation", "--identify", "stiffness", "--quiet")
        a = cli("verify", "--cell", CELL, "--poses", t / "joints.csv", "--json", t / "a.json", *common)
        self.assertEqual(a.returncode, 0, a.stderr)
        b = cli("verify", "--cell", CELL, PROGRAM, "--holes", HOLES, "--poses", t / "targets.csv", "--json",
                t / "b.json", *common)
        self.assertEqual(b.returncode, 0, b.stderr)
        ja, jb = (json.loads((t / f).read_text()) for f in ("a.json", "b.json"))
        self.assertEqual(jb["poses"]["count"], len(targets) - 1)
        # (the predict JSON's joints have 6 decimals: 1e-6 deg moves the TCP by some 10 nm)
        for pa, pb in zip(ja["identification"]["parameters"], jb["identification"]["parameters"]):
            self.assertEqual(pa["name"], pb["name"])
            tol = 1e-8 if pa["unit"] == "m" else 1e-4 * abs(pa["value"])
            self.assertLessEqual(abs(pa["value"] - pb["value"]), tol, pa["name"])
        tb = jb["registration"]["translation_um"]
        self.assertLessEqual(math.dist(tb, [1e3 * o for o in offset]), 5.0, tb)
        # an id that names no target of the program, and target rows without a program: exit 2 at the line
        (t / "bad.csv").write_text(targets[0] + "\n" + targets[1] + "\nNOPE,,,,,,,1,2,3\n")
        r = cli("verify", "--cell", CELL, PROGRAM, "--holes", HOLES, "--poses", t / "bad.csv")
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("bad.csv:3:", r.stderr)
        self.assertIn("names no target", r.stderr)
        r = cli("verify", "--cell", CELL, "--poses", t / "targets.csv")
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("targets.csv:2:", r.stderr)

    def test_bad_measured_file_is_an_input_error_everywhere(self):
        bad = self.tmp / "bad.csv"
        bad.write_text("id,x,y\nH1,1,2\n")
        with self.assertRaises(roprec.InputError) as e:
            roprec.verify(CELL, PROGRAM, bad, holes=HOLES, json_out=self.tmp / "x.json")
        self.assertIn("bad.csv:", str(e.exception))
        rc, _, err = C().verify(bad, None, self.tmp / "y.json", None)
        self.assertEqual(rc, 2)
        self.assertEqual(err, str(e.exception))
        self.assertFalse((self.tmp / "x.json").exists() or (self.tmp / "y.json").exists())

    def test_plan_test_cli_c_python_identical(self):
        region = (-150, -150, 200, 150, 150, 230)
        r = cli("plan-test", "--cell", CELL, "--region", " ".join(str(v) for v in region), "--count", 8,
                "-o", self.tmp / "cli.csv", "--quiet")
        self.assertEqual(r.returncode, 0, r.stderr)
        rc, summary, err = C().plan_test(region, 8, self.tmp / "c.csv")
        self.assertEqual(rc, 0, err)
        py = roprec.plan_test(CELL, region, 8, self.tmp / "py.csv")
        rows = lambda f: [l for l in (self.tmp / f).read_text().splitlines() if not l.startswith("#")]
        self.assertEqual(rows("cli.csv"), rows("c.csv"))
        self.assertEqual(rows("cli.csv"), rows("py.csv"))
        self.assertEqual(len(rows("cli.csv")), 9)
        s = json.loads(summary)
        self.assertEqual(py["holes"], 8)
        py.pop("written")
        s.pop("written")
        close(py, s, "plan_test python vs C")


if __name__ == "__main__":
    unittest.main()
