"""Stand-in for robodk.robolink: the calls roprec's RoboDK app makes, with RoboDK's signatures.

Instead of talking to a RoboDK process it works on ``STATION``, an in-memory station (robots and
programs with their instructions) that a test fills, or that ``Robolink.AddFile`` loads from a
JSON description::

    {"robots": [{"name": "R", "tool_mm": 4x4, "frame_mm": 4x4, "accuracy_active": false,
                 "legacy_api": false}],
     "programs": [{"name": "P", "robot": "R", "instructions": [
         {"name": "MoveL 1", "type": 0, "move_type": 2, "joint_target": 0, "pose": 4x4, "joints": [6]},
         {"name": "Spindle on", "type": 8}]}],
     "selected": "P"}

Every call that changes something is recorded in ``STATION.calls`` (and, when the environment
variable ROBODK_STUB_RECORD names a file, written there as JSON after each call, so a test can
inspect an app run in another process). ``Robolink(args=[... "-NEWINSTANCE" ...])`` starts from an
empty station, like a new RoboDK instance; ``Robolink()`` attaches to the current one.
"""

import json
import os

from .robomath import Mat

ITEM_TYPE_STATION = 1
ITEM_TYPE_ROBOT = 2
ITEM_TYPE_PROGRAM = 8

INS_TYPE_INVALID = -1
INS_TYPE_MOVE = 0
INS_TYPE_MOVEC = 1
INS_TYPE_CODE = 8

MOVE_TYPE_INVALID = -1
MOVE_TYPE_JOINT = 1
MOVE_TYPE_LINEAR = 2
MOVE_TYPE_CIRCULAR = 3

RUNMODE_MAKE_ROBOTPROG = 3


class Station(object):
    """The stand-in's RoboDK: robots, programs, the selected program, and the recorded calls."""

    def __init__(self, description=None):
        d = description or {}
        self.robots = {r["name"]: dict(r) for r in d.get("robots", [])}
        self.programs = {p["name"]: {"name": p["name"], "robot": p.get("robot"),
                                     "instructions": [dict(i) for i in p.get("instructions", [])]}
                         for p in d.get("programs", [])}
        self.selected = d.get("selected")
        self.calls = []
        self.launch_args = []

    def description(self):
        """The station as its JSON description."""
        return {"robots": list(self.robots.values()), "programs": list(self.programs.values()),
                "selected": self.selected}

    def record(self, *call):
        self.calls.append(list(call))
        path = os.environ.get("ROBODK_STUB_RECORD")
        if path:
            with open(path, "w", encoding="utf-8") as f:
                json.dump({"launch_args": self.launch_args, "calls": self.calls}, f)


STATION = Station()


def _identity():
    return [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]]


class Item(object):
    """A station item (robot, program, station) or an invalid one."""

    def __init__(self, link, name=None, itemtype=-1):
        self.link = link
        self._name = name
        self._type = itemtype

    def _station(self):
        return self.link._station

    def Valid(self, check_deleted=False):
        """True when the item exists."""
        return self._name is not None

    def Name(self):
        """The item's name."""
        return self._name or ""

    def Type(self):
        """The item's type (ITEM_TYPE_*)."""
        return self._type

    # ---- program
    def _program(self):
        return self._station().programs[self._name]

    def getLink(self, type_linked=ITEM_TYPE_ROBOT):
        """The robot linked to a program."""
        if self._type != ITEM_TYPE_PROGRAM or type_linked != ITEM_TYPE_ROBOT:
            return Item(self.link)
        name = self._program().get("robot")
        if name not in self._station().robots:
            return Item(self.link)
        cls = LegacyRobotItem if self._station().robots[name].get("legacy_api") else Item
        return cls(self.link, name, ITEM_TYPE_ROBOT)

    def InstructionCount(self):
        """The number of instructions of a program."""
        return len(self._program()["instructions"])

    def Instruction(self, ins_id=-1):
        """(name, instype, movetype, isjointtarget, target pose Mat, joints Mat) of instruction ins_id."""
        ins = self._program()["instructions"][ins_id]
        if ins["type"] != INS_TYPE_MOVE:
            return ins["name"], ins["type"], None, None, None, None
        return (ins["name"], ins["type"], ins["move_type"], ins.get("joint_target", 0),
                Mat(ins.get("pose", _identity())), Mat(list(ins.get("joints", [0.0] * 6))))

    def setInstruction(self, ins_id, name, instype, movetype, isjointtarget, target, joints):
        """Updates instruction ins_id (recorded)."""
        pose = target.Rows() if isinstance(target, Mat) else [list(r) for r in target]
        jl = joints.list() if isinstance(joints, Mat) else [float(x) for x in joints]
        ins = {"name": name, "type": instype, "move_type": movetype, "joint_target": isjointtarget,
               "pose": [[float(x) for x in r] for r in pose], "joints": jl}
        self._program()["instructions"][ins_id] = ins
        self._station().record("setInstruction", self._name, ins_id, ins)

    def MakeProgram(self, folder_path="", run_mode=RUNMODE_MAKE_ROBOTPROG):
        """Writes FOLDER/NAME.json (the program's instructions); returns (success, log, transfer_ok)."""
        path = os.path.join(folder_path, self._name + ".json")
        with open(path, "w", encoding="utf-8") as f:
            json.dump(self._program(), f)
        self._station().record("MakeProgram", self._name, folder_path)
        return True, "Program generated: " + path, False

    # ---- robot
    def _robot(self):
        return self._station().robots[self._name]

    def AccuracyActive(self):
        """True when the robot's accurate (calibrated) kinematics are used."""
        return bool(self._robot().get("accuracy_active", False))

    def setAccuracyActive(self, accurate=1):
        """Activates (1) or deactivates (0) the accurate kinematics (recorded)."""
        self._robot()["accuracy_active"] = bool(accurate)
        self._station().record("setAccuracyActive", self._name, int(accurate))

    def PoseTool(self):
        """The active tool (TCP) in the flange frame."""
        return Mat(self._robot().get("tool_mm", _identity()))

    def PoseFrame(self):
        """The active reference frame in the robot base frame."""
        return Mat(self._robot().get("frame_mm", _identity()))


class LegacyRobotItem(Item):
    """A robot of an older RoboDK API that has no AccuracyActive() getter."""

    def __getattribute__(self, name):
        if name == "AccuracyActive":
            raise AttributeError("'Item' object has no attribute 'AccuracyActive'")
        return object.__getattribute__(self, name)


class Robolink(object):
    """The link to (the stand-in's) RoboDK."""

    def __init__(self, robodk_ip="localhost", port=None, args=[], robodk_path=None, close_std_out=False,
                 quit_on_close=False, com_object=None, skipstatus=False):
        global STATION
        args = [args] if isinstance(args, str) and args else list(args or [])
        if "-NEWINSTANCE" in args:
            STATION = Station()
        self._station = STATION
        self._station.launch_args = args
        self.ARGUMENTS = args

    def Item(self, name, itemtype=None):
        """The item named `name` (of `itemtype`), or an invalid item."""
        s = self._station
        if itemtype in (None, ITEM_TYPE_PROGRAM) and name in s.programs:
            return Item(self, name, ITEM_TYPE_PROGRAM)
        if itemtype in (None, ITEM_TYPE_ROBOT) and name in s.robots:
            return Item(self, name, ITEM_TYPE_ROBOT)
        return Item(self)

    def ItemUserPick(self, message="Pick one item", itemtype_or_list=None):
        """The selected program, else the only one; invalid when none (the user cancelled)."""
        s = self._station
        if itemtype_or_list == ITEM_TYPE_PROGRAM:
            if s.selected in s.programs:
                return Item(self, s.selected, ITEM_TYPE_PROGRAM)
            if len(s.programs) == 1:
                return Item(self, next(iter(s.programs)), ITEM_TYPE_PROGRAM)
        return Item(self)

    def AddFile(self, filename, parent=0):
        """Loads a station description (JSON, see the module docstring)."""
        try:
            with open(filename, encoding="utf-8") as f:
                d = json.load(f)
        except (OSError, ValueError):
            return Item(self)
        loaded = Station(d)
        self._station.robots.update(loaded.robots)
        self._station.programs.update(loaded.programs)
        self._station.selected = loaded.selected
        self._station.record("AddFile", filename)
        return Item(self, os.path.basename(filename), ITEM_TYPE_STATION)

    def Save(self, filename, itemsave=0):
        """Saves the station description (JSON)."""
        with open(filename, "w", encoding="utf-8") as f:
            json.dump(self._station.description(), f)
        self._station.record("Save", filename)

    def ShowMessage(self, message, popup=True):
        """Shows a message (recorded)."""
        self._station.record("ShowMessage", message, bool(popup))
