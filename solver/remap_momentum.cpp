// MUSL remap. Reads particle mass and the updated particle velocity; writes node momentum by a
// colored scatter, then node velocity = momentum / mass (the node mass of this step is unchanged).
// Constraints are applied again by the caller.
#include "engine/shape_functions.hpp"
#include "solver/passes.hpp"

namespace mpile::passes {

template <GeometryMode mode>
void remap_momentum(Scene& scene, const ParticleBins& bins, const StepParameters& step) {
  constexpr int dofs = has_theta(mode) ? 3 : 2;
  Grid& grid = scene.grid;
  const Particles& p = scene.particles;
  parallel_for(grid.nodes.size(), [&](std::size_t i) {
    for (int d = 0; d < dofs; ++d) {
      grid.nodes[i].momentum[d] = 0.0;
    }
  });
  bins.for_each_block_colored([&](int, std::span<const std::int32_t> particles) {
    for (const std::int32_t q : particles) {
      const auto i = static_cast<std::size_t>(q);
      const CellWeights w = bilinear_weights(grid, p.cell_r[i], p.cell_y[i], p.r[i], p.y[i]);
      const double m = p.mass[i];
      double momentum[3] = {m * p.v_r[i], m * p.v_y[i], 0.0};
      if constexpr (has_theta(mode)) {
        momentum[2] = m * p.v_theta[i];
      }
      for (int k = 0; k < 4; ++k) {
        GridNode& node = grid.nodes[static_cast<std::size_t>(w.node[k])];
        for (int d = 0; d < dofs; ++d) {
          node.momentum[d] += w.N[k] * momentum[d];
        }
      }
    }
  });
  parallel_for(grid.nodes.size(), [&](std::size_t i) {
    GridNode& node = grid.nodes[i];
    const double inverse_mass = node.mass > step.mass_floor ? 1.0 / node.mass : 0.0;
    for (int d = 0; d < dofs; ++d) {
      node.momentum[d] *= inverse_mass;
    }
  });
}

template void remap_momentum<GeometryMode::axisymmetric>(Scene&, const ParticleBins&,
                                                         const StepParameters&);
template void remap_momentum<GeometryMode::plane_strain>(Scene&, const ParticleBins&,
                                                         const StepParameters&);

} // namespace mpile::passes
