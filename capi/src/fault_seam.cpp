#include "capi/src/fault_seam.hpp"

#include <atomic>
#include <stdexcept>

namespace spread::capi::detail {

namespace {
std::atomic<bool> g_armed{false};
}  // namespace

void arm_internal_fault_for_test() { g_armed.store(true, std::memory_order_relaxed); }

void fault_point() {
  if (g_armed.load(std::memory_order_relaxed) && g_armed.exchange(false)) {
    throw std::logic_error("spread C API: fault injected by a test (SPREAD_ERROR_INTERNAL path)");
  }
}

}  // namespace spread::capi::detail
