"""roprec — predict where an industrial robot really drills, and pre-offset its targets.

The Python face of libroprec (the same library as the ``roprec`` command line and the C ABI
``roprec.h``), giving the same numbers.

Units and frames
    mm, degrees; deviations in µm (translation) and µrad (rotation). Poses are 4x4 numpy arrays
    (homogeneous, mm): the TCP (flange x the cell's ``<tool>``) in the robot base frame (the robot
    card's base link; FANUC: the World frame at J2 height). Joints of a Session are in the robot
    controller's convention (as the teach pendant shows them).

API
    ``__version__``                          the library version
    ``Session(cell_path)``                   a cell loaded once, for one target at a time:
        ``.filter_target(pose_mm, seed_joints_deg=None, *, tool=None, diameter_mm=None,
        depth_mm=None, feed_mm_per_rev=None, spindle_rpm=None, details=False)
        -> (pose_mm, joints_deg)``           (the hole's process; None: the cell's)
        ``.filter_targets(poses_mm, seed_joints_deg=None, holes=None) -> dict``   a program's
        targets in order (RoboDK's FilterProgram), one process dict per hole
        ``.predict_joints(joints_deg, *, tool=None, diameter_mm=None, ...) -> dict``
        ``.hole_pose(position_mm, direction) -> pose_mm``
    ``predict(cell, program, holes=None, json_out=None) -> Prediction``   (a list of per-hole dicts)
    ``compensate(cell, program, out, orientation="keep", targets=None, holes=None) -> dict``
    ``verify(cell, program, measured, holes=None, register="none", calibrate=None, json_out=None,
    ..., poses=None, u_rot=None) -> dict``    measured holes (CMM) or tracker poses vs prediction;
                                              new robot card
    ``plan_test(cell, region, count, out) -> dict``   D-optimal drilling test program

Errors
    ``RoprecError`` (subclass of Exception) and its subclasses ``InputError`` (a bad file:
    ``str(e)`` is ``FILE:LINE: what is wrong``, as the CLI prints it after ``roprec: error:``),
    ``UsageError`` (a bad argument; also a ValueError) and ``ItemError`` (a target or hole that
    could not be handled; a compensation not written).

Example::

    import numpy as np, roprec
    s = roprec.Session("samples/cells/housing-kr120.xml")
    wanted = s.hole_pose([150, 0, 250], [0, 0, -1])        # hole T001 of the sample hole list
    program, joints = s.filter_target(wanted)
    dev = s.predict_joints(joints)["deviation_um"]
    assert np.allclose(program[:3, 3] + dev * 1e-3, wanted[:3, 3], atol=1e-4)
"""

import json as _json

import os as _os

if _os.environ.get("ROPREC_PYTHON_BACKEND") == "ctypes":
    from . import _cabi as _roprec
else:
    try:
        from . import _roprec
    except ImportError:  # no extension built for this interpreter (RoboDK's Python on Windows):
        from . import _cabi as _roprec  # the C library through ctypes, same API (roprec/_cabi.py)
InputError, ItemError, RoprecError = _roprec.InputError, _roprec.ItemError, _roprec.RoprecError
Session, UsageError = _roprec.Session, _roprec.UsageError

__version__ = _roprec.version()

__all__ = [
    "__version__",
    "Session",
    "predict",
    "compensate",
    "verify",
    "plan_test",
    "Prediction",
    "RoprecError",
    "InputError",
    "UsageError",
    "ItemError",
]


class Prediction(list):
    """The result of :func:`predict`: a list with one dict per hole, in program order.

    Attributes:
        summary (dict): the ``summary`` object of the prediction JSON (``holes``, ``verdicts``,
            ``robot_can_take``, ``mc_time_taken_s``, ``mc_time_total_s``,
            ``process_share_mean``, ``process_share_max``) plus ``failed`` (holes not predicted).
        failed (list of dict): the holes whose ``status`` is not ``"ok"``.
        failures (str): one line per such hole, ``hole ID (FILE:LINE): verdict: reason`` (as the
            CLI lists them), or "".
        notes (list of str): notes on how the job was read (e.g. which frame was assumed).
        robot, cell, process (str): the robot card, the cell and the process description.
    """

    summary: dict
    failures: str
    notes: list
    robot: str
    cell: str
    process: str

    @property
    def failed(self):
        """The holes whose ``status`` is not ``"ok"``."""
        return [h for h in self if h["status"] != "ok"]


def _opt(x):
    return None if x is None else str(x)


def predict(cell, program, holes=None, json_out=None, frame=None, tool=None):
    """Predicts every hole of a program: ``roprec predict --cell CELL PROGRAM [--holes H] [--json J]``.

    Args:
        cell: the cell XML (path).
        program: KUKA ``.src``, ABB ``.mod/.prg/.sys``, FANUC ``.ls``, a CSV/JSON target list, or a
            hole-list CSV.
        holes: optional hole-list CSV whose ids, diameters, depths and tolerances are matched to
            the program's holes (by id, else by position within 0.5 mm).
        json_out: optional path: the full prediction JSON is written there, byte for byte the
            document of ``roprec predict ... --json``.
        frame: how base frames that only the controller defines (FANUC ``UFRAME[n]``, KUKA
            ``BASE_DATA[n]``) are resolved, as ``--frame``: "cell" (the cell's workobject),
            "x y z a b c" (mm, deg, KUKA ABC, robot base frame) or "REF=x y z a b c[;REF=...]".
            Without it such a frame is an InputError.
        tool: a program tool that differs from the cell's (or only the controller defines), as
            ``--tool``: "program" (the program's TCP is the real one) or "cell". Without it a
            differing tool is an InputError. The resolution is listed in ``.notes``.

    Returns:
        A :class:`Prediction` (a list) of per-hole dicts, at full precision (the JSON rounds):
        ``id``, ``line``, ``status`` ("ok", "unreachable", "singular", "not-converged"),
        ``verdict`` (ISO 14253-1: "conforms", "conforms-after-compensation",
        "not-capable", "unreachable", "singular", "not-converged"), ``reason``;
        the nominal TCP: ``nominal_pose_mm`` (4x4), ``nominal_position_mm``,
        ``nominal_quaternion_wxyz``, ``axis`` (drilling direction); ``diameter_mm``,
        ``depth_mm``, ``tolerance_mm``, ``mc_time_s``;
        the IK solution: ``joints_deg`` (as the prediction JSON: robot-model convention),
        ``controller_joints_deg``, ``config``, ``branch``;
        the deviation (base frame): ``deviation_um`` (δwork = δrobot + δmach), ``robot_deviation_um``,
        ``mach_deviation_um``, ``rotation_urad``, ``work_tool_xy_um``, ``position_error_um``
        (⊥ the hole axis), ``axis_tilt_urad``, ``from_nominal_axis_um`` (with ``holes``);
        the budget: ``U_robot_um``, ``U_mach_um``, ``U_work_um`` (expanded, 95 %, 2-D radial),
        ``k``, ``U_work_anisotropic_um``, ``budget_um`` (standard uncertainties per axis),
        ``process_share``, ``process_force_share``, ``process_force_N``,
        ``equilibrium_converged``, ``equilibrium_iterations``.
        Values that do not exist for a hole (no IK solution, no deviation) are None.
        Holes that could not be predicted are statuses, not exceptions (see ``.failed``).

    Raises:
        InputError: a bad cell, program or hole list.
    """
    r = _roprec._predict(str(cell), str(program), _opt(holes), _opt(json_out), _opt(frame),
                         _opt(tool))
    p = Prediction(r["holes"])
    p.summary = _json.loads(r["summary_json"])
    p.failures = r["failures"]
    p.notes = list(r["notes"])
    p.robot = r["robot"]
    p.cell = r["cell"]
    p.process = r["process"]
    return p


def compensate(cell, program, out, orientation="keep", targets=None, holes=None, frame=None,
               tool=None, force=False):
    """Pre-offsets a drilling program: ``roprec compensate --cell CELL PROGRAM -o OUT ...``.

    Every hole's targets are moved so that the predicted real hole lands on the nominal one (every
    target of a drill cycle moves with its drill point), and the corrected program is written to
    ``out`` in the program's own dialect (only the compensated targets' bytes change; KRL writes
    the ``.dat`` beside the ``.src``). With a milling cell every linear path point is compensated.

    Args:
        cell, program: as for :func:`predict` (a hole-list CSV is rewritten as a hole list).
        out: the corrected program's path.
        orientation: "keep" (positions only), "flip-free" (the rotation about each drill axis
            chosen so axes 4/6 do not flip) or "stiffest".
        targets: optional corrected-target export: CSV when the name ends in ".csv", else JSON —
            the document of ``roprec compensate ... --targets``.
        holes: optional hole-list CSV matched to the program's holes.
        frame, tool: as for :func:`predict`.
        force: compensate a program that already carries roprec's compensation marker (it is
            refused otherwise: InputError), as ``--force``.

    Returns:
        dict: ``orientation``, ``holes``, ``compensated``, ``failed``, ``error_before_um`` and
        ``residual_after_um`` (``{"mean", "max"}``, ⊥ the hole axis), ``conform_before``,
        ``conform_after``, ``jumps_before``, ``jumps_after`` (axis-4/6 jumps within a face),
        ``written`` (the paths written), and ``results``: one dict per hole at full precision —
        ``id``, ``status`` ("compensated" / "original-kept"), ``reason``, ``nominal_pose_mm``,
        ``nominal_position_mm``, ``nominal_quaternion_wxyz``, ``before_deviation_um``,
        ``before_rotation_urad``, ``before_verdict``, ``programmed_pose_mm``,
        ``programmed_position_mm``, ``programmed_quaternion_wxyz``, ``joints_deg`` (as the
        export), ``controller_joints_deg``, ``config``, ``rotation_about_axis_deg``,
        ``residual_um``, ``residual_vector_um``, ``branch_changed``, ``note``, ``U_robot_um``,
        ``U_mach_um``, ``U_work_um``, ``k``, ``verdict``.
        A milling cell gives ``process``, ``points``, ``failed``, ``deviation_before_um``,
        ``residual_after_um``, ``written``.

    Raises:
        ItemError: some holes could not be compensated or the writer refused an edit; nothing was
            written. ``e.result`` holds the dict above (``written`` empty).
        InputError, UsageError: bad input or arguments; nothing was written.
    """
    r = _roprec._compensate(str(cell), str(program), str(out), str(orientation), _opt(targets),
                            _opt(holes), _opt(frame), _opt(tool), bool(force))
    result = _json.loads(r["summary_json"])
    if "results" in r:
        result["results"] = r["results"]
    if r["problems"]:
        e = ItemError(r["problems"])
        e.result = result
        raise e
    return result


def verify(cell, program, measured, holes=None, register="none", calibrate=None, json_out=None,
           write_cell=None, identify="all", date=None, folds=5, poses=None, u_rot=None):
    """Measured holes against the prediction: ``roprec verify --cell CELL PROGRAM --measured M ...``.

    Args:
        cell, program: as for :func:`predict` (the program the part was drilled with; None with
            ``poses`` alone when their rows give the joints).
        measured: the CMM file — roprec CSV (``id,x,y,z[,i,j,k][,u]``), PC-DMIS CSV or DMIS output;
            hole positions in the cell's workobject frame, mm; ``u`` the standard measurement
            uncertainty per axis in µm (5 µm when absent). Matched to the program's holes by id.
            None: no measured holes (``poses`` then required).
        holes: optional hole-list CSV (the nominal holes) matched to the program's holes.
        register: "none", "translation" or "rigid": a part registration estimated jointly with
            the joint stiffness and removed from the measured positions before the comparison.
        calibrate: optional path: the geometry and the joint stiffness are identified and the new
            robot card is written there (``--calibrate``); unidentifiable parameters keep the
            card's value. The fit is checked (``identification.fit_check``: χ² against the
            measurement σ) and cross-validated (``identification.validation``, 5-fold); a card
            whose held-out residual is not below the original card's is not written
            (``identification.card_refused`` says why).
        write_cell: optional path: the cell with the registered part as its
            ``<part_registration>`` (workobject kept) and its robot = the new card (``--write-cell``; needs ``register`` or ``calibrate``).
        json_out: optional path: the verification JSON, byte for byte ``roprec verify --json``.
        identify: "all" (default: every parameter the measurements make observable), "stiffness"
            or "geometry": what the calibration may move (``--identify``).
        date: the written calibration's date, ``YYYY-MM-DD`` (``--date``); None: the rule of
            docs/cards.md (SOURCE_DATE_EPOCH, else the measured file's day).
        folds: k of the held-out validation, 0..100 (``--folds``; 0: none, the card is written
            unchecked).
        poses: optional path: measured TCP poses (laser tracker / CMM CSV, docs/contract.md §8.2)
            identified with the holes (``--poses``).
        u_rot: σ per axis of a measured pose orientation (``rx,ry,rz``) when its row has no
            ``u_rot``, µrad, > 0 (``--u-rot``; None: 100).

    Returns:
        dict: the verification JSON document (µm, µrad, mm) — ``measured`` (file, format, holes,
        matched), ``registration``, ``summary`` (``measured_um``/``predicted_um``/``residual_um``
        ``{"rms", "mean", "max"}``, ``explained``, ``inside``, ``coverage``,
        ``correlation_workobject_xyz``, ``measured_decisions``), ``identification`` (when run:
        ``parameters``, ``joints`` with ``k`` and ``k_sigma`` in N·m/rad, ``condition_number``,
        ``not_identifiable``, ``covariance``), ``holes`` (per hole ``measured_um``,
        ``predicted_um``, ``residual_um``, ``U_work_um``, ``inside``, ``decision`` …), ``failed``,
        ``notes`` — plus ``written`` (the paths written).

    Raises:
        ItemError: some measured holes could not be predicted; nothing was written. ``e.result``
            holds the dict above (``written`` empty).
        InputError, UsageError: a bad file (``FILE:LINE: what``) or argument; nothing was written.
    """
    r = _roprec._verify(str(cell), None if program is None else str(program),
                        None if measured is None else str(measured),
                        None if holes is None else str(holes), str(register),
                        None if calibrate is None else str(calibrate),
                        None if json_out is None else str(json_out),
                        None if write_cell is None else str(write_cell), str(identify),
                        None if date is None else str(date), int(folds),
                        poses=None if poses is None else str(poses),
                        u_rot=None if u_rot is None else float(u_rot))
    result = _json.loads(r["json"])
    result["written"] = _json.loads(r["summary_json"])["written"]
    if r["problems"]:
        e = ItemError(r["problems"])
        e.result = result
        raise e
    return result


def plan_test(cell, region, count, out):
    """A D-optimal drilling test program: ``roprec plan-test --cell CELL --region R --count N -o OUT``.

    Args:
        cell: the cell XML.
        region: 6 numbers ``(x0, y0, z0, x1, y1, z1)``: the box of candidate drill points (hole
            bottoms) in the workobject frame, mm; a 4 x 4 x 4 grid, drilled along -z of the
            workobject, rotated 0 and 90 deg about the drill axis.
        count: how many holes to choose.
        out: the program path, in the cell robot's dialect (``.src`` + ``.dat``, ``.mod``, ``.ls``),
            or a hole list when it ends in ``.csv``.

    Returns:
        dict: ``holes``, ``candidates``, ``rejected``, ``log_det``, ``joints`` (per joint
        ``k_card``, ``prior_sigma_rel``, ``expected_sigma_rel``, ``expected_sigma_k`` N·m/rad),
        ``ids``, ``written``.

    Raises:
        InputError, UsageError: a bad cell, region or count (fewer admissible candidates).
    """
    r = _roprec._plan_test(str(cell), [float(v) for v in region], int(count), str(out))
    return _json.loads(r["summary_json"])
