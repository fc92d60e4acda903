#pragma once

// Verification cases (../docs/verification.md): scenes with a closed-form or published reference,
// built at a chosen resolution, run, and compared. The unit tests and `mpile verify` share them.

#include "engine/materials/hardening_soil.hpp"
#include "engine/scene.hpp"
#include "solver/equilibrium.hpp"
#include "solver/solver_settings.hpp"

#include <array>
#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace mpile::verification {

/// One compared quantity: error = |measured - reference| / scale, where scale is |reference|
/// unless the reference is zero or a natural magnitude is more meaningful (stated per check).
struct Check {
  std::string quantity;
  std::string unit;
  double measured = 0.0;
  double reference = 0.0;
  double scale = 1.0;
  double tolerance = 0.0; // on the relative error, from the reference case's table
  double error() const;
  bool passed() const { return error() <= tolerance; }
};

/// Choices a user or a convergence study can change; each case documents its defaults.
struct Options {
  int refinement = 1;                  // multiplies the case's base number of cells per direction
  int particles_per_direction = 2;     // particles per cell = this squared
  std::optional<bool> bbar;            // default: on
  std::optional<double> flip_fraction; // default: per case
  std::optional<int> xpic_order;       // default: off (the case's FLIP/PIC blend)
  std::optional<double> poisson_ratio; // for the cases with a nu-dependent closed form
  std::optional<double> courant_number;
  std::optional<bool> musl; // default: MUSL; false: USL
  int block_cells = 8;
};

struct Report {
  std::string id;
  std::string title;
  std::vector<Check> checks;
  std::size_t particles = 0;
  long steps = 0;
  double wall_seconds = 0.0;
  std::vector<std::string> warnings;
  bool passed() const;
};

struct Case {
  std::string id;
  std::string title;
  std::function<Report(const Options&)> run;
};

const std::vector<Case>& all_cases();
const Case* find_case(const std::string& id);

/// A uniform grid from (r0, y0) to (r1, y1) with nr x ny cells.
Grid uniform_grid(double r0, double r1, int nr, double y0, double y1, int ny);

/// Solver settings of a case with the user's options applied on top.
SolverSettings apply_options(SolverSettings settings, const Options& options);

Report run_vibrating_bar(const Options& options);
Report run_single_point(const Options& options);
Report run_lame_cylinder(const Options& options);
Report run_radial_patch(const Options& options);
Report run_plane_strain_patch(const Options& options);
Report run_uniaxial_cylinder(const Options& options);
Report run_shaft_torsion(const Options& options);
Report run_self_weight_column(const Options& options);
Report run_k0_column(const Options& options);
Report run_hs_oedometer(const Options& options);

/// The seed paper's dry sand, Hardening Soil parameters of its Table 5 (p_ref = 100 kPa).
HardeningSoilParameters seed_sand();

} // namespace mpile::verification

namespace mpile::verification {

/// Least-squares coefficients (c1, c2) of y ~ c1 f1 + c2 f2 over samples.
std::array<double, 2> fit_two_functions(const std::vector<double>& f1,
                                        const std::vector<double>& f2,
                                        const std::vector<double>& y);

/// Quasi-static cases are relaxed until the out-of-balance force ratio and the kinetic energy
/// relative to the external work are both below this (solver/equilibrium.hpp).
inline constexpr double equilibrium_tolerance = 1e-9;

/// The check that a quasi-static case reached equilibrium before it was compared.
Check equilibrium_check(const EquilibriumResult& result);

/// A velocity history that moves a support by `travel` over `duration`: a trapezoid (a quarter of
/// the time to accelerate, half at peak, a quarter to stop), so the load comes on without a jolt.
TimeFunction trapezoid_velocity(double travel, double duration);

/// A smooth rigid platen on the grid's top face ("top platen") that moves down by `travel` along
/// trapezoid_velocity over `duration`; its reaction is the platen force.
NodeConstraint top_platen(const Grid& grid, double travel, double duration);

/// Follows a sampled oscillation: its largest amplitude and its period from the zero crossings
/// (linearly interpolated between samples, half a period apart).
class OscillationMeter {
public:
  OscillationMeter(double t0, double v0) : previous_t_(t0), previous_v_(v0) {}
  void sample(double t, double v);
  double amplitude() const { return amplitude_; }
  double period() const;

private:
  double previous_t_, previous_v_;
  double amplitude_ = 0.0;
  std::vector<double> crossings_;
};

/// Wall-clock seconds since start, for reports.
double seconds_since(std::chrono::steady_clock::time_point start);

} // namespace mpile::verification
