// Particle-to-grid. Reads particle position, cell, mass, volume, velocity and stress; writes node
// mass, momentum and force (f_ext - f_int, physics.md section 2) with a colored scatter, and in
// axisymmetric mode the angular momentum, rotational inertia and torque of the theta DOF (the
// node's angular velocity, docs/design.md). With contact, each particle writes to its body's field
// (and to its mass gradient where one is kept).
#include "engine/shape_functions.hpp"
#include "solver/cell_slots.hpp"
#include "solver/particle_fields.hpp"
#include "solver/passes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace mpile::passes {

namespace {

/// Scatters particle i's mass, momentum, forces and, in axisymmetric mode, its angular momentum,
/// rotational inertia and torque to the nodes of one field; returns its weights. `mean_shift` is
/// added to its normal stresses (B-bar's cell mean stress: bbar_mean_stress_shift).
template <GeometryMode mode, ShapeFunctions shape>
[[gnu::always_inline]] inline auto scatter(GridNode* nodes, const Grid& grid, const Particles& p,
                                           std::size_t i, double g_r, double g_y,
                                           double mean_shift) {
  const auto w = particle_weights<shape>(grid, p, i);
  const double m = p.mass[i];
  const double weight = p.volume[i]; // integration weight (A r per radian in axisymmetry)
  const Stress& s = p.stress[i];
  const double m_v_r = m * p.v_r[i];
  const double m_v_y = m * p.v_y[i];
  // Stresses times the integration weight, so that each node needs only multiply-adds.
  const double w_rr = weight * (s[RR] + mean_shift);
  const double w_yy = weight * (s[YY] + mean_shift);
  const double w_ry = weight * s[RY];
  for (int k = 0; k < w.size; ++k) {
    GridNode& node = nodes[static_cast<std::size_t>(w.node[k])];
    const double n = w.N[k];
    node.mass += n * m;
    node.momentum[0] += n * m_v_r;
    node.momentum[1] += n * m_v_y;
    node.force[0] += n * m * g_r - (w.dN_dr[k] * w_rr + w.dN_dy[k] * w_ry);
    node.force[1] += n * m * g_y - (w.dN_dy[k] * w_yy + w.dN_dr[k] * w_ry);
  }
  if constexpr (has_theta(mode)) {
    // Hoop stress in the r row. The theta DOF is the node's angular velocity (v_theta =
    // r sum N omega), so a rigid spin is exact: the node takes angular momentum m r v_theta
    // and rotational inertia m r^2, and its torque row is the virtual work of tau_ytheta and
    // tau_rtheta on gamma_ytheta = r d(omega)/dy and gamma_rtheta = r d(omega)/dr (seed eq. 8's
    // dv/dr - v/r with v = r omega: its -v/r term cancels the rigid part exactly).
    const double r = p.r[i];
    const double w_hoop = weight * (s[TT] + mean_shift) * (1.0 / r);
    const double w_yt = weight * r * s[YT];
    const double w_rt = weight * r * s[RT];
    const double m_r = m * r;
    const double angular_momentum = m_r * p.v_theta[i];
    const double rotational_inertia = m_r * r;
    for (int k = 0; k < w.size; ++k) {
      GridNode& node = nodes[static_cast<std::size_t>(w.node[k])];
      const double n = w.N[k];
      node.force[0] -= n * w_hoop;
      node.momentum[2] += n * angular_momentum;
      node.inertia += n * rotational_inertia;
      node.force[2] -= w.dN_dy[k] * w_yt + w.dN_dr[k] * w_rt;
    }
  }
  return w;
}

} // namespace

template <GeometryMode mode, bool contact, ShapeFunctions shape>
void particle_to_grid(Scene& scene, const ParticleBins& bins, const SolverSettings& settings) {
  Grid& grid = scene.grid;
  const Particles& p = scene.particles;
  parallel_for(grid.nodes.size(), [&](std::size_t i) { grid.nodes[i] = GridNode{}; });
  if constexpr (contact) {
    // A structure field is zero outside the box it was last scattered to (NodeField::held).
    for (NodeField& field : grid.structure_fields) {
      const bool gradient = !field.mass_gradient.empty();
      parallel_for_box(field.held, grid.nodes_r(), [&](std::size_t i) {
        field.nodes[i] = GridNode{};
        if (gradient) {
          field.mass_gradient[i] = {0.0, 0.0};
        }
      });
      field.held = field.reach;
    }
  }
  // Gaps between the soil and each structure outline, as the smallest over the soil particles
  // of a node's cells (ContactPair::gap), at the nodes of the structure's reach: only there can
  // the structure have mass, and only there is the gap read.
  struct OutlineGap {
    OutlineDistance distance;
    double* gap;
    SurfaceGap* surface_gap;
    NodeBox reach;
  };
  std::vector<OutlineGap> gaps;
  if constexpr (contact) {
    for (ContactPair& pair : scene.contacts) {
      const NodeBox& reach = grid.structure_fields[static_cast<std::size_t>(pair.field - 1)].reach;
      if (pair.outline && !reach.empty()) {
        parallel_for_box(reach, grid.nodes_r(), [&](std::size_t i) {
          pair.gap[i] = std::numeric_limits<double>::infinity();
          if (pair.surface_gap_at_node) {
            pair.surface_gap[i] = SurfaceGap{};
          }
        });
        gaps.push_back({OutlineDistance(*pair.outline), pair.gap.data(),
                        pair.surface_gap_at_node ? pair.surface_gap.data() : nullptr, reach});
      }
    }
  }
  [[maybe_unused]] const auto fields =
      contact ? std::optional<ParticleFields>(std::in_place, grid, scene) : std::nullopt;

  const double g_r = settings.gravity[0];
  const double g_y = settings.gravity[1];
  const bool consistent = settings.bbar_consistent_force; // validated: only with B-bar
  bins.for_each_block_colored([&](int block, std::span<const std::int32_t> particles) {
    const auto [cr0, cy0] = bins.block_origin(block);
    const bool mixed = contact && bins.block_tag(block) != 0;
    thread_local std::vector<double> shift;
    if (consistent) {
      bbar_mean_stress_shift(
          p, particles, CellSlots<contact>{scene, p, cr0, cy0, bins.block_cells(), mixed}, shift);
    }
    const auto shift_of = [&](std::size_t k) { return consistent ? shift[k] : 0.0; };
    if constexpr (!contact) {
      for (std::size_t k = 0; k < particles.size(); ++k) {
        scatter<mode, shape>(grid.nodes.data(), grid, p, static_cast<std::size_t>(particles[k]),
                             g_r, g_y, shift_of(k));
      }
    } else {
      // A block of soil particles scatters to field 0 alone, as without contact, and keeps no
      // mass gradient; it needs the gaps only where its nodes meet a structure's reach.
      const NodeBox block_nodes = block_node_box(grid, bins, block);
      bool near_outline = false;
      for (const OutlineGap& g : gaps) {
        near_outline = near_outline || block_nodes.intersects(g.reach);
      }
      if (!mixed && !near_outline) {
        for (std::size_t k = 0; k < particles.size(); ++k) {
          scatter<mode, shape>(grid.nodes.data(), grid, p, static_cast<std::size_t>(particles[k]),
                               g_r, g_y, shift_of(k));
        }
        return;
      }
      for (std::size_t k = 0; k < particles.size(); ++k) {
        const auto i = static_cast<std::size_t>(particles[k]);
        const std::uint16_t body = p.body[i];
        const auto w = scatter<mode, shape>(mixed ? fields->nodes(body) : grid.nodes.data(), grid,
                                            p, i, g_r, g_y, shift_of(k));
        if (near_outline && (!mixed || fields->is_soil(body))) {
          // Half the particle's size (a square domain of its area in the r-y plane), widened by
          // 1 % so that a particle whose domain ends on the outline counts as touching it.
          // A particle seeded from a cut sub-cell has the extent of its part: its half-extent
          // along the outline's normal, with the same margin.
          const bool cut = !scene.cut_cell_bodies.empty() && scene.cut_cell_bodies[body] != 0;
          const double area = has_theta(mode) ? p.volume[i] / p.r[i] : p.volume[i];
          const double half_size = 0.505 * std::sqrt(area);
          for (const OutlineGap& g : gaps) {
            if (!cut && g.surface_gap == nullptr) {
              const double gap = g.distance(p.r[i], p.y[i]) - half_size;
              for_each_support_node(grid, w, [&](int node) {
                double& node_gap = g.gap[static_cast<std::size_t>(node)];
                node_gap = std::min(node_gap, gap);
              });
              continue;
            }
            // The nearest edge's normal: its tangent runs along r for an edge nearer horizontal,
            // along y otherwise.
            const OutlineDistance::Nearest near = g.distance.nearest(p.r[i], p.y[i]);
            const double gap = cut ? near.distance - 1.01 * std::hypot(near.n_r * p.half_r[i],
                                                                       near.n_y * p.half_y[i])
                                   : g.distance(p.r[i], p.y[i]) - half_size;
            const bool along_r = std::abs(near.n_y) >= std::abs(near.n_r);
            const double x = along_r ? p.r[i] : p.y[i];
            const double cell = along_r ? grid.r_axis().cell_size(p.cell_r[i])
                                        : grid.y_axis().cell_size(p.cell_y[i]);
            for_each_support_node(grid, w, [&](int support_node) {
              const auto node = static_cast<std::size_t>(support_node);
              double& node_gap = g.gap[node];
              node_gap = std::min(node_gap, gap);
              const double offset =
                  x - (along_r ? grid.node_r(support_node) : grid.node_y(support_node));
              if (g.surface_gap != nullptr && std::abs(offset) <= cell) {
                g.surface_gap[node].add(gap, offset);
              }
            });
          }
        }
        std::array<double, 2>* gradient = mixed ? fields->mass_gradient(body) : nullptr;
        if (gradient != nullptr) {
          const double m = p.mass[i];
          for (int a = 0; a < w.size; ++a) {
            auto& g = gradient[static_cast<std::size_t>(w.node[a])];
            g[0] += m * w.dN_dr[a];
            g[1] += m * w.dN_dy[a];
          }
        }
      }
    }
  });
}

template void particle_to_grid<GeometryMode::axisymmetric, false, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const SolverSettings&);
template void particle_to_grid<GeometryMode::axisymmetric, false, ShapeFunctions::gimp>(
    Scene&, const ParticleBins&, const SolverSettings&);
template void particle_to_grid<GeometryMode::axisymmetric, true, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const SolverSettings&);
template void particle_to_grid<GeometryMode::axisymmetric, true, ShapeFunctions::gimp>(
    Scene&, const ParticleBins&, const SolverSettings&);
template void particle_to_grid<GeometryMode::plane_strain, false, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const SolverSettings&);
template void particle_to_grid<GeometryMode::plane_strain, false, ShapeFunctions::gimp>(
    Scene&, const ParticleBins&, const SolverSettings&);
template void particle_to_grid<GeometryMode::plane_strain, true, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const SolverSettings&);
template void particle_to_grid<GeometryMode::plane_strain, true, ShapeFunctions::gimp>(
    Scene&, const ParticleBins&, const SolverSettings&);

} // namespace mpile::passes
