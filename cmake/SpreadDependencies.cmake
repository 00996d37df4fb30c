# All dependencies come from Debian 12 packages; tools/setup.sh installs them.
find_package(Threads REQUIRED)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(SQLite3 REQUIRED)
# The C API (capi/) needs only the three above; SPREAD_CAPI_ONLY stops here.
if(SPREAD_CAPI_ONLY)
  return()
endif()
find_package(tomlplusplus REQUIRED)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(PkgConfig REQUIRED)
# PROJ (libproj-dev): the field module projects boundaries in longitude/latitude to metres.
pkg_check_modules(PROJ REQUIRED IMPORTED_TARGET proj)
if(SPREAD_WITH_PLOTS)
  pkg_check_modules(CAIRO REQUIRED IMPORTED_TARGET cairo)
endif()
if(SPREAD_BUILD_TESTS)
  find_package(GTest REQUIRED)
  include(GoogleTest)
endif()
if(SPREAD_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()
if(SPREAD_WITH_MPI)
  find_package(MPI COMPONENTS CXX)
endif()
# LCM 1.3.1 in Debian ships no CMake package; lcm-gen runs at build time (docs/design.md §6). Required by
# default: without it firmware_sim, spread-tractor and the firmware LCM tests would silently vanish.
if(SPREAD_WITH_LCM)
  find_program(LCM_GEN lcm-gen)
  find_library(LCM_LIBRARY lcm)
  find_path(LCM_INCLUDE_DIR lcm/lcm.h)
  if(NOT LCM_GEN OR NOT LCM_LIBRARY OR NOT LCM_INCLUDE_DIR)
    message(FATAL_ERROR "LCM not found (lcm-gen: ${LCM_GEN}, liblcm: ${LCM_LIBRARY}, lcm/lcm.h: ${LCM_INCLUDE_DIR}). "
                        "Install the Debian packages liblcm-dev liblcm-bin (tools/setup.sh does), or configure "
                        "with -DSPREAD_WITH_LCM=OFF to build without firmware_sim and spread-tractor.")
  endif()
endif()
