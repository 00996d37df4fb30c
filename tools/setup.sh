#!/usr/bin/env bash
# Installs the Debian 12 packages libspread needs (only those missing), then configures and builds.
# Usage: tools/setup.sh [build-dir [target...]]   (default: build, every target). Idempotent; safe to run
# on every invocation. With targets, only those (and what they need) are built.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
shift $(( $# > 0 ? 1 : 0 ))
targets=()
for t in "$@"; do targets+=(--target "$t"); done

packages=(build-essential cmake pkg-config ninja-build
  libeigen3-dev libsqlite3-dev sqlite3 libtomlplusplus-dev libcli11-dev nlohmann-json3-dev libcairo2-dev
  liblcm-dev liblcm-bin libgtest-dev libgmock-dev libbenchmark-dev libopenmpi-dev openmpi-bin
  python3 python3-scipy iproute2 util-linux clang libclang-rt-14-dev abigail-tools
  libproj-dev  # PROJ: field boundaries in longitude/latitude projected to metres (libspread/analysis/field)
  zlib1g-dev  # libz.a, which static SQLite needs: the package test links a C program with cc -static
  poppler-utils  # pdftoppm and pdftotext: the PDF report tests (tests/tools/test_report_cli.cpp)
  strace)  # counts the opens of a table file per command (tests/tools/table_opened_once.sh)
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

# -O2 with line tables (-g1): backtraces and perf name functions and lines, and the build takes about a
# third less time than with full debug information (-g). For gdb's variables, configure a build of your own
# with -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g -DNDEBUG". The C API's shipped objects always carry full
# debug information: the ABI check reads their types (capi/CMakeLists.txt).
. "$root/tools/ci/ccache.sh"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "${spread_launcher[@]}" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" >/dev/null
cmake --build "$build" -j2 "${targets[@]}"
