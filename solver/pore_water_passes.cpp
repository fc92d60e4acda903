// The pore water of coupled soil (physics.md section 9b): two-phase single-point MPM in the
// velocity form Anura3D implements (each material point carries the skeleton's velocity v and the
// water's w; Jassim, Stolle and Vermeer 2013). Per unit volume, with n the porosity, rho_w the
// water's density, p the pore pressure (tension positive) and sigma the total stress:
//   water:    rho_w a_w = grad p + rho_w g - (n rho_w g / k) (w - v)
//   mixture:  (1 - n) rho_s a_v + n rho_w a_w = div sigma + rho_sat g
//   pressure: dp = (K_w / n) ((1 - n) div v + n div w) dt
// The passes, in step order:
//   map_water_to_grid       reads the coupled particles' water state; writes Grid::liquid
//   couple_phases           field 0's node becomes the skeleton's, with the water's inertia and
//                           drag folded into an effective mass and force (the drag implicit, so
//                           it sets no time step); at a structure's wall the phases are tied
//   update_water_velocities after the skeleton's supports and contact: w^{n+1} from the skeleton's
//                           v^{n+1}, the drag again implicit
//   update_water_particle_velocities  the particles' w (FLIP/PIC, as the skeleton's v, their own
//                           relative flow relaxed by the drag; under XPIC(m) the water's own
//                           field's, solver/water_xpic.cpp)
//   rescale_remapped_skeleton, remap_water  MUSL: both phases' nodal velocities from the
//                           particles' (the skeleton's remap weighted by the mixture's masses)
//   pore_pressure_from_flow the pore pressure's share from div w, from the velocities the
//                           stress pass reads, held until ...
//   apply_pore_pressure_from_flow  ... the stress pass has used the stress at the step's start
// A scene without coupled soil runs none of them.
#include "engine/materials/pore_water.hpp"
#include "engine/parallel.hpp"
#include "engine/shape_functions.hpp"
#include "solver/cell_slots.hpp"
#include "solver/passes.hpp"
#include "solver/xpic.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <vector>

namespace mpile::passes {

namespace {

/// Calls f(i, phase, state) for each particle of coupled soil among `particles`, state its own.
template <class F>
void for_each_coupled(std::span<const std::int32_t> particles, Particles& p,
                      const std::vector<const LiquidPhase*>& phases, F&& f) {
  const auto stride = static_cast<std::size_t>(p.state_stride);
  for (const std::int32_t q : particles) {
    const auto i = static_cast<std::size_t>(q);
    if (const LiquidPhase* phase = phases[p.material[i]]) {
      f(i, *phase, p.state.data() + i * stride);
    }
  }
}

} // namespace

std::vector<const LiquidPhase*> liquid_phases(const Scene& scene) {
  std::vector<const LiquidPhase*> phases;
  for (const auto& material : scene.materials) {
    phases.push_back(material->liquid_phase());
  }
  return phases;
}

template <GeometryMode mode, ShapeFunctions shape>
void map_water_to_grid(Scene& scene, const ParticleBins& bins,
                       const std::vector<const LiquidPhase*>& phases,
                       const SolverSettings& settings) {
  Grid& grid = scene.grid;
  grid.liquid.resize(grid.nodes.size());
  parallel_for(grid.liquid.size(), [&](std::size_t i) { grid.liquid[i] = LiquidNode{}; });
  Particles& p = scene.particles;
  const double g_r = settings.gravity[0];
  const double g_y = settings.gravity[1];
  const auto stride = static_cast<std::size_t>(p.state_stride);
  const bool consistent = settings.bbar_consistent_force; // validated: only with B-bar
  bins.for_each_block_colored([&](int block, std::span<const std::int32_t> particles) {
    // With B-bar the water's divergence is its cell's volume-weighted mean (pore_pressure_from_
    // flow); B-bar's consistent force takes the cell's mean pore pressure for the water, as the
    // mixture's takes the cell's mean stress (bbar_mean_stress_shift).
    thread_local std::vector<std::array<double, 2>> cell_pressure;
    const auto [cr0, cy0] = bins.block_origin(block);
    const CellSlots<false> cell_of{scene, p, cr0, cy0, bins.block_cells(), false};
    if (consistent) {
      cell_pressure.assign(cell_of.cells(), {0.0, 0.0});
      for (const std::int32_t q : particles) {
        const auto i = static_cast<std::size_t>(q);
        if (const LiquidPhase* phase = phases[p.material[i]]) {
          auto& sum = cell_pressure[cell_of(i)];
          sum[0] += p.volume[i] * p.state[i * stride + static_cast<std::size_t>(phase->pore_slot)];
          sum[1] += p.volume[i];
        }
      }
    }
    for_each_coupled(
        particles, p, phases, [&](std::size_t i, const LiquidPhase& phase, const double* state) {
          const double n = state[phase.porosity_slot];
          const double* w = state + phase.velocity_slot;
          const double water_mass = phase.water_fraction(n) * p.mass[i];
          const double inertia = water_mass / n; // rho_w V
          const double drag = water_mass * phase.drag_per_mass;
          // The pore pressure's share of the water's internal force, as the particle-to-grid pass
          // takes the total stress's, with sigma = p 1.
          double pressure = state[phase.pore_slot];
          if (consistent) {
            const auto& sum = cell_pressure[cell_of(i)];
            pressure = sum[0] / sum[1];
          }
          const double weighted = p.volume[i] * pressure;
          const double hoop = has_theta(mode) ? weighted / p.r[i] : 0.0;
          const auto weights = particle_weights<shape>(grid, p, i);
          for (int k = 0; k < weights.size; ++k) {
            LiquidNode& node = grid.liquid[static_cast<std::size_t>(weights.node[k])];
            const double N = weights.N[k];
            node.mass += N * inertia;
            node.share += N * water_mass;
            node.drag += N * drag;
            node.momentum[0] += N * inertia * w[0];
            node.momentum[1] += N * inertia * w[1];
            node.force[0] += N * inertia * g_r - (weights.dN_dr[k] * weighted + N * hoop);
            node.force[1] += N * inertia * g_y - weights.dN_dy[k] * weighted;
            node.skeleton_momentum[0] += N * water_mass * p.v_r[i];
            node.skeleton_momentum[1] += N * water_mass * p.v_y[i];
          }
          if constexpr (has_theta(mode)) {
            // The theta DOF is angular, as the skeleton's: the water's angular momentum and its
            // three rotational inertias. The pore pressure exerts no torque.
            const double r = p.r[i];
            for (int k = 0; k < weights.size; ++k) {
              LiquidNode& node = grid.liquid[static_cast<std::size_t>(weights.node[k])];
              const double N = weights.N[k];
              node.momentum[2] += N * inertia * r * w[2];
              node.inertia += N * inertia * r * r;
              node.share_inertia += N * water_mass * r * r;
              node.drag_inertia += N * drag * r * r;
              node.skeleton_momentum[2] += N * water_mass * r * p.v_theta[i];
            }
          }
        });
  });
}

namespace {

/// One DOF of the coupled balance at a node. The water's update with the drag at the new
/// velocities, (M_w + dt Q) w' = M_w w + dt F_w + dt Q v', put into the mixture's, M_s (v' - v) +
/// M_nw (w' - w) = dt F, leaves the skeleton's own balance with an effective mass and force:
///   M* = M_s + M_nw dt Q / D,  F* = F - (M_nw / D) (F_w - Q (w - v)),  D = M_w + dt Q,
/// so that v' = v + dt F* / M*. With k -> 0 the phases move together (M* -> M_s + M_nw); with
/// k -> infinity the skeleton feels the water only through the pore pressure in F.
struct EffectiveDof {
  double mass;
  double force;
};
inline EffectiveDof effective_dof(double skeleton_mass, double share, double water_mass,
                                  double drag, double force, double water_force, double v, double w,
                                  double dt, double beta) {
  // Mass scaling beta multiplies both phases' inertia and leaves the drag: the grid update divides
  // the effective force by beta times the mass returned here, so the drag enters as dt Q / beta.
  const double d = water_mass + dt * drag / beta;
  return {skeleton_mass + share * dt * drag / beta / d,
          force - share / d * (water_force - drag * (w - v))};
}

} // namespace

template <GeometryMode mode>
CoupledPhasesResult couple_phases(Scene& scene, const StepParameters& step, double beta) {
  Grid& grid = scene.grid;
  const bool structures = !grid.structure_fields.empty();
  const bool drains = !grid.water_drained.empty();
  return parallel_reduce(
      grid.liquid.size(), CoupledPhasesResult{},
      [&](std::size_t begin, std::size_t end, CoupledPhasesResult result) {
        double& merged = result.tied_drag;
        for (std::size_t i = begin; i < end; ++i) {
          LiquidNode& water = grid.liquid[i];
          if (!(water.mass > 0.0)) {
            continue;
          }
          GridNode& node = grid.nodes[i];
          const double skeleton_mass = node.mass - water.share;
          if (!(skeleton_mass > step.mass_floor)) {
            // Every particle brings its grains with its water, so only round-off leaves a node
            // here.
            for (int d = 0; d < 3; ++d) {
              water.velocity()[d] = 0.0;
            }
            continue;
          }
          water.mixture_mass = node.mass;
          water.mixture_inertia = node.inertia;
          // At a structure's wall the water cannot flow into the wall, and the contact corrects
          // the node as a whole: the phases move as one there (Darcy's drag taken as infinite),
          // so that the contact sees the mixture's mass and total force, as in undrained soil,
          // and the structure takes the water's pressure with the skeleton's. Tying them merges
          // their momenta; the kinetic energy that takes is the drag's.
          const bool tied = structures && grid.structure_occupies(i, step.mass_floor);
          double mass = skeleton_mass;
          for (int d = 0; d < 2; ++d) {
            const double v = (node.momentum[d] - water.skeleton_momentum[d]) / skeleton_mass;
            double w = water.momentum[d] / water.mass;
            if (drains && (grid.water_drained[i] & (1u << d)) != 0) {
              // The drain keeps the water velocity it ended the last step with (Grid::
              // drain_water_velocity); update_water_velocities books the jump's work.
              const double kept = grid.drain_water_velocity[i][static_cast<std::size_t>(d)];
              water.drain_jump[d] = 0.0;
              if (std::isfinite(kept)) {
                water.drain_jump[d] = kept - w;
                w = kept;
              }
            }
            water.velocity()[d] = w;
            if (tied) {
              mass = node.mass;
              node.momentum[d] = mass * v;
              node.force[d] += beta * water.share * (w - v) / step.dt;
              // Booked once the contact has said whether the water stays tied along this DOF.
              water.tie_merged[d] =
                  beta * 0.5 * skeleton_mass * water.share / mass * (w - v) * (w - v);
              continue;
            }
            const EffectiveDof dof =
                effective_dof(skeleton_mass, water.share, water.mass, water.drag, node.force[d],
                              water.force[d], v, w, step.dt, beta);
            mass = dof.mass; // the same for r and y
            node.momentum[d] = dof.mass * v;
            node.force[d] = dof.force;
          }
          node.mass = mass;
          if constexpr (has_theta(mode)) {
            const double skeleton_inertia = node.inertia - water.share_inertia;
            const double omega = (node.momentum[2] - water.skeleton_momentum[2]) / skeleton_inertia;
            const double omega_w = water.momentum[2] / water.inertia;
            water.velocity()[2] = omega_w;
            if (tied) {
              node.momentum[2] = node.inertia * omega;
              node.force[2] += beta * water.share_inertia * (omega_w - omega) / step.dt;
              merged += beta * 0.5 * skeleton_inertia * water.share_inertia / node.inertia *
                        (omega_w - omega) * (omega_w - omega);
              continue;
            }
            const EffectiveDof dof = effective_dof(skeleton_inertia, water.share_inertia,
                                                   water.inertia, water.drag_inertia, node.force[2],
                                                   water.force[2], omega, omega_w, step.dt, beta);
            node.inertia = dof.mass;
            node.momentum[2] = dof.mass * omega;
            node.force[2] = dof.force;
          }
        }
        return result;
      },
      [](CoupledPhasesResult a, const CoupledPhasesResult& b) {
        a.tied_drag += b.tied_drag;
        a.drain_work += b.drain_work;
        return a;
      },
      true);
}

namespace {

/// The DOFs (r, y) along which the wall at node i runs on a grid line: a contact there this step
/// whose normal has no component along the DOF (a shaft's face along y, a plate's underside along
/// r), the skeleton not held along it. Elsewhere at a wall (a cone, a corner, a structure in
/// reach but not touching) the water keeps to the skeleton in both directions.
std::uint8_t wall_free_dofs(const Scene& scene, const Grid& grid, std::size_t i) {
  for (const ContactPair& pair : scene.contacts) {
    if (pair.state.size() <= i || pair.state[i] == 0) {
      continue;
    }
    const auto& n = pair.contact_normal[i];
    std::uint8_t free = 0;
    for (int d = 0; d < 2; ++d) {
      const bool along = std::abs(n[static_cast<std::size_t>(d)]) <= 1e-9 &&
                         std::abs(n[static_cast<std::size_t>(1 - d)]) >= 1.0 - 1e-9;
      // A held skeleton DOF along the wall (a drained face beside it) lets the water past only
      // if it is drained.
      const bool held = (grid.constrained[i] & (1u << d)) != 0;
      const bool drained = !grid.water_drained.empty() && (grid.water_drained[i] & (1u << d)) != 0;
      if (along && (!held || drained)) {
        free |= static_cast<std::uint8_t>(1u << d);
      }
    }
    return free;
  }
  return 0;
}

/// Along a wall the water flows past the skeleton (the wall is impermeable across, not along):
/// the contact has settled the mixture's momentum P = M v along DOF d, which the two phases now
/// share as the water's own balance with the drag at the new velocities asks,
///   M_w (w' - w) = dt (F_w - Q (w' - v')),  M_s v' + M_nw w' = P,
/// so the structure's impulse, friction included, is the mixture's, as when tied.
void split_along_wall(LiquidNode& water, GridNode& node, int d, double dt, double dt_over_beta,
                      WaterVelocityResult& result) {
  const auto k = static_cast<std::size_t>(d);
  const double share = water.share;
  const double skeleton_mass = water.mixture_mass - share;
  const double momentum = node.mass * node.velocity()[k];
  const double w = water.velocity()[k];
  const double q = dt_over_beta * water.drag;
  const double w_new =
      (water.mass * w + dt_over_beta * water.force[k] + q * momentum / skeleton_mass) /
      (water.mass + q * (1.0 + share / skeleton_mass));
  const double v_new = (momentum - share * w_new) / skeleton_mass;
  node.velocity_increment()[k] += v_new - node.velocity()[k];
  node.velocity()[k] = v_new;
  water.held_force[k] = 0.0;
  // Darcy's drag at the velocities it acts on, as at any node; the tie's merged energy is not
  // booked along this DOF, the phases having parted again.
  result.drag += share / water.mass * water.drag * (w_new - v_new) * (w_new - v_new) * dt;
  water.velocity()[k] = w_new;
  water.velocity_increment()[k] = w_new - w;
}

} // namespace

template <GeometryMode mode>
WaterVelocityResult update_water_velocities(Scene& scene, const StepParameters& step, double beta) {
  constexpr int dofs = has_theta(mode) ? 3 : 2;
  Grid& grid = scene.grid;
  const double dt = step.dt;
  const double dt_over_beta = dt / beta; // the water's inertia scaled as the skeleton's
  const bool structures = !grid.structure_fields.empty();
  const bool drains = !grid.water_drained.empty();
  auto update = [&](std::size_t begin, std::size_t end, WaterVelocityResult result) {
    for (std::size_t i = begin; i < end; ++i) {
      LiquidNode& water = grid.liquid[i];
      GridNode& node = grid.nodes[i];
      if (!(water.mass > 0.0) || node.mass <= step.mass_floor) {
        water = LiquidNode{};
        if (drains) {
          grid.drain_water_velocity[i] = {std::nan(""), std::nan(""), std::nan("")};
        }
        continue;
      }
      const double mass[3] = {water.mass, water.mass, water.inertia};
      const double porosity = water.share / water.mass;
      // A structure's wall is impermeable: where one has mass the water keeps to the skeleton,
      // which the contact has just kept out of the wall (the wall's tangential drag on the water
      // is left out: water has no friction).
      const bool at_wall = structures && grid.structure_occupies(i, step.mass_floor);
      water.wall_free = at_wall ? wall_free_dofs(scene, grid, i) : 0;
      const double drag[3] = {water.drag, water.drag, water.drag_inertia};
      for (int d = 0; d < dofs; ++d) {
        const bool along_wall = at_wall && d < 2 && (water.wall_free & (1u << d)) != 0;
        if (along_wall && (grid.constrained[i] & (1u << d)) == 0) {
          split_along_wall(water, node, d, dt, dt_over_beta, result);
          continue;
        }
        const bool tied = at_wall && !along_wall; // along a held, drained DOF: as at a drain
        if (tied && d < 2) {
          result.tied_drag += water.tie_merged[d];
        }
        const double v = node.velocity()[d];
        const double w = water.velocity()[d];
        const double held = mass[d] + dt_over_beta * drag[d];
        double w_new =
            (mass[d] * w + dt_over_beta * water.force[d] + dt_over_beta * drag[d] * v) / held;
        // A face that holds the skeleton is impermeable: the water keeps to the skeleton's normal
        // velocity there (the theta DOF is a direction along every face). The skeleton's support
        // booked the mixture's reaction as if the water had moved freely; held, the water's share
        // of the mixture's momentum, M_nw = n M_w, changes by M_nw (v - w_free) more, and the
        // face does that work too.
        if (d < 2) {
          water.held_force[d] = 0.0;
        }
        if (tied) {
          w_new = v; // tied to the skeleton in couple_phases, its drag booked there
        } else if (d < 2 && (grid.water_held[i] & (1u << d)) != 0) {
          result.support_work += beta * porosity * mass[d] * (v - w_new) * v;
          water.held_force[d] = beta * porosity * mass[d] * (v - w_new) / dt;
          w_new = v;
        }
        // Darcy's drag takes n Q (w - v)^2 per unit time, at the velocities it acts on: the
        // water's balance here is per unit pore volume (divided by n), so its forces' power is
        // n times theirs; the node's n is the water's share over its mass.
        result.drag += porosity * drag[d] * (w_new - v) * (w_new - v) * dt;
        water.velocity()[d] = w_new;
        water.velocity_increment()[d] = w_new - w;
        if (drains && d < 2 && (grid.water_drained[i] & (1u << d)) != 0) {
          grid.drain_water_velocity[i][static_cast<std::size_t>(d)] = w_new;
          // The particles take this step's increment from the kept velocity, w_new - w, but
          // their water's momentum at the node was the mapped one: their kinetic energy changes
          // by share (w_mapped - w) (w_new - w) less than the grid's to first order, the work of
          // the momentum the drain gave the node.
          result.drain_work -= beta * water.share * water.drain_jump[d] * (w_new - w);
        }
      }
    }
    return result;
  };
  return parallel_reduce(
      grid.liquid.size(), WaterVelocityResult{}, update,
      [](WaterVelocityResult a, const WaterVelocityResult& b) {
        a.drag += b.drag;
        a.support_work += b.support_work;
        a.drain_work += b.drain_work;
        a.tied_drag += b.tied_drag;
        return a;
      },
      true);
}

template <GeometryMode mode, ShapeFunctions shape>
WaterParticleResult update_water_particle_velocities(Scene& scene, const ParticleBins& bins,
                                                     const std::vector<const LiquidPhase*>& phases,
                                                     const SolverSettings& settings,
                                                     const StepParameters& step,
                                                     const WaterXpic* xpic) {
  const Grid& grid = scene.grid;
  const NodeVector* water_correction =
      xpic != nullptr && !xpic->correction.empty() ? xpic->correction.data() : nullptr;
  Particles& p = scene.particles;
  // Under XPIC(m) each phase's particle velocity is its own grid field's XPIC(m) extrapolation
  // (the water's from `xpic`), which keeps no memory the grid does not see: the next step's nodal
  // drag acts on all of it, and nothing is relaxed on the particle. A FLIP deviation of the water
  // at a skeleton particle is not the memory of water that stays there: at Mandel's drained face
  // it is the transfer's smoothing of the steep Darcy flow, renewed every step (+4 % of w), and
  // relaxed into the skeleton it left the face 18 % short (docs/consolidation.md). Under FLIP the
  // water keeps its own deviation, relaxed below; PIC water there would take the skeleton's FLIP
  // memory away at m_w / m a step (Terzaghi's column drains wrong).
  const bool memoryless = xpic != nullptr;
  const double water_flip = memoryless ? 0.0 : settings.flip_fraction;
  const double g_r = settings.gravity[0];
  const double g_y = settings.gravity[1];
  std::vector<WaterParticleResult> block_results(static_cast<std::size_t>(bins.block_count()));
  bins.for_each_block([&](int block, std::span<const std::int32_t> particles) {
    WaterParticleResult& out = block_results[static_cast<std::size_t>(block)];
    for_each_coupled(
        particles, p, phases, [&](std::size_t i, const LiquidPhase& phase, double* state) {
          const auto weights = particle_weights<shape>(grid, p, i);
          double velocity[3] = {0.0, 0.0, 0.0}, increment[3] = {0.0, 0.0, 0.0};
          double skeleton[3] = {0.0, 0.0, 0.0};
          constexpr int dofs = has_theta(mode) ? 3 : 2;
          for (int a = 0; a < weights.size; ++a) {
            const auto node = static_cast<std::size_t>(weights.node[a]);
            const LiquidNode& water = grid.liquid[node];
            for (int d = 0; d < dofs; ++d) {
              velocity[d] += weights.N[a] * water.velocity()[d];
              if (water_correction != nullptr) {
                velocity[d] += weights.N[a] * water_correction[node][static_cast<std::size_t>(d)];
              }
              increment[d] += weights.N[a] * water.velocity_increment()[d];
            }
            for (int d = 0; d < dofs; ++d) {
              skeleton[d] += weights.N[a] * grid.nodes[node].velocity()[d];
            }
          }
          const double r = has_theta(mode) ? p.r[i] : 0.0;
          double* w = state + phase.velocity_slot;
          const double w_flip[3] = {w[0] + increment[0], w[1] + increment[1],
                                    has_theta(mode) ? w[2] + r * increment[2] : 0.0};
          // FLIP keeps each phase's particle velocity apart from its grid field (w_flip - w_pic,
          // and the skeleton's v_p - v_grid, already updated), and no nodal drag sees the
          // difference between the two: left alone a particle's water would flow through its
          // skeleton for ever (a water velocity frozen at a particle beside a pile tip while its
          // neighbours' drag had stopped theirs). Darcy's drag damps it as it damps the grid's
          // relative flow (couple_phases), implicitly over the step and between the particle's two
          // phases: their relative deviation decays at n (g / k) (1 + m_w / m_s), and the
          // particle's momentum m_s v + m_w w is kept, so the drag only takes kinetic energy.
          // Pulling the water alone towards its skeleton (at g / k) made momentum, and energy
          // where the skeleton's FLIP deviation was the larger: on 60 GDP cycles at k = 1e-4 m/s
          // it booked -2.8 kJ of drag against 28 kJ of work (docs/physics.md 9b).
          const double w_pic[3] = {velocity[0], velocity[1], r * velocity[2]};
          double* v[3] = {&p.v_r[i], &p.v_y[i], has_theta(mode) ? &p.v_theta[i] : nullptr};
          const double water_mass = phase.water_fraction(state[phase.porosity_slot]) * p.mass[i];
          const double grain_mass = p.mass[i] - water_mass;
          const double relative_rate = state[phase.porosity_slot] * phase.drag_per_mass *
                                       (1.0 + water_mass / grain_mass) / settings.mass_scaling;
          const double decay = memoryless ? 1.0 : 1.0 / (1.0 + step.dt * relative_rate);
          const double water_part = grain_mass / p.mass[i];          // of the relative change
          const double inertia = settings.mass_scaling * water_mass; // what the kinetic energy sees
          const double grain_inertia = settings.mass_scaling * grain_mass;
          double blend_drop = 0.0, drag_drop = 0.0;
          for (int d = 0; d < dofs; ++d) {
            const double w_off = water_flip * (w_flip[d] - w_pic[d]);
            const double w_blend = w_pic[d] + w_off;
            const double v_old = *v[d];
            const double v_off = v_old - (d == 2 ? r * skeleton[2] : skeleton[d]);
            const double change = (decay - 1.0) * (w_off - v_off);
            const double w_new = w_blend + water_part * change;
            const double v_new = v_old - (1.0 - water_part) * change;
            blend_drop += w_flip[d] * w_flip[d] - w_blend * w_blend;
            drag_drop += inertia * (w_blend * w_blend - w_new * w_new) +
                         grain_inertia * (v_old * v_old - v_new * v_new);
            w[d] = w_new;
            *v[d] = v_new;
          }
          out.transfer += 0.5 * inertia * blend_drop;
          out.drag += 0.5 * drag_drop;
          // Gravity on the water works along the water's path; the stress pass books the mixture's
          // weight along the skeleton's, so the difference is added here.
          out.external_work +=
              water_mass * (g_r * (velocity[0] - skeleton[0]) + g_y * (velocity[1] - skeleton[1])) *
              step.dt;
        });
  });
  WaterParticleResult total;
  for (const std::int32_t block : bins.non_empty_blocks()) {
    const WaterParticleResult& out = block_results[static_cast<std::size_t>(block)];
    total.external_work += out.external_work;
    total.transfer += out.transfer;
    total.drag += out.drag;
  }
  return total;
}

template <GeometryMode mode> void rescale_remapped_skeleton(Scene& scene) {
  Grid& grid = scene.grid;
  parallel_for(grid.liquid.size(), [&](std::size_t i) {
    const LiquidNode& water = grid.liquid[i];
    if (!(water.mass > 0.0) || !(water.mixture_mass > 0.0)) {
      return;
    }
    // The remap summed N m v over the mixture's masses m and divided by the effective mass
    // couple_phases left; divided by the mixture's own sum it is their weighted mean.
    GridNode& node = grid.nodes[i];
    node.velocity()[0] *= node.mass / water.mixture_mass;
    node.velocity()[1] *= node.mass / water.mixture_mass;
    if constexpr (has_theta(mode)) {
      node.velocity()[2] *= node.inertia / water.mixture_inertia;
    }
  });
}

template <GeometryMode mode, ShapeFunctions shape>
void remap_water(Scene& scene, const ParticleBins& bins,
                 const std::vector<const LiquidPhase*>& phases, double mass_floor) {
  constexpr int dofs = has_theta(mode) ? 3 : 2;
  Grid& grid = scene.grid;
  Particles& p = scene.particles;
  parallel_for(grid.liquid.size(), [&](std::size_t i) {
    for (int d = 0; d < 3; ++d) {
      grid.liquid[i].momentum[d] = 0.0;
    }
  });
  bins.for_each_block_colored([&](int, std::span<const std::int32_t> particles) {
    for_each_coupled(particles, p, phases,
                     [&](std::size_t i, const LiquidPhase& phase, const double* state) {
                       const double* w = state + phase.velocity_slot;
                       const double n = state[phase.porosity_slot];
                       const double inertia = phase.water_fraction(n) * p.mass[i] / n;
                       const double momentum[3] = {inertia * w[0], inertia * w[1],
                                                   has_theta(mode) ? inertia * p.r[i] * w[2] : 0.0};
                       const auto weights = particle_weights<shape>(grid, p, i);
                       for (int a = 0; a < weights.size; ++a) {
                         LiquidNode& node = grid.liquid[static_cast<std::size_t>(weights.node[a])];
                         for (int d = 0; d < dofs; ++d) {
                           node.momentum[d] += weights.N[a] * momentum[d];
                         }
                       }
                     });
  });
  const bool structures = !grid.structure_fields.empty();
  const bool drains = !grid.water_drained.empty();
  parallel_for(grid.liquid.size(), [&](std::size_t i) {
    LiquidNode& water = grid.liquid[i];
    const GridNode& node = grid.nodes[i];
    const bool at_wall = structures && grid.structure_occupies(i, mass_floor);
    const double inverse[3] = {water.mass > 0.0 ? 1.0 / water.mass : 0.0,
                               water.mass > 0.0 ? 1.0 / water.mass : 0.0,
                               water.inertia > 0.0 ? 1.0 / water.inertia : 0.0};
    for (int d = 0; d < dofs; ++d) {
      water.velocity()[d] = water.momentum[d] * inverse[d];
      // Impermeable where the skeleton is held or a structure is, as in update_water_velocities
      // (along a wall on a grid line the water flows past the skeleton).
      const bool along_wall = d < 2 && (water.wall_free & (1u << d)) != 0;
      if ((at_wall && !along_wall) || (d < 2 && (grid.water_held[i] & (1u << d)) != 0)) {
        water.velocity()[d] = node.velocity()[d];
      } else if (drains && d < 2 && (grid.water_drained[i] & (1u << d)) != 0 &&
                 std::isfinite(grid.drain_water_velocity[i][static_cast<std::size_t>(d)])) {
        // A drain keeps its own velocity through the remap too: the flow's divergence must see
        // the flux whose drag update_water_velocities booked.
        water.velocity()[d] = grid.drain_water_velocity[i][static_cast<std::size_t>(d)];
      }
    }
  });
}

template <GeometryMode mode, ShapeFunctions shape>
void pore_pressure_from_flow(Scene& scene, const ParticleBins& bins,
                             const std::vector<const LiquidPhase*>& phases,
                             const SolverSettings& settings, const StepParameters& step,
                             std::vector<PendingPorePressure>& pending) {
  const Grid& grid = scene.grid;
  Particles& p = scene.particles;
  const double dt = step.dt;
  pending.resize(p.size());
  bins.for_each_block([&](int block, std::span<const std::int32_t> particles) {
    // The divergences of both phases' velocities (the ones the stress pass reads) at each
    // particle, then (with B-bar) as the volume-weighted mean of its cell, as the skeleton's
    // volumetric strain is taken: the water's share of the pressure is no rougher than the
    // skeleton's.
    thread_local std::vector<std::array<double, 2>> divergence;
    thread_local std::vector<std::array<double, 3>> cell_sum;
    divergence.assign(particles.size(), {0.0, 0.0});
    const auto [cr0, cy0] = bins.block_origin(block);
    const int block_cells = bins.block_cells();
    cell_sum.assign(static_cast<std::size_t>(block_cells * block_cells), {0.0, 0.0, 0.0});
    const auto cell_of = [&](std::size_t i) {
      return static_cast<std::size_t>((p.cell_r[i] - cr0) + block_cells * (p.cell_y[i] - cy0));
    };
    for (std::size_t k = 0; k < particles.size(); ++k) {
      const auto i = static_cast<std::size_t>(particles[k]);
      if (phases[p.material[i]] == nullptr) {
        continue;
      }
      const auto weights = particle_weights<shape>(grid, p, i);
      double div_w = 0.0, div_v = 0.0, w_r = 0.0, v_r = 0.0;
      for (int a = 0; a < weights.size; ++a) {
        const auto node = static_cast<std::size_t>(weights.node[a]);
        const double* w = grid.liquid[node].velocity();
        const double* v = grid.nodes[node].velocity();
        div_w += weights.dN_dr[a] * w[0] + weights.dN_dy[a] * w[1];
        div_v += weights.dN_dr[a] * v[0] + weights.dN_dy[a] * v[1];
        w_r += weights.N[a] * w[0];
        v_r += weights.N[a] * v[0];
      }
      if constexpr (has_theta(mode)) {
        div_w += w_r / p.r[i];
        div_v += v_r / p.r[i];
      }
      divergence[k] = {div_w, div_v};
      if (settings.bbar) {
        auto& sum = cell_sum[cell_of(i)];
        sum[0] += p.volume[i] * div_w;
        sum[1] += p.volume[i] * div_v;
        sum[2] += p.volume[i];
      }
    }
    for (std::size_t k = 0; k < particles.size(); ++k) {
      const auto i = static_cast<std::size_t>(particles[k]);
      const LiquidPhase* phase = phases[p.material[i]];
      if (phase == nullptr) {
        continue;
      }
      double div_w = divergence[k][0], div_v = divergence[k][1];
      if (settings.bbar) {
        const auto& sum = cell_sum[cell_of(i)];
        div_w = sum[0] / sum[2];
        div_v = sum[1] / sum[2];
      }
      // The water's share of the pressure change, K_w div w dt (its flow into or out of the
      // pores); the skeleton's share is the material's.
      pending[i] = {phase->bulk_modulus * div_w * dt, div_w * dt, div_v * dt,
                    p.state[i * static_cast<std::size_t>(p.state_stride) +
                            static_cast<std::size_t>(phase->pore_slot)]};
    }
  });
}

double apply_pore_pressure_from_flow(Scene& scene, const ParticleBins& bins,
                                     const std::vector<const LiquidPhase*>& phases,
                                     const std::vector<PendingPorePressure>& pending,
                                     bool some_made_stress_free) {
  Particles& p = scene.particles;
  std::vector<double> block_work(static_cast<std::size_t>(bins.block_count()), 0.0);
  bins.for_each_block([&](int block, std::span<const std::int32_t> particles) {
    double work = 0.0;
    for_each_coupled(
        particles, p, phases, [&](std::size_t i, const LiquidPhase& phase, double* state) {
          const PendingPorePressure& change = pending[i];
          if (some_made_stress_free && state[phase.pore_slot] == 0.0 && p.stress[i] == Stress{}) {
            // Made stress-free inside a rigid body by this step's stress pass: its water let go
            // too.
            return;
          }
          const double n = state[phase.porosity_slot];
          double& pore = state[phase.pore_slot];
          // The water's stored energy n p^2 / (2 K_w) V changes by p_mid ((1 - n) d eps + n d
          // eps_w) V, p_mid the step's mean pressure. The stress pass booked its trapezoid on sigma
          // : d eps with the skeleton's share dp_s alone, (p^n + dp_s / 2) d eps V; this is the
          // rest. The two shares are each large and nearly cancel while the water barely drains, so
          // neither half step may be dropped.
          const double skeleton_mean = 0.5 * (change.pore_before + pore); // p^n + dp_s / 2
          const double storage = (1.0 - n) * change.skeleton_strain + n * change.water_strain;
          // No further than the cavitation stress (infinite without a cut-off): what the water's
          // volume gains beyond it is vapour, and the work on it is dissipated. In a cell the
          // implicit pore pressure held at the limit the particle goes to it, and the trapezoid's
          // half is the cell's increment over two times what the particle stores (the vapour's
          // work is the solve's).
          const double pressure = change.cavitated
                                      ? phase.pore_limit - pore
                                      : std::min(change.pressure, phase.pore_limit - pore);
          const double stored_volume =
              change.cavitated ? n / phase.bulk_modulus * change.pressure : storage;
          work +=
              p.volume[i] * (n * skeleton_mean * (change.water_strain - change.skeleton_strain) +
                             0.5 * pressure * stored_volume);
          pore += pressure;
          state[phase.pore_slot + 1] += pressure;
          Stress& s = p.stress[i];
          s[RR] += pressure;
          s[YY] += pressure;
          s[TT] += pressure;
        });
    block_work[static_cast<std::size_t>(block)] = work;
  });
  double total = 0.0;
  for (const std::int32_t block : bins.non_empty_blocks()) {
    total += block_work[static_cast<std::size_t>(block)];
  }
  return total;
}

double water_porosity(const Particles& p, std::size_t i, const LiquidPhase& phase) {
  return p.state[i * static_cast<std::size_t>(p.state_stride) +
                 static_cast<std::size_t>(phase.porosity_slot)];
}

double water_kinetic_energy(const Particles& p, std::size_t i, const LiquidPhase& phase) {
  const double* w =
      p.state.data() + i * static_cast<std::size_t>(p.state_stride) + phase.velocity_slot;
  const double w2 = w[0] * w[0] + w[1] * w[1] + (has_theta(p.mode) ? w[2] * w[2] : 0.0);
  return 0.5 * phase.water_fraction(water_porosity(p, i, phase)) * p.mass[i] * w2;
}

#define MPILE_WATER_PASSES(MODE, SHAPE)                                                            \
  template void map_water_to_grid<MODE, SHAPE>(                                                    \
      Scene&, const ParticleBins&, const std::vector<const LiquidPhase*>&, const SolverSettings&); \
  template WaterParticleResult update_water_particle_velocities<MODE, SHAPE>(                      \
      Scene&, const ParticleBins&, const std::vector<const LiquidPhase*>&, const SolverSettings&,  \
      const StepParameters&, const WaterXpic*);                                                    \
  template void remap_water<MODE, SHAPE>(Scene&, const ParticleBins&,                              \
                                         const std::vector<const LiquidPhase*>&, double);          \
  template void pore_pressure_from_flow<MODE, SHAPE>(                                              \
      Scene&, const ParticleBins&, const std::vector<const LiquidPhase*>&, const SolverSettings&,  \
      const StepParameters&, std::vector<PendingPorePressure>&);
MPILE_WATER_PASSES(GeometryMode::axisymmetric, ShapeFunctions::linear)
MPILE_WATER_PASSES(GeometryMode::axisymmetric, ShapeFunctions::gimp)
MPILE_WATER_PASSES(GeometryMode::plane_strain, ShapeFunctions::linear)
MPILE_WATER_PASSES(GeometryMode::plane_strain, ShapeFunctions::gimp)
#undef MPILE_WATER_PASSES
template void rescale_remapped_skeleton<GeometryMode::axisymmetric>(Scene&);
template void rescale_remapped_skeleton<GeometryMode::plane_strain>(Scene&);
template CoupledPhasesResult
couple_phases<GeometryMode::axisymmetric>(Scene&, const StepParameters&, double);
template CoupledPhasesResult
couple_phases<GeometryMode::plane_strain>(Scene&, const StepParameters&, double);
template WaterVelocityResult
update_water_velocities<GeometryMode::axisymmetric>(Scene&, const StepParameters&, double);
template WaterVelocityResult
update_water_velocities<GeometryMode::plane_strain>(Scene&, const StepParameters&, double);

} // namespace mpile::passes
