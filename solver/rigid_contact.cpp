// A force-driven rigid DOF and the contact correction of the soil it touches, solved together
// (physics.md section 6): the soil at a contact node is corrected to the velocity u the body ends
// the step with, and u closes the body's step with the reaction that correction gives it. The
// correction is evaluated again from the same start (CorrectedNodes) at each DOF's next guess
// (DofRoot: regula falsi, Illinois), to rounding; other DOFs keep their prediction.
#include "solver/contact_passes.hpp"

#include <cmath>
#include <vector>

namespace mpile::passes {

namespace {

/// Whether DOF d of a body is driven by a force (its velocity then follows from the reaction).
bool force_driven(const RigidBody& body, int d) {
  return body.has_dof(d) && body.drive[static_cast<std::size_t>(d)].kind == RigidDrive::Kind::force;
}

/// The nodes a contact correction writes, kept to evaluate it again from the same start: the soil's
/// over every pair's reach and each deformable structure's over its own.
class CorrectedNodes {
public:
  explicit CorrectedNodes(Grid& grid) : grid_(grid) {}
  void save(const Scene& scene) {
    for (const ContactPair& pair : scene.contacts) {
      const NodeBox& reach = grid_.structure_fields[static_cast<std::size_t>(pair.field - 1)].reach;
      soil_box_ = NodeBox::hull(soil_box_, reach);
      if (pair.rigid_body < 0) {
        fields_.push_back({pair.field, reach, copy(grid_.field_nodes(pair.field), reach)});
      }
    }
    soil_ = copy(grid_.nodes, soil_box_);
  }
  void restore() {
    paste(soil_, grid_.nodes, soil_box_);
    for (const Saved& field : fields_) {
      paste(field.nodes, grid_.field_nodes(field.field), field.box);
    }
  }

private:
  struct Saved {
    int field;
    NodeBox box;
    std::vector<GridNode> nodes;
  };
  std::vector<GridNode> copy(const std::vector<GridNode>& from, const NodeBox& box) const {
    std::vector<GridNode> kept;
    kept.reserve(box.count());
    box.visit(0, box.count(), grid_.nodes_r(), [&](std::size_t i) { kept.push_back(from[i]); });
    return kept;
  }
  void paste(const std::vector<GridNode>& kept, std::vector<GridNode>& to,
             const NodeBox& box) const {
    std::size_t k = 0;
    box.visit(0, box.count(), grid_.nodes_r(), [&](std::size_t i) { to[i] = kept[k++]; });
  }
  Grid& grid_;
  NodeBox soil_box_;
  std::vector<GridNode> soil_;
  std::vector<Saved> fields_;
};

/// The root of one force-driven DOF's residual g(u) = u - u_pred - dt R(u) / (beta M): the
/// velocity the DOF ends the step with equals the one the soil was corrected to. The soil's
/// reaction R falls as u moves into it, so g rises with a slope of at least 1; the fixed-point
/// step from u_pred (slope 1) overshoots the root or meets it, and the two bracket it. Then
/// regula falsi with the Illinois halving: exact in one step where the contact set does not
/// change (g is linear there), and safe where it does.
struct DofRoot {
  double below = 0.0, g_below = 0.0; // g < 0
  double above = 0.0, g_above = 0.0; // g > 0
  bool has_below = false, has_above = false;
  int last_side = 0; // -1 below, +1 above: the side the last evaluation replaced

  /// Takes the residual at u and returns the next guess.
  double next(double u, double g) {
    const int side = g < 0.0 ? -1 : 1;
    if (side < 0) {
      below = u;
      g_below = g;
      has_below = true;
    } else {
      above = u;
      g_above = g;
      has_above = true;
    }
    if (!(has_below && has_above)) {
      last_side = side;
      return u - g; // the fixed-point step
    }
    if (side == last_side) {
      // The same end moved twice: halve the other's weight (Illinois), so that it moves too.
      (side < 0 ? g_above : g_below) *= 0.5;
    }
    last_side = side;
    return above - g_above * (above - below) / (g_above - g_below);
  }
};

} // namespace

template <GeometryMode mode>
double resolve_contact_with_rigid_bodies(Scene& scene, const SolverSettings& settings,
                                         const StepParameters& step,
                                         const std::vector<std::array<double, 3>>& predicted) {
  bool iterate = false;
  for (const RigidBody& body : scene.rigid_bodies) {
    for (int d = 0; d < 3; ++d) {
      iterate = iterate || force_driven(body, d);
    }
  }
  if (!iterate) {
    return resolve_contact<mode>(scene, settings, step, CorrectionPass::after_balance);
  }
  // A force-driven DOF's velocity at the end of the step depends on the reaction of the soil
  // the correction gives it, and the soil must be corrected to that same velocity: with the
  // prediction instead, the soil under a body pushed by a constant force moved at the body's
  // unresisted velocity while the body itself moved at the resisted one, and a plate on an
  // elastic layer sank without end (docs/verification.md, the plate under a force).
  CorrectedNodes start(scene.grid);
  start.save(scene);
  std::vector<std::array<double, 3>> u = predicted;
  std::vector<std::array<DofRoot, 3>> roots(scene.rigid_bodies.size());
  constexpr int max_evaluations = 40;
  double dissipated = 0.0;
  for (int evaluation = 1;; ++evaluation) {
    for (std::size_t b = 0; b < scene.rigid_bodies.size(); ++b) {
      set_rigid_motion(scene.grid, scene.rigid_bodies[b], u[b], step.mass_floor);
    }
    // The outlines' nodal areas do not change within the step: integrated at the first only.
    dissipated =
        evaluation == 1
            ? resolve_contact<mode>(scene, settings, step, CorrectionPass::after_balance)
            : resolve_contact_pairs<mode>(scene, settings, step, CorrectionPass::after_balance);
    bool converged = true;
    for (std::size_t b = 0; b < scene.rigid_bodies.size(); ++b) {
      const RigidBody& body = scene.rigid_bodies[b];
      for (int d = 0; d < 3; ++d) {
        if (!force_driven(body, d)) {
          continue;
        }
        const auto k = static_cast<std::size_t>(d);
        const double m = settings.mass_scaling * (d == RIGID_ROTATION ? body.inertia : body.mass);
        const double closed = predicted[b][k] + step.dt * body.contact[k] / m;
        const double g = u[b][k] - closed;
        // Converged to rounding against the velocities in play (the step's change included).
        const double scale =
            std::abs(u[b][k]) + std::abs(closed) + std::abs(predicted[b][k] - body.velocity[k]);
        if (std::abs(g) <= 1e-12 * scale) {
          continue;
        }
        converged = false;
        u[b][k] = roots[b][k].next(u[b][k], g);
      }
    }
    if (converged || evaluation == max_evaluations) {
      return dissipated;
    }
    start.restore();
  }
}

template double resolve_contact_with_rigid_bodies<GeometryMode::axisymmetric>(
    Scene&, const SolverSettings&, const StepParameters&,
    const std::vector<std::array<double, 3>>&);
template double resolve_contact_with_rigid_bodies<GeometryMode::plane_strain>(
    Scene&, const SolverSettings&, const StepParameters&,
    const std::vector<std::array<double, 3>>&);

} // namespace mpile::passes
