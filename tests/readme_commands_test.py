#!/usr/bin/env python3
"""Every command block of README.md (```sh) runs as written against the build, and README's C
table lists exactly the functions plugin/c/roprec.h exports.

Each block runs with `bash -e -o pipefail` in a scratch folder that looks like the source tree
(copies of samples/, examples/, robots/ and plugin/robodk/, the bundled robots read from that
robots/ copy, scripts/ linked, build/ linked to the build tree), with build/bin first on PATH (`roprec` is the built CLI), HOME in the
scratch folder, and must exit 0. The blocks that build or install the project itself are not run
here (SKIPPED names them and the test that covers each); a README block that is neither run nor
skipped fails the test. The shop-floor block, which re-plans the shipped verification programs,
must leave them byte-identical.

Usage: readme_commands_test.py SOURCE_DIR BUILD_DIR
"""

import filecmp
import os
import re
import shutil
import subprocess
import sys
import tempfile

# The first line of a block -> why it is not run here.
SKIPPED = {
    "scripts/demo.sh": "installs packages and builds the project (scripts/test.sh is the suite itself)",
    "cmake --install build --prefix /opt/roprec": "installs and packages the build (ctest -L packaging)",
    "scripts/windows.sh": "installs the cross toolchain and cross-builds the project (.ci/run runs it)",
}


def blocks(readme):
    """(line number, text) of each ```sh block."""
    out, current, start = [], None, 0
    for n, line in enumerate(readme.splitlines(), 1):
        if current is None and line.strip() == "```sh":
            current, start = [], n
        elif current is not None and line.strip() == "```":
            out.append((start, "\n".join(current) + "\n"))
            current = None
        elif current is not None:
            current.append(line)
    return out


def scratch_tree(src, build, tmp):
    """A folder where README's relative paths resolve as in the source tree."""
    work = os.path.join(tmp, "tree")
    os.makedirs(os.path.join(work, "plugin"))
    shutil.copytree(os.path.join(src, "samples"), os.path.join(work, "samples"))
    shutil.copytree(os.path.join(src, "examples"), os.path.join(work, "examples"))
    shutil.copytree(os.path.join(src, "plugin", "robodk"), os.path.join(work, "plugin", "robodk"))
    shutil.copytree(os.path.join(src, "robots"), os.path.join(work, "robots"))
    os.symlink(os.path.join(src, "scripts"), os.path.join(work, "scripts"))
    os.symlink(build, os.path.join(work, "build"))
    os.makedirs(os.path.join(work, "home"))
    return work


def run_block(work, build, line, text):
    env = dict(os.environ, HOME=os.path.join(work, "home"), LC_ALL="C",
               PATH=os.pathsep.join([os.path.join(build, "bin"), "/usr/bin", "/bin"]))
    env["ROPREC_ROBOTS_DIR"] = os.path.join(work, "robots")  # paths written relative to it, as in the source tree
    r = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", text], cwd=work, env=env, capture_output=True,
                       text=True, timeout=1500)
    if r.returncode != 0:
        return "README.md:%d: the block exits %d:\n%s\n--- stderr (tail) ---\n%s" % (
            line, r.returncode, text, "\n".join(r.stderr.splitlines()[-15:]))
    return None


def c_table_check(src, readme):
    header = open(os.path.join(src, "plugin", "c", "roprec.h"), encoding="utf-8").read()
    exported = set(re.findall(r"ROPREC_API\s+[^;(]*?\b(roprec_[a-z_]+)\s*\(", header))
    section = readme[readme.index("### C\n"):readme.index("### Python\n")]
    table = set(re.findall(r"`(roprec_[a-z_]+)`", "\n".join(l for l in section.splitlines() if l.startswith("| `"))))
    if not exported:
        return ["plugin/c/roprec.h: no ROPREC_API function found"]
    return ["README's C table %s %s" % (what, ", ".join(sorted(names)))
            for what, names in (("lacks", exported - table), ("lists unknown", table - exported)) if names]


def main():
    src, build = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    readme = open(os.path.join(src, "README.md"), encoding="utf-8").read()
    failures = c_table_check(src, readme)
    found = blocks(readme)
    with tempfile.TemporaryDirectory() as tmp:
        work = scratch_tree(src, build, tmp)
        ran = 0
        for line, text in found:
            first = text.strip().splitlines()[0]
            if any(first.startswith(k) for k in SKIPPED):
                print("README.md:%d: not run here: %s" % (line, next(v for k, v in SKIPPED.items() if first.startswith(k))))
                continue
            failure = run_block(work, build, line, text)
            if failure:
                failures.append(failure)
            else:
                ran += 1
                print("README.md:%d: ok (%d lines)" % (line, len(text.splitlines())))
        shipped = os.path.join(src, "samples", "verification")
        replanned = os.path.join(work, "samples", "verification")
        for name in sorted(os.listdir(shipped)):
            if not filecmp.cmp(os.path.join(shipped, name), os.path.join(replanned, name), shallow=False):
                failures.append("samples/verification/%s: README's shop-floor commands write it differently "
                                "(regenerate the shipped sample)" % name)
    if len(found) < 5:
        failures.append("README.md has only %d command blocks: the parser found too few" % len(found))
    for f in failures:
        print("FAIL: " + f)
    print("%d README command blocks run, %d not run here, %d failures" % (ran, len(found) - ran, len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
