#include "engine/particle_fill.hpp"

#include <stdexcept>

namespace mpile {

std::size_t fill_rectangle(Scene& scene, const Rectangle& region, int per_direction,
                           std::uint16_t material, std::uint16_t body) {
  if (per_direction < 1) {
    throw std::invalid_argument("particles per cell direction must be at least 1");
  }
  const Grid& grid = scene.grid;
  const double density = scene.materials.at(material)->density();
  const bool axisymmetric = scene.mode == GeometryMode::axisymmetric;
  const std::size_t before = scene.particles.size();
  for (int cy = 0; cy < grid.cells_y(); ++cy) {
    for (int cr = 0; cr < grid.cells_r(); ++cr) {
      const double hr = grid.r_axis().cell_size(cr);
      const double hy = grid.y_axis().cell_size(cy);
      const double area = hr * hy / (per_direction * per_direction);
      for (int j = 0; j < per_direction; ++j) {
        for (int i = 0; i < per_direction; ++i) {
          const double r = grid.r_axis().node(cr) + (i + 0.5) * hr / per_direction;
          const double y = grid.y_axis().node(cy) + (j + 0.5) * hy / per_direction;
          if (!region.contains(r, y)) {
            continue;
          }
          const double weight = axisymmetric ? area * r : area;
          scene.particles.add(r, y, density * weight, weight, 0.5 * hr / per_direction,
                              0.5 * hy / per_direction, material, body);
          scene.particles.cell_r.back() = cr;
          scene.particles.cell_y.back() = cy;
        }
      }
    }
  }
  return scene.particles.size() - before;
}

void initialise_geostatic_stress(Scene& scene, std::uint16_t body, double y_surface,
                                 double unit_weight, double k0) {
  Particles& p = scene.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] != body) {
      continue;
    }
    const double vertical = -unit_weight * (y_surface - p.y[i]);
    p.stress[i] = Stress{k0 * vertical, vertical, k0 * vertical, 0.0, 0.0, 0.0};
    const Material& material = *scene.materials[p.material[i]];
    material.initialise_state(p.stress[i],
                              p.state.data() + i * static_cast<std::size_t>(p.state_stride));
  }
}

} // namespace mpile
