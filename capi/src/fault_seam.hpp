// Internal test seam, not part of the public header spread/spread.h: the C API's catch-all
// (SPREAD_ERROR_INTERNAL, "a bug: please report") has no input that reaches it by design, so a test arms
// this seam to make the next entry point throw a non-allocation exception inside its try block and checks
// that the code comes out as SPREAD_ERROR_INTERNAL instead of an exception crossing into C.
#pragma once

namespace spread::capi::detail {

// Makes the next fault_point() throw std::logic_error (once; the seam disarms itself).
void arm_internal_fault_for_test();

// Called first inside the try block of spread_open, spread_predict and spread_trajectory. One relaxed
// atomic load when not armed; never allocates unless armed.
void fault_point();

}  // namespace spread::capi::detail
