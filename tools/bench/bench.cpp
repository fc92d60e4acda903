// mpile-bench: throughput and memory of the full explicit step on standard scenes.
//
// For each scene and thread count it runs a warm-up, then a fixed number of steps, and prints one
// line: scene, threads, particles, steps, wall seconds, particle-steps per second, bytes per
// particle (peak resident set over particles) and each pass's share of the step. Every scene runs
// in a child process of its own, so that the peak resident set is that scene's alone.
//
// With --against OTHER, it compares this build with another build of the benchmark side by side:
// for each scene and thread count it runs the two alternately (A, B, A, B, ...), so that both see
// the same machine, and prints the best throughput of each and their ratio. On a shared machine a
// speed-up is a ratio measured in one run, not two absolute figures from two days.
#include "cases/case_builder.hpp"
#include "cases/verification/verification_cases.hpp"
#include "engine/materials/hardening_soil.hpp"
#include "engine/materials/linear_elastic.hpp"
#include "engine/particle_fill.hpp"
#include "solver/explicit_solver.hpp"

#include <CLI/CLI.hpp>
#include <sys/resource.h>
#include <sys/wait.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace mpile;

/// A soil column on a fixed base, confined by rollers, from K0 stresses under gravity with local
/// damping: the quasi-static kind of step the monopile cases spend most of their particles on.
enum class Soil { elastic, hardening_soil, hypoplastic };

std::unique_ptr<Material> soil_material(Soil soil) {
  if (soil == Soil::elastic) {
    return std::make_unique<LinearElastic>(50e6, 0.3, 1650.0);
  }
  if (soil == Soil::hypoplastic) {
    return verification::karlsruhe_fine_sand(); // docs/hypoplasticity.md
  }
  return verification::seed_sand();
}

std::unique_ptr<Scene> soil_column(GeometryMode mode, std::size_t target_particles, Soil soil) {
  // Square cells, 4 particles each, a column twice as tall as wide.
  const int cells_r = std::max(4, static_cast<int>(std::sqrt(target_particles / 8.0)));
  const int cells_y = 2 * cells_r;
  const double width = 5.0, height = 10.0;
  auto scene = std::make_unique<Scene>(
      mode, Grid(GradedAxis::uniform(0.0, width, cells_r),
                 GradedAxis::uniform(0.0, height * 1.05, cells_y + cells_y / 20)));
  const auto material = scene->add_material(soil_material(soil));
  const auto body = scene->add_body("soil");
  fill_rectangle(*scene, {0.0, width, 0.0, height}, 2, material, body);
  // K0 stresses (and, for Hardening Soil, the consistent hardening state) under gravity.
  initialise_geostatic_stress(*scene, body, height, scene->materials[material]->density() * 9.81,
                              0.5);
  scene->boundaries.constraints = {
      face_constraint(scene->grid, mode, GridFace::y_min, FaceCondition::fixed),
      face_constraint(scene->grid, mode, GridFace::r_max, FaceCondition::roller)};
  if (mode == GeometryMode::axisymmetric) {
    scene->boundaries.constraints.push_back(axis_constraint(scene->grid));
  } else {
    scene->boundaries.constraints.push_back(
        face_constraint(scene->grid, mode, GridFace::r_min, FaceCondition::roller));
  }
  return scene;
}

/// A scene and the solver settings it runs with.
struct BenchScene {
  std::unique_ptr<Scene> scene;
  SolverSettings settings;
};

BenchScene quasi_static(std::unique_ptr<Scene> scene) {
  SolverSettings settings;
  settings.gravity = {0.0, -9.81};
  settings.local_damping = 0.7;
  return {std::move(scene), settings};
}

/// The elastic column with the contact code path switched on and nothing for it to do: a contact
/// structure without particles. What this costs over elastic-1e5 is what the contact machinery
/// charges a scene whose soil never touches a structure.
BenchScene contact_path_idle(std::size_t count) {
  auto scene = soil_column(GeometryMode::axisymmetric, count, Soil::elastic);
  scene->add_contact_structure(scene->add_body("idle structure")).friction = 0.4;
  return quasi_static(std::move(scene));
}

/// The quick GDP monopile case in its installation phase (K0 stresses, drives started): the
/// monopile step with contact, the rigid pile and the moving mesh.
BenchScene gdp_quick(const std::string& case_file = "gdp_quick.toml") {
  const CaseSpec spec =
      read_case_file(std::string(MPILE_SOURCE_DIR) + "/cases/monopile/" + case_file);
  BenchScene b{build_scene(spec), phase_settings(spec, spec.phases.back())};
  apply_k0(*b.scene, spec, spec.phases.front());
  activate_phase_boundaries(*b.scene, spec, spec.phases.size() - 1, 0.0);
  return b;
}

struct SceneSpec {
  std::string name;
  std::function<BenchScene()> make;
};

std::map<std::string, SceneSpec> scenes() {
  std::map<std::string, SceneSpec> all;
  for (const auto& [label, count] :
       std::vector<std::pair<std::string, std::size_t>>{{"1e5", 100000}, {"1e6", 1000000}}) {
    all["elastic-" + label] = {"elastic-" + label, [count = count] {
                                 return quasi_static(
                                     soil_column(GeometryMode::axisymmetric, count, Soil::elastic));
                               }};
    all["elastic-plane-" + label] = {
        "elastic-plane-" + label, [count = count] {
          return quasi_static(soil_column(GeometryMode::plane_strain, count, Soil::elastic));
        }};
    all["hypoplastic-" + label] = {
        "hypoplastic-" + label, [count = count] {
          return quasi_static(soil_column(GeometryMode::axisymmetric, count, Soil::hypoplastic));
        }};
    all["hardening-soil-" + label] = {
        "hardening-soil-" + label, [count = count] {
          return quasi_static(soil_column(GeometryMode::axisymmetric, count, Soil::hardening_soil));
        }};
  }
  all["elastic-contact-idle-1e5"] = {"elastic-contact-idle-1e5",
                                     [] { return contact_path_idle(100000); }};
  all["gdp-quick"] = {"gdp-quick", [] { return gdp_quick(); }};
  // The same with the seed's sand in hypoplasticity (cases/base/seed_sand_hypoplastic.toml).
  all["gdp-quick-hypoplastic"] = {"gdp-quick-hypoplastic",
                                  [] { return gdp_quick("gdp_quick_hypoplastic.toml"); }};
  // The same two scenes with GIMP shape functions (docs/design.md, "Shape functions").
  all["elastic-gimp-1e5"] = {"elastic-gimp-1e5", [] {
                               BenchScene b = quasi_static(
                                   soil_column(GeometryMode::axisymmetric, 100000, Soil::elastic));
                               b.settings.shape_functions = ShapeFunctions::gimp;
                               return b;
                             }};
  all["gdp-quick-gimp"] = {"gdp-quick-gimp", [] {
                             BenchScene b = gdp_quick();
                             b.settings.shape_functions = ShapeFunctions::gimp;
                             return b;
                           }};
  return all;
}

long peak_resident_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss * 1024L;
}

void run_scene(const SceneSpec& spec, int threads, int warmup, int steps) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(threads));
  BenchScene bench = spec.make();
  const auto& scene = bench.scene;
  RunLog log;
  ExplicitSolver solver(*scene, bench.settings, log);
  for (int s = 0; s < warmup; ++s) {
    solver.step();
  }
  const PassTimings before = solver.timings();
  const auto start = std::chrono::steady_clock::now();
  for (int s = 0; s < steps; ++s) {
    solver.step();
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const PassTimings& after = solver.timings();
  const double n = static_cast<double>(scene->particles.size());
  auto share = [&](double PassTimings::*pass) {
    return 100.0 * (after.*pass - before.*pass) / wall;
  };
  std::printf("%-20s %3d %9.0f %6d %8.3f %12.3e %8.0f   bin %4.1f%%  p2g %4.1f%%  grid %4.1f%%  "
              "contact %4.1f%%  g2p %4.1f%%  remap %4.1f%%  stress %4.1f%%  output  0.0%%   "
              "stress pass %.0f ns/particle\n",
              spec.name.c_str(), threads, n, steps, wall, n * steps / wall,
              static_cast<double>(peak_resident_bytes()) / n, share(&PassTimings::binning),
              share(&PassTimings::particle_to_grid), share(&PassTimings::grid_update),
              share(&PassTimings::contact), share(&PassTimings::grid_to_particle),
              share(&PassTimings::momentum_remap), share(&PassTimings::stress_update),
              1e9 * (after.stress_update - before.stress_update) / (n * steps));
  std::fflush(stdout);
}

/// Runs one scene on one thread count in another benchmark binary (or this one) and returns its
/// particle-steps per second, read from the line it prints; throws with the binary's output if it
/// fails or prints no such line.
double run_binary(const std::string& binary, const std::string& scene, int threads, int warmup,
                  int steps) {
  std::vector<std::string> args{binary,
                                "--scenes",
                                scene,
                                "--threads",
                                std::to_string(threads),
                                "--steps",
                                std::to_string(steps),
                                "--warmup",
                                std::to_string(warmup)};
  int pipe_ends[2];
  if (pipe(pipe_ends) != 0) {
    throw std::runtime_error("cannot create a pipe");
  }
  const pid_t child = fork();
  if (child == 0) {
    dup2(pipe_ends[1], STDOUT_FILENO);
    close(pipe_ends[0]);
    close(pipe_ends[1]);
    std::vector<char*> argv;
    for (std::string& a : args) {
      argv.push_back(a.data());
    }
    argv.push_back(nullptr);
    execv(binary.c_str(), argv.data());
    std::fprintf(stderr, "mpile-bench: cannot run %s: %s\n", binary.c_str(), std::strerror(errno));
    std::_Exit(127);
  }
  close(pipe_ends[1]);
  std::string output;
  std::array<char, 4096> buffer{};
  for (ssize_t n; (n = read(pipe_ends[0], buffer.data(), buffer.size())) > 0;) {
    output.append(buffer.data(), static_cast<std::size_t>(n));
  }
  close(pipe_ends[0]);
  int status = 0;
  waitpid(child, &status, 0);
  // The result line: scene, threads, particles, steps, wall seconds, particle-steps per second.
  const bool succeeded = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  std::istringstream lines(output);
  for (std::string line; succeeded && std::getline(lines, line);) {
    std::istringstream fields(line);
    std::string name;
    int t = 0;
    double particles = 0.0, wall = 0.0, rate = 0.0;
    int n_steps = 0;
    if (fields >> name >> t >> particles >> n_steps >> wall >> rate && name == scene &&
        t == threads) {
      return rate;
    }
  }
  throw std::runtime_error(binary + " gave no result for " + scene + " on " +
                           std::to_string(threads) + " threads; it printed:\n" + output);
}

/// The side-by-side comparison: rounds of A then B per scene and thread count.
int compare(const std::string& self, const std::string& other,
            const std::vector<std::string>& chosen, const std::vector<int>& threads, int warmup,
            int steps, int rounds) {
  std::printf("A = %s\nB = %s\n", self.c_str(), other.c_str());
  std::printf("%-20s %3s %6s %12s %12s %8s %8s %8s\n", "scene", "thr", "rounds", "A p-steps/s",
              "B p-steps/s", "A/B best", "A/B min", "A/B max");
  std::fflush(stdout);
  for (const std::string& scene : chosen) {
    for (const int t : threads) {
      double best_a = 0.0, best_b = 0.0;
      double lowest_ratio = std::numeric_limits<double>::infinity(), highest_ratio = 0.0;
      for (int round = 0; round < rounds; ++round) {
        const double a = run_binary(self, scene, t, warmup, steps);
        const double b = run_binary(other, scene, t, warmup, steps);
        best_a = std::max(best_a, a);
        best_b = std::max(best_b, b);
        lowest_ratio = std::min(lowest_ratio, a / b);
        highest_ratio = std::max(highest_ratio, a / b);
      }
      std::printf("%-20s %3d %6d %12.3e %12.3e %8.3f %8.3f %8.3f\n", scene.c_str(), t, rounds,
                  best_a, best_b, best_a / best_b, lowest_ratio, highest_ratio);
      std::fflush(stdout);
    }
  }
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  CLI::App app{"mpile-bench: particle-steps per second, memory and pass shares on standard scenes"};
  std::vector<std::string> chosen{"elastic-1e5", "elastic-plane-1e5", "elastic-1e6"};
  std::vector<int> threads{1, 2};
  int steps = 100, warmup = 10;
  app.add_option("--scenes", chosen, "scenes to run")->delimiter(',')->capture_default_str();
  app.add_option("--threads", threads, "thread counts")->delimiter(',')->capture_default_str();
  app.add_option("--steps", steps, "timed steps per run")->capture_default_str();
  app.add_option("--warmup", warmup, "untimed steps first")->capture_default_str();
  bool list = false;
  app.add_flag("--list", list, "list the scenes");
  std::string against;
  int rounds = 3;
  app.add_option("--against", against,
                 "another build's mpile-bench: run both alternately and print the ratios")
      ->check(CLI::ExistingFile);
  app.add_option("--rounds", rounds, "with --against: runs of each build per scene and threads")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  const auto all = scenes();
  if (list) {
    for (const auto& [name, spec] : all) {
      std::cout << name << '\n';
    }
    return 0;
  }
  for (const std::string& name : chosen) {
    if (all.find(name) == all.end()) {
      std::cerr << "mpile-bench: unknown scene " << name << " (see --list)\n";
      return 2;
    }
  }
  if (!against.empty()) {
    try {
      return compare(std::filesystem::canonical("/proc/self/exe").string(), against, chosen,
                     threads, warmup, steps, rounds);
    } catch (const std::exception& e) {
      std::cerr << "mpile-bench: " << e.what() << '\n';
      return 1;
    }
  }
  std::printf("%-20s %3s %9s %6s %8s %12s %8s   %s\n", "scene", "thr", "particles", "steps",
              "wall_s", "p-steps/s", "B/part", "time share of each pass");
  std::fflush(stdout);
  for (const std::string& name : chosen) {
    const SceneSpec& spec = all.at(name); // checked above
    for (const int t : threads) {
      // A child process per run: the peak resident set is this run's, and oneTBB starts fresh.
      const pid_t child = fork();
      if (child == 0) {
        run_scene(spec, t, warmup, steps);
        std::_Exit(0);
      }
      int status = 0;
      waitpid(child, &status, 0);
      if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        std::cerr << "mpile-bench: " << name << " on " << t << " threads failed\n";
        return 1;
      }
    }
  }
  return 0;
}
