#!/usr/bin/env python3
"""Generates the e-motor housing sample job: a die-cast AlSi9Cu3 housing (Ø340 x 250 mm, axis
vertical) with 204 holes of four diameters on four faces, as

  holes.csv            the contract's hole list (workobject frame, mm)
  housing_kr120.src    KUKA KRL (KRC4 style: inline aggregates, $BASE/$TOOL set in the program)
  housing_kr120_tools.src  the same holes drilled tool by tool: TOOL_DATA[1..4] (one drill per
                       diameter, samples/cells/housing-kr120-tools.xml) selected by $TOOL
  housing_irb6640.mod  ABB RAPID (wobjdata/tooldata in the module, MoveJ/MoveL, inline robtargets)
  housing_r2000.ls     FANUC TP (/POS records in UFRAME 1 / UTOOL 1; the frame lives in the
                       controller, so roprec takes it from the cell's <workobject>)

The ABB confdata and FANUC CONFIG of every target are computed with roprec's own IK (the solution
nearest the previous hole's, like an OLP would choose), so the generator needs a built roprec:
  python3 samples/emotor-housing/make_samples.py build/bin/roprec
Every hole is an OLP-style drill cycle: approach 50 mm above the entry (joint move), rapid to
2 mm, feed to the bottom at the process feed, dwell, retract. TCP z = drilling direction; the
rotation about it follows roprec's hole-list rule (x = workobject x projected, or y near x).
Deterministic output; run again to regenerate:  python3 samples/emotor-housing/make_samples.py
"""
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))

# (workobject pose in each robot's base frame, mm / deg) -- must match samples/cells/*.xml
WOBJ = {
    "kuka": (1350.0, 0.0, 300.0),
    "abb": (1700.0, 0.0, 250.0),
    "fanuc": (1400.0, 0.0, 300.0 - 670.0),  # FANUC World is at J2 height (670 mm)
}
FEED_MM_S = 20.0      # 0.2 mm/rev x 6000 rpm
RAPID_MM_S = 250.0


def holes():
    out = []
    def add(hid, p, d, dia, depth, tol):
        out.append((hid, p, d, dia, depth, tol))
    n = 0
    # top face z = 250, drilled -z
    for k in range(24):   # cover bolt circle PCD 300, M8 tap drill 6.8
        a = 2 * math.pi * k / 24
        n += 1; add("T%03d" % n, (150 * math.cos(a), 150 * math.sin(a), 250.0), (0, 0, -1), 6.8, 16.0, 0.2)
    for k in range(12):   # coolant passages PCD 220, 10.2
        a = 2 * math.pi * (k + 0.5) / 12
        n += 1; add("T%03d" % n, (110 * math.cos(a), 110 * math.sin(a), 250.0), (0, 0, -1), 10.2, 30.0, 0.2)
    for k in range(12):   # bearing cover PCD 140, 8.5
        a = 2 * math.pi * k / 12
        n += 1; add("T%03d" % n, (70 * math.cos(a), 70 * math.sin(a), 250.0), (0, 0, -1), 8.5, 20.0, 0.15)
    for k in range(12):   # sensor flange PCD 60, 6.8
        a = 2 * math.pi * (k + 0.25) / 12
        n += 1; add("T%03d" % n, (30 * math.cos(a), 30 * math.sin(a), 250.0), (0, 0, -1), 6.8, 12.0, 0.15)
    # front chamfer pad (45 deg, facing the robot and up), drilled along (1, 0, -1)/sqrt2: mounting holes
    n = 0
    s2 = math.sqrt(0.5)
    for r in range(6):
        for c in range(8):
            n += 1
            dia = 12.0 if (r in (0, 5) and c in (0, 7)) else 8.5
            t = -50.0 + 20.0 * r  # along the pad's slope (up and inwards)
            add("F%03d" % n, (-140.0 + t * s2, -105.0 + 30.0 * c, 190.0 + t * s2), (s2, 0, -s2), dia, 24.0, 0.2)
    # right pad y = -170, drilled +y: fluid passages
    n = 0
    for r in range(6):
        for c in range(8):
            n += 1
            add("R%03d" % n, (-105.0 + 30.0 * c, -170.0, 40.0 + 35.0 * r), (0, 1, 0), 10.2, 30.0, 0.2)
    # left pad y = +170, drilled -y
    n = 0
    for r in range(6):
        for c in range(8):
            n += 1
            dia = 12.0 if c in (0, 7) else 6.8
            add("L%03d" % n, (-105.0 + 30.0 * c, 170.0, 40.0 + 35.0 * r), (0, -1, 0), dia, 18.0, 0.2)
    return out


def hole_frame(d):
    z = d
    ref = (1.0, 0.0, 0.0) if abs(z[0]) < 0.9 else (0.0, 1.0, 0.0)
    y = cross(z, ref); y = norm(y)
    x = cross(y, z)
    return [[x[0], y[0], z[0]], [x[1], y[1], z[1]], [x[2], y[2], z[2]]]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


def zyx(R):
    cb = math.hypot(R[0][0], R[1][0])
    b = math.atan2(-R[2][0], cb)
    if cb < 1e-9:
        return (math.degrees(math.atan2(-R[0][1], R[1][1])), math.degrees(b), 0.0)
    return (math.degrees(math.atan2(R[1][0], R[0][0])), math.degrees(b), math.degrees(math.atan2(R[2][1], R[2][2])))


def quat(R):
    t = R[0][0] + R[1][1] + R[2][2]
    if t > 0:
        w = 0.5 * math.sqrt(1 + t); x = (R[2][1] - R[1][2]) / (4 * w); y = (R[0][2] - R[2][0]) / (4 * w); z = (R[1][0] - R[0][1]) / (4 * w)
    elif R[0][0] >= R[1][1] and R[0][0] >= R[2][2]:
        x = 0.5 * math.sqrt(1 + R[0][0] - R[1][1] - R[2][2]); w = (R[2][1] - R[1][2]) / (4 * x); y = (R[0][1] + R[1][0]) / (4 * x); z = (R[0][2] + R[2][0]) / (4 * x)
    elif R[1][1] >= R[2][2]:
        y = 0.5 * math.sqrt(1 - R[0][0] + R[1][1] - R[2][2]); w = (R[0][2] - R[2][0]) / (4 * y); x = (R[0][1] + R[1][0]) / (4 * y); z = (R[1][2] + R[2][1]) / (4 * y)
    else:
        z = 0.5 * math.sqrt(1 - R[0][0] - R[1][1] + R[2][2]); w = (R[1][0] - R[0][1]) / (4 * z); x = (R[0][2] + R[2][0]) / (4 * z); y = (R[1][2] + R[2][1]) / (4 * z)
    if w < 0:
        w, x, y, z = -w, -x, -y, -z
    return (w, x, y, z)


ROBOT = {"abb": ("abb-irb6640-185-280", "housing-irb6640.xml"), "fanuc": ("fanuc-r2000ic-165f", "housing-r2000.xml")}


def configs(roprec, vendor, hs):
    """Vendor configuration string per hole (at its drill point), continuity from hole to hole."""
    name, cell = ROBOT[vendor]
    cell = os.path.join(HERE, "..", "cells", cell)
    wx, wy, wz = WOBJ[vendor]
    seed = None
    out = []
    for hid, p, d, dia, depth, tol in hs:
        q = quat(hole_frame(d))
        pose = "%f %f %f %.12f %.12f %.12f %.12f" % (wx + p[0] + depth * d[0], wy + p[1] + depth * d[1],
                                                     wz + p[2] + depth * d[2], q[0], q[1], q[2], q[3])
        cmd = [roprec, "ik", "--robot", name, "--cell", cell, "--pose", pose]
        if seed:
            cmd += ["--seed", " ".join("%f" % v for v in seed)]
        r = subprocess.run(cmd, capture_output=True, text=True)
        sols = [x for x in json.loads(r.stdout)["solutions"] if x["within_limits"] and x["converged"]
                and not any(x["singular"][k] for k in ("wrist", "shoulder", "elbow"))] if r.stdout else []
        if not sols:
            raise SystemExit("hole %s unreachable for %s" % (hid, name))
        ref = seed or sols[0]["joints_deg"]
        w = (1, 1, 1, 0.5, 0.5, 0.3)
        best = min(sols, key=lambda x: sum(wi * (a - b) ** 2 for wi, a, b in zip(w, x["joints_deg"], ref)))
        seed = best["joints_deg"]
        out.append(best["config"])
    return out


def cycle_points(p, d, depth):
    """approach +50, entry +2, bottom -depth (along the drilling direction d)."""
    return [tuple(p[i] - 50.0 * d[i] for i in range(3)), tuple(p[i] - 2.0 * d[i] for i in range(3)),
            tuple(p[i] + depth * d[i] for i in range(3))]


def fd(v):
    return "%d" % v if v == int(v) else "%.9f" % v


def f3(v):
    s = "%.3f" % v
    return "0.000" if s == "-0.000" else s


def write(path, text, crlf=False):
    data = text.replace("\n", "\r\n") if crlf else text
    with open(os.path.join(HERE, path), "w", newline="") as f:
        f.write(data)


def krl(hs):
    L = ["&ACCESS RVP", "&REL 1", "&COMMENT e-motor housing drilling (roprec sample)", "DEF housing_kr120 ( )",
         ";FOLD INI", "BAS (#INITMOV,0 )", ";ENDFOLD (INI)", "",
         "; workobject = housing fixture; tool = spindle with drill (TCP at the drill tip)",
         "$BASE = {FRAME: X %s,Y %s,Z %s,A 0.000,B 0.000,C 0.000}" % tuple(f3(v) for v in WOBJ["kuka"]),
         "$TOOL = {FRAME: X 0.000,Y 0.000,Z 320.000,A 0.000,B 0.000,C 0.000}", "SPINDLE_ON()"]
    for hid, p, d, dia, depth, tol in hs:
        a, b, c = zyx(hole_frame(d))
        pts = cycle_points(p, d, depth)
        agg = lambda q: "{X %s,Y %s,Z %s,A %s,B %s,C %s}" % (f3(q[0]), f3(q[1]), f3(q[2]), f3(a), f3(b), f3(c))
        L += ["; %s drill D%.1f depth %.1f" % (hid, dia, depth), "$VEL.CP = %.5f" % (RAPID_MM_S / 1000),
              "PTP %s C_PTP" % agg(pts[0]), "LIN %s C_DIS" % agg(pts[1]),
              "$VEL.CP = %.5f" % (FEED_MM_S / 1000), "LIN %s" % agg(pts[2]), "WAIT SEC 0.3",
              "$VEL.CP = %.5f" % (RAPID_MM_S / 1000), "LIN %s C_DIS" % agg(pts[0])]
    L += ["SPINDLE_OFF()", "END", ""]
    write("housing_kr120.src", "\n".join(L), crlf=True)


# tool number of each diameter: samples/cells/housing-kr120-tools.xml's tool table
TOOLS = {6.8: 1, 8.5: 2, 10.2: 3, 12.0: 4}


def krl_tools(hs):
    """The KRL job drilled tool by tool (a tool change per diameter), each tool's holes in the
    hole list's order; TOOL_DATA[n] defined in the program (the spindle's TCP: one TCP per job)."""
    L = ["&ACCESS RVP", "&REL 1", "&COMMENT e-motor housing drilled tool by tool (roprec sample)",
         "DEF housing_kr120_tools ( )", ";FOLD INI", "BAS (#INITMOV,0 )", ";ENDFOLD (INI)", "",
         "; workobject = housing fixture; tools 1..4 = drills D6.8, D8.5, D10.2, D12 in the spindle",
         "$BASE = {FRAME: X %s,Y %s,Z %s,A 0.000,B 0.000,C 0.000}" % tuple(f3(v) for v in WOBJ["kuka"])]
    for dia, n in sorted(TOOLS.items(), key=lambda kv: kv[1]):
        L.append("TOOL_DATA[%d] = {X 0.000,Y 0.000,Z 320.000,A 0.000,B 0.000,C 0.000} ; D%.1f" % (n, dia))
    for dia, n in sorted(TOOLS.items(), key=lambda kv: kv[1]):
        L += ["; tool change: tool %d, drill D%.1f" % (n, dia), "SPINDLE_OFF()", "$TOOL = TOOL_DATA[%d]" % n,
              "SPINDLE_ON()"]
        for hid, p, d, hdia, depth, tol in hs:
            if hdia != dia:
                continue
            a, b, c = zyx(hole_frame(d))
            pts = cycle_points(p, d, depth)
            agg = lambda q: "{X %s,Y %s,Z %s,A %s,B %s,C %s}" % (f3(q[0]), f3(q[1]), f3(q[2]), f3(a), f3(b), f3(c))
            L += ["; %s drill D%.1f depth %.1f" % (hid, hdia, depth), "$VEL.CP = %.5f" % (RAPID_MM_S / 1000),
                  "PTP %s C_PTP" % agg(pts[0]), "LIN %s C_DIS" % agg(pts[1]),
                  "$VEL.CP = %.5f" % (FEED_MM_S / 1000), "LIN %s" % agg(pts[2]), "WAIT SEC 0.3",
                  "$VEL.CP = %.5f" % (RAPID_MM_S / 1000), "LIN %s C_DIS" % agg(pts[0])]
    L += ["SPINDLE_OFF()", "END", ""]
    write("housing_kr120_tools.src", "\n".join(L), crlf=True)


def rapid(hs, cfgs):
    L = ["MODULE housing_irb6640", "  ! e-motor housing drilling (roprec sample)",
         "  PERS tooldata tSpindle:=[TRUE,[[0,0,320],[1,0,0,0]],[25.8,[0,0,120],[1,0,0,0],0.35,0.33,0.08]];",
         "  PERS wobjdata wHousing:=[FALSE,TRUE,\"\",[[%s,%s,%s],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];" % tuple(f3(v) for v in WOBJ["abb"]),
         "  CONST speeddata vFeed:=[%.1f,500,5000,1000];" % FEED_MM_S, "",
         "  PROC main()", "    ConfJ \\On;", "    ConfL \\Off;"]
    for (hid, p, d, dia, depth, tol), cf in zip(hs, cfgs):
        q = quat(hole_frame(d))
        pts = cycle_points(p, d, depth)
        q = tuple(0.0 if abs(c) < 5e-10 else c for c in q)
        rt = lambda v: "[[%s,%s,%s],[%.9f,%.9f,%.9f,%.9f],%s,[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]]" % (
            f3(v[0]), f3(v[1]), f3(v[2]), q[0], q[1], q[2], q[3], cf)
        L += ["    ! %s drill D%.1f depth %.1f" % (hid, dia, depth),
              "    MoveJ %s,v1000,z10,tSpindle\\WObj:=wHousing;" % rt(pts[0]),
              "    MoveL %s,v250,z1,tSpindle\\WObj:=wHousing;" % rt(pts[1]),
              "    MoveL %s,vFeed,fine,tSpindle\\WObj:=wHousing;" % rt(pts[2]),
              "    WaitTime 0.3;",
              "    MoveL %s,v250,z10,tSpindle\\WObj:=wHousing;" % rt(pts[0])]
    L += ["  ENDPROC", "ENDMODULE", ""]
    write("housing_irb6640.mod", "\n".join(L))


def tp(hs, cfgs):
    mn = []
    pos = []
    n = 0
    for (hid, p, d, dia, depth, tol), cf in zip(hs, cfgs):
        w, pp, r = zyx(hole_frame(d))[::-1]  # FANUC W,P,R = KUKA C,B,A
        pts = cycle_points(p, d, depth)
        idx = []
        for q in pts:
            n += 1
            idx.append(n)
            pos += ["P[%d]{" % n, "   GP1:", "\tUF : 1, UT : 1,\t\tCONFIG : '%s'," % cf,
                    "\tX = %9.3f  mm,\tY = %9.3f  mm,\tZ = %9.3f  mm," % tuple(0.0 if abs(v) < 5e-4 else v for v in q),
                    "\tW = %9.3f deg,\tP = %9.3f deg,\tR = %9.3f deg" % tuple(0.0 if abs(v) < 5e-4 else v for v in (w, pp, r)), "};"]
        mn += ["!%s drill D%.1f ;" % (hid, dia), "J P[%d] 50%% CNT50 ;" % idx[0], "L P[%d] 250mm/sec CNT10 ;" % idx[1],
               "L P[%d] %dmm/sec FINE ;" % (idx[2], FEED_MM_S), "WAIT   .30(sec) ;", "L P[%d] 250mm/sec CNT50 ;" % idx[0]]
    lines = ["/PROG  HOUSING_R2000", "/ATTR", "OWNER\t\t= MNEDITOR;", "COMMENT\t\t= \"roprec sample\";",
             "PROG_SIZE\t= 0;", "FILE_NAME\t= ;", "VERSION\t\t= 0;", "LINE_COUNT\t= %d;" % (len(mn) + 2),
             "MEMORY_SIZE\t= 0;", "PROTECT\t\t= READ_WRITE;", "TCD:  STACK_SIZE\t= 0,", "      TASK_PRIORITY\t= 50,",
             "      TIME_SLICE\t= 0,", "      BUSY_LAMP_OFF\t= 0,", "      ABORT_REQUEST\t= 0,", "      PAUSE_REQUEST\t= 0;",
             "DEFAULT_GROUP\t= 1,*,*,*,*;", "CONTROL_CODE\t= 00000000 00000000;", "/MN"]
    body = ["UFRAME_NUM=1 ;", "UTOOL_NUM=1 ;"] + mn
    lines += ["%4d:%s" % (i + 1, s) if s[:2] in ("J ", "L ") else "%4d:  %s" % (i + 1, s) for i, s in enumerate(body)]
    lines += ["/POS"] + pos + ["/END", ""]
    write("housing_r2000.ls", "\n".join(lines), crlf=True)


def holes_csv(hs):
    L = ["# e-motor housing (AlSi9Cu3 die casting): 204 holes on 4 faces (top, 45 deg front chamfer, two sides), workobject frame, mm",
         "id,x,y,z,i,j,k,diameter,depth,tolerance"]
    for hid, p, d, dia, depth, tol in hs:
        L.append("%s,%s,%s,%s,%s,%s,%s,%.1f,%.1f,%.2f" % (hid, f3(p[0]), f3(p[1]), f3(p[2]), fd(d[0]), fd(d[1]), fd(d[2]), dia, depth, tol))
    write("holes.csv", "\n".join(L) + "\n")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        raise SystemExit("usage: make_samples.py ROPREC_BINARY")
    hs = holes()
    holes_csv(hs)
    krl(hs)
    krl_tools(hs)
    rapid(hs, configs(sys.argv[1], "abb", hs))
    tp(hs, configs(sys.argv[1], "fanuc", hs))
    print("%d holes" % len(hs))
