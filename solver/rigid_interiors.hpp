#pragma once

// Where the rigid bodies are: soil particles whose centre lies there carry no stress
// (SolverSettings::stress_free_inside_rigid, solver/stress_update.cpp).

#include "engine/scene.hpp"
#include "solver/solver_settings.hpp"

#include <array>
#include <optional>
#include <vector>

namespace mpile::passes {

/// The outlines of the rigid bodies that have one, with their bounding boxes, at the start of a
/// step. Contact acts at nodes, so soil whose nodes move partly with a rigid body and partly with
/// the soil (under a pile's tip) can be overtaken by the body's surface. Inside, its nodes are
/// pushed towards different faces, which stretches it (to 6 kg/m^3 against the sand's 1 656 in a
/// three-cell pile wall) while its stress falls to near zero, and its wave speed at that density
/// set the time step. Such a particle, once stretched below `stretched_share` of its material's
/// density, carries no stress while it is there, so it neither pushes on the body from inside nor
/// limits the step; its mass and momentum stay with the soil, and outside again it starts from
/// zero stress. Soil the surface has just overtaken is still dense and carries the tip's
/// pressure: taking that away as soon as the centre crossed (tried) lowered a jacked pile's tip
/// force by 40 %.
class RigidInteriors {
public:
  static constexpr double stretched_share = 0.5;

  explicit RigidInteriors(const Scene& scene) : field_of_body_(scene.field_of_body) {
    for (const ContactPair& pair : scene.contacts) {
      if (pair.rigid_body >= 0 && pair.outline) {
        interiors_.push_back({&*pair.outline, pair.outline->bounds()});
      }
    }
    for (const auto& material : scene.materials) {
      stretched_density_.push_back(stretched_share * material->density());
    }
  }

  bool empty() const { return interiors_.empty(); }

  /// Whether particle i is soil (field 0), stretched below `stretched_share` of its material's
  /// density, whose centre lies inside a rigid body's outline.
  bool holds_soil(const Particles& p, std::size_t i) const {
    const double r = p.r[i];
    const double y = p.y[i];
    for (const Interior& interior : interiors_) {
      const auto& box = interior.box;
      if (r > box[0] && r < box[1] && y > box[2] && y < box[3] &&
          (field_of_body_.empty() || field_of_body_[p.body[i]] == 0) &&
          p.mass[i] < stretched_density_[p.material[i]] * p.volume[i] &&
          interior.outline->contains(r, y)) {
        return true;
      }
    }
    return false;
  }

private:
  struct Interior {
    const StructureOutline* outline;
    std::array<double, 4> box; // r_min, r_max, y_min, y_max
  };
  const std::vector<std::uint8_t>& field_of_body_;
  std::vector<Interior> interiors_;
  std::vector<double> stretched_density_; // per material
};

/// The rigid bodies' interiors when the settings make soil there stress-free and the scene has a
/// rigid body with an outline; nothing otherwise.
inline std::optional<RigidInteriors> kept_rigid_interiors(const Scene& scene,
                                                          const SolverSettings& settings) {
  if (!settings.stress_free_inside_rigid || scene.contacts.empty()) {
    return std::nullopt;
  }
  std::optional<RigidInteriors> interiors(std::in_place, scene);
  if (interiors->empty()) {
    return std::nullopt;
  }
  return interiors;
}

} // namespace mpile::passes
