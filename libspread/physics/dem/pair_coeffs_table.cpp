// The engine's table of Law::coeffs per material pair (contact_laws.hpp, ComposedLaw::Coeffs): R*, M* and
// the sub-models' spring and damping prefactors computed once when every particle of a material has one
// radius and mass, so the per-step kernels skip them.
#include <cstdint>
#include <utility>
#include <vector>

#include "libspread/physics/dem/contact_laws.hpp"
#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/engine_detail.hpp"

namespace spread::dem {

template <class Law>
void DemEngine::update_pair_coeffs() {
  const std::size_t mc = materials_.size();
  // One radius and mass per material? (Removing particles cannot break it, so only additions refresh.)
  std::vector<double> r(mc, 0.0), m(mc, 0.0);
  std::vector<std::uint8_t> seen(mc, 0), uniform(mc, 1);
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (!p_.active[i]) continue;
    const std::size_t a = p_.material[i];
    if (!seen[a]) { seen[a] = 1; r[a] = p_.radius_m[i]; m[a] = p_.mass_kg[i]; }
    else if (p_.radius_m[i] != r[a] || p_.mass_kg[i] != m[a]) uniform[a] = 0;
  }
  using Coeffs = typename Law::Coeffs;
  std::vector<Coeffs> pair_coeffs(mc * mc, Coeffs{}), wall_coeffs(mc * mc, Coeffs{});
  for (std::size_t a = 0; a < mc; ++a) {
    if (!seen[a] || !uniform[a]) continue;
    for (std::size_t b = 0; b < mc; ++b) {
      const PairParams& pp = pair_table_(static_cast<int>(a), static_cast<int>(b));
      // The same expressions as the per-contact fallback in the pass, so the results are bit-identical.
      wall_coeffs[a * mc + b] = Law::coeffs(pp, r[a], m[a]);
      wall_coeffs[a * mc + b].uniform = true;
      if (!seen[b] || !uniform[b]) continue;
      pair_coeffs[a * mc + b] = Law::coeffs(pp, r[a] * r[b] / (r[a] + r[b]), m[a] * m[b] / (m[a] + m[b]));
      pair_coeffs[a * mc + b].uniform = true;
    }
  }
  one_size_per_material_ = true;
  for (std::size_t a = 0; a < mc; ++a) one_size_per_material_ = one_size_per_material_ && (!seen[a] || uniform[a]);
  pair_coeffs_ = std::move(pair_coeffs);
  wall_coeffs_ = std::move(wall_coeffs);
  coeffs_dirty_ = false;
}

const ForcePassTable kCoeffUpdates = ForcePassTables::coeffs(std::make_index_sequence<kForceVariantCount>{});

}  // namespace spread::dem
