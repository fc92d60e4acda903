// Contact between the soil and the structures (physics.md section 5) and the rigid bodies' DOFs
// (section 6). Reads and writes the velocities of field 0 and of the structure fields at nodes
// that both occupy; writes each pair's per-node forces and per-surface sums, and the rigid
// bodies' state. Every node is corrected independently, so the nodal loop runs in parallel; the
// sums use a deterministic reduction, so results do not depend on the thread count.
//
// Outline:
//   thresholds and node spacing; a rigid body's field set to its rigid motion
//   NodeDofs and PairNodes: a pair's two fields at the nodes both occupy, measured and changed
//   hold_contact_after_remap, sum_dissipation
//   the outline's normal and area at a node (single_surface, outline normals)
//   correct_nodes: the contact law at every node after the momentum balance
//   sum_surface_forces: node forces summed per surface and on the rigid body
//   resolve_pair: one pair's correction, forces and energy, after the balance and after the remap
//   the passes: prepare_contact, predict_rigid_bodies, resolve_contact, finish_rigid_bodies,
//     reset_rigid_fields, move_rigid_bodies
//   (resolve_contact_with_rigid_bodies, which calls these again, is solver/rigid_contact.cpp)
#include "solver/contact_passes.hpp"

#include "engine/parallel.hpp"
#include "engine/structures/coulomb_slip.hpp"
#include "engine/structures/surface_split.hpp"

#include <cmath>
#include <optional>
#include <span>

namespace mpile::passes {

namespace {

constexpr std::size_t max_surfaces = max_contact_surfaces;
constexpr std::uint8_t contact_free = 0;
constexpr std::uint8_t contact_slide = 1;
constexpr std::uint8_t contact_stick = 2;

/// Below this share of a node's mass a deformable structure's field is not tested for separation
/// there: the soil keeps the normal velocity of the centre of mass, pulling as well as pushing.
/// Where a structure's particle has just entered a cell, its field holds a sliver of mass at the
/// new nodes but the particle's whole stress gradient, so the field's velocity there is that
/// force over almost no mass and flips sign with it; the separation test then passed every
/// compressive impulse of the particle to the soil and withheld every tensile one, a rectifier
/// that pumped the steel pile of cases/stability/steel_pile.toml into a blow-up (the soil node
/// under its tip reached -83 m/s within 1 ms; the contact's booked dissipation went to -1e5 J).
/// Measured on that case (0.05 s, with B-bar per field): 1 % is not enough (unstable at the first
/// crossing); 5 % and 10 % run through it, energy residual 3.1 % and 3.0 % at the end. A rigid
/// field carries no stress, so it is left as it was.
constexpr double structure_bonded_share = 0.1;

/// Mean size of the cells on either side of a node along one axis.
double node_spacing(const GradedAxis& axis, int i) {
  if (i == 0) {
    return axis.cell_size(0);
  }
  if (i == axis.cell_count()) {
    return axis.cell_size(i - 1);
  }
  return 0.5 * (axis.cell_size(i - 1) + axis.cell_size(i));
}

/// Whether a velocity change is also recorded as part of the step's FLIP increment.
enum class FlipIncrement { record, skip };

/// Sets a rigid body's field to the rigid motion of DOF velocities u (its spin as every node's
/// angular velocity); the FLIP increment is the change from the velocities u_before.
void set_rigid_field(Grid& grid, const RigidBody& body, const std::array<double, 3>& u,
                     const std::array<double, 3>& u_before, double mass_floor,
                     FlipIncrement increment) {
  std::vector<GridNode>& nodes = grid.field_nodes(body.field);
  const NodeBox& reach = grid.structure_fields[static_cast<std::size_t>(body.field - 1)].reach;
  parallel_for_box(reach, grid.nodes_r(), [&](std::size_t i) {
    GridNode& node = nodes[i];
    if (node.mass <= mass_floor) {
      return;
    }
    const double r = grid.node_r(static_cast<int>(i));
    const double y = grid.node_y(static_cast<int>(i));
    const auto v = body.node_motion(u, r, y);
    if (increment == FlipIncrement::record) {
      const auto v_before = body.node_motion(u_before, r, y);
      for (std::size_t d = 0; d < 3; ++d) {
        node.velocity_increment()[d] = v[d] - v_before[d];
      }
    }
    for (std::size_t d = 0; d < 3; ++d) {
      node.velocity()[d] = v[d];
    }
  });
}

struct SurfaceSums {
  std::array<double, 4 * max_surfaces> surface{}; // (F_r, F_y, F_theta, torque) per surface
  std::array<double, 2 * max_surfaces> pore{};    // the pore pressure's (F_r, F_y) per surface
  std::array<double, 3> body{};                   // rigid DOF reactions: (F_r, F_y, moment)
};

/// The DOFs contact corrects at a node. Contact works on velocities: the theta one of a node is
/// v_theta = r omega (its unknown is the angular velocity, docs/design.md), and the inertia that
/// goes with it is J / r^2, the mass that carries the node's angular momentum J omega at its
/// radius. On the axis v_theta is zero in every field, so there is no theta slip to correct.
struct NodeDofs {
  int count;    // DOFs contact corrects at the node
  double r;     // v_theta = r omega
  double lever; // 1 / r, from a v_theta change to an omega change
};

/// One contact pair's two fields at the nodes both occupy: how contact measures the soil's
/// velocity against the structure's and how it changes both.
template <GeometryMode mode> class PairNodes {
public:
  PairNodes(Scene& scene, ContactPair& pair)
      : grid(scene.grid),
        field(scene.grid.structure_fields[static_cast<std::size_t>(pair.field - 1)]),
        soil(scene.grid.nodes), structure(scene.grid.field_nodes(pair.field)),
        held(scene.grid.field_constrained(pair.field)), rigid(pair.rigid_body >= 0) {}

  NodeDofs dofs_at(std::size_t i) const {
    const double r = grid.node_r(static_cast<int>(i));
    return has_theta(mode) && r > 0.0 ? NodeDofs{3, r, 1.0 / r} : NodeDofs{2, r, 0.0};
  }
  static double velocity(const GridNode& node, int d, const NodeDofs& at) {
    return d == 2 ? at.r * node.velocity()[2] : node.velocity()[d];
  }
  static double inertia(const GridNode& node, int d, const NodeDofs& at) {
    return d == 2 ? node.inertia * at.lever * at.lever : node.mass;
  }
  /// A rigid structure, or a constrained DOF of a deformable one, moves as prescribed: for
  /// contact it is rigid.
  bool prescribed(std::size_t i, int d) const { return rigid || (held[i] & (1u << d)) != 0; }

  /// The soil's velocity relative to what it is measured against at node i: the structure where
  /// it moves as prescribed, otherwise the centre of mass (for theta that of the angular
  /// momenta).
  std::array<double, 3> relative_velocity(std::size_t i, const NodeDofs& at, const GridNode& s,
                                          const GridNode& k) const {
    std::array<double, 3> relative{0.0, 0.0, 0.0};
    for (int d = 0; d < at.count; ++d) {
      const double v_s = velocity(s, d, at);
      const double v_k = velocity(k, d, at);
      const double m_s = inertia(s, d, at);
      const double m_k = inertia(k, d, at);
      const double reference = prescribed(i, d) ? v_k : (m_s * v_s + m_k * v_k) / (m_s + m_k);
      relative[static_cast<std::size_t>(d)] = v_s - reference;
    }
    return relative;
  }

  /// Applies a velocity change to the soil and the opposite impulse to a deformable structure's
  /// free DOFs; after the momentum balance it is also part of the FLIP increment.
  void apply(std::size_t i, const NodeDofs& at, GridNode& s, GridNode& k,
             const std::array<double, 3>& change, FlipIncrement increment) const {
    for (int d = 0; d < at.count; ++d) {
      const double to_unknown = d == 2 ? at.lever : 1.0;
      const double dv = change[static_cast<std::size_t>(d)] * to_unknown;
      s.velocity()[d] += dv;
      if (increment == FlipIncrement::record) {
        s.velocity_increment()[d] += dv;
      }
      if (!prescribed(i, d)) {
        const double dk = inertia(s, d, at) / inertia(k, d, at) * dv;
        k.velocity()[d] -= dk;
        if (increment == FlipIncrement::record) {
          k.velocity_increment()[d] -= dk;
        }
      }
    }
  }

  /// The energy the normal part of a correction takes over the step (per beta). With r0, r1 and r2
  /// the normal relative velocity at the start of the step (v^{n+1} less the increment the
  /// momentum balance left in the force slot; a rigid field's holds the change of its body's
  /// velocity), after the balance and after the correction, the node's kinetic energy goes from
  /// m r0^2 / 2 to m r2^2 / 2 relative to the structure; the balance's force works on the end
  /// velocity (as the internal work, from the strain increments, does) and the impulse on the
  /// structure's. What is left is m ((r1 - r0) r2 - (r2^2 - r0^2) / 2), times kappa = 1 where the
  /// structure's DOF moves as prescribed and 1 + m_s / m_k where both fields share the impulse
  /// (v_rel then from the centre of mass): where the gap closes (r2 = 0), the inelastic m r0^2 / 2
  /// of the approach the node brought into the step, nil for soil pushed quasi-statically. That
  /// approach comes from the particles' velocity update (FLIP's noise, XPIC's smoothing beside a
  /// footing), whose energy the transfer term books. With `pushed_after_contact` (the implicit pore
  /// pressure, which moves wall nodes after the contact and leaves the next correction to undo the
  /// push) the approach is instead the push of a force whose work the ledger has not taken, and the
  /// impulse is charged at the step's mean relative velocity, -m (r0 + r2) (r2 - r1) / 2: the
  /// push's work against the node's own force, r0 (r1 - r0) m / 2, is then booked too. (Charged so
  /// everywhere, XPIC's approach beside a footing booked the clay's resistance times half of it,
  /// 6 % of the work at a Tresca footing; booked as m r0^2 / 2 under the implicit pressure,
  /// Mandel's plate lacked 10 %: docs/verification.md, "Energy ledger".) The tangential part
  /// (friction and adhesion) is the work of the tangential force on the slip the remapped
  /// velocities make (slip_work).
  double correction_work(std::size_t i, const NodeDofs& at, const GridNode& s, const GridNode& k,
                         const std::array<double, 3>& relative, const std::array<double, 3>& change,
                         const std::array<double, 2>& n, bool pushed_after_contact) const {
    auto start_of_step = [](const GridNode& node) {
      GridNode start = node;
      for (std::size_t d = 0; d < 3; ++d) {
        start.velocity()[d] -= node.velocity_increment()[d];
      }
      return start;
    };
    const auto relative_start = relative_velocity(i, at, start_of_step(s), start_of_step(k));
    const double r0 = relative_start[0] * n[0] + relative_start[1] * n[1];
    const double r1 = relative[0] * n[0] + relative[1] * n[1];
    const double r2 = r1 + change[0] * n[0] + change[1] * n[1];
    const double per_mass = pushed_after_contact ? -0.5 * (r0 + r2) * (r2 - r1)
                                                 : (r1 - r0) * r2 - 0.5 * (r2 * r2 - r0 * r0);
    double lost = 0.0;
    for (int d = 0; d < 2; ++d) {
      const auto u = static_cast<std::size_t>(d);
      const double m_s = inertia(s, d, at);
      const double kappa = prescribed(i, d) ? 1.0 : 1.0 + m_s / inertia(k, d, at);
      lost += kappa * m_s * n[u] * n[u] * per_mass;
    }
    return lost;
  }

  /// The work over the step of a node's tangential contact force f_t (the soil's on the structure,
  /// r-y along the tangent and theta) on the slip of the remapped velocities, f_t . v_rel dt times
  /// kappa as in correction_work: what friction and adhesion dissipate. The strain increments, and
  /// so the internal work, come from the remapped velocities; the slip of the first pass is that of
  /// a node the step's force has just accelerated, which the particles do not make (at a footing
  /// whose rough base drags the clay it dissipated as much again as the energy balance lacks).
  double slip_work(std::size_t i, const NodeDofs& at, const GridNode& s, const GridNode& k,
                   const std::array<double, 3>& force, const std::array<double, 2>& n,
                   double dt) const {
    const auto relative = relative_velocity(i, at, s, k);
    const double force_n = force[0] * n[0] + force[1] * n[1];
    double work = 0.0;
    for (int d = 0; d < at.count; ++d) {
      const auto u = static_cast<std::size_t>(d);
      const double tangential = d < 2 ? force[u] - force_n * n[u] : force[u];
      const double kappa = prescribed(i, d) ? 1.0 : 1.0 + inertia(s, d, at) / inertia(k, d, at);
      work += kappa * tangential * relative[u] * dt;
    }
    return work;
  }

  const Grid& grid;
  const NodeField& field; // the structure's: its reach (both fields have mass only there)
  std::vector<GridNode>& soil;
  std::vector<GridNode>& structure;
  const std::vector<std::uint8_t>& held;
  const bool rigid;
};

/// After the remap: the nodes in contact in this step keep their kind of contact (stuck nodes
/// move with the structure, sliding ones lose their approach along the normal); a sliding node
/// adds the work of its tangential force on the slip that remains to its dissipation.
template <GeometryMode mode>
void hold_contact_after_remap(PairNodes<mode>& nodes, ContactPair& pair, double dt) {
  parallel_for_box(nodes.field.reach, nodes.grid.nodes_r(), [&](std::size_t i) {
    if (pair.state[i] == contact_free) {
      return;
    }
    GridNode& s = nodes.soil[i];
    GridNode& k = nodes.structure[i];
    const NodeDofs at = nodes.dofs_at(i);
    const auto relative = nodes.relative_velocity(i, at, s, k);
    std::array<double, 3> change{-relative[0], -relative[1], -relative[2]};
    if (pair.state[i] == contact_slide) {
      const auto& n = pair.contact_normal[i];
      const double normal_velocity = relative[0] * n[0] + relative[1] * n[1];
      change = {-normal_velocity * n[0], -normal_velocity * n[1], 0.0};
    }
    nodes.apply(i, at, s, k, change, FlipIncrement::skip);
    if (pair.state[i] == contact_slide) {
      pair.node_dissipation[i] +=
          nodes.slip_work(i, at, s, k, pair.node_force[i], pair.contact_normal[i], dt);
    }
  });
}

/// The sum of the per-node dissipations over the pair's nodes (a deterministic reduction).
double sum_dissipation(const Scene& scene, const ContactPair& pair) {
  const NodeBox& reach =
      scene.grid.structure_fields[static_cast<std::size_t>(pair.field - 1)].reach;
  const int nodes_r = scene.grid.nodes_r();
  return parallel_reduce(
      reach.count(), 0.0,
      [&](std::size_t begin, std::size_t end, double sum) {
        reach.visit(begin, end, nodes_r, [&](std::size_t i) { sum += pair.node_dissipation[i]; });
        return sum;
      },
      [](double a, double b) { return a + b; }, true, 2048);
}

/// The structure's outward normal (into the soil) at a node and the node's contact area.
struct NodeSurface {
  std::array<double, 2> normal{0.0, 0.0};
  double area = 0.0;
};

/// Whether all of a node's outline area lies on one surface (not a corner shared by two).
bool single_surface(const ContactPair& pair, std::size_t i) {
  const std::size_t surfaces = pair.surface_count();
  for (std::size_t q = 0; q < surfaces; ++q) {
    const double share = pair.surface_area[i * surfaces + q];
    if (share != 0.0) {
      return share == pair.area[i];
    }
  }
  return false;
}

/// The outline's normal and area where the node has them (inside the outline, the facing edge's
/// normal for the soil's relative velocity `relative`, and no area), or the normalised mass
/// gradient with the area of a straight surface through the node across its share of the cells.
/// None where the soil does not reach the outline yet, or where the gradient vanishes.
template <GeometryMode mode>
std::optional<NodeSurface> node_surface(const Grid& grid, const NodeField& field,
                                        const ContactPair& pair, std::size_t i,
                                        const std::array<double, 3>& relative) {
  NodeSurface at;
  if (pair.outline) {
    // On a straight run of one surface along r or y, the gap of the soil's surface at the node;
    // elsewhere (a corner shared by surfaces, a slanted face, a node inside the outline) the
    // smallest gap of its cells. (On the CPT cone's 30 degree face the interpolation along one
    // axis let the soil close on the face later: q_c at 0.1 m fell from 6.4 to 5.35 MPa.)
    const bool straight = pair.surface_gap_at_node && pair.area[i] > 0.0 &&
                          single_surface(pair, i) &&
                          (pair.normal[i][0] == 0.0 || pair.normal[i][1] == 0.0);
    const double gap = straight ? pair.surface_gap[i].at_node() : pair.gap[i];
    if (gap > 0.0) {
      return std::nullopt;
    }
    if (pair.area[i] > 0.0) {
      at.normal = pair.normal[i];
      at.area = pair.area[i];
    } else {
      at.normal = facing_edge_normal(*pair.outline, grid.node_r(static_cast<int>(i)),
                                     grid.node_y(static_cast<int>(i)), {-relative[0], -relative[1]})
                      .normal;
    }
    return at;
  }
  const auto& gradient = field.mass_gradient[i];
  const double g = std::hypot(gradient[0], gradient[1]);
  if (g == 0.0) {
    return std::nullopt;
  }
  // sum_p m_p grad N_i(x_p) points from the particles towards the node: outward at a surface.
  at.normal = {gradient[0] / g, gradient[1] / g};
  const int ir = static_cast<int>(i) % grid.nodes_r();
  const int iy = static_cast<int>(i) / grid.nodes_r();
  at.area = std::abs(at.normal[1]) * node_spacing(grid.r_axis(), ir) +
            std::abs(at.normal[0]) * node_spacing(grid.y_axis(), iy);
  if constexpr (mode == GeometryMode::axisymmetric) {
    at.area *= grid.node_r(static_cast<int>(i));
  }
  return at;
}

/// After the momentum balance: every node both fields occupy is corrected by the contact law;
/// its force, the energy the correction took and its kind of contact are recorded.
template <GeometryMode mode>
void correct_nodes(PairNodes<mode>& nodes, ContactPair& pair, const SolverSettings& settings,
                   const StepParameters& step) {
  const NodeBox& reach = nodes.field.reach;
  const double beta = settings.mass_scaling;
  const double adhesion_impulse = pair.adhesion * step.dt / beta;
  const std::vector<std::array<double, 2>>& pore_force = nodes.grid.pore_force;
  // The implicit pore pressure moves the soil at a wall after the contact (correction_work).
  const bool pushed_after_contact = settings.implicit_pore_pressure && !pore_force.empty();
  // The per-node results of the last step were written in pair.written: cleared with these.
  const NodeBox visited = NodeBox::hull(pair.written, reach);
  pair.written = reach;
  parallel_for_box(visited, nodes.grid.nodes_r(), [&](std::size_t i) {
    GridNode& s = nodes.soil[i];
    GridNode& k = nodes.structure[i];
    pair.node_force[i] = {0.0, 0.0, 0.0};
    if (!pair.node_pore_force.empty()) {
      pair.node_pore_force[i] = {0.0, 0.0};
    }
    pair.node_dissipation[i] = 0.0;
    pair.state[i] = contact_free;
    if (s.mass <= step.mass_floor || k.mass <= step.mass_floor) {
      return;
    }
    const NodeDofs at = nodes.dofs_at(i);
    const auto relative = nodes.relative_velocity(i, at, s, k);
    const std::optional<NodeSurface> surface =
        node_surface<mode>(nodes.grid, nodes.field, pair, i, relative);
    if (!surface) {
      return;
    }
    const auto& n = surface->normal;
    const double normal_velocity = relative[0] * n[0] + relative[1] * n[1];
    const bool bonded = !nodes.rigid && k.mass < structure_bonded_share * (s.mass + k.mass);
    if (normal_velocity > 0.0 && !bonded) {
      return; // separating: no tension, and no tangential force either
    }
    // Coulomb friction on the normal impulse plus adhesion over the node's area, as impulses per
    // beta (engine/structures/coulomb_slip.hpp). The theta slip has its own inertia (J / r^2, not
    // m). (The normal impulse is a pull only at a bonded node.)
    const double theta_mass = at.count == 3 ? PairNodes<mode>::inertia(s, 2, at) : s.mass;
    // Friction on the effective normal force: the pore water's share of the node's force along
    // the normal, p A where the water is uniform (physics.md section 9a).
    const double pore_impulse =
        pore_force.empty() ? 0.0
                           : (pore_force[i][0] * n[0] + pore_force[i][1] * n[1]) * step.dt / beta;
    const ContactCorrection correction =
        contact_correction(relative, n, s.mass, theta_mass, pair.friction,
                           adhesion_impulse * surface->area, pore_impulse);
    const std::array<double, 3>& change = correction.change;
    pair.node_dissipation[i] =
        beta * nodes.correction_work(i, at, s, k, relative, change, n, pushed_after_contact);
    nodes.apply(i, at, s, k, change, FlipIncrement::record);
    const double beta_per_dt = beta / step.dt;
    for (int d = 0; d < at.count; ++d) {
      const auto u = static_cast<std::size_t>(d);
      pair.node_force[i][u] = -beta_per_dt * PairNodes<mode>::inertia(s, d, at) * change[u];
    }
    const SlipKept keep = correction.keep;
    pair.state[i] = keep.plane == 0.0 && keep.theta == 0.0 ? contact_stick : contact_slide;
    if (!pair.node_pore_force.empty()) {
      const double pressure = pore_impulse * beta_per_dt; // along n, onto the structure
      pair.node_pore_force[i] = {pressure * n[0], pressure * n[1]};
    }
    pair.contact_normal[i] = n;
  });
}

/// The pair's node forces summed per surface (a node's force split over its surfaces' areas) and on
/// the rigid body's DOFs; written to the pair and its body.
void sum_surface_forces(Scene& scene, ContactPair& pair) {
  const Grid& grid = scene.grid;
  const NodeBox& reach = grid.structure_fields[static_cast<std::size_t>(pair.field - 1)].reach;
  const int nodes_r = grid.nodes_r();
  const bool rigid = pair.rigid_body >= 0;
  const std::size_t surfaces = pair.surface_count();
  const RigidBody* body =
      rigid ? &scene.rigid_bodies[static_cast<std::size_t>(pair.rigid_body)] : nullptr;
  const SurfaceSums sums = parallel_reduce(
      reach.count(), SurfaceSums{},
      [&](std::size_t begin, std::size_t end, SurfaceSums sum) {
        reach.visit(begin, end, nodes_r, [&](std::size_t i) {
          const auto& f = pair.node_force[i];
          if (f[0] == 0.0 && f[1] == 0.0 && f[2] == 0.0) {
            return;
          }
          const std::array<double, 2> pore =
              pair.node_pore_force.empty() ? std::array<double, 2>{} : pair.node_pore_force[i];
          const double r = grid.node_r(static_cast<int>(i));
          const double y = grid.node_y(static_cast<int>(i));
          const double torque = r * f[2];
          auto add = [&](std::size_t surface, double share) {
            for (std::size_t d = 0; d < 3; ++d) {
              sum.surface[4 * surface + d] += share * f[d];
            }
            sum.surface[4 * surface + 3] += share * torque;
            sum.pore[2 * surface] += share * pore[0];
            sum.pore[2 * surface + 1] += share * pore[1];
          };
          if (!pair.outline) {
            add(0, 1.0);
          } else if (pair.area[i] > 0.0) {
            // A node shared by surfaces (a tip corner): its force split as one traction over each
            // surface's part of its area (engine/structures/surface_split.hpp), so that the
            // surfaces add up to the body's force and each keeps the node's friction ratio.
            std::array<double, max_contact_surfaces> share{};
            std::array<std::array<double, 2>, max_contact_surfaces> normal{};
            std::array<std::array<double, 3>, max_contact_surfaces> part{};
            std::array<std::size_t, max_contact_surfaces> surface{};
            std::size_t shared = 0;
            for (std::size_t q = 0; q < surfaces; ++q) {
              const double s = pair.surface_area[i * surfaces + q] / pair.area[i];
              if (s == 1.0) {
                add(q, 1.0);
              } else if (s != 0.0) {
                share[shared] = s;
                normal[shared] = nearest_edge_normal(*pair.outline, r, y, static_cast<int>(q));
                surface[shared++] = q;
              }
            }
            if (shared > 0) { // not on most nodes, whose one surface took the whole force
              split_over_surfaces(f, std::span(share).first(shared),
                                  std::span<const std::array<double, 2>>(normal).first(shared),
                                  std::span(part).first(shared));
              for (std::size_t k = 0; k < shared; ++k) {
                for (std::size_t d = 0; d < 3; ++d) {
                  sum.surface[4 * surface[k] + d] += part[k][d];
                }
                sum.surface[4 * surface[k] + 3] += share[k] * torque;
              }
              if (pore[0] != 0.0 || pore[1] != 0.0) {
                // The water's pressure, as one pressure over the surfaces' parts of the area.
                split_over_surfaces({pore[0], pore[1], 0.0}, std::span(share).first(shared),
                                    std::span<const std::array<double, 2>>(normal).first(shared),
                                    std::span(part).first(shared));
                for (std::size_t k = 0; k < shared; ++k) {
                  sum.pore[2 * surface[k]] += part[k][0];
                  sum.pore[2 * surface[k] + 1] += part[k][1];
                }
              }
            }
          } else {
            // Inside the outline: the surface of the edge whose normal the contact took.
            const int surface =
                facing_edge_normal(*pair.outline, r, y, pair.contact_normal[i]).surface;
            add(static_cast<std::size_t>(surface), 1.0);
          }
          if (body != nullptr) {
            sum.body[0] += f[0];
            sum.body[1] += f[1];
            sum.body[2] += body->moment_of(f, r, y);
          }
        });
        return sum;
      },
      [](SurfaceSums a, const SurfaceSums& b) {
        for (std::size_t q = 0; q < a.surface.size(); ++q) {
          a.surface[q] += b.surface[q];
        }
        for (std::size_t q = 0; q < a.pore.size(); ++q) {
          a.pore[q] += b.pore[q];
        }
        for (std::size_t d = 0; d < 3; ++d) {
          a.body[d] += b.body[d];
        }
        return a;
      },
      true, 2048);
  for (std::size_t q = 0; q < surfaces; ++q) {
    pair.surface_force[q] = {sums.surface[4 * q], sums.surface[4 * q + 1], sums.surface[4 * q + 2]};
    pair.surface_torque[q] = sums.surface[4 * q + 3];
    pair.surface_pore_force[q] = {sums.pore[2 * q], sums.pore[2 * q + 1]};
  }
  if (rigid) {
    scene.rigid_bodies[static_cast<std::size_t>(pair.rigid_body)].contact = sums.body;
  }
}

/// After the momentum balance: the correction, the forces and the normal part of the energy it
/// took; after the remap: the same kind of correction and the tangential part. Returns the energy
/// of the pass (J [/rad]).
template <GeometryMode mode>
double resolve_pair(Scene& scene, ContactPair& pair, const SolverSettings& settings,
                    const StepParameters& step, CorrectionPass pass) {
  PairNodes<mode> nodes(scene, pair);
  if (pass == CorrectionPass::after_remap) {
    parallel_for_box(pair.written, scene.grid.nodes_r(),
                     [&](std::size_t i) { pair.node_dissipation[i] = 0.0; });
    hold_contact_after_remap(nodes, pair, step.dt);
    return sum_dissipation(scene, pair);
  }
  correct_nodes(nodes, pair, settings, step);
  sum_surface_forces(scene, pair);
  return sum_dissipation(scene, pair);
}

} // namespace

void prepare_contact(Scene& scene) {
  for (ContactPair& pair : scene.contacts) {
    if (pair.surface_count() > max_surfaces) {
      throw std::invalid_argument("contact with " + pair.name + ": more than " +
                                  std::to_string(max_surfaces) + " surfaces");
    }
    pair.allocate(scene.grid.node_count());
    pair.node_pore_force.assign(has_pore_water(scene) ? scene.grid.node_count() : 0, {0.0, 0.0});
    if (!pair.outline) {
      auto& field = scene.grid.structure_fields[static_cast<std::size_t>(pair.field - 1)];
      field.mass_gradient.assign(scene.grid.node_count(), {0.0, 0.0});
    }
  }
}

std::vector<std::array<double, 3>>
predict_rigid_bodies(Scene& scene, const SolverSettings& settings, const StepParameters& step) {
  std::vector<std::array<double, 3>> predicted;
  for (const RigidBody& body : scene.rigid_bodies) {
    predicted.push_back(body.predict(step.time, step.dt, settings.gravity, settings.mass_scaling));
    // The increment from the last step's velocity, for the contact's energy; finish_rigid_bodies
    // sets it again once the step's velocity is final.
    set_rigid_field(scene.grid, body, predicted.back(), body.velocity, step.mass_floor,
                    FlipIncrement::record);
  }
  return predicted;
}

template <GeometryMode mode>
double resolve_contact_pairs(Scene& scene, const SolverSettings& settings,
                             const StepParameters& step, CorrectionPass pass) {
  double dissipation = 0.0;
  for (ContactPair& pair : scene.contacts) {
    dissipation += resolve_pair<mode>(scene, pair, settings, step, pass);
  }
  return dissipation;
}

void set_rigid_motion(Grid& grid, const RigidBody& body, const std::array<double, 3>& u,
                      double mass_floor) {
  set_rigid_field(grid, body, u, body.velocity, mass_floor, FlipIncrement::record);
}

template <GeometryMode mode>
double resolve_contact(Scene& scene, const SolverSettings& settings, const StepParameters& step,
                       CorrectionPass pass) {
  if (pass == CorrectionPass::after_balance) {
    for (ContactPair& pair : scene.contacts) {
      if (pair.outline) {
        integrate_outline(scene.grid, mode, pair);
      }
    }
  }
  return resolve_contact_pairs<mode>(scene, settings, step, pass);
}

void finish_rigid_bodies(Scene& scene, const SolverSettings& settings, const StepParameters& step,
                         const std::vector<std::array<double, 3>>& predicted) {
  for (std::size_t b = 0; b < scene.rigid_bodies.size(); ++b) {
    RigidBody& body = scene.rigid_bodies[b];
    const std::array<double, 3> before = body.velocity;
    body.finish_step(predicted[b], step.time, step.dt, settings.gravity, settings.mass_scaling);
    set_rigid_field(scene.grid, body, body.velocity, before, step.mass_floor,
                    FlipIncrement::record);
  }
}

void reset_rigid_fields(Scene& scene, const StepParameters& step) {
  for (const RigidBody& body : scene.rigid_bodies) {
    set_rigid_field(scene.grid, body, body.velocity, body.velocity, step.mass_floor,
                    FlipIncrement::skip);
  }
}

void move_rigid_bodies(Scene& scene, const StepParameters& step) {
  for (ContactPair& pair : scene.contacts) {
    if (pair.rigid_body < 0) {
      continue;
    }
    RigidBody& body = scene.rigid_bodies[static_cast<std::size_t>(pair.rigid_body)];
    if (pair.outline) {
      if (body.mode == GeometryMode::plane_strain) {
        pair.outline->rotate(body.velocity[RIGID_ROTATION] * step.dt, body.centre[0],
                             body.centre[1]);
        pair.outline->translate(body.velocity[RIGID_X] * step.dt, body.velocity[RIGID_Y] * step.dt);
      } else {
        pair.outline->translate(0.0, body.velocity[RIGID_Y] * step.dt);
      }
    }
    body.move_centre(step.dt);
  }
}

template double resolve_contact_pairs<GeometryMode::axisymmetric>(Scene&, const SolverSettings&,
                                                                  const StepParameters&,
                                                                  CorrectionPass);
template double resolve_contact_pairs<GeometryMode::plane_strain>(Scene&, const SolverSettings&,
                                                                  const StepParameters&,
                                                                  CorrectionPass);
template double resolve_contact<GeometryMode::axisymmetric>(Scene&, const SolverSettings&,
                                                            const StepParameters&, CorrectionPass);
template double resolve_contact<GeometryMode::plane_strain>(Scene&, const SolverSettings&,
                                                            const StepParameters&, CorrectionPass);

} // namespace mpile::passes
