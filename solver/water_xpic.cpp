// The pore water's own XPIC(m) (solver/xpic.hpp): the series of solver/xpic.cpp on the water's
// nodes, with the water's weights and the DOFs whose water velocity the step decided.
#include "engine/materials/pore_water.hpp"
#include "engine/parallel.hpp"
#include "solver/xpic.hpp"

namespace mpile::passes {

template <GeometryMode mode, ShapeFunctions shape>
void extrapolate_water_xpic(const Scene& scene, const ParticleBins& bins,
                            const std::vector<const LiquidPhase*>& phases, int order,
                            const StepParameters& step, WaterXpic& water) {
  constexpr int dofs = has_theta(mode) ? 3 : 2;
  const Grid& grid = scene.grid;
  const Particles& p = scene.particles;
  const std::size_t node_count = grid.liquid.size();
  water.correction.assign(node_count, NodeVector{0.0, 0.0, 0.0});
  water.term.resize(node_count);
  water.smoothed.assign(node_count, NodeVector{0.0, 0.0, 0.0});
  water.decided.resize(node_count);
  const bool structures = !grid.structure_fields.empty();
  // D_0 = w^L, the water's nodal velocity at the step's start. Decided, as update_water_velocities
  // sets them: a face that holds the water to the skeleton (water_held), and every DOF where a
  // structure occupies the node (the water tied to the skeleton, or along the wall as the
  // contact's mixture balance leaves it). A drain's DOF is the water's own: p = 0 beyond it.
  parallel_for(node_count, [&](std::size_t i) {
    const LiquidNode& node = grid.liquid[i];
    const bool empty = !(node.mass > 0.0) || grid.nodes[i].mass <= step.mass_floor;
    const bool at_wall = structures && grid.structure_occupies(i, step.mass_floor);
    water.decided[i] = at_wall ? std::uint8_t{DOF_R | DOF_Y | DOF_THETA}
                               : static_cast<std::uint8_t>(grid.water_held[i] & (DOF_R | DOF_Y));
    for (int d = 0; d < 3; ++d) {
      water.term[i][d] =
          !empty && d < dofs ? node.velocity()[d] - node.velocity_increment()[d] : 0.0;
    }
  });
  const auto stride = static_cast<std::size_t>(p.state_stride);
  for (int j = 1; j < order; ++j) {
    // S S+ D_{j-1} with the water's weights, rho_w V = m_w / n a particle (r^2 times it for the
    // angular DOF): those of its nodal mass and inertia (map_water_to_grid), so that S S+ of a
    // uniform field is that field.
    bins.for_each_block_colored([&](int, std::span<const std::int32_t> particles) {
      for (const std::int32_t q : particles) {
        const auto i = static_cast<std::size_t>(q);
        const LiquidPhase* phase = phases[p.material[i]];
        if (phase == nullptr) {
          continue;
        }
        const double n = p.state[i * stride + static_cast<std::size_t>(phase->porosity_slot)];
        const double inertia = phase->water_fraction(n) * p.mass[i] / n;
        const auto w = particle_weights<shape>(grid, p, i);
        double v[3] = {0.0, 0.0, 0.0};
        for (int k = 0; k < w.size; ++k) {
          const NodeVector& t = water.term[static_cast<std::size_t>(w.node[k])];
          for (int d = 0; d < dofs; ++d) {
            v[d] += w.N[k] * t[d];
          }
        }
        const double inertia_r2 = has_theta(mode) ? inertia * p.r[i] * p.r[i] : 0.0;
        for (int k = 0; k < w.size; ++k) {
          NodeVector& s = water.smoothed[static_cast<std::size_t>(w.node[k])];
          const double N = w.N[k];
          s[0] += N * inertia * v[0];
          s[1] += N * inertia * v[1];
          if constexpr (has_theta(mode)) {
            s[2] += N * inertia_r2 * v[2];
          }
        }
      }
    });
    // D_j = D_{j-1} - S S+ D_{j-1}, zero on decided DOFs and empty nodes; the correction sums it.
    parallel_for(node_count, [&](std::size_t i) {
      const LiquidNode& node = grid.liquid[i];
      NodeVector& term = water.term[i];
      NodeVector& s = water.smoothed[i];
      if (!(node.mass > 0.0) || grid.nodes[i].mass <= step.mass_floor) {
        term = {0.0, 0.0, 0.0};
        s = {0.0, 0.0, 0.0};
        return;
      }
      const double inverse[3] = {1.0 / node.mass, 1.0 / node.mass,
                                 dofs == 3 ? 1.0 / node.inertia : 0.0};
      NodeVector& c = water.correction[i];
      for (int d = 0; d < dofs; ++d) {
        term[d] = (water.decided[i] & (1u << d)) != 0 ? 0.0 : term[d] - s[d] * inverse[d];
        c[d] += term[d];
        s[d] = 0.0;
      }
    });
  }
}

#define MPILE_WATER_XPIC(mode, shape)                                                              \
  template void extrapolate_water_xpic<mode, shape>(const Scene&, const ParticleBins&,             \
                                                    const std::vector<const LiquidPhase*>&, int,   \
                                                    const StepParameters&, WaterXpic&);
MPILE_WATER_XPIC(GeometryMode::axisymmetric, ShapeFunctions::linear)
MPILE_WATER_XPIC(GeometryMode::axisymmetric, ShapeFunctions::gimp)
MPILE_WATER_XPIC(GeometryMode::plane_strain, ShapeFunctions::linear)
MPILE_WATER_XPIC(GeometryMode::plane_strain, ShapeFunctions::gimp)
#undef MPILE_WATER_XPIC

} // namespace mpile::passes
