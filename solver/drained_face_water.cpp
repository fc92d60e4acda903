// The far field's pore water beyond drained faces held at its hydrostatic pressure ([boundaries]
// drained_pressure = "hydrostatic", physics.md section 9b): the traction p_b n it puts on the face
// nodes' water and mixture before their momentum balance, and the work it does on the water that
// flows through the face.
#include "engine/absorbing_boundary.hpp"
#include "solver/passes.hpp"

#include <algorithm>

namespace mpile::passes {

namespace {

/// The integral of N_k p_b n over the face, taken with the particles' quadrature: each coupled
/// particle in the cells along the face lends the face its footprint, its volume over the cell's
/// width normal to the face (at the face's radius in axisymmetric mode), at its coordinate along
/// the face. The water's internal force is integrated on the same points, so that a hydrostatic
/// column meets the far field's pressure in equilibrium node by node. Integrated exactly instead,
/// the node on the axis got 12 % less than its particles pushed (the integral of N r dr against
/// two points per cell) and the water circulated out through it at 5e-3 m/s.
void face_forces(const Scene& scene, const std::vector<const LiquidPhase*>& phases,
                 DrainedFaceWater& water, double g_y) {
  const Grid& grid = scene.grid;
  const Particles& p = scene.particles;
  const int normal = face_normal(water.face);
  const bool low = water.face == GridFace::r_min || water.face == GridFace::y_min;
  const GradedAxis& across = normal == 0 ? grid.r_axis() : grid.y_axis();
  const GradedAxis& along = normal == 0 ? grid.y_axis() : grid.r_axis();
  const int layer = low ? 0 : across.cell_count() - 1;
  const double face = low ? across.node(0) : across.node(across.node_count() - 1);
  const double width = across.cell_size(layer);
  const double outward = low ? -1.0 : 1.0;
  const bool axisymmetric = scene.mode == GeometryMode::axisymmetric;
  water.force.assign(water.nodes.size(), {0.0, 0.0});
  // Serial, in particle order: the same sums for any thread count.
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (phases[p.material[i]] == nullptr) {
      continue;
    }
    const int cell_across = normal == 0 ? p.cell_r[i] : p.cell_y[i];
    if (cell_across != layer) {
      continue;
    }
    const int c = normal == 0 ? p.cell_y[i] : p.cell_r[i];
    const double t = normal == 0 ? p.y[i] : p.r[i];
    const double s = std::clamp((t - along.node(c)) / along.cell_size(c), 0.0, 1.0);
    const double r_face = normal == 0 ? face : p.r[i];
    const double y_face = normal == 0 ? p.y[i] : face;
    const double footprint =
        axisymmetric ? p.volume[i] / p.r[i] / width * r_face : p.volume[i] / width;
    const double depth = std::max(0.0, water.surface - y_face);
    const double traction = outward * water.density * g_y * depth * footprint;
    const auto n = static_cast<std::size_t>(normal);
    water.force[static_cast<std::size_t>(c)][n] += (1.0 - s) * traction;
    water.force[static_cast<std::size_t>(c) + 1][n] += s * traction;
  }
}

} // namespace

void apply_drained_face_water(Scene& scene, const std::vector<const LiquidPhase*>& phases,
                              const SolverSettings& settings) {
  Grid& grid = scene.grid;
  for (DrainedFaceWater& water : scene.boundaries.drained_water) {
    face_forces(scene, phases, water, settings.gravity[1]);
    for (std::size_t k = 0; k < water.nodes.size(); ++k) {
      const auto i = static_cast<std::size_t>(water.nodes[k]);
      if (!(grid.liquid[i].mass > 0.0)) {
        continue; // no pore water reaches this node
      }
      for (std::size_t d = 0; d < 2; ++d) {
        // The total stress's share is the mixture's (its support then carries the effective
        // stress alone), the pore pressure's the water's.
        grid.nodes[i].force[d] += water.force[k][d];
        grid.liquid[i].force[d] += water.force[k][d];
      }
    }
  }
}

double drained_face_water_work(const Scene& scene, const StepParameters& step) {
  const Grid& grid = scene.grid;
  double work = 0.0;
  for (const DrainedFaceWater& water : scene.boundaries.drained_water) {
    for (std::size_t k = 0; k < water.nodes.size(); ++k) {
      const LiquidNode& node = grid.liquid[static_cast<std::size_t>(water.nodes[k])];
      if (!(node.mass > 0.0)) {
        continue;
      }
      // The face holds the skeleton along its normal, so the traction works on the water's flux
      // alone: n p_b w_n per unit area, the node's porosity being its water's share over its mass
      // (update_water_velocities), at the step's mean velocity.
      const double porosity = node.share / node.mass;
      for (int d = 0; d < 2; ++d) {
        const double mean = node.velocity()[d] - 0.5 * node.velocity_increment()[d];
        work += porosity * water.force[k][static_cast<std::size_t>(d)] * mean * step.dt;
      }
    }
  }
  return work;
}

} // namespace mpile::passes
