#include "engine/particle_fill.hpp"

#include "engine/materials/undrained_soil.hpp"

#include <algorithm>
#include <stdexcept>

namespace mpile {

namespace {

/// Calls seed(cr, cy, r, y, hr, hy) for every sub-cell centre in the region and the band, cell
/// by cell along r, then y.
template <typename Seed>
void for_each_seed(const GradedAxis& r_axis, const GradedAxis& y_axis, const Region& region,
                   int per_direction, SeedBand band, Seed&& seed) {
  if (per_direction < 1) {
    throw std::invalid_argument("particles per cell direction must be at least 1");
  }
  const Rectangle& box = region.bounds();
  for (int cy = 0; cy < y_axis.cell_count(); ++cy) {
    if (y_axis.node(cy + 1) < box.y_min || y_axis.node(cy) > box.y_max) {
      continue; // no point of this row of cells lies in the region
    }
    for (int cr = 0; cr < r_axis.cell_count(); ++cr) {
      if (r_axis.node(cr + 1) < box.r_min || r_axis.node(cr) > box.r_max) {
        continue;
      }
      const double hr = r_axis.cell_size(cr);
      const double hy = y_axis.cell_size(cy);
      for (int j = 0; j < per_direction; ++j) {
        for (int i = 0; i < per_direction; ++i) {
          const double r = r_axis.node(cr) + (i + 0.5) * hr / per_direction;
          const double y = y_axis.node(cy) + (j + 0.5) * hy / per_direction;
          if (band.contains(y) && region.contains(r, y)) {
            seed(cr, cy, r, y, hr, hy);
          }
        }
      }
    }
  }
}

/// The part of the sub-cell [r0, r0 + hr] x [y0, y0 + hy] inside the region and the band, from a
/// lattice of samples: its area, its integral of r dA, its centroid and the half-extents from the
/// centroid to its far edges.
struct CutPart {
  double area = 0.0;
  double r_area = 0.0;
  double r = 0.0;
  double y = 0.0;
  double half_r = 0.0;
  double half_y = 0.0;
};

CutPart cut_part(const Region& region, SeedBand band, double r0, double y0, double hr, double hy) {
  constexpr int samples = 16;
  const double dr = hr / samples;
  const double dy = hy / samples;
  CutPart part;
  double r_low = r0 + hr, r_high = r0, y_low = y0 + hy, y_high = y0;
  int inside = 0;
  for (int b = 0; b < samples; ++b) {
    const double y = y0 + (b + 0.5) * dy;
    if (!band.contains(y)) {
      continue;
    }
    for (int a = 0; a < samples; ++a) {
      const double r = r0 + (a + 0.5) * dr;
      if (!region.contains(r, y)) {
        continue;
      }
      ++inside;
      part.r += r;
      part.y += y;
      part.r_area += r * dr * dy;
      r_low = std::min(r_low, r - 0.5 * dr);
      r_high = std::max(r_high, r + 0.5 * dr);
      y_low = std::min(y_low, y - 0.5 * dy);
      y_high = std::max(y_high, y + 0.5 * dy);
    }
  }
  if (inside > 0) {
    part.area = inside * dr * dy;
    part.r /= inside;
    part.y /= inside;
    part.half_r = std::max(part.r - r_low, r_high - part.r);
    part.half_y = std::max(part.y - y_low, y_high - part.y);
  }
  return part;
}

/// Seeds the sub-cells the region's outline cuts (not all four corners inside) with their part
/// inside; whole sub-cells as fill_region does.
std::size_t fill_cut_cells(Scene& scene, const Region& region, int per_direction,
                           std::uint16_t material, std::uint16_t body, SeedBand band) {
  const Grid& grid = scene.grid;
  const double density = scene.materials.at(material)->density();
  const bool axisymmetric = scene.mode == GeometryMode::axisymmetric;
  const std::size_t before = scene.particles.size();
  const Rectangle& box = region.bounds();
  auto inside = [&](double r, double y) { return band.contains(y) && region.contains(r, y); };
  for (int cy = 0; cy < grid.y_axis().cell_count(); ++cy) {
    if (grid.y_axis().node(cy + 1) < box.y_min || grid.y_axis().node(cy) > box.y_max) {
      continue;
    }
    for (int cr = 0; cr < grid.r_axis().cell_count(); ++cr) {
      if (grid.r_axis().node(cr + 1) < box.r_min || grid.r_axis().node(cr) > box.r_max) {
        continue;
      }
      const double hr = grid.r_axis().cell_size(cr) / per_direction;
      const double hy = grid.y_axis().cell_size(cy) / per_direction;
      for (int j = 0; j < per_direction; ++j) {
        for (int i = 0; i < per_direction; ++i) {
          const double r0 = grid.r_axis().node(cr) + i * hr;
          const double y0 = grid.y_axis().node(cy) + j * hy;
          if (inside(r0, y0) && inside(r0 + hr, y0) && inside(r0, y0 + hy) &&
              inside(r0 + hr, y0 + hy)) {
            const double r = r0 + 0.5 * hr;
            const double area = hr * hy;
            const double weight = axisymmetric ? area * r : area;
            scene.particles.add(r, y0 + 0.5 * hy, density * weight, weight, 0.5 * hr, 0.5 * hy,
                                material, body);
          } else {
            const CutPart part = cut_part(region, band, r0, y0, hr, hy);
            if (part.area == 0.0) {
              continue;
            }
            const double weight = axisymmetric ? part.r_area : part.area;
            scene.particles.add(part.r, part.y, density * weight, weight, part.half_r, part.half_y,
                                material, body);
          }
          scene.particles.cell_r.back() = cr;
          scene.particles.cell_y.back() = cy;
        }
      }
    }
  }
  return scene.particles.size() - before;
}

} // namespace

std::size_t fill_region(Scene& scene, const Region& region, int per_direction,
                        std::uint16_t material, std::uint16_t body, SeedBand band, bool cut_cells) {
  if (cut_cells) {
    return fill_cut_cells(scene, region, per_direction, material, body, band);
  }
  const Grid& grid = scene.grid;
  const double density = scene.materials.at(material)->density();
  const bool axisymmetric = scene.mode == GeometryMode::axisymmetric;
  const bool coupled = scene.materials[material]->liquid_phase() != nullptr;
  const std::size_t before = scene.particles.size();
  for_each_seed(grid.r_axis(), grid.y_axis(), region, per_direction, band,
                [&](int cr, int cy, double r, double y, double hr, double hy) {
                  const double area = hr * hy / (per_direction * per_direction);
                  const double weight = axisymmetric ? area * r : area;
                  scene.particles.add(r, y, density * weight, weight, 0.5 * hr / per_direction,
                                      0.5 * hy / per_direction, material, body);
                  scene.particles.cell_r.back() = cr;
                  scene.particles.cell_y.back() = cy;
                  if (coupled) {
                    // Its water at rest in the pores of the dry density, before any K0 state.
                    Particles& p = scene.particles;
                    const auto stride = static_cast<std::size_t>(p.state_stride);
                    scene.materials[material]->initialise_state(
                        Stress{}, p.state.data() + (p.size() - 1) * stride);
                  }
                });
  return scene.particles.size() - before;
}

std::size_t fill_rectangle(Scene& scene, const Rectangle& region, int per_direction,
                           std::uint16_t material, std::uint16_t body) {
  return fill_region(scene, Region(region), per_direction, material, body);
}

std::size_t count_region_seeds(const GradedAxis& r_axis, const GradedAxis& y_axis,
                               const Region& region, int per_direction, SeedBand band) {
  std::size_t count = 0;
  for_each_seed(r_axis, y_axis, region, per_direction, band,
                [&](int, int, double, double, double, double) { ++count; });
  return count;
}

namespace {

/// A particle at rest under its effective vertical stress `vertical` with K0 beside it and its
/// pore water at `pore` (saturated; 0 for dry soil): sigma = sigma' + p 1, and the material's
/// state made consistent with it.
void set_geostatic_state(Particles& p, std::size_t i, const Material& material,
                         const UndrainedSoil* saturated, double vertical, double pore, double k0) {
  double* state = p.state.data() + i * static_cast<std::size_t>(p.state_stride);
  p.stress[i] = Stress{k0 * vertical + pore, vertical + pore, k0 * vertical + pore, 0.0, 0.0, 0.0};
  if (saturated) {
    state[saturated->pore_pressure_index()] = pore;
  }
  material.initialise_state(p.stress[i], state);
}

} // namespace

void initialise_geostatic_stress(Scene& scene, std::uint16_t body, double y_surface,
                                 double unit_weight, double k0, double surcharge) {
  Particles& p = scene.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] != body) {
      continue;
    }
    const Material& material = *scene.materials[p.material[i]];
    const double depth = y_surface - p.y[i];
    // A saturated soil: its water is hydrostatic from the surface down and carries its own
    // weight; the skeleton carries the buoyant weight, and K0 acts on the effective stress.
    const auto* saturated = dynamic_cast<const UndrainedSoil*>(&material);
    const double water_weight =
        saturated ? unit_weight * saturated->water_density() / saturated->density() : 0.0;
    const double pore = -water_weight * depth;
    const double vertical = -surcharge - (unit_weight - water_weight) * depth;
    set_geostatic_state(p, i, material, saturated, vertical, pore, k0);
  }
}

void initialise_layered_geostatic_stress(Scene& scene, std::uint16_t body,
                                         const std::function<double(double, double)>& overburden,
                                         double water_table, double gravity, double k0) {
  Particles& p = scene.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] != body) {
      continue;
    }
    const Material& material = *scene.materials[p.material[i]];
    const auto* saturated = dynamic_cast<const UndrainedSoil*>(&material);
    const double pore =
        saturated ? -saturated->water_density() * gravity * (water_table - p.y[i]) : 0.0;
    const double vertical = -overburden(p.r[i], p.y[i]) - pore; // effective
    set_geostatic_state(p, i, material, saturated, vertical, pore, k0);
  }
}

} // namespace mpile
