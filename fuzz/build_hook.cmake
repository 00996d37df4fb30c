# Adds the fuzz harnesses to a build without editing the top-level CMakeLists.txt (which does not list
# fuzz/ yet):
#   cmake -S . -B build-fuzz -DCMAKE_PROJECT_INCLUDE=$PWD/fuzz/build_hook.cmake ...
# CMake includes this file at the end of the top-level project() call. fuzz/CMakeLists.txt is then
# included (add_subdirectory is not allowed there) at the end of the top-level CMakeLists.txt, when every
# library target exists. If the top level adds fuzz/ itself (SPREAD_BUILD_FUZZ), this does nothing.
set(SPREAD_FUZZ_HOOK_LIST ${CMAKE_CURRENT_LIST_DIR}/CMakeLists.txt)
function(spread_fuzz_add_late)
  if(NOT TARGET spread_fuzzers)
    include(${SPREAD_FUZZ_HOOK_LIST})
  endif()
endfunction()
cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL spread_fuzz_add_late)
