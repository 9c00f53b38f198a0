#!/usr/bin/env bash
# roprec for Windows, cross-built on Debian 12 (run as root, like scripts/setup.sh):
#   1. installs the MinGW-w64 cross compiler (posix threads), wine64 and nsis;
#   2. adds a deb-src entry for the Debian registry this machine already uses (in its own file,
#      /etc/apt/sources.list.d/roprec-windows-src.sources) and fetches the dependencies' Debian
#      sources with `apt-get source`;
#   3. cross-builds them for x86_64-w64-mingw32 into a prefix outside the clone, keyed by their
#      versions ($ROPREC_WINDOWS_CACHE, default /var/cache/roprec-windows/<key>): built once per
#      machine, reused by later runs;
#   4. builds roprec into build-windows/ with cmake/mingw-w64.cmake;
#   5. runs the tests under wine64 (see "Tests" below);
#   6. packs build-windows/roprec-<version>-win64.zip and the NSIS installer (CPack);
#   7. runs the README's sample job from the ZIP under wine64 against Linux, byte for byte.
# Tests: the C++ suite (roprec_tests, KDL and kdl_parser cross-built for its reference tests) under
# wine64 in two shards, without the POSIX-only tests of tests/windows/posix_only_tests.txt; the
# fuzz seed replays; the C example; then the sample job from the ZIP against build/bin/roprec
# (so .ci/run runs this after scripts/test.sh). The Python package is tested on Linux (ctest
# python_api_ctypes, python_cabi, whose Windows DLL loading runs against a stand-in os module):
# Debian has no Windows CPython.
# --ci (what .ci/run runs): the same steps with roprec_tests built from the test files of
# tests/windows/ci_tests.txt only (-DROPREC_TEST_ONLY): the platform layer, UTF-8 paths, atomic
# output sets, input files, number formatting, the CLI's main and the C ABI, the parts that differ
# between Linux and Windows. The rest of the suite is portable code whose Windows build differs
# only in the C library's rounding (MinGW-w64's sin/cos/exp: 1-3 ulp on 0.1-0.2 % of arguments).
# Budget (the shared 2-core machine, 6 builds at once, each its fair share of ~1/3 core): the
# dependencies up to SUNDIALS took ~17 min, KDL + kdl_parser + GoogleTest 7 min, once per machine;
# roprec's library, CLI and C DLL ~18 min at -O1; the whole suite's 95 test files ~60-70 min more
# (precompiled header) and 5-17 min under wine64 (its last run: 684 passed, none failed, 8 left
# out, 4.7 min). --ci adds to --sample-job the precompiled header,
# its 7 test files, the fuzz harnesses and their run: measured on that loaded machine 98 + 184 s
# (header, c_api_test) + 188 s (the rest) of build and 60 s under wine64 (49 tests, 13 ctests);
# with the header and c_api_test built, the whole --ci run took 6.2 min and 1.7 min of CPU
# (user + sys, packing included). Estimate on 2 free cores: ~2-3 min more than --sample-job.
# Options: --ci (above), --no-tests (steps 1-4 and 6), --sample-job (steps 1-4, 6 and the sample
# job of 7), --deps-only (steps 1-3). Each step's wall time is printed.
# Logs: build-windows/logs/. ROPREC_WINDOWS_JOBS sets the parallel jobs (default: nproc);
# ROPREC_WINDOWS_OPT replaces Release's -O3 (e.g. -O1: about half the compile time on a loaded
# machine; IEEE arithmetic without -ffast-math, so the same numbers).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="$ROOT/build-windows"
LOGS="$BUILD/logs"
JOBS="${ROPREC_WINDOWS_JOBS:-$(nproc)}"
RUN_TESTS=1
SAMPLE_JOB=1
DEPS_ONLY=0
CI_TESTS=0
for a in "$@"; do
  case "$a" in
    --no-tests) RUN_TESTS=0; SAMPLE_JOB=0 ;;
    --sample-job) RUN_TESTS=0 ;;  # no C++ suite: build, pack, and the sample job against Linux
    --ci) CI_TESTS=1 ;;  # roprec_tests of tests/windows/ci_tests.txt's files only, then as the default
    --deps-only) DEPS_ONLY=1 ;;
    *) echo "usage: scripts/windows.sh [--ci | --no-tests | --sample-job | --deps-only]" >&2; exit 2 ;;
  esac
done
mkdir -p "$LOGS"

# The dependencies' Debian source packages and the versions the cache is keyed by (Debian 12).
DEPS=(
  "console-bridge 1.0.1"
  "urdfdom-headers 1.0.5"
  "tinyxml 2.6.2"
  "tinyxml2 9.0.0"
  "urdfdom 3.0.1"
  "nlopt 2.7.1"
  "sundials 6.4.1"
  "orocos-kdl 1.5.1"
  "ros-kdl-parser 1.14.2"
)
TRIPLE=x86_64-w64-mingw32

# The cache of the cross-built dependencies, keyed by their versions, the cross compiler's and
# googletest's (known once the packages are installed). Bump RECIPE when build_deps changes what
# it builds: a new prefix is then built once.
RECIPE=1
set_cache_paths() {
  KEY="$(printf '%s\n' "${DEPS[@]}" "googletest $(dpkg-query -W -f='${Version}' googletest)" \
    "mingw $(dpkg-query -W -f='${Version}' g++-mingw-w64-x86-64-posix)" "recipe $RECIPE" | sha1sum | cut -c1-12)"
  CACHE="${ROPREC_WINDOWS_CACHE:-/var/cache/roprec-windows/$KEY}"
  PREFIX="$CACHE/prefix"
  SRC="${CACHE%/*}/sources"  # the Debian source packages (their names hold their versions)
}

phase_start=0
phase() {
  phase_start=$(date +%s)
  echo "windows: $1"
}
phase_done() { echo "windows:   done in $(($(date +%s) - phase_start)) s"; }

# ---- 1. packages
install_packages() {
  local packages=(g++-mingw-w64-x86-64-posix gcc-mingw-w64-x86-64-posix wine64 nsis dpkg-dev cmake ninja-build
    zip unzip libeigen3-dev nlohmann-json3-dev googletest)
  local missing=() p
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if ((${#missing[@]})); then
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends "${missing[@]}" >"$LOGS/apt-install.log"
  fi
}

# ---- 2. sources: deb-src twins of this machine's Debian deb entries (deb822 *.sources files and
# one-line sources.list entries), then `apt-get source` of each dependency
add_deb_src() {
  local list=/etc/apt/sources.list.d/roprec-windows-src.sources
  [[ -f "$list" ]] && return 0
  local out="" f
  for f in /etc/apt/sources.list.d/*.sources; do
    [[ -f "$f" && "$f" != "$list" ]] || continue
    # a stanza whose Types has "deb" and whose URI is a Debian archive
    out+="$(awk 'BEGIN{RS=""; ORS="\n\n"}
      $0 ~ /(^|\n)Types:[^\n]*deb( |\n|$)/ && $0 ~ /(^|\n)URIs:[^\n]*debian/ {
        gsub(/(^|\n)Types:[^\n]*/, "\nTypes: deb-src"); sub(/^\n/, ""); print }' "$f")"$'\n'
  done
  if [[ -f /etc/apt/sources.list ]]; then
    local line
    while read -r line; do
      out+="$(awk '$1=="deb" && $0 ~ /debian/ {
        i=2; if ($2 ~ /^\[/) { while ($i !~ /\]$/) i++; i++ }
        printf "Types: deb-src\nURIs: %s\nSuites: %s\nComponents:", $i, $(i+1)
        for (j=i+2; j<=NF; j++) printf " %s", $j; printf "\n\n" }' <<<"$line")"
    done </etc/apt/sources.list
  fi
  [[ -n "${out//[$'\n ']/}" ]] || { echo "windows: no Debian deb entry found in /etc/apt" >&2; exit 1; }
  printf '# added by roprec scripts/windows.sh: the Debian sources of the Windows dependencies\n%s' "$out" >"$list"
  apt-get update -qq
}

fetch_sources() {
  mkdir -p "$SRC"
  local d name version orig
  for d in "${DEPS[@]}"; do
    read -r name version <<<"$d"
    [[ -f "$SRC/.fetched-$name-$version" ]] && continue
    if ! compgen -G "$SRC/${name}-${version}*/" >/dev/null; then
      if ! (cd "$SRC" && apt-get source -qq "$name" >>"$LOGS/apt-source.log" 2>&1); then
        # the registry may lack the Debian packaging tarball (seen for ros-kdl-parser 1.14.2-2:
        # 404): the upstream tarball it did fetch is used as it is
        orig="$(compgen -G "$SRC/${name}_${version}*.orig.tar.*" | head -1 || true)"
        [[ -n "$orig" ]] || { echo "windows: apt-get source $name failed ($LOGS/apt-source.log)" >&2; exit 1; }
        tar -xf "$orig" -C "$SRC"
      fi
    fi
    touch "$SRC/.fetched-$name-$version"
  done
}
srcdir() {  # the unpacked Debian source tree of package $1 (version $2)
  local d
  local upstream="${1#ros-}"  # ros-kdl-parser's upstream tarball unpacks to kdl_parser-VERSION
  for d in "$SRC/$1-$2"*/ "$SRC/${upstream//-/_}-$2"*/; do
    [[ -d "$d" ]] && { echo "${d%/}"; return; }
  done
  echo "windows: no source tree for $1 $2 in $SRC" >&2
  exit 1
}

# ---- the dependencies' builds
cross_cmake() {  # NAME SOURCE_DIR [cmake args...]: configure, build and install one CMake project
  local name="$1" src="$2"
  shift 2
  local b="$CACHE/build/$name"
  rm -rf "$b"  # a fresh build: a left-over tree may name another clone's toolchain file
  nice -n 10 cmake -S "$src" -B "$b" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$ROOT/cmake/mingw-w64.cmake" \
    -DROPREC_WINDOWS_PREFIX="$PREFIX" -DCMAKE_INSTALL_PREFIX="$PREFIX" -DCMAKE_BUILD_TYPE=Release \
    -DBUILD_TESTING=OFF "$@" >"$LOGS/deps-$name.log" 2>&1
  nice -n 10 cmake --build "$b" --parallel "$JOBS" >>"$LOGS/deps-$name.log" 2>&1
  nice -n 10 cmake --install "$b" >>"$LOGS/deps-$name.log" 2>&1
}

build_tinyxml() {  # tinyxml 2.6.2 has no build system of its own: a static library with TIXML_USE_STL
  local s b
  s="$(srcdir tinyxml 2.6.2)"
  b="$CACHE/build/tinyxml"
  mkdir -p "$b" "$PREFIX/lib" "$PREFIX/include"
  local f
  for f in tinyxml tinystr tinyxmlerror tinyxmlparser; do
    nice -n 10 $TRIPLE-g++-posix -O2 -DTIXML_USE_STL -c "$s/$f.cpp" -o "$b/$f.o"
  done
  $TRIPLE-ar rcs "$PREFIX/lib/libtinyxml.a" "$b"/*.o
  cp "$s/tinyxml.h" "$s/tinystr.h" "$PREFIX/include/"
}

build_kdl_parser() {  # ROS kdl_parser without ROS (no HAS_ROS/HAS_URDF): its catkin build replaced by one DLL
  local s
  s="$(srcdir ros-kdl-parser 1.14.2)/kdl_parser"
  mkdir -p "$PREFIX/include/kdl_parser" "$PREFIX/bin"
  nice -n 10 $TRIPLE-g++-posix -std=c++17 -O2 -shared -DTIXML_USE_STL -DKDL_PARSER_BUILDING_LIBRARY \
    -I"$s/include" -I"$PREFIX/include" -I"$PREFIX/include/eigen3" "$s/src/kdl_parser.cpp" \
    -o "$PREFIX/bin/libkdl_parser.dll" -Wl,--out-implib,"$PREFIX/lib/libkdl_parser.dll.a" \
    -L"$PREFIX/lib" -lorocos-kdl -lurdfdom_model -ltinyxml2 -ltinyxml >"$LOGS/deps-kdl_parser.log" 2>&1
  cp "$s"/include/kdl_parser/*.hpp "$PREFIX/include/kdl_parser/"
}

dep() {  # NAME COMMAND...: builds one dependency unless an earlier run did (stamp)
  local stamp="$CACHE/stamps/$1"
  shift
  [[ -f "$stamp" ]] && return 0
  "$@"
  mkdir -p "${stamp%/*}"
  touch "$stamp"
}

build_deps() {
  mkdir -p "$PREFIX"
  # header-only dependencies: Debian's headers, with their CMake packages relocated into the
  # prefix (the packages locate the headers relative to themselves; /usr/include itself must not
  # be on a cross build's include path)
  mkdir -p "$PREFIX/include" "$PREFIX/share"
  ln -sfn /usr/include/eigen3 "$PREFIX/include/eigen3"
  ln -sfn /usr/include/nlohmann "$PREFIX/include/nlohmann"
  cp -r /usr/share/eigen3 "$PREFIX/share/"
  mkdir -p "$PREFIX/share/cmake"
  cp -r /usr/share/cmake/nlohmann_json "$PREFIX/share/cmake/"

  dep console_bridge cross_cmake console_bridge "$(srcdir console-bridge 1.0.1)" -DBUILD_SHARED_LIBS=ON
  dep urdfdom_headers cross_cmake urdfdom_headers "$(srcdir urdfdom-headers 1.0.5)"
  dep tinyxml build_tinyxml
  dep tinyxml2 cross_cmake tinyxml2 "$(srcdir tinyxml2 9.0.0)" -DBUILD_SHARED_LIBS=ON -Dtinyxml2_BUILD_TESTING=OFF
  dep urdfdom cross_cmake urdfdom "$(srcdir urdfdom 3.0.1)" -DBUILD_SHARED_LIBS=ON \
    -DTinyXML_INCLUDE_DIR="$PREFIX/include" -DTinyXML_LIBRARY="$PREFIX/lib/libtinyxml.a"
  # NLopt's C library alone, as Debian's libnlopt (the CMake target NLopt::nlopt)
  dep nlopt cross_cmake nlopt "$(srcdir nlopt 2.7.1)" -DBUILD_SHARED_LIBS=ON -DNLOPT_CXX=OFF -DNLOPT_PYTHON=OFF \
    -DNLOPT_OCTAVE=OFF -DNLOPT_MATLAB=OFF -DNLOPT_GUILE=OFF -DNLOPT_SWIG=OFF -DNLOPT_TESTS=OFF
  dep sundials cross_cmake sundials "$(srcdir sundials 6.4.1)" -DBUILD_SHARED_LIBS=ON -DBUILD_STATIC_LIBS=OFF \
    -DBUILD_ARKODE=OFF -DBUILD_CVODES=OFF -DBUILD_IDA=OFF -DBUILD_IDAS=OFF -DBUILD_KINSOL=OFF \
    -DBUILD_CVODE=ON -DEXAMPLES_ENABLE_C=OFF -DEXAMPLES_ENABLE_CXX=OFF -DEXAMPLES_INSTALL=OFF
  # for the tests only: KDL, kdl_parser (the reference kinematics) and GoogleTest
  ((RUN_TESTS)) || return 0
  dep orocos_kdl cross_cmake orocos_kdl "$(srcdir orocos-kdl 1.5.1)/orocos_kdl" -DBUILD_SHARED_LIBS=ON \
    -DENABLE_TESTS=OFF -DENABLE_EXAMPLES=OFF -DEIGEN3_INCLUDE_DIR="$PREFIX/include/eigen3"
  dep kdl_parser build_kdl_parser
  dep googletest cross_cmake googletest /usr/src/googletest -DBUILD_SHARED_LIBS=OFF -Dgtest_disable_pthreads=OFF
}

phase "packages (g++-mingw-w64-x86-64-posix, wine64, nsis)"
install_packages
phase_done
set_cache_paths
if [[ ! -f "$CACHE/ok" ]] && { ((RUN_TESTS)) || [[ ! -f "$CACHE/stamps/sundials" ]]; }; then
  phase "Debian sources of the dependencies (apt-get source) into $SRC"
  add_deb_src
  fetch_sources
  phase_done
  phase "cross-building the dependencies into $PREFIX (logs: $LOGS/deps-*.log)"
  build_deps  # an interrupted run resumes at the dependency it was building
  printf '%s\n' "${DEPS[@]}" >"$CACHE/versions.txt"
  ((RUN_TESTS)) && touch "$CACHE/ok"  # with --no-tests the test-only ones are still to build
  phase_done
else
  echo "windows: dependencies cached in $PREFIX"
fi
if ((DEPS_ONLY)); then exit 0; fi

# ---- 4. roprec
# Debian's wine64 package keeps its loader in /usr/lib/wine (the `wine` package links it into /usr/bin)
export WINE="$(command -v wine64 || echo /usr/lib/wine/wine64)"
export WINEDEBUG=-all
export WINEPREFIX="${ROPREC_WINEPREFIX:-${CACHE%/*}/wine}"  # a private Wine prefix, made once
RUNTIME_DIR="$(dirname "$($TRIPLE-g++-posix -print-file-name=libstdc++-6.dll)")"
winpath() { local p="$1"; echo "Z:${p//\//\\}"; }
# the DLLs the exe and the tests load: the dependencies' and the GCC runtime's
# (SUNDIALS installs its DLLs in lib/)
export WINEPATH="$(winpath "$PREFIX/bin");$(winpath "$PREFIX/lib");$(winpath "$RUNTIME_DIR");$(winpath "/usr/$TRIPLE/lib")"
if [[ ! -d "$WINEPREFIX" ]]; then
  phase "Wine prefix $WINEPREFIX"
  "$WINE" wineboot -i >"$LOGS/wineboot.log" 2>&1
  phase_done
fi

phase "building roprec into $BUILD (log: $LOGS/build.log)"
CCACHE="$(command -v ccache || true)"  # a later run on the same machine compiles only what changed
# --ci: roprec_tests from the files of tests/windows/ci_tests.txt (a regex of their names, dots
# escaped); otherwise from every test file (an empty value clears one cached by an earlier --ci)
TEST_ONLY=""
if ((CI_TESTS)); then
  TEST_ONLY="/($(awk '$1 == "file" { gsub(/\./, "\\.", $2); print $2 }' "$ROOT/tests/windows/ci_tests.txt" | paste -sd'|'))\$"
fi
nice -n 10 cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$ROOT/cmake/mingw-w64.cmake" \
  -DROPREC_WINDOWS_PREFIX="$PREFIX" -DCMAKE_BUILD_TYPE=Release -DROPREC_BUILD_BENCH=OFF \
  -DROPREC_BUILD_PYTHON=OFF -DROPREC_BUILD_TESTS="$([[ $RUN_TESTS == 1 ]] && echo ON || echo OFF)" \
  -DROPREC_TEST_ONLY="$TEST_ONLY" \
  ${CCACHE:+-DCMAKE_C_COMPILER_LAUNCHER=$CCACHE -DCMAKE_CXX_COMPILER_LAUNCHER=$CCACHE} \
  ${ROPREC_WINDOWS_OPT:+"-DCMAKE_CXX_FLAGS_RELEASE=$ROPREC_WINDOWS_OPT -DNDEBUG"} \
  >"$LOGS/configure.log" 2>&1 || { tail -30 "$LOGS/configure.log" >&2; exit 1; }
if ! nice -n 10 cmake --build "$BUILD" --parallel "$JOBS" >"$LOGS/build.log" 2>&1; then
  grep -E "error|FAILED" "$LOGS/build.log" | head -40 >&2
  echo "windows: build failed (full log: $LOGS/build.log)" >&2
  exit 1
fi
if grep -q "warning:" "$LOGS/build.log"; then
  grep -E "warning:" "$LOGS/build.log" | sort -u | head -20 >&2
  echo "windows: the build printed compiler warnings (full log: $LOGS/build.log)" >&2
  exit 1
fi
phase_done

# ---- 5. tests under wine64
# The GoogleTest XML of the shards, summarised: tests run, passed, failed (named), skipped, and the
# tests of tests/windows/posix_only_tests.txt that the filter left out.
gtest_summary() {
  python3 - "$LOGS" <<'PY'
import glob, sys, xml.etree.ElementTree as ET
run = failed = skipped = 0
names = []
for f in sorted(glob.glob(sys.argv[1] + "/gtest-shard*.xml")):
    for case in ET.parse(f).getroot().iter("testcase"):
        if case.get("status") == "notrun" or case.get("result") == "suppressed":
            continue
        run += 1
        if case.find("failure") is not None:
            failed += 1
            names.append(case.get("classname") + "." + case.get("name"))
        elif case.get("result") == "skipped" or case.find("skipped") is not None:
            skipped += 1
for n in names:
    print("windows:   FAILED " + n)
print("windows: %d passed, %d failed, %d skipped" % (run - failed - skipped, failed, skipped))
PY
}
excluded_count() {  # the tests of tests/windows/posix_only_tests.txt's "test" lines in roprec_tests
  local patterns
  patterns="$(awk '$1 == "test" { print $2 }' "$ROOT/tests/windows/posix_only_tests.txt" | paste -sd:)"
  "$WINE" "$BUILD/bin/roprec_tests.exe" --gtest_list_tests --gtest_filter="$patterns" 2>/dev/null |
    grep -c '^  ' || true
}
if ((RUN_TESTS)); then
  phase "test suite under wine64 (log: $LOGS/ctest.log)"
  rm -f "$LOGS"/gtest-shard*.xml
  # not run here: `packaging` (installs and builds consumers with the Linux tools, the .deb) and
  # `memory_check` (peak memory by GNU time of the Linux process)
  ctest_ok=1
  (cd "$BUILD" && nice -n 10 ctest --parallel "$JOBS" --timeout 900 --output-on-failure \
    -E "^(packaging|memory_check)$" >"$LOGS/ctest.log" 2>&1) || ctest_ok=0
  tail -3 "$LOGS/ctest.log"
  gtest_summary
  echo "windows:   $(excluded_count) tests of roprec_tests left out (tests/windows/posix_only_tests.txt)"
  ((ctest_ok)) || { tail -40 "$LOGS/ctest.log" >&2; exit 1; }
  phase_done
fi

# ---- 6. ZIP and NSIS installer
phase "packages (CPack ZIP and NSIS; log: $LOGS/cpack.log)"
(cd "$BUILD" && nice -n 10 cpack -G ZIP >"$LOGS/cpack.log" 2>&1 && nice -n 10 cpack -G NSIS >>"$LOGS/cpack.log" 2>&1) ||
  { tail -30 "$LOGS/cpack.log" >&2; exit 1; }
ls -1 "$BUILD"/roprec-*-win64.zip "$BUILD"/roprec-*-win64.exe
phase_done

# ---- 7. the README's sample job from the ZIP under wine64, byte for byte against Linux
if ((SAMPLE_JOB)); then
  phase "sample job: the ZIP's roprec.exe under wine64 against build/bin/roprec"
  bash "$ROOT/tests/windows/sample_job_test.sh" --linux "$ROOT/build/bin/roprec" \
    --zip "$(ls "$BUILD"/roprec-*-win64.zip | head -1)" --source "$ROOT"
  phase_done
fi
