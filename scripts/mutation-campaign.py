#!/usr/bin/env python3
"""Mutation campaign: corrupted inputs through every roprec command under the sanitizers.

usage: scripts/mutation-campaign.py [--binary build-mut/bin/roprec] [--count N] [--seed S]
                                    [--jobs J] [--timeout SEC] [--out DIR] [--only KIND,...]
                                    [--encodings]

Build the CLI with AddressSanitizer + UndefinedBehaviorSanitizer first (the flags of
scripts/sanitize.sh, e.g. in build-mut/: `ninja -C build-mut roprec`), then run this script.

It takes the valid sample inputs (samples/cells/*.xml, robots/*/robot.xml and their URDFs, the
e-motor housing hole list and its KRL/RAPID/TP programs, the verification program, hole list
and measured file) and makes N seeded mutants (fixed seed: the same N and S give the same
mutants): byte flips, digit changes, deleted/duplicated lines, truncation, a numeric field set to
0 / -x / 1e300 / nan / inf / 1e-300, a one-letter misspelling of an element, attribute or column
name, a removed element or column, swapped columns, mm values divided by 1000, comma decimals.
Each mutant is written into a fresh temporary copy of the inputs it needs (cells, the robot
folder with card and URDF, programs; ROPREC_ROBOTS_DIR points at the copy) and run, with a
timeout (10 s), through every command that reads that file (predict, compensate, inspect,
convert, verify, forces, deflect), outputs into a fresh folder, with
ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 and UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1.

A run FAILS on: a sanitizer report; a timeout; a signal or an exit code other than 0/1/2; exit 2
without a `roprec: error: ...` line; an "internal error"; exit 2 with any output file, exit 1 with
some but not all outputs, exit 0 with an output missing, or a staging temporary (*.roprec-tmp.*)
left in the output folder; NaN/inf/null numbers in an output JSON/CSV or nan/inf or 40-digit
numbers in a message (unless the mutant itself put nan/inf there); and a "silent wrong answer":
exit 0 on a mutant whose mutation is strict (a misspelled name, a removed required element or
column, a non-finite or absurd value, a zero or negative size/mass/diameter/stiffness, a comma
decimal, a hole list in metres, a duplicated hole row) while the outputs differ from the
unmutated baseline's (stdout and outputs other than programs and HTML: a written program carries
its uncompensated lines as they are) and no new warning/note line on stderr says so; value
mutations through inspect and convert, which report values as they are, are not judged so.
Other mutations that make a valid different input (a changed digit in a coordinate) may exit 0.

--encodings mutates encodings instead (its own mutants for a seed, so the seeds above keep theirs):
the file re-encoded as UTF-16/32 or given a NUL byte must be refused (exit 2, else FAIL
"not_refused"); a byte that is not UTF-8 put into a name must leave every JSON and HTML output
valid UTF-8 (else "invalid_utf8_output"); a name grown to 1 MB must end within the timeout with
no stderr line longer than 5000 bytes (else "timeout" / "huge_message"). These checks apply to
every run.

Prints a summary (mutants, runs, per-category counts, every failing case with a reproduction
command), writes DIR/log.json (DIR defaults to mutation/ beside the binary's bin/ folder) and
copies each failing case's input tree to DIR/cases/<id>/. Exit 1 on any FAIL, 0 otherwise.
Python 3 standard library only.
"""

import argparse
import concurrent.futures
import json
import math
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# ---------------------------------------------------------------------------------------------
# Scenarios: the files a group of commands reads (paths relative to the temporary tree) and the
# commands. {O} is the output folder (relative to the tree). Every command lists the tree files
# it reads ("reads") and the output files it must write ("outputs").
# ---------------------------------------------------------------------------------------------

ROBOT_OF_CELL = {}


def cell_robot(cell_rel):
    if cell_rel not in ROBOT_OF_CELL:
        with open(os.path.join(ROOT, cell_rel), encoding="utf-8") as f:
            m = re.search(r'<robot\s+ref="([^"]+)"', f.read())
        ROBOT_OF_CELL[cell_rel] = m.group(1)
    return ROBOT_OF_CELL[cell_rel]


def robot_files(name):
    folder = os.path.join(ROOT, "robots", name)
    return ["robots/%s/%s" % (name, f) for f in sorted(os.listdir(folder))
            if f.endswith(".xml") or f.endswith(".urdf")]


def cmd(args, reads, outputs, echo=False):
    """echo: the command reports the input's values as they are (inspect, convert), so a changed
    value in its output is no wrong answer."""
    return {"args": args, "reads": reads, "outputs": outputs, "echo": echo}


JOINTS = {  # a reachable, non-singular pose per robot (deg, URDF convention)
    "kuka-kr120-r2500-pro": "0 -60 100 0 50 0",
    "kuka-kr210-r2700-2": "0 -60 100 0 50 0",
    "abb-irb6640-185-280": "0 20 10 0 40 0",
    "abb-irb6700-200-260": "0 20 10 0 40 0",
    "fanuc-r2000ic-165f": "0 20 -10 0 -40 0",
    "fanuc-r2000ic-210f": "0 20 -10 0 -40 0",
}


def scenarios():
    H = "samples/emotor-housing/"
    V = "samples/verification/"
    out = []

    def forces_cmd(cell):
        return cmd(["forces", "--cell", cell, "--csv", "{O}/f.csv", "--json", "{O}/f.json"],
                   [cell], ["f.csv", "f.json"])

    def robot_cmds(cell, robot):
        card = "robots/%s/robot.xml" % robot
        urdf = [f for f in robot_files(robot) if f.endswith(".urdf")]
        rd = [card] + urdf
        return [
            cmd(["deflect", "--robot", robot, "--joints", JOINTS[robot], "--cell", cell,
                 "-o", "{O}/d.json"], [cell] + rd, ["d.json"]),
            cmd(["fk", "--robot", robot, "--joints", JOINTS[robot]], rd, []),
        ]

    # KUKA KR 120: program, hole list, cell, card, URDF.
    cell = "samples/cells/housing-kr120.xml"
    rob = cell_robot(cell)
    rd = robot_files(rob)
    src, holes = H + "housing_kr120.src", H + "holes.csv"
    out.append({"name": "kr120", "files": [cell, src, holes] + rd, "commands": [
        cmd(["predict", "--cell", cell, src, "--json", "{O}/p.json", "--report", "{O}/p.html"],
            [cell, src] + rd, ["p.json", "p.html"]),
        cmd(["predict", "--cell", cell, holes, "--json", "{O}/p.json"], [cell, holes] + rd,
            ["p.json"]),
        cmd(["predict", "--cell", cell, src, "--holes", holes, "--json", "{O}/p.json"],
            [cell, src, holes] + rd, ["p.json"]),
        cmd(["compensate", "--cell", cell, src, "-o", "{O}/out.src", "--targets", "{O}/t.csv",
             "--report", "{O}/c.html"], [cell, src] + rd, ["out.src", "t.csv", "c.html"]),
        cmd(["inspect", src, "-o", "{O}/i.json"], [src], ["i.json"], echo=True),
        cmd(["inspect", holes, "-o", "{O}/i.json"], [holes], ["i.json"], echo=True),
        cmd(["convert", src, "-o", "{O}/c.src"], [src], ["c.src"], echo=True),
        cmd(["convert", src, "--to", "rapid", "-o", "{O}/c.mod"], [src], ["c.mod"], echo=True),
        forces_cmd(cell),
    ] + robot_cmds(cell, rob)})

    # ABB IRB 6640: RAPID.
    cell = "samples/cells/housing-irb6640.xml"
    rob = cell_robot(cell)
    rd = robot_files(rob)
    mod = H + "housing_irb6640.mod"
    out.append({"name": "irb6640", "files": [cell, mod] + rd, "commands": [
        cmd(["predict", "--cell", cell, mod, "--json", "{O}/p.json"], [cell, mod] + rd,
            ["p.json"]),
        cmd(["compensate", "--cell", cell, mod, "-o", "{O}/out.mod", "--targets", "{O}/t.json",
             "--allow-partial"], [cell, mod] + rd, ["out.mod", "t.json"]),
        cmd(["inspect", mod, "-o", "{O}/i.json"], [mod], ["i.json"], echo=True),
        cmd(["convert", mod, "-o", "{O}/c.mod"], [mod], ["c.mod"], echo=True),
        cmd(["convert", mod, "--to", "csv", "-o", "{O}/c.csv"], [mod], ["c.csv"], echo=True),
        forces_cmd(cell),
    ] + robot_cmds(cell, rob)})

    # FANUC R-2000iC/165F: TP (UFRAME[1] is the cell's workobject).
    cell = "samples/cells/housing-r2000.xml"
    rob = cell_robot(cell)
    rd = robot_files(rob)
    ls = H + "housing_r2000.ls"
    out.append({"name": "r2000", "files": [cell, ls] + rd, "commands": [
        cmd(["predict", "--cell", cell, ls, "--frame", "cell", "--tool", "cell", "--json",
             "{O}/p.json"], [cell, ls] + rd, ["p.json"]),
        cmd(["compensate", "--cell", cell, ls, "--frame", "cell", "--tool", "cell", "-o",
             "{O}/out.ls", "--targets", "{O}/t.csv", "--allow-partial"], [cell, ls] + rd,
            ["out.ls", "t.csv"]),
        cmd(["inspect", ls, "-o", "{O}/i.json"], [ls], ["i.json"], echo=True),
        cmd(["convert", ls, "-o", "{O}/c.ls"], [ls], ["c.ls"], echo=True),
        cmd(["convert", ls, "--to", "json", "-o", "{O}/c.json"], [ls], ["c.json"], echo=True),
        forces_cmd(cell),
    ] + robot_cmds(cell, rob)})

    # Verification: program + .dat, its hole list, the measured file.
    cell = "samples/cells/housing-kr120.xml"
    rob = cell_robot(cell)
    rd = robot_files(rob)
    vsrc, vdat = V + "test_kr120.src", V + "test_kr120.dat"
    vholes, meas = V + "test_kr120_holes.csv", V + "measured.csv"
    vr = [cell, vsrc, vdat, vholes, meas] + rd
    out.append({"name": "verify", "files": [vsrc, vdat, vholes, meas], "commands": [
        cmd(["verify", "--cell", cell, vsrc, "--holes", vholes, "--measured", meas, "--json",
             "{O}/v.json", "--report", "{O}/v.html"], vr, ["v.json", "v.html"]),
        cmd(["verify", "--cell", cell, vsrc, "--holes", vholes, "--measured", meas,
             "--register", "rigid", "--calibrate", "{O}/card.xml", "--json", "{O}/v.json"], vr,
            ["card.xml", "v.json"]),
        cmd(["inspect", vsrc, "-o", "{O}/i.json"], [vsrc, vdat], ["i.json"], echo=True),
        cmd(["convert", vsrc, "-o", "{O}/c.src"], [vsrc, vdat], ["c.src"], echo=True),
    ]})

    # The other cells: forces, and (drilling cells) the hole list and the robot.
    done = {"housing-kr120.xml", "housing-irb6640.xml", "housing-r2000.xml"}
    for name in sorted(os.listdir(os.path.join(ROOT, "samples/cells"))):
        if name in done:
            continue
        cell = "samples/cells/" + name
        rob = cell_robot(cell)
        rd = robot_files(rob)
        commands = [forces_cmd(cell)]
        with open(os.path.join(ROOT, cell), encoding="utf-8") as f:
            drilling = 'type="drilling"' in f.read()
        if drilling:
            commands.append(cmd(["predict", "--cell", cell, holes, "--json", "{O}/p.json"],
                                [cell, holes] + rd, ["p.json"]))
        own = [cell]
        if rob not in ("kuka-kr120-r2500-pro", "abb-irb6640-185-280", "fanuc-r2000ic-165f"):
            own += rd
            commands += robot_cmds(cell, rob)
        out.append({"name": name[:-4], "files": own, "commands": commands,
                    "extra": [holes] + rd})
    return out


# ---------------------------------------------------------------------------------------------
# Mutations. Each returns (new_text, operator, strict, description) or None when it cannot
# apply. strict: exit 0 with changed outputs and no new note is a silent wrong answer.
# ---------------------------------------------------------------------------------------------

NUM_RE = re.compile(r"(?<![A-Za-z_\d.])[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")
# Fields that must be > 0 (0, a negative value or 1e-300 is absurd) and fields that must be >= 0
# (a negative value is absurd; 0 is a valid massless tool or uncertainty-free input).
POSITIVE_RE = re.compile(r"diam|depth|toleran|stiff|rp_mm|feed|rpm|stickout|web|(?<!half)width|radius|"
                         r"position_gain$", re.I)
NONNEG_RE = re.compile(r"mass|^value$|^i[xyz][xyz]$|effort|velocity|_rel$|halfwidth", re.I)
# Elements a file cannot do without (the contract's optional ones, e.g. the cell's <tool> and
# <process>, have documented defaults and are not listed).
REQUIRED = {
    "cell": {"robot", "workobject", "drill", "cut", "material"},
    "card": {"joint", "repeatability", "robot"},
    "urdf": {"joint", "link", "limit", "inertial", "mass", "inertia", "parent", "child", "robot"},
}
HOLE_REQUIRED = {"id", "x", "y", "z", "i", "j", "k"}  # diameter, depth, tolerance, u: optional


def kind_of(path):
    if path.endswith(".urdf"):
        return "urdf"
    if path.endswith("robot.xml"):
        return "card"
    if path.endswith(".xml"):
        return "cell"
    if path.endswith(".csv"):
        return "csv"
    return "program"


def name_at(text, pos):
    """The XML attribute a number at pos belongs to, when the attribute's value is numbers only
    ('' otherwise: text, names, sources)."""
    m = None
    for m in re.finditer(r'([A-Za-z_][\w.:-]*)\s*=\s*"[^"]*$', text[max(0, pos - 400):pos]):
        pass
    if not m or m.group(1) in ("version", "encoding"):
        return ""
    end = text.find('"', pos)
    value = text[pos - (len(m.group(0)) - m.group(0).index('"') - 1):end]
    return m.group(1) if re.fullmatch(r"[\s\d.eE+-]*", value) else ""


def mut_byteflip(text, rng, kind):
    b = bytearray(text.encode("utf-8", "surrogateescape"))
    if not b:
        return None
    i = rng.randrange(len(b))
    b[i] ^= 1 << rng.randrange(8)
    return b.decode("utf-8", "surrogateescape"), "byteflip", False, "byte %d flipped" % i


def mut_digit(text, rng, kind):
    idx = [i for i, c in enumerate(text) if c.isdigit()]
    if not idx:
        return None
    i = rng.choice(idx)
    d = rng.choice([c for c in "0123456789" if c != text[i]])
    return text[:i] + d + text[i + 1:], "digit", False, "digit at %d -> %s" % (i, d)


def data_lines(text):
    lines = text.splitlines(keepends=True)
    return lines, [i for i, l in enumerate(lines) if l.strip() and not l.lstrip().startswith("#")]


def mut_delete_line(text, rng, kind):
    lines, idx = data_lines(text)
    if not idx:
        return None
    i = rng.choice(idx)
    return "".join(lines[:i] + lines[i + 1:]), "delete_line", False, "line %d deleted" % (i + 1)


def mut_dup_line(text, rng, kind):
    lines, idx = data_lines(text)
    if len(idx) < 2:
        return None
    i = rng.choice(idx[1:]) if kind == "csv" else rng.choice(idx)
    strict = kind == "csv"  # a duplicated hole/measurement id
    return ("".join(lines[:i + 1] + [lines[i]] + lines[i + 1:]), "dup_line", strict,
            "line %d duplicated" % (i + 1))


def mut_truncate(text, rng, kind):
    if len(text) < 2:
        return None
    n = rng.randrange(1, len(text))
    return text[:n], "truncate", False, "truncated to %d chars" % n


def csv_header(text):
    lines = text.splitlines(keepends=True)
    for i, l in enumerate(lines):
        if l.strip() and not l.lstrip().startswith("#"):
            return lines, i, [c.strip() for c in l.rstrip("\r\n").split(",")]
    return lines, -1, []


def column_at(text, pos):
    lines, h, cols = csv_header(text)
    if h < 0:
        return ""
    line_start = text.rfind("\n", 0, pos) + 1
    field = text[line_start:pos].count(",")
    return cols[field] if field < len(cols) else ""


def mut_numeric(text, rng, kind):
    nums = list(NUM_RE.finditer(text))
    if kind == "csv":
        _, h, _ = csv_header(text)
        start = sum(len(l) for l in text.splitlines(keepends=True)[:h + 1])
        nums = [m for m in nums if m.start() >= start and not text[text.rfind("\n", 0, m.start()) + 1:].lstrip().startswith("#")]
    if not nums:
        return None
    if kind in ("cell", "card", "urdf"):
        nums = [m for m in nums if name_at(text, m.start())]
    if not nums:
        return None
    m = rng.choice(nums)
    field = column_at(text, m.start()) if kind == "csv" else name_at(text, m.start())
    if kind == "csv" and field == "id":
        return None
    v = rng.choice(["0", "-x", "1e300", "nan", "inf", "1e-300"])
    new = ("-" + m.group(0).lstrip("+")) if v == "-x" else v
    if v == "-x" and m.group(0).startswith("-"):
        new = m.group(0)[1:]
    positive = bool(POSITIVE_RE.search(field)) and kind != "program"
    nonneg = positive or (bool(NONNEG_RE.search(field)) and kind != "program")
    strict = v in ("1e300", "nan", "inf") or (positive and v in ("0", "1e-300")) or (
        nonneg and v == "-x" and not m.group(0).startswith("-"))
    return (text[:m.start()] + new + text[m.end():], "value_" + v.replace("-x", "neg"), strict,
            "%s%s -> %s at %d" % ((field + " ") if field else "", m.group(0), new, m.start()))


def misspell(word, rng):
    letters = [i for i, c in enumerate(word) if c.isalpha()]
    if not letters:
        return None
    i = rng.choice(letters)
    c = rng.choice([x for x in "abcdefghijklmnopqrstuvwxyz" if x != word[i].lower()])
    return word[:i] + c + word[i + 1:]


def mut_misspell(text, rng, kind):
    if kind == "csv":
        lines, h, cols = csv_header(text)
        if h < 0:
            return None
        j = rng.randrange(len(cols))
        w = misspell(cols[j], rng)
        if w is None:
            return None
        cols2 = cols[:]
        cols2[j] = w
        lines[h] = ",".join(cols2) + "\n"
        return "".join(lines), "misspell", True, "column %s -> %s" % (cols[j], w)
    if kind == "program":
        return None
    body = re.sub(r"<!--.*?-->", lambda m: " " * len(m.group(0)), text, flags=re.S)
    cands = [(m.start(1), m.group(1), "element") for m in re.finditer(r"<([A-Za-z_][\w]*)", body)
             if m.group(1) not in ("xml",)]
    cands += [(m.start(1), m.group(1), "attribute")
              for m in re.finditer(r"\s([A-Za-z_][\w:]*)\s*=\s*\"", body)
              if m.group(1) not in ("version", "encoding")]
    if not cands:
        return None
    pos, w, what = rng.choice(cands)
    w2 = misspell(w, rng)
    if w2 is None:
        return None
    text2 = text[:pos] + w2 + text[pos + len(w):]
    if what == "element":  # the closing tag too, so the XML stays well formed
        close = "</%s>" % w
        depth_pos = text2.find(close, pos)
        if depth_pos >= 0:
            text2 = text2[:depth_pos] + "</%s>" % w2 + text2[depth_pos + len(close):]
    return text2, "misspell", True, "%s %s -> %s" % (what, w, w2)


def mut_remove(text, rng, kind):
    if kind == "csv":
        lines, h, cols = csv_header(text)
        if h < 0 or len(cols) < 2:
            return None
        j = rng.randrange(len(cols))
        new = []
        for i, l in enumerate(lines):
            if i < h or not l.strip() or l.lstrip().startswith("#"):
                new.append(l)
                continue
            f = l.rstrip("\r\n").split(",")
            if j < len(f):
                del f[j]
            new.append(",".join(f) + "\n")
        strict = cols[j] in HOLE_REQUIRED
        return "".join(new), "remove", strict, "column %s removed" % cols[j]
    if kind == "program":
        return None
    body = re.sub(r"<!--.*?-->", lambda m: " " * len(m.group(0)), text, flags=re.S)
    elems = []
    for m in re.finditer(r"<([A-Za-z_]\w*)\b[^>]*?(/?)>", body):
        name = m.group(1)
        if m.group(2) == "/":
            elems.append((m.start(), m.end(), name))
        else:
            close = body.find("</%s>" % name, m.end())
            if close >= 0:
                elems.append((m.start(), close + len(name) + 3, name))
    if len(elems) < 2:
        return None
    s, e, name = rng.choice(elems[1:])
    strict = name in REQUIRED.get(kind, set())
    return (text[:s] + text[e:], "remove", strict, "element <%s> at %d removed" % (name, s))


def mut_swap_columns(text, rng, kind):
    if kind != "csv":
        return None
    lines, h, cols = csv_header(text)
    if h < 0 or len(cols) < 3:
        return None
    a, b = rng.sample(range(1, len(cols)), 2)
    new = []
    for i, l in enumerate(lines):
        f = l.rstrip("\r\n").split(",")
        if i > h and l.strip() and not l.lstrip().startswith("#") and max(a, b) < len(f):
            f[a], f[b] = f[b], f[a]
            l = ",".join(f) + "\n"
        new.append(l)
    return "".join(new), "swap_columns", False, "columns %s <-> %s" % (cols[a], cols[b])


def mut_unit(text, rng, kind):
    if kind == "csv":
        lines, h, cols = csv_header(text)
        xyz = [i for i, c in enumerate(cols) if c in ("x", "y", "z", "X", "Y", "Z")]
        if h < 0 or not xyz:
            return None
        new = []
        for i, l in enumerate(lines):
            f = l.rstrip("\r\n").split(",")
            if i > h and l.strip() and not l.lstrip().startswith("#"):
                for j in xyz:
                    if j < len(f):
                        try:
                            f[j] = "%.9g" % (float(f[j]) / 1000.0)
                        except ValueError:
                            pass
                l = ",".join(f) + "\n"
            new.append(l)
        return "".join(new), "unit_m", True, "x,y,z in metres"
    nums = [m for m in NUM_RE.finditer(text) if "." in m.group(0) or len(m.group(0)) > 1]
    if kind in ("cell", "card", "urdf"):
        nums = [m for m in nums if name_at(text, m.start())]
    if not nums:
        return None
    m = rng.choice(nums)
    try:
        v = "%.9g" % (float(m.group(0)) / 1000.0)
    except ValueError:
        return None
    return text[:m.start()] + v + text[m.end():], "unit_value", False, "%s -> %s at %d" % (
        m.group(0), v, m.start())


def mut_comma(text, rng, kind):
    nums = [m for m in NUM_RE.finditer(text) if "." in m.group(0)]
    if kind in ("cell", "card", "urdf"):
        nums = [m for m in nums if name_at(text, m.start())]
    if not nums:
        return None
    m = rng.choice(nums)
    new = m.group(0).replace(".", ",", 1)
    strict = kind != "program"
    return text[:m.start()] + new + text[m.end():], "comma_decimal", strict, "%s -> %s at %d" % (
        m.group(0), new, m.start())


MUTATORS = [mut_byteflip, mut_digit, mut_delete_line, mut_dup_line, mut_truncate, mut_numeric,
            mut_numeric, mut_misspell, mut_remove, mut_swap_columns, mut_unit, mut_comma]


# --encodings (kept apart so that the seeds of the mutations above give the same mutants): the
# text re-encoded as UTF-16/32 or with a NUL byte (must be refused: exit 2), a byte that is not
# UTF-8 in a name (JSON and HTML outputs must stay valid UTF-8), and a name grown to 1 MB (must end
# at once with a short message).
def mut_wide(text, rng, kind):
    enc = rng.choice(["utf-16-le", "utf-16-be", "utf-16", "utf-32-le", "utf-32"])
    b = text.encode("utf-8", "surrogateescape").decode("utf-8", "replace").encode(enc)
    op = "utf32" if "32" in enc else "utf16"
    return b.decode("utf-8", "surrogateescape"), op, True, "re-encoded as %s" % enc


def mut_nul(text, rng, kind):
    if not text:
        return None
    i = rng.randrange(len(text))
    return text[:i] + "\0" + text[i:], "nul", True, "NUL byte at %d" % i


def mut_latin1(text, rng, kind):
    spots = [m.start() for m in re.finditer(r"[A-Za-z]", text)]
    if not spots:
        return None
    i = rng.choice(spots)
    return text[:i] + "\udce4" + text[i + 1:], "latin1", False, "byte 0xE4 at %d" % i


def mut_huge_name(text, rng, kind):
    spots = [m.start() for m in re.finditer(r"[A-Za-z_]{3,}", text)]
    if not spots:
        return None
    i = rng.choice(spots)
    return text[:i] + "q" * 1000000 + text[i:], "huge_name", False, "1 MB name at %d" % i


ENCODING_MUTATORS = [mut_wide, mut_nul, mut_latin1, mut_huge_name]


# ---------------------------------------------------------------------------------------------
# Running and classifying.
# ---------------------------------------------------------------------------------------------

SAN_RE = re.compile(r"ERROR: AddressSanitizer|runtime error:|LeakSanitizer")
NOTE_RE = re.compile(r"warning|note|refus|ignor|assum|did you mean", re.I)
NONFINITE_MSG_RE = re.compile(r"(?<![\w.])-?(nan|inf|infinity)(?![\w])", re.I)
LONGNUM_RE = re.compile(r"\d{40,}")


def make_tree(files, tree):
    for rel in files:
        dst = os.path.join(tree, rel)
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        shutil.copyfile(os.path.join(ROOT, rel), dst)


def run_one(binary, tree, command, timeout):
    out_rel = "out"
    out_dir = os.path.join(tree, out_rel)
    if os.path.exists(out_dir):
        shutil.rmtree(out_dir)
    os.makedirs(out_dir)
    args = [a.replace("{O}", out_rel) for a in command["args"]]
    env = dict(os.environ)
    env.update({"ASAN_OPTIONS": "detect_leaks=1:abort_on_error=0",
                "UBSAN_OPTIONS": "print_stacktrace=1:halt_on_error=1",
                "ROPREC_ROBOTS_DIR": os.path.join(tree, "robots"), "LC_ALL": "C"})
    t0 = time.monotonic()
    try:
        p = subprocess.run([binary] + args, cwd=tree, env=env, stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, timeout=timeout)
        rc, so, se = p.returncode, p.stdout, p.stderr
        timed_out = False
    except subprocess.TimeoutExpired as e:
        rc, so, se, timed_out = None, e.stdout or b"", e.stderr or b"", True
    dt = time.monotonic() - t0
    files = {}
    for dirpath, _, names in os.walk(out_dir):
        for n in names:
            full = os.path.join(dirpath, n)
            rel = os.path.relpath(full, out_dir)
            with open(full, "rb") as f:
                files[rel] = f.read()
    norm = lambda b: b.decode("utf-8", "replace").replace(tree, "@T")

    def not_utf8(b):
        try:
            b.decode("utf-8")
            return False
        except UnicodeDecodeError:
            return True
    bad_utf8 = [k for k, v in files.items() if k.endswith((".json", ".html")) and not_utf8(v)]
    if so.lstrip().startswith(b"{") and not_utf8(so):
        bad_utf8.append("stdout")
    return {"args": args, "rc": rc, "timeout": timed_out, "seconds": round(dt, 3),
            "stdout": norm(so), "stderr": norm(se),
            "stderr_longest_line": max((len(l) for l in se.split(b"\n")), default=0),
            "bad_utf8": bad_utf8, "files": {k: norm(v) for k, v in files.items()}}


def json_bad_numbers(text):
    bad = []

    def walk(v, key):
        if isinstance(v, float) and not math.isfinite(v):
            bad.append("%s=%r" % (key, v))
        elif v is None:
            bad.append("%s=null" % key)
        elif isinstance(v, dict):
            for k, x in v.items():
                walk(x, k)
        elif isinstance(v, list):
            for x in v:
                walk(x, key)

    try:
        walk(json.loads(text), "")
    except ValueError:
        return []
    return bad


def csv_bad_numbers(text):
    bad = []
    for line in text.splitlines():
        if line.lstrip().startswith("#"):
            continue
        for f in line.split(","):
            if re.fullmatch(r"\s*[-+]?(nan|inf|infinity)\s*", f, re.I):
                bad.append(f.strip())
    return bad


PROGRAM_EXT = (".src", ".dat", ".mod", ".prg", ".ls", ".html")


def comparable(run):
    """The run's numbers as they matter: stdout and every output file but programs (a written
    program carries every input line it does not compensate as it is: the targets export has
    the numbers) and HTML reports."""
    return (run["stdout"], {k: v for k, v in run["files"].items() if not k.endswith(PROGRAM_EXT)})


def classify(run, command, mutation, baseline):
    """A list of failure categories (empty: the run is OK) and the run's outcome label."""
    fails = []
    se = run["stderr"]
    if SAN_RE.search(se):
        fails.append("sanitizer")
    if run["timeout"]:
        fails.append("timeout")
        return fails, "timeout"
    rc = run["rc"]
    if rc not in (0, 1, 2):
        fails.append("crash")
    if rc == 2 and not re.search(r"^roprec: error: \S", se, re.M):
        fails.append("no_error_line")
    if "internal error" in se.lower():
        fails.append("internal_error")
    files = run["files"]
    if any(".roprec-tmp" in k for k in files):
        fails.append("staging_left")
    present = [o for o in command["outputs"] if o in files]
    if rc == 2 and files:
        fails.append("partial_output")
    elif rc == 1 and present and len(present) != len(command["outputs"]):
        fails.append("partial_output")
    elif rc == 0 and len(present) != len(command["outputs"]):
        fails.append("missing_output")
    if rc in (0, 1):
        for k, v in files.items():
            bad = json_bad_numbers(v) if k.endswith(".json") else (
                csv_bad_numbers(v) if k.endswith(".csv") else [])
            base_bad = set()
            if baseline is not None and k in baseline["files"]:
                b = baseline["files"][k]
                base_bad = set(json_bad_numbers(b) if k.endswith(".json") else [])
            if [x for x in bad if x not in base_bad]:
                fails.append("nonfinite_output")
                break
        if rc == 0 and run["stdout"].lstrip().startswith(("{", "[")):
            base_bad = set(json_bad_numbers(baseline["stdout"])) if baseline else set()
            if [x for x in json_bad_numbers(run["stdout"]) if x not in base_bad]:
                fails.append("nonfinite_output")
    injected_nonfinite = mutation["operator"] in ("value_nan", "value_inf") or "nan" in \
        mutation["desc"].lower() or "inf" in mutation["desc"].lower()
    msg = se + ("" if run["stdout"].lstrip().startswith("{") else run["stdout"])
    base_msg = baseline["stderr"] if baseline else ""
    if not injected_nonfinite and rc is not None:
        hits = [m.group(0) for m in NONFINITE_MSG_RE.finditer(msg)]
        base_hits = [m.group(0) for m in NONFINITE_MSG_RE.finditer(base_msg)]
        if len(hits) > len(base_hits):
            fails.append("nonfinite_message")
    if LONGNUM_RE.search(se) and not LONGNUM_RE.search(base_msg):
        fails.append("long_number_message")
    if run.get("bad_utf8"):
        fails.append("invalid_utf8_output")
    if mutation["operator"] in ("utf16", "utf32", "nul") and rc != 2:
        fails.append("not_refused")
    if run.get("stderr_longest_line", 0) > 5000:
        fails.append("huge_message")
    echo_ok = command["echo"] and mutation["operator"].startswith("value_")
    if rc == 0 and mutation["strict"] and not echo_ok and baseline is not None and \
            baseline["rc"] == 0:
        if comparable(run) != comparable(baseline):
            base_lines = set(baseline["stderr"].splitlines())
            new_notes = [l for l in se.splitlines() if l not in base_lines and NOTE_RE.search(l)]
            if not new_notes:
                fails.append("silent_wrong_answer")
    outcome = "timeout" if run["timeout"] else ("exit%d" % rc if rc in (0, 1, 2) else "signal")
    return sorted(set(fails)), outcome


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--binary", default=os.path.join(ROOT, "build-mut", "bin", "roprec"))
    ap.add_argument("--count", type=int, default=700, help="number of mutants (700)")
    ap.add_argument("--seed", type=int, default=13)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=10.0)
    ap.add_argument("--out", default=None, help="log folder (default: BINARY/../../mutation)")
    ap.add_argument("--only", default="", help="comma list of file kinds: cell,card,urdf,csv,program")
    ap.add_argument("--encodings", action="store_true",
                    help="mutate encodings instead: UTF-16/32, NUL, a Latin-1 byte, a 1 MB name")
    a = ap.parse_args()
    binary = os.path.abspath(a.binary)
    if not os.access(binary, os.X_OK):
        sys.exit("mutation-campaign: no executable %s (build the roprec target first)" % binary)
    out = os.path.abspath(a.out or os.path.join(os.path.dirname(os.path.dirname(binary)),
                                                "mutation"))
    os.makedirs(out, exist_ok=True)
    shutil.rmtree(os.path.join(out, "cases"), ignore_errors=True)
    only = set(x for x in a.only.split(",") if x)

    scen = scenarios()
    # Every (scenario, file) pair that can be mutated, in a fixed order.
    targets = [(s, f) for s in scen for f in s["files"]
               if not only or kind_of(f) in only]
    rng = random.Random(a.seed)
    mutants = []
    attempts = 0
    while len(mutants) < a.count and attempts < a.count * 20:
        attempts += 1
        s, f = targets[len(mutants) % len(targets)] if attempts % 3 else rng.choice(targets)
        with open(os.path.join(ROOT, f), encoding="utf-8", errors="surrogateescape",
                  newline="") as fh:
            text = fh.read()
        r = rng.choice(ENCODING_MUTATORS if a.encodings else MUTATORS)(text, rng, kind_of(f))
        if r is None or r[0] == text:
            continue
        mutants.append({"id": "m%05d" % len(mutants), "scenario": s["name"], "file": f,
                        "kind": kind_of(f), "text": r[0], "operator": r[1], "strict": r[2],
                        "desc": r[3]})

    t_start = time.monotonic()
    workdir = tempfile.mkdtemp(prefix="roprec-mutation-")
    by_name = {s["name"]: s for s in scen}

    def tree_files(s):
        files = set(s["files"]) | set(s.get("extra", []))
        for c in s["commands"]:
            files |= set(c["reads"])
        return sorted(files)

    # Baselines: every command on the unmutated inputs.
    baselines = {}
    for s in scen:
        tree = os.path.join(workdir, "base-" + s["name"])
        make_tree(tree_files(s), tree)
        for ci, c in enumerate(s["commands"]):
            baselines[(s["name"], ci)] = run_one(binary, tree, c, a.timeout * 3)

    def do_mutant(m):
        s = by_name[m["scenario"]]
        tree = os.path.join(workdir, m["id"])
        make_tree(tree_files(s), tree)
        with open(os.path.join(tree, m["file"]), "w", encoding="utf-8",
                  errors="surrogateescape", newline="") as fh:
            fh.write(m["text"])
        results = []
        for ci, c in enumerate(s["commands"]):
            if m["file"] not in c["reads"]:
                continue
            run = run_one(binary, tree, c, a.timeout)
            fails, outcome = classify(run, c, m, baselines[(s["name"], ci)])
            results.append({"command": ci, "args": run["args"], "rc": run["rc"],
                            "seconds": run["seconds"], "outcome": outcome, "fails": fails,
                            "stderr": run["stderr"][-2000:]})
        if any(r["fails"] for r in results):
            case = os.path.join(out, "cases", m["id"])
            shutil.rmtree(os.path.join(tree, "out"), ignore_errors=True)
            shutil.copytree(tree, case)
        shutil.rmtree(tree, ignore_errors=True)
        return m, results

    log = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as ex:
        for i, (m, results) in enumerate(ex.map(do_mutant, mutants)):
            log.append((m, results))
            if (i + 1) % 50 == 0:
                print("  %d/%d mutants, %.0f s" % (i + 1, len(mutants), time.monotonic() - t_start),
                      file=sys.stderr, flush=True)
    shutil.rmtree(workdir, ignore_errors=True)
    wall = time.monotonic() - t_start

    # Summary.
    runs = sum(len(r) for _, r in log)
    outcomes, ops, cats = {}, {}, {}
    failing = []
    base_bad = [(k, v) for k, v in baselines.items() if v["rc"] != 0 or v["timeout"]]
    for m, results in log:
        ops[m["operator"]] = ops.get(m["operator"], 0) + 1
        for r in results:
            outcomes[r["outcome"]] = outcomes.get(r["outcome"], 0) + 1
            for f in r["fails"]:
                cats[f] = cats.get(f, 0) + 1
            if r["fails"]:
                failing.append((m, r))
    print("roprec mutation campaign: seed %d, %d mutants, %d runs, %.0f s wall, %d jobs" %
          (a.seed, len(mutants), runs, wall, a.jobs))
    for k, v in sorted(base_bad):
        print("  baseline %s command %d exited %s (its mutants are judged without it)" %
              (k[0], k[1], v["rc"]))
    print("  outcomes:   " + ", ".join("%s %d" % kv for kv in sorted(outcomes.items())))
    print("  mutations:  " + ", ".join("%s %d" % kv for kv in sorted(ops.items())))
    print("  failures:   " + (", ".join("%s %d" % kv for kv in sorted(cats.items())) or "none"))
    for m, r in failing:
        print("FAIL %s [%s] %s %s: %s (%s)" % (m["id"], ",".join(r["fails"]), m["file"],
                                               m["operator"], m["desc"], r["outcome"]))
        print("  repro: cd %s && ROPREC_ROBOTS_DIR=robots %s %s" % (
            os.path.join(out, "cases", m["id"]), binary,
            " ".join("'%s'" % x if (" " in x or not x) else x for x in r["args"])))
        tail = [l for l in r["stderr"].splitlines() if l.strip()][:3]
        for l in tail:
            print("    " + l[:300])
    with open(os.path.join(out, "log.json"), "w", encoding="utf-8") as fh:
        json.dump({"seed": a.seed, "count": len(mutants), "runs": runs, "wall_s": round(wall, 1),
                   "binary": binary, "outcomes": outcomes, "operators": ops, "failures": cats,
                   "mutants": [{k: v for k, v in m.items() if k != "text"} | {"runs": r}
                               for m, r in log]}, fh, indent=1)
    print("log: %s" % os.path.join(out, "log.json"))
    return 1 if failing else 0


if __name__ == "__main__":
    sys.exit(main())
