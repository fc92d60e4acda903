// Absorbing faces (engine/absorbing_boundary.hpp). Reads node mass, rotational inertia, velocity,
// velocity increment and the constrained-DOF mask of the soil's field; writes the holding forces
// into the node forces (before the momentum balance) and the dashpots' share of the velocity and
// its increment (after it). Face node sets are small, so this runs serially, which also fixes the
// summation order of the energies.
#include "solver/passes.hpp"

#include <algorithm>
#include <cmath>

namespace mpile::passes {

namespace {

/// Node k's share of the weights of the segments beside it.
double node_weight(const std::vector<std::array<double, 2>>& weights, std::size_t k) {
  return (k > 0 ? weights[k - 1][1] : 0.0) + (k < weights.size() ? weights[k][0] : 0.0);
}

} // namespace

std::vector<FaceNodeTerms> absorbing_face_terms(const Scene& scene) {
  const Grid& grid = scene.grid;
  const WeightPowers powers = weight_powers(scene.mode);
  const bool theta = has_theta(scene.mode);
  std::vector<FaceNodeTerms> terms;
  for (const AbsorbingFace& face : scene.boundaries.absorbing) {
    if (!face.active || face.nodes.size() < 2) {
      continue;
    }
    const auto force_w = segment_weights(grid, face, powers.force);
    const auto dashpot_w = theta ? segment_weights(grid, face, powers.theta_dashpot) : force_w;
    const auto torque_w = theta ? segment_weights(grid, face, powers.theta_torque) : force_w;
    const int normal = face_normal(face.face);
    const std::size_t first = terms.size();
    for (std::size_t k = 0; k < face.nodes.size(); ++k) {
      FaceNodeTerms t;
      t.node = face.nodes[k];
      const std::array<double, 3> traction = holding_traction_now(grid, face, k);
      const double w = node_weight(force_w, k);
      t.holding = {w * traction[0], w * traction[1],
                   theta ? node_weight(torque_w, k) * traction[2] : 0.0};
      terms.push_back(t);
    }
    // Each segment's dashpots: rho c_p on the normal DOF, rho c_s on the tangential and theta.
    for (std::size_t j = 0; j + 1 < face.nodes.size(); ++j) {
      const auto [p_impedance, s_impedance] = segment_impedance(grid, face, j);
      for (std::size_t side = 0; side < 2; ++side) {
        FaceNodeTerms& t = terms[first + j + side];
        for (int d = 0; d < 2; ++d) {
          t.dashpot[static_cast<std::size_t>(d)] +=
              (d == normal ? p_impedance : s_impedance) * force_w[j][side];
        }
        if (theta) {
          t.dashpot[2] += s_impedance * dashpot_w[j][side];
        }
      }
    }
  }
  std::stable_sort(terms.begin(), terms.end(),
                   [](const FaceNodeTerms& a, const FaceNodeTerms& b) { return a.node < b.node; });
  std::vector<FaceNodeTerms> merged;
  for (const FaceNodeTerms& t : terms) {
    if (!merged.empty() && merged.back().node == t.node) {
      for (std::size_t d = 0; d < 3; ++d) {
        merged.back().dashpot[d] += t.dashpot[d];
        merged.back().holding[d] += t.holding[d];
      }
    } else {
      merged.push_back(t);
    }
  }
  return merged;
}

double apply_holding_tractions(Scene& scene, const std::vector<FaceNodeTerms>& terms,
                               const StepParameters& step) {
  double squares = 0.0;
  Grid& grid = scene.grid;
  const int dofs = has_theta(scene.mode) ? 3 : 2;
  for (const FaceNodeTerms& t : terms) {
    GridNode& node = grid.nodes[static_cast<std::size_t>(t.node)];
    if (node.mass <= step.mass_floor) {
      continue;
    }
    for (int d = 0; d < dofs; ++d) {
      // A DOF still held by a support (the axis) takes its force from the support.
      if ((grid.constrained[static_cast<std::size_t>(t.node)] & (1u << d)) == 0) {
        const double f = t.holding[static_cast<std::size_t>(d)];
        node.force[d] += f;
        squares += f * f * (d == 2 ? node.mass / node.inertia : 1.0);
      }
    }
  }
  return squares;
}

AbsorbedWork absorb_at_faces(Scene& scene, const std::vector<FaceNodeTerms>& terms,
                             const SolverSettings& settings, const StepParameters& step) {
  AbsorbedWork work;
  Grid& grid = scene.grid;
  const int dofs = has_theta(scene.mode) ? 3 : 2;
  // Mass scaling multiplies the density by beta and divides the wave speeds by sqrt(beta): the
  // impedance rho c grows by sqrt(beta).
  const double impedance_scale = std::sqrt(settings.mass_scaling);
  const double dt_over_beta = step.dt / settings.mass_scaling;
  for (const FaceNodeTerms& t : terms) {
    GridNode& node = grid.nodes[static_cast<std::size_t>(t.node)];
    if (node.mass <= step.mass_floor) {
      continue;
    }
    for (int d = 0; d < dofs; ++d) {
      if ((grid.constrained[static_cast<std::size_t>(t.node)] & (1u << d)) != 0) {
        continue;
      }
      const auto dof = static_cast<std::size_t>(d);
      const double dashpot = impedance_scale * t.dashpot[dof];
      const double inertia = d == 2 ? node.inertia : node.mass;
      // The dashpot force -C v^{n+1} taken implicitly: beta m (v^{n+1} - v^n) = dt (f - C v^{n+1})
      // gives v^{n+1} = v* / (1 + dt C / (beta m)) from the velocity v* the momentum balance
      // reached without it, stable for any C (an explicit dashpot needs dt < 2 beta m / C, which
      // a boundary node holding a sliver of soil would break).
      const double before = node.velocity()[d] - node.velocity_increment()[d];
      const double after = node.velocity()[d] / (1.0 + dt_over_beta * dashpot / inertia);
      node.velocity()[d] = after;
      node.velocity_increment()[d] = after - before;
      // The dashpot's work at the mean velocity over the step; the holding force's as a load's.
      work.radiated += dashpot * after * 0.5 * (before + after) * step.dt;
      work.holding += t.holding[dof] * after * step.dt;
    }
  }
  return work;
}

void switch_on_absorbing_faces(Scene& scene, const std::vector<std::size_t>& faces,
                               const StepParameters& step) {
  Grid& grid = scene.grid;
  const WeightPowers powers = weight_powers(scene.mode);
  const bool theta = has_theta(scene.mode);
  // The supports of the faces give way to the dashpots (the axis keeps its own).
  for (const std::size_t f : faces) {
    scene.boundaries.absorbing[f].active = true;
  }
  scene.boundaries.release_absorbing_supports();
  scene.boundaries.mark_constrained_dofs(grid);
  // A node on several faces switching on together (a corner) shares its holding force out.
  std::vector<int> all_nodes;
  for (const std::size_t f : faces) {
    const auto& nodes = scene.boundaries.absorbing[f].nodes;
    all_nodes.insert(all_nodes.end(), nodes.begin(), nodes.end());
  }
  std::sort(all_nodes.begin(), all_nodes.end());
  for (const std::size_t f : faces) {
    AbsorbingFace& face = scene.boundaries.absorbing[f];
    sample_face_impedance(scene, face);
    const auto force_w = segment_weights(grid, face, powers.force);
    const auto torque_w = theta ? segment_weights(grid, face, powers.theta_torque) : force_w;
    face.holding_traction.assign(face.nodes.size(), {0.0, 0.0, 0.0});
    for (std::size_t k = 0; k < face.nodes.size(); ++k) {
      const auto index = static_cast<std::size_t>(face.nodes[k]);
      const GridNode& node = grid.nodes[index];
      if (node.mass <= step.mass_floor) {
        continue;
      }
      const auto [low, high] = std::equal_range(all_nodes.begin(), all_nodes.end(), face.nodes[k]);
      const double share = 1.0 / static_cast<double>(high - low);
      for (int d = 0; d < (theta ? 3 : 2); ++d) {
        const double w = d == 2 ? node_weight(torque_w, k) : node_weight(force_w, k);
        // The node force is f_ext - f_int of the state now: the face holds it with the opposite.
        if ((grid.constrained[index] & (1u << d)) == 0 && w > 0.0) {
          face.holding_traction[k][static_cast<std::size_t>(d)] = -share * node.force[d] / w;
        }
      }
    }
  }
}

} // namespace mpile::passes
