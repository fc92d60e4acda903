// XPIC(m) extrapolation (solver/xpic.hpp). Reads node mass, rotational inertia, velocity and
// increment of every deformable field (with coupled soil, field 0's mixture mass and inertia kept
// in Grid::liquid), the constrained-DOF masks and the contact states, and the particles' position,
// cell, mass and body; writes the XPIC fields only.
#include "solver/xpic.hpp"

#include "engine/parallel.hpp"

#include <algorithm>

namespace mpile::passes {

namespace {

/// Which fields get a correction: the soil's and each deformable structure's. A rigid body's
/// field is its body's motion, which the particles take as it is.
std::vector<char> deformable_fields(const Scene& scene) {
  std::vector<char> deformable(static_cast<std::size_t>(scene.grid.field_count()), 1);
  for (const ContactPair& pair : scene.contacts) {
    if (pair.rigid_body >= 0) {
      deformable[static_cast<std::size_t>(pair.field)] = 0;
    }
  }
  return deformable;
}

/// The nodes a field can hold mass at: the whole grid for the soil, a structure's reach.
NodeBox field_box(const Grid& grid, int field) {
  return field == 0 ? NodeBox{0, grid.nodes_r(), 0, grid.nodes_y()}
                    : grid.structure_fields[static_cast<std::size_t>(field - 1)].reach;
}

void resize(std::vector<NodeVector>& v, std::size_t n) {
  if (v.size() != n) {
    v.assign(n, NodeVector{0.0, 0.0, 0.0});
  }
}

} // namespace

template <GeometryMode mode, bool contact, ShapeFunctions shape>
void extrapolate_xpic(const Scene& scene, const ParticleBins& bins, int order,
                      const StepParameters& step, XpicFields& fields) {
  constexpr int dofs = has_theta(mode) ? 3 : 2;
  const Grid& grid = scene.grid;
  const Particles& p = scene.particles;
  const auto field_count = static_cast<std::size_t>(grid.field_count());
  const std::size_t node_count = grid.node_count();
  const std::vector<char> deformable = deformable_fields(scene);
  const bool has_water = !grid.liquid.empty();
  fields.correction.resize(field_count);
  fields.term.resize(field_count);
  fields.smoothed.resize(field_count);
  if (order <= 1) {
    // XPIC(1) is PIC: no correction.
    for (auto& c : fields.correction) {
      c.clear();
    }
    return;
  }

  // Per field and node, the DOFs whose velocity is decided for the step (bit d set): a support's,
  // or the contact law's where the field met its partner. Their terms stay zero. A velocity field
  // prescribed over the whole grid decides every DOF of the soil.
  std::vector<std::vector<std::uint8_t>>& decided = fields.decided;
  decided.resize(field_count);
  const std::uint8_t all_dofs = DOF_R | DOF_Y | DOF_THETA;
  for (std::size_t f = 0; f < field_count; ++f) {
    if (!deformable[f]) {
      fields.correction[f].clear();
      decided[f].clear();
      continue;
    }
    const int field = static_cast<int>(f);
    decided[f] = field == 0 ? grid.constrained : grid.structure_fields[f - 1].constrained;
    if (field == 0 && scene.velocity_field) {
      std::fill(decided[f].begin(), decided[f].end(), all_dofs);
    }
  }
  for (const ContactPair& pair : scene.contacts) {
    for (const int field : {0, pair.field}) {
      auto& mask = decided[static_cast<std::size_t>(field)];
      if (mask.empty()) {
        continue;
      }
      parallel_for_box(pair.written, grid.nodes_r(), [&](std::size_t i) {
        if (pair.state[i] != 0) {
          mask[i] = all_dofs;
        }
      });
    }
  }

  // D_0 = v^L = v^{n+1} minus the step's increment, on the nodes that hold mass.
  for (std::size_t f = 0; f < field_count; ++f) {
    if (!deformable[f]) {
      continue;
    }
    resize(fields.correction[f], node_count);
    resize(fields.term[f], node_count);
    resize(fields.smoothed[f], node_count);
    const std::vector<GridNode>& nodes = grid.field_nodes(static_cast<int>(f));
    parallel_for_box(field_box(grid, static_cast<int>(f)), grid.nodes_r(), [&](std::size_t i) {
      const GridNode& node = nodes[i];
      NodeVector& term = fields.term[f][i];
      fields.correction[f][i] = {0.0, 0.0, 0.0};
      fields.smoothed[f][i] = {0.0, 0.0, 0.0};
      for (int d = 0; d < 3; ++d) {
        term[d] = node.mass > step.mass_floor && d < dofs
                      ? node.velocity()[d] - node.velocity_increment()[d]
                      : 0.0;
      }
    });
  }
  // Outside a structure's reach the arrays keep stale values: nothing reads them, as the
  // structure's particles touch only its reach.

  std::vector<NodeVector*> term_of(field_count, nullptr);
  std::vector<NodeVector*> smoothed_of(field_count, nullptr);
  for (std::size_t f = 0; f < field_count; ++f) {
    if (deformable[f]) {
      term_of[f] = fields.term[f].data();
      smoothed_of[f] = fields.smoothed[f].data();
    }
  }
  for (int j = 1; j < order; ++j) {
    // S S+ D_{j-1}: each particle gathers the term and scatters it back with its mass (and its
    // rotational inertia m r^2 for the angular DOF), coloured as the particle-to-grid scatter.
    bins.for_each_block_colored([&](int, std::span<const std::int32_t> particles) {
      for (const std::int32_t q : particles) {
        const auto i = static_cast<std::size_t>(q);
        const std::size_t f = contact ? scene.field_of(p.body[i]) : 0;
        const NodeVector* term = term_of[f];
        if (term == nullptr) {
          continue;
        }
        NodeVector* smoothed = smoothed_of[f];
        const auto w = particle_weights<shape>(grid, p, i);
        double v[3] = {0.0, 0.0, 0.0};
        for (int k = 0; k < w.size; ++k) {
          const NodeVector& t = term[static_cast<std::size_t>(w.node[k])];
          for (int d = 0; d < dofs; ++d) {
            v[d] += w.N[k] * t[d];
          }
        }
        const double m = p.mass[i];
        const double m_r2 = has_theta(mode) ? m * p.r[i] * p.r[i] : 0.0;
        for (int k = 0; k < w.size; ++k) {
          NodeVector& s = smoothed[static_cast<std::size_t>(w.node[k])];
          const double n = w.N[k];
          s[0] += n * m * v[0];
          s[1] += n * m * v[1];
          if constexpr (has_theta(mode)) {
            s[2] += n * m_r2 * v[2];
          }
        }
      }
    });
    // D_j = D_{j-1} - S S+ D_{j-1}, zero on decided DOFs and empty nodes; the correction sums it.
    for (std::size_t f = 0; f < field_count; ++f) {
      if (!deformable[f]) {
        continue;
      }
      const std::vector<GridNode>& nodes = grid.field_nodes(static_cast<int>(f));
      const std::vector<std::uint8_t>& mask = decided[f];
      parallel_for_box(field_box(grid, static_cast<int>(f)), grid.nodes_r(), [&](std::size_t i) {
        const GridNode& node = nodes[i];
        NodeVector& term = fields.term[f][i];
        NodeVector& s = fields.smoothed[f][i];
        if (node.mass <= step.mass_floor) {
          term = {0.0, 0.0, 0.0};
          s = {0.0, 0.0, 0.0};
          return;
        }
        // The scatter above weighs with the particles' (mixture's) masses: so must the division.
        // Coupled soil's field-0 node holds the skeleton's effective mass by now (couple_phases),
        // so it divides by the mixture's it kept; with the skeleton's, S S+ of a uniform velocity
        // was not that velocity, and XPIC(2) took 1.5 % of a saturated pulse's energy each step.
        const bool coupled = f == 0 && has_water && grid.liquid[i].mixture_mass > 0.0;
        const double mass = coupled ? grid.liquid[i].mixture_mass : node.mass;
        const double inertia = coupled ? grid.liquid[i].mixture_inertia : node.inertia;
        const double inverse[3] = {1.0 / mass, 1.0 / mass, dofs == 3 ? 1.0 / inertia : 0.0};
        NodeVector& c = fields.correction[f][i];
        for (int d = 0; d < dofs; ++d) {
          term[d] = (mask[i] & (1u << d)) != 0 ? 0.0 : term[d] - s[d] * inverse[d];
          c[d] += term[d];
          s[d] = 0.0;
        }
      });
    }
  }
}

#define MPILE_XPIC(mode, contact, shape)                                                           \
  template void extrapolate_xpic<mode, contact, shape>(const Scene&, const ParticleBins&, int,     \
                                                       const StepParameters&, XpicFields&);
MPILE_XPIC(GeometryMode::axisymmetric, false, ShapeFunctions::linear)
MPILE_XPIC(GeometryMode::axisymmetric, false, ShapeFunctions::gimp)
MPILE_XPIC(GeometryMode::axisymmetric, true, ShapeFunctions::linear)
MPILE_XPIC(GeometryMode::axisymmetric, true, ShapeFunctions::gimp)
MPILE_XPIC(GeometryMode::plane_strain, false, ShapeFunctions::linear)
MPILE_XPIC(GeometryMode::plane_strain, false, ShapeFunctions::gimp)
MPILE_XPIC(GeometryMode::plane_strain, true, ShapeFunctions::linear)
MPILE_XPIC(GeometryMode::plane_strain, true, ShapeFunctions::gimp)
#undef MPILE_XPIC

} // namespace mpile::passes
