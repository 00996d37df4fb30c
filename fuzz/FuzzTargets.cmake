# The fuzz harnesses and what each links, shared by fuzz/CMakeLists.txt (libFuzzer binaries, clang) and
# tests/stability/CMakeLists.txt (replay binaries in the test suite, any compiler).
# A harness whose library is not part of this build (e.g. no LCM) is left out.
#
# spread_fuzz_harnesses(<out-list>): names, e.g. scene_parser → source fuzz/fuzz_scene_parser.cpp,
# libraries in SPREAD_FUZZ_LIBS_<name>.
set(SPREAD_FUZZ_DIR ${CMAKE_CURRENT_LIST_DIR})

macro(spread_fuzz_harnesses out)
  set(${out})
  set(SPREAD_FUZZ_LIBS_scene_parser spread::scene)
  set(SPREAD_FUZZ_LIBS_table_loader spread::tables)
  set(SPREAD_FUZZ_LIBS_can_frames spread::firmware_can)
  set(SPREAD_FUZZ_LIBS_candump spread::isobus_can)
  set(SPREAD_FUZZ_LIBS_lcm_handlers spread::firmware_lcm)
  set(SPREAD_FUZZ_LIBS_capi_open spreadc)
  set(SPREAD_FUZZ_LIBS_capi_predict spreadc spread::lookup spread::scene)
  set(SPREAD_FUZZ_LIBS_capi_trajectory spreadc)
  set(SPREAD_FUZZ_LIBS_stl_reader spread::dem)
  set(SPREAD_FUZZ_LIBS_transport_protocol spread::isobus)
  set(SPREAD_FUZZ_LIBS_ddop spread::isobus)
  set(SPREAD_FUZZ_LIBS_tc_server spread::firmware_can)
  foreach(_h scene_parser table_loader can_frames candump lcm_handlers capi_open capi_predict capi_trajectory stl_reader
             transport_protocol ddop tc_server)
    set(_available TRUE)
    foreach(_lib ${SPREAD_FUZZ_LIBS_${_h}})
      if(NOT TARGET ${_lib})
        set(_available FALSE)
      endif()
    endforeach()
    if(_available)
      list(APPEND ${out} ${_h})
    endif()
  endforeach()
endmacro()

# Compile settings every harness needs, whichever driver (libFuzzer or replay_main.cpp) it is linked with.
function(spread_fuzz_configure target harness)
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR})
  target_link_libraries(${target} PRIVATE ${SPREAD_FUZZ_LIBS_${harness}} spread_warnings)
  target_compile_definitions(${target} PRIVATE SPREAD_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
endfunction()

# spread_fuzz_object(<harness>): the harness source compiled once, as the object library fuzz_obj_<harness>,
# for both drivers: the libFuzzer binary (fuzz/CMakeLists.txt) and the replay binary of the test suite
# (tests/stability). In the one sanitizer build (tools/ci/sanitizer_config.sh) every object already carries
# libFuzzer's coverage instrumentation, so the two drivers can share it. Defined on first use.
function(spread_fuzz_object harness)
  if(NOT TARGET fuzz_obj_${harness})
    add_library(fuzz_obj_${harness} OBJECT ${SPREAD_FUZZ_DIR}/fuzz_${harness}.cpp)
    spread_fuzz_configure(fuzz_obj_${harness} ${harness})
  endif()
endfunction()

# The replay driver (fuzz/replay_main.cpp: each input file once, instead of libFuzzer), compiled once for
# every replay binary.
function(spread_fuzz_replay_main)
  if(NOT TARGET spread_fuzz_replay_main)
    add_library(spread_fuzz_replay_main OBJECT ${SPREAD_FUZZ_DIR}/replay_main.cpp)
    target_link_libraries(spread_fuzz_replay_main PRIVATE spread_warnings)
  endif()
endfunction()
