#include "libspread/physics/dem/mesh_near_list.hpp"

namespace spread::dem {

void MeshNearLists::configure(std::size_t meshes, double skin_m) {
  meshes_ = meshes;
  skin_m_ = skin_m;
  records_.clear();
}

void MeshNearLists::resize(std::size_t particles) { records_.resize(particles * meshes_); }

void MeshNearLists::compact(const std::vector<std::uint8_t>& active) {
  if (meshes_ == 0) return;
  std::size_t w = 0;
  for (std::size_t r = 0; r < active.size() && r * meshes_ < records_.size(); ++r) {
    if (!active[r]) continue;
    if (w != r)
      for (std::size_t m = 0; m < meshes_; ++m) records_[w * meshes_ + m] = records_[r * meshes_ + m];
    ++w;
  }
  records_.resize(w * meshes_);
}

}  // namespace spread::dem
