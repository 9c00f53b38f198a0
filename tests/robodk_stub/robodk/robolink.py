"""Stand-in for robodk.robolink: the calls roprec's RoboDK app makes, with RoboDK's signatures.

Instead of talking to a RoboDK process it works on ``STATION``, an in-memory station that a test
fills, or that ``Robolink.AddFile`` loads from a JSON description::

    {"robots": [{"name": "R", "tool_mm": 4x4, "frame_mm": 4x4, "base_abs_mm": 4x4,
                 "accuracy_active": false, "legacy_api": false}],
     "frames": [{"name": "Part", "pose_abs_mm": 4x4}],
     "tools": [{"name": "Drill 6.8", "robot": "R", "tcp_mm": 4x4}],
     "programs": [{"name": "P", "robot": "R", "params": {}, "calls": ["Sub"], "instructions": [
         {"name": "Set Reference Frame (Part)", "type": 3},
         {"name": "MoveL 1", "type": 0, "move_type": 2, "joint_target": 0, "pose": 4x4, "joints": [6]},
         {"name": "Spindle on", "type": 8}]}],
     "params": {"ROPREC_CELL": "..."},
     "selected": "P",
     "shared_targets": false}

As in RoboDK, Item.Instruction() gives a move's target only for INS_TYPE_MOVE; other instructions
give their name and type. ``shared_targets`` makes a pasted program share its move instructions
with the original (a RoboDK whose copy keeps the original's target items).

Every call that changes something is recorded in ``STATION.calls`` (and, when the environment
variable ROBODK_STUB_RECORD names a file, written there as JSON after each call, so a test can
inspect an app run in another process). Every API call at all is appended to ``API_CALLS`` as
(Class.method, args, kwargs), so that a test can check it against RoboDK's published signatures.
``Robolink(args=[... "-NEWINSTANCE" ...])`` starts from an empty station, like a new RoboDK
instance; ``Robolink()`` attaches to the current one.
"""

import copy
import functools
import json
import os

from .robomath import Mat

ITEM_TYPE_STATION = 1
ITEM_TYPE_ROBOT = 2
ITEM_TYPE_FRAME = 3
ITEM_TYPE_TOOL = 4
ITEM_TYPE_PROGRAM = 8

INS_TYPE_INVALID = -1
INS_TYPE_MOVE = 0
INS_TYPE_MOVEC = 1
INS_TYPE_CHANGESPEED = 2
INS_TYPE_CHANGEFRAME = 3
INS_TYPE_CHANGETOOL = 4
INS_TYPE_PAUSE = 6
INS_TYPE_CODE = 8

MOVE_TYPE_INVALID = -1
MOVE_TYPE_JOINT = 1
MOVE_TYPE_LINEAR = 2
MOVE_TYPE_CIRCULAR = 3

RUNMODE_MAKE_ROBOTPROG = 3

API_CALLS = []


def api(method):
    """Records a call of an API method (for the signature check)."""
    owner = method.__qualname__

    @functools.wraps(method)
    def wrapper(self, *args, **kwargs):
        API_CALLS.append((owner, args, kwargs))
        return method(self, *args, **kwargs)
    return wrapper


class Station(object):
    """The stand-in's RoboDK: robots, frames, tools, programs, parameters and the recorded calls."""

    def __init__(self, description=None):
        d = copy.deepcopy(description or {})
        self.robots = {r["name"]: r for r in d.get("robots", [])}
        self.frames = {f["name"]: f for f in d.get("frames", [])}
        self.tools = {t["name"]: t for t in d.get("tools", [])}
        self.programs = {p["name"]: {"name": p["name"], "robot": p.get("robot"), "params": p.get("params", {}),
                                     "calls": p.get("calls", []), "instructions": p.get("instructions", [])}
                         for p in d.get("programs", [])}
        self.params = d.get("params", {})
        self.selected = d.get("selected")
        self.shared_targets = d.get("shared_targets", False)
        self.clipboard = None
        self.calls = []
        self.launch_args = []

    def description(self):
        """The station as its JSON description."""
        return {"robots": list(self.robots.values()), "frames": list(self.frames.values()),
                "tools": list(self.tools.values()),
                "programs": [{"name": p["name"], "robot": p["robot"], "calls": p["calls"],
                              "instructions": p["instructions"],
                              "params": {k: v.decode("utf-8") if isinstance(v, bytes) else v
                                         for k, v in p["params"].items()}}
                             for p in self.programs.values()],
                "params": {k: v.decode("utf-8") if isinstance(v, bytes) else v for k, v in self.params.items()},
                "selected": self.selected}

    def record(self, *call):
        self.calls.append(list(call))
        path = os.environ.get("ROBODK_STUB_RECORD")
        if path:
            with open(path, "w", encoding="utf-8") as f:
                json.dump({"launch_args": self.launch_args, "calls": self.calls}, f)

    def items(self, itemtype):
        return {ITEM_TYPE_ROBOT: self.robots, ITEM_TYPE_FRAME: self.frames, ITEM_TYPE_TOOL: self.tools,
                ITEM_TYPE_PROGRAM: self.programs}.get(itemtype, {})


STATION = Station()


def _identity():
    return [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]]


class Item(object):
    """A station item (robot, frame, tool, program, station) or an invalid one."""

    def __init__(self, link, name=None, itemtype=-1):
        self.link = link
        self._name = name
        self._type = itemtype

    def _station(self):
        return self.link._station

    def _data(self):
        return self._station().items(self._type)[self._name]

    @api
    def Valid(self, check_deleted=False):
        """True when the item exists."""
        if self._name is None:
            return False
        return self._type == ITEM_TYPE_STATION or self._name in self._station().items(self._type)

    @api
    def Name(self):
        """The item's name."""
        return self._name or ""

    @api
    def Type(self):
        """The item's type (ITEM_TYPE_*)."""
        return self._type

    @api
    def setName(self, name):
        """Renames the item (recorded)."""
        items = self._station().items(self._type)
        items[name] = items.pop(self._name)
        items[name]["name"] = name
        self._station().record("setName", self._name, name)
        self._name = name
        return self

    @api
    def Parent(self):
        """A program's parent: the station."""
        return Item(self.link, "station", ITEM_TYPE_STATION)

    @api
    def Copy(self, copy_children=True):
        """Copies the item to the clipboard."""
        self.link.Copy(self, copy_children)

    @api
    def Paste(self):
        """Pastes the clipboard as a child of this item."""
        return self.link.Paste(self)

    @api
    def Delete(self):
        """Removes the item (recorded)."""
        del self._station().items(self._type)[self._name]
        self._station().record("Delete", self._name)

    @api
    def getParam(self, param):
        """An item's custom data (bytes; empty when none)."""
        return self._data().get("params", {}).get(param, b"")

    @api
    def setParam(self, param, value="", skip_result=False):
        """Stores an item's custom data (recorded)."""
        self._data().setdefault("params", {})[param] = value
        self._station().record("Item.setParam", self._name, param,
                               value.decode("utf-8") if isinstance(value, bytes) else value)
        return ""

    @api
    def PoseAbs(self):
        """The pose in the station: a robot's base, a frame."""
        key = "base_abs_mm" if self._type == ITEM_TYPE_ROBOT else "pose_abs_mm"
        return Mat(self._data().get(key, _identity()))

    # ---- program
    def _program(self):
        return self._station().programs[self._name]

    @api
    def getLink(self, type_linked=ITEM_TYPE_ROBOT):
        """The robot linked to a program."""
        if self._type != ITEM_TYPE_PROGRAM or type_linked != ITEM_TYPE_ROBOT:
            return Item(self.link)
        name = self._program().get("robot")
        if name not in self._station().robots:
            return Item(self.link)
        cls = LegacyRobotItem if self._station().robots[name].get("legacy_api") else Item
        return cls(self.link, name, ITEM_TYPE_ROBOT)

    @api
    def Childs(self):
        """A program's called programs (RoboDK: Childs() of a program lists its subprograms)."""
        return [Item(self.link, n, ITEM_TYPE_PROGRAM) for n in self._program().get("calls", [])]

    @api
    def InstructionCount(self):
        """The number of instructions of a program."""
        return len(self._program()["instructions"])

    @api
    def Instruction(self, ins_id=-1):
        """(name, instype, movetype, isjointtarget, target pose Mat, joints Mat) of instruction ins_id."""
        ins = self._program()["instructions"][ins_id]
        if ins["type"] != INS_TYPE_MOVE:
            return ins["name"], ins["type"], None, None, None, None
        return (ins["name"], ins["type"], ins["move_type"], ins.get("joint_target", 0),
                Mat(ins.get("pose", _identity())), Mat(list(ins.get("joints", [0.0] * 6))))

    @api
    def setInstruction(self, ins_id, name, instype, movetype, isjointtarget, target, joints):
        """Updates instruction ins_id (recorded). Shared instructions change in both programs."""
        pose = target.Rows() if isinstance(target, Mat) else [list(r) for r in target]
        jl = joints.list() if isinstance(joints, Mat) else [float(x) for x in joints]
        ins = self._program()["instructions"][ins_id]
        ins.clear()
        ins.update({"name": name, "type": instype, "move_type": movetype, "joint_target": isjointtarget,
                    "pose": [[float(x) for x in r] for r in pose], "joints": jl})
        self._station().record("setInstruction", self._name, ins_id, dict(ins))

    @api
    def MakeProgram(self, folder_path="", run_mode=RUNMODE_MAKE_ROBOTPROG):
        """Writes FOLDER/NAME.json (the program's instructions); returns (success, log, transfer_ok)."""
        path = os.path.join(folder_path, self._name + ".json")
        with open(path, "w", encoding="utf-8") as f:
            json.dump(self._program()["instructions"], f)
        self._station().record("MakeProgram", self._name, folder_path)
        return True, "Program generated: " + path, False

    # ---- robot, tool
    def _robot(self):
        return self._station().robots[self._name]

    @api
    def AccuracyActive(self):
        """True when the robot's accurate (calibrated) kinematics are used."""
        return bool(self._robot().get("accuracy_active", False))

    @api
    def setAccuracyActive(self, accurate=1):
        """Activates (1) or deactivates (0) the accurate kinematics (recorded)."""
        self._robot()["accuracy_active"] = bool(accurate)
        self._station().record("setAccuracyActive", self._name, int(accurate))

    @api
    def PoseTool(self):
        """A robot's active tool, or a tool's TCP, in the flange frame."""
        if self._type == ITEM_TYPE_TOOL:
            return Mat(self._data().get("tcp_mm", _identity()))
        return Mat(self._robot().get("tool_mm", _identity()))

    @api
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
        API_CALLS.append(("Robolink.__init__", (), {"robodk_ip": robodk_ip, "port": port, "args": args}))
        args = [args] if isinstance(args, str) and args else list(args or [])
        if "-NEWINSTANCE" in args:
            STATION = Station()
        self._station = STATION
        self._station.launch_args = args
        self.ARGUMENTS = args

    @api
    def Item(self, name, itemtype=None):
        """The item named `name` (of `itemtype`), or an invalid item."""
        for t in (ITEM_TYPE_PROGRAM, ITEM_TYPE_ROBOT, ITEM_TYPE_FRAME, ITEM_TYPE_TOOL):
            if itemtype in (None, t) and name in self._station.items(t):
                return Item(self, name, t)
        return Item(self)

    @api
    def ItemList(self, filter=None, list_names=False):
        """The items (or their names) of one type."""
        names = list(self._station.items(filter))
        return names if list_names else [Item(self, n, filter) for n in names]

    @api
    def ItemUserPick(self, message="Pick one item", itemtype_or_list=None):
        """The only program; invalid otherwise (the user cancelled)."""
        s = self._station
        if itemtype_or_list == ITEM_TYPE_PROGRAM and len(s.programs) == 1:
            return Item(self, next(iter(s.programs)), ITEM_TYPE_PROGRAM)
        return Item(self)

    @api
    def Selection(self):
        """The selected items: the selected program, if any."""
        s = self._station
        return [Item(self, s.selected, ITEM_TYPE_PROGRAM)] if s.selected in s.programs else []

    @api
    def AddFile(self, filename, parent=0):
        """Loads a station description (JSON, see the module docstring)."""
        try:
            with open(filename, encoding="utf-8") as f:
                d = json.load(f)
        except (OSError, ValueError):
            return Item(self)
        loaded = Station(d)
        for t in (ITEM_TYPE_ROBOT, ITEM_TYPE_FRAME, ITEM_TYPE_TOOL, ITEM_TYPE_PROGRAM):
            self._station.items(t).update(loaded.items(t))
        self._station.params.update(loaded.params)
        self._station.selected = loaded.selected
        self._station.record("AddFile", filename)
        return Item(self, os.path.basename(filename), ITEM_TYPE_STATION)

    @api
    def Save(self, filename, itemsave=0):
        """Saves the station description (JSON)."""
        with open(filename, "w", encoding="utf-8") as f:
            json.dump(self._station.description(), f)
        self._station.record("Save", filename)

    @api
    def Copy(self, item, copy_childs=True):
        """Copies a program to the clipboard."""
        self._station.clipboard = item._program()

    @api
    def Paste(self, paste_to=0, paste_times=1):
        """Pastes the clipboard's program into the station under a new name (recorded)."""
        s = self._station
        source = s.clipboard
        name = source["name"] + " (copy)"
        while name in s.programs:
            name += "'"
        instructions = (list(source["instructions"]) if s.shared_targets
                        else copy.deepcopy(source["instructions"]))
        s.programs[name] = {"name": name, "robot": source["robot"], "params": copy.deepcopy(source["params"]),
                            "calls": list(source["calls"]), "instructions": instructions}
        s.record("Paste", source["name"], name)
        return Item(self, name, ITEM_TYPE_PROGRAM)

    @api
    def getParam(self, param="PATH_OPENSTATION", str_type=True):
        """A station parameter (str_type=False: its binary data, b"" when none), or None when unknown."""
        value = self._station.params.get(param)
        if not str_type:
            return value.encode("utf-8") if isinstance(value, str) else (value or b"")
        return value.decode("utf-8") if isinstance(value, bytes) else value

    @api
    def setParam(self, param, value):
        """Sets a station parameter, or binary data when value is bytes (recorded)."""
        self._station.params[param] = value if isinstance(value, bytes) else str(value)
        self._station.record("setParam", param, value.decode("utf-8") if isinstance(value, bytes) else str(value))

    @api
    def ShowMessage(self, message, popup=True):
        """Shows a message (recorded)."""
        self._station.record("ShowMessage", message, bool(popup))
