#pragma once
// Patterson & Reece's vane case (libspread/physics/dem/verify_vane.cpp) with the DEM's steps per contact N_c
// as a parameter: dem::run_vane() uses the engine's default N_c, and the study needs to vary it.
// Same set-up and same closed-form reference (dem::vane_reference); only N_c differs.
#include "libspread/physics/dem/verify.hpp"

namespace spread::accuracy::detail {

struct VaneExit {
  double speed_m_s = 0.0, speed_ref_m_s = 0.0;  // |v| in the horizontal plane at r = R, simulated / closed form
  double rel_error = 0.0;                        // (speed − ref) / ref
  double dt_s = 0.0;                             // the DEM step used
  long steps = 0;
};
VaneExit run_vane_at(const dem::VaneCase& c, double contact_steps);

}  // namespace spread::accuracy::detail
