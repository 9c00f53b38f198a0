#!/usr/bin/env bash
# Packaging test (ctest label "packaging"): installs a built tree into a temporary prefix and
# uses it the way a host would, away from the source tree.
#
#   packaging_test.sh --source SRC --build BUILD [--cmake CMAKE] [--cpack CPACK] [--generator GEN]
#                     [--with-c 0|1] [--with-python 0|1]
#
# Consumers are built with no flags of their own: no C++ standard, no include path beyond what
# the package gives (the CMake targets, roprec.pc, roprec_c.pc).
# 1. `cmake --install BUILD --prefix $TMP/prefix`; checks the installed layout: the public headers
#    under include/roprec/ only (no internal header, no other top-level folder), the samples and
#    the RoboDK app under share/roprec/, the copyright file; every installed C++ header compiles
#    with roprec.pc's flags alone.
# 2. Runs the installed `roprec robots` with ROPREC_ROBOTS_DIR unset (cwd outside the repository):
#    it must list kuka-kr120-r2500-pro.
# 3. Builds examples/cpp (find_package(roprec), CMAKE_PREFIX_PATH=$TMP/prefix) in its own build
#    folder under $TMP and runs it on the sample cell; compiles it once more with pkg-config.
# 4. With --with-c 1 (or when libroprec_c is installed): builds examples/c against roprec::roprec_c
#    with CMake (Eigen hidden from find_package: the C ABI needs none) and with roprec_c.pc, and
#    runs both.
# 5. With --with-python 1 (or when the package is installed): imports roprec from
#    $TMP/prefix/lib/python3/dist-packages.
# 6. Relocation: copies the prefix, moves the original away, renames and removes robots in the
#    copy's share/roprec/robots, and checks that the copy's CLI sees exactly that change (so it
#    reads its own share/ folder, not the source tree's robots/); imports the copy's Python package.
#    With share/roprec/robots removed the copy's CLI fails (exit 2) with a hint, never falling back
#    to the source tree.
# 7. With --cpack: `cpack -G DEB`; checks the package's Depends (python3, python3-numpy with the
#    Python module) and its files, and builds the C++ consumer against the unpacked package.
# Any failure exits non-zero. ROPREC_KEEP_TMP=1 keeps $TMP.
set -euo pipefail

SRC="" BUILD="" CMAKE=cmake CPACK="" GEN="" WITH_C=0 WITH_PY=0
while (($#)); do
  case "$1" in
    --source) SRC="$2"; shift 2 ;;
    --build) BUILD="$2"; shift 2 ;;
    --cmake) CMAKE="$2"; shift 2 ;;
    --cpack) CPACK="$2"; shift 2 ;;
    --generator) GEN="$2"; shift 2 ;;
    --with-c) WITH_C="$2"; shift 2 ;;
    --with-python) WITH_PY="$2"; shift 2 ;;
    *) echo "packaging_test: unknown argument $1" >&2; exit 2 ;;
  esac
done
[[ -n "$SRC" && -n "$BUILD" ]] || { echo "usage: $0 --source SRC --build BUILD [...]" >&2; exit 2; }
SRC="$(cd "$SRC" && pwd)"
BUILD="$(cd "$BUILD" && pwd)"

TMP="$(mktemp -d "${TMPDIR:-/tmp}/roprec-packaging.XXXXXX")"
cleanup() { if [[ "${ROPREC_KEEP_TMP:-0}" == "1" ]]; then echo "kept $TMP"; else rm -rf "$TMP"; fi; }
trap cleanup EXIT
fail() { echo "packaging_test: FAIL: $*" >&2; exit 1; }
step() { echo "== $*"; }
# Runs a command with its output in a log; on failure prints the log's tail and fails.
logged() {
  local log="$1"; shift
  if ! "$@" >"$log" 2>&1; then tail -40 "$log" >&2; fail "$* (log: $log)"; fi
}
GEN_ARGS=()
if [[ -n "$GEN" ]]; then GEN_ARGS=(-G "$GEN"); fi
unset ROPREC_ROBOTS_DIR
# Nothing may come from the build or source tree through the environment.
unset LD_LIBRARY_PATH PYTHONPATH CMAKE_PREFIX_PATH PKG_CONFIG_PATH

CELL="$SRC/samples/cells/housing-kr120.xml"
HOLES="$SRC/samples/emotor-housing/holes.csv"
P="$TMP/prefix"

step "install into $P"
logged "$TMP/install.log" "$CMAKE" --install "$BUILD" --prefix "$P"
INSTALLED=(bin/roprec lib/libroprec.so include/roprec/compensator/robot/model.hpp
           include/roprec/plugin/api/job.hpp include/roprec/postproc/program.hpp
           share/roprec/robots/kuka-kr120-r2500-pro/robot.xml
           share/roprec/samples/cells/housing-kr120.xml share/roprec/samples/emotor-housing/holes.csv
           share/roprec/robodk/roprec/roprec_compensate_program.py share/roprec/robodk/roprec/AppConfig.ini
           share/doc/roprec/copyright
           lib/cmake/roprec/roprecConfig.cmake lib/cmake/roprec/roprecConfigVersion.cmake
           lib/cmake/roprec/roprecTargets.cmake lib/pkgconfig/roprec.pc)
for f in "${INSTALLED[@]}"; do
  [[ -e "$P/$f" ]] || fail "not installed: $f"
done
ls "$P"/lib/libroprec.so.0* >/dev/null 2>&1 || fail "not installed: lib/libroprec.so.0*"
# One include path: nothing but roprec/ under include/; internal headers stay out.
[[ "$(ls "$P/include")" == "roprec" ]] || fail "include/ holds more than roprec/: $(ls "$P/include" | tr '\n' ' ')"
[[ ! -e "$P/include/roprec/compensator/compensation/nlopt_problem.hpp" ]] || fail "internal header nlopt_problem.hpp installed"
[[ ! -e "$P/include/roprec/plugin/cli" ]] || fail "the CLI's headers are installed"
if grep -rn '#include "\(compensator\|postproc\|plugin\)/' "$P/include/roprec" >/dev/null; then
  fail "an installed header includes a project header without the roprec/ prefix"
fi

cd "$TMP"  # away from the repository

step "installed roprec robots (ROPREC_ROBOTS_DIR unset)"
"$P/bin/roprec" robots >"$TMP/robots.txt" || fail "installed roprec robots failed"
grep -q '^kuka-kr120-r2500-pro ' "$TMP/robots.txt" || { cat "$TMP/robots.txt" >&2; fail "kuka-kr120-r2500-pro not listed"; }

step "C++ consumer (examples/cpp, find_package(roprec))"
logged "$TMP/cpp-configure.log" "$CMAKE" -S "$SRC/examples/cpp" -B "$TMP/build-cpp" "${GEN_ARGS[@]}" \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$P"
logged "$TMP/cpp-build.log" "$CMAKE" --build "$TMP/build-cpp"
"$TMP/build-cpp/predict_hole" "$CELL" "$HOLES" T001 >"$TMP/predict_hole.txt" || \
  { cat "$TMP/predict_hole.txt" >&2; fail "predict_hole failed"; }
cat "$TMP/predict_hole.txt"
grep -q '^hole T001: ' "$TMP/predict_hole.txt" || fail "predict_hole printed no hole T001"
grep -q 'U_work' "$TMP/predict_hole.txt" || fail "predict_hole printed no U_work"

step "pkg-config (roprec.pc): the consumer, and every installed header on its own flags"
export PKG_CONFIG_PATH="$P/lib/pkgconfig"
PC="$(pkg-config --cflags --libs roprec)" || fail "pkg-config --cflags --libs roprec"
read -r -a PC_FLAGS <<<"$PC"
logged "$TMP/pc-build.log" "${CXX:-c++}" "$SRC/examples/cpp/predict_hole.cpp" -o "$TMP/predict_hole_pc" \
  "${PC_FLAGS[@]}" -Wl,-rpath,"$P/lib"
"$TMP/predict_hole_pc" "$CELL" "$HOLES" T001 >/dev/null || fail "predict_hole (pkg-config build) failed"
(cd "$P/include" && find roprec -name '*.hpp' | sort | sed 's/.*/#include <&>/') >"$TMP/all_headers.cpp"
read -r -a PC_CFLAGS <<<"$(pkg-config --cflags roprec)"
logged "$TMP/headers-build.log" "${CXX:-c++}" -fsyntax-only "${PC_CFLAGS[@]}" "$TMP/all_headers.cpp"
echo "$(wc -l <"$TMP/all_headers.cpp") installed headers compile with: ${PC_CFLAGS[*]}"
unset PKG_CONFIG_PATH

if [[ "$WITH_C" == "1" || -e "$P/lib/libroprec_c.so" ]]; then
  step "C consumer (examples/c, roprec::roprec_c)"
  [[ -e "$P/lib/libroprec_c.so" ]] || fail "libroprec_c.so not installed"
  [[ -e "$P/include/roprec/roprec.h" ]] || fail "include/roprec/roprec.h not installed"
  mkdir -p "$TMP/c-src"
  cp "$SRC/examples/c/filter_and_predict.c" "$TMP/c-src/"
  cat >"$TMP/c-src/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.20)
project(roprec_c_consumer LANGUAGES C)
find_package(roprec REQUIRED)
add_executable(filter_and_predict filter_and_predict.c)
target_link_libraries(filter_and_predict PRIVATE roprec::roprec_c m)
CMAKE
  # A machine without Eigen: find_package(Eigen3) finds nothing, the C consumer still builds.
  logged "$TMP/c-configure.log" "$CMAKE" -S "$TMP/c-src" -B "$TMP/build-c" "${GEN_ARGS[@]}" \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$P" -DCMAKE_DISABLE_FIND_PACKAGE_Eigen3=ON
  logged "$TMP/c-build.log" "$CMAKE" --build "$TMP/build-c"
  logged "$TMP/c-run.log" "$TMP/build-c/filter_and_predict" "$CELL" "$HOLES"
  head -5 "$TMP/c-run.log"
  step "C consumer (pkg-config roprec_c.pc)"
  export PKG_CONFIG_PATH="$P/lib/pkgconfig"
  PCC="$(pkg-config --cflags --libs roprec_c)" || fail "pkg-config --cflags --libs roprec_c"
  unset PKG_CONFIG_PATH
  [[ "$PCC" != *eigen* ]] || fail "roprec_c.pc pulls in Eigen: $PCC"
  read -r -a PCC_FLAGS <<<"$PCC"
  logged "$TMP/c-pc-build.log" "${CC:-cc}" -std=c99 -Wall -Werror "$SRC/examples/c/filter_and_predict.c" \
    -o "$TMP/filter_and_predict_pc" "${PCC_FLAGS[@]}" -lm -Wl,-rpath,"$P/lib"
  logged "$TMP/c-pc-run.log" "$TMP/filter_and_predict_pc" "$CELL" "$HOLES"
fi

PYDIR="$P/lib/python3/dist-packages"
if [[ "$WITH_PY" == "1" || -e "$PYDIR/roprec" ]]; then
  step "Python package ($PYDIR)"
  [[ -e "$PYDIR/roprec" ]] || fail "Python package not installed in $PYDIR/roprec"
  PYTHONPATH="$PYDIR" python3 -c "import roprec; print('roprec (python)', roprec.__version__)" || \
    fail "import roprec"
fi

step "relocated copy of the prefix"
Q="$TMP/relocated/usr"
mkdir -p "$TMP/relocated"
cp -a "$P" "$Q"
mv "$P" "$TMP/prefix.moved"   # nothing can still reach the first prefix
R="$Q/share/roprec/robots"
mv "$R/kuka-kr120-r2500-pro" "$R/kuka-relocated"
rm -rf "$R/abb-irb6640-185-280"
"$Q/bin/roprec" robots >"$TMP/robots-copy.txt" || fail "relocated roprec robots failed"
grep -q '^fanuc-r2000ic-165f ' "$TMP/robots-copy.txt" || fail "relocated copy does not list fanuc-r2000ic-165f"
if grep -q '^abb-irb6640-185-280 ' "$TMP/robots-copy.txt"; then
  fail "relocated copy still lists the removed abb-irb6640-185-280 (robots not read from its share/)"
fi
JOINTS="0 -90 90 0 0 0"
"$Q/bin/roprec" fk --robot kuka-relocated --joints "$JOINTS" >/dev/null || \
  fail "relocated copy cannot load its renamed robot kuka-relocated"
if "$Q/bin/roprec" fk --robot kuka-kr120-r2500-pro --joints "$JOINTS" >/dev/null 2>&1; then
  fail "relocated copy still loads kuka-kr120-r2500-pro (robots not read from its share/)"
fi
if [[ -e "$Q/lib/python3/dist-packages/roprec" ]]; then
  PYTHONPATH="$Q/lib/python3/dist-packages" python3 -c "import roprec" || fail "import roprec from the relocated copy"
fi
step "relocated copy without share/roprec/robots: an error with a hint, never the source tree"
rm -rf "$R"
set +e
"$Q/bin/roprec" robots >"$TMP/robots-none.txt" 2>&1
code=$?
set -e
[[ $code -eq 2 ]] || { cat "$TMP/robots-none.txt" >&2; fail "roprec robots without share/roprec/robots exited $code, not 2"; }
grep -q "no bundled robots: .*ROPREC_ROBOTS_DIR" "$TMP/robots-none.txt" || { cat "$TMP/robots-none.txt" >&2; fail "no hint"; }
if grep -q "$SRC" "$TMP/robots-none.txt"; then fail "the installed roprec looked into the source tree $SRC"; fi

if [[ -n "$CPACK" ]]; then
  step ".deb (cpack -G DEB)"
  mkdir -p "$TMP/deb"
  logged "$TMP/cpack.log" "$CPACK" -G DEB -B "$TMP/deb" --config "$BUILD/CPackConfig.cmake"
  DEB="$(ls "$TMP"/deb/*.deb | head -1)"
  [[ -f "$DEB" ]] || fail "cpack wrote no .deb"
  DEPENDS="$(dpkg-deb -f "$DEB" Depends)"
  echo "Depends: $DEPENDS"
  WANT=(libeigen3-dev)
  if [[ "$WITH_PY" == "1" ]]; then WANT+=(python3 python3-numpy); fi
  for d in "${WANT[@]}"; do
    grep -qE "(^|, )$d( |,|$)" <<<"$DEPENDS" || fail ".deb does not depend on $d (Depends: $DEPENDS)"
  done
  dpkg-deb -c "$DEB" | awk '{print $6}' | sed 's,^\./,,' >"$TMP/deb-files.txt"
  for f in "${INSTALLED[@]}" include/roprec/roprec.h lib/pkgconfig/roprec_c.pc; do
    grep -qx "usr/$f" "$TMP/deb-files.txt" || fail ".deb lacks usr/$f"
  done
  if grep -E '^usr/include/[^/]+/?$' "$TMP/deb-files.txt" | grep -vqx 'usr/include/roprec/'; then
    fail ".deb installs headers outside usr/include/roprec/"
  fi
  echo "$(wc -l <"$TMP/deb-files.txt") entries in $(basename "$DEB")"
  step "C++ consumer against the unpacked .deb"
  dpkg-deb -x "$DEB" "$TMP/deb-root"
  logged "$TMP/deb-cpp-configure.log" "$CMAKE" -S "$SRC/examples/cpp" -B "$TMP/build-deb-cpp" "${GEN_ARGS[@]}" \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$TMP/deb-root/usr"
  logged "$TMP/deb-cpp-build.log" "$CMAKE" --build "$TMP/build-deb-cpp"
  grep -q "$TMP/deb-root/usr" "$TMP/build-deb-cpp/CMakeCache.txt" || fail "the .deb consumer did not use the unpacked package"
  "$TMP/build-deb-cpp/predict_hole" "$CELL" "$HOLES" T001 \
    >/dev/null || fail "predict_hole built against the .deb failed"
fi

echo "packaging_test: OK"
