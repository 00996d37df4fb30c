# spread_warnings: link it to every target of ours (not to third-party code).
add_library(spread_warnings INTERFACE)
target_compile_options(spread_warnings INTERFACE
  $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion>
  $<$<COMPILE_LANGUAGE:C>:-Wall -Wextra -Wpedantic>)
if(SPREAD_SANITIZE)
  # -fno-sanitize=vptr: LCM 1.3.1's header-only C++ wrapper (lcm/lcm-cpp-impl.hpp:108) casts its
  # subscription objects in a way the vptr check rejects; the check cannot be suppressed per file when
  # UBSan does not recover, and everything else of UBSan stays on.
  add_compile_options(-fsanitize=address,undefined -fno-sanitize=vptr -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
