#!/usr/bin/env python3
"""The shop-floor loop of README on the shipped sample (samples/verification/), through the CLI.

Proves: (0) the shipped test programs (.src, .dat) are byte for byte what `plan-test` writes today
with README's arguments; (1) the shipped measured files are what the truth robot drills from the shipped programs
(make_measured.py --drill, same noise and seed: identical data rows); (2) calibrating on the
geometry test part (verify --calibrate --write-cell), compensating the held-out test program
with the written cell and drilling it with the truth leaves <= 25 um RMS (and <= 5 % of the
uncompensated error) perpendicular to the nominal hole axes of the held-out holes.

Usage: shop_floor_loop_test.py ROPREC_BIN SOURCE_DIR
"""

import csv
import math
import os
import subprocess
import sys
import tempfile


def rows(path):
    with open(path, encoding="utf-8") as f:
        return [line for line in f if not line.startswith("#")]


def table(path):
    return {r["id"]: r for r in csv.DictReader(rows(path))}


def rms_perp_um(holes_csv, measured_csv):
    holes, meas = table(holes_csv), table(measured_csv)
    s = 0.0
    for k, h in holes.items():
        d = [float(meas[k][c]) - float(h[c]) for c in "xyz"]
        a = [float(h[c]) for c in "ijk"]
        dot = sum(x * y for x, y in zip(d, a))
        s += sum((x - dot * y) ** 2 for x, y in zip(d, a))
    return math.sqrt(s / len(holes)) * 1000.0


# README's shop-floor loop, step 1: the arguments that plan the shipped test programs.
PLANS = {
    "geometry_kr120.src": ["--region", "-200 -200 0 200 200 300", "--directions", "0 0 -1, 0 1 0, 0 -1 0, 1 0 0",
                           "--psi", "0 90", "--per-axis", "4", "--count", "40", "--register", "rigid"],
    "test_kr120.src": ["--region", "-200 -200 100 200 200 230", "--directions", "0 0 -1, 0 1 0, 0 -1 0, 1 0 0",
                       "--per-axis", "3", "--count", "24", "--identify", "stiffness"],
}


def replanned_differences(roprec, src, v, tmp):
    """The shipped program files that plan-test no longer writes byte for byte."""
    out = []
    for prog, args in PLANS.items():
        dest = os.path.join(tmp, prog)
        subprocess.run([roprec, "plan-test", "--cell", os.path.join(src, "samples", "cells", "housing-kr120.xml")] +
                       args + ["-o", dest, "--quiet"], check=True, cwd=tmp, stdout=subprocess.DEVNULL)
        for name in (prog, prog[:-4] + ".dat"):
            with open(os.path.join(tmp, name), "rb") as a, open(os.path.join(v, name), "rb") as b:
                if a.read() != b.read():
                    out.append("samples/verification/%s is not what plan-test writes today (regenerate it "
                               "with README's shop-floor step 1)" % name)
    return out


def main():
    roprec, src = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    v = os.path.join(src, "samples", "verification")
    make = [sys.executable, os.path.join(v, "make_measured.py"), roprec]
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        failures += replanned_differences(roprec, src, v, tmp)
        for prog, shipped in (("test_kr120.src", "measured.csv"), ("geometry_kr120.src", "measured_geometry.csv")):
            out = os.path.join(tmp, shipped)
            subprocess.run(make + ["--drill", os.path.join(v, prog), out], check=True, cwd=src,
                           stdout=subprocess.DEVNULL)
            if rows(out) != rows(os.path.join(v, shipped)):
                failures.append("%s is not what the truth robot drills from %s" % (shipped, prog))
        card, cell = os.path.join(tmp, "kr120-cal.xml"), os.path.join(tmp, "cell.xml")
        subprocess.run([roprec, "verify", "--cell", os.path.join(src, "samples", "cells", "housing-kr120.xml"),
                        os.path.join(v, "geometry_kr120.src"), "--holes", os.path.join(v, "geometry_kr120_holes.csv"),
                        "--measured", os.path.join(v, "measured_geometry.csv"), "--register", "rigid",
                        "--calibrate", card, "--write-cell", cell, "--quiet"], check=True, cwd=src)
        comp = os.path.join(tmp, "test_kr120_comp.src")
        subprocess.run([roprec, "compensate", "--cell", cell, os.path.join(v, "test_kr120.src"), "-o", comp,
                        "--quiet"], check=True, cwd=src)
        drilled = os.path.join(tmp, "measured_comp.csv")
        subprocess.run(make + ["--drill", comp, drilled, cell], check=True, cwd=src, stdout=subprocess.DEVNULL)
        holes = os.path.join(v, "test_kr120_holes.csv")
        before, after = rms_perp_um(holes, os.path.join(v, "measured.csv")), rms_perp_um(holes, drilled)
        print("held-out holes, RMS perpendicular to the nominal axes: before %.1f um, after %.1f um" % (before, after))
        if before < 500.0:
            failures.append("the truth robot's uncompensated error %.1f um is not that of an uncalibrated robot" % before)
        if not (after <= 25.0 and after <= 0.05 * before):
            failures.append("the loop leaves %.1f um of %.1f um" % (after, before))
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
