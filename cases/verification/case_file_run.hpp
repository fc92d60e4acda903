#pragma once

// A verification case file run as `mpile run` runs it, with the options of `mpile verify` (a
// refinement, particles per cell, a Poisson ratio, solver choices) applied on top. The case files
// are the cases' one source: each case's code only measures the run against its reference.

#include "cases/case_spec.hpp"
#include "cases/verification/verification_case.hpp"
#include "solver/equilibrium.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/phase_runner.hpp"

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace mpile::verification {

/// The case text with every grid zone's cell count (`cells = n`) multiplied by the refinement.
std::string refined(std::string_view text, int refinement);

/// Whether a case's closed form holds for any Poisson ratio, so that `--poisson` may set it.
enum class PoissonRatio { the_files, the_options };

/// The case file (built into the program) read with the options applied: the zones' cells times
/// the refinement, the deformable bodies' particles per cell direction and, where the case lets
/// it, every material's Poisson ratio. The solver choices go on the phase's settings (CaseFileRun).
CaseSpec read_verification_case(std::string_view file, const Options& options,
                                PoissonRatio poisson = PoissonRatio::the_files);

/// The integral of a velocity history over the case's single phase (the travel or the rotation
/// a prescribed motion makes): the midpoint rule on 200 000 intervals, exact for a table whose
/// points fall on their ends.
double travel_of(const TimeFunction& velocity, const CaseSpec& spec);

/// A verification case file built and run through its single phase by the phase runner, its K0
/// procedure, end criteria and energy guard included.
class CaseFileRun final : public RunObserver {
public:
  using AfterStep = std::function<void(const ExplicitSolver&)>;

  CaseFileRun(std::string_view file, const Options& options,
              PoissonRatio poisson = PoissonRatio::the_files);

  const CaseSpec& spec() const { return spec_; }
  Scene& scene() { return *scene_; }
  const Scene& scene() const { return *scene_; }
  /// A parameter of a material of the case file as read (after the options).
  double parameter(std::string_view material, std::string_view key) const;

  /// Runs the phase, calling after_step after every step. The report carries the id, title,
  /// particle and step counts, wall time and the log's warnings; the case adds its checks.
  Report run(std::string id, std::string title, const AfterStep& after_step = {});

  /// The equilibrium check of a phase that ends at equilibrium: the end state's measure within
  /// the case file's equilibrium_tolerance.
  Check equilibrium() const;

  void stepped(const RunPhase&, long, const PhaseGoal&) override;

private:
  CaseSpec spec_;
  std::unique_ptr<Scene> scene_;
  /// The options' solver choices, applied on the phase's settings.
  std::function<SolverSettings(SolverSettings)> solver_options_;
  RunLog log_;
  const ExplicitSolver* solver_ = nullptr;
  AfterStep after_step_;
  std::optional<EquilibriumMeasure> rest_;
};

} // namespace mpile::verification
