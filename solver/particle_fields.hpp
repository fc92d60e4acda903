#pragma once

#include "engine/scene.hpp"

#include <vector>

namespace mpile::passes {

/// Which node array a particle scatters to and gathers from in a scene with contact: that of its
/// body's field (physics.md section 5). Built once per pass; a scene without contact never makes
/// one (its passes use the single field directly).
class ParticleFields {
public:
  explicit ParticleFields(Grid& grid, const Scene& scene) : field_of_body_(scene.field_of_body) {
    for (int f = 0; f < grid.field_count(); ++f) {
      nodes_.push_back(grid.field_nodes(f).data());
      gradient_.push_back(
          f == 0 || grid.structure_fields[static_cast<std::size_t>(f - 1)].mass_gradient.empty()
              ? nullptr
              : grid.structure_fields[static_cast<std::size_t>(f - 1)].mass_gradient.data());
    }
  }

  GridNode* nodes(std::uint16_t body) const { return nodes_[field_of_body_[body]]; }
  bool is_soil(std::uint16_t body) const { return field_of_body_[body] == 0; }
  /// The mass-gradient array of the body's field, or nullptr when the field keeps none.
  std::array<double, 2>* mass_gradient(std::uint16_t body) const {
    return gradient_[field_of_body_[body]];
  }

private:
  const std::vector<std::uint8_t>& field_of_body_;
  std::vector<GridNode*> nodes_;
  std::vector<std::array<double, 2>*> gradient_;
};

} // namespace mpile::passes
