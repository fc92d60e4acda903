#include "engine/materials/mohr_coulomb.hpp"

#include "engine/angles.hpp"
#include "engine/materials/principal_stress.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace mpile {

namespace {

using Vector3 = std::array<double, 3>;

double dot(const Vector3& a, const Vector3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

Vector3 unit(const Vector3& v) {
  const double length = std::sqrt(dot(v, v));
  return {v[0] / length, v[1] / length, v[2] / length};
}

// Indices of the planes in sorted principal space (sigma_1 >= sigma_2 >= sigma_3). In that sextant
// the shear plane between sigma_1 and sigma_3 is the most critical one and sigma_3 is the most
// tensile, so the other planes matter only on the edges and corners where they meet these two.
constexpr std::size_t shear_13 = 0; // sigma_1 - N sigma_3 = k, the main plane
// sigma_2 - N sigma_3 = k: meets the main plane on the extension edge sigma_1 = sigma_2
constexpr std::size_t shear_23 = 1;
// sigma_1 - N sigma_2 = k: meets the main plane on the compression edge sigma_2 = sigma_3
constexpr std::size_t shear_12 = 2;
constexpr std::size_t tension_3 = 3; // -sigma_3 = t
constexpr std::size_t tension_2 = 4; // -sigma_2 = t
constexpr std::size_t tension_1 = 5; // -sigma_1 = t

// Solves the n x n system a x = b (n <= 3) by Cramer's rule; false when it is singular relative to
// the size of its columns (planes whose correctors are parallel cannot fix a point).
bool solve_small(std::size_t n, const std::array<Vector3, 3>& a, const Vector3& b, Vector3& x) {
  if (n == 1) {
    if (!(std::abs(a[0][0]) > 0.0)) {
      return false;
    }
    x = {b[0] / a[0][0], 0.0, 0.0};
    return true;
  }
  if (n == 2) {
    const double det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    const double size = std::hypot(a[0][0], a[1][0]) * std::hypot(a[0][1], a[1][1]);
    if (!(std::abs(det) > 1e-12 * size)) {
      return false;
    }
    x = {(b[0] * a[1][1] - a[0][1] * b[1]) / det, (a[0][0] * b[1] - b[0] * a[1][0]) / det, 0.0};
    return true;
  }
  auto det3 = [](const std::array<Vector3, 3>& m) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  const double det = det3(a);
  double size = 1.0;
  for (std::size_t j = 0; j < 3; ++j) {
    size *= std::sqrt(a[0][j] * a[0][j] + a[1][j] * a[1][j] + a[2][j] * a[2][j]);
  }
  if (!(std::abs(det) > 1e-12 * size)) {
    return false;
  }
  for (std::size_t j = 0; j < 3; ++j) {
    std::array<Vector3, 3> replaced = a;
    for (std::size_t i = 0; i < 3; ++i) {
      replaced[i][j] = b[i];
    }
    x[j] = det3(replaced) / det;
  }
  return true;
}

} // namespace

MohrCoulomb::MohrCoulomb(double young_modulus, double poisson_ratio, double density,
                         double cohesion, double friction_angle, double dilatancy_angle,
                         double tension_limit)
    : young_(young_modulus), poisson_(poisson_ratio), density_(density), cohesion_(cohesion),
      friction_degrees_(friction_angle), dilatancy_degrees_(dilatancy_angle) {
  require_in_range("young_modulus", young_modulus_range, young_modulus);
  require_in_range("poisson_ratio", poisson_ratio_range, poisson_ratio);
  require_in_range("density", density_range, density);
  require_in_range("cohesion", cohesion_range, cohesion);
  require_in_range("friction_angle", mohr_coulomb_friction_range, friction_angle);
  // The message begins with the parameter it refuses and names the one it compares it with: a
  // case file's error points at whichever of them the case wrote.
  if (!(dilatancy_angle >= 0.0 && dilatancy_angle <= friction_angle)) {
    throw std::invalid_argument("dilatancy_angle must lie between 0 and friction_angle (" +
                                std::to_string(friction_angle) + " degrees), got " +
                                std::to_string(dilatancy_angle));
  }
  require_in_range("tension_limit", tension_limit_range, tension_limit);
  if (cohesion == 0.0 && friction_angle == 0.0) {
    throw std::invalid_argument("cohesion is zero and so is the friction angle: the material "
                                "would have no shear strength");
  }
  mu_ = young_ / (2.0 * (1.0 + poisson_));
  lambda_ = young_ * poisson_ / ((1.0 + poisson_) * (1.0 - 2.0 * poisson_));
  const double phi = radians(friction_angle);
  const double psi = radians(dilatancy_angle);
  n_phi_ = (1.0 + std::sin(phi)) / (1.0 - std::sin(phi));
  n_psi_ = (1.0 + std::sin(psi)) / (1.0 - std::sin(psi));
  strength_ = 2.0 * cohesion * std::sqrt(n_phi_);
  // Beyond c cot(phi) the cone's apex, not the cut-off, limits the tension. With phi = 0 (Tresca)
  // there is no apex and the cut-off alone closes the surface.
  const double apex =
      friction_angle > 0.0 ? cohesion / std::tan(phi) : std::numeric_limits<double>::infinity();
  const bool capped = tension_limit >= apex;
  tension_ = capped ? apex : tension_limit;

  // Normals and flows are unit vectors, so that every f is a distance in stress space and every
  // multiplier times the stiffness is a stress: one tolerance then fits all of them.
  const double n = n_phi_, m = n_psi_, k = strength_, t = tension_;
  const double scale_13 = std::sqrt(1.0 + n * n);
  auto shear = [&](Vector3 normal, Vector3 flow) {
    return Plane{unit(normal), k / scale_13, unit(flow), {}, true};
  };
  planes_[shear_13] = shear({1.0, 0.0, -n}, {1.0, 0.0, -m});
  planes_[shear_23] = shear({0.0, 1.0, -n}, {0.0, 1.0, -m});
  planes_[shear_12] = shear({1.0, -n, 0.0}, {1.0, -m, 0.0});
  planes_[tension_3] = Plane{{0.0, 0.0, -1.0}, t, {0.0, 0.0, -1.0}, {}, false};
  planes_[tension_2] = Plane{{0.0, -1.0, 0.0}, t, {0.0, -1.0, 0.0}, {}, false};
  planes_[tension_1] = Plane{{-1.0, 0.0, 0.0}, t, {-1.0, 0.0, 0.0}, {}, false};
  for (Plane& plane : planes_) {
    const Vector3& g = plane.flow;
    const double volumetric = lambda_ * (g[0] + g[1] + g[2]);
    plane.corrector = {volumetric + 2.0 * mu_ * g[0], volumetric + 2.0 * mu_ * g[1],
                       volumetric + 2.0 * mu_ * g[2]};
  }

  // Candidates in the order they are tried: the planes first (the common case), then the edges,
  // then the corners. The regions of trial stresses that return to each are disjoint, so the order
  // only decides which of two coinciding returns on a region boundary is reported.
  using R = MohrCoulombRegion;
  const double corner_1 = k - n * t; // sigma_1 on the shear plane with sigma_3 at the cut-off
  candidates_.push_back({R::shear_plane, {{shear_13, 0, 0}}, 1, false, {}});
  candidates_.push_back({R::tension_plane, {{tension_3, 0, 0}}, 1, false, {}});
  candidates_.push_back({R::compression_edge, {{shear_13, shear_12, 0}}, 2, false, {}});
  candidates_.push_back({R::extension_edge, {{shear_13, shear_23, 0}}, 2, false, {}});
  if (!capped) {
    candidates_.push_back({R::shear_tension_edge, {{shear_13, tension_3, 0}}, 2, false, {}});
    candidates_.push_back({R::tension_edge, {{tension_3, tension_2, 0}}, 2, false, {}});
    // Four planes meet here (both shear planes through sigma_2 = sigma_3 and both cut-offs).
    candidates_.push_back({R::compression_tension_corner,
                           {{shear_13, shear_12, tension_3},
                            {shear_13, tension_3, tension_2},
                            {shear_13, shear_12, tension_2},
                            {shear_12, tension_3, tension_2}},
                           3,
                           true,
                           {corner_1, -t, -t}});
    candidates_.push_back({R::extension_tension_corner,
                           {{shear_13, shear_23, tension_3}},
                           3,
                           true,
                           {corner_1, corner_1, -t}});
    candidates_.push_back({R::apex, {{tension_3, tension_2, tension_1}}, 3, true, {-t, -t, -t}});
  } else {
    // The cut-off passes through the apex of the cone: all six planes meet there.
    Candidate apex_corner{R::apex, {}, 3, true, {-t, -t, -t}};
    for (std::size_t a = 0; a < 6; ++a) {
      for (std::size_t b = a + 1; b < 6; ++b) {
        for (std::size_t c = b + 1; c < 6; ++c) {
          apex_corner.plane_sets.push_back({a, b, c});
        }
      }
    }
    candidates_.push_back(std::move(apex_corner));
  }
}

std::span<const std::string> MohrCoulomb::state_names() const {
  static const std::array<std::string, 1> names{"plastic_shear_strain"};
  return names;
}

void MohrCoulomb::initialise_state(const Stress&, double* state) const {
  state[0] = 0.0;
}

double MohrCoulomb::shear_yield_function(const std::array<double, 3>& s) const {
  return s[0] - n_phi_ * s[2] - strength_;
}

MohrCoulombReturn MohrCoulomb::return_principal(const std::array<double, 3>& trial) const {
  MohrCoulombReturn result;
  result.stress = trial;
  std::array<double, 6> f_trial{};
  for (std::size_t i = 0; i < planes_.size(); ++i) {
    f_trial[i] = dot(planes_[i].normal, trial) - planes_[i].level;
  }
  // Rounding of the spectral decomposition alone puts a stress that lies on the surface about
  // 1e-16 of its size outside it; such a state is elastic, not worth a return.
  // The size of the problem: a return never ends farther from the origin than the trial or the
  // shear strength (the cut-off lies between them), so the tension limit stays out of it.
  const double scale = std::abs(trial[0]) + std::abs(trial[1]) + std::abs(trial[2]) + strength_;
  if (f_trial[shear_13] <= 1e-13 * scale && f_trial[tension_3] <= 1e-13 * scale) {
    return result;
  }

  // A candidate is the return when its multipliers are non-negative and the stress it gives is
  // sorted and inside every plane; the tolerance absorbs the rounding of the trial's size.
  const double tolerance = 1e-10 * scale;
  const double stiffness = lambda_ + 2.0 * mu_;
  double best_violation = std::numeric_limits<double>::infinity();
  MohrCoulombReturn best;
  for (const Candidate& candidate : candidates_) {
    for (const std::array<std::size_t, 3>& set : candidate.plane_sets) {
      const std::size_t size = candidate.size;
      std::array<Vector3, 3> a{};
      Vector3 b{}, x{};
      for (std::size_t i = 0; i < size; ++i) {
        b[i] = f_trial[set[i]];
        for (std::size_t j = 0; j < size; ++j) {
          a[i][j] = dot(planes_[set[i]].normal, planes_[set[j]].corrector);
        }
      }
      if (!solve_small(size, a, b, x)) {
        continue;
      }
      MohrCoulombReturn r;
      r.region = candidate.region;
      r.stress = trial;
      Vector3 shear_strain{};
      double violation = 0.0;
      for (std::size_t j = 0; j < size; ++j) {
        const Plane& plane = planes_[set[j]];
        violation = std::max(violation, -x[j] * stiffness);
        for (std::size_t c = 0; c < 3; ++c) {
          r.stress[c] -= x[j] * plane.corrector[c];
          r.plastic_strain[c] += x[j] * plane.flow[c];
          if (plane.shear) {
            shear_strain[c] += x[j] * plane.flow[c];
          }
        }
      }
      if (candidate.corner) {
        // The planes fix the point exactly; the corrected trial would carry its rounding.
        r.stress = candidate.corner_stress;
      }
      r.plastic_shear_strain = *std::max_element(shear_strain.begin(), shear_strain.end()) -
                               *std::min_element(shear_strain.begin(), shear_strain.end());
      violation = std::max({violation, r.stress[1] - r.stress[0], r.stress[2] - r.stress[1]});
      for (const Plane& plane : planes_) {
        violation = std::max(violation, dot(plane.normal, r.stress) - plane.level);
      }
      if (violation <= tolerance) {
        best = r;
        best_violation = violation;
        break;
      }
      if (violation < best_violation) {
        best = r;
        best.nearest = true;
        best_violation = violation;
      }
    }
    if (best_violation <= tolerance) {
      break;
    }
  }

  // Clip what the tolerance let through (and, in the never-expected nearest case, the rest), in an
  // order that keeps each earlier bound: the cut-off, the ordering, then the shear plane.
  Vector3& s = best.stress;
  for (double& value : s) {
    value = std::max(value, -tension_);
  }
  s[1] = std::min(s[1], s[0]);
  s[2] = std::min(s[2], s[1]);
  s[0] = std::min(s[0], n_phi_ * s[2] + strength_);
  s[1] = std::min(s[1], s[0]);
  return best;
}

void MohrCoulomb::update_stress(const StressUpdateBatch& batch) const {
  const double modulus = lambda_ + 2.0 * mu_;
  for (std::size_t k = 0; k < batch.particles.size(); ++k) {
    const StrainIncrement& de = batch.strain[k];
    const auto particle = static_cast<std::size_t>(batch.particles[k]);
    Stress& s = batch.stress[particle];
    // Elastic trial on the full tensor (torsion shears included).
    Stress trial = s;
    add_isotropic_elastic_increment(trial, de, lambda_, mu_);
    const PrincipalStress principal = principal_compression(trial);
    const MohrCoulombReturn r = return_principal(principal.values);
    if (r.region == MohrCoulombRegion::elastic) {
      s = trial; // no recomposition, so elastic steps carry no rounding of the decomposition
    } else {
      // Isotropy: the return keeps the principal directions of the trial.
      s = compose_from_principal(r.stress, principal.directions);
      if (batch.state != nullptr) {
        batch.state[particle * static_cast<std::size_t>(batch.state_stride)] +=
            r.plastic_shear_strain;
      }
    }
    batch.constrained_modulus[k] = modulus;
  }
}

double MohrCoulomb::elastic_energy_density(const Stress& s, const double*) const {
  return isotropic_elastic_energy_density(s, lambda_ + 2.0 * mu_ / 3.0, mu_);
}

} // namespace mpile
