#pragma once

// A case built from TOML text and stepped through its first phase by the tests, with the helpers
// they share for reading and editing case files.
#include "cases/case_builder.hpp"
#include "cases/case_spec.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/phase_runner.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>

namespace mpile {

inline const std::filesystem::path source = MPILE_SOURCE_DIR;

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// An empty directory under the system's temporary directory, named mpile_test_<name>.
inline std::filesystem::path fresh_directory(const std::string& name) {
  const auto directory = std::filesystem::temp_directory_path() / ("mpile_test_" + name);
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  return directory;
}

/// The text with every occurrence of `from` replaced by `to` (at least one must exist).
inline std::string replaced(std::string text, const std::string& from, const std::string& to) {
  std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  while (at != std::string::npos) {
    text.replace(at, from.size(), to);
    at = text.find(from, at + to.size());
  }
  return text;
}

/// A case built from text and run through its first phase by the phase runner, as `mpile run` runs
/// it (its end criteria and the energy guard included), with a callback after every step.
struct CaseRun {
  CaseSpec spec;
  std::unique_ptr<Scene> scene;
  RunLog log;
  std::unique_ptr<ExplicitSolver> solver;

  explicit CaseRun(const std::string& text) : spec(read_case_text(text, "test.toml")) {
    scene = build_scene(spec);
    solver = std::make_unique<ExplicitSolver>(*scene, phase_settings(spec, spec.phases[0]), log);
    // As `mpile run` does at the first phase's start (the K0 procedure is left to the test).
    switch_on_absorbing_faces(*solver, spec, 0);
  }
  template <class F> void run(F&& after_step) {
    struct EachStep final : RunObserver {
      explicit EachStep(F& f) : callback(f) {}
      void stepped(const RunPhase&, long, const PhaseGoal&) override { callback(); }
      F& callback;
    };
    EachStep observer(after_step);
    const std::vector<RunPhase> phases{spec.phases[0]};
    RunProgress progress;
    begin_phase(progress, phases, *scene, 0, solver->time());
    OutputSchedule no_outputs;
    no_outputs.history_interval = std::numeric_limits<double>::infinity();
    PhaseRunner runner(*solver, phases, no_outputs, progress, log);
    runner.add_observer(observer);
    runner.start();
    runner.run([](std::size_t, double) {}, [](long) { return false; });
  }
  const ContactPair& pair() const { return scene->contacts.at(0); }
  double surface_force(const std::string& surface, int component) const {
    return pair().surface_force[surface_index(surface)][static_cast<std::size_t>(component)];
  }
  /// The pore water's part of a surface's force (r or y), with pore water in the soil.
  double surface_pore_force(const std::string& surface, int component) const {
    return pair().surface_pore_force[surface_index(surface)][static_cast<std::size_t>(component)];
  }
  std::size_t surface_index(const std::string& surface) const {
    for (std::size_t q = 0; q < pair().surfaces.size(); ++q) {
      if (pair().surfaces[q] == surface) {
        return q;
      }
    }
    ADD_FAILURE() << "no surface " << surface;
    return 0;
  }
};

/// Elastic soil 2 m deep on a fixed base, and a rigid block above it driven down at 0.5 m/s that
/// never reaches it, under a moving mesh whose band (y from 1 to 1.4 m) follows the block for up to
/// 0.2 m: the case's grid, bodies and boundaries, without solver settings or phases.
inline const char* block_above_soil = R"(geometry = "axisymmetric"
[grid]
r = [{ start = 0.0, end = 1.0, cells = 10 }]
y = [{ start = 0.0, end = 1.0, cells = 10 }, { start = 1.0, end = 1.4, cells = 8 },
     { start = 1.4, end = 2.5, cells = 11 }]
[materials.soil]
type = "linear_elastic"
young_modulus = 50e6
poisson_ratio = 0.3
density = 1650.0
[materials.steel]
type = "linear_elastic"
young_modulus = 200e9
poisson_ratio = 0.0
density = 8000.0
[[bodies]]
name = "soil"
material = "soil"
region = { r = [0.0, 1.0], y = [0.0, 2.0] }
[[bodies]]
name = "block"
material = "steel"
region = { r = [0.5, 0.6], y = [2.3, 2.4] }
[bodies.rigid]
velocity_y = -0.5
[[contact]]
structure = "block"
[boundaries]
r_max = "roller"
y_min = "fixed"
[moving_mesh]
body = "block"
band = [1.0, 1.4]
travel = 0.2
)";

/// A small open pile (D = 1 m, wall 0.1 m, one cell across it unless `monopile_extra` says
/// otherwise) in Mohr-Coulomb soil on the moving mesh, jacked at 1 m/s after a 0.1 s ramp for
/// `duration` seconds: a thick wall and a coarse mesh keep it short. `monopile_extra` and
/// `solver_extra` are lines added to those tables (band sizes, wall cells, solver choices).
inline std::string jacked_thick_pile(const std::string& monopile_extra,
                                     const std::string& solver_extra, double duration) {
  std::ostringstream s;
  s << R"(
title = "jacked thick pile"
[materials.soil]
type = "mohr_coulomb"
young_modulus = 20e6
poisson_ratio = 0.3
cohesion = 5e3
friction_angle = 30.0
density = 1800.0
[materials.steel]
type = "linear_elastic"
young_modulus = 200e9
poisson_ratio = 0.0
density = 8000.0
[monopile]
pile_length = 4.0
diameter = 1.0
wall_thickness = 0.1
embedment = 1.0
soil_width = 2.5
soil_depth = 5.0
head_room = 0.8
fine_cell = 0.1
fine_width = 0.2
shaft_cell = 0.1
coarse_cell = 0.4
soil_material = "soil"
pile_material = "steel"
friction = 0.4
)" << monopile_extra
    << R"(
[monopile.drive]
velocity_y = { type = "ramp", value = -1.0, duration = 0.1 }
angular_velocity = 0.0
[solver]
gravity = [0.0, -9.81]
flip_fraction = 0.99
)" << solver_extra
    << R"(
[[phases]]
name = "jacking"
duration = )"
    << duration << R"(
k0 = [{ material = "soil", surface = 5.0, k0 = 0.5 }]
)";
  return s.str();
}

} // namespace mpile
