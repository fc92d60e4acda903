// Particles that grow larger than their cells are split (engine/particle_split.hpp). The split
// itself keeps every sum the grid sees; a bar crossing a factor-4 grading step then hits a wall
// with the impulse of the closed form, which without splitting it misses by half.
#include "cases/verification/verification_case.hpp"
#include "engine/materials/linear_elastic.hpp"
#include "engine/particle_fill.hpp"
#include "engine/particle_split.hpp"
#include "tests/bitwise.hpp"
#include "tests/case_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace mpile {
namespace {

struct Sums {
  double mass = 0.0, volume = 0.0, momentum_r = 0.0, momentum_y = 0.0, angular = 0.0;
  double weighted_stress = 0.0; // sum V sigma_rr
  double reference_r = 0.0;     // sum m (r - r0): the displacement's mass-weighted sum
};

Sums sums(const Particles& p) {
  Sums s;
  for (std::size_t i = 0; i < p.size(); ++i) {
    s.mass += p.mass[i];
    s.volume += p.volume[i];
    s.momentum_r += p.mass[i] * p.v_r[i];
    s.momentum_y += p.mass[i] * p.v_y[i];
    s.angular += p.v_theta.empty() ? 0.0 : p.mass[i] * p.r[i] * p.v_theta[i];
    s.weighted_stress += p.volume[i] * p.stress[i][RR];
    s.reference_r += p.mass[i] * (p.r[i] - p.r0[i]);
  }
  return s;
}

void expect_same(const Sums& a, const Sums& b) {
  // Round-off of sums of a few dozen terms.
  constexpr double tolerance = 1e-13;
  EXPECT_NEAR(a.mass, b.mass, tolerance * std::abs(a.mass));
  EXPECT_NEAR(a.volume, b.volume, tolerance * std::abs(a.volume));
  EXPECT_NEAR(a.momentum_r, b.momentum_r, tolerance * std::abs(a.mass));
  EXPECT_NEAR(a.momentum_y, b.momentum_y, tolerance * std::abs(a.mass));
  EXPECT_NEAR(a.angular, b.angular, tolerance * std::abs(a.mass));
  EXPECT_NEAR(a.weighted_stress, b.weighted_stress, tolerance * std::abs(a.weighted_stress));
  EXPECT_NEAR(a.reference_r, b.reference_r, tolerance * std::abs(a.mass));
}

/// Particles seeded 2 x 2 per cell of a 0.4 m grid, then regridded onto a grid whose cells are four
/// times smaller along r and twice along y over part of the body, as if they had moved there.
void split_and_check(GeometryMode mode) {
  Scene seeded(mode, verification::uniform_grid(0.0, 1.6, 4, 0.0, 1.6, 4));
  const auto material = seeded.add_material(std::make_unique<LinearElastic>(1e6, 0.3, 2000.0));
  fill_rectangle(seeded, {0.0, 1.6, 0.0, 1.6}, 2, material, seeded.add_body("body"));
  Particles& p = seeded.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.v_r[i] = 0.1 * p.y[i];
    p.v_y[i] = -0.2 * p.r[i];
    if (has_theta(mode)) {
      p.v_theta[i] = 0.3 * p.r[i] + 0.1;
    }
    p.stress[i] = {-1e3 * p.y[i], -2e3, -1e3, 50.0, 0.0, 0.0};
    p.r0[i] = p.r[i] - 0.01; // a displacement of 1 cm, which the halves must keep
  }
  const AxisZone r_zones[] = {{0.0, 0.8, 8}, {0.8, 1.6, 2}}; // 0.1 m cells, then 0.4 m
  const AxisZone y_zones[] = {{0.0, 0.8, 4}, {0.8, 1.6, 2}}; // 0.2 m cells, then 0.4 m
  const Grid fine{GradedAxis(r_zones), GradedAxis(y_zones)};
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.cell_r[i] = fine.r_axis().locate(p.r[i]);
    p.cell_y[i] = fine.y_axis().locate(p.y[i]);
  }
  const Sums before = sums(p);
  const std::size_t count = p.size();
  const std::vector<std::int32_t> ids_before = p.id;
  const auto parents = split_oversized_particles(p, fine, mode);
  // The 0.2 m particles in the 0.1 m columns halve along r once (their 0.2 and 0.4 m rows hold
  // them along y); none elsewhere.
  std::size_t in_fine = 0;
  for (std::size_t i = 0; i < count; ++i) {
    in_fine += p.r[i] < 0.8 ? 1 : 0;
  }
  EXPECT_EQ(parents.size(), in_fine);
  EXPECT_EQ(p.size(), count + parents.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_FALSE(oversized(p, fine, i)) << i;
    EXPECT_EQ(p.cell_r[i], fine.r_axis().locate(p.r[i]));
    EXPECT_EQ(p.cell_y[i], fine.y_axis().locate(p.y[i]));
  }
  expect_same(before, sums(p));
  // A particle keeps its id; each new half takes a new one.
  for (std::size_t i = 0; i < count; ++i) {
    EXPECT_EQ(p.id[i], ids_before[i]);
  }
  for (std::size_t i = count; i < p.size(); ++i) {
    EXPECT_EQ(p.id[i], static_cast<std::int32_t>(i));
  }
  EXPECT_EQ(p.next_id, static_cast<std::int32_t>(p.size()));
}

TEST(ParticleSplit, KeepsMassVolumeMomentumStressAndDisplacementAxisymmetric) {
  split_and_check(GeometryMode::axisymmetric);
}

TEST(ParticleSplit, KeepsMassVolumeMomentumStressAndDisplacementInPlaneStrain) {
  split_and_check(GeometryMode::plane_strain);
}

// An elastic bar (nu = 0, so one-dimensional) moving at v0 = 1 m/s from 0.2 m cells into 0.05 m
// cells, then hitting a wall: elastic rebound reverses its momentum, so the wall's impulse is
// 2 m v0 = 0.48 N s/m, delivered in 2 L / c = 0.12 s. Seeded 2 x 2 per coarse cell, its particles
// are 0.1 m long: without splitting every other fine cell between them is empty.
const char* bar = R"(title = "bar crossing a grading step"
geometry = "plane_strain"
[grid]
r = [{ start = 0.0, end = 2.0, cells = 10 }, { start = 2.0, end = 3.0, cells = 20 }]
y = [{ start = 0.0, end = 0.4, cells = 2 }]
[materials.bar]
type = "linear_elastic"
young_modulus = 100.0
poisson_ratio = 0.0
density = 1.0
[[bodies]]
name = "bar"
material = "bar"
region = { r = [0.4, 1.0], y = [0.0, 0.4] }
velocity = [1.0, 0.0, 0.0]
[boundaries]
y_min = "roller"
y_max = "roller"
r_max = "roller"
[solver]
courant_number = 0.5
[[phases]]
name = "move"
duration = 2.3
)";

struct Impact {
  double impulse = 0.0;       // of the wall on the bar (N s/m)
  double first_contact = 0.0; // the time the wall first pushes (s)
  double peak_residual = 0.0; // the energy balance's largest relative residual
  std::size_t particles = 0;
};

Impact impact(const std::string& text) {
  CaseRun run(text);
  Impact result;
  run.run([&] {
    const double force = run.scene->boundaries.constraint("r_max").reaction[0];
    if (force != 0.0 && result.first_contact == 0.0) {
      result.first_contact = run.solver->time();
    }
    result.impulse += force * run.solver->last_time_step();
    result.peak_residual =
        std::max(result.peak_residual, run.solver->energy_balance().relative_residual);
  });
  result.particles = run.scene->particles.size();
  return result;
}

TEST(ParticleSplit, ABarCrossingAGradingStepHitsTheWallWithTheImpulseOfTheClosedForm) {
  constexpr double exact = -2.0 * 1.0 * 0.6 * 0.4 * 1.0; // -2 rho L H v0
  const Impact split = impact(bar);
  EXPECT_EQ(split.particles, 48u); // 24 seeded; each halves once in the fine cells
  // Measured 0.8 % off; the same bar on a uniform 0.05 m grid is 1.3 % off, so 2 % is the
  // discretisation's own error with a margin.
  EXPECT_NEAR(split.impulse, exact, 0.02 * std::abs(exact));
  // The front (at r = 1 m) reaches the wall at t = 2 s; contact begins once the last cell, 0.05 m
  // wide, holds the front particles' mass: from 1.95 s.
  EXPECT_GT(split.first_contact, 1.95);
  EXPECT_LT(split.first_contact, 2.0);
  // The balance closes to the error of bilinear weights crossing cells at one particle per fine
  // cell (measured 12 %; 4.6 % with GIMP), well inside the guard's 50 %.
  EXPECT_LT(split.peak_residual, 0.2);

  const Impact starved = impact(
      replaced(bar, "courant_number = 0.5", "courant_number = 0.5\nsplit_particles = false"));
  EXPECT_EQ(starved.particles, 24u);
  // Without splitting the bar's energy is not accounted for (measured: 110 % of it): the run
  // guard would stop it as unstable.
  EXPECT_GT(starved.peak_residual, 0.5);
  std::cout << "impulse / 2 m v0 - 1: " << split.impulse / exact - 1.0 << ", peak residual "
            << split.peak_residual << "; without splitting " << starved.peak_residual << '\n';
}

TEST(ParticleSplit, ResultsAreBitwiseIdenticalOnOneAndTwoThreads) {
  const auto particles_after = [](int threads) {
    Particles result;
    with_threads(threads, [&] {
      CaseRun run(bar);
      run.run([] {});
      result = run.scene->particles;
    });
    return result;
  };
  const Particles one = particles_after(1);
  ASSERT_EQ(one.size(), 48u);
  expect_particles_identical(one, particles_after(2));
}

} // namespace
} // namespace mpile
