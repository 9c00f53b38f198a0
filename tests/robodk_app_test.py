"""roprec's RoboDK app (plugin/robodk/roprec_compensate_program.py) against the RoboDK stand-in
(tests/robodk_stub): on a program built from the sample hole list, every MoveL to a Cartesian target
is written back as Session.filter_target gives it, everything else is left alone; an active RoboDK
accuracy model, a tool mismatch, an unreachable target and a missing program are refused; the
headless command line works.

Run by ctest with PYTHONPATH = tests/robodk_stub + the build tree's python/ folder.
"""

import contextlib
import csv
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


def run_app(description, *args):
    """Runs the app in this process against a RoboDK (stand-in) holding `description`."""
    robolink.STATION = robolink.Station(description)
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = app.main(["--cell", CELL] + list(args))
    return code, out.getvalue(), err.getvalue(), robolink.STATION


def expected_edit(ins):
    """What the app must write for a MoveL to a Cartesian target: Session.filter_target of the
    target in the base frame, seeded with its joints, back in the program's frame."""
    wanted = FRAME @ np.array(ins["pose"])
    pose, joints = SESSION.filter_target(wanted, ins["joints"])
    return pose, joints


class RoboDKAppTest(unittest.TestCase):
    def test_filters_every_linear_cartesian_target_and_leaves_the_rest(self):
        original = drill_program()
        code, out, err, st = run_app(station(original))
        self.assertEqual(code, 0, err)
        sets = [c for c in st.calls if c[0] == "setInstruction"]
        linear = [i for i, ins in enumerate(original) if ins["type"] == robolink.INS_TYPE_MOVE and
                  ins["move_type"] == robolink.MOVE_TYPE_LINEAR and not ins["joint_target"]]
        self.assertEqual(len(linear), 2 * len(HOLE_ROWS))
        self.assertEqual([c[2] for c in sets], linear)     # only those, each once, in order
        final = st.programs["Drill"]["instructions"]
        worst_mm, worst_real_um = 0.0, 0.0
        for i, ins in enumerate(original):
            if i not in linear:
                self.assertEqual(final[i], ins)            # joint moves, joint targets, code: untouched
                continue
            new = final[i]
            self.assertEqual((new["name"], new["type"], new["move_type"], new["joint_target"]),
                             (ins["name"], ins["type"], ins["move_type"], ins["joint_target"]))
            pose, joints = expected_edit(ins)
            written_base = FRAME @ np.array(new["pose"])
            np.testing.assert_allclose(written_base[:3, 3], pose[:3, 3], rtol=0, atol=1e-9)
            np.testing.assert_allclose(written_base[:3, :3], pose[:3, :3], rtol=0, atol=1e-12)
            np.testing.assert_allclose(np.array(new["pose"]), np.linalg.inv(FRAME) @ pose, rtol=0, atol=1e-9)
            np.testing.assert_allclose(new["joints"], joints, rtol=0, atol=1e-12)
            worst_mm = max(worst_mm, float(np.linalg.norm(written_base[:3, 3] - pose[:3, 3])))
            if i % 25 == 0:  # the predicted real TCP at the written joints is the original target
                dev = SESSION.predict_joints(new["joints"])["deviation_um"]
                real = written_base[:3, 3] + dev * 1e-3
                worst_real_um = max(worst_real_um,
                                    1e3 * float(np.linalg.norm(real - (FRAME @ np.array(ins["pose"]))[:3, 3])))
        self.assertLess(worst_real_um, 0.1)
        self.assertIn("compensated %d linear Cartesian targets" % len(linear), out)
        self.assertIn("left alone: %d joint moves, 1 moves to joint targets, 1 other instructions"
                      % len(HOLE_ROWS), out)
        # Inside RoboDK the summary goes to the status bar, not a popup.
        self.assertEqual(st.calls[-1][0], "ShowMessage")
        self.assertFalse(st.calls[-1][2])
        print("robodk app: %d targets filtered, written = filter_target to %.2g mm, real TCP off by max %.3g um"
              % (len(linear), worst_mm, worst_real_um))

    def test_refuses_when_robodk_accuracy_model_is_active(self):
        code, out, err, st = run_app(station(drill_program(5), accuracy_active=True))
        self.assertEqual(code, 2)
        self.assertIn("accuracy model is active", err)
        self.assertIn("compensate gravity twice", err)
        self.assertEqual([c for c in st.calls if c[0] in ("setInstruction", "setAccuracyActive")], [])
        self.assertEqual(st.calls[-1][0], "ShowMessage")
        self.assertTrue(st.calls[-1][2])                   # a popup

    def test_api_without_accuracy_getter_needs_confirmation(self):
        code, _, err, st = run_app(station(drill_program(3), legacy_api=True))
        self.assertEqual(code, 2)
        self.assertIn("--assume-accuracy-inactive", err)
        self.assertFalse([c for c in st.calls if c[0] == "setInstruction"])
        code, _, err, st = run_app(station(drill_program(3), legacy_api=True), "--assume-accuracy-inactive")
        self.assertEqual(code, 0, err)
        self.assertEqual(len([c for c in st.calls if c[0] == "setInstruction"]), 6)

    def test_refuses_a_tool_other_than_the_cells(self):
        tool = SESSION.tool_pose_mm.copy()
        tool[2, 3] += 5.0
        code, _, err, st = run_app(station(drill_program(3), tool=tool))
        self.assertEqual(code, 2)
        self.assertIn("is not the cell's <tool>", err)
        self.assertFalse([c for c in st.calls if c[0] == "setInstruction"])
        code, _, err, _ = run_app(station(drill_program(3), tool=tool), "--skip-tool-check")
        self.assertEqual(code, 0, err)

    def test_unreachable_target_changes_nothing(self):
        code, _, err, st = run_app(station(drill_program(4, far_hole=True)))
        self.assertEqual(code, 1)
        self.assertIn("could not be filtered; nothing changed", err)
        self.assertIn("Drill " + HOLE_ROWS[3][0], err)
        self.assertFalse([c for c in st.calls if c[0] == "setInstruction"])

    def test_dry_run_and_missing_program(self):
        code, out, err, st = run_app(station(drill_program(3)), "--dry-run")
        self.assertEqual(code, 0, err)
        self.assertIn("would compensate 6 linear", out)
        self.assertFalse([c for c in st.calls if c[0] == "setInstruction"])
        code, _, err, _ = run_app(station(drill_program(3)), "--program", "NoSuchProgram")
        self.assertEqual(code, 2)
        self.assertIn("no program named 'NoSuchProgram'", err)

    def test_bad_cell_reports_the_roprec_error(self):
        code, _, err, st = run_app(station(drill_program(2)), "--cell", "/nonexistent/cell.xml")
        self.assertEqual(code, 2)
        self.assertIn("/nonexistent/cell.xml: cannot open file", err)

    def test_cell_from_environment_and_from_file_beside_the_app(self):
        tmp = tempfile.mkdtemp()
        try:
            robolink.STATION = robolink.Station(station(drill_program(2)))
            with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
                os.environ["ROPREC_CELL"] = CELL
                try:
                    self.assertEqual(app.main([]), 0)
                finally:
                    del os.environ["ROPREC_CELL"]
            copy = Path(tmp) / APP.name
            shutil.copy(APP, copy)
            (Path(tmp) / "roprec_cell.txt").write_text(CELL + "\n", encoding="utf-8")
            spec = importlib.util.spec_from_file_location("app_copy", copy)
            module = importlib.util.module_from_spec(spec)
            spec.loader.exec_module(module)
            robolink.STATION = robolink.Station(station(drill_program(2)))
            with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
                self.assertEqual(module.main([]), 0)
            self.assertEqual(len([c for c in robolink.STATION.calls if c[0] == "setInstruction"]), 4)
            # Without any cell: refused.
            err = io.StringIO()
            with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
                self.assertEqual(app.main([]), 2)
            self.assertIn("no roprec cell", err.getvalue())
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
            self.assertEqual(kinds, ["AddFile"] + ["setInstruction"] * 12 + ["MakeProgram", "Save"])
            self.assertNotIn("ShowMessage", kinds)         # headless: no popups
            self.assertTrue((Path(tmp) / "Drill.json").exists())
            final = json.loads(saved.read_text(encoding="utf-8"))["programs"][0]["instructions"]
            for i, ins in enumerate(original):
                if ins.get("move_type") == robolink.MOVE_TYPE_LINEAR and not ins.get("joint_target"):
                    pose, _ = expected_edit(ins)
                    np.testing.assert_allclose((FRAME @ np.array(final[i]["pose"]))[:3, 3], pose[:3, 3], rtol=0, atol=1e-9)
                else:
                    self.assertEqual(final[i], ins)
            self.assertIn("program generated into", r.stdout)
        finally:
            shutil.rmtree(tmp)


if __name__ == "__main__":
    unittest.main(verbosity=2)
