// Internal test seam, not part of the public header spread/spread.h: the C API's catch-all
// (SPREAD_ERROR_INTERNAL, "a bug: please report") has no input that reaches it by design, so a test arms
// this seam to make the next entry point throw a non-allocation exception inside its try block and checks
// that the code comes out as SPREAD_ERROR_INTERNAL instead of an exception crossing into C.
// Only the in-tree library `spreadc` defines SPREAD_CAPI_FAULT_SEAM; the installed libspreadc.so and
// libspreadc.a are built without it, so they carry no way to inject a fault.
#pragma once

namespace spread::capi::detail {

#ifdef SPREAD_CAPI_FAULT_SEAM
// Makes the next fault_point() throw std::logic_error (once; the seam disarms itself).
void arm_internal_fault_for_test();

// Called first inside the try block of spread_open, spread_predict and spread_trajectory. One relaxed
// atomic load when not armed; never allocates unless armed.
void fault_point();
#else
inline void fault_point() {}
#endif

}  // namespace spread::capi::detail
