// Strain increment, B-bar, objective rate, constitutive update, then volume and position update.
// Reads node velocities (MUSL-remapped) and particle position, cell, du, volume, stress, state;
// writes particle stress, state, volume, position and cell. Runs per block without coloring: it
// writes only to its own particles and to the B-bar sums of its own cells.
#include "engine/materials/pore_water.hpp"
#include "engine/shape_functions.hpp"
#include "engine/theta_gradient.hpp"
#include "solver/cell_slots.hpp"
#include "solver/particle_fields.hpp"
#include "solver/passes.hpp"
#include "solver/rigid_interiors.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace mpile::passes {

// Named, not anonymous: the pass's lambdas capture these types, and a unity build that puts this
// file beside others would make an anonymous one a subobject of another linkage.
namespace stress_pass {

/// Per-thread work arrays of one block, kept between steps to avoid allocation in the loop.
struct BlockScratch {
  std::vector<StrainIncrement> strain;
  std::vector<double> spin;
  std::vector<double> modulus;
  std::vector<double> work_before; // sigma^n : d eps, for the internal work
  std::vector<double> grain_mass;  // coupled soil: the grains' mass, kept through the step
  // B-bar sums per cell and velocity field: (volume-weighted volumetric increment, volume).
  std::vector<double> cell_volumetric;
  std::vector<double> cell_weight;
  void resize(std::size_t n) {
    strain.resize(n);
    spin.resize(n);
    modulus.resize(n);
    work_before.resize(n);
  }
};

/// sigma += W sigma - sigma W with the in-plane spin angle w = (dv_r/dy - dv_y/dr) dt / 2.
void rotate_in_plane(Stress& s, double w) {
  const Stress old = s;
  s[RR] += 2.0 * w * old[RY];
  s[YY] -= 2.0 * w * old[RY];
  s[RY] += w * (old[YY] - old[RR]);
  s[RT] += w * old[YT];
  s[YT] -= w * old[RT];
}

/// sigma : d eps with engineering shear strains.
double stress_power(const Stress& s, const StrainIncrement& de) {
  return s[RR] * de[RR] + s[YY] * de[YY] + s[TT] * de[TT] + s[RY] * de[RY] + s[YT] * de[YT] +
         s[RT] * de[RT];
}

/// One block's sums, reduced serially afterwards: no shared writes, and a fixed order.
struct BlockResult {
  double min_time = std::numeric_limits<double>::infinity();
  double step_time = std::numeric_limits<double>::infinity();
  bool changed = false;
  bool cell_changed = false;
  bool rigid_outside = false;
  std::int64_t first_outside = std::numeric_limits<std::int64_t>::max();
  double gravity_work = 0.0;
  double internal_work = 0.0;
  std::int64_t first_nonfinite = std::numeric_limits<std::int64_t>::max();
  std::int64_t stress_free = 0; // soil particles inside rigid bodies
};

/// 1. Strain increment and spin from the nodal velocities at x^n (physics.md section 2), and the
/// B-bar sums of each cell.
template <GeometryMode mode, bool contact, ShapeFunctions shape>
void strain_increments(const Grid& grid, const Particles& p,
                       const std::optional<ParticleFields>& fields,
                       std::span<const std::int32_t> particles, const CellSlots<contact>& slot,
                       bool bbar, double dt, BlockScratch& scratch) {
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const auto i = static_cast<std::size_t>(particles[k]);
    const GridNode* nodes = grid.nodes.data();
    if constexpr (contact) {
      if (slot.mixed) {
        nodes = fields->nodes(p.body[i]);
      }
    }
    const auto w = particle_weights<shape>(grid, p, i);
    double drr = 0.0, dry = 0.0, dyr = 0.0, dyy = 0.0, vr = 0.0;
    double dwy = 0.0;                        // d(omega)/dy
    double omega[support_nodes(shape)] = {}; // the nodes' angular velocities, for d(omega)/dr
    for (int n = 0; n < w.size; ++n) {
      const GridNode& node = nodes[static_cast<std::size_t>(w.node[n])];
      drr += w.dN_dr[n] * node.velocity()[0];
      dry += w.dN_dy[n] * node.velocity()[0];
      dyr += w.dN_dr[n] * node.velocity()[1];
      dyy += w.dN_dy[n] * node.velocity()[1];
      if constexpr (has_theta(mode)) {
        vr += w.N[n] * node.velocity()[0];
        omega[n] = node.velocity()[2];
        dwy += w.dN_dy[n] * node.velocity()[2];
      }
    }
    StrainIncrement& de = scratch.strain[k];
    if constexpr (has_theta(mode)) {
      // v_theta = r omega: gamma_ytheta = r d(omega)/dy and gamma_rtheta = dv_theta/dr -
      // v_theta/r = r d(omega)/dr, zero for a rigid spin whatever the cell. d(omega)/dr is
      // taken in s = 1/r^2 (engine/theta_gradient.hpp): exact for Couette flow, omega = A + B/r^2.
      const double r = p.r[i];
      const double inverse_r = 1.0 / r;
      const double dwr = radial_slope_in_s(grid.r_axis(), w, omega, r);
      de = {dt * drr, dt * dyy, dt * vr * inverse_r, dt * (dry + dyr), dt * r * dwy, dt * r * dwr};
    } else {
      de = {dt * drr, dt * dyy, 0.0, dt * (dry + dyr), 0.0, 0.0};
    }
    scratch.spin[k] = 0.5 * dt * (dry - dyr);
    if (bbar) {
      const std::size_t cell = slot(i);
      scratch.cell_volumetric[cell] += p.volume[i] * (de[RR] + de[YY] + de[TT]);
      scratch.cell_weight[cell] += p.volume[i];
    }
  }
}

/// 2. B-bar: the volumetric part (hoop included) becomes the cell's volume-weighted mean.
template <bool contact>
void apply_bbar(std::span<const std::int32_t> particles, const CellSlots<contact>& slot,
                BlockScratch& scratch) {
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const std::size_t cell = slot(static_cast<std::size_t>(particles[k]));
    StrainIncrement& de = scratch.strain[k];
    const double correction =
        (scratch.cell_volumetric[cell] / scratch.cell_weight[cell] - (de[RR] + de[YY] + de[TT])) /
        3.0;
    de[RR] += correction;
    de[YY] += correction;
    de[TT] += correction;
  }
}

/// 3. Objective rate: co-rotate the stress with the in-plane spin before the increment. The
/// internal work over the step is the trapezoidal rule on sigma : d eps (the co-rotation does no
/// work), so it needs the stress before the update too.
void corotate(Particles& p, std::span<const std::int32_t> particles, bool jaumann_rate,
              BlockScratch& scratch) {
  for (std::size_t k = 0; k < particles.size(); ++k) {
    Stress& stress = p.stress[static_cast<std::size_t>(particles[k])];
    if (jaumann_rate) {
      rotate_in_plane(stress, scratch.spin[k]);
    }
    scratch.work_before[k] = stress_power(stress, scratch.strain[k]);
  }
}

/// 4. Constitutive update, one call per run of particles with the same material.
void update_materials(Scene& scene, std::span<const std::int32_t> particles,
                      BlockScratch& scratch) {
  Particles& p = scene.particles;
  for (std::size_t begin = 0; begin < particles.size();) {
    const std::uint16_t material = p.material[static_cast<std::size_t>(particles[begin])];
    std::size_t end = begin + 1;
    while (end < particles.size() &&
           p.material[static_cast<std::size_t>(particles[end])] == material) {
      ++end;
    }
    const std::size_t count = end - begin;
    StressUpdateBatch batch;
    batch.particles = particles.subspan(begin, count);
    batch.strain = std::span<const StrainIncrement>(scratch.strain.data() + begin, count);
    batch.constrained_modulus = std::span<double>(scratch.modulus.data() + begin, count);
    batch.stress = p.stress.data();
    batch.state = p.state.data();
    batch.state_stride = p.state_stride;
    scene.materials[material]->update_stress(batch);
    begin = end;
  }
}

/// 5. Volume and position, the new cell, and the particle's limit on the next time step. Soil
/// inside a rigid body (`interiors`, null when not kept) ends the step without stress and sets no
/// wave speed (RigidInteriors).
template <GeometryMode mode, bool contact>
void move_particles(const Grid& grid, Particles& p, const ParticleBins& bins, int block,
                    std::span<const std::int32_t> particles, bool mixed,
                    const std::vector<char>& rigid_material,
                    const std::vector<int>& pore_pressure_slot,
                    const std::vector<const LiquidPhase*>& liquid, const RigidInteriors* interiors,
                    const SolverSettings& settings, const BlockScratch& scratch,
                    std::span<double> signal_speed, BlockResult& out) {
  const double inverse_beta = 1.0 / settings.mass_scaling;
  const double g_r = settings.gravity[0];
  const double g_y = settings.gravity[1];
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const auto i = static_cast<std::size_t>(particles[k]);
    const StrainIncrement& de = scratch.strain[k];
    const double volume_before = p.volume[i];
    p.volume[i] *= 1.0 + de[RR] + de[YY] + de[TT];
    if (!liquid.empty()) {
      // A coupled soil's particle holds the water that fills its pores now: the grains' mass is
      // kept, the water's follows the porosity its material has just updated.
      if (const LiquidPhase* phase = liquid[p.material[i]]) {
        p.mass[i] = scratch.grain_mass[k] /
                    (1.0 - phase->water_fraction(passes::water_porosity(p, i, *phase)));
      }
    }
    bool stress_free = false;
    if constexpr (contact) {
      if (interiors != nullptr && interiors->holds_soil(p, i)) {
        // Its stress at the start of the step took part in this step's forces; the work of the
        // step is booked from it to zero (the stored energy it had becomes dissipation).
        p.stress[i] = Stress{};
        // A saturated particle's stress is total: its pore water lets go too.
        if (const int slot = pore_pressure_slot[p.material[i]]; slot >= 0) {
          p.state[i * static_cast<std::size_t>(p.state_stride) + static_cast<std::size_t>(slot)] =
              0.0;
        }
        stress_free = true;
        ++out.stress_free;
      }
    }
    const Stress& s = p.stress[i];
    out.internal_work +=
        0.25 * (volume_before + p.volume[i]) * (scratch.work_before[k] + stress_power(s, de));
    // A run going unstable shows here first: catch it at the particle, with its position.
    double finite_check = s[RR] + s[YY] + s[TT] + s[RY] + s[YT] + s[RT] + p.v_r[i] + p.v_y[i];
    if constexpr (has_theta(mode)) {
      finite_check += p.v_theta[i];
    }
    if (!std::isfinite(finite_check)) {
      out.first_nonfinite = std::min(out.first_nonfinite, static_cast<std::int64_t>(i));
    }
    // Gravity on a rigid body acts on its DOFs (RigidBody), not on its particles.
    bool carries_gravity = true;
    if constexpr (contact) {
      carries_gravity = !mixed || rigid_material[p.material[i]] == 0;
    }
    if (carries_gravity) {
      out.gravity_work += p.mass[i] * (g_r * p.du_r[i] + g_y * p.du_y[i]);
    }
    const double step_cell_size = grid.cell_min_size(p.cell_r[i], p.cell_y[i]);
    p.r[i] += p.du_r[i];
    p.y[i] += p.du_y[i];
    const int cr = grid.r_axis().locate(p.r[i]);
    const int cy = grid.y_axis().locate(p.y[i]);
    if (cr < 0 || cy < 0) {
      // A rigid body's particle only marks the nodes its body occupies (its motion is the
      // body's): one that leaves the grid is dropped after the pass, not an error.
      bool rigid = false;
      if constexpr (contact) {
        rigid = mixed && rigid_material[p.material[i]] != 0;
      }
      if (rigid) {
        p.cell_r[i] = -1;
        out.rigid_outside = true;
      } else {
        out.first_outside = std::min(out.first_outside, static_cast<std::int64_t>(i));
      }
      continue;
    }
    out.changed = out.changed || bins.block_of(cr, cy) != block;
    out.cell_changed = out.cell_changed || cr != p.cell_r[i] || cy != p.cell_y[i];
    p.cell_r[i] = cr;
    p.cell_y[i] = cy;
    const double density = p.mass[i] / p.volume[i];
    const double wave_speed =
        stress_free ? 0.0 : std::sqrt(scratch.modulus[k] * inverse_beta / density);
    double speed = p.v_r[i] * p.v_r[i] + p.v_y[i] * p.v_y[i];
    if constexpr (has_theta(mode)) {
      speed += p.v_theta[i] * p.v_theta[i];
    }
    const double particle_speed = wave_speed + std::sqrt(speed);
    // A modulus the update returned as NaN: std::min below would pass over it and the step would
    // come from the other particles, with this one's stiffness unchecked.
    if (std::isnan(particle_speed)) {
      out.first_nonfinite = std::min(out.first_nonfinite, static_cast<std::int64_t>(i));
    }
    if (!signal_speed.empty()) {
      signal_speed[i] = particle_speed;
    }
    out.min_time = std::min(out.min_time, grid.cell_min_size(cr, cy) / particle_speed);
    out.step_time = std::min(out.step_time, step_cell_size / particle_speed);
  }
}

/// The blocks' sums in block order, whatever thread ran which block.
StressPassResult reduce(const ParticleBins& bins, const std::vector<BlockResult>& block_results) {
  StressPassResult result;
  result.min_crossing_time = std::numeric_limits<double>::infinity();
  result.step_crossing_time = std::numeric_limits<double>::infinity();
  std::int64_t first_outside = std::numeric_limits<std::int64_t>::max();
  std::int64_t first_nonfinite = std::numeric_limits<std::int64_t>::max();
  for (const std::int32_t block : bins.non_empty_blocks()) {
    const BlockResult& out = block_results[static_cast<std::size_t>(block)];
    result.min_crossing_time = std::min(result.min_crossing_time, out.min_time);
    result.step_crossing_time = std::min(result.step_crossing_time, out.step_time);
    result.block_changed = result.block_changed || out.changed;
    result.cell_changed = result.cell_changed || out.cell_changed;
    result.rigid_left_grid = result.rigid_left_grid || out.rigid_outside;
    first_outside = std::min(first_outside, out.first_outside);
    result.gravity_work += out.gravity_work;
    result.internal_work += out.internal_work;
    first_nonfinite = std::min(first_nonfinite, out.first_nonfinite);
    result.stress_free_inside_rigid += out.stress_free;
  }
  result.particle_outside =
      first_outside == std::numeric_limits<std::int64_t>::max() ? -1 : first_outside;
  result.particle_nonfinite =
      first_nonfinite == std::numeric_limits<std::int64_t>::max() ? -1 : first_nonfinite;
  return result;
}

} // namespace stress_pass

using namespace stress_pass;

template <GeometryMode mode, bool contact, ShapeFunctions shape>
StressPassResult
update_stress_and_positions(Scene& scene, const ParticleBins& bins, const SolverSettings& settings,
                            const StepParameters& step, std::span<double> signal_speed) {
  Grid& grid = scene.grid;
  Particles& p = scene.particles;
  const auto fields =
      contact ? std::optional<ParticleFields>(std::in_place, grid, scene) : std::nullopt;
  const std::vector<char> rigid_material = contact ? scene.rigid_materials() : std::vector<char>{};
  const std::vector<int> pore_pressure_slot =
      contact ? pore_pressure_slots(scene) : std::vector<int>{};
  // Empty unless some material is coupled soil, so a dry scene's loop asks nothing per particle.
  std::vector<const LiquidPhase*> liquid = passes::liquid_phases(scene);
  if (std::none_of(liquid.begin(), liquid.end(),
                   [](const LiquidPhase* l) { return l != nullptr; })) {
    liquid.clear();
  }
  const std::optional<RigidInteriors> interiors =
      contact ? kept_rigid_interiors(scene, settings) : std::nullopt;
  const RigidInteriors* inside_rigid = interiors ? &*interiors : nullptr;
  std::vector<BlockResult> block_results(static_cast<std::size_t>(bins.block_count()));

  bins.for_each_block([&](int block, std::span<const std::int32_t> particles) {
    thread_local BlockScratch scratch;
    scratch.resize(particles.size());
    const auto [cr0, cy0] = bins.block_origin(block);
    // A block of soil particles only reads field 0 (and carries no rigid particle).
    const bool mixed = contact && bins.block_tag(block) != 0;
    const CellSlots<contact> slot{scene, p, cr0, cy0, bins.block_cells(), mixed};
    if (settings.bbar) {
      scratch.cell_volumetric.assign(slot.fields() * slot.cells(), 0.0);
      scratch.cell_weight.assign(slot.fields() * slot.cells(), 0.0);
    }
    strain_increments<mode, contact, shape>(grid, p, fields, particles, slot, settings.bbar,
                                            step.dt, scratch);
    if (settings.bbar) {
      apply_bbar(particles, slot, scratch);
    }
    corotate(p, particles, settings.jaumann_rate, scratch);
    if (!liquid.empty()) {
      scratch.grain_mass.resize(particles.size());
      for (std::size_t k = 0; k < particles.size(); ++k) {
        const auto i = static_cast<std::size_t>(particles[k]);
        const LiquidPhase* phase = liquid[p.material[i]];
        scratch.grain_mass[k] =
            phase == nullptr
                ? 0.0
                : p.mass[i] * (1.0 - phase->water_fraction(passes::water_porosity(p, i, *phase)));
      }
    }
    update_materials(scene, particles, scratch);
    move_particles<mode, contact>(grid, p, bins, block, particles, mixed, rigid_material,
                                  pore_pressure_slot, liquid, inside_rigid, settings, scratch,
                                  signal_speed, block_results[static_cast<std::size_t>(block)]);
  });
  return reduce(bins, block_results);
}

template StressPassResult
update_stress_and_positions<GeometryMode::axisymmetric, false, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&, std::span<double>);
template StressPassResult
update_stress_and_positions<GeometryMode::axisymmetric, false, ShapeFunctions::gimp>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&, std::span<double>);
template StressPassResult
update_stress_and_positions<GeometryMode::axisymmetric, true, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&, std::span<double>);
template StressPassResult
update_stress_and_positions<GeometryMode::axisymmetric, true, ShapeFunctions::gimp>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&, std::span<double>);
template StressPassResult
update_stress_and_positions<GeometryMode::plane_strain, false, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&, std::span<double>);
template StressPassResult
update_stress_and_positions<GeometryMode::plane_strain, false, ShapeFunctions::gimp>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&, std::span<double>);
template StressPassResult
update_stress_and_positions<GeometryMode::plane_strain, true, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&, std::span<double>);
template StressPassResult
update_stress_and_positions<GeometryMode::plane_strain, true, ShapeFunctions::gimp>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&, std::span<double>);

} // namespace mpile::passes
