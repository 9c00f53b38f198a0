#!/usr/bin/env python3
"""Makes samples/verification/measured.csv: the "CMM result" of the verification sample.

Usage: samples/verification/make_measured.py build/bin/roprec
       samples/verification/make_measured.py build/bin/roprec --drill PROGRAM OUT.csv [CELL]

The second form "drills" another program of the same holes (e.g. the compensated test program)
with the truth robot and writes its CMM result the same way (same offset, noise and seed), for the
second round of the loop in README. CELL is the cell the program was compensated for: its
``<workobject>`` is the base frame the controller is given with a program that takes its base from
the cell (``verify --write-cell`` keeps it and states where the part was found as the cell's
``<part_registration>``, which only roprec's compensation reads); the part itself stays where it is.

How the file is made (deterministic: running it again gives identical bytes):

1. The test program ``test_kr120.src`` (+ ``.dat``) was planned by roprec itself for the sample cell
   samples/cells/housing-kr120.xml (KUKA KR 120 R2500 pro, bundled card)::

       roprec plan-test --cell samples/cells/housing-kr120.xml --region "-200 -200 100 200 200 230" \\
              --directions "0 0 -1, 0 1 0, 0 -1 0, 1 0 0" --per-axis 3 --count 24 --identify stiffness \\
              -o samples/verification/test_kr120.src

   This script re-runs that command first, so the files always belong together. roprec's KRL
   reader names the recognised drill holes H1, H2, … in program order; the drill points are named
   V01, V02, … and the measured file and the hole list use those names (so ``roprec verify`` is
   given the hole list: ``--holes test_kr120_holes.csv`` matches the holes by these names).
2. The part is "drilled" by a TRUTH ROBOT: ``truth-kr120.xml`` is the bundled KR 120 card (same
   URDF, inertials, balancer and mastering pose) with other joint stiffness: the main axes 0.6 x
   the card's class value (Jiao et al., Chinese J. Mech. Eng. 35:115 (2022), Eq. (38), KUKA KR500)
   and the wrist from the same paper's grid-cell-1 set (Eq. (39)): k1..k6 = 9.48e6, 3.672e6,
   3.168e6, 3.38e5, 1.2e5, 2.17e5 N·m/rad, against the card's 1.58e7, 6.12e6, 5.28e6, 4.66e5,
   2.19e5, 3.49e5.
   The truth also has GEOMETRIC errors (its ``<calibration>`` block: joint origins 0.1-0.35 mm,
   tilts and zero offsets 0.17-0.61 mrad), so predict computes its real TCPs by FK_real of the
   joint angles the controller reaches with the card's nominal URDF.
   ``truth-cell.xml`` is the sample cell with that card. ``roprec predict --cell truth-cell.xml
   test_kr120.src`` gives the truth's real drill point of every hole: the programmed drill point
   (base frame) + δwork (gravity, the 25.8 kg spindle, the drilling thrust, δmach, the
   gravity-compensating controller of the cell — everything roprec models, with the truth's
   stiffness).
3. The real points are taken to the cell's workobject frame (xyz 1350 0 300 mm, rpy 0), the part is
   assumed to sit on its fixture shifted by FIXTURE_OFFSET_MM (a small fixture offset, workobject
   axes), and every coordinate gets Gaussian noise of NOISE_UM (5 µm) standard deviation from
   Python's Mersenne Twister seeded with SEED (Box–Muller on random.random(), which is the same on
   every Python 3). Positions are printed in mm with 4 decimals; u = 5 µm per axis.
5. The geometry test part ``geometry_kr120.src`` (40 holes planned for the geometry, the
   compliances and the registration together, GEO_PLAN) is made the same way: its CMM result
   ``measured_geometry.csv`` and its hole list ``geometry_kr120_holes.csv``.
4. ``test_kr120_holes.csv`` is the hole list of the test program: the nominal holes (drill points
   and drilling directions, workobject frame, ids V01…), for verifying the program, and a
   compensated version of it, against the nominal holes (``roprec verify --holes``).
"""

import json
import math
import os
import random
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
CELL = os.path.join(ROOT, "samples", "cells", "housing-kr120.xml")
TRUTH_CELL = os.path.join(HERE, "truth-cell.xml")
PROGRAM = os.path.join(HERE, "test_kr120.src")
OUT = os.path.join(HERE, "measured.csv")
HOLES = os.path.join(HERE, "test_kr120_holes.csv")
GEO_PROGRAM = os.path.join(HERE, "geometry_kr120.src")
GEO_OUT = os.path.join(HERE, "measured_geometry.csv")
GEO_HOLES = os.path.join(HERE, "geometry_kr120_holes.csv")
WOBJ_MM = (1350.0, 0.0, 300.0)  # the cell's <workobject xyz>, rpy 0
FIXTURE_OFFSET_MM = (0.040, -0.025, 0.030)
NOISE_UM = 5.0
SEED = 11
PLAN = ["--cell", CELL, "--region", "-200 -200 100 200 200 230",
        "--directions", "0 0 -1, 0 1 0, 0 -1 0, 1 0 0", "--per-axis", "3", "--count", "24",
        "--identify", "stiffness"]
GEO_PLAN = ["--cell", CELL, "--region", "-200 -200 0 200 200 300",
            "--directions", "0 0 -1, 0 1 0, 0 -1 0, 1 0 0", "--psi", "0 90", "--per-axis", "4",
            "--count", "40", "--register", "rigid"]


def run(roprec, *args):
    subprocess.run([roprec, *args], check=True, stdout=subprocess.DEVNULL)


def gauss(rng):
    u1 = rng.random()
    u2 = rng.random()
    return math.sqrt(-2.0 * math.log(1.0 - u1)) * math.cos(2.0 * math.pi * u2)


def truth_cell(tmp, cell):
    """The truth cell, with the <workobject> (the controller's base frame) of `cell` if given."""
    if cell is None:
        return TRUTH_CELL
    with open(cell, encoding="utf-8") as f:
        wobj = re.search(r"<workobject [^>]*/>", f.read()).group(0)
    with open(TRUTH_CELL, encoding="utf-8") as f:
        text = f.read()
    text = re.sub(r"<workobject [^>]*/>", lambda _: wobj, text, count=1)
    text = text.replace('file="truth-kr120.xml"', 'file="%s"' % os.path.join(HERE, "truth-kr120.xml"))
    path = os.path.join(tmp, "truth-cell.xml")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    return path


def truth_holes(roprec, program, hole_list=None, cell=None):
    with tempfile.TemporaryDirectory() as tmp:
        js = os.path.join(tmp, "truth.json")
        extra = ["--holes", hole_list] if hole_list else []
        run(roprec, "predict", "--cell", truth_cell(tmp, cell), program, *extra, "--json", js, "--quiet")
        with open(js, encoding="utf-8") as f:
            return json.load(f)["holes"]


def write_measured(holes, out, program):
    rng = random.Random(SEED)
    lines = ["# CMM result of %s drilled by the truth robot truth-kr120.xml" % program,
             "# made by samples/verification/make_measured.py (see its docstring): workobject frame, mm;",
             "# fixture offset %.3f %.3f %.3f mm, Gaussian noise %.1f um per axis, seed %d; u in um"
             % (*FIXTURE_OFFSET_MM, NOISE_UM, SEED),
             "id,x,y,z,u"]
    for h in holes:
        p = h["nominal"]["position_mm"]
        d = h["deviation_um"]["work"]
        xyz = []
        for k in range(3):
            real = p[k] + d[k] * 1e-3 - WOBJ_MM[k]
            xyz.append(real + FIXTURE_OFFSET_MM[k] + NOISE_UM * 1e-3 * gauss(rng))
        lines.append("%s,%.4f,%.4f,%.4f,%.1f" % (h["id"], xyz[0], xyz[1], xyz[2], NOISE_UM))
    with open(out, "w", encoding="utf-8", newline="\n") as f:
        f.write("\n".join(lines) + "\n")


def write_hole_list(holes, program, path):
    lines = ["# nominal holes of samples/verification/%s (drill points), workobject frame, mm;"
             " made by make_measured.py" % program,
             "id,x,y,z,i,j,k,diameter,depth,tolerance"]
    for h in holes:
        p = [h["nominal"]["position_mm"][k] - WOBJ_MM[k] for k in range(3)]
        a = h["nominal"]["axis"]
        lines.append("%s,%.6f,%.6f,%.6f,%.9f,%.9f,%.9f,%.3f,%.3f,0.20"
                     % (h["id"], *p, *a, h["diameter_mm"], 20.0))  # the cell's process depth
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        f.write("\n".join(lines) + "\n")


def main():
    roprec = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "bin", "roprec"))
    if len(sys.argv) in (5, 6) and sys.argv[2] == "--drill":
        program, out = os.path.abspath(sys.argv[3]), os.path.abspath(sys.argv[4])
        cell = os.path.abspath(sys.argv[5]) if len(sys.argv) == 6 else None
        hole_list = GEO_HOLES if os.path.basename(program).startswith("geometry_kr120") else HOLES
        write_measured(truth_holes(roprec, program, hole_list, cell), out, os.path.basename(program))
        print("wrote", out)
        return
    os.chdir(ROOT)  # the programs name their files relative to the source tree
    for plan, program, out, hole_list in ((PLAN, PROGRAM, OUT, HOLES),
                                          (GEO_PLAN, GEO_PROGRAM, GEO_OUT, GEO_HOLES)):
        run(roprec, "plan-test", *plan, "-o", os.path.relpath(program))
        holes = truth_holes(roprec, program)
        for h in holes:  # the planned points are V01, V02, ... in program order (roprec reads H1, H2, ...)
            h["id"] = "V%02d" % int(h["id"][1:])
        name = os.path.basename(program)
        write_measured(holes, out, "samples/verification/" + name)
        write_hole_list(holes, name, hole_list)
        print("wrote", os.path.relpath(out, ROOT), "(%d holes) and" % len(holes), os.path.relpath(hole_list, ROOT))


if __name__ == "__main__":
    main()
