# spread_precompile_eigen(<target>): the target's sources start from a precompiled header of Eigen's Core and
# Geometry modules (what libspread/core/vec3.hpp and the meshes include) and the standard headers every file
# of the physics libraries includes. Parsing them is about half of a small physics file's compile time
# (measured at -O2 -g1: an empty file including <Eigen/Geometry> takes 1.7 s of CPU, dem/particles.cpp 3.2 s);
# the header is parsed once per target instead of once per file. The objects are the same code: the header
# only saves the parse (the physics libraries' run time is measured with their objects as they are).
# Measured building the four (ninja spread_dem spread_flight spread_drum spread_launch, -j2, no ccache, on the
# shared 2-core AMD EPYC under load): 260 s user + 48 s sys without, 235 s user + 55 s sys with (-6 % CPU;
# most of their time is code generation, pair_pass.cpp alone 57 s).
#
# Used on the physics libraries the main job builds file by file (dem, drum, launch; the others compile as
# unity files, SpreadUnityBuild.cmake). Not on flight: its objects are the C API's too, and the pre-linked
# libspreadc.a takes them as $<TARGET_OBJECTS>, which would carry the precompiled header (not an object). With ccache (tools/ci/ccache.sh) the files that use the
# header are cached only with CCACHE_SLOPPINESS pch_defines,time_macros, which tools/ci/ccache.sh sets.
function(spread_precompile_eigen target)
  target_precompile_headers(${target} PRIVATE <Eigen/Core> <Eigen/Geometry> <algorithm> <cmath> <cstdint> <string>
                            <vector>)
endfunction()
