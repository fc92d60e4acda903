#include "io/verification_files.hpp"

#include "io/case_builder.hpp"
#include "io/case_spec.hpp"
#include "solver/phase_runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <regex>
#include <stdexcept>

namespace mpile {

namespace {

using verification::Check;
using verification::Options;
using verification::Report;

} // namespace

std::string refined(std::string_view text, int refinement) {
  const std::regex cells(R"(cells = ([0-9]+))");
  std::string out;
  auto begin = std::cregex_iterator(text.data(), text.data() + text.size(), cells);
  std::size_t last = 0;
  for (auto it = begin; it != std::cregex_iterator(); ++it) {
    const auto& match = *it;
    out.append(text.substr(last, static_cast<std::size_t>(match.position(0)) - last));
    out += "cells = " + std::to_string(std::stoi(match[1].str()) * refinement);
    last = static_cast<std::size_t>(match.position(0) + match.length(0));
  }
  out.append(text.substr(last));
  return out;
}

namespace {

/// A case file built and run through its single phase by the phase runner, as `mpile run` runs
/// it, with a callback after every step.
class FileCaseRun final : public RunObserver {
public:
  FileCaseRun(std::string_view text, const std::string& name, const Options& options)
      : spec_(read_case_text(refined(text, options.refinement), name)), scene_(build_scene(spec_)) {
    if (spec_.phases.size() != 1) {
      throw std::logic_error(name + ": a verification case file has one phase");
    }
    settings_ = verification::apply_options(phase_settings(spec_, spec_.phases[0]), options);
  }
  Scene& scene() { return *scene_; }

  template <class AfterStep> Report run(const std::string& id, AfterStep&& after_step) {
    const auto start = std::chrono::steady_clock::now();
    ExplicitSolver solver(*scene_, settings_, log_);
    switch_on_absorbing_faces(solver, spec_, 0);
    after_step_ = [&] { after_step(solver); };
    const std::vector<RunPhase> phases(spec_.phases.begin(), spec_.phases.end());
    RunProgress progress;
    begin_phase(progress, phases, *scene_, 0, 0.0);
    OutputSchedule no_rows;
    no_rows.history_interval = std::numeric_limits<double>::infinity();
    PhaseRunner runner(solver, phases, no_rows, progress, log_);
    runner.add_observer(*this);
    runner.start();
    runner.run([](std::size_t, double) {}, [](long) { return false; });
    Report report;
    report.id = id;
    report.particles = scene_->particles.size();
    report.steps = solver.step_count();
    report.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return report;
  }

  void stepped(const RunPhase&, long, const PhaseGoal&) override {
    if (after_step_) {
      after_step_();
    }
  }

private:
  CaseSpec spec_;
  std::unique_ptr<Scene> scene_;
  SolverSettings settings_;
  RunLog log_;
  std::function<void()> after_step_;
};

double surface_theta_force(const Scene& scene, const std::string& surface) {
  const ContactPair& pair = scene.contacts.at(0);
  for (std::size_t q = 0; q < pair.surfaces.size(); ++q) {
    if (pair.surfaces[q] == surface) {
      return pair.surface_force[q][2];
    }
  }
  throw std::logic_error("V9 has no surface " + surface);
}

} // namespace

Report run_block_on_incline(const Options& options) {
  // The case file's incline: a = 30 deg, mu = 0.3 (its gravity and friction keys).
  const double a = std::numbers::pi / 6.0, mu = 0.3, g = 9.81, rho = 1000.0;
  FileCaseRun run(v7_block_on_incline_toml, "v7_block_on_incline.toml", options);
  // The block starts in the equilibrium of an infinitely long layer (zero at its top, y = 1):
  // released unstressed it would bounce on the incline, and the normal force would dip below what
  // holds it.
  Particles& p = run.scene().particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] == 0) {
      p.stress[i][YY] = -rho * g * std::cos(a) * (1.0 - p.y[i]);
      p.stress[i][RY] = rho * g * std::sin(a) * (1.0 - p.y[i]);
    }
  }
  Report report = run.run("V7", [](const ExplicitSolver&) {});
  double mass = 0.0, moment = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] == 0) {
      mass += p.mass[i];
      moment += p.mass[i] * (p.r[i] - p.r0[i]);
    }
  }
  report.title = "block sliding on a rigid incline, Coulomb friction";
  // 3 %: the tolerance of the block-on-incline test at mu = 0.3 (the block's start and the
  // contact's one-step lag at release, docs/verification.md V7).
  const double slide = 0.5 * g * (std::sin(a) - mu * std::cos(a)); // t = 1 s
  report.checks.push_back(
      {"mean slide of the block after 1 s", "m", moment / mass, slide, slide, 0.03});
  return report;
}

Report run_torsion_with_adhesion(const Options& options) {
  FileCaseRun run(v9_torsion_adhesion_toml, "v9_torsion_adhesion.toml", options);
  double internal = 0.0, external = 0.0, base = 0.0, weight = 0.0;
  Report report = run.run("V9", [&](const ExplicitSolver& solver) {
    if (solver.time() < 0.5) {
      return;
    }
    const double dt = solver.last_time_step();
    internal += dt * surface_theta_force(solver.scene(), "internal_shaft");
    external += dt * surface_theta_force(solver.scene(), "external_shaft");
    base += dt * surface_theta_force(solver.scene(), "base");
    weight += dt;
  });
  report.title = "seed torsion with adhesion (c_a = 10 kPa)";
  // c_a r h on the shafts and c_a (r2^2 - r1^2) / 2 on the base, against the spin; 3 % per face
  // and 2 % on the sum, the seed comparison's tolerances (docs/verification.md V9).
  const double c_a = 10e3;
  const double refs[3] = {-c_a * 0.4 * 0.5, -c_a * 0.6 * 0.5, -c_a * (0.36 - 0.16) / 2.0};
  const double got[3] = {internal / weight, external / weight, base / weight};
  const char* names[3] = {"F_theta on the internal shaft (mean, 0.5 to 1 s)",
                          "F_theta on the external shaft (mean, 0.5 to 1 s)",
                          "F_theta on the base (mean, 0.5 to 1 s)"};
  for (int k = 0; k < 3; ++k) {
    report.checks.push_back({names[k], "N/rad", got[k], refs[k], std::abs(refs[k]), 0.03});
  }
  report.checks.push_back({"F_theta on the three surfaces together", "N/rad",
                           got[0] + got[1] + got[2], refs[0] + refs[1] + refs[2],
                           std::abs(refs[0] + refs[1] + refs[2]), 0.02});
  return report;
}

const std::vector<verification::Case>& verification_cases() {
  static const std::vector<verification::Case> cases = [] {
    std::vector<verification::Case> all = verification::all_cases();
    all.push_back({"V7", "block sliding on a rigid incline (plane strain), from its case file",
                   run_block_on_incline});
    all.push_back(
        {"V9", "seed torsion with adhesion, from its case file", run_torsion_with_adhesion});
    // In the order of docs/verification.md: by number, variants after their case.
    std::stable_sort(all.begin(), all.end(), [](const auto& x, const auto& y) {
      return x.id.substr(0, 2) < y.id.substr(0, 2);
    });
    return all;
  }();
  return cases;
}

const verification::Case* find_verification_case(const std::string& id) {
  for (const verification::Case& c : verification_cases()) {
    if (c.id == id) {
      return &c;
    }
  }
  return nullptr;
}

} // namespace mpile
