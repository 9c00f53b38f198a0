#!/usr/bin/env python3
"""A generated KUKA KRL drilling job for the benchmark scripts: N OLP-style drill cycles (approach,
feed, dwell, retract) on a 1.2 mm grid centred on the e-motor housing's top face (z = 250) of the
KR 120 sample cell (samples/cells/housing-kr120.xml), like samples/emotor-housing/housing_kr120.src.
About 367 bytes a hole: 300,000 holes make a 110 MB program.

    python3 scripts/gen-drill-job.py N OUT.src
"""
import math
import sys

n, path = int(sys.argv[1]), sys.argv[2]
cols = int(math.ceil(math.sqrt(n * 1.2)))  # a 1.2 mm grid centred on the top face (z = 250)
x0, y0 = -0.6 * (cols - 1), -0.6 * (int(math.ceil(n / cols)) - 1)
name = "bench_%d" % n
with open(path, "w") as f:
    f.write("&ACCESS RVP\n&REL 1\n&COMMENT roprec bench-cli job\nDEF %s ( )\n" % name)
    f.write(";FOLD INI\nBAS (#INITMOV,0 )\n;ENDFOLD (INI)\n\n")
    f.write("$BASE = {FRAME: X 1350.000,Y 0.000,Z 300.000,A 0.000,B 0.000,C 0.000}\n")
    f.write("$TOOL = {FRAME: X 0.000,Y 0.000,Z 320.000,A 0.000,B 0.000,C 0.000}\n")
    f.write("SPINDLE_ON()\n")
    for k in range(n):
        x = x0 + 1.2 * (k % cols)
        y = y0 + 1.2 * (k // cols)
        p = "X %.3f,Y %.3f,Z %%.3f,A 0.000,B 0.000,C 180.000" % (x, y)
        f.write("; B%06d drill D6.8 depth 16.0\n$VEL.CP = 0.25000\n" % (k + 1))
        f.write("PTP {" + p % 300.0 + "} C_PTP\n")
        f.write("LIN {" + p % 252.0 + "} C_DIS\n$VEL.CP = 0.02000\n")
        f.write("LIN {" + p % 234.0 + "}\nWAIT SEC 0.3\n$VEL.CP = 0.25000\n")
        f.write("LIN {" + p % 300.0 + "} C_DIS\n")
    f.write("SPINDLE_OFF()\nEND\n")
