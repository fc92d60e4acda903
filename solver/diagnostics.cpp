// Whole-scene sums. Deterministic reductions (fixed split of the range), so the figures are the
// same for any thread count.
#include "solver/diagnostics.hpp"
#include "engine/materials/pore_water.hpp"
#include "solver/passes.hpp"

#include "engine/parallel.hpp"

#include <cmath>
#include <sstream>

namespace mpile {

namespace {

constexpr std::size_t grain = 4096;

template <class Term> double deterministic_sum(std::size_t n, Term term) {
  return parallel_reduce(
      n, 0.0,
      [&](std::size_t begin, std::size_t end, double sum) {
        for (std::size_t i = begin; i != end; ++i) {
          sum += term(i);
        }
        return sum;
      },
      [](double a, double b) { return a + b; }, true, grain);
}

double speed_squared(const Particles& p, std::size_t i, bool theta) {
  const double v2 = p.v_r[i] * p.v_r[i] + p.v_y[i] * p.v_y[i];
  return theta ? v2 + p.v_theta[i] * p.v_theta[i] : v2;
}

} // namespace

double kinetic_energy(const Scene& scene) {
  const Particles& p = scene.particles;
  const bool theta = has_theta(scene.mode);
  const std::vector<char> rigid = scene.rigid_materials();
  const std::vector<const LiquidPhase*> water = passes::liquid_phases(scene);
  double energy = deterministic_sum(p.size(), [&](std::size_t i) {
    if (rigid[p.material[i]] != 0) {
      return 0.0;
    }
    const LiquidPhase* phase = water[p.material[i]];
    if (phase == nullptr) {
      return 0.5 * p.mass[i] * speed_squared(p, i, theta);
    }
    // Coupled soil: the grains' mass moves at v, the water's at w.
    const double grains = 1.0 - phase->water_fraction(passes::water_porosity(p, i, *phase));
    return 0.5 * grains * p.mass[i] * speed_squared(p, i, theta) +
           passes::water_kinetic_energy(p, i, *phase);
  });
  for (const RigidBody& body : scene.rigid_bodies) {
    energy += body.kinetic_energy();
  }
  return energy;
}

double elastic_energy(const Scene& scene) {
  const Particles& p = scene.particles;
  return deterministic_sum(p.size(), [&](std::size_t i) {
    const Material& material = *scene.materials[p.material[i]];
    return p.volume[i] *
           material.elastic_energy_density(
               p.stress[i], p.state.data() + i * static_cast<std::size_t>(p.state_stride));
  });
}

KineticHotspot kinetic_hotspot(const Scene& scene) {
  const Particles& p = scene.particles;
  const bool theta = has_theta(scene.mode);
  KineticHotspot hot;
  hot.body_energy.assign(scene.body_names.size(), 0.0);
  const std::vector<char> rigid = scene.rigid_materials();
  // Serial: this runs once, when a guard reports, and the sums then come in index order.
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (rigid[p.material[i]] != 0) {
      continue;
    }
    const double v2 = speed_squared(p, i, theta);
    const double energy = 0.5 * p.mass[i] * v2;
    if (p.body[i] < hot.body_energy.size()) {
      hot.body_energy[p.body[i]] += energy;
    }
    // A non-finite energy is the first thing to name.
    if (hot.particle < 0 || energy > hot.particle_energy ||
        (!std::isfinite(energy) && std::isfinite(hot.particle_energy))) {
      hot.particle = static_cast<std::int64_t>(i);
      hot.particle_energy = energy;
      hot.particle_speed = std::sqrt(v2);
    }
  }
  for (const ContactPair& pair : scene.contacts) {
    if (pair.rigid_body >= 0 && pair.structure_body < hot.body_energy.size()) {
      hot.body_energy[pair.structure_body] =
          scene.rigid_bodies[static_cast<std::size_t>(pair.rigid_body)].kinetic_energy();
    }
  }
  return hot;
}

std::string particle_position(const Particles& particles, std::size_t i) {
  std::ostringstream s;
  s << "particle " << i << " at (r, y) = (" << particles.r[i] << ", " << particles.y[i] << ")";
  return s.str();
}

std::string describe_kinetic_hotspot(const Scene& scene, double mass_scaling) {
  KineticHotspot hot = kinetic_hotspot(scene);
  for (double& e : hot.body_energy) {
    e *= mass_scaling;
  }
  hot.particle_energy *= mass_scaling;
  std::ostringstream s;
  double total = 0.0;
  std::size_t top = 0;
  for (std::size_t b = 0; b < hot.body_energy.size(); ++b) {
    total += hot.body_energy[b];
    if (hot.body_energy[b] > hot.body_energy[top]) {
      top = b;
    }
  }
  if (hot.body_energy.empty()) {
    return "no body has kinetic energy";
  }
  s << "most kinetic energy in body '" << scene.body_names[top] << "' (" << hot.body_energy[top]
    << " J";
  if (total > 0.0 && std::isfinite(total)) {
    s << ", " << std::lround(100.0 * hot.body_energy[top] / total) << " % of " << total << " J";
  }
  s << ")";
  if (hot.particle >= 0) {
    const auto i = static_cast<std::size_t>(hot.particle);
    const Particles& p = scene.particles;
    s << "; the most in one particle: particle " << i << " of body '" << scene.body_names[p.body[i]]
      << "' at (r, y) = (" << p.r[i] << ", " << p.y[i] << ") in cell (" << p.cell_r[i] << ", "
      << p.cell_y[i] << "), " << hot.particle_energy << " J at " << hot.particle_speed << " m/s";
  }
  return s.str();
}

std::array<double, 3> mean_velocity(const Scene& scene, int body) {
  const Particles& p = scene.particles;
  const bool theta = has_theta(scene.mode);
  auto in_body = [&](std::size_t i) { return body < 0 || p.body[i] == body; };
  const double mass =
      deterministic_sum(p.size(), [&](std::size_t i) { return in_body(i) ? p.mass[i] : 0.0; });
  std::array<double, 3> v{};
  v[0] = deterministic_sum(p.size(),
                           [&](std::size_t i) { return in_body(i) ? p.mass[i] * p.v_r[i] : 0.0; }) /
         mass;
  v[1] = deterministic_sum(p.size(),
                           [&](std::size_t i) { return in_body(i) ? p.mass[i] * p.v_y[i] : 0.0; }) /
         mass;
  if (theta) {
    v[2] =
        deterministic_sum(
            p.size(), [&](std::size_t i) { return in_body(i) ? p.mass[i] * p.v_theta[i] : 0.0; }) /
        mass;
  }
  return v;
}

} // namespace mpile
