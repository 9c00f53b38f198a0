#!/usr/bin/env bash
# Packaging test (ctest label "packaging"): installs a built tree into a temporary prefix and
# uses it the way a host would, away from the source tree.
#
#   packaging_test.sh --source SRC --build BUILD [--cmake CMAKE] [--generator GEN]
#                     [--with-c 0|1] [--with-python 0|1]
#
# 1. `cmake --install BUILD --prefix $TMP/prefix`; checks the installed layout.
# 2. Runs the installed `roprec robots` with ROPREC_ROBOTS_DIR unset (cwd outside the repository):
#    it must list kuka-kr120-r2500-pro.
# 3. Builds examples/cpp (find_package(roprec), CMAKE_PREFIX_PATH=$TMP/prefix) in its own build
#    folder under $TMP and runs it on the sample cell; compiles it once more with pkg-config.
# 4. With --with-c 1 (or when libroprec_c is installed): builds examples/c against roprec::roprec_c
#    and runs it.
# 5. With --with-python 1 (or when the package is installed): imports roprec from
#    $TMP/prefix/lib/python3/dist-packages.
# 6. Relocation: copies the prefix, moves the original away, renames and removes robots in the
#    copy's share/roprec/robots, and checks that the copy's CLI sees exactly that change (so it
#    reads its own share/ folder, not the source tree's robots/); imports the copy's Python package.
# Any failure exits non-zero. ROPREC_KEEP_TMP=1 keeps $TMP.
set -euo pipefail

SRC="" BUILD="" CMAKE=cmake GEN="" WITH_C=0 WITH_PY=0
while (($#)); do
  case "$1" in
    --source) SRC="$2"; shift 2 ;;
    --build) BUILD="$2"; shift 2 ;;
    --cmake) CMAKE="$2"; shift 2 ;;
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
for f in bin/roprec lib/libroprec.so include/roprec/compensator/robot/model.hpp \
         include/roprec/plugin/api/job.hpp include/roprec/postproc/program.hpp \
         share/roprec/robots/kuka-kr120-r2500-pro/robot.xml \
         lib/cmake/roprec/roprecConfig.cmake lib/cmake/roprec/roprecConfigVersion.cmake \
         lib/cmake/roprec/roprecTargets.cmake lib/pkgconfig/roprec.pc; do
  [[ -e "$P/$f" ]] || fail "not installed: $f"
done
ls "$P"/lib/libroprec.so.0* >/dev/null 2>&1 || fail "not installed: lib/libroprec.so.0*"

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

step "pkg-config (roprec.pc)"
export PKG_CONFIG_PATH="$P/lib/pkgconfig"
PC="$(pkg-config --cflags --libs roprec)" || fail "pkg-config --cflags --libs roprec"
read -r -a PC_FLAGS <<<"$PC"
logged "$TMP/pc-build.log" "${CXX:-c++}" -std=c++20 "$SRC/examples/cpp/predict_hole.cpp" -o "$TMP/predict_hole_pc" \
  "${PC_FLAGS[@]}" -Wl,-rpath,"$P/lib"
"$TMP/predict_hole_pc" "$CELL" "$HOLES" T001 >/dev/null || fail "predict_hole (pkg-config build) failed"
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
  logged "$TMP/c-configure.log" "$CMAKE" -S "$TMP/c-src" -B "$TMP/build-c" "${GEN_ARGS[@]}" \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$P"
  logged "$TMP/c-build.log" "$CMAKE" --build "$TMP/build-c"
  logged "$TMP/c-run.log" "$TMP/build-c/filter_and_predict" "$CELL" "$HOLES"
  head -5 "$TMP/c-run.log"
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

echo "packaging_test: OK"
