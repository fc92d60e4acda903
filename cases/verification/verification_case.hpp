#pragma once

// What a verification case (docs/verification.md) reports: its checks against a closed-form or
// published reference, and the options a user or a convergence study runs it with. The cases
// themselves: verification_cases.hpp.

#include "engine/grid.hpp"
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

/// Choices a user or a convergence study can change on top of a case file.
struct Options {
  int refinement = 1;                         // multiplies every zone's number of cells
  std::optional<int> particles_per_direction; // deformable bodies; default: the case file's
  std::optional<bool> bbar;                   // default: on
  std::optional<double> flip_fraction;        // default: per case
  std::optional<int> xpic_order;              // default: off (the case's FLIP/PIC blend)
  std::optional<double> poisson_ratio;        // V3 and V5, whose closed forms take any nu
  std::optional<double> courant_number;
  std::optional<bool> musl;                      // default: MUSL; false: USL
  std::optional<ShapeFunctions> shape_functions; // default: the case file's
  bool implicit_pore_pressure = false; // saturated cases: the pore pressure solved on the grid
  std::optional<double> mass_scaling;  // default: the case's (1)
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

/// A uniform grid from (r0, y0) to (r1, y1) with nr x ny cells.
Grid uniform_grid(double r0, double r1, int nr, double y0, double y1, int ny);

/// Solver settings of a case with the user's options applied on top.
SolverSettings apply_options(SolverSettings settings, const Options& options);

} // namespace mpile::verification

namespace mpile::verification {

/// Least-squares coefficients (c1, c2) of y ~ c1 f1 + c2 f2 over samples.
std::array<double, 2> fit_two_functions(const std::vector<double>& f1,
                                        const std::vector<double>& f2,
                                        const std::vector<double>& y);

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
