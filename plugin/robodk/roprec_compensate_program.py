#!/usr/bin/env python3
"""roprec_compensate_program — pre-offset a RoboDK program's drilling targets with roprec, on a copy.

The app reads the program's instructions in order and writes a compensated copy, ``NAME_roprec``,
next to it; the original is never changed. In the copy every linear move (MoveL) to a Cartesian
target is replaced by roprec's filtered target: the pose to program so that the robot's predicted
real TCP (deflected by gravity, the spindle's weight and the drilling thrust of the roprec cell)
lands on the pose RoboDK shows. Orientation is kept (positions are pre-offset); the new joints keep
the configuration RoboDK had for the target. Nothing is written unless every target could be
filtered.

Instructions, in program order
    Set Reference Frame   the frame whose name the instruction shows becomes the frame of the
                          following targets (its pose from the station: frame.PoseAbs() in the
                          robot base, robot.PoseAbs()). Before the first one: robot.PoseFrame().
    Set Tool              the tool whose name the instruction shows becomes the TCP
                          (tool.PoseTool()); it must be the cell's <tool> (--skip-tool-check to
                          override). Before the first one: robot.PoseTool().
    MoveL                 to a Cartesian target: compensated. To a joint target: left alone.
    MoveJ                 left alone (an approach or retract motion, no process load).
    MoveC                 left alone and listed: RoboDK's Item.Instruction() does not give a
                          MoveC's two targets.
    Pause, program calls  listed in the summary with the programs it calls (prog.Childs()): a
                          called program is compensated on its own (run the app on it); any
                          other instruction is copied as it is.

Hole data
    A MoveL's hole is named by its target (the instruction ``MoveL (T001)`` or ``Drill T001``: the
    first word that is a hole of the hole list). The hole list (roprec's CSV, columns
    id,x,y,z,i,j,k[,diameter,depth,tolerance]) is --holes, kept with the station (saved in the .rdk):
    its path as the station parameter ROPREC_HOLES, its text as the station data ROPREC_HOLES_CSV
    (RDK.setParam with bytes), which later runs use. A target name may also carry the hole's process as key=value words:
    ``tool=2 dia=6.8 depth=16 feed=0.12 rpm=6000`` (tool number or name, diameter and depth in mm,
    feed in mm/rev, spindle speed in 1/min); they override the hole list. The active Set Tool's
    name is the hole's tool unless the target names one. Without any hole data the cell's drill is
    used, and the summary counts those holes.

Runs twice without harm
    The copy carries a marker (the item parameter ROPREC_SOURCE: the original's name and the
    cell). Run on the original again, the app rebuilds the copy from the original; run on a copy
    (marker, or a name ending in _roprec), it refuses.

The cell
    --cell CELL.xml, stored with the station as the station parameter ROPREC_CELL (RoboDK: right
    click the station, Station parameters); else that station parameter; else the environment
    variable ROPREC_CELL. The Python RoboDK uses must import both ``robodk`` and ``roprec``
    (PYTHONPATH=P/lib/python3/dist-packages).

Inside RoboDK
    python3 roprec_compensate_program.py --install-app ROBODK_APPS_FOLDER installs the app (this
    script and its AppConfig.ini) into RoboDK's Apps folder (e.g. ~/RoboDK/Apps, C:/RoboDK/Apps)
    as Apps/roprec/; with the AppLoader plug-in loaded, a right click on a program offers
    "Compensate with roprec", and the menu "roprec" holds the same action. It works on the selected
    program (else a pick dialog).

Headless
    python3 roprec_compensate_program.py --headless --station S.rdk --program NAME --cell C.xml \\
            [--holes H.csv] [--make-program DIR] [--save S_OUT.rdk]

Options
    --cell CELL.xml          the roprec cell (robot card, tool, workobject, process, controller).
    --holes HOLES.csv        the hole list the targets are named after.
    --program NAME           the program to compensate (exact name); default: the program selected
                             in RoboDK, else a pick dialog (RDK.ItemUserPick).
    --headless               start a new RoboDK without UI:
                             Robolink(args=["-NEWINSTANCE", "-NOUI", "-EXIT_LAST_COM"]).
    --station FILE.rdk       load this station first (RDK.AddFile).
    --make-program DIR       afterwards generate the copy's robot program into DIR.
    --save FILE.rdk          afterwards save the station (RDK.Save).
    --dry-run                filter and report, change nothing.
    --skip-tool-check        do not compare RoboDK's tool with the cell's <tool>.
    --assume-accuracy-inactive
                             for RoboDK APIs without Item.AccuracyActive(): you confirm the robot's
                             accuracy model is off (see below).
    --install-app APPS_DIR   install the app into RoboDK's Apps folder and exit.

Frames and units
    RoboDK poses are robomath.Mat 4x4 in mm, a target relative to the program's reference frame.
    roprec works in the robot base frame: the robot card's base link, which must be RoboDK's robot
    base frame for that robot model. Joints are in the controller's convention (RoboDK's), degrees;
    external axes are kept as they are.

RoboDK's accuracy model
    RoboDK's calibrated kinematics (robot.setAccuracyActive(1)) also model the robot's deflection;
    filtering through roprec on top of it would compensate gravity twice, so the app refuses while
    robot.AccuracyActive() is true and never changes the setting. Without that getter it refuses
    unless --assume-accuracy-inactive is given.

Exit codes
    0 done; 1 some targets could not be filtered, or RoboDK changed the original (listed; nothing
    kept); 2 bad usage or input, or refused.
"""

import argparse
import csv
import json
import os
import re
import shutil
import sys

import numpy as np

APP = "roprec_compensate_program"
HEADLESS_ARGS = ["-NEWINSTANCE", "-NOUI", "-EXIT_LAST_COM"]
CELL_PARAM = "ROPREC_CELL"        # station parameter: the cell's path
HOLES_PARAM = "ROPREC_HOLES"      # station parameter: the hole list's path
HOLES_DATA_PARAM = "ROPREC_HOLES_CSV"  # station data: the hole list itself (saved with the .rdk)
MARKER_PARAM = "ROPREC_SOURCE"    # item parameter of a compensated copy
COPY_SUFFIX = "_roprec"
APP_FOLDER = "roprec"             # the app's folder in RoboDK's Apps folder
TOOL_TOL_MM = 0.01                # RoboDK tool vs the cell's tool: position
TOOL_TOL_ROT = 1e-5               # and rotation-matrix entries
# key=value words of a target name -> the hole's process keys (see filter_hole)
NAME_KEYS = {"tool": ("tool", str), "dia": ("diameter_mm", float), "depth": ("depth_mm", float),
             "feed": ("feed_mm_per_rev", float), "rpm": ("spindle_rpm", float)}


class Refused(Exception):
    """A condition under which the app changes nothing (exit code 2)."""


class Failed(Exception):
    """Work that could not be done; nothing kept (exit code 1)."""


def parse_args(argv):
    """Command-line options (see the module docstring)."""
    p = argparse.ArgumentParser(prog=APP, description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--cell", help="roprec cell XML (stored as the station parameter ROPREC_CELL)")
    p.add_argument("--holes", help="hole list CSV (stored as the station parameter ROPREC_HOLES)")
    p.add_argument("--program", help="name of the RoboDK program to compensate (default: selected / pick)")
    p.add_argument("--headless", action="store_true", help="start a new RoboDK instance without UI")
    p.add_argument("--station", help="station (.rdk) to load first")
    p.add_argument("--make-program", metavar="DIR", help="generate the copy's robot program into DIR afterwards")
    p.add_argument("--save", metavar="FILE", help="save the station to FILE afterwards")
    p.add_argument("--dry-run", action="store_true", help="report only, change nothing")
    p.add_argument("--skip-tool-check", action="store_true", help="do not compare RoboDK's tool with the cell's")
    p.add_argument("--assume-accuracy-inactive", action="store_true",
                   help="confirm RoboDK's accuracy model is off when the API cannot tell")
    p.add_argument("--install-app", metavar="APPS_DIR", help="install the app into RoboDK's Apps folder and exit")
    return p.parse_args(argv)


# ---- installation into RoboDK's Apps folder

def install_app(apps_dir):
    """Copies this script and AppConfig.ini into APPS_DIR/roprec/ (overwriting an older copy)."""
    here = os.path.dirname(os.path.abspath(__file__))
    config = os.path.join(here, "AppConfig.ini")
    if not os.path.isfile(config):
        raise Refused("AppConfig.ini is not beside the app (%s): install from roprec's share/roprec/robodk/"
                      "roprec/ or its source folder plugin/robodk/" % here)
    if not os.path.isdir(apps_dir):
        raise Refused("RoboDK's Apps folder %s does not exist (create it: mkdir -p %s)" % (apps_dir, apps_dir))
    target = os.path.join(apps_dir, APP_FOLDER)
    os.makedirs(target, exist_ok=True)
    for name in (os.path.basename(os.path.abspath(__file__)), "AppConfig.ini"):
        shutil.copyfile(os.path.join(here, name), os.path.join(target, name))
    return target


# ---- settings kept with the station

def station_param(rdk, name):
    """A station parameter's text, or None (RDK.getParam returns None when it is unknown)."""
    value = rdk.getParam(name)
    return str(value) if value not in (None, "") else None


def resolve_cell(rdk, arg):
    """The cell path: --cell (then stored as ROPREC_CELL), else the station's ROPREC_CELL, else $ROPREC_CELL."""
    if arg:
        path = os.path.abspath(arg)
        rdk.setParam(CELL_PARAM, path)
        return path
    stored = station_param(rdk, CELL_PARAM)
    if stored:
        return stored
    if os.environ.get("ROPREC_CELL"):
        return os.environ["ROPREC_CELL"]
    raise Refused("no roprec cell for this station: run the app once with --cell CELL.xml (it is kept as the "
                  "station parameter %s), or add that parameter to the station (right click the station, "
                  "Station parameters), or set the environment variable ROPREC_CELL" % CELL_PARAM)


def resolve_holes(rdk, arg):
    """(where, text) of the hole list: --holes (then kept with the station: its path as ROPREC_HOLES,
    its text as the station data ROPREC_HOLES_CSV), else the station's copy; (None, None) without."""
    if arg:
        path = os.path.abspath(arg)
        try:
            with open(path, "rb") as f:
                data = f.read()
        except OSError as e:
            raise Refused("cannot read the hole list %s: %s" % (path, e.strerror))
        rdk.setParam(HOLES_PARAM, path)
        rdk.setParam(HOLES_DATA_PARAM, data)
        return path, data.decode("utf-8")
    data = rdk.getParam(HOLES_DATA_PARAM, False)
    if data:
        return "%s (kept with the station)" % (station_param(rdk, HOLES_PARAM) or HOLES_DATA_PARAM), data.decode("utf-8")
    return None, None


def read_hole_list(where, text):
    """{hole id: process keys} from a roprec hole list (its diameter and depth columns, when present)."""
    rows = [line for line in text.splitlines() if line.strip() and not line.lstrip().startswith("#")]
    holes = {}
    for row in csv.DictReader(rows):
        row = {k.strip().lower(): (v or "").strip() for k, v in row.items() if k}
        if not row.get("id"):
            raise Refused("%s: the hole list has no 'id' column (columns: id,x,y,z,i,j,k[,diameter,depth,"
                          "tolerance])" % where)
        process = {}
        for column, key in (("diameter", "diameter_mm"), ("depth", "depth_mm")):
            if row.get(column):
                process[key] = float(row[column])
        holes[row["id"]] = process
    return holes


# ---- poses

def mat_to_np(mat):
    """robomath.Mat (4x4 pose, mm) -> numpy array."""
    return np.array(mat.Rows(), dtype=float)


def np_to_mat(array, Mat):
    """numpy 4x4 -> robomath.Mat."""
    return Mat([[float(x) for x in row] for row in array])


def inverse_pose(T):
    """Inverse of a rigid 4x4 pose."""
    inv = np.eye(4)
    inv[:3, :3] = T[:3, :3].T
    inv[:3, 3] = -T[:3, :3].T @ T[:3, 3]
    return inv


def accuracy_active(robot, assume_inactive):
    """True when RoboDK's accuracy model is active for `robot` (robot.AccuracyActive())."""
    getter = getattr(robot, "AccuracyActive", None)
    if getter is None:
        if assume_inactive:
            return False
        raise Refused("this RoboDK API has no Item.AccuracyActive(), so the app cannot tell whether RoboDK's "
                      "accuracy model is active; check that it is off for the robot, then run with "
                      "--assume-accuracy-inactive")
    return bool(getter())


def check_tool(tool_mm, where, session):
    """Refuses when a tool (TCP in the flange frame) differs from the cell's <tool>."""
    cell = session.tool_pose_mm
    if (np.abs(tool_mm[:3, 3] - cell[:3, 3]).max() > TOOL_TOL_MM or
            np.abs(tool_mm[:3, :3] - cell[:3, :3]).max() > TOOL_TOL_ROT):
        raise Refused("RoboDK's tool %s (TCP %s mm in the flange frame) is not the cell's <tool> (TCP %s mm): "
                      "make them equal (or run with --skip-tool-check)"
                      % (where, np.round(tool_mm[:3, 3], 3).tolist(), np.round(cell[:3, 3], 3).tolist()))


# ---- reading the program

def named_item(rdk, robodk, text, itemtype):
    """The item of `itemtype` whose name the instruction name `text` shows (the longest such name)."""
    names = [n for n in rdk.ItemList(itemtype, True) if n and n in text]
    if not names:
        return None
    return rdk.Item(max(names, key=len), itemtype)


def target_name(name):
    """The target an instruction name shows: 'MoveL (T001)' -> 'T001'; otherwise the name itself."""
    m = re.match(r"^\s*Move[A-Za-z]*\s*\((.*)\)\s*$", name)
    return m.group(1) if m else name


def hole_of(name, holes, tool_name):
    """(hole id or None, process keys) for a MoveL whose instruction is named `name`."""
    words = target_name(name).replace(",", " ").split()
    hole_id = next((w for w in words if w in holes), None)
    process = dict(holes.get(hole_id, {}))
    if tool_name:
        process["tool"] = tool_name
    for w in words:
        key, sep, value = w.partition("=")
        if sep and key.lower() in NAME_KEYS:
            field, kind = NAME_KEYS[key.lower()]
            try:
                process[field] = kind(value)
            except ValueError:
                raise Refused("instruction '%s': %s=%s is not a number" % (name, key, value))
    return hole_id, process


def read_program(prog):
    """Every instruction of `prog` in order, as the tuple Item.Instruction() gives."""
    return [prog.Instruction(i) for i in range(prog.InstructionCount())]


class Walk(object):
    """What the app finds walking a program: the edits to make and what it leaves alone."""

    def __init__(self):
        self.edits, self.failures = [], []
        self.counts = {"joint_moves": 0, "joint_targets": 0, "circular": 0, "pauses": 0, "calls": 0, "other": 0}
        self.listed = []        # MoveC and program calls / code, by name
        self.no_hole_data = 0   # MoveL targets with no hole data: the cell's drill


def frame_pose(rdk, robodk, robot, name):
    """The frame a Set Reference Frame instruction sets, in the robot base frame."""
    frame = named_item(rdk, robodk, name, robodk.ITEM_TYPE_FRAME)
    if frame is None:
        raise Refused("instruction '%s': no reference frame of the station has a name it shows" % name)
    return inverse_pose(mat_to_np(robot.PoseAbs())) @ mat_to_np(frame.PoseAbs())


def tool_of(rdk, robodk, name):
    """(TCP in the flange frame, tool name) that a Set Tool instruction sets."""
    tool = named_item(rdk, robodk, name, robodk.ITEM_TYPE_TOOL)
    if tool is None:
        raise Refused("instruction '%s': no tool of the station has a name it shows" % name)
    return mat_to_np(tool.PoseTool()), tool.Name()


def walk_program(instructions, ctx):
    """Filters every MoveL to a Cartesian target in program order; changes nothing."""
    rdk, robodk, robot, session, args = ctx["rdk"], ctx["robodk"], ctx["robot"], ctx["session"], ctx["args"]
    T_base_ref = mat_to_np(robot.PoseFrame())
    tool_mm, tool_name, tool_checked = mat_to_np(robot.PoseTool()), None, args.skip_tool_check
    w = Walk()
    for i, (name, ins_type, move_type, isjointtarget, pose, joints) in enumerate(instructions):
        if ins_type == robodk.INS_TYPE_CHANGEFRAME:
            T_base_ref = frame_pose(rdk, robodk, robot, name)
        elif ins_type == robodk.INS_TYPE_CHANGETOOL:
            tool_mm, tool_name = tool_of(rdk, robodk, name)
            tool_checked = args.skip_tool_check
        elif ins_type == robodk.INS_TYPE_MOVEC:
            w.counts["circular"] += 1
            w.listed.append("MoveC '%s' (left alone)" % name)
        elif ins_type == robodk.INS_TYPE_PAUSE:
            w.counts["pauses"] += 1
        elif ins_type == robodk.INS_TYPE_CODE:
            w.counts["calls"] += 1
            w.listed.append("call/code '%s'" % name)
        elif ins_type != robodk.INS_TYPE_MOVE:
            w.counts["other"] += 1
        elif move_type != robodk.MOVE_TYPE_LINEAR:
            w.counts["joint_moves" if move_type == robodk.MOVE_TYPE_JOINT else "other"] += 1
        elif isjointtarget:
            w.counts["joint_targets"] += 1
        else:
            if not tool_checked:
                check_tool(tool_mm, "'%s'" % (tool_name or "active"), session)
                tool_checked = True
            filter_move(w, i, instructions[i], T_base_ref, tool_name, ctx)
    return w


def filter_move(w, i, instruction, T_base_ref, tool_name, ctx):
    """Filters one MoveL to a Cartesian target into w.edits (or w.failures)."""
    name, ins_type, move_type, isjointtarget, pose, joints = instruction
    all_joints = [float(x) for x in joints.list()] if joints is not None else []
    seed = all_joints[:6] if len(all_joints) >= 6 else None
    hole_id, process = hole_of(name, ctx["holes"], tool_name)
    wanted = T_base_ref @ mat_to_np(pose)
    try:
        programmed, new_joints, own_process = filter_hole(ctx["session"], wanted, seed, process)
    except ctx["roprec"].ItemError as e:
        w.failures.append("instruction %d (%s): %s" % (i, name, e))
        return
    if not own_process:
        w.no_hole_data += 1
    shift = float(np.linalg.norm(programmed[:3, 3] - wanted[:3, 3]))
    w.edits.append((i, name, ins_type, move_type, isjointtarget, inverse_pose(T_base_ref) @ programmed,
                    [float(x) for x in new_joints] + all_joints[6:], shift))


def filter_hole(session, wanted, seed, process):
    """Session.filter_target for one hole: the adapter between the app and the roprec module.

    `process` holds the hole's own process (keys tool, diameter_mm, depth_mm, feed_mm_per_rev,
    spindle_rpm; tool is the active Set Tool's name unless the target names one); empty: the
    cell's drill. They go to filter_target as keyword arguments. A roprec module whose
    filter_target takes none refuses a hole with its own data (its drill would be wrong); a RoboDK
    tool's name alone then means the cell's drill. Returns (pose, joints, whether the hole's own
    process was used)."""
    if not process:
        pose, joints = session.filter_target(wanted, seed)
        return pose, joints, False
    try:
        pose, joints = session.filter_target(wanted, seed, **process)
        return pose, joints, True
    except TypeError as e:
        if "incompatible function arguments" not in str(e) and "unexpected keyword" not in str(e):
            raise
        if set(process) == {"tool"}:
            pose, joints = session.filter_target(wanted, seed)
            return pose, joints, False
        raise Refused("this roprec module's filter_target takes no per-hole process (%s); update roprec, or "
                      "run without hole data to use the cell's drill for every hole" % ", ".join(sorted(process)))


# ---- the copy

def copy_name(prog):
    return prog.Name() + COPY_SUFFIX


def marker(prog):
    """The compensated-copy marker of a program (decoded), or None."""
    raw = prog.getParam(MARKER_PARAM)
    if not raw:
        return None
    try:
        return json.loads(raw.decode("utf-8") if isinstance(raw, bytes) else raw)
    except ValueError:
        return {"source": "?"}


def refuse_compensated(prog):
    """Refuses a program that is itself a compensated copy."""
    mark = marker(prog)
    if mark is not None or prog.Name().endswith(COPY_SUFFIX):
        source = mark.get("source", "?") if mark else prog.Name()[:-len(COPY_SUFFIX)]
        raise Refused("program '%s' is already compensated by roprec (from '%s'); run the app on '%s' "
                      "instead (it rebuilds the copy)" % (prog.Name(), source, source))


def make_copy(rdk, robodk, prog):
    """A fresh copy of `prog` named NAME_roprec (an older roprec copy is replaced)."""
    name = copy_name(prog)
    old = rdk.Item(name, robodk.ITEM_TYPE_PROGRAM)
    replaced = old.Valid() and old.Name() == name
    if replaced:
        mark = marker(old)
        if mark is None or mark.get("source") != prog.Name():
            raise Refused("a program named '%s' exists and is not roprec's copy of '%s': rename it first"
                          % (name, prog.Name()))
        old.Delete()
    prog.Copy(True)
    copy = prog.Parent().Paste()
    if not copy.Valid():
        raise Failed("RoboDK could not copy program '%s'" % prog.Name())
    copy.setName(name)
    return copy, replaced


def write_copy(copy, prog, edits, cell, Mat):
    """Writes the edits into the copy and marks it."""
    for i, name, ins_type, move_type, isjointtarget, pose, joints, _ in edits:
        copy.setInstruction(i, name, ins_type, move_type, isjointtarget, np_to_mat(pose, Mat), joints)
    copy.setParam(MARKER_PARAM, json.dumps({"source": prog.Name(), "cell": cell}).encode("utf-8"))


def same_instruction(a, b):
    """True when two Item.Instruction() tuples are equal (poses and joints by value)."""
    def plain(ins):
        return [x.Rows() if hasattr(x, "Rows") else x for x in ins]
    return plain(a) == plain(b)


def guard_original(prog, original, copy):
    """Fails (restoring the original, deleting the copy) when writing the copy changed the original:
    a RoboDK whose program copy shares its target items with the original."""
    changed = [i for i, ins in enumerate(read_program(prog)) if not same_instruction(ins, original[i])]
    if not changed:
        return
    for i in changed:
        name, ins_type, move_type, isjointtarget, pose, joints = original[i]
        prog.setInstruction(i, name, ins_type, move_type, isjointtarget, pose, joints.list())
    copy.Delete()
    raise Failed("RoboDK changed the original program '%s' when its copy was written (instructions %s share "
                 "their targets with the copy); the original is restored and no copy is kept: make the "
                 "targets of the copy independent (RoboDK: copy the targets too) and run again"
                 % (prog.Name(), ", ".join(str(i) for i in changed)))


# ---- the run

def pick_program(rdk, robodk, name):
    """--program NAME, else the one selected program, else a pick dialog."""
    if name:
        prog = rdk.Item(name, robodk.ITEM_TYPE_PROGRAM)
        if not prog.Valid() or prog.Name() != name:
            raise Refused("no program named '%s' in the station" % name)
        return prog
    selected = [i for i in rdk.Selection() if i.Type() == robodk.ITEM_TYPE_PROGRAM]
    if len(selected) == 1:
        return selected[0]
    prog = rdk.ItemUserPick("Select the program to compensate with roprec", robodk.ITEM_TYPE_PROGRAM)
    if not prog.Valid():
        raise Refused("no program selected")
    return prog


def run(args, robodk, Mat, roprec, say):
    """The app's work once RoboDK and roprec are importable; returns the exit code."""
    rdk = robodk.Robolink(args=HEADLESS_ARGS) if args.headless else robodk.Robolink()
    try:
        return _run(args, rdk, robodk, Mat, roprec, say)
    except Refused as e:
        say(rdk, "%s: refused: %s" % (APP, e), error=True)
        return 2
    except Failed as e:
        say(rdk, "%s: %s" % (APP, e), error=True)
        return 1
    except roprec.RoprecError as e:
        say(rdk, "%s: error: %s" % (APP, e), error=True)
        return 2


def open_job(args, rdk, robodk, roprec):
    """Station, program, robot and session, after the refusals that need no filtering."""
    if args.station:
        station = rdk.AddFile(args.station)
        if not station.Valid():
            raise Refused("RoboDK could not load the station " + args.station)
    cell = resolve_cell(rdk, args.cell)
    holes_where, holes_text = resolve_holes(rdk, args.holes)
    prog = pick_program(rdk, robodk, args.program)
    refuse_compensated(prog)
    robot = prog.getLink(robodk.ITEM_TYPE_ROBOT)
    if not robot.Valid():
        raise Refused("program '%s' has no robot linked to it" % prog.Name())
    if accuracy_active(robot, args.assume_accuracy_inactive):
        raise Refused("RoboDK's accuracy model is active for robot '%s': it already compensates the robot's "
                      "deflection, and roprec would compensate gravity twice. Turn it off for this robot "
                      "(robot.setAccuracyActive(0)) to use roprec, or keep RoboDK's and do not run this app"
                      % robot.Name())
    session = roprec.Session(cell)
    holes = read_hole_list(holes_where, holes_text) if holes_text else {}
    return {"rdk": rdk, "robodk": robodk, "roprec": roprec, "args": args, "cell": cell, "prog": prog,
            "robot": robot, "session": session, "holes": holes}


def summary(ctx, w, action):
    """The one-paragraph report of a run."""
    c = w.counts
    text = ("%s: program '%s' (robot '%s', cell %s): %s %d linear Cartesian targets (largest shift %.3f mm); "
            "left alone: %d joint moves, %d moves to joint targets, %d MoveC, %d other instructions; "
            "%d pauses, %d program calls/code"
            % (APP, ctx["prog"].Name(), ctx["robot"].Name(), ctx["session"].cell, action, len(w.edits),
               max((e[7] for e in w.edits), default=0.0), c["joint_moves"], c["joint_targets"], c["circular"],
               c["other"], c["pauses"], c["calls"]))
    if w.no_hole_data:
        text += "; %d targets have no hole data and use the cell's drill" % w.no_hole_data
    called = [p.Name() for p in ctx["prog"].Childs()]
    if called:
        text += "\n  calls the programs %s: run the app on each of them too" % ", ".join("'%s'" % n for n in called)
    if w.listed:
        text += "\n  " + "\n  ".join(w.listed)
    return text


def _run(args, rdk, robodk, Mat, roprec, say):
    ctx = open_job(args, rdk, robodk, roprec)
    prog = ctx["prog"]
    original = read_program(prog)
    w = walk_program(original, ctx)
    if w.failures:
        raise Failed("%d of %d linear targets of '%s' could not be filtered; nothing changed:\n  %s"
                     % (len(w.failures), len(w.failures) + len(w.edits), prog.Name(), "\n  ".join(w.failures)))
    if args.dry_run:
        say(rdk, summary(ctx, w, "would compensate"), error=False)
        return 0
    copy, replaced = make_copy(rdk, robodk, prog)
    write_copy(copy, prog, w.edits, ctx["cell"], Mat)
    guard_original(prog, original, copy)
    msg = summary(ctx, w, "compensated") + "\n  %s copy '%s' (the original is unchanged)" % (
        "replaced the" if replaced else "wrote the", copy.Name())
    if args.make_program:
        result = copy.MakeProgram(args.make_program)
        ok = result[0] if isinstance(result, tuple) else bool(result)
        if not ok:
            raise Failed("RoboDK could not generate the program into %s: %s"
                         % (args.make_program, result[1] if isinstance(result, tuple) else result))
        msg += "; program generated into " + args.make_program
    if args.save:
        rdk.Save(args.save)
        msg += "; station saved to " + args.save
    say(rdk, msg, error=False)
    return 0


def main(argv=None):
    """Entry point: parses `argv` (default sys.argv[1:]) and returns the exit code."""
    args = parse_args(sys.argv[1:] if argv is None else argv)
    if args.install_app:
        try:
            print("%s: installed into %s (load RoboDK's AppLoader plug-in: Tools, Plug-Ins)"
                  % (APP, install_app(args.install_app)))
            return 0
        except Refused as e:
            print("%s: refused: %s" % (APP, e), file=sys.stderr)
            return 2
    try:
        import roprec
    except ImportError as e:
        print("%s: error: cannot import roprec (%s): add P/lib/python3/dist-packages to PYTHONPATH" % (APP, e),
              file=sys.stderr)
        return 2
    try:
        from robodk import robolink as robodk
        from robodk.robomath import Mat
    except ImportError as e:
        print("%s: error: cannot import the RoboDK API (%s): pip install robodk, or run inside RoboDK" % (APP, e),
              file=sys.stderr)
        return 2

    def say(rdk, text, error):
        print(text, file=sys.stderr if error else sys.stdout)
        if not args.headless:
            rdk.ShowMessage(text, error)  # a popup for refusals and failures, the status bar otherwise

    return run(args, robodk, Mat, roprec, say)


if __name__ == "__main__":
    sys.exit(main())
