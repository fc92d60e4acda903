#include "cases/verification/case_file_run.hpp"

#include "cases/case_builder.hpp"
#include "cases/case_phases.hpp"
#include "cases/verification/case_texts.hpp"

#include <chrono>
#include <limits>
#include <regex>
#include <stdexcept>
#include <utility>

namespace mpile::verification {

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

CaseSpec read_verification_case(std::string_view file, const Options& options,
                                PoissonRatio poisson) {
  // The refinement goes into the text, so that the reader checks the refined grid as it checks
  // any case (regions and node lines on grid lines).
  CaseSpec spec = read_case_text(refined(case_text(file), options.refinement), std::string(file));
  if (spec.phases.size() != 1) {
    throw std::logic_error(std::string(file) + ": a verification case file has one phase");
  }
  for (BodySpec& body : spec.bodies) {
    if (options.particles_per_direction && !body.rigid) {
      body.particles_per_direction = *options.particles_per_direction;
    }
  }
  for (MaterialSpec& material : spec.materials) {
    if (options.implicit_pore_pressure && material.water.drainage != Drainage::drained) {
      // As the reader sets it from [solver] implicit_pore_pressure.
      material.water.implicit_pressure = true;
      spec.solver.implicit_pore_pressure = true;
    }
    const auto nu = material.parameters.find("poisson_ratio");
    if (poisson == PoissonRatio::the_options && options.poisson_ratio &&
        nu != material.parameters.end()) {
      nu->second = *options.poisson_ratio;
    }
  }
  return spec;
}

double travel_of(const TimeFunction& velocity, const CaseSpec& spec) {
  constexpr int intervals = 200000;
  const double dt = spec.phases.at(0).duration / intervals;
  double travel = 0.0;
  for (int k = 0; k < intervals; ++k) {
    travel += velocity.value((k + 0.5) * dt) * dt;
  }
  return travel;
}

CaseFileRun::CaseFileRun(std::string_view file, const Options& options, PoissonRatio poisson)
    : spec_(read_verification_case(file, options, poisson)), scene_(build_scene(spec_)),
      solver_options_(
          [options](SolverSettings s) { return apply_options(std::move(s), options); }) {}

double CaseFileRun::parameter(std::string_view material, std::string_view key) const {
  for (const MaterialSpec& m : spec_.materials) {
    if (m.name == material) {
      const auto value = m.parameters.find(key);
      if (value != m.parameters.end()) {
        return value->second;
      }
    }
  }
  throw std::logic_error(spec_.file + ": no parameter " + std::string(key) + " of material " +
                         std::string(material));
}

Report CaseFileRun::run(std::string id, std::string title, const AfterStep& after_step) {
  const auto start = std::chrono::steady_clock::now();
  // As `mpile run` begins a case, with the options' solver choices on the phase's settings.
  const CasePhases phases(spec_, *scene_, solver_options_);
  RunProgress progress;
  const std::unique_ptr<ExplicitSolver> owned = phases.start(progress, log_);
  ExplicitSolver& solver = *owned;
  solver_ = &solver;
  after_step_ = after_step;

  OutputSchedule no_rows;
  no_rows.history_interval = std::numeric_limits<double>::infinity();
  PhaseRunner runner(solver, phases.phases(), no_rows, progress, log_);
  runner.add_observer(*this);
  runner.start();
  runner.run(phases.set_up_on(solver), [](long) { return false; });
  if (spec_.phases[0].equilibrium_tolerance) {
    rest_ = measure_equilibrium(solver, *spec_.phases[0].equilibrium_tolerance);
  }
  solver_ = nullptr;

  Report report;
  report.id = std::move(id);
  report.title = std::move(title);
  report.particles = scene_->particles.size();
  report.steps = solver.step_count();
  report.warnings = log_.warnings();
  report.wall_seconds = seconds_since(start);
  return report;
}

void CaseFileRun::stepped(const RunPhase&, long, const PhaseGoal&) {
  if (after_step_) {
    after_step_(*solver_);
  }
}

Check CaseFileRun::equilibrium() const {
  if (!rest_) {
    throw std::logic_error(spec_.file + ": its phase does not end at equilibrium");
  }
  // The larger of the two ratios of the equilibrium test; the force ratio is NaN (a failed check)
  // when the kinetic energy never passed.
  return {"out-of-balance force and kinetic/work ratios, the larger (equilibrium)",
          "-",
          std::max(rest_->force_ratio, rest_->kinetic_ratio),
          0.0,
          1.0,
          *spec_.phases[0].equilibrium_tolerance};
}

} // namespace mpile::verification
