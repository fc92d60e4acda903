// Soil inside a rigid body carries no stress and sets no time step (solver/rigid_interiors.hpp):
// the outline's inside test, a step with soil inside a block, and a pipe jacked into sand with and
// without the rule.
#include "engine/structures/contact.hpp"
#include "solver/rigid_interiors.hpp"
#include "tests/case_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

namespace mpile {
namespace {

TEST(StructureOutline, ContainsTellsTheInsideOfANonConvexOutline) {
  // An L: the square [0, 2] x [0, 2] without its top right quarter.
  StructureOutline outline;
  outline.vertices = {{0.0, 0.0}, {2.0, 0.0}, {2.0, 1.0}, {1.0, 1.0}, {1.0, 2.0}, {0.0, 2.0}};
  outline.edge_surface = {0, 0, 0, 0, 0, 0};
  EXPECT_TRUE(outline.contains(0.5, 0.5));
  EXPECT_TRUE(outline.contains(1.5, 0.5)); // the foot
  EXPECT_TRUE(outline.contains(0.5, 1.5)); // the leg
  // In the notch: inside the convex hull, outside the outline (the largest distance to the edges'
  // lines, exact for convex outlines only, would call it inside).
  EXPECT_FALSE(outline.contains(1.5, 1.5));
  EXPECT_FALSE(outline.contains(-0.1, 0.5));
  EXPECT_FALSE(outline.contains(0.5, 2.1));
  EXPECT_FALSE(outline.contains(2.5, 0.5));
  // At the height of a vertex (y = 1, where two edges meet) the crossing is counted once.
  EXPECT_TRUE(outline.contains(0.5, 1.0));
  EXPECT_FALSE(outline.contains(2.5, 1.0));
  EXPECT_EQ(outline.bounds(), (std::array<double, 4>{0.0, 2.0, 0.0, 2.0}));
}

/// Elastic soil to y = 2 m and a rigid block [0.51, 0.59] x [2.0, 2.1] resting on it, held still
/// (a case may not seed overlapping bodies; the test moves the block's outline into the soil).
std::string soil_under_block(bool stress_free) {
  std::string text =
      replaced(replaced(std::string(block_above_soil), "r = [0.5, 0.6], y = [2.3, 2.4]",
                        "r = [0.51, 0.59], y = [2.0, 2.1]"),
               "[moving_mesh]\nbody = \"block\"\nband = [1.0, 1.4]\ntravel = 0.2\n", "");
  text = replaced(text, "velocity_y = -0.5", "velocity_y = 0.0");
  return text + "[solver]\nstress_free_inside_rigid = " + (stress_free ? "true" : "false") +
         "\n[[phases]]\nname = \"still\"\nduration = 0.1\n";
}

struct OneStep {
  double stable_dt = 0.0;
  int inside = 0, inside_stress_free = 0, dense_inside_stressed = 0, outside_stressed = 0,
      outside = 0;
};

/// One step of the block scene with the outline 85 mm down in the soil, to [0.51, 0.59] x [1.915,
/// 2.015]: the four soil particles at r = 0.525 and 0.575, y = 1.925 and 1.975 (two per 0.1 m
/// cell and axis) lie inside it. Every particle starts at -10 kPa; three of the four inside are
/// stretched to a hundredth of their density, as in a pile wall, so the rule takes them; the
/// fourth keeps its density, as soil the surface has just overtaken, and its stress.
OneStep step_with_soil_inside(bool stress_free) {
  CaseRun run(soil_under_block(stress_free));
  run.scene->contacts.at(0).outline->translate(0.0, -0.085);
  Particles& p = run.scene->particles;
  const StructureOutline& outline = *run.scene->contacts.at(0).outline;
  std::vector<char> inside(p.size(), 0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.stress[i] = {-1e4, -1e4, -1e4, 0.0, 0.0, 0.0};
    if (run.scene->body_names[p.body[i]] == "soil" && outline.contains(p.r[i], p.y[i])) {
      const bool first = std::count(inside.begin(), inside.end(), 2) == 0;
      inside[i] = first ? 2 : 1; // 2: left dense
      if (!first) {
        p.volume[i] *= 100.0;
      }
    }
  }
  // A solver made after the changes, so that its first step is judged on them too.
  run.solver = std::make_unique<ExplicitSolver>(
      *run.scene, phase_settings(run.spec, run.spec.phases[0]), run.log);
  run.solver->step(1.0);
  OneStep out;
  out.stable_dt = run.solver->stable_time_step();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (run.scene->body_names[p.body[i]] != "soil") {
      continue;
    }
    const bool free = p.stress[i] == Stress{};
    if (inside[i] == 2) {
      ++out.inside;
      out.dense_inside_stressed += free ? 0 : 1;
    } else if (inside[i] == 1) {
      ++out.inside;
      out.inside_stress_free += free ? 1 : 0;
    } else {
      ++out.outside;
      out.outside_stressed += free ? 0 : 1;
    }
  }
  return out;
}

TEST(StressFreeInsideRigid, SoilInsideARigidBodyLosesItsStressAndSetsNoStep) {
  const OneStep with = step_with_soil_inside(true);
  const OneStep without = step_with_soil_inside(false);
  EXPECT_EQ(with.inside, 4);
  EXPECT_EQ(with.inside_stress_free, 3);
  EXPECT_EQ(with.dense_inside_stressed, 1);
  EXPECT_EQ(with.outside_stressed, with.outside);
  EXPECT_EQ(without.inside_stress_free, 0);
  // Stretched a hundred times, the three particles' wave speed is ten times the soil's: without
  // the rule they set a step about ten times shorter. With it the soil outside sets the step,
  // which the rule leaves as it is.
  EXPECT_LT(without.stable_dt * 5.0, with.stable_dt);
  std::cout << "stable step after one step: " << with.stable_dt << " s with the rule, "
            << without.stable_dt << " s without\n";
}

/// A thick pipe (wall 0.1 m over two 0.05 m cells) jacked at 1 m/s into Mohr-Coulomb sand on the
/// moving mesh with GIMP, for 0.35 s: soil from below the tip ends up inside the wall.
std::string jacked_pipe(bool stress_free) {
  return jacked_thick_pile("wall_cells = 2\nband_below = 0.5\nband_above = 0.5\n",
                           std::string("shape_functions = \"gimp\"\nstress_free_inside_rigid = ") +
                               (stress_free ? "true" : "false") + "\n",
                           0.35);
}

struct Jacked {
  double first_dt = 0.0, min_dt = 1.0; // the first step and the shortest stable step after it
  double tip_y[2]{}, inner_r[2]{}, outer_r[2]{}; // means over 0.08-0.12 and 0.18-0.22 m (N/rad)
};

Jacked jack_rigid_interior(bool stress_free) {
  CaseRun run(jacked_pipe(stress_free));
  apply_k0(*run.scene, run.spec, run.spec.phases[0]);
  Jacked out;
  int samples[2] = {0, 0};
  run.run([&] {
    if (out.first_dt == 0.0) {
      out.first_dt = run.solver->last_time_step();
    }
    out.min_dt = std::min(out.min_dt, run.solver->stable_time_step());
    const double penetration = -run.scene->rigid_bodies[0].displacement[RIGID_Y];
    for (int k = 0; k < 2; ++k) {
      const double depth = 0.1 * (k + 1);
      if (std::abs(penetration - depth) <= 0.02) {
        out.tip_y[k] += run.surface_force("tip", 1);
        out.inner_r[k] += run.surface_force("internal_shaft", 0);
        out.outer_r[k] += run.surface_force("external_shaft", 0);
        ++samples[k];
      }
    }
  });
  for (int k = 0; k < 2; ++k) {
    out.tip_y[k] /= samples[k];
    out.inner_r[k] /= samples[k];
    out.outer_r[k] /= samples[k];
  }
  return out;
}

TEST(StressFreeInsideRigid, AJackedPipeKeepsItsStepAndItsForces) {
  const Jacked with = jack_rigid_interior(true);
  const Jacked without = jack_rigid_interior(false);
  // Without the rule, soil stretched inside the wall cuts the step to 0.47 of the first by
  // 0.35 m (the log names a particle inside the wall at a third of its density); with it the
  // shortest step is 0.70 of the first (set by soil squeezed beside the tip, which is real). The
  // bounds sit between the two.
  EXPECT_LT(without.min_dt, 0.55 * without.first_dt);
  EXPECT_GT(with.min_dt, 0.6 * with.first_dt);
  // The particles made stress-free were stretched to under half their density, where their
  // stresses had fallen near zero, so the forces hardly move: the same to the digit at 0.1 m
  // (none yet), 1.2 to 1.5 % at 0.2 m. 2 % bounds that with room for the step-to-step scatter of
  // the reactions, which the different step lengths sample differently.
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(with.tip_y[k] / without.tip_y[k], 1.0, 0.02) << k;
    EXPECT_NEAR(with.inner_r[k] / without.inner_r[k], 1.0, 0.02) << k;
    EXPECT_NEAR(with.outer_r[k] / without.outer_r[k], 1.0, 0.02) << k;
  }
  std::cout << "shortest step / first: " << with.min_dt / with.first_dt << " with the rule, "
            << without.min_dt / without.first_dt
            << " without; tip F_y at 0.1, 0.2 m: " << with.tip_y[0] << ", " << with.tip_y[1]
            << " against " << without.tip_y[0] << ", " << without.tip_y[1]
            << " N/rad; ratios of internal, external F_r: " << with.inner_r[0] / without.inner_r[0]
            << ", " << with.inner_r[1] / without.inner_r[1] << ", "
            << with.outer_r[0] / without.outer_r[0] << ", " << with.outer_r[1] / without.outer_r[1]
            << "\n";
}

} // namespace
} // namespace mpile
