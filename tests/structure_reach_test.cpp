// A contact structure's field is worked on only in its reach (NodeField::reach): the nodes its
// particles can touch. These tests hold the two promises that makes: the reach holds every node a
// structure particle scatters to, whatever its motion across blocks and cells, and outside it the
// field is exactly zero; and a structure with no particles changes nothing in the soil.
#include "cases/verification/verification_case.hpp"
#include "engine/materials/linear_elastic.hpp"
#include "engine/particle_fill.hpp"
#include "engine/shape_functions.hpp"
#include "solver/explicit_solver.hpp"
#include "tests/bitwise.hpp"

#include <gtest/gtest.h>

#include <cstring>

namespace mpile {
namespace {

/// A soil layer, and (when `block_speed` is given) an elastic block thrown at it across the grid.
/// Small blocks of cells make the thrown block cross many of them.
struct Throw {
  Scene scene;
  SolverSettings settings;

  Throw(ShapeFunctions shape, bool structure, bool block_particles)
      : scene(GeometryMode::plane_strain,
              Grid(GradedAxis::uniform(0.0, 2.0, 40), GradedAxis::uniform(0.0, 2.0, 40))) {
    const auto soil = scene.add_material(std::make_unique<LinearElastic>(2e6, 0.3, 1800.0));
    const auto steel = scene.add_material(std::make_unique<LinearElastic>(2e7, 0.3, 2500.0));
    fill_rectangle(scene, {0.0, 2.0, 0.0, 0.6}, 2, soil, scene.add_body("soil"));
    if (structure) {
      const auto block = scene.add_body("block");
      if (block_particles) {
        fill_rectangle(scene, {0.3, 0.55, 1.2, 1.45}, 2, steel, block);
        for (std::size_t i = 0; i < scene.particles.size(); ++i) {
          if (scene.particles.body[i] == block) {
            scene.particles.v_r[i] = 5.0;
            scene.particles.v_y[i] = -5.0;
          }
        }
      }
      scene.add_contact_structure(block).friction = 0.3;
    }
    // Plane strain: a block moving sideways in axisymmetry would be a ring stretched round.
    constexpr GeometryMode mode = GeometryMode::plane_strain;
    scene.boundaries.constraints = {
        face_constraint(scene.grid, mode, GridFace::y_min, FaceCondition::fixed),
        face_constraint(scene.grid, mode, GridFace::r_min, FaceCondition::roller),
        face_constraint(scene.grid, mode, GridFace::r_max, FaceCondition::roller)};
    settings.gravity = {0.0, -9.81};
    settings.shape_functions = shape;
    settings.block_cells = shape == ShapeFunctions::gimp ? 3 : 2;
    settings.local_damping = 0.05;
  }
};

template <ShapeFunctions shape> void expect_reach_holds_the_structure() {
  Throw t(shape, true, true);
  RunLog log;
  ExplicitSolver solver(t.scene, t.settings, log);
  const Grid& grid = t.scene.grid;
  const NodeField& field = grid.structure_fields.at(0);
  const ContactPair& pair = t.scene.contacts.at(0);
  const Particles& p = t.scene.particles;
  const std::uint16_t block = t.scene.contacts[0].structure_body;
  int steps_in_contact = 0;
  std::vector<NodeBox> reaches;
  for (int s = 0; s < 500; ++s) {
    solver.step();
    // Every node a block particle scatters to in the next step lies in the reach.
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.body[i] != block) {
        continue;
      }
      const auto w = particle_weights<shape>(grid, p, i);
      for (int k = 0; k < w.size; ++k) {
        if (w.N[k] != 0.0 || w.dN_dr[k] != 0.0 || w.dN_dy[k] != 0.0) {
          ASSERT_TRUE(
              field.reach.contains_node(static_cast<std::size_t>(w.node[k]), grid.nodes_r()))
              << "step " << s << ": node " << w.node[k] << " of particle " << i;
        }
      }
    }
    // Outside the box the step worked on, the field and the contact results are exactly zero.
    bool any_force = false;
    for (std::size_t n = 0; n < grid.node_count(); ++n) {
      if (!field.held.contains_node(n, grid.nodes_r())) {
        const GridNode zero{};
        ASSERT_EQ(std::memcmp(&field.nodes[n], &zero, sizeof(GridNode)), 0)
            << "step " << s << ", node " << n;
        ASSERT_EQ(field.mass_gradient[n][0], 0.0);
        ASSERT_EQ(field.mass_gradient[n][1], 0.0);
      }
      const auto& f = pair.node_force[n];
      if (!pair.written.contains_node(n, grid.nodes_r())) {
        ASSERT_TRUE(f[0] == 0.0 && f[1] == 0.0 && f[2] == 0.0 && pair.state[n] == 0)
            << "step " << s << ", node " << n;
      }
      any_force = any_force || f[0] != 0.0 || f[1] != 0.0;
    }
    steps_in_contact += any_force ? 1 : 0;
    if (reaches.empty() || !(reaches.back() == field.reach)) {
      reaches.push_back(field.reach);
    }
  }
  // The test means something only if the block crossed blocks of cells and hit the soil.
  EXPECT_GT(reaches.size(), 5u);
  EXPECT_GT(steps_in_contact, 50);
  // The reach is a small part of the grid: the point of it.
  EXPECT_LT(field.reach.count(), grid.node_count() / 4);
}

TEST(StructureReach, HoldsEveryNodeAThrownBlockTouchesAndTheFieldIsZeroOutsideIt) {
  expect_reach_holds_the_structure<ShapeFunctions::linear>();
}

TEST(StructureReach, HoldsEveryNodeAThrownBlockTouchesWithGimpDomains) {
  expect_reach_holds_the_structure<ShapeFunctions::gimp>();
}

Particles settle(bool idle_structure, int threads) {
  Particles particles;
  with_threads(threads, [&] {
    Throw t(ShapeFunctions::gimp, idle_structure, false);
    RunLog log;
    ExplicitSolver solver(t.scene, t.settings, log);
    for (int s = 0; s < 200; ++s) {
      solver.step();
    }
    if (idle_structure) {
      EXPECT_TRUE(t.scene.grid.structure_fields.at(0).reach.empty());
    }
    particles = t.scene.particles;
  });
  return particles;
}

TEST(StructureReach, AStructureWithoutParticlesLeavesTheSoilBitwiseAsWithoutContact) {
  // The contact code path runs, with nothing to do: the soil's results must be those of the
  // single-field path to the last bit, on one thread and on two.
  const Particles plain = settle(false, 1);
  expect_particles_identical(settle(true, 1), plain);
  expect_particles_identical(settle(true, 2), plain);
}

TEST(StructureReach, AThrownBlockGivesBitwiseIdenticalResultsOnOneAndTwoThreads) {
  Particles results[2];
  for (int threads : {1, 2}) {
    with_threads(threads, [&] {
      Throw t(ShapeFunctions::gimp, true, true);
      RunLog log;
      ExplicitSolver solver(t.scene, t.settings, log);
      for (int s = 0; s < 300; ++s) {
        solver.step();
      }
      results[threads - 1] = t.scene.particles;
    });
  }
  expect_particles_identical(results[0], results[1]);
}

} // namespace
} // namespace mpile
