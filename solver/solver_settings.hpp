#pragma once

#include "engine/parameter_range.hpp"
#include "engine/shape_functions.hpp"

#include <array>
#include <limits>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace mpile {

/// Numerical choices of a run (physics.md sections 3, 4 and 8).
struct SolverSettings {
  /// dt = courant_number * min over particles of h_cell / (c_p + |v_p|).
  double courant_number = 0.8;
  /// Upper bound on dt (s), for loads that need a finer sampling than the stability limit.
  double max_time_step = std::numeric_limits<double>::infinity();
  /// Particle velocity update: 1 = FLIP (no numerical dissipation), 0 = PIC, between: a blend.
  double flip_fraction = 1.0;
  /// 0: the FLIP/PIC blend above. m >= 1: XPIC(m) (Hammerquist and Nairn 2017), which takes the
  /// particle velocities from the grid after removing, to order m, the part of their old field the
  /// grid cannot represent (the cell-crossing noise FLIP keeps) while keeping the part it can
  /// (which PIC smears). XPIC(1) is PIC; as m grows the update tends to the particles' velocity
  /// field projected onto the grid's. Excludes a flip_fraction below 1.
  int xpic_order = 0;
  static constexpr int max_xpic_order = 16;
  /// MUSL (true): the strain increment uses nodal velocities remapped from the updated particle
  /// momenta; USL (false): it uses the grid's updated velocities directly, one scatter less.
  bool musl = true;
  /// Replace each particle's volumetric strain increment by its cell's volume-weighted mean.
  bool bbar = true;
  /// With B-bar, take B-bar's transpose in the internal force: each particle's mean stress (and a
  /// coupled particle's pore pressure in its water's force) as its cell's volume-weighted mean, so
  /// that the nodal forces do the work the strains store (physics.md section 4). Needs bbar.
  bool bbar_consistent_force = false;
  /// Replace the excess pore pressure of each cell's saturated particles (undrained or coupled) by
  /// their volume-weighted mean after every stress update: the pore pressure as one value per cell,
  /// against the per-particle checkerboard of nearly incompressible soil.
  bool cell_mean_pore_pressure = false;
  /// Find each step's pore pressure increment of saturated soil on the grid, implicitly in the
  /// water's stiffness (one pressure per cell, a sparse symmetric system solved by conjugate
  /// gradients; physics.md section 9d): the step then follows the skeleton's wave speed, not the
  /// undrained one, five to seven times slower in sand with K_w = 2.2 GPa. MUSL only.
  bool implicit_pore_pressure = false;
  /// With the implicit pore pressure and a cavitation stress: hold the cells of coupled soil at a
  /// structure's wall at the limit in the solve, as every other cell (docs/saturated.md, "Holding
  /// the wall cells"). Off, their particles are capped after the solve and the velocities take
  /// suction the capped stress does not keep: the quick installations' ledgers close three to
  /// five times worse and the quick saturated capacities read 11 to 47 % lower. Off is kept for the
  /// cases measured so.
  bool hold_wall_cells = true;
  /// Co-rotate stress with the in-plane spin (Jaumann rate) for large rotations.
  bool jaumann_rate = true;
  /// Local (Cundall) damping coefficient alpha: f_damp = -alpha |f_unbalanced| sign(v).
  double local_damping = 0.0;
  /// Density multiplier beta for inertia only (gravity keeps the true mass); dt grows by
  /// sqrt(beta). Quasi-static work only: the run log warns when it is not 1.
  double mass_scaling = 1.0;
  /// Gravitational acceleration (r, y) in m/s^2; physics.md puts gravity along -y.
  std::array<double, 2> gravity{0.0, 0.0};
  /// The time step below which a run stops as collapsed (s); 0: a thousandth of the first step.
  double min_time_step = 0.0;
  /// A history row whose energy residual exceeds this fraction of the energy in play warns.
  double energy_residual_warning = 0.05;
  /// An energy residual that stays above this fraction for 100 steps stops the run as unstable:
  /// energy the physics cannot account for exceeds half the energy in play (an energy blow-up).
  double energy_residual_limit = 0.5;
  /// Cells per side of a scatter block (colored scatter); at least 3 with GIMP, whose particles
  /// reach one cell beyond their own.
  int block_cells = 8;
  /// Split a particle whose domain has grown longer than its cell (it moved into finer cells) into
  /// halves that fit, so that no fine cell inside a body is left empty (engine/particle_split.hpp).
  bool split_particles = true;
  /// Soil stretched to under half its material's density whose centre lies inside a rigid body's
  /// outline carries no stress there and sets no time step (solver/rigid_interiors.hpp says why).
  /// Off: with the step held it leaves a resolved pile wall's forces as they are, and the longer
  /// step it allows moves them as any other perturbation of the step does (docs/resolution.md).
  bool stress_free_inside_rigid = false;
  /// How particles reach the grid: bilinear at their centre, or GIMP over their domain.
  ShapeFunctions shape_functions = ShapeFunctions::linear;

  /// Throws std::invalid_argument naming the setting that is out of range (its declared range,
  /// solver_parameters()) or that contradicts another.
  void validate() const;
};

/// A numerical setting as a case file names it: key, unit, meaning, range and the member it sets.
/// Declared once (solver_settings.cpp): the case format's [solver] and [[phases]] keys are built
/// from it, the reader stores each value through it, and validate() checks its range.
struct SolverParameter {
  std::string name;
  std::string unit; // "-" for a ratio, "s" for a time, "" for a count or a switch
  std::string meaning;
  std::variant<double SolverSettings::*, int SolverSettings::*, bool SolverSettings::*> member;
  ParameterRange range;
  /// Not empty: the member's default is a sentinel the solver replaces by this (documentation).
  std::string computed_default;
  /// Set by each phase ([[phases]]), not by [solver].
  bool per_phase = false;
};
const std::vector<SolverParameter>& solver_parameters();
/// The declaration of one setting; throws std::logic_error for a name not declared.
const SolverParameter& solver_parameter(std::string_view name);

} // namespace mpile
