"""`roprec verify` and `roprec plan-test`: the CLI, the C ABI (ctypes) and the Python
module give identical numbers on the shipped sample (samples/verification/): identical JSON and
card bytes, and every number of the summaries equal within 1e-9 relative.

Run by ctest with PYTHONPATH = the build tree's python/ folder, ROPREC_BIN = the CLI and
ROPREC_C_LIB = libroprec_c.so.
"""

import ctypes
import json
import os
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
