// MUSL remap. Reads particle mass and the updated particle velocity; writes node momentum by a
// colored scatter, then node velocity = momentum / mass (the node mass of this step is unchanged),
// and in axisymmetric mode angular momentum sum N m r v_theta, then angular velocity = it over the
// rotational inertia of this step. Constraints are applied again by the caller.
#include "engine/shape_functions.hpp"
#include "solver/particle_fields.hpp"
#include "solver/passes.hpp"

#include <optional>

namespace mpile::passes {

namespace {

template <int dofs>
void clear_momentum(std::vector<GridNode>& nodes, const NodeBox& box, int nodes_r) {
  parallel_for_box(box, nodes_r, [&](std::size_t i) {
    for (int d = 0; d < dofs; ++d) {
      nodes[i].momentum[d] = 0.0;
    }
  });
}

template <int dofs>
void momentum_to_velocity(std::vector<GridNode>& nodes, const NodeBox& box, int nodes_r,
                          double mass_floor) {
  parallel_for_box(box, nodes_r, [&](std::size_t i) {
    GridNode& node = nodes[i];
    const bool occupied = node.mass > mass_floor;
    const double inverse_mass = occupied ? 1.0 / node.mass : 0.0;
    // In place: the remapped momentum becomes the node's velocity (angular velocity for theta).
    node.velocity()[0] = node.momentum[0] * inverse_mass;
    node.velocity()[1] = node.momentum[1] * inverse_mass;
    if constexpr (dofs == 3) {
      node.velocity()[2] = node.momentum[2] * (occupied ? 1.0 / node.inertia : 0.0);
    }
  });
}

} // namespace

template <GeometryMode mode, bool contact, ShapeFunctions shape>
void remap_momentum(Scene& scene, const ParticleBins& bins, const StepParameters& step) {
  constexpr int dofs = has_theta(mode) ? 3 : 2;
  Grid& grid = scene.grid;
  const Particles& p = scene.particles;
  const NodeBox all{0, grid.nodes_r(), 0, grid.nodes_y()};
  // A structure field holds mass only in its reach (NodeField).
  auto box_of = [&](int f) {
    return f == 0 ? all : grid.structure_fields[static_cast<std::size_t>(f - 1)].reach;
  };
  for (int f = 0; f < (contact ? grid.field_count() : 1); ++f) {
    clear_momentum<dofs>(grid.field_nodes(f), box_of(f), grid.nodes_r());
  }
  [[maybe_unused]] const auto fields =
      contact ? std::optional<ParticleFields>(std::in_place, grid, scene) : std::nullopt;
  bins.for_each_block_colored([&](int block, std::span<const std::int32_t> particles) {
    // A block of soil particles only scatters to field 0.
    [[maybe_unused]] const bool mixed = contact && bins.block_tag(block) != 0;
    for (const std::int32_t q : particles) {
      const auto i = static_cast<std::size_t>(q);
      GridNode* nodes = grid.nodes.data();
      if constexpr (contact) {
        if (mixed) {
          nodes = fields->nodes(p.body[i]);
        }
      }
      const auto w = particle_weights<shape>(grid, p, i);
      const double m = p.mass[i];
      double momentum[3] = {m * p.v_r[i], m * p.v_y[i], 0.0};
      if constexpr (has_theta(mode)) {
        momentum[2] = m * p.r[i] * p.v_theta[i]; // angular momentum
      }
      for (int k = 0; k < w.size; ++k) {
        GridNode& node = nodes[static_cast<std::size_t>(w.node[k])];
        for (int d = 0; d < dofs; ++d) {
          node.momentum[d] += w.N[k] * momentum[d];
        }
      }
    }
  });
  for (int f = 0; f < (contact ? grid.field_count() : 1); ++f) {
    momentum_to_velocity<dofs>(grid.field_nodes(f), box_of(f), grid.nodes_r(), step.mass_floor);
  }
}

template void remap_momentum<GeometryMode::axisymmetric, false, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const StepParameters&);
template void
remap_momentum<GeometryMode::axisymmetric, false, ShapeFunctions::gimp>(Scene&, const ParticleBins&,
                                                                        const StepParameters&);
template void remap_momentum<GeometryMode::axisymmetric, true, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const StepParameters&);
template void
remap_momentum<GeometryMode::axisymmetric, true, ShapeFunctions::gimp>(Scene&, const ParticleBins&,
                                                                       const StepParameters&);
template void remap_momentum<GeometryMode::plane_strain, false, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const StepParameters&);
template void
remap_momentum<GeometryMode::plane_strain, false, ShapeFunctions::gimp>(Scene&, const ParticleBins&,
                                                                        const StepParameters&);
template void remap_momentum<GeometryMode::plane_strain, true, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const StepParameters&);
template void
remap_momentum<GeometryMode::plane_strain, true, ShapeFunctions::gimp>(Scene&, const ParticleBins&,
                                                                       const StepParameters&);

} // namespace mpile::passes
