#include "solver/pore_water_coupling.hpp"

#include "engine/parallel.hpp"
#include "solver/diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <type_traits>

namespace mpile {

namespace {

/// Mass scaling multiplies both phases' inertia and leaves Darcy's drag, so that the water drains
/// as fast as unscaled while inertia is negligible (physics.md section 9d). With the water's
/// stiffness explicit its waves would set the step still: only the implicit pore pressure gains.
void require_scalable_water(const SolverSettings& settings) {
  if (settings.mass_scaling != 1.0 && !settings.implicit_pore_pressure) {
    throw std::invalid_argument("mass_scaling must be 1 in a scene with coupled soil unless "
                                "[solver] implicit_pore_pressure is on: the water's explicit "
                                "stiffness would still set the step");
  }
}

/// The materials leave their pore pressure to the solver exactly when the solver finds it: else
/// the water's increment would be counted twice, or not at all.
void require_pore_pressure_agreement(const Scene& scene, const SolverSettings& settings) {
  for (std::size_t m = 0; m < scene.materials.size(); ++m) {
    const Material& material = *scene.materials[m];
    if (material.pore_pressure_index() < 0) {
      continue;
    }
    if ((material.implicit_pore_storage() != nullptr) != settings.implicit_pore_pressure) {
      throw std::invalid_argument(
          "material '" + scene.material_names[m] + "' was built for " +
          (settings.implicit_pore_pressure ? "an explicit" : "an implicit") +
          " pore pressure and the solver's implicit_pore_pressure is " +
          (settings.implicit_pore_pressure ? "on" : "off"));
    }
  }
}

} // namespace

std::unique_ptr<PoreWaterCoupling> PoreWaterCoupling::of(Scene& scene, const ParticleBins& bins,
                                                         const SolverSettings& settings,
                                                         PassTimings& timings) {
  if (!has_pore_water(scene) && !has_coupled_water(scene)) {
    return nullptr;
  }
  return std::make_unique<PoreWaterCoupling>(scene, bins, settings, timings);
}

PoreWaterCoupling::PoreWaterCoupling(Scene& scene, const ParticleBins& bins,
                                     const SolverSettings& settings, PassTimings& timings)
    : scene_(scene), bins_(bins), settings_(settings), timings_(timings),
      phases_(passes::liquid_phases(scene)), context_{scene, bins, settings, timings, phases_} {
  if (scene_.has_contact()) {
    const std::vector<int> slots = passes::pore_pressure_slots(scene_);
    at_contact_ = std::any_of(slots.begin(), slots.end(), [](int slot) { return slot >= 0; });
  }
  if (std::none_of(phases_.begin(), phases_.end(),
                   [](const LiquidPhase* phase) { return phase != nullptr; })) {
    phases_.clear();
  } else {
    require_scalable_water(settings_);
    const Particles& p = scene_.particles;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (phases_[p.material[i]] != nullptr && scene_.field_of(p.body[i]) != 0) {
        throw std::invalid_argument(
            "body '" + scene_.body_names[p.body[i]] +
            "' is a contact structure of coupled soil: only the soil's field carries pore water");
      }
    }
  }
  require_pore_pressure_agreement(scene_, settings_);
  if (settings_.implicit_pore_pressure) {
    pressure_.emplace<ProjectedPorePressure>();
  }
}

void PoreWaterCoupling::check(const SolverSettings& settings) const {
  if (!phases_.empty()) {
    require_scalable_water(settings);
  }
  require_pore_pressure_agreement(scene_, settings);
}

template <GeometryMode mode, bool contact, ShapeFunctions shape> void PoreWaterCoupling::to_grid() {
  if constexpr (contact) {
    if (at_contact_) {
      // Undrained soil beside a structure: the pore water's share of field 0's node forces, for
      // the contact's effective normal force.
      PassTimer timer(timings_.contact);
      passes::map_pore_force<mode, shape>(scene_, bins_);
    }
  }
  if (phases_.empty()) {
    return;
  }
  PassTimer timer(timings_.particle_to_grid);
  passes::map_water_to_grid<mode, shape>(scene_, bins_, phases_, settings_);
  passes::apply_drained_face_water(scene_, phases_, settings_);
}

template <GeometryMode mode>
passes::CoupledPhasesResult
PoreWaterCoupling::couple_to_skeleton(const passes::StepParameters& step) {
  if (phases_.empty()) {
    return {};
  }
  return passes::couple_phases<mode>(scene_, step, settings_.mass_scaling);
}

template <GeometryMode mode>
EnergyIncrement PoreWaterCoupling::update_grid_velocities(const passes::StepParameters& step) {
  if (phases_.empty()) {
    return {};
  }
  PassTimer timer(timings_.grid_update);
  const passes::WaterVelocityResult water =
      passes::update_water_velocities<mode>(scene_, step, settings_.mass_scaling);
  // A support's reaction holds the water too, where its face is impermeable: without that part a
  // saturated slab's base carried 5.8 % less than its load (the explicit water) and a lid's
  // reaction read 0.79 of the load under a consolidating cell.
  // A node two supports hold (a corner) is the first's, as its skeleton's reaction is.
  std::vector<std::uint8_t> claimed(scene_.grid.nodes.size(), 0);
  for (NodeConstraint& c : scene_.boundaries.constraints) {
    if (c.drained || (c.field != NodeConstraint::all_fields && c.field != 0)) {
      continue;
    }
    for (const int node : c.nodes) {
      const auto i = static_cast<std::size_t>(node);
      const LiquidNode& held = scene_.grid.liquid[i];
      for (int d = 0; d < 2; ++d) {
        if ((c.dofs & (1u << d)) != 0 && (claimed[i] & (1u << d)) == 0) {
          c.reaction[static_cast<std::size_t>(d)] += held.held_force[d];
          claimed[i] |= static_cast<std::uint8_t>(1u << d);
        }
      }
    }
  }
  // With the pore pressure solved on the grid the drag is booked there, at the corrected
  // velocities: the predictor's drag and the correction's add to one drag implicit in the
  // corrected relative flow, and the pore pressure's work is booked on the same velocities
  // (docs/saturated.md, "The step's energy identity").
  const bool drag_at_correction = std::visit(
      [](const auto& method) { return std::decay_t<decltype(method)>::drag_booked_at_correction; },
      pressure_);
  const double far_field =
      scene_.boundaries.drained_water.empty() ? 0.0 : passes::drained_face_water_work(scene_, step);
  return {.external_work = water.support_work + water.drain_work + far_field,
          .drag = water.tied_drag + (drag_at_correction ? 0.0 : water.drag)};
}

template <GeometryMode mode, ShapeFunctions shape>
EnergyIncrement PoreWaterCoupling::to_particles(const passes::StepParameters& step) {
  if (phases_.empty()) {
    return {};
  }
  PassTimer timer(timings_.grid_to_particle);
  // Under XPIC(m) the water takes its own field's XPIC(m) velocity as the skeleton takes its
  // field's (XPIC(1), PIC: no correction).
  const bool xpic = settings_.xpic_order >= 1;
  if (settings_.xpic_order >= 2) {
    passes::extrapolate_water_xpic<mode, shape>(scene_, bins_, phases_, settings_.xpic_order, step,
                                                xpic_);
  } else {
    xpic_.correction.clear();
  }
  const passes::WaterParticleResult water = passes::update_water_particle_velocities<mode, shape>(
      scene_, bins_, phases_, settings_, step, xpic ? &xpic_ : nullptr);
  return {.external_work = water.external_work, .transfer = water.transfer, .drag = water.drag};
}

template <GeometryMode mode> void PoreWaterCoupling::rescale_remapped_skeleton() {
  if (!phases_.empty()) {
    passes::rescale_remapped_skeleton<mode>(scene_);
  }
}

template <GeometryMode mode, ShapeFunctions shape>
EnergyIncrement PoreWaterCoupling::find_pore_pressure(const passes::StepParameters& step,
                                                      long step_number) {
  if (settings_.musl && !phases_.empty()) {
    // The water's remap after the skeleton's and its supports: the flow's divergence and the
    // implicit pore pressure read the remapped velocities of both phases.
    PassTimer timer(timings_.momentum_remap);
    passes::remap_water<mode, shape>(scene_, bins_, phases_, step.mass_floor);
  }
  return std::visit(
      [&](auto& method) { return method.template find<mode, shape>(context_, step, step_number); },
      pressure_);
}

void PoreWaterCoupling::apply_pore_pressure(bool some_made_stress_free, EnergyLedger& energy) {
  std::visit([&](auto& method) { method.apply(context_, some_made_stress_free, energy); },
             pressure_);
}

void PoreWaterCoupling::smooth_excess_pore_pressure() {
  if (!settings_.cell_mean_pore_pressure || !has_pore_water(scene_)) {
    return;
  }
  PassTimer timer(timings_.stress_update);
  passes::smooth_excess_pore_pressure(scene_, bins_);
}

void PoreWaterCoupling::report_tension(RunLog& log, long step, double time) {
  // Water at the atmosphere's pressure cavitates about 100 kPa below it. Without a cut-off the
  // pore pressure of an undrained or slowly draining dilative sand keeps falling (the coarse CPT
  // chamber undrained at psi = 7.5 degrees reached 33 MPa of suction and a q_c of 168 MPa), and
  // the effective stress it lends the skeleton is not one water could give.
  constexpr double tension_water_holds = 100e3; // Pa
  if (tension_reported_) {
    return;
  }
  const Particles& p = scene_.particles;
  const auto stride = static_cast<std::size_t>(p.state_stride);
  std::vector<const Material*> unbounded(scene_.materials.size(), nullptr);
  bool any = false;
  for (std::size_t m = 0; m < scene_.materials.size(); ++m) {
    const Material& material = *scene_.materials[m];
    if (material.pore_pressure_index() >= 0 && std::isinf(material.pore_pressure_limit())) {
      unbounded[m] = &material;
      any = true;
    }
  }
  if (!any) {
    tension_reported_ = true; // nothing to watch in this scene
    return;
  }
  struct Worst {
    double tension = 0.0;
    std::int64_t particle = -1;
  };
  const Worst worst = parallel_reduce(
      p.size(), Worst{},
      [&](std::size_t begin, std::size_t end, Worst found) {
        for (std::size_t i = begin; i < end; ++i) {
          const Material* material = unbounded[p.material[i]];
          if (material == nullptr) {
            continue;
          }
          const double tension =
              p.state[i * stride + static_cast<std::size_t>(material->pore_pressure_index())] -
              material->water_column_pressure();
          if (tension > found.tension) {
            found = {tension, static_cast<std::int64_t>(i)};
          }
        }
        return found;
      },
      [](const Worst& a, const Worst& b) {
        // The larger tension, the lower index on a tie: the same particle on any thread count.
        if (a.tension != b.tension) {
          return a.tension > b.tension ? a : b;
        }
        return lowest_found(a.particle, b.particle) == a.particle ? a : b;
      },
      true);
  if (worst.particle < 0 || !(worst.tension > tension_water_holds)) {
    return;
  }
  tension_reported_ = true;
  std::ostringstream s;
  s << at_step(step, time) << "the pore water of "
    << particle_position(p, static_cast<std::size_t>(worst.particle)) << " is in "
    << worst.tension / 1e3
    << " kPa of tension, more than water holds (it cavitates about 100 kPa below the "
       "atmosphere), and nothing caps it: the effective stress it lends the soil is not one water "
       "could give; [water] cavitation_stress = 100e3 caps it (docs/physics.md section 9c)";
  log.warn(s.str());
}

#define MPILE_PORE_WATER_SHAPE(MODE, SHAPE)                                                        \
  template void PoreWaterCoupling::to_grid<MODE, false, SHAPE>();                                  \
  template void PoreWaterCoupling::to_grid<MODE, true, SHAPE>();                                   \
  template EnergyIncrement PoreWaterCoupling::to_particles<MODE, SHAPE>(                           \
      const passes::StepParameters&);                                                              \
  template EnergyIncrement PoreWaterCoupling::find_pore_pressure<MODE, SHAPE>(                     \
      const passes::StepParameters&, long);
#define MPILE_PORE_WATER_MODE(MODE)                                                                \
  template passes::CoupledPhasesResult PoreWaterCoupling::couple_to_skeleton<MODE>(                \
      const passes::StepParameters&);                                                              \
  template EnergyIncrement PoreWaterCoupling::update_grid_velocities<MODE>(                        \
      const passes::StepParameters&);                                                              \
  template void PoreWaterCoupling::rescale_remapped_skeleton<MODE>();                              \
  MPILE_PORE_WATER_SHAPE(MODE, ShapeFunctions::linear)                                             \
  MPILE_PORE_WATER_SHAPE(MODE, ShapeFunctions::gimp)
MPILE_PORE_WATER_MODE(GeometryMode::axisymmetric)
MPILE_PORE_WATER_MODE(GeometryMode::plane_strain)
#undef MPILE_PORE_WATER_MODE
#undef MPILE_PORE_WATER_SHAPE

} // namespace mpile
