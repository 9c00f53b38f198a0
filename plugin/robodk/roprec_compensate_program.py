#!/usr/bin/env python3
"""roprec_compensate_program — pre-offset a RoboDK program's drilling targets with roprec.

For every linear move (MoveL) to a Cartesian target of a RoboDK program, the target is replaced by
roprec's filtered target: the pose to program so that the robot's predicted real TCP — deflected
by gravity, the spindle's weight and the drilling thrust described in the roprec cell — lands on
the pose RoboDK shows. Orientation is kept (only positions are pre-offset); the new joints keep the
configuration RoboDK had for the target. Joint moves (MoveJ), moves to joint targets and every
other instruction are left alone. Nothing is changed unless every target could be filtered.

Inside RoboDK
    Copy this script into a folder of RoboDK's Apps folder (e.g. Apps/roprec/; the AppLoader
    plug-in then shows it as an action), or load it as a Python program, and run it: it works on
    the program selected in the station tree (or asks you to pick one). The cell is --cell, else
    the environment variable ROPREC_CELL, else the first line of roprec_cell.txt next to this
    script. The Python RoboDK uses must import both ``robodk`` and ``roprec`` (roprec:
    PYTHONPATH=P/lib/python3/dist-packages).

Headless
    python3 roprec_compensate_program.py --headless --station S.rdk --program NAME --cell C.xml \\
            [--make-program DIR] [--save S_OUT.rdk]

Options
    --cell CELL.xml          the roprec cell: robot card, tool (TCP, mass), workobject, process
                             (drill, feed, material) and controller (gravity compensation).
    --program NAME           the program item to compensate (exact name); default: the program
                             selected in RoboDK, else a pick dialog (RDK.ItemUserPick).
    --headless               start a new RoboDK without UI:
                             Robolink(args=["-NEWINSTANCE", "-NOUI", "-EXIT_LAST_COM"]).
    --station FILE.rdk       load this station first (RDK.AddFile).
    --make-program DIR       afterwards generate the robot program into DIR (prog.MakeProgram).
    --save FILE.rdk          afterwards save the station (RDK.Save); headless runs need this or
                             --make-program to keep anything.
    --dry-run                filter and report, change nothing.
    --skip-tool-check        do not compare RoboDK's tool (robot.PoseTool) with the cell's <tool>.
    --assume-accuracy-inactive
                             for RoboDK APIs without Item.AccuracyActive(): you confirm the
                             robot's accuracy model is off (see "RoboDK's accuracy model").

Frames and units
    RoboDK poses are robomath.Mat 4x4 in mm. An instruction's Cartesian target is relative to the
    program's reference frame; the app takes that frame from robot.PoseFrame() (the robot's active
    reference frame, in the robot base frame), so the program must use the reference frame that is
    active when the app runs (one frame per program). roprec works in the robot base frame: the
    robot card's base link, which must be RoboDK's robot base frame for that robot model. The TCP
    is the robot's active tool (robot.PoseTool(), flange frame); it must equal the cell's <tool>,
    otherwise the app refuses (--skip-tool-check to override). Joints are in the controller's
    convention (RoboDK's), degrees; external axes are kept as they are.

RoboDK's accuracy model
    RoboDK's calibrated ("accurate") kinematics (robot.setAccuracyActive(1), from a robot
    calibration) also models the robot's deflection. Filtering through roprec on top of it would
    compensate gravity twice, so the app refuses to run while it is active: it asks
    robot.AccuracyActive() (the documented getter of setAccuracyActive) and never changes the
    setting itself. If the RoboDK API in use has no AccuracyActive(), the app refuses too unless
    --assume-accuracy-inactive is given.

Exit codes
    0 done; 1 some targets could not be filtered (listed; nothing changed); 2 bad usage or input,
    or refused (accuracy model active, tool mismatch, program or robot not found).
"""

import argparse
import os
import sys

import numpy as np

APP = "roprec_compensate_program"
HEADLESS_ARGS = ["-NEWINSTANCE", "-NOUI", "-EXIT_LAST_COM"]
CELL_FILE = "roprec_cell.txt"
TOOL_TOL_MM = 0.01      # RoboDK tool vs the cell's tool: position
TOOL_TOL_ROT = 1e-5     # and rotation-matrix entries


class Refused(Exception):
    """A condition under which the app changes nothing (exit code 2)."""


def parse_args(argv):
    """Command-line options (see the module docstring)."""
    p = argparse.ArgumentParser(prog=APP, description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--cell", help="roprec cell XML (default: $ROPREC_CELL, else roprec_cell.txt beside the app)")
    p.add_argument("--program", help="name of the RoboDK program to compensate (default: selected / pick)")
    p.add_argument("--headless", action="store_true", help="start a new RoboDK instance without UI")
    p.add_argument("--station", help="station (.rdk) to load first")
    p.add_argument("--make-program", metavar="DIR", help="generate the robot program into DIR afterwards")
    p.add_argument("--save", metavar="FILE", help="save the station to FILE afterwards")
    p.add_argument("--dry-run", action="store_true", help="report only, change nothing")
    p.add_argument("--skip-tool-check", action="store_true", help="do not compare RoboDK's tool with the cell's")
    p.add_argument("--assume-accuracy-inactive", action="store_true",
                   help="confirm RoboDK's accuracy model is off when the API cannot tell")
    return p.parse_args(argv)


def resolve_cell(arg):
    """The cell path: --cell, else $ROPREC_CELL, else the first line of roprec_cell.txt beside the app."""
    if arg:
        return arg
    if os.environ.get("ROPREC_CELL"):
        return os.environ["ROPREC_CELL"]
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), CELL_FILE)
    if os.path.isfile(path):
        with open(path, encoding="utf-8") as f:
            line = f.readline().strip()
        if line:
            return line if os.path.isabs(line) else os.path.join(os.path.dirname(path), line)
    raise Refused("no roprec cell: give --cell CELL.xml, set ROPREC_CELL, or write the cell's path into " + path)


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


def check_tool(robot, session):
    """Refuses when RoboDK's active tool differs from the cell's <tool>."""
    rdk = mat_to_np(robot.PoseTool())
    cell = session.tool_pose_mm
    if (np.abs(rdk[:3, 3] - cell[:3, 3]).max() > TOOL_TOL_MM or
            np.abs(rdk[:3, :3] - cell[:3, :3]).max() > TOOL_TOL_ROT):
        raise Refused("RoboDK's tool (TCP %s mm in the flange frame) is not the cell's <tool> (TCP %s mm): "
                      "make them equal (or run with --skip-tool-check)"
                      % (np.round(rdk[:3, 3], 3).tolist(), np.round(cell[:3, 3], 3).tolist()))


def filter_program(prog, robot, session, robodk, roprec):
    """Filters every MoveL to a Cartesian target. Returns (edits, counts, failures); changes nothing."""
    T_base_ref = mat_to_np(robot.PoseFrame())
    T_ref_base = inverse_pose(T_base_ref)
    edits, failures = [], []
    counts = {"linear": 0, "joint_moves": 0, "joint_targets": 0, "other": 0}
    for i in range(prog.InstructionCount()):
        name, ins_type, move_type, isjointtarget, pose, joints = prog.Instruction(i)
        if ins_type != robodk.INS_TYPE_MOVE:
            counts["other"] += 1
            continue
        if move_type != robodk.MOVE_TYPE_LINEAR:
            counts["joint_moves" if move_type == robodk.MOVE_TYPE_JOINT else "other"] += 1
            continue
        if isjointtarget:
            counts["joint_targets"] += 1
            continue
        all_joints = [float(x) for x in joints.list()] if joints is not None else []
        seed = all_joints[:6] if len(all_joints) >= 6 else None
        wanted = T_base_ref @ mat_to_np(pose)
        try:
            programmed, new_joints = session.filter_target(wanted, seed)
        except roprec.ItemError as e:
            failures.append("instruction %d (%s): %s" % (i, name, e))
            continue
        counts["linear"] += 1
        shift = float(np.linalg.norm(programmed[:3, 3] - wanted[:3, 3]))
        edits.append((i, name, ins_type, move_type, isjointtarget, T_ref_base @ programmed,
                      [float(x) for x in new_joints] + all_joints[6:], shift))
    return edits, counts, failures


def run(args, robodk, Mat, roprec, say):
    """The app's work once RoboDK and roprec are importable; returns the exit code."""
    rdk = robodk.Robolink(args=HEADLESS_ARGS) if args.headless else robodk.Robolink()
    try:
        return _run(args, rdk, robodk, Mat, roprec, say)
    except Refused as e:
        say(rdk, "%s: refused: %s" % (APP, e), error=True)
        return 2
    except roprec.RoprecError as e:
        say(rdk, "%s: error: %s" % (APP, e), error=True)
        return 2


def _run(args, rdk, robodk, Mat, roprec, say):
    cell = resolve_cell(args.cell)
    if args.station:
        station = rdk.AddFile(args.station)
        if not station.Valid():
            raise Refused("RoboDK could not load the station " + args.station)
    if args.program:
        prog = rdk.Item(args.program, robodk.ITEM_TYPE_PROGRAM)
        if not prog.Valid() or prog.Name() != args.program:
            raise Refused("no program named '%s' in the station" % args.program)
    else:
        prog = rdk.ItemUserPick("Select the program to compensate with roprec", robodk.ITEM_TYPE_PROGRAM)
        if not prog.Valid():
            raise Refused("no program selected")
    robot = prog.getLink(robodk.ITEM_TYPE_ROBOT)
    if not robot.Valid():
        raise Refused("program '%s' has no robot linked to it" % prog.Name())
    if accuracy_active(robot, args.assume_accuracy_inactive):
        raise Refused("RoboDK's accuracy model is active for robot '%s': it already compensates the robot's "
                      "deflection, and roprec would compensate gravity twice. Turn it off for this robot "
                      "(robot.setAccuracyActive(0)) to use roprec, or keep RoboDK's and do not run this app"
                      % robot.Name())
    session = roprec.Session(cell)
    if not args.skip_tool_check:
        check_tool(robot, session)

    edits, counts, failures = filter_program(prog, robot, session, robodk, roprec)
    if failures:
        say(rdk, "%s: %d of %d linear targets of '%s' could not be filtered; nothing changed:\n  %s"
            % (APP, len(failures), len(failures) + len(edits), prog.Name(), "\n  ".join(failures)), error=True)
        return 1
    if not args.dry_run:
        for i, name, ins_type, move_type, isjointtarget, pose, joints, _ in edits:
            prog.setInstruction(i, name, ins_type, move_type, isjointtarget, np_to_mat(pose, Mat), joints)
    shift = max((e[7] for e in edits), default=0.0)
    msg = ("%s: program '%s' (robot '%s', cell %s): %s %d linear Cartesian targets (largest shift %.3f mm); "
           "left alone: %d joint moves, %d moves to joint targets, %d other instructions"
           % (APP, prog.Name(), robot.Name(), session.cell, "would compensate" if args.dry_run else "compensated",
              len(edits), shift, counts["joint_moves"], counts["joint_targets"], counts["other"]))
    if args.make_program and not args.dry_run:
        result = prog.MakeProgram(args.make_program)
        ok = result[0] if isinstance(result, tuple) else bool(result)
        if not ok:
            raise Refused("RoboDK could not generate the program into %s: %s"
                          % (args.make_program, result[1] if isinstance(result, tuple) else result))
        msg += "; program generated into " + args.make_program
    if args.save and not args.dry_run:
        rdk.Save(args.save)
        msg += "; station saved to " + args.save
    say(rdk, msg, error=False)
    return 0


def main(argv=None):
    """Entry point: parses `argv` (default sys.argv[1:]) and returns the exit code."""
    args = parse_args(sys.argv[1:] if argv is None else argv)
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
