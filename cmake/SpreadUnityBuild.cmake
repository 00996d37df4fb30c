# spread_compile_together(<target> [BATCHES n]): the target's sources compile as unity files (CMake's
# UNITY_BUILD), `n` of them (default 1). The headers its files share (Eigen, nlohmann/json, CLI11) are then
# parsed, and their inline code generated, once per unity file instead of once per source file. Measured
# at -O2 -g1 on the eight targets below: 269 s of compile CPU file by file, 98 s compiled together (spread
# 150 s to 37 s, calibration 37 s to 22 s). Same flags; the files are only concatenated. For that, no two
# files of a target may declare the same name in an anonymous namespace of the same enclosing namespace.
#
# Used on the libraries and programs the main job builds (tools/run-default.sh: accuracy, calibration,
# predict, metrics, scene, lookup, lookup_builder, spread), not on the physics libraries (dem, flight,
# drum, launch): the DEM's run time is measured with their objects as they are. Not on tables: GCC then
# warns about its writer's lock (-Wsubobject-linkage) for a gain of 3 s. The cost: editing one file
# recompiles its whole unity file.
function(spread_compile_together target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "BATCHES" "")
  if(NOT arg_BATCHES)
    set(arg_BATCHES 1)
  endif()
  get_target_property(sources ${target} SOURCES)
  list(LENGTH sources count)
  math(EXPR batch_size "(${count} + ${arg_BATCHES} - 1) / ${arg_BATCHES}")
  set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${batch_size})
endfunction()
