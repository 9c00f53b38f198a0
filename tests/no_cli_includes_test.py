"""The tests use the library's API, never the CLI's internals: no file under tests/ includes a
plugin/cli/ header — except tests the CLI owns (files named cli_*, which test the CLI's own
option parsing and are built with its sources). Fails listing every offending include.

    python3 tests/no_cli_includes_test.py [TESTS_DIR]
"""

import re
import sys
from pathlib import Path

INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]*plugin/cli/[^>"]*)[>"]', re.M)
SOURCES = {".cpp", ".cc", ".cxx", ".hpp", ".h", ".hh", ".c", ".inc"}


def offenders(tests_dir):
    found = []
    for path in sorted(Path(tests_dir).rglob("*")):
        if path.suffix not in SOURCES or not path.is_file() or path.name.startswith("cli_"):
            continue
        text = path.read_text(encoding="utf-8", errors="replace")
        for m in INCLUDE.finditer(text):
            line = text.count("\n", 0, m.start()) + 1
            found.append("%s:%d: includes %s" % (path, line, m.group(1)))
    return found


def main(argv):
    tests_dir = Path(argv[1]) if len(argv) > 1 else Path(__file__).resolve().parent
    bad = offenders(tests_dir)
    for b in bad:
        print(b, file=sys.stderr)
    if bad:
        print("%d include(s) of plugin/cli/ in %s: tests must use the library API (plugin/api, compensator, "
              "postproc), or be named cli_* when they test the CLI itself" % (len(bad), tests_dir), file=sys.stderr)
        return 1
    print("no test includes a plugin/cli/ header (%s)" % tests_dir)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
