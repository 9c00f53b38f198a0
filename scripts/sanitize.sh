#!/usr/bin/env bash
# The sanitizer job: the same package set-up as test.sh (scripts/setup.sh), but its own build
# folder build-asan/, built RelWithDebInfo with AddressSanitizer (+ LeakSanitizer) and
# UndefinedBehaviorSanitizer, then the whole ctest suite with every finding fatal.
# ROPREC_CMAKE_ARGS (word-split) and ROPREC_CMAKE_ARGV (one argument per line) pass through to
# the first configure of build-asan/.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="$ROOT/build-asan"

SAN="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
# Under ASan, Eigen switches to its own aligned allocator (a header before each block), while the
# uninstrumented liborocos-kdl the tests link exports plain-malloc instantiations of the same Eigen
# templates; the dynamic linker mixes the two and ASan reports the mismatched free. glibc's and
# ASan's malloc align to 16 bytes, so Eigen's plain-malloc path is correct and matches KDL.
EIGEN_SAN="-DEIGEN_MALLOC_ALREADY_ALIGNED=1"
ARGS=(
  -DCMAKE_BUILD_TYPE=RelWithDebInfo
  # -O1 with line tables only: what the sanitizers need for useful reports, and about half the
  # compile time of -O2 -g on this Eigen-heavy code (CI has 2 cores and a 30-minute goal).
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG"
  "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG"
  -DROPREC_BUILD_BENCH=OFF
  # The Python module cannot be loaded under ASan by the (uninstrumented) system interpreter
  # without preloading libasan; it is built and tested by scripts/test.sh.
  -DROPREC_BUILD_PYTHON=OFF
  "-DCMAKE_CXX_FLAGS=$SAN $EIGEN_SAN"
  "-DCMAKE_C_FLAGS=$SAN"
  "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined"
  "-DCMAKE_SHARED_LINKER_FLAGS=-fsanitize=address,undefined"
)
if command -v ccache >/dev/null 2>&1; then
  ARGS+=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
if [[ -n "${ROPREC_CMAKE_ARGV:-}" ]]; then mapfile -t -O "${#ARGS[@]}" ARGS <<<"$ROPREC_CMAKE_ARGV"; fi
# setup.sh configures a missing build folder only; an existing one must already be a sanitizer build.
if [[ -f "$BUILD/CMakeCache.txt" ]] && ! grep -q '^CMAKE_CXX_FLAGS:.*-fsanitize=address' "$BUILD/CMakeCache.txt"; then
  echo "sanitize: $BUILD is not configured with the sanitizers; remove it and run again" >&2
  exit 1
fi

# a compiler warning fails the job, as in scripts/test.sh (CMakeLists.txt turns off the one that
# only the sanitizers make GCC report falsely)
ROPREC_WARNINGS_FAIL=1 ROPREC_BUILD_DIR="$BUILD" ROPREC_CMAKE_ARGV="$(printf '%s\n' "${ARGS[@]}")" \
  "$ROOT/scripts/setup.sh"
if ! grep -q '^CMAKE_CXX_FLAGS:.*-fsanitize=address' "$BUILD/CMakeCache.txt"; then
  echo "sanitize: setup.sh did not configure $BUILD with the sanitizer flags (ROPREC_CMAKE_ARGV)" >&2
  exit 1
fi

cd "$BUILD"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# Not run here (scripts/test.sh runs them), because they start programs that are not instrumented
# with the ASan-built libroprec, which the ASan runtime refuses (it must be loaded first):
# * label `packaging`: installs the build and runs consumer programs built without the sanitizers;
# * tests named *python* / *Python* and robodk_app: they load the roprec module into the system Python
#   (the module is not even built here, see ROPREC_BUILD_PYTHON above).
ctest --output-on-failure --parallel "$(nproc)" --timeout 900 -LE '^(packaging|perf)$' -E '[Pp]ython|robodk_app'
