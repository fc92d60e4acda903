#pragma once

// The implicit pore pressure of saturated soil ([solver] implicit_pore_pressure; physics.md
// section 9d). Explicitly, the pore water's stiffness K_w / n sets the step: its undrained P-wave
// is five to seven times faster than the skeleton's. Here the step's pore pressure increment is
// found on the grid instead, one value dp_c per cell, from the remapped velocities the stress
// pass will read, so that the velocities it leaves and the increment agree (backward Euler in
// the water's stiffness, a fractional step: the step's momentum balance took the pressure at the
// step's start, and this pass adds what its increment does):
//   (S_c / dt) dp_c = G_c u',   u' = u* - H G^T dp,
// with S_c = sum over the cell's saturated particles of V n / K_w, G_c the cell's divergence
// operator (sum of V grad N, and V N / r in the hoop direction), u the pore water's volume flux
// per node, (1 - n) v + n w (v for undrained soil), and H each node DOF's response to a force
// from the pressure: dt / M for undrained soil, the two phases' implicit-drag response for
// coupled soil (the mixture's at a structure's wall, where the phases are tied), 0 where a
// support or a drained face holds the skeleton. The system S + dt G H G^T is symmetric positive
// definite; Eigen's conjugate gradients solve it. The correction -H G^T dp goes onto the nodes and,
// interpolated, onto the particles.
//
// Water that would go past its cavitation stress takes no more tension (PLAXIS's cut-off): a cell
// whose increment would carry its water's pressure beyond the limit is held at it, its increment
// known (the limit less the cell's storage-weighted mean pressure) and its row of the system
// replaced by that, while the water's volume grows beyond what the pressure stores: vapour. A
// cell whose vapour would shrink is let go again. The held cells are found by iteration (a
// primal-dual active set: solve, hold the cells past the limit, free the held cells whose vapour
// would shrink, until none changes), so that the velocities take the tension the water carries,
// not the one it would have carried without the cut-off. A cell of coupled soil a structure
// occupies is not held (the contact decides there whether the soil leaves the wall): its particles
// are capped after it, unless [solver] hold_wall_cells holds it as the others.
//
// Reads particle cell, position, volume, body, material, state and stress, grid field 0 and the
// liquid nodes after the MUSL remap; writes their velocities, the particles' velocities (and
// their water's) and the increment each saturated particle takes after the stress pass.

#include "engine/geometry_mode.hpp"
#include "engine/particle_bins.hpp"
#include "engine/scene.hpp"
#include "engine/shape_functions.hpp"
#include "solver/passes.hpp"

#include <Eigen/SparseCore>

#include <cstdint>
#include <vector>

namespace mpile::passes {

struct ProjectionResult {
  std::int64_t cells = 0; // pressure unknowns (cells holding saturated soil)
  int iterations = 0;     // conjugate-gradient iterations
  double residual = 0.0;  // the solve's relative residual
  bool converged = true;
  double dissipated = 0.0; // backward Euler's numerical damping over the step (J)
  double drag = 0.0;       // Darcy's dissipation over the step at the corrected velocities (J)
  /// The work of the held cells' water at the limit on the vapour's volume, sum d_c V_vapour (J):
  /// the water's work on the volume it does not store, taken by the vapour.
  double vapour_work = 0.0;
};

class PorePressureProjection {
public:
  /// Solves for this step's pore pressure increment and corrects the velocities: assemble, solve
  /// with the cavitation cut-off, correct the nodes' velocities, hand back to the particles.
  template <GeometryMode mode, ShapeFunctions shape>
  ProjectionResult project(Scene& scene, const ParticleBins& bins, const SolverSettings& settings,
                           const StepParameters& step);

  /// The increment each particle takes (0 for a particle without implicit pore water), by
  /// particle index, from the last projection.
  const std::vector<double>& particle_increment() const { return particle_increment_; }

  /// By particle index, from the last projection: 1 where the particle's cell was held at the
  /// cavitation limit. Such a particle's pressure goes to its limit (the cell's increment moved its
  /// storage-weighted mean there) and the trapezoid's half of its work is d_c / 2 times what it
  /// stores.
  const std::vector<std::uint8_t>& particle_cavitated() const { return particle_cavitated_; }

private:
  /// One cell's sums over its saturated particles: the divergence operator's coefficients on the
  /// 4 x 4 nodes a GIMP particle of the cell can reach (r and y), and its storage (> 0 exactly
  /// where the cell holds saturated soil).
  struct CellSums {
    double coefficient[16][2];
    double storage;  // sum V n / K_w
    double headroom; // sum V n / K_w (limit - p): the storage the cut-off leaves (infinite: none)
    double flowing;  // sum V over its coupled soil's particles (their water flows)
  };

  /// The cells' sums, the unknowns (the cells holding saturated soil), each node DOF's response
  /// to the pressure's force, G, the system S + dt G H G^T and its right-hand side dt G u*.
  /// Returns the number of unknowns (0: nothing to solve; the particles take no increment).
  template <GeometryMode mode, ShapeFunctions shape>
  Eigen::Index assemble(Scene& scene, const ParticleBins& bins, const SolverSettings& settings,
                        const StepParameters& step);
  /// The increment, with the cells past their cavitation limit held at it (a primal-dual active
  /// set) and the vapour's work; false if a solve failed.
  bool solve_with_cavitation(const Grid& grid, const StepParameters& step, bool hold_wall_cells,
                             ProjectionResult& result);
  /// The nodes' velocities of both phases take the correction -H G^T dp; backward Euler's damping
  /// and Darcy's drag at the corrected velocities.
  void correct_velocities(Grid& grid, const StepParameters& step, ProjectionResult& result);
  /// The particles' velocities (and their water's) take the nodes' corrections; each saturated
  /// particle keeps its cell's increment and whether the cell was held.
  template <ShapeFunctions shape>
  void hand_back_to_particles(Scene& scene, const ParticleBins& bins, const StepParameters& step);
  /// Solves again with the held cells' increments fixed: their rows and columns become their
  /// diagonal's (scaled as the others, so the solve's tolerance still speaks of the free cells).
  /// Starts from `increment` and leaves the solution there; false if the solve failed.
  bool solve_held(const Eigen::VectorXd& rhs, const Eigen::VectorXd& limit_increment,
                  Eigen::VectorXd& increment, ProjectionResult& result);

  std::vector<CellSums> cells_;
  std::vector<int> unknown_of_cell_;
  std::vector<int> cell_of_unknown_;
  std::vector<double> response_;       // H per node DOF (2 per node): dv / f
  std::vector<double> water_response_; // dw / f per node DOF (coupled only)
  std::vector<double> correction_;     // dv per node DOF
  std::vector<double> water_correction_;
  std::vector<double> particle_increment_;
  std::vector<std::uint8_t> particle_cavitated_;
  std::vector<std::uint8_t> held_;            // per unknown: held at the cavitation limit
  std::vector<std::uint8_t> takes_increment_; // per particle: saturated soil in the solve
  Eigen::VectorXd storage_;                   // S per unknown
  Eigen::VectorXd rhs_;                       // dt G u*
  Eigen::VectorXd increment_;                 // dp per unknown, the solve's
  Eigen::SparseMatrix<double, Eigen::RowMajor> divergence_;
  Eigen::SparseMatrix<double> system_;
  Eigen::SparseMatrix<double> held_system_;
};

/// After the stress pass: each undrained particle's pore pressure and total stress take the
/// increment (no further than its cavitation limit; to it in a held cell); returns the water's
/// work beyond the stress pass's (which booked the pressure at the step's start), dp / 2 times
/// the stored volume change. A particle the stress pass made stress-free inside a rigid body is
/// left so.
double apply_projected_pore_pressure(Scene& scene, const ParticleBins& bins,
                                     const std::vector<double>& increment,
                                     const std::vector<std::uint8_t>& cavitated,
                                     bool some_made_stress_free);

} // namespace mpile::passes
