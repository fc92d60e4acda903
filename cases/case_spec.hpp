#pragma once

// A run as described by a case file, read and validated (cases/case_reader.cpp), before it becomes
// a scene (cases/case_builder.cpp). Units SI; docs/case-format.md documents every key.

#include "engine/boundary_conditions.hpp"
#include "engine/geometry_mode.hpp"
#include "engine/graded_axis.hpp"
#include "engine/materials/material_registry.hpp"
#include "engine/particle_fill.hpp"
#include "engine/structures/rigid_body.hpp"
#include "engine/time_function.hpp"
#include "solver/run_phase.hpp"
#include "solver/solver_settings.hpp"

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mpile {

struct MaterialSpec {
  std::string name;
  std::string type;
  MaterialParameters parameters;
  PoreWater water; // drained unless the table says otherwise
  /// "file:line: materials.<name>.<key>" of each parameter written, for errors found once the
  /// particles carry their initial stress.
  std::map<std::string, std::string> where;
};

/// An initial velocity component varying along r or y, added to the body's uniform velocity.
struct VelocityProfile {
  int component = 1;
  bool along_y = true;
  TimeFunction function; // evaluated at the position (m) instead of a time
};

/// A rigid body's mass, inertia and drives (physics.md section 6). A DOF without a drive is free;
/// until the drives' phase starts every DOF is held at rest.
/// A circle region's radius as read (its centre is an array, read by itself).
struct CircleSpec {
  double radius = 0.0;
};

struct RigidSpec {
  double mass = 0.0; // 0: from the particles
  /// The moment of inertia the body turns with, each under its mode's key (0: from the particles).
  double polar_inertia = 0.0;                     // axisymmetric: about the axis, per radian
  double inertia = 0.0;                           // plane strain: about the centre, per metre
  std::array<std::optional<RigidDrive>, 3> drive; // RigidDof order
  std::string phase;
};

struct BodySpec {
  std::string name;
  std::string material;
  Region region{Rectangle{0.0, 0.0, 0.0, 0.0}};
  int particles_per_direction = 2;
  /// Sub-cells the outline cuts are seeded with the part inside (their own centroid, volume and
  /// extent), not by whether their centre lies inside.
  bool cut_cells = false;
  std::array<double, 3> velocity{0.0, 0.0, 0.0};
  std::optional<VelocityProfile> velocity_profile;
  std::optional<RigidSpec> rigid;
  /// Where the region is written (for messages about it); 0 for a body a generator made.
  int line = 0;
  std::string key; // its key path, e.g. "bodies[1].region"
};

/// Contact between the soil (every body that is not a structure) and one structure body.
/// A rectangle's contact surfaces as read, by edge (empty: no contact surface).
struct RectangleSurfaces {
  std::string bottom, right, top, left;
};
/// The edges in the order of a rectangle's vertices(), as ContactSpec::surfaces keeps them.
inline constexpr std::array<std::string RectangleSurfaces::*, 4> rectangle_edges{
    &RectangleSurfaces::bottom, &RectangleSurfaces::right, &RectangleSurfaces::top,
    &RectangleSurfaces::left};

struct ContactSpec {
  std::string structure;
  double friction = 0.0;
  double adhesion = 0.0;
  bool outline = true; // normals from the structure's region, else its mass gradient
  /// With an outline: contact at a node on a straight run of one surface along r or y needs the
  /// soil's surface interpolated to the node to reach the outline (ContactPair::surface_gap).
  bool surface_gap = false;
  /// The single surface's name as written (`surface`; empty when absent): mass-gradient normals'
  /// or a circle's, gathered into `surfaces`.
  std::string surface;
  /// With an outline, the surface name of each of its edges (empty: not a contact surface), in
  /// the order of the region's vertices(): a rectangle's bottom, right, top and left edges, a
  /// polygon's edges counter-clockwise; a circle's single name. With mass-gradient normals, the
  /// single name.
  std::vector<std::string> surfaces{"bottom", "right", "top", "left"};
};

/// Grid nodes on one grid line: r = at (all y within [from, to]) or y = at (r within [from, to]).
struct NodeLineSpec {
  bool along_y = true; // true: the line r = at; false: the line y = at
  double at = 0.0;
  double from = 0.0;
  double to = 0.0;
};

/// Prescribed nodal velocities (m/s; for theta optionally an angular velocity in rad/s).
struct MotionSpec {
  std::string name;
  NodeLineSpec nodes;
  std::array<std::optional<TimeFunction>, 3> velocity;
  bool theta_is_rotation = false;
  std::string phase; // starts with this phase (its time functions count from its start)
  std::string body;  // a contact structure whose field it acts on; empty: the soil's field
};

/// A normal or tangential traction (Pa) on a grid line.
struct LoadSpec {
  std::string name;
  NodeLineSpec nodes;
  int component = 0;
  TimeFunction traction;
  std::string phase;
};

struct K0Spec {
  std::string body;     // each body the stress is set in
  std::string material; // as read: every body of this material (then one K0Spec per body)
  double surface = 0.0;
  double k0 = 0.5;
  double surcharge = 0.0; // Pa on the surface (a calibration chamber's vertical stress)
};

/// A rigid body's drives from a phase's start on (a load test after an installation): the DOFs
/// given are driven, the others free (force 0), as a body's own drives once their phase starts.
struct PhaseDrive {
  std::string body;
  std::array<std::optional<RigidDrive>, 3> drive; // RigidDof order
};

/// A phase of the case: what the phase runner needs (name, duration, end criteria) and the
/// settings and initial conditions the phase brings.
struct PhaseSpec : RunPhase {
  double local_damping = 0.0;
  bool gravity = true;
  std::optional<double> flip_fraction;
  std::optional<int> xpic_order;
  std::optional<double> mass_scaling;
  std::optional<double> courant_number;
  std::vector<K0Spec> k0;
  std::optional<PhaseDrive> drive;
};

/// A material point whose stress, strain and state go into the history ([[output.monitor]]):
/// a particle id, or the soil particle nearest a position (r, y) at the start.
struct MonitorSpec {
  std::string name;
  std::string where; // "file:line: output.monitor.<key>", for errors found once particles exist
  std::optional<std::array<double, 2>> position;
  std::optional<long> particle;
  /// A point fixed in space (a transducer), sampled from the soil particles around it at every
  /// row, instead of the particle nearest it followed.
  bool fixed = false;
  /// The material a fixed monitor reads; empty: that of the soil particle nearest its point at
  /// the start. Named, the point may lie where soil arrives later (NaN rows until then).
  std::string material;
};

struct OutputSpec {
  std::string directory;          // empty: out/<case file stem>
  double snapshot_interval = 0.0; // s of simulated time; 0: first and last only
  std::vector<double> snapshot_times;
  double history_interval = 0.0;    // s; 0: every step
  double checkpoint_interval = 0.0; // s of simulated time; 0: only when stopped
  bool grid_snapshots = false;
  /// Snapshots when a rigid body's downward displacement reaches these depths (m).
  std::vector<double> snapshot_penetrations;
  std::string penetration_body;
  /// A cone penetration test's q_c, f_s and R_f in the history ([output.cpt]).
  struct Cpt {
    std::string body;              // the contact structure that is the cone
    std::string cone = "cone";     // its surface whose F_y over its plan area is q_c
    std::string sleeve = "sleeve"; // its surface whose F_y over its side area is f_s
  };
  std::optional<Cpt> cpt;
  std::vector<MonitorSpec> monitors;
};

/// [boundaries]' conditions by face as written (CaseSpec::faces holds them in GridFace order).
struct FaceConditions {
  FaceCondition r_min = FaceCondition::free;
  FaceCondition r_max = FaceCondition::free;
  FaceCondition y_min = FaceCondition::free;
  FaceCondition y_max = FaceCondition::free;
  /// The pore pressure beyond the drained faces: zero (an open drain) or the far field's
  /// hydrostatic pressure below the saturated soil's surface.
  bool hydrostatic_drains = false;
};

/// A time function's table as written: its type and the numbers that type takes (the reader reads
/// those alone, TomlTable::read_members, so that another type's key is refused as unknown).
struct TimeFunctionKeys {
  std::string type;
  double value = 0.0;
  double duration = 0.0;
  double amplitude = 0.0;
  double frequency = 0.0;
  double phase = 0.0;
  double mean = 0.0;
  double interval = 0.0;
};

/// [monopile]'s keys beyond the geometry's (MonopileParameters) and its contact's (ContactSpec):
/// the materials it builds the soil and the pile of, their particles, whether the band moves.
struct MonopileSetup {
  std::string soil_material;
  std::string pile_material;
  int particles_per_cell = 2;
  bool moving_mesh = true;
};

/// y-lines between band_bottom and band_top (grid lines) move with a rigid body.
struct MovingMeshSpec {
  std::string body;
  double band_bottom = 0.0;
  double band_top = 0.0;
  double travel = 0.0; // m the band may move from where it starts; 0: up to the squeeze limit
  /// Grid lines (y) beyond which no line moves; unset: the grid's bottom and top.
  std::optional<std::array<double, 2>> stretch;
};

/// A value that reads but is likely a mistake (cases/case_warnings.hpp): "file:line: key: message".
struct CaseWarning {
  enum class Kind {
    units,     // outside what any soil, steel or installation uses: most likely the wrong unit
    resolution // a mesh that resolves less than the results need: a note, never an error
  };
  Kind kind = Kind::units;
  std::string text;    // "file:line: key.path: message", as printed
  std::string key;     // the key the value was written under, in its table ("friction_angle")
  std::string message; // what is implausible and the likely slip, without the location
};

/// [water]: the sea's free surface above a horizontal seabed, or a water table inside the soil
/// (physics.md section 9c).
struct WaterSpec {
  double level = 0.0;           // m: y of the sea's free surface
  double seabed = 0.0;          // m: the saturated bodies' K0 surface (the table, with one)
  double column_pressure = 0.0; // Pa: rho_w g (level - seabed)
  double table = 0.0;           // m: y of the phreatic level inside the soil ...
  bool phreatic = false;        // ... when one is given (then level = seabed = table)
};

struct CaseSpec {
  std::string file;
  std::string text;     // the case file's own text
  std::string resolved; // the case as read: its bases merged and --set applied, as TOML
  std::vector<std::string> overrides; // the --set key.path=value assignments, in order
  std::vector<std::string> bases;     // the base files under the case file, nearest first
  std::string title;
  GeometryMode mode = GeometryMode::axisymmetric;
  std::vector<AxisZone> r_zones;
  std::vector<AxisZone> y_zones;
  std::vector<MaterialSpec> materials;
  std::vector<BodySpec> bodies;
  std::array<FaceCondition, 4> faces{FaceCondition::free, FaceCondition::free, FaceCondition::free,
                                     FaceCondition::free};
  /// Held faces the pore water of coupled soil flows out through (p = 0 beyond them); every other
  /// held face is impermeable.
  std::vector<GridFace> drained_faces;
  /// [boundaries] drained_pressure = "hydrostatic": where the far field's pore pressure is zero
  /// (the saturated soil's surface) and its water's density (DrainedFaceWater).
  struct DrainedWater {
    double surface = 0.0;
    double density = 0.0;
  };
  std::optional<DrainedWater> drained_water;
  /// Faces whose support gives way to dashpots (engine/absorbing_boundary.hpp) at the start of a
  /// phase (empty: the first).
  struct Absorbing {
    std::vector<GridFace> faces;
    std::string phase;
  } absorbing;
  std::vector<ContactSpec> contacts;
  std::vector<MotionSpec> motions;
  std::vector<LoadSpec> loads;
  std::optional<MovingMeshSpec> moving_mesh;
  /// [affine_motion]: every node moves with v = L x; L row by row (dv_r/dr, dv_r/dy, dv_y/dr,
  /// dv_y/dy).
  std::optional<std::array<double, 4>> velocity_gradient;
  SolverSettings solver;
  std::vector<PhaseSpec> phases;
  OutputSpec output;
  std::optional<WaterSpec> water; // none: no sea above the seabed
  /// What the reader found implausible but readable, in the order read.
  std::vector<CaseWarning> warnings;

  double end_time() const; // sum of the phase durations (the longest the run can take)
};

class TomlTable;

/// Reads one material table (type and the type's parameters, checked against the registry and by
/// building the model once); errors name the file, line and parameter.
MaterialSpec read_material_table(TomlTable& table, const std::string& name);

/// Reads and validates a case file, with the base files it names and --set overrides
/// (key.path=value); throws CaseError naming file, line, key and reason.
CaseSpec read_case_file(const std::string& path, const std::vector<std::string>& overrides = {});

/// The largest case file read (bytes): the shipped ones are below 10 KiB, a case with every
/// snapshot time of a long run listed below 1 MiB.
constexpr std::uintmax_t max_case_file_bytes = 16u << 20;
CaseSpec read_case_text(const std::string& text, const std::string& file);

} // namespace mpile
