#pragma once

// The passes of one explicit MUSL step (physics.md section 3), each in its own file. Every pass
// says at its top which fields it reads and which it writes. The particle passes take contact =
// true in a scene with contact: each particle then maps to its body's velocity field; a scene
// without contact runs the single-field version and pays nothing for it.

#include "engine/geometry_mode.hpp"
#include "engine/particle_bins.hpp"
#include "engine/scene.hpp"
#include "engine/shape_functions.hpp"
#include "solver/solver_settings.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace mpile::passes {

/// Node masses at or below this are treated as empty (no velocity).
struct StepParameters {
  double time = 0.0;
  double dt = 0.0;
  double mass_floor = 0.0;
};

template <GeometryMode mode, bool contact = false, ShapeFunctions shape = ShapeFunctions::linear>
void particle_to_grid(Scene& scene, const ParticleBins& bins, const SolverSettings& settings);

/// Each material's Material::pore_pressure_index (-1 for a dry or drained one), by material.
std::vector<int> pore_pressure_slots(const Scene& scene);

/// The pore water's share of field 0's internal force (Grid::pore_force), for a scene with
/// contact and undrained soil (solver/pore_pressure_to_grid.cpp).
template <GeometryMode mode, ShapeFunctions shape>
void map_pore_force(Scene& scene, const ParticleBins& bins);

/// Each material's LiquidPhase (null for all but coupled soil), by material.
std::vector<const LiquidPhase*> liquid_phases(const Scene& scene);

/// The pore water of coupled soil (solver/pore_water_passes.cpp): its particle-to-grid map into
/// Grid::liquid, ...
template <GeometryMode mode, ShapeFunctions shape>
void map_water_to_grid(Scene& scene, const ParticleBins& bins,
                       const std::vector<const LiquidPhase*>& phases,
                       const SolverSettings& settings);
/// ... the water's inertia and drag folded into field 0's nodes before their momentum balance ...
/// Returns the kinetic energy the water tied to the skeleton at a structure's wall gives up, and
/// the work a drained face does in giving its nodes' water the velocity they kept.
struct CoupledPhasesResult {
  double tied_drag = 0.0;
  double drain_work = 0.0;
};
template <GeometryMode mode>
CoupledPhasesResult couple_phases(Scene& scene, const StepParameters& step, double mass_scaling);
/// ... the water's velocities from the skeleton's final ones ...
struct WaterVelocityResult {
  double drag = 0.0;         // taken by Darcy's drag over the step
  double support_work = 0.0; // done on the water by the impermeable faces
  double drain_work = 0.0;   // done on the water by the drained faces (Grid::drain_water_velocity)
  double tied_drag = 0.0;    // the kinetic energy tying the phases at a wall took (couple_phases)
};
template <GeometryMode mode>
WaterVelocityResult update_water_velocities(Scene& scene, const StepParameters& step,
                                            double mass_scaling);
/// Drained faces held at the far field's hydrostatic pressure (Boundaries::drained_water): its
/// traction on the face nodes' water and mixture, after map_water_to_grid; and the work it did on
/// the water over the step, after update_water_velocities (solver/drained_face_water.cpp).
void apply_drained_face_water(Scene& scene, const std::vector<const LiquidPhase*>& phases,
                              const SolverSettings& settings);
double drained_face_water_work(const Scene& scene, const StepParameters& step);
/// With cell_mean_pore_pressure: each cell's saturated particles take their volume-weighted mean
/// excess pore pressure (the total stress following, the effective stress kept); the stored energy
/// this changes is the ledger's plastic term (solver/pore_pressure_to_grid.cpp).
void smooth_excess_pore_pressure(Scene& scene, const ParticleBins& bins);
/// ... the particles' water velocity (under XPIC(m) with the water's own correction, xpic.hpp;
/// null otherwise) ...
struct WaterXpic;
struct WaterParticleResult {
  double external_work = 0.0; // gravity on the water's path beyond the skeleton's
  double transfer = 0.0;      // the water's kinetic energy a FLIP/PIC blend takes
  double drag = 0.0;          // taken by the drag on the particles' own relative flow
};
template <GeometryMode mode, ShapeFunctions shape>
WaterParticleResult update_water_particle_velocities(Scene& scene, const ParticleBins& bins,
                                                     const std::vector<const LiquidPhase*>& phases,
                                                     const SolverSettings& settings,
                                                     const StepParameters& step,
                                                     const WaterXpic* xpic);
/// ... with MUSL, the skeleton's remapped velocities as the mixture's mass-weighted mean, and
/// the water's remapped ...
template <GeometryMode mode> void rescale_remapped_skeleton(Scene& scene);
template <GeometryMode mode, ShapeFunctions shape>
void remap_water(Scene& scene, const ParticleBins& bins,
                 const std::vector<const LiquidPhase*>& phases, double mass_floor);
/// ... and the pore pressure's share from the water's flow, found before the stress pass (at the
/// particles' positions of the step's start) and added after it (so that it takes the stress at
/// the step's start); the second returns the pore water's work beyond the stress pass's.
struct PendingPorePressure {
  double pressure = 0.0;        // K_w div w dt
  double water_strain = 0.0;    // div w dt
  double skeleton_strain = 0.0; // div v dt
  double pore_before = 0.0;     // p at the step's start
  /// The implicit pore pressure held the particle's cell at the cavitation limit: the particle
  /// goes to its limit, and `pressure` is the cell's increment.
  bool cavitated = false;
};
template <GeometryMode mode, ShapeFunctions shape>
void pore_pressure_from_flow(Scene& scene, const ParticleBins& bins,
                             const std::vector<const LiquidPhase*>& phases,
                             const SolverSettings& settings, const StepParameters& step,
                             std::vector<PendingPorePressure>& pending);
double apply_pore_pressure_from_flow(Scene& scene, const ParticleBins& bins,
                                     const std::vector<const LiquidPhase*>& phases,
                                     const std::vector<PendingPorePressure>& pending,
                                     bool some_made_stress_free);
/// Particle i's porosity now, as its coupled material keeps it.
double water_porosity(const Particles& p, std::size_t i, const LiquidPhase& phase);
/// The kinetic energy of particle i's water, 1/2 m_w |w|^2.
double water_kinetic_energy(const Particles& p, std::size_t i, const LiquidPhase& phase);

void apply_nodal_loads(Scene& scene, const StepParameters& step);

struct GridUpdateResult {
  double damping_dissipation = 0.0; // work taken by local damping over the step (J)
  std::int64_t node_nonfinite = -1; // lowest index of a node with a non-finite velocity, or -1
};

template <GeometryMode mode>
GridUpdateResult update_grid_velocities(Scene& scene, const SolverSettings& settings,
                                        const StepParameters& step);

/// One absorbing-face node's dashpot coefficients (force per velocity; theta: torque per angular
/// velocity) and holding force (theta: torque), summed over the faces it lies on.
struct FaceNodeTerms {
  int node = 0;
  std::array<double, 3> dashpot{0.0, 0.0, 0.0};
  std::array<double, 3> holding{0.0, 0.0, 0.0};
};

/// Every active absorbing face's nodes with their terms at the grid's coordinates now, merged at
/// shared corner nodes, in node order (empty without active faces).
std::vector<FaceNodeTerms> absorbing_face_terms(const Scene& scene);

/// Adds the forces (theta: torques) that absorbing faces hold their nodes with to the soil's node
/// forces, as loads are added. Returns the sum of their squares (a torque counted as a force at the
/// node's radius of gyration), for the equilibrium check's measure of the forces that hold.
double apply_holding_tractions(Scene& scene, const std::vector<FaceNodeTerms>& terms,
                               const StepParameters& step);

struct AbsorbedWork {
  double radiated = 0.0; // taken by the dashpots over the step (J)
  double holding = 0.0;  // done by the holding forces, an external work
};

/// After the momentum balance: the dashpots of the active absorbing faces, taken implicitly, on the
/// soil's free DOFs of their nodes.
AbsorbedWork absorb_at_faces(Scene& scene, const std::vector<FaceNodeTerms>& terms,
                             const SolverSettings& settings, const StepParameters& step);

/// Switches absorbing faces on from the node forces f_ext - f_int now (a particle-to-grid map with
/// loads and the holding forces of faces already on): their supports give way, each node keeps
/// the force that held it as a traction profile along the face, and the impedances of the soil
/// beside the face are sampled.
void switch_on_absorbing_faces(Scene& scene, const std::vector<std::size_t>& faces,
                               const StepParameters& step);

/// Which constraints a call applies: with contact, those on structure fields come before the
/// contact correction (which then sees the structure's prescribed velocity), those on the soil
/// after it.
enum class ConstraintFields { all, soil, structures };

/// The two passes of a step that correct nodal velocities (supports, contact): the one after the
/// momentum balance, which decides contact and records reactions, forces and FLIP increments, and
/// its repeat on the velocities the MUSL remap gives, which only applies the same corrections.
enum class CorrectionPass { after_balance, after_remap };

/// Sets constrained DOFs to their prescribed velocities. After the momentum balance, also the
/// velocity increment and the reaction of each constraint, and returns the work the reactions do
/// over the step; after the remap, only the velocities (and returns 0).
double apply_constraints(Scene& scene, const SolverSettings& settings, const StepParameters& step,
                         CorrectionPass pass, ConstraintFields fields = ConstraintFields::all);

/// Work of the nodal loads over the step, from the updated nodal velocities.
double nodal_load_work(const Scene& scene, const StepParameters& step);

struct XpicFields;

/// With xpic, the XPIC velocity update from its corrections (solver/xpic.hpp); without, the
/// FLIP/PIC blend of the settings. Returns the kinetic energy the update took against what FLIP
/// would have kept (the velocity update's numerical dissipation; 0 for pure FLIP).
template <GeometryMode mode, bool contact = false, ShapeFunctions shape = ShapeFunctions::linear>
double grid_to_particle(Scene& scene, const ParticleBins& bins, const SolverSettings& settings,
                        const StepParameters& step, const XpicFields* xpic = nullptr);

template <GeometryMode mode, bool contact = false, ShapeFunctions shape = ShapeFunctions::linear>
void remap_momentum(Scene& scene, const ParticleBins& bins, const StepParameters& step);

struct StressPassResult {
  double min_crossing_time = 0.0;       // min over particles of h_cell / (c_p + |v_p|)
  double step_crossing_time = 0.0;      // the same in the cells the step was computed in
  bool block_changed = false;           // a particle moved into another scatter block
  bool cell_changed = false;            // a particle moved into another cell
  bool rigid_left_grid = false;         // a rigid body's particle left the grid (cell_r = -1)
  std::int64_t particle_outside = -1;   // lowest index of a particle that left the grid, or -1
  double gravity_work = 0.0;            // sum of m g . du over the particles
  double internal_work = 0.0;           // sum of V sigma : d eps over the particles
  std::int64_t particle_nonfinite = -1; // lowest index of a particle with a non-finite stress or
                                        // velocity, or -1
  std::int64_t stress_free_inside_rigid = 0; // soil particles inside rigid bodies, made stress-free
};

/// With signal_speed (one entry per particle), also keeps each particle's c_p + |v_p| there, for a
/// step limit after the cells have moved (a moving mesh); empty, it is not kept.
template <GeometryMode mode, bool contact = false, ShapeFunctions shape = ShapeFunctions::linear>
StressPassResult
update_stress_and_positions(Scene& scene, const ParticleBins& bins, const SolverSettings& settings,
                            const StepParameters& step, std::span<double> signal_speed = {});

/// The bit a particle of a field sets in its block's tag (ParticleBins::tag_blocks): none for the
/// soil (field 0), one per structure field (fields past the 64th share the last bit).
std::uint64_t structure_tag(int field);

/// The nodes the particles of a block can touch: its cells widened by one on either side (GIMP).
NodeBox block_node_box(const Grid& grid, const ParticleBins& bins, int block);

/// Tags the blocks with their particles' structure fields and sets each structure field's reach
/// to the nodes its blocks' particles can touch. Called whenever the particles are binned anew.
void find_structure_reach(Scene& scene, ParticleBins& bins);

/// min over particles of h_cell / (c_p + |v_p|) from the materials' current stiffness; NaN if any
/// particle's is (its material reports no finite modulus there).
double min_crossing_time(const Scene& scene, const SolverSettings& settings);

/// The particle min_crossing_time's limit comes from, and what sets it there: for the log when
/// the step falls (a scan of every particle, done once for each halving of the step), and the
/// first particle whose crossing time is NaN if one is.
struct StepLimit {
  std::size_t particle = 0;
  double crossing_time = 0.0; // h / (c + |v|), s
  double wave_speed = 0.0;    // c = sqrt(M / rho), m/s, with the mass scaling
  double density = 0.0;       // m / V, kg/m^3, without it
  double speed = 0.0;         // |v|, m/s
  double cell = 0.0;          // h, the cell's smaller side, m
};
StepLimit step_limit(const Scene& scene, const SolverSettings& settings);

} // namespace mpile::passes
