# spread_optimize_for_build_time(<target>): the target compiles at -O1 instead of -O2 in the optimised
# configurations (RelWithDebInfo, Release; a Debug or sanitizer build keeps its own level). For the programs'
# glue only -- reading arguments, scenes and files, printing results -- whose run time is a few milliseconds
# beside the libraries' work and is measured by no benchmark: their code generation at -O2 is most of their
# compile time (`-ftime-report` on the spread CLI's larger unity file: 64 % "opt and generate"), the largest
# part of the main job's build outside the DEM. Measured on the CLI's two unity files (CPU, one compile each,
# alternated, -g1, the shared 2-core AMD EPYC under load): -O2 20.3 s and 32.7 s, -O1 15.9 s and 22.3 s.
# Results are the same bits: no -ffast-math at either level and -ffp-contract=off (CMakeLists.txt), so
# neither level may reorder or fuse floating-point operations.
#
# Used on the `spread` CLI, the lookup_builder program (its main; the sweep is spread_lookup's, at -O2) and
# the scene reader. Not on the libraries whose run time is measured (physics, predict, metrics, tables,
# field, capi): their objects stay as the benchmarks measure them.
function(spread_optimize_for_build_time target)
  target_compile_options(${target} PRIVATE $<$<AND:$<COMPILE_LANGUAGE:CXX>,$<CONFIG:RelWithDebInfo,Release>>:-O1>)
endfunction()
