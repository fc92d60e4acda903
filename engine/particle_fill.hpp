#pragma once

#include "engine/region.hpp"
#include "engine/scene.hpp"

#include <cstdint>
#include <functional>
#include <limits>

namespace mpile {

/// A band y_from <= y < y_to that seeding keeps to (a body split at a moving band's start).
struct SeedBand {
  double y_from = -std::numeric_limits<double>::infinity();
  double y_to = std::numeric_limits<double>::infinity();
  bool contains(double y) const { return y >= y_from && y < y_to; }
};

/// Fills a region with particles: per cell, per_direction x per_direction particles at the
/// centres of equal sub-cells, keeping those inside the region (and the band). Mass rho A_p r_p
/// and weight A_p r_p per radian (axisymmetric) or rho A_p and A_p (plane strain). Returns how many
/// were added. With cut_cells, a sub-cell whose corners are not all inside is sampled on a 16 x 16
/// lattice and, where any of it is inside, seeded with the part inside: a particle at that part's
/// centroid, with its area (times r) and the half-extents that reach its far edges, so that a
/// curved outline is not seeded as a staircase of whole sub-cells.
std::size_t fill_region(Scene& scene, const Region& region, int per_direction,
                        std::uint16_t material, std::uint16_t body, SeedBand band = {},
                        bool cut_cells = false);
std::size_t fill_rectangle(Scene& scene, const Rectangle& region, int per_direction,
                           std::uint16_t material, std::uint16_t body);

/// How many particles fill_region would add on a grid of these lines (the reader's check that a
/// region is not too small for its cells).
std::size_t count_region_seeds(const GradedAxis& r_axis, const GradedAxis& y_axis,
                               const Region& region, int per_direction, SeedBand band = {});

/// Geostatic stress from a horizontal surface carrying a surcharge q: sigma_yy = -(q + rho g
/// (y_surface - y)) and sigma_rr = sigma_thth = K0 sigma_yy, no shear, for every particle of a
/// body; then each particle's material sets its state consistently. In a saturated (undrained)
/// material, the pore water is hydrostatic from the surface, p = -rho_w g (y_surface - y), the
/// skeleton carries the rest (K0 on the effective stress), and sigma = sigma' + p 1.
void initialise_geostatic_stress(Scene& scene, std::uint16_t body, double y_surface,
                                 double unit_weight, double k0, double surcharge = 0.0);

/// Geostatic stress in layered ground with a water table inside it: `overburden(r, y)` is the
/// total vertical stress's magnitude at a point (a surcharge and the weight of every layer above
/// it, dry above the table, saturated below), sigma_yy = -overburden. A saturated particle's pore
/// water is hydrostatic from the table, p = -rho_w g (water_table - y); K0 acts on the effective
/// stress sigma' = sigma - p 1, as above. A dry particle carries it all.
void initialise_layered_geostatic_stress(Scene& scene, std::uint16_t body,
                                         const std::function<double(double, double)>& overburden,
                                         double water_table, double gravity, double k0);

} // namespace mpile
