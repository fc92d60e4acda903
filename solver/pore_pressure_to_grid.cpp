// The pore water's share of field 0's internal force, for the contact's effective normal force
// (physics.md section 9a). Reads the soil particles' volume, position and pore pressure (their
// state at Material::pore_pressure_index); writes Grid::pore_force = -sum V p grad N (with the
// hoop term -sum V p N / r on the r row in axisymmetry) by a colored scatter: the same sum the
// particle-to-grid pass makes of the total stress, taken of p 1 alone, so that the water's share of
// a node's normal force is what the grid gives it, not a pressure times an area. The solver runs it
// only in a scene with contact and undrained soil; otherwise the field stays empty. Also here, the
// other pass on the particles' pore pressures alone: smooth_excess_pore_pressure.
#include "engine/shape_functions.hpp"
#include "solver/particle_fields.hpp"
#include "solver/passes.hpp"

#include <stdexcept>

namespace mpile::passes {

std::vector<int> pore_pressure_slots(const Scene& scene) {
  std::vector<int> slots;
  for (const auto& material : scene.materials) {
    slots.push_back(material->pore_pressure_index());
  }
  return slots;
}

template <GeometryMode mode, ShapeFunctions shape>
void map_pore_force(Scene& scene, const ParticleBins& bins) {
  Grid& grid = scene.grid;
  const std::vector<int> slots = pore_pressure_slots(scene);
  grid.pore_force.assign(grid.nodes.size(), {0.0, 0.0});
  const Particles& p = scene.particles;
  const ParticleFields fields(grid, scene);
  const auto stride = static_cast<std::size_t>(p.state_stride);
  bins.for_each_block_colored([&](int, std::span<const std::int32_t> particles) {
    for (const std::int32_t q : particles) {
      const auto i = static_cast<std::size_t>(q);
      const int slot = slots[p.material[i]];
      if (slot < 0 || !fields.is_soil(p.body[i])) {
        continue;
      }
      const double weighted = p.volume[i] * p.state[i * stride + static_cast<std::size_t>(slot)];
      const double hoop = has_theta(mode) ? weighted / p.r[i] : 0.0;
      const auto w = particle_weights<shape>(grid, p, i);
      for (int k = 0; k < w.size; ++k) {
        std::array<double, 2>& f = grid.pore_force[static_cast<std::size_t>(w.node[k])];
        f[0] -= w.dN_dr[k] * weighted + w.N[k] * hoop;
        f[1] -= w.dN_dy[k] * weighted;
      }
    }
  });
}

void smooth_excess_pore_pressure(Scene& scene, const ParticleBins& bins) {
  Particles& p = scene.particles;
  const std::vector<int> slots = pore_pressure_slots(scene);
  const auto stride = static_cast<std::size_t>(p.state_stride);
  // A block holds every particle of its cells, so each cell's mean is the block's own work and
  // the result is the same for any thread count.
  bins.for_each_block([&](int block, std::span<const std::int32_t> particles) {
    thread_local std::vector<std::array<double, 2>> cell_sum;
    const auto [cr0, cy0] = bins.block_origin(block);
    const int block_cells = bins.block_cells();
    cell_sum.assign(static_cast<std::size_t>(block_cells * block_cells), {0.0, 0.0});
    const auto cell_of = [&](std::size_t i) {
      const int r = p.cell_r[i] - cr0;
      const int y = p.cell_y[i] - cy0;
      if (r < 0 || r >= block_cells || y < 0 || y >= block_cells) {
        // Run between a particle's move and its rebinning, a cell could lie outside the block
        // and the sum be written out of bounds (a coupled run's heap once broke so).
        throw std::logic_error("smooth_excess_pore_pressure: a particle is not binned in its "
                               "cell's block");
      }
      return static_cast<std::size_t>(r + block_cells * y);
    };
    // A particle made stress-free inside a rigid body (no stress, no pore pressure) is left out.
    const auto saturated = [&](std::size_t i, int slot) {
      return slot >= 0 && !(p.stress[i] == Stress{} &&
                            p.state[i * stride + static_cast<std::size_t>(slot)] == 0.0);
    };
    for (const std::int32_t q : particles) {
      const auto i = static_cast<std::size_t>(q);
      const int slot = slots[p.material[i]];
      if (saturated(i, slot)) {
        auto& sum = cell_sum[cell_of(i)];
        sum[0] += p.volume[i] * p.state[i * stride + static_cast<std::size_t>(slot) + 1];
        sum[1] += p.volume[i];
      }
    }
    for (const std::int32_t q : particles) {
      const auto i = static_cast<std::size_t>(q);
      const int slot = slots[p.material[i]];
      if (!saturated(i, slot)) {
        continue;
      }
      const auto& sum = cell_sum[cell_of(i)];
      double* pore = p.state.data() + i * stride + static_cast<std::size_t>(slot);
      const double change = sum[0] / sum[1] - pore[1];
      pore[0] += change;
      pore[1] += change;
      Stress& s = p.stress[i];
      s[RR] += change;
      s[YY] += change;
      s[TT] += change;
    }
  });
}

template void
map_pore_force<GeometryMode::axisymmetric, ShapeFunctions::linear>(Scene&, const ParticleBins&);
template void map_pore_force<GeometryMode::axisymmetric, ShapeFunctions::gimp>(Scene&,
                                                                               const ParticleBins&);
template void
map_pore_force<GeometryMode::plane_strain, ShapeFunctions::linear>(Scene&, const ParticleBins&);
template void map_pore_force<GeometryMode::plane_strain, ShapeFunctions::gimp>(Scene&,
                                                                               const ParticleBins&);

} // namespace mpile::passes
