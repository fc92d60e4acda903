#include "cases/case_phases.hpp"

#include "cases/plausibility.hpp"
#include "solver/diagnostics.hpp"
#include "solver/simulation_error.hpp"

#include <sstream>
#include <utility>

namespace mpile {

CasePhases::CasePhases(const CaseSpec& spec, Scene& scene, SettingsChange change)
    : spec_(spec), scene_(scene), phases_(spec.phases.begin(), spec.phases.end()),
      change_(std::move(change)) {}

SolverSettings CasePhases::settings(std::size_t p) const {
  SolverSettings s = phase_settings(spec_, spec_.phases.at(p));
  return change_ ? change_(std::move(s)) : s;
}

std::unique_ptr<ExplicitSolver> CasePhases::start(RunProgress& progress, RunLog& log) const {
  // The K0 stresses come before the solver, which takes its stable step and its elastic energy's
  // reference from them.
  begin_phase(progress, phases_, scene_, 0, 0.0);
  apply_k0(scene_, spec_, spec_.phases.front());
  activate_phase_boundaries(scene_, spec_, 0, 0.0);
  auto solver = std::make_unique<ExplicitSolver>(scene_, settings(0), log);
  switch_on_absorbing_faces(*solver, spec_, 0);
  return solver;
}

std::unique_ptr<ExplicitSolver> CasePhases::resume(RunProgress& progress, RunLog& log,
                                                   const SolverState& restored) const {
  // A complete run's checkpoint stands after its last phase; a case that now has a phase more
  // begins it here.
  const bool begins_added_phase =
      progress.phase > 0 && progress.phase == progress.phase_starts.size();
  for (std::size_t p = 0; p < progress.phase_starts.size(); ++p) {
    activate_phase_boundaries(scene_, spec_, p, progress.phase_starts[p]);
  }
  const std::size_t in_force = begins_added_phase ? progress.phase - 1 : progress.phase;
  auto solver = std::make_unique<ExplicitSolver>(scene_, settings(in_force), log, restored);
  if (begins_added_phase) {
    begin_phase(progress, phases_, scene_, progress.phase, solver->time());
    set_up(*solver, progress.phase, solver->time());
  }
  return solver;
}

void CasePhases::set_up(ExplicitSolver& solver, std::size_t p, double start) const {
  activate_phase_boundaries(scene_, spec_, p, start);
  const double elastic_before = elastic_energy(scene_);
  apply_k0(scene_, spec_, spec_.phases[p]);
  if (!spec_.phases[p].k0.empty()) {
    // The sand has moved since the start's check: a phase's own K0 stresses (a surcharge added)
    // may put it where no sand exists at its void ratio now. The run stops there, its outputs
    // kept, rather than go on in a state the material's equations do not cover.
    if (const auto found = first_inadmissible_particle(spec_, scene_)) {
      std::ostringstream s;
      s << spec_.file << ": phase '" << spec_.phases[p].name << "' (phases." << p
        << "), its k0 at t = " << start
        << " s: gives a state the material does not admit: " << found->key_and_reason << "; in "
        << found->particle << ", the first such";
      throw SimulationError(s.str());
    }
    solver.account_for_stress_reset(elastic_before);
  }
  solver.change_settings(settings(p));
  switch_on_absorbing_faces(solver, spec_, p);
}

PhaseRunner::PhaseSetUp CasePhases::set_up_on(ExplicitSolver& solver) const {
  return [this, &solver](std::size_t p, double start) { set_up(solver, p, start); };
}

} // namespace mpile
