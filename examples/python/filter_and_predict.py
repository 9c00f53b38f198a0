#!/usr/bin/env python3
"""filter_and_predict.py — roprec from Python on the sample job.

    python3 examples/python/filter_and_predict.py [SAMPLES_DIR]

1. Loads the cell samples/cells/housing-kr120.xml (KUKA KR 120 R2500 pro, 25.8 kg spindle, AlSi9Cu3
   drilling) and filters one target: hole T001 of the sample hole list (150, 0, 250 mm in the
   workobject, drilled along -z). Prints the pose to program, its joints, and checks that the
   predicted real TCP at those joints lands on the hole.
2. Predicts the sample KRL job (samples/emotor-housing/housing_kr120.src with holes.csv) and prints
   the verdict summary and the worst holes.

Needs the module on the path: PYTHONPATH=build/python (build tree) or P/lib/python3/dist-packages.
"""

import sys
from pathlib import Path

import numpy as np

import roprec


def fmt(values, decimals):
    return " ".join("%.*f" % (decimals, v) for v in values)


def main(argv):
    samples = Path(argv[1]) if len(argv) > 1 else Path(__file__).resolve().parents[2] / "samples"
    cell = samples / "cells" / "housing-kr120.xml"
    print("roprec", roprec.__version__)

    s = roprec.Session(cell)
    print("cell %s: robot %s, process %s" % (s.cell, s.robot, s.process))
    wanted = s.hole_pose([150.0, 0.0, 250.0], [0.0, 0.0, -1.0])   # T001, base frame, mm
    pose, joints = s.filter_target(wanted)
    print("wanted   x y z = %s mm" % fmt(wanted[:3, 3], 3))
    print("program  x y z = %s mm" % fmt(pose[:3, 3], 6))
    print("joints   %s deg" % fmt(joints, 4))
    p = s.predict_joints(joints)
    real = pose[:3, 3] + p["deviation_um"] * 1e-3
    miss_um = float(np.linalg.norm(real - wanted[:3, 3])) * 1e3
    print("deviation at those joints %s um, U_work %.1f um; real TCP misses the hole by %.6f um"
          % (fmt(p["deviation_um"], 3), p["U_work_um"], miss_um))

    job = roprec.predict(cell, samples / "emotor-housing" / "housing_kr120.src",
                         holes=samples / "emotor-housing" / "holes.csv")
    print("job: %d holes, verdicts %s, the robot can take %d" % (job.summary["holes"], job.summary["verdicts"],
                                                                  job.summary["robot_can_take"]))
    for h in sorted(job, key=lambda h: -(h["position_error_um"] or 0))[:3]:
        print("  %s: %s, error %.1f um, U_work %.1f um, joints %s (%s)"
              % (h["id"], h["verdict"], h["position_error_um"], h["U_work_um"],
                 fmt(h["controller_joints_deg"], 2), h["config"]))
    return 0 if miss_um < 0.1 and not job.failed else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
