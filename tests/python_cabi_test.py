"""roprec/_cabi.py, the ctypes binding over roprec_c: where it looks for the C library (Windows and
Linux install layouts, ROPREC_C_LIB first), how it loads it on Windows (os.add_dll_directory on
Python >= 3.8, PATH on 3.7; run on Linux with a stand-in of Windows' os module), that its error kinds map to roprec's exceptions and
that without numpy its per-hole Session calls give nested lists of the same values.
Its API is the same as the compiled module's: tests/python_api_test.py runs against both
(ctest python_api and python_api_ctypes)."""

import json
import ntpath
import os
import subprocess
import sys
import types
import unittest

os.environ["ROPREC_PYTHON_BACKEND"] = "ctypes"
import roprec  # noqa: E402
from roprec import _cabi  # noqa: E402

SRC = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class LibraryCandidatesTest(unittest.TestCase):
    def test_windows_zip_layout_finds_roprec_c_in_bin_beside_the_exe(self):
        pkg = r"C:\RoboDK\Apps\roprec\python\roprec"  # <install folder>\python\roprec
        c = _cabi.library_candidates(env={}, package_dir=pkg, platform="win32")
        self.assertEqual(c[0], pkg + r"\roprec_c.dll")  # first: beside the package
        self.assertIn(r"C:\RoboDK\Apps\roprec\bin\roprec_c.dll", c)
        self.assertTrue(all(p.endswith("roprec_c.dll") for p in c), c)
        self.assertEqual(c[-1], "roprec_c.dll")  # last: the system's own search (PATH)

    def test_linux_dist_packages_layout_finds_the_versioned_library_in_lib(self):
        pkg = "/opt/roprec/lib/python3/dist-packages/roprec"
        c = _cabi.library_candidates(env={}, package_dir=pkg, platform="linux")
        self.assertIn("/opt/roprec/lib/libroprec_c.so.0", c)
        self.assertLess(c.index("/opt/roprec/lib/libroprec_c.so.0"), c.index("libroprec_c.so.0"))

    def test_the_environment_variable_comes_first(self):
        c = _cabi.library_candidates(env={"ROPREC_C_LIB": "/x/libroprec_c.so"}, package_dir="/p/roprec",
                                     platform="linux")
        self.assertEqual(c[0], "/x/libroprec_c.so")
        self.assertEqual(len(c), len(set(c)))

    def test_the_loaded_library_is_the_one_the_environment_names(self):
        self.assertEqual(os.path.realpath(_cabi._lib._name), os.path.realpath(os.environ["ROPREC_C_LIB"]))
        self.assertIs(roprec._roprec, _cabi)


class FakeWindows:
    """The os module of a Windows CPython, for _cabi._load: ntpath, the files that exist, PATH, and
    os.add_dll_directory when `dll_directories` is a list (Python >= 3.8; absent on 3.7)."""

    name = "nt"
    pathsep = ";"

    def __init__(self, existing, dll_directories=None):
        self.path = types.SimpleNamespace(sep="\\", exists=lambda p: p in existing, isabs=ntpath.isabs,
                                          dirname=ntpath.dirname)
        self.environ = {"PATH": r"C:\Windows\system32"}
        if dll_directories is not None:
            self.add_dll_directory = lambda folder: dll_directories.append(folder) or folder


class WindowsLoadingTest(unittest.TestCase):
    """_cabi._load as on Windows, with the DLL loader replaced by a recorder of what it was given."""

    PKG = r"C:\Program Files\roprec\python\roprec"
    DLL = r"C:\Program Files\roprec\bin\roprec_c.dll"

    def load(self, system, fail=()):
        loaded = []

        def cdll(path):
            if path in fail:
                raise OSError("[WinError 126] The specified module could not be found")
            loaded.append(path)
            return "handle of " + path

        c = _cabi.library_candidates(env={}, package_dir=self.PKG, platform="win32")
        return _cabi._load(c, system=system, cdll=cdll), loaded

    def test_python_38_adds_the_dll_folder_to_the_search_and_loads_the_full_path(self):
        dirs = []
        system = FakeWindows({self.DLL}, dll_directories=dirs)
        lib, loaded = self.load(system)
        self.assertEqual(loaded, [self.DLL])
        self.assertEqual(lib, "handle of " + self.DLL)
        self.assertEqual(dirs, [r"C:\Program Files\roprec\bin"])
        self.assertEqual(system.environ["PATH"], r"C:\Windows\system32")  # PATH left alone

    def test_python_37_puts_the_dll_folder_in_front_of_path(self):
        system = FakeWindows({self.DLL})
        self.assertFalse(hasattr(system, "add_dll_directory"))
        _, loaded = self.load(system)
        self.assertEqual(loaded, [self.DLL])
        self.assertEqual(system.environ["PATH"], r"C:\Program Files\roprec\bin;C:\Windows\system32")

    def test_the_dll_beside_the_package_comes_before_the_install_layout(self):
        beside = self.PKG + r"\roprec_c.dll"
        dirs = []
        _, loaded = self.load(FakeWindows({beside, self.DLL}, dll_directories=dirs))
        self.assertEqual(loaded, [beside])
        self.assertEqual(dirs, [self.PKG])

    def test_without_a_dll_on_disk_the_bare_name_is_left_to_the_system_search(self):
        dirs = []
        system = FakeWindows(set(), dll_directories=dirs)
        _, loaded = self.load(system)
        self.assertEqual(loaded, ["roprec_c.dll"])
        self.assertEqual(dirs, [])  # no folder of its own: nothing added
        self.assertEqual(system.environ["PATH"], r"C:\Windows\system32")

    def test_a_dll_that_fails_to_load_is_named_in_the_import_error(self):
        with self.assertRaises(ImportError) as e:
            self.load(FakeWindows({self.DLL}, dll_directories=[]), fail=(self.DLL, "roprec_c.dll"))
        self.assertIn(self.DLL + ": [WinError 126]", str(e.exception))
        self.assertIn("ROPREC_C_LIB", str(e.exception))


class ErrorKindsTest(unittest.TestCase):
    def test_a_missing_cell_is_an_input_error_and_a_bad_pose_a_usage_error(self):
        with self.assertRaises(roprec.InputError):
            roprec.Session(os.path.join(SRC, "no-such-cell.xml"))
        s = roprec.Session(os.path.join(SRC, "samples", "cells", "housing-kr120.xml"))
        with self.assertRaises(roprec.UsageError):
            s.filter_target([[1, 0, 0, 0]] * 4)  # not a rigid pose
        with self.assertRaises(ValueError):
            s.filter_target([1, 2, 3])  # not 16 numbers


# The per-hole Session calls (tool 2 of the tool table, a hole of its own size) as a JSON text.
PER_HOLE_CALLS = r"""
import json, sys
import roprec
s = roprec.Session(sys.argv[1])
hole = dict(tool="2", diameter_mm=8.5, depth_mm=17.0)
wanted = s.hole_pose([150, 0, 250], [0, 0, -1])
far = [list(row) for row in wanted]
far[0][3] = 9000.0
one = s.filter_target(wanted, None, details=True, **hole)
joints = s.predict_joints(one["joints_deg"], **hole)
batch = s.filter_targets([wanted, far], holes=[hole, None])
lists = lambda x: x.tolist() if hasattr(x, "tolist") else x
out = [{k: lists(v) for k, v in d.items()} for d in (one, joints, batch)]
print(json.dumps(out))
"""


class WithoutNumpyTest(unittest.TestCase):
    def test_per_hole_calls_give_nested_lists_of_the_numpy_values(self):
        cell = os.path.join(SRC, "samples", "cells", "housing-kr120-tools.xml")
        runs = []
        for block in ("", "import sys; sys.modules['numpy'] = None\n"):  # None: 'import numpy' fails
            r = subprocess.run([sys.executable, "-c", block + PER_HOLE_CALLS, cell], capture_output=True, text=True,
                               env=dict(os.environ), timeout=300)
            self.assertEqual(r.returncode, 0, r.stderr)
            runs.append(r.stdout)
        self.assertEqual(runs[1], runs[0])
        one, joints, batch = json.loads(runs[0])
        self.assertEqual(len(one["pose_mm"]), 4)
        self.assertEqual((one["process"]["tool"], joints["process"]["depth_mm"]), ("2", 17.0))
        self.assertEqual(batch["ok"], [True, False])
        self.assertEqual(batch["process"][1]["from_cell"], True)


if __name__ == "__main__":
    unittest.main(verbosity=2)
