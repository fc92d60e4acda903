// Soil kept out of rigid bodies (physics.md section 5). Contact acts at nodes: between them a soil
// particle follows the interpolated velocity and can cross a rigid outline, most often at a pile
// tip's corner, where the nodes' mean normal lets soil slide round it. Inside a rigid wall the
// particle is no longer in contact with anything the nodes resolve: it stretched to densities of
// 4 kg/m^3 in a 5.3 mm wall and, its wave speed growing as its density fell, cut the time step by
// three (docs/results.md, "A resolved pile tip"). A rigid body's outline is known exactly, so
// every soil particle whose centre ends a step inside one is put back on the nearest contact
// surface, along that surface's normal. Its velocity is left alone (the next step's contact
// corrects what the nodes see); the gravity work of the move is booked so that the energy balance
// stays closed.
#include "solver/contact_passes.hpp"

#include "engine/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mpile::passes {

namespace {

struct BlockExclusion {
  std::int64_t moved = 0;
  double gravity_work = 0.0;
  bool block_changed = false;
  bool cell_changed = false;
};

/// The outline's bounding box, to skip the particles far from it with two comparisons.
std::array<double, 4> bounds(const StructureOutline& outline) {
  std::array<double, 4> box{
      std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
      std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const auto& [r, y] : outline.vertices) {
    box = {std::min(box[0], r), std::max(box[1], r), std::min(box[2], y), std::max(box[3], y)};
  }
  return box;
}

} // namespace

SoilExclusion keep_soil_out_of_rigid_bodies(Scene& scene, const ParticleBins& bins,
                                            const SolverSettings& settings) {
  SoilExclusion result;
  Grid& grid = scene.grid;
  Particles& p = scene.particles;
  for (const ContactPair& pair : scene.contacts) {
    if (pair.rigid_body < 0 || !pair.outline) {
      continue;
    }
    const NodeBox& reach = grid.structure_fields[static_cast<std::size_t>(pair.field - 1)].reach;
    if (reach.empty()) {
      continue;
    }
    const OutlineDistance outline(*pair.outline);
    const auto box = bounds(*pair.outline);
    const double g_r = settings.gravity[0];
    const double g_y = settings.gravity[1];
    std::vector<BlockExclusion> blocks(static_cast<std::size_t>(bins.block_count()));
    bins.for_each_block([&](int block, std::span<const std::int32_t> particles) {
      // A particle moves less than a cell in a step and the reach spans a cell beyond the
      // structure's particles, so a particle inside the outline is in a block that meets it.
      if (!block_node_box(grid, bins, block).intersects(reach)) {
        return;
      }
      BlockExclusion& out = blocks[static_cast<std::size_t>(block)];
      for (const std::int32_t q : particles) {
        const auto i = static_cast<std::size_t>(q);
        const double r = p.r[i];
        const double y = p.y[i];
        if (r <= box[0] || r >= box[1] || y <= box[2] || y >= box[3] ||
            scene.field_of(p.body[i]) != 0) {
          continue;
        }
        const OutlineDistance::Exit exit = outline.exit(r, y);
        if (exit.distance >= 0.0 || !std::isfinite(exit.surface_distance)) {
          continue;
        }
        const double move_r = -exit.surface_distance * exit.n_r;
        const double move_y = -exit.surface_distance * exit.n_y;
        p.r[i] = r + move_r;
        p.y[i] = y + move_y;
        out.gravity_work += p.mass[i] * (g_r * move_r + g_y * move_y);
        ++out.moved;
        const int cr = grid.r_axis().locate(p.r[i]);
        const int cy = grid.y_axis().locate(p.y[i]);
        if (cr < 0 || cy < 0) {
          continue; // on the grid's edge: the step's check of positions names it
        }
        out.block_changed = out.block_changed || bins.block_of(cr, cy) != block;
        out.cell_changed = out.cell_changed || cr != p.cell_r[i] || cy != p.cell_y[i];
        p.cell_r[i] = cr;
        p.cell_y[i] = cy;
      }
    });
    // Summed in block order, so that the work is the same for any thread count.
    for (const BlockExclusion& b : blocks) {
      result.moved += b.moved;
      result.gravity_work += b.gravity_work;
      result.block_changed = result.block_changed || b.block_changed;
      result.cell_changed = result.cell_changed || b.cell_changed;
    }
  }
  return result;
}

} // namespace mpile::passes
