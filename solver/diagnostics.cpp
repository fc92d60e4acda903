// Whole-scene sums. Deterministic reductions (fixed split of the range), so the figures are the
// same for any thread count.
#include "solver/diagnostics.hpp"

#include "engine/parallel.hpp"

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

} // namespace

double kinetic_energy(const Scene& scene) {
  const Particles& p = scene.particles;
  const bool theta = has_theta(scene.mode);
  // A rigid body's energy is that of its DOFs with its whole mass, not of its meshed particles.
  std::vector<char> rigid;
  for (const auto& material : scene.materials) {
    rigid.push_back(material->is_rigid() ? 1 : 0);
  }
  double energy = deterministic_sum(p.size(), [&](std::size_t i) {
    if (rigid[p.material[i]] != 0) {
      return 0.0;
    }
    double v2 = p.v_r[i] * p.v_r[i] + p.v_y[i] * p.v_y[i];
    if (theta) {
      v2 += p.v_theta[i] * p.v_theta[i];
    }
    return 0.5 * p.mass[i] * v2;
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
