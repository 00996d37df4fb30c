#!/usr/bin/env bash
# Optional compiler cache for every build the scripts configure (tools/setup.sh, tools/ci/sanitizer_config.sh,
# tools/check-build-options.sh). When ccache is installed (Debian package ccache; not installed by
# tools/setup.sh) and SPREAD_CCACHE is not 0, the builds compile through it. CCACHE_BASEDIR is the source
# tree and CCACHE_NOHASHDIR is set, so two clones at different paths (a developer's and CI's on a machine
# that kept ~/.cache/ccache) share their entries. The stage budgets (tools/ci/stage-budgets.txt) are for an
# empty cache.
#
# Sourced, not run:   . tools/ci/ccache.sh; cmake ... "${spread_launcher[@]}"
spread_launcher=()
if [ "${SPREAD_CCACHE:-1}" != 0 ] && command -v ccache >/dev/null; then
  export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}
  export CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-1}
  # The physics libraries compile with a precompiled header (cmake/SpreadPrecompiledHeaders.cmake): ccache
  # caches their files only with these.
  export CCACHE_SLOPPINESS=${CCACHE_SLOPPINESS:-pch_defines,time_macros}
  spread_launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
