// Physical plausibility of a whole run, judged from its first stable step before anything is
// written: a stiffness or density off by powers of ten shows as a step count no machine can run
// or a step longer than the run.
#include "cases/plausibility.hpp"

#include "cases/case_error.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

namespace mpile {

namespace {

/// The particle of a case's own material whose crossing time h / c_p is shortest (the step's
/// limit at rest). A rigid body's particles are left out: their material is the one the scene
/// gives the body (it has no entry among the case's materials) and sets no step.
std::size_t stiffest_particle(const CaseSpec& spec, const Scene& scene) {
  const Particles& p = scene.particles;
  std::size_t found = 0;
  bool eligible = false;
  double shortest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.material[i] >= spec.materials.size()) {
      continue; // a rigid body's material, which the scene adds after the case's
    }
    const Material& material = *scene.materials[p.material[i]];
    const double modulus = material.constrained_modulus(
        p.stress[i], p.state.data() + i * static_cast<std::size_t>(p.state_stride));
    const double speed = std::sqrt(modulus * p.volume[i] / p.mass[i]);
    const double time = scene.grid.cell_min_size(p.cell_r[i], p.cell_y[i]) / speed;
    // The first eligible particle stands until a shorter time is found (a modulus so small that
    // every time is infinite still names one of the case's particles).
    if (!eligible || time < shortest || (std::isnan(time) && !std::isnan(shortest))) {
      shortest = time;
      found = i;
      eligible = true;
    }
  }
  return found;
}

/// Particle i's initial stress if a component is past max_initial_stress or not a number. Beyond
/// it the models' invariants overflow (a stress squared past 1e308) and hide the stress: at a K0
/// surcharge of 1e200 Pa the moduli fell to their floor, the first step looked plausible, and the
/// first stress update iterated for minutes on every particle.
std::optional<InadmissibleParticle> stress_past_any_material(const CaseSpec& spec,
                                                             const Scene& scene, std::size_t i) {
  const Particles& p = scene.particles;
  const Stress& stress = p.stress[i];
  double largest = 0.0;
  for (const double component : stress) {
    if (std::isnan(component)) {
      largest = component;
      break;
    }
    largest = std::abs(component) > std::abs(largest) ? component : largest;
  }
  if (std::abs(largest) <= max_initial_stress) {
    return std::nullopt;
  }
  std::ostringstream where;
  where << spec.file << ": an initial stress of " << largest
        << " Pa, past any material's (more than " << max_initial_stress
        << " Pa): check the phases' k0 (its surcharge, surface and k0)";
  std::ostringstream particle;
  particle << "particle " << i << " of body '" << scene.body_names[p.body[i]] << "' at (r, y) = ("
           << p.r[i] << ", " << p.y[i] << ")";
  return InadmissibleParticle{where.str(), particle.str()};
}

} // namespace

std::optional<InadmissibleParticle> first_inadmissible_particle(const CaseSpec& spec,
                                                                const Scene& scene) {
  const Particles& p = scene.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.material[i] >= spec.materials.size()) {
      continue; // a rigid body's
    }
    if (const auto past = stress_past_any_material(spec, scene, i)) {
      return past;
    }
    const Material::Inadmissible why = scene.materials[p.material[i]]->inadmissible_state(
        p.stress[i], p.state.data() + i * static_cast<std::size_t>(p.state_stride));
    if (why.key.empty()) {
      continue;
    }
    const MaterialSpec& material = spec.materials[p.material[i]];
    const auto written = material.where.find(why.key);
    std::ostringstream where;
    where << (written != material.where.end()
                  ? written->second
                  : spec.file + ": materials." + material.name + "." + why.key)
          << ": " << why.reason;
    std::ostringstream particle;
    particle << "particle " << i << " of body '" << scene.body_names[p.body[i]] << "' at (r, y) = ("
             << p.r[i] << ", " << p.y[i] << ")";
    return InadmissibleParticle{where.str(), particle.str()};
  }
  return std::nullopt;
}

void refuse_inadmissible_states(const CaseSpec& spec, const Scene& scene) {
  if (const auto found = first_inadmissible_particle(spec, scene)) {
    throw CaseError(found->key_and_reason + "; found at the start in " + found->particle +
                    ", the first such");
  }
}

void refuse_implausible_run(const CaseSpec& spec, const Scene& scene, double first_step) {
  refuse_inadmissible_states(spec, scene);
  const double run = spec.end_time();
  // Steps land on snapshot times, so an interval shorter than the stable step sets the step.
  const double snapshot_interval = spec.output.snapshot_interval;
  if (snapshot_interval > 0.0 && !(run / snapshot_interval <= max_run_steps)) {
    std::ostringstream s;
    s << spec.file << ": output.snapshot_interval = " << snapshot_interval
      << " s: steps land on snapshot times, so the phases' " << run << " s would take about "
      << run / snapshot_interval << " steps (more than " << max_run_steps
      << ") and as many snapshots; the first stable step is " << first_step
      << " s (0 writes the first and last snapshots only)";
    throw CaseError(s.str());
  }
  if (snapshot_interval > 0.0 && !(run / snapshot_interval <= max_snapshots)) {
    std::ostringstream s;
    s << spec.file << ": output.snapshot_interval = " << snapshot_interval << " s: the phases' "
      << run << " s would write about " << run / snapshot_interval << " snapshots (more than "
      << max_snapshots << ", each a file of every particle); a longer interval, or "
      << "output.snapshot_times at the moments wanted";
    throw CaseError(s.str());
  }
  const double steps = run / first_step;
  const bool too_many = !(steps <= max_run_steps);
  const bool too_long = first_step > run;
  if (!too_many && !too_long) {
    return;
  }
  const Particles& p = scene.particles;
  const std::size_t i = stiffest_particle(spec, scene);
  const MaterialSpec& material = spec.materials[p.material[i]];
  std::ostringstream s;
  s << spec.file << ": the first stable time step is " << first_step << " s";
  if (too_many) {
    s << ", so the phases' " << run << " s need about " << steps << " steps (more than "
      << max_run_steps << ")";
  } else {
    s << ", longer than the whole run (" << run << " s of phases): waves would not cross a cell";
  }
  s << "; it is set by particle " << i << " of body '" << scene.body_names[p.body[i]]
    << "' in a cell of " << scene.grid.cell_min_size(p.cell_r[i], p.cell_y[i]) << " m, material '"
    << material.name << "' (" << material.type << ":";
  const char* separator = " ";
  for (const auto& [key, value] : material.parameters) {
    s << separator << key << " = " << value;
    separator = ", ";
  }
  s << "): check materials." << material.name << " (a stiffness or density off by powers of ten) "
    << "and the phases' duration";
  throw CaseError(s.str());
}

} // namespace mpile
