"""roprec's RoboDK app (plugin/robodk/roprec_compensate_program.py) against the RoboDK stand-in
(tests/robodk_stub): on a program built from the sample hole list, the compensated copy NAME_roprec
holds every MoveL to a Cartesian target as Session.filter_target gives it, in the frame the
program's Set Reference Frame instructions set, and everything else as it was; the original is
never changed; a second run rebuilds the copy and a run on the copy is refused; hole data comes
from the hole list and target names through one adapter; the cell and hole list are kept as
station parameters; an active RoboDK accuracy model, a tool mismatch, an unreachable target and a
missing program are refused; the headless command line and the installation into RoboDK's Apps
folder (AppConfig.ini) work; every RoboDK call the app makes exists in RoboDK's published API with
that signature (tests/data/robodk/api_signatures.txt).

Run by ctest with PYTHONPATH = tests/robodk_stub + the build tree's python/ folder.
"""

import ast
import configparser
import contextlib
import csv
import inspect
import importlib.util
import io
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np

import roprec
from robodk import robolink

SRC = Path(__file__).resolve().parents[1]
APP = SRC / "plugin" / "robodk" / "roprec_compensate_program.py"
CELL = str(SRC / "samples" / "cells" / "housing-kr120.xml")
HOLES = str(SRC / "samples" / "emotor-housing" / "holes.csv")
ROBOT = "KUKA KR 120 R2500 pro"


def load_app():
    spec = importlib.util.spec_from_file_location("roprec_compensate_program", APP)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


app = load_app()


def read_holes():
    with open(HOLES, encoding="utf-8") as f:
        rows = [r for r in f if not r.startswith("#")]
    return [(r["id"], [float(r["x"]), float(r["y"]), float(r["z"])], [float(r["i"]), float(r["j"]), float(r["k"])])
            for r in csv.DictReader(rows)]


SESSION = roprec.Session(CELL)
FRAME = SESSION.workobject_pose_mm          # the program's reference frame: the cell's workobject
HOLE_ROWS = read_holes()
# The joints RoboDK would show for each nominal hole: roprec's IK of the hole list (controller joints).
NOMINAL_JOINTS = {h["id"]: h["controller_joints_deg"] for h in roprec.predict(CELL, HOLES)}


def drill_program(n_holes=None, far_hole=False):
    """A RoboDK program over the sample holes, targets in the workobject frame: per hole a MoveJ
    approach 20 mm before the hole, a MoveL to the hole and a MoveL back; plus a code instruction
    and a MoveL to a joint target."""
    inv_frame = np.linalg.inv(FRAME)
    ins = [{"name": "Spindle on", "type": robolink.INS_TYPE_CODE},
           {"name": "Home", "type": robolink.INS_TYPE_MOVE, "move_type": robolink.MOVE_TYPE_LINEAR,
            "joint_target": 1, "pose": np.eye(4).tolist(), "joints": [0.0, -90.0, 90.0, 0.0, 45.0, 0.0]}]
    rows = HOLE_ROWS[:n_holes] if n_holes else HOLE_ROWS
    for hid, p, d in rows:
        hole = inv_frame @ SESSION.hole_pose(p, d)
        if far_hole and hid == rows[-1][0]:
            hole[:3, 3] += [3000.0, 0.0, 0.0]
        approach = hole.copy()
        approach[:3, 3] -= 20.0 * hole[:3, 2]
        joints = [float(x) for x in NOMINAL_JOINTS[hid]]
        for name, move, pose in (("Approach " + hid, robolink.MOVE_TYPE_JOINT, approach),
                                 ("Drill " + hid, robolink.MOVE_TYPE_LINEAR, hole),
                                 ("Retract " + hid, robolink.MOVE_TYPE_LINEAR, approach)):
            ins.append({"name": name, "type": robolink.INS_TYPE_MOVE, "move_type": move, "joint_target": 0,
                        "pose": pose.tolist(), "joints": joints})
    return ins


def station(instructions, accuracy_active=False, legacy_api=False, tool=None):
    return {"robots": [{"name": ROBOT, "tool_mm": (SESSION.tool_pose_mm if tool is None else tool).tolist(),
                        "frame_mm": FRAME.tolist(), "accuracy_active": accuracy_active, "legacy_api": legacy_api}],
            "programs": [{"name": "Drill", "robot": ROBOT, "instructions": instructions}],
            "selected": "Drill"}


API_LIST = SRC / "tests" / "data" / "robodk" / "api_signatures.txt"
COPY = "Drill_roprec"


def run_app(description, *args, cell=CELL, fresh=True):
    """Runs the app in this process against a RoboDK (stand-in) holding `description` (or, with
    fresh=False, the station as the previous run left it)."""
    if fresh:
        robolink.STATION = robolink.Station(description)
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = app.main((["--cell", cell] if cell else []) + list(args))
    return code, out.getvalue(), err.getvalue(), robolink.STATION


def set_calls(st):
    return [c for c in st.calls if c[0] == "setInstruction"]


def expected_edit(ins):
    """What the app must write for a MoveL to a Cartesian target: Session.filter_target of the
    target in the base frame, seeded with its joints, back in the program's frame."""
    wanted = FRAME @ np.array(ins["pose"])
    pose, joints = SESSION.filter_target(wanted, ins["joints"])
    return pose, joints


def linear_cartesian(instructions):
    return [i for i, ins in enumerate(instructions) if ins["type"] == robolink.INS_TYPE_MOVE and
            ins["move_type"] == robolink.MOVE_TYPE_LINEAR and not ins["joint_target"]]


def pose_of(rows):
    return np.array(rows, dtype=float)


def rot_z(deg, xyz):
    c, s = np.cos(np.radians(deg)), np.sin(np.radians(deg))
    T = np.eye(4)
    T[:2, :2] = [[c, -s], [s, c]]
    T[:3, 3] = xyz
    return T


class RecordingSession(object):
    """A roprec.Session that records the keyword arguments filter_target gets (the per-hole
    process) and filters with the cell's drill."""

    calls = []
    real = roprec.Session

    def __init__(self, cell):
        self._s = RecordingSession.real(cell)
        self.tool_pose_mm, self.cell = self._s.tool_pose_mm, self._s.cell

    def filter_target(self, pose, seed=None, **process):
        RecordingSession.calls.append(process)
        return self._s.filter_target(pose, seed)


class RoboDKAppTest(unittest.TestCase):
    def test_copy_holds_every_linear_cartesian_target_filtered_and_the_original_is_kept(self):
        original = drill_program()
        code, out, err, st = run_app(station(original))
        self.assertEqual(code, 0, err)
        linear = linear_cartesian(original)
        self.assertEqual(len(linear), 2 * len(HOLE_ROWS))
        self.assertEqual([(c[1], c[2]) for c in set_calls(st)], [(COPY, i) for i in linear])  # each once, in order
        self.assertEqual(st.programs["Drill"]["instructions"], original)           # the original is kept
        final = st.programs[COPY]["instructions"]
        worst_mm, worst_real_um = 0.0, 0.0
        for i, ins in enumerate(original):
            if i not in linear:
                self.assertEqual(final[i], ins)            # joint moves, joint targets, code: as they were
                continue
            new = final[i]
            self.assertEqual((new["name"], new["type"], new["move_type"], new["joint_target"]),
                             (ins["name"], ins["type"], ins["move_type"], ins["joint_target"]))
            pose, joints = expected_edit(ins)
            written_base = FRAME @ np.array(new["pose"])
            np.testing.assert_allclose(written_base[:3, 3], pose[:3, 3], rtol=0, atol=1e-9)
            np.testing.assert_allclose(written_base[:3, :3], pose[:3, :3], rtol=0, atol=1e-12)
            np.testing.assert_allclose(new["joints"], joints, rtol=0, atol=1e-12)
            worst_mm = max(worst_mm, float(np.linalg.norm(written_base[:3, 3] - pose[:3, 3])))
            if i % 25 == 0:  # the predicted real TCP at the written joints is the original target
                dev = SESSION.predict_joints(new["joints"])["deviation_um"]
                real = written_base[:3, 3] + dev * 1e-3
                worst_real_um = max(worst_real_um,
                                    1e3 * float(np.linalg.norm(real - (FRAME @ np.array(ins["pose"]))[:3, 3])))
        self.assertLess(worst_real_um, 0.1)
        mark = json.loads(st.programs[COPY]["params"][app.MARKER_PARAM].decode("utf-8"))
        self.assertEqual(mark, {"source": "Drill", "cell": CELL})
        self.assertIn("compensated %d linear Cartesian targets" % len(linear), out)
        self.assertIn("left alone: %d joint moves, 1 moves to joint targets, 0 MoveC" % len(HOLE_ROWS), out)
        self.assertIn("%d targets have no hole data and use the cell's drill" % len(linear), out)
        self.assertIn("wrote the copy '%s' (the original is unchanged)" % COPY, out)
        # Inside RoboDK the summary goes to the status bar, not a popup.
        self.assertEqual(st.calls[-1][0], "ShowMessage")
        self.assertFalse(st.calls[-1][2])
        print("robodk app: %d targets filtered, written = filter_target to %.2g mm, real TCP off by max %.3g um"
              % (len(linear), worst_mm, worst_real_um))

    def test_second_run_rebuilds_the_copy_and_a_run_on_the_copy_is_refused(self):
        code, _, err, st = run_app(station(drill_program(4)))
        self.assertEqual(code, 0, err)
        first = json.loads(json.dumps(st.programs[COPY]["instructions"]))
        code, out, err, st = run_app(None, fresh=False)
        self.assertEqual(code, 0, err)
        self.assertIn("replaced the copy '%s'" % COPY, out)
        self.assertEqual(sorted(st.programs), ["Drill", COPY])
        self.assertEqual(st.programs[COPY]["instructions"], first)   # the same numbers, not compensated twice
        self.assertEqual(st.programs["Drill"]["instructions"], drill_program(4))
        before = len(set_calls(st))
        code, _, err, st = run_app(None, "--program", COPY, fresh=False)
        self.assertEqual(code, 2)
        self.assertIn("'%s' is already compensated by roprec (from 'Drill')" % COPY, err)
        self.assertEqual(len(set_calls(st)), before)
        # A program of that name that roprec did not write is not replaced.
        desc = station(drill_program(2))
        desc["programs"].append({"name": COPY, "robot": ROBOT, "instructions": []})
        code, _, err, st = run_app(desc, "--program", "Drill")
        self.assertEqual(code, 2)
        self.assertIn("exists and is not roprec's copy of 'Drill'", err)
        self.assertEqual(st.programs[COPY]["instructions"], [])

    def test_frame_and_tool_instructions_apply_in_program_order(self):
        # The robot base stands somewhere in the station; frame "Part B" is the workobject turned
        # 90 deg about z. The first two holes are programmed in the robot's active frame (FRAME),
        # the next two after "Set Reference Frame (Part B)" in Part B, with a Set Tool between.
        base_abs = rot_z(30.0, [500.0, -200.0, 100.0])
        part_b = FRAME @ rot_z(90.0, [10.0, 20.0, 0.0])
        ins = drill_program(2)
        ins.append({"name": "Set Reference Frame (Part B)", "type": robolink.INS_TYPE_CHANGEFRAME})
        ins.append({"name": "Set Tool (Drill 6.8)", "type": robolink.INS_TYPE_CHANGETOOL})
        for move in drill_program(4)[-6:]:
            if move["type"] == robolink.INS_TYPE_MOVE:
                move["pose"] = (np.linalg.inv(part_b) @ FRAME @ pose_of(move["pose"])).tolist()
            ins.append(move)
        desc = station(ins)
        desc["robots"][0]["base_abs_mm"] = base_abs.tolist()
        desc["frames"] = [{"name": "Part", "pose_abs_mm": (base_abs @ FRAME).tolist()},
                          {"name": "Part B", "pose_abs_mm": (base_abs @ part_b).tolist()}]
        desc["tools"] = [{"name": "Drill 6.8", "robot": ROBOT, "tcp_mm": SESSION.tool_pose_mm.tolist()}]
        code, out, err, st = run_app(desc)
        self.assertEqual(code, 0, err)
        final = st.programs[COPY]["instructions"]
        linear = linear_cartesian(ins)
        self.assertEqual(len(linear), 8)
        for i in linear:
            frame = FRAME if i < len(drill_program(2)) else part_b
            wanted = frame @ pose_of(ins[i]["pose"])
            pose, _ = SESSION.filter_target(wanted, ins[i]["joints"])
            np.testing.assert_allclose(frame @ pose_of(final[i]["pose"]), pose, rtol=0, atol=1e-9)
        # A tool that is not the cell's, set before a MoveL, is refused by name.
        desc["tools"].append({"name": "Probe", "robot": ROBOT,
                              "tcp_mm": (SESSION.tool_pose_mm @ rot_z(0.0, [0, 0, 40.0])).tolist()})
        desc["programs"][0]["instructions"][len(drill_program(2)) + 1]["name"] = "Set Tool (Probe)"
        code, _, err, st = run_app(desc)
        self.assertEqual(code, 2)
        self.assertIn("RoboDK's tool 'Probe'", err)
        self.assertNotIn(COPY, st.programs)
        # A frame instruction naming no frame of the station is refused.
        desc["programs"][0]["instructions"][len(drill_program(2))]["name"] = "Set Reference Frame (Gone)"
        code, _, err, _ = run_app(desc)
        self.assertEqual(code, 2)
        self.assertIn("'Set Reference Frame (Gone)': no reference frame of the station", err)

    def test_movec_pauses_and_program_calls_are_listed_and_copied_unchanged(self):
        ins = drill_program(2) + [{"name": "MoveC (Arc1, Arc2)", "type": robolink.INS_TYPE_MOVEC},
                                  {"name": "Pause 500 ms", "type": robolink.INS_TYPE_PAUSE},
                                  {"name": "ChangeDrill", "type": robolink.INS_TYPE_CODE},
                                  {"name": "Set Speed 100", "type": robolink.INS_TYPE_CHANGESPEED}]
        desc = station(ins)
        desc["programs"].append({"name": "ChangeDrill", "robot": ROBOT, "instructions": []})
        desc["programs"][0]["calls"] = ["ChangeDrill"]
        code, out, err, st = run_app(desc)
        self.assertEqual(code, 0, err)
        self.assertIn("calls the programs 'ChangeDrill': run the app on each of them too", out)
        self.assertIn("1 MoveC, 1 other instructions; 1 pauses, 2 program calls/code", out)
        self.assertIn("MoveC 'MoveC (Arc1, Arc2)' (left alone)", out)
        self.assertIn("call/code 'ChangeDrill'", out)
        self.assertEqual(st.programs[COPY]["instructions"][-4:], ins[-4:])

    def test_hole_data_from_hole_list_and_target_names_reach_filter_target(self):
        ins = drill_program(3)
        ins.insert(0, {"name": "Set Tool (Drill 6.8)", "type": robolink.INS_TYPE_CHANGETOOL})
        drills = [i for i, x in enumerate(ins) if x["name"].startswith("Drill ")]
        ins[drills[1]]["name"] += " tool=3 dia=7.0 feed=0.12 rpm=6000"
        desc = station(ins)
        desc["tools"] = [{"name": "Drill 6.8", "robot": ROBOT, "tcp_mm": SESSION.tool_pose_mm.tolist()}]
        real = roprec.Session
        RecordingSession.calls = []
        roprec.Session = RecordingSession
        try:
            code, out, err, st = run_app(desc, "--holes", HOLES)
        finally:
            roprec.Session = real
        self.assertEqual(code, 0, err)
        with open(HOLES, encoding="utf-8") as f:
            rows = {r["id"]: r for r in csv.DictReader(l for l in f if not l.startswith("#"))}
        expected = []
        for x in (x for x in ins if x.get("move_type") == robolink.MOVE_TYPE_LINEAR and not x.get("joint_target")):
            hid = x["name"].split()[1]
            p = {"tool": "Drill 6.8", "diameter_mm": float(rows[hid]["diameter"]), "depth_mm": float(rows[hid]["depth"])}
            if "tool=3" in x["name"]:
                p.update(tool="3", diameter_mm=7.0, feed_mm_per_rev=0.12, spindle_rpm=6000.0)
            expected.append(p)
        self.assertEqual(RecordingSession.calls, expected)
        self.assertNotIn("no hole data", out)
        self.assertEqual(st.params[app.HOLES_PARAM], HOLES)
        with open(HOLES, "rb") as f:
            self.assertEqual(st.params[app.HOLES_DATA_PARAM], f.read())
        # Later runs take the hole list the station keeps, even when its file has gone.
        desc["params"] = {app.HOLES_PARAM: "/gone/holes.csv", app.HOLES_DATA_PARAM: st.params[app.HOLES_DATA_PARAM]}
        RecordingSession.calls = []
        roprec.Session = RecordingSession
        try:
            code, out, err, _ = run_app(desc)
        finally:
            roprec.Session = RecordingSession.real
        self.assertEqual(code, 0, err)
        self.assertEqual(RecordingSession.calls, expected)
        # The roprec module as built: its filter_target either takes the process or the app refuses
        # (never the cell's drill in silence). It takes it: a program that changes tools (the
        # station's "Drill 6.8", then tool 3) on a single-drill cell is refused, nothing written.
        code, out, err, st = run_app(desc, "--holes", HOLES)
        try:
            SESSION.filter_target(np.eye(4), None, diameter_mm=6.8)
            takes_process = True
        except TypeError:
            takes_process = False
        except roprec.RoprecError:
            takes_process = True
        if takes_process:
            self.assertEqual(code, 2, err)
            self.assertIn("changes tools (Drill 6.8, then 3) but the cell has a single drill", err)
            self.assertNotIn(COPY, st.programs)
        else:
            self.assertEqual(code, 2)
            self.assertIn("filter_target takes no per-hole process (depth_mm, diameter_mm, tool)", err)
            self.assertNotIn(COPY, st.programs)

    def test_cell_and_hole_list_are_kept_as_station_parameters(self):
        code, _, err, st = run_app(station(drill_program(2)))
        self.assertEqual(code, 0, err)
        self.assertEqual(st.params[app.CELL_PARAM], CELL)
        code, _, err, st = run_app(None, cell=None, fresh=False)     # no --cell: the station's
        self.assertEqual(code, 0, err)
        desc = station(drill_program(2))
        desc["params"] = {app.CELL_PARAM: "/nonexistent/stored.xml"}
        code, _, err, _ = run_app(desc, cell=None)
        self.assertEqual(code, 2)
        self.assertIn("/nonexistent/stored.xml: cannot open file", err)
        os.environ["ROPREC_CELL"] = CELL
        try:
            code, _, err, _ = run_app(station(drill_program(2)), cell=None)
        finally:
            del os.environ["ROPREC_CELL"]
        self.assertEqual(code, 0, err)
        code, _, err, _ = run_app(station(drill_program(2)), cell=None)
        self.assertEqual(code, 2)
        self.assertIn("no roprec cell for this station", err)
        self.assertIn(app.CELL_PARAM, err)

    def test_refuses_when_robodk_accuracy_model_is_active(self):
        code, out, err, st = run_app(station(drill_program(5), accuracy_active=True))
        self.assertEqual(code, 2)
        self.assertIn("accuracy model is active", err)
        self.assertIn("compensate gravity twice", err)
        self.assertEqual([c for c in st.calls if c[0] in ("setInstruction", "setAccuracyActive", "Paste")], [])
        self.assertEqual(st.calls[-1][0], "ShowMessage")
        self.assertTrue(st.calls[-1][2])                   # a popup

    def test_api_without_accuracy_getter_needs_confirmation(self):
        code, _, err, st = run_app(station(drill_program(3), legacy_api=True))
        self.assertEqual(code, 2)
        self.assertIn("--assume-accuracy-inactive", err)
        self.assertFalse(set_calls(st))
        code, _, err, st = run_app(station(drill_program(3), legacy_api=True), "--assume-accuracy-inactive")
        self.assertEqual(code, 0, err)
        self.assertEqual(len(set_calls(st)), 6)

    def test_refuses_a_tool_other_than_the_cells(self):
        tool = SESSION.tool_pose_mm.copy()
        tool[2, 3] += 5.0
        code, _, err, st = run_app(station(drill_program(3), tool=tool))
        self.assertEqual(code, 2)
        self.assertIn("is not the cell's <tool>", err)
        self.assertFalse(set_calls(st))
        code, _, err, _ = run_app(station(drill_program(3), tool=tool), "--skip-tool-check")
        self.assertEqual(code, 0, err)

    def test_unreachable_target_changes_nothing(self):
        code, _, err, st = run_app(station(drill_program(4, far_hole=True)))
        self.assertEqual(code, 1)
        self.assertIn("could not be filtered; nothing changed", err)
        self.assertIn("Drill " + HOLE_ROWS[3][0], err)
        self.assertFalse(set_calls(st))
        self.assertNotIn(COPY, st.programs)

    def test_copy_sharing_targets_with_the_original_is_undone(self):
        desc = station(drill_program(3))
        desc["shared_targets"] = True
        code, _, err, st = run_app(desc)
        self.assertEqual(code, 1)
        self.assertIn("RoboDK changed the original program 'Drill'", err)
        self.assertEqual(st.programs["Drill"]["instructions"], drill_program(3))
        self.assertNotIn(COPY, st.programs)

    def test_dry_run_and_missing_program(self):
        code, out, err, st = run_app(station(drill_program(3)), "--dry-run")
        self.assertEqual(code, 0, err)
        self.assertIn("would compensate 6 linear", out)
        self.assertFalse([c for c in st.calls if c[0] in ("setInstruction", "Paste")])
        code, _, err, _ = run_app(station(drill_program(3)), "--program", "NoSuchProgram")
        self.assertEqual(code, 2)
        self.assertIn("no program named 'NoSuchProgram'", err)

    def test_bad_cell_reports_the_roprec_error(self):
        code, _, err, st = run_app(station(drill_program(2)), cell="/nonexistent/cell.xml")
        self.assertEqual(code, 2)
        self.assertIn("/nonexistent/cell.xml: cannot open file", err)

    def test_install_app_writes_the_app_and_its_appconfig(self):
        tmp = tempfile.mkdtemp()
        try:
            for _ in range(2):                              # installing again overwrites
                out = io.StringIO()
                with contextlib.redirect_stdout(out):
                    self.assertEqual(app.main(["--install-app", tmp]), 0)
            folder = Path(tmp) / app.APP_FOLDER
            self.assertEqual(sorted(p.name for p in folder.iterdir()), ["AppConfig.ini", APP.name])
            self.assertEqual((folder / APP.name).read_bytes(), APP.read_bytes())
            ini = configparser.ConfigParser()
            ini.optionxform = str
            ini.read(folder / "AppConfig.ini", encoding="utf-8")
            self.assertEqual(ini["General"]["MenuName"], "roprec")
            self.assertEqual(ini["General"]["MenuVisible"], "true")
            action = ini[APP.stem]                          # the AppLoader runs SECTION.py
            self.assertEqual(action["TypeOnContextMenu"], str(robolink.ITEM_TYPE_PROGRAM))
            self.assertEqual(action["Visible"], "true")
            err = io.StringIO()
            with contextlib.redirect_stderr(err):
                self.assertEqual(app.main(["--install-app", str(Path(tmp) / "missing")]), 2)
            self.assertIn("does not exist (create it: mkdir -p", err.getvalue())
        finally:
            shutil.rmtree(tmp)

    def test_headless_command_line(self):
        tmp = tempfile.mkdtemp()
        try:
            original = drill_program(6)
            st_file = Path(tmp) / "station.json"
            st_file.write_text(json.dumps(station(original)), encoding="utf-8")
            record = Path(tmp) / "record.json"
            saved = Path(tmp) / "saved.json"
            env = dict(os.environ, ROBODK_STUB_RECORD=str(record))
            r = subprocess.run([sys.executable, str(APP), "--headless", "--station", str(st_file), "--program", "Drill",
                                "--cell", CELL, "--make-program", tmp, "--save", str(saved)],
                               env=env, capture_output=True, text=True, timeout=300)
            self.assertEqual(r.returncode, 0, r.stderr)
            rec = json.loads(record.read_text(encoding="utf-8"))
            self.assertEqual(rec["launch_args"], ["-NEWINSTANCE", "-NOUI", "-EXIT_LAST_COM"])
            kinds = [c[0] for c in rec["calls"]]
            self.assertEqual(kinds, ["AddFile", "setParam", "Paste", "setName"] + ["setInstruction"] * 12 +
                             ["Item.setParam", "MakeProgram", "Save"])
            self.assertNotIn("ShowMessage", kinds)         # headless: no popups
            self.assertTrue((Path(tmp) / (COPY + ".json")).exists())
            programs = {p["name"]: p for p in json.loads(saved.read_text(encoding="utf-8"))["programs"]}
            self.assertEqual(programs["Drill"]["instructions"], original)
            final = programs[COPY]["instructions"]
            for i, ins in enumerate(original):
                if ins.get("move_type") == robolink.MOVE_TYPE_LINEAR and not ins.get("joint_target"):
                    pose, _ = expected_edit(ins)
                    np.testing.assert_allclose((FRAME @ np.array(final[i]["pose"]))[:3, 3], pose[:3, 3], rtol=0, atol=1e-9)
                else:
                    self.assertEqual(final[i], ins)
            self.assertIn("program generated into", r.stdout)
        finally:
            shutil.rmtree(tmp)


def published_api():
    """{Class.method: inspect.Signature} and {constant: value} from tests/data/robodk/api_signatures.txt."""
    methods, constants = {}, {}
    for line in API_LIST.read_text(encoding="utf-8").splitlines():
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        if " = " in line:
            name, value = line.split(" = ")
            constants[name] = int(value)
            continue
        name, params = line[:line.index("(")], line[line.index("("):]
        fn = ast.parse("def f(self, %s): pass" % params[1:-1] if params != "()" else "def f(self): pass").body[0]
        ns = {}
        exec(compile(ast.Module(body=[fn], type_ignores=[]), "api", "exec"), ns)
        methods[name] = inspect.signature(ns["f"])
    return methods, constants


class PublishedApiTest(unittest.TestCase):
    """The stand-in has RoboDK's published signatures, and every call the app makes (in two full
    runs here, and in whatever tests of this file ran before) binds to them."""

    def test_stub_has_the_published_signatures(self):
        from robodk import robomath
        methods, constants = published_api()
        classes = {"Robolink": robolink.Robolink, "Item": robolink.Item, "Mat": robomath.Mat}
        for name, sig in methods.items():
            cls, method = name.split(".")
            impl = inspect.unwrap(getattr(classes[cls], method))
            self.assertEqual(str(inspect.signature(impl)), str(sig), name)
        for name, value in constants.items():
            self.assertEqual(getattr(robolink, name), value, name)

    def test_every_call_the_app_makes_is_in_the_published_api(self):
        methods, _ = published_api()
        RoboDKAppTest("test_frame_and_tool_instructions_apply_in_program_order").debug()
        RoboDKAppTest("test_headless_command_line").debug()
        self.assertGreater(len(robolink.API_CALLS), 100)
        used = set()
        for name, args, kwargs in robolink.API_CALLS:
            self.assertIn(name, methods, "%s is not in RoboDK's published API" % name)
            methods[name].bind(None, *args, **kwargs)       # raises TypeError when the call does not fit
            used.add(name)
        print("robodk api: %d calls of %d published methods, all with RoboDK's signatures"
              % (len(robolink.API_CALLS), len(used)))
        # The app's source names no RoboDK method outside the list.
        tree = ast.parse(APP.read_text(encoding="utf-8"))
        robodk_names = {n.split(".")[1] for n in methods}
        stub_names = {n for n in dir(robolink.Item) + dir(robolink.Robolink) if not n.startswith("_")}
        called = {node.func.attr for node in ast.walk(tree)
                  if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)}
        self.assertEqual(sorted((called & stub_names) - robodk_names), [])


if __name__ == "__main__":
    unittest.main(verbosity=2)
