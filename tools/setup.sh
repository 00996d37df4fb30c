#!/usr/bin/env bash
# Installs the Debian 12 packages libspread needs (only those missing), then configures and builds.
# Usage: tools/setup.sh [--main-job] [build-dir [target...]]   (default: build, every target). Idempotent;
# safe to run on every invocation. With targets, only those (and what they need) are built.
#
# --main-job (tools/run-default.sh): only what lookup_builder and spread need -- the compilers, CMake, Ninja
# and the libraries they link (Eigen, SQLite, toml++, CLI11, nlohmann/json, cairo, PROJ) -- and a build directory
# made here is configured without the tests, the benchmarks, LCM and MPI (none of which the two programs
# use: lookup_builder --jobs runs on threads). An existing build directory keeps its configuration. Without
# it (tools/run-tests.sh) everything the tests need too (GoogleTest, Google Benchmark, LCM, Open MPI, clang
# and its sanitizer runtime, abigail-tools, poppler-utils, python3-scipy, ...), and a build directory the
# main job made is configured with the tests, the benchmarks, LCM and MPI turned back on.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
profile=full
if [ "${1:-}" = --main-job ]; then profile=main-job; shift; fi
build=${1:-$root/build}
shift $(( $# > 0 ? 1 : 0 ))
targets=()
for t in "$@"; do targets+=(--target "$t"); done

main_job_packages=(build-essential cmake pkg-config ninja-build
  libeigen3-dev libsqlite3-dev libtomlplusplus-dev libcli11-dev nlohmann-json3-dev libcairo2-dev
  libproj-dev)  # PROJ: field boundaries in longitude/latitude projected to metres (libspread/analysis/field)
test_packages=(sqlite3 liblcm-dev liblcm-bin libgtest-dev libgmock-dev libbenchmark-dev libopenmpi-dev openmpi-bin
  python3 python3-scipy iproute2 util-linux clang libclang-rt-14-dev abigail-tools
  zlib1g-dev  # libz.a, which static SQLite needs: the package test links a C program with cc -static
  poppler-utils  # pdftoppm and pdftotext: the PDF report tests (tests/tools/test_report_cli.cpp)
  strace)  # counts the opens of a table file per command (tests/tools/table_opened_once.sh)
setup_started=$SECONDS
packages=("${main_job_packages[@]}")
[ "$profile" = main-job ] || packages+=("${test_packages[@]}")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=(); [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}" ||
    { "${sudo_cmd[@]}" apt-get update && "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"; }
fi

packages_s=$((SECONDS - setup_started))

# -O2 with line tables (-g1): backtraces and perf name functions and lines, and the build takes about a
# third less time than with full debug information (-g). For gdb's variables, configure a build of your own
# with -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g -DNDEBUG". The C API's shipped objects always carry full
# debug information: the ABI check reads their types (capi/CMakeLists.txt).
. "$root/tools/ci/ccache.sh"
# The options the profile sets: a new directory for the main job leaves out what only the tests use (and
# says so in a marker file); the full set-up turns them back on where the main job made the directory, and
# leaves any other directory's choices as they are.
marker=$build/main-job-configuration
options=()
if [ "$profile" = main-job ] && [ ! -f "$build/CMakeCache.txt" ]; then
  options=(-DSPREAD_BUILD_TESTS=OFF -DSPREAD_BUILD_BENCH=OFF -DSPREAD_WITH_LCM=OFF -DSPREAD_WITH_MPI=OFF)
elif [ "$profile" = full ] && [ -f "$marker" ]; then
  options=(-DSPREAD_BUILD_TESTS=ON -DSPREAD_BUILD_BENCH=ON -DSPREAD_WITH_LCM=ON -DSPREAD_WITH_MPI=ON)
fi
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "${spread_launcher[@]}" "${options[@]}" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" >/dev/null
if [ "$profile" = main-job ] && [ ${#options[@]} -gt 0 ]; then
  echo "configured by tools/setup.sh --main-job: no tests, benchmarks, LCM or MPI" >"$marker"
elif [ "$profile" = full ]; then
  rm -f "$marker"
fi
configure_s=$((SECONDS - setup_started - packages_s))
cmake --build "$build" -j2 "${targets[@]}"
echo "setup: wall times: packages ${packages_s} s (${#missing[@]} of ${#packages[@]} to install), configure ${configure_s} s," \
  "build $((SECONDS - setup_started - packages_s - configure_s)) s" >&2
