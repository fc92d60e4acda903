// The guards that stop a run going wrong: each must stop it with a message naming the cause, the
// step and where, and `mpile run` must leave a readable history saying how the run ended.
#include "app/run_command.hpp"
#include "case_run.hpp"
#include "engine/materials/linear_elastic.hpp"
#include "engine/particle_fill.hpp"
#include "io/hdf5_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

namespace mpile {
namespace {

const char* column = R"(title = "elastic column"
geometry = "plane_strain"
[grid]
r = [{ start = 0.0, end = 1.0, cells = 10 }]
y = [{ start = 0.0, end = 2.0, cells = 20 }]
[materials.soil]
type = "linear_elastic"
young_modulus = 10e6
poisson_ratio = 0.3
density = 2000.0
[[bodies]]
name = "column"
material = "soil"
region = { r = [0.0, 1.0], y = [0.0, 1.5] }
[boundaries]
r_min = "roller"
r_max = "roller"
y_min = "fixed"
[solver]
gravity = [0.0, -9.81]
courant_number = 0.8
[[phases]]
name = "load"
duration = 0.05
[output]
history_interval = 0.0
)";

/// The message of the SimulationError a run stops with ("" if it does not stop).
std::string stop_message(CaseRun& run) {
  try {
    run.run([] {});
  } catch (const SimulationError& e) {
    return e.what();
  }
  return "";
}

TEST(Guards, CourantNumberAboveOneStopsTheFirstStep) {
  CaseRun run(replaced(column, "courant_number = 0.8", "courant_number = 1.2"));
  const std::string message = stop_message(run);
  EXPECT_EQ(message.rfind("step 1, t = ", 0), 0u) << message;
  EXPECT_NE(message.find("the Courant number reached 1.2"), std::string::npos) << message;
  EXPECT_NE(message.find("lower courant_number"), std::string::npos) << message;
}

TEST(Guards, CourantNumberJustBelowOneRunsAndOneItselfStops) {
  // 0.95 leaves room for the particles' acceleration under gravity; at 1.0 the first step's
  // acceleration already shortens the crossing time (1.00015 after one step here), so the guard
  // stops it: 1 is the limit, not a setting.
  CaseRun below(replaced(column, "courant_number = 0.8", "courant_number = 0.95"));
  EXPECT_EQ(stop_message(below), "");
  CaseRun limit(replaced(column, "courant_number = 0.8", "courant_number = 1.0"));
  EXPECT_NE(stop_message(limit).find("the Courant number reached 1.0"), std::string::npos);
}

TEST(Guards, ParticlesEnteringSmallerCellsShortenTheNextStepWithoutStoppingTheRun) {
  // A block translating at 2 m/s from cells of 0.2 m into cells of 0.05 m: a particle's crossing
  // time drops fourfold as it crosses, so the step it crossed in has a Courant number of 3.2 in
  // its new cell. That step was computed in the old cell, where it had 0.8: the run goes on and
  // the next step follows the small cells. Uniform translation is exact in MPM, so the block
  // keeps its speed to rounding.
  std::string text = replaced(column, "cells = 10", "cells = 5");
  text = replaced(
      text, "y = [{ start = 0.0, end = 2.0, cells = 20 }]",
      "y = [{ start = 0.0, end = 1.0, cells = 5 }, { start = 1.0, end = 2.0, cells = 20 }]");
  text = replaced(text, "region = { r = [0.0, 1.0], y = [0.0, 1.5] }",
                  "region = { r = [0.2, 0.8], y = [0.2, 0.6] }\nvelocity = [0.0, 2.0, 0.0]");
  text = replaced(text, "gravity = [0.0, -9.81]", "gravity = [0.0, 0.0]");
  text = replaced(text, "duration = 0.05", "duration = 0.3");
  CaseRun run(text);
  const double c_p = std::sqrt(10e6 * 0.7 / (1.3 * 0.4) / 2000.0);
  const double first_dt = run.solver->stable_time_step();
  EXPECT_NEAR(first_dt, 0.8 * 0.2 / (c_p + 2.0), 1e-9 * first_dt);
  EXPECT_EQ(stop_message(run), "");
  // The leading particles are in the 0.05 m cells now (front at 0.6 + 2 x 0.3 = 1.2 m).
  EXPECT_NEAR(run.solver->stable_time_step(), 0.8 * 0.05 / (c_p + 2.0), 1e-6 * first_dt);
  const Particles& p = run.scene->particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    ASSERT_NEAR(p.v_y[i], 2.0, 1e-9);
  }
}

TEST(Guards, TimeStepBelowTheFloorStops) {
  CaseRun run(
      replaced(column, "courant_number = 0.8", "courant_number = 0.8\nmin_time_step = 1.0"));
  const std::string message = stop_message(run);
  EXPECT_NE(message.find("the time step collapsed to"), std::string::npos) << message;
  EXPECT_NE(message.find("below the floor of 1 s (min_time_step)"), std::string::npos) << message;
}

TEST(Guards, NonFiniteNodeIsNamedWithItsPosition) {
  CaseRun run(column);
  Particles& p = run.scene->particles;
  // Poison one particle's stress: its internal force reaches the nodes of its cell first.
  std::size_t target = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.r0[i] > 0.5 && p.r0[i] < 0.6 && p.y0[i] > 1.0 && p.y0[i] < 1.1) {
      target = i;
    }
  }
  p.stress[target][YY] = std::numeric_limits<double>::quiet_NaN();
  const std::string message = stop_message(run);
  EXPECT_NE(message.find("step 1, t = 0 s: node "), std::string::npos) << message;
  EXPECT_NE(message.find("has a non-finite velocity"), std::string::npos) << message;
  // One of the four nodes of the particle's cell, (0.5 or 0.6, 1.0 or 1.1).
  const bool corner = message.find("(0.5, 1)") != std::string::npos ||
                      message.find("(0.6, 1)") != std::string::npos ||
                      message.find("(0.5, 1.1)") != std::string::npos ||
                      message.find("(0.6, 1.1)") != std::string::npos;
  EXPECT_TRUE(corner) << message;
}

/// What goes wrong for one particle while its material is otherwise linear elastic: its stress
/// update returns a non-finite stress, or a NaN modulus with a finite stress (which only its wave
/// speed shows), or the modulus it reports for a marked stress is NaN from the start.
enum class Fault { stress, update_modulus, start_modulus };

class FailingAtOneParticle final : public Material {
public:
  FailingAtOneParticle(std::int32_t particle, Fault fault)
      : elastic_(10e6, 0.3, 2000.0), particle_(particle), fault_(fault) {}
  std::string_view type() const override { return "failing"; }
  double density() const override { return elastic_.density(); }
  void update_stress(const StressUpdateBatch& batch) const override {
    elastic_.update_stress(batch);
    for (std::size_t k = 0; k < batch.particles.size(); ++k) {
      const std::int32_t i = batch.particles[k];
      if (i == particle_ && fault_ == Fault::stress) {
        batch.stress[i][RR] = std::numeric_limits<double>::infinity();
      } else if (i == particle_ && fault_ == Fault::update_modulus) {
        batch.constrained_modulus[k] = std::numeric_limits<double>::quiet_NaN();
      }
    }
  }
  /// The modulus for a stress: NaN for the stress `mark` sets (1 Pa of r-theta shear, which a
  /// plane-strain column's particles never carry otherwise) under Fault::start_modulus.
  double constrained_modulus(const Stress& s, const double* state) const override {
    return fault_ == Fault::start_modulus && s[RT] == 1.0 ? std::numeric_limits<double>::quiet_NaN()
                                                          : elastic_.constrained_modulus(s, state);
  }
  static void mark(Stress& s) { s[RT] = 1.0; }
  double shear_modulus(const Stress& s, const double* state) const override {
    return elastic_.shear_modulus(s, state);
  }
  double elastic_energy_density(const Stress& s, const double* state) const override {
    return elastic_.elastic_energy_density(s, state);
  }

private:
  LinearElastic elastic_;
  std::int32_t particle_;
  Fault fault_;
};

/// The column whose particle 7 fails in its first stress update as `fault` says stops there,
/// naming the particle and where it is.
void expect_first_update_stops_naming_particle_seven(Fault fault) {
  CaseRun run(column);
  run.scene->materials[0] = std::make_unique<FailingAtOneParticle>(7, fault);
  const std::string message = stop_message(run);
  std::ostringstream expected;
  expected << "step 1, t = " << run.solver->time() << " s: particle 7 at (r, y) = ("
           << run.scene->particles.r[7] << ", " << run.scene->particles.y[7]
           << ") has a non-finite stress, velocity or wave speed";
  EXPECT_NE(message.find(expected.str()), std::string::npos) << message;
}

TEST(Guards, NonFiniteParticleIsNamedWithItsPosition) {
  expect_first_update_stops_naming_particle_seven(Fault::stress);
}

TEST(Guards, AParticleWithoutAFiniteModulusAtTheStartIsNamed) {
  // std::min passes over a NaN: before, the first step came from the other particles and the run
  // went on with this one's stiffness unchecked. Now the step cannot be set, and the run says why.
  CaseRun run(column);
  run.scene->materials[0] = std::make_unique<FailingAtOneParticle>(7, Fault::start_modulus);
  FailingAtOneParticle::mark(run.scene->particles.stress[7]);
  std::string message;
  try {
    [[maybe_unused]] const ExplicitSolver solver(
        *run.scene, phase_settings(run.spec, run.spec.phases[0]), run.log);
  } catch (const SimulationError& e) {
    message = e.what();
  }
  // The solver sorts the particles by cell: the marked one is found again by its mark.
  const Particles& p = run.scene->particles;
  std::size_t marked = 0;
  while (marked < p.size() && p.stress[marked][RT] != 1.0) {
    ++marked;
  }
  ASSERT_LT(marked, p.size());
  std::ostringstream expected;
  expected << "particle " << marked << " at (r, y) = (" << p.r[marked] << ", " << p.y[marked]
           << ") of body 'column' has no finite crossing time, so the stable time step cannot be "
              "set: wave speed nan m/s from its material's (failing) constrained modulus of "
              "nan Pa at its stress, velocity 0 m/s";
  EXPECT_NE(message.find(expected.str()), std::string::npos) << message;
}

TEST(Guards, AParticleWhoseUpdateReturnsNoFiniteModulusStopsTheRun) {
  // Its stress and velocity stay finite: only its wave speed shows the update went wrong.
  expect_first_update_stops_naming_particle_seven(Fault::update_modulus);
}

TEST(Guards, UnstableRunStopsAndLeavesAReadableHistory) {
  const auto directory = std::filesystem::temp_directory_path() / "mpile_test_guard_run";
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  const auto path = directory / "unstable.toml";
  std::ofstream(path) << replaced(column, "courant_number = 0.8", "courant_number = 1.5");
  RunOptions options;
  options.case_path = path.string();
  options.output_directory = (directory / "out").string();
  std::ostringstream out, err;
  EXPECT_EQ(run_case(options, out, err), exit_failure);
  EXPECT_NE(err.str().find("the Courant number reached 1.5"), std::string::npos) << err.str();
  EXPECT_NE(err.str().find("outputs so far are in"), std::string::npos) << err.str();
  Hdf5File history((directory / "out" / "history.h5").string(), Hdf5File::Mode::read);
  const std::string status = history.string_attribute("/", "status");
  EXPECT_EQ(status.rfind("failed: step 1, t = ", 0), 0u) << status;
  EXPECT_NE(status.find("the Courant number reached 1.5"), std::string::npos) << status;
  EXPECT_EQ(history.read_doubles("/time").size(), 1u); // the initial row, nothing half-written
  EXPECT_TRUE(std::filesystem::exists(directory / "out" / "checkpoint.h5"));
}

/// The column case written into a fresh temporary directory `name`, to run into `name`/out; the
/// directory, for a test to put an obstacle into out/ first.
RunOptions column_run(const std::string& name, std::filesystem::path& directory) {
  directory = std::filesystem::temp_directory_path() / name;
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory / "out");
  std::ofstream(directory / "column.toml") << column;
  RunOptions options;
  options.case_path = (directory / "column.toml").string();
  options.output_directory = (directory / "out").string();
  return options;
}

TEST(Guards, AnOutputThatCannotBeWrittenIsNamedWithTheSystemsReason) {
  // particles.pvd is a directory: the snapshot index cannot replace it. The message names the file
  // and the reason, not the library's "filesystem error: cannot rename".
  std::filesystem::path directory;
  const RunOptions options = column_run("mpile_test_guard_write", directory);
  std::filesystem::create_directories(directory / "out" / "particles.pvd" / "inside");
  std::ostringstream out, err;
  EXPECT_EQ(run_case(options, out, err), exit_failure);
  const std::string expected =
      "cannot write " + (directory / "out" / "particles.pvd").string() + ": ";
  EXPECT_NE(err.str().find(expected), std::string::npos) << err.str();
  EXPECT_EQ(err.str().find("filesystem error"), std::string::npos) << err.str();
  EXPECT_FALSE(std::filesystem::exists(directory / "out" / "particles.pvd.tmp"));
}

TEST(Guards, AForeignIndexWithAHugeFileNameIsReplacedNotAStackOverflow) {
  // A fresh run removes the files an earlier run's particles.pvd lists. A foreign index naming a
  // file of 30 000 characters overflowed the stack of the regular expression that read it
  // (SIGSEGV); one of 300 characters ended the run with the library's "File name too long". Such
  // a name is none this program wrote: it is left alone and the index replaced.
  std::filesystem::path directory;
  const RunOptions options = column_run("mpile_test_guard_foreign_pvd", directory);
  std::ofstream(directory / "out" / "particles.pvd")
      << "<VTKFile><Collection><DataSet file=\"" << std::string(30000, 'a')
      << "\"/><DataSet file=\"" << std::string(300, 'b') << ".vtu\"/></Collection></VTKFile>\n";
  std::ostringstream out, err;
  EXPECT_EQ(run_case(options, out, err), exit_success) << err.str();
  EXPECT_EQ(read_text(directory / "out" / "particles.pvd").find("aaaa"), std::string::npos);
}

TEST(Guards, ADirectoryWhereTheCheckpointGoesIsRefusedBeforeTheRun) {
  // Found only when the checkpoint was due (the end of the run, at checkpoint_interval 0): the
  // whole run lost and the advice "once there is room" wrong. Now bad input before the first step.
  std::filesystem::path directory;
  const RunOptions options = column_run("mpile_test_guard_checkpoint_dir", directory);
  std::filesystem::create_directories(directory / "out" / "checkpoint.h5");
  std::ostringstream out, err;
  EXPECT_EQ(run_case(options, out, err), exit_bad_input);
  EXPECT_NE(err.str().find((directory / "out" / "checkpoint.h5").string() +
                           " is not a file (a directory?): the run writes its checkpoint there"),
            std::string::npos)
      << err.str();
  EXPECT_FALSE(std::filesystem::exists(directory / "out" / "history.h5"));
}

TEST(Guards, EnergyResidualPastTheLimitStopsTheRun) {
  // The column under suddenly applied gravity closes its energy balance to O(omega dt) (a few
  // 1e-3 here), never exactly: a limit of 1e-9 is passed from the first rows on, and the run must
  // stop once it has stayed past it for 100 steps, with every row up to then in the history.
  // (A physical blow-up trips the default 50 %: docs/stability.md.)
  const auto directory = std::filesystem::temp_directory_path() / "mpile_test_guard_energy";
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  const auto path = directory / "energy.toml";
  std::ofstream(path) << replaced(replaced(column, "duration = 0.05", "duration = 0.5"),
                                  "courant_number = 0.8",
                                  "courant_number = 0.8\nenergy_residual_warning = 5e-10\n"
                                  "energy_residual_limit = 1e-9");
  RunOptions options;
  options.case_path = path.string();
  options.output_directory = (directory / "out").string();
  std::ostringstream out, err;
  EXPECT_EQ(run_case(options, out, err), exit_failure);
  EXPECT_NE(err.str().find("% of the energy in play (energy_residual_limit 1e-07 % since step "),
            std::string::npos)
      << err.str();
  EXPECT_NE(err.str().find("the run went unstable"), std::string::npos) << err.str();
  // It says where the energy is: the one body holds all of it, and the particle with the most is
  // named with its place.
  EXPECT_NE(err.str().find("most kinetic energy in body 'column' ("), std::string::npos)
      << err.str();
  EXPECT_NE(err.str().find(" J, 100 % of "), std::string::npos) << err.str();
  EXPECT_NE(err.str().find("; the most in one particle: particle "), std::string::npos)
      << err.str();
  EXPECT_NE(err.str().find(") in cell ("), std::string::npos) << err.str();
  Hdf5File history((directory / "out" / "history.h5").string(), Hdf5File::Mode::read);
  const std::string status = history.string_attribute("/", "status");
  EXPECT_EQ(status.rfind("failed: step ", 0), 0u) << status;
  const std::vector<double> residual = history.read_doubles("/energy/relative_residual");
  const std::vector<double> step = history.read_doubles("/step");
  ASSERT_GE(residual.size(), 3u);
  // Rows from the first past the limit to the stop span exactly 100 steps (a row every step).
  std::size_t first = 0;
  while (first < residual.size() && !(residual[first] > 1e-9)) {
    ++first;
  }
  ASSERT_LT(first, residual.size());
  EXPECT_EQ(step.back() - step[first], 100.0);
  EXPECT_EQ(status.find("failed: step " + std::to_string(static_cast<long>(step.back())) + ","), 0u)
      << status;
}

} // namespace

TEST(Guards, TheEnergyGuardLooksBetweenHistoryRowsToo) {
  // The same column with one history row at the start and none after: the guard looks every 20
  // steps, so the run stops 100 steps after its first look past the limit (at step 20), on step
  // 120, and the history ends on that step.
  const auto directory = std::filesystem::temp_directory_path() / "mpile_test_guard_sparse";
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  const auto path = directory / "energy.toml";
  std::ofstream(path) << replaced(
      replaced(
          replaced(column, "duration = 0.05", "duration = 0.5"), "courant_number = 0.8",
          "courant_number = 0.8\nenergy_residual_warning = 5e-10\nenergy_residual_limit = 1e-9"),
      "history_interval = 0.0", "history_interval = 100.0");
  RunOptions options;
  options.case_path = path.string();
  options.output_directory = (directory / "out").string();
  std::ostringstream out, err;
  EXPECT_EQ(run_case(options, out, err), exit_failure);
  EXPECT_NE(err.str().find("step 120, t = "), std::string::npos) << err.str();
  EXPECT_NE(err.str().find("(energy_residual_limit 1e-07 % since step 20)"), std::string::npos)
      << err.str();
  Hdf5File history((directory / "out" / "history.h5").string(), Hdf5File::Mode::read);
  const std::vector<double> step = history.read_doubles("/step");
  ASSERT_EQ(step.size(), 2u); // the start, and the step that stopped the run
  EXPECT_EQ(step.back(), 120.0);
}
} // namespace mpile
