// The case reader must reject bad input with the file, line, key and reason, and run_case must turn
// that into exit status 2. Each row of the table below is one mistake a user makes.
#include "app/run_command.hpp"
#include "cases/case_error.hpp"
#include "cases/case_spec.hpp"
#include "cases/plausibility.hpp"
#include "tests/case_run.hpp"

#include <gtest/gtest.h>

#include <cstdlib>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <sys/stat.h>

namespace mpile {
namespace {

const std::string valid_case = R"(title = "reader test"
geometry = "axisymmetric"

[grid]
r = [{ start = 0.0, end = 1.0, cells = 8 }]
y = [{ start = 0.0, end = 1.0, cells = 8 }]

[materials.soil]
type = "linear_elastic"
young_modulus = 1e7
poisson_ratio = 0.3
density = 1800.0

[[bodies]]
name = "block"
material = "soil"
region = { r = [0.0, 0.5], y = [0.0, 0.5] }
particles_per_cell = 2

[boundaries]
y_min = "fixed"

[[prescribed]]
name = "top"
nodes = { y = 0.5, r = [0.0, 0.5] }
velocity_y = { type = "ramp", value = -0.01, duration = 0.1 }

[[loads]]
name = "side"
nodes = { r = 0.5 }
component = "r"
traction = -1000.0

[solver]
courant_number = 0.5
gravity = [0.0, -9.81]

[[phases]]
name = "settle"
duration = 0.2
local_damping = 0.7
k0 = [{ body = "block", surface = 0.5, k0 = 0.5 }]

[output]
snapshot_interval = 0.05
)";

/// The text with the first occurrence of `from` (which must exist) replaced by `to`.
std::string edited_text(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) {
    throw std::logic_error("test edit does not apply: " + from);
  }
  return text.replace(at, from.size(), to);
}

std::string edited(const std::string& from, const std::string& to) {
  return edited_text(valid_case, from, to);
}

int line_of(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  return at == std::string::npos
             ? -1
             : 1 + static_cast<int>(
                       std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

struct BadInput {
  const char* what;
  std::string text;
  std::string expected;  // a fragment of the message: key and reason
  std::string line_text; // the line the message must point at ("" when it names no line)
};

std::vector<BadInput> bad_inputs() {
  return {
      {"TOML syntax error", edited("title = \"reader test\"", "title = \"reader test"),
       "not valid TOML", ""},
      {"misspelt top-level key", edited("title =", "titel ="), "titel: unknown key", "titel ="},
      // A misspelt required key is named as the typo, on its own line, not as the key it missed.
      {"misspelt table array", edited("[[phases]]", "[[phase]]"),
       "phase: unknown key; did you mean 'phases'?", "[[phase]]"},
      {"unknown geometry", edited("geometry = \"axisymmetric\"", "geometry = \"3d\""),
       "geometry: must be \"axisymmetric\" or \"plane_strain\"", "geometry = \"3d\""},
      {"no grid",
       edited("[grid]\nr = [{ start = 0.0, end = 1.0, cells = 8 }]\ny = [{ start = 0.0, end = 1.0, "
              "cells = 8 }]\n",
              ""),
       "grid: missing (required)", ""},
      // y is one edit from r, but a key of [grid]: the missing r is the error.
      {"grid without r", edited("r = [{ start = 0.0, end = 1.0, cells = 8 }]\n", ""),
       "grid.r: missing (required): at least one zone", "[grid]"},
      {"a NUL in the output directory",
       edited("snapshot_interval = 0.05", "snapshot_interval = 0.05\ndirectory = \"out\\u0000x\""),
       "output.directory: a path cannot hold a NUL character (\\u0000)", "directory = "},
      {"zero cells", edited("end = 1.0, cells = 8 }]\ny", "end = 1.0, cells = 0 }]\ny"),
       "grid.r[0].cells: must lie between 1 and 100000, got 0", "r = [{"},
      {"cells as a string", edited("end = 1.0, cells = 8 }]\ny", "end = 1.0, cells = \"8\" }]\ny"),
       "grid.r[0].cells: expected an integer, got a string", "r = [{"},
      {"zone end before start",
       edited("r = [{ start = 0.0, end = 1.0", "r = [{ start = 0.0, end = -1.0"),
       "grid.r[0].end: must be greater than start", "r = [{"},
      {"zones with a gap",
       edited("r = [{ start = 0.0, end = 1.0, cells = 8 }]",
              "r = [{ start = 0.0, end = 0.5, cells = 4 }, { start = 0.6, end = 1.0, cells = 4 }]"),
       "grid.r: zone 1: starts at 0.6", "r = [{"},
      {"axisymmetric grid behind the axis", edited("r = [{ start = 0.0,", "r = [{ start = -0.5,"),
       "grid.r: starts at r = -0.5 < 0", ""},
      {"unknown material type", edited("type = \"linear_elastic\"", "type = \"elastic\""),
       "materials.soil.type: must be \"linear_elastic\", \"mohr_coulomb\", \"hardening_soil\" or "
       "\"hypoplastic\", "
       "got \"elastic\"",
       "type = \"elastic\""},
      {"velocity not finite",
       edited("[[bodies]]\nname = \"block\"",
              "[[bodies]]\nvelocity = [nan, 0, 0]\nname = \"block\""),
       "bodies[0].velocity: must hold finite numbers, got nan at index 0", "velocity = [nan"},
      // More memory than any machine has: refused at the key that drives it, before allocating.
      {"grid past the memory budget",
       edited("r = [{ start = 0.0, end = 1.0, cells = 8 }]\ny = [{ start = 0.0, end = 1.0, cells = "
              "8 }]",
              "r = [{ start = 0.0, end = 1.0, cells = 100000 }]\ny = [{ start = 0.0, end = 1.0, "
              "cells = 100000 }]"),
       "grid.r: the case needs about", "r = [{"},
      {"block size past int's range",
       edited("courant_number = 0.5", "courant_number = 0.5\nblock_cells = 4294967304"),
       "solver.block_cells: must lie between 1 and 16, got 4294967304", "block_cells ="},
      {"XPIC order out of range",
       edited("courant_number = 0.5", "courant_number = 0.5\nxpic_order = 17"),
       "solver.xpic_order: must lie between 0 and 16, got 17", "xpic_order ="},
      {"XPIC with a FLIP/PIC blend",
       edited("courant_number = 0.5", "courant_number = 0.5\nxpic_order = 3\nflip_fraction = 0.98"),
       "solver.xpic_order: XPIC(3) replaces the FLIP/PIC blend", "xpic_order ="},
      {"a phase's blend under the solver's XPIC",
       edited_text(edited("courant_number = 0.5", "courant_number = 0.5\nxpic_order = 3"),
                   "local_damping = 0.7\n", "local_damping = 0.7\nflip_fraction = 0.98\n"),
       "phases[0].flip_fraction: the phase would run XPIC(3) with flip_fraction 0.98",
       "flip_fraction ="},
      {"affine motion with three components",
       edited("[[phases]]", "[affine_motion]\nvelocity_gradient = [0.1, 0.0, 0.0]\n\n[[phases]]"),
       "affine_motion.velocity_gradient: expected 4 numbers, got 3", "velocity_gradient ="},
      {"affine motion without its gradient", edited("[[phases]]", "[affine_motion]\n\n[[phases]]"),
       "affine_motion.velocity_gradient: missing", ""},
      {"unknown shape functions",
       edited("courant_number = 0.5", "courant_number = 0.5\nshape_functions = \"cubic\""),
       "solver.shape_functions: must be \"linear\" or \"gimp\", got \"cubic\"",
       "shape_functions ="},
      {"GIMP with blocks of 2 cells",
       edited("courant_number = 0.5",
              "courant_number = 0.5\nshape_functions = \"gimp\"\nblock_cells = 2"),
       "solver.block_cells: must be at least 3 with GIMP shape functions", "block_cells = 2"},
      {"GIMP on a grid one cell high",
       edited_text(edited("y = [{ start = 0.0, end = 1.0, cells = 8 }]\n",
                          "y = [{ start = 0.0, end = 1.0, cells = 1 }]\n"),
                   "courant_number = 0.5", "courant_number = 0.5\nshape_functions = \"gimp\""),
       "solver.shape_functions: GIMP needs at least 2 cells along r and along y",
       "shape_functions ="},
      {"negative Young's modulus", edited("young_modulus = 1e7", "young_modulus = -1e7"),
       "materials.soil.young_modulus: linear_elastic: young_modulus must be > 0 Pa",
       "young_modulus = -1e7"},
      {"Poisson ratio 0.5", edited("poisson_ratio = 0.3", "poisson_ratio = 0.5"),
       "materials.soil.poisson_ratio: linear_elastic: poisson_ratio must lie in (-1, 0.5)",
       "poisson_ratio = 0.5"},
      {"missing density", edited("density = 1800.0\n", ""),
       "materials.soil.density: missing (required)", ""},
      {"misspelt material parameter", edited("young_modulus = 1e7", "youngs_modulus = 1e7"),
       "materials.soil.youngs_modulus: unknown key; did you mean 'young_modulus'?",
       "youngs_modulus = 1e7"},
      {"missing material parameter", edited("young_modulus = 1e7\n", ""),
       "materials.soil.young_modulus: missing (required): Young's modulus E, in Pa", ""},
      {"body of an undefined material", edited("material = \"soil\"", "material = \"sand\""),
       "bodies[0].material: no material named 'sand'", "material = \"sand\""},
      {"body outside the grid",
       edited("region = { r = [0.0, 0.5], y = [0.0, 0.5] }",
              "region = { r = [0.0, 1.5], y = [0.0, 0.5] }"),
       "bodies[0].region: lies outside the grid", "region = {"},
      {"region given backwards", edited("region = { r = [0.0, 0.5]", "region = { r = [0.5, 0.0]"),
       "bodies[0].region.r: must be [r_min, r_max] with r_max > r_min", "region = {"},
      {"zero particles per cell", edited("particles_per_cell = 2", "particles_per_cell = 0"),
       "bodies[0].particles_per_cell: must lie between 1 and 8", "particles_per_cell = 0"},
      {"two bodies of one name",
       edited("[boundaries]", "[[bodies]]\nname = \"block\"\nmaterial = \"soil\"\nregion = { r = "
                              "[0.5, 1.0], y = [0.0, 0.5] }\n\n[boundaries]"),
       "bodies[1].name: a body named 'block' already exists",
       "name = \"block\"\nmaterial = \"soil\"\nregion = { r = [0.5"},
      {"a phase named \"\"", edited("name = \"settle\"", "name = \"\""),
       "phases[0].name: a phase needs a name (\"\" names none)", "name = \"\""},
      {"a condition on the axis",
       edited("y_min = \"fixed\"", "y_min = \"fixed\"\nr_min = \"roller\""),
       "boundaries.r_min: the grid starts on the axis", "r_min = \"roller\""},
      {"absorbing face not a list",
       edited("y_min = \"fixed\"", "y_min = \"fixed\"\nabsorbing = \"y_min\""),
       "boundaries.absorbing: must be a list of grid faces", "absorbing = \"y_min\""},
      {"absorbing face unknown",
       edited("y_min = \"fixed\"", "y_min = \"fixed\"\nabsorbing = [\"bottom\"]"),
       "boundaries.absorbing: must be a list of grid faces, each \"r_min\", \"r_max\", \"y_min\" "
       "or \"y_max\" once, got \"bottom\"",
       "absorbing = [\"bottom\"]"},
      {"absorbing face twice",
       edited("y_min = \"fixed\"",
              "y_min = \"fixed\"\nabsorbing = [\"y_min\", \"r_max\", \"y_min\"]"),
       "boundaries.absorbing: lists \"y_min\" twice", "absorbing = [\"y_min\""},
      {"absorbing axis", edited("y_min = \"fixed\"", "y_min = \"fixed\"\nabsorbing = [\"r_min\"]"),
       "boundaries.absorbing: \"r_min\" is the axis here", "absorbing = [\"r_min\"]"},
      {"absorbing phase unknown",
       edited("y_min = \"fixed\"",
              "y_min = \"fixed\"\nabsorbing = [\"y_min\"]\nabsorbing_phase = \"shake\""),
       "boundaries.absorbing_phase: no phase named 'shake' in [[phases]]", "absorbing_phase ="},
      {"absorbing phase without faces",
       edited("y_min = \"fixed\"", "y_min = \"fixed\"\nabsorbing_phase = \"settle\""),
       "boundaries.absorbing_phase: given without `absorbing`", "absorbing_phase ="},
      {"unknown face condition", edited("y_min = \"fixed\"", "y_min = \"clamped\""),
       "boundaries.y_min: must be \"free\", \"roller\" or \"fixed\"", "y_min = \"clamped\""},
      {"prescribed range beside the grid",
       edited("nodes = { y = 0.5, r = [0.0, 0.5] }", "nodes = { y = 0.5, r = [5.0, 6.0] }"),
       "prescribed[0].nodes.r: the range [5, 6] holds no node of the grid (r from 0 to 1)",
       "nodes = { y = 0.5, r = [5.0"},
      {"load off the grid lines", edited("nodes = { r = 0.5 }", "nodes = { r = 0.55 }"),
       "loads[0].nodes.r: 0.55 is not on a grid line of r", "nodes = { r = 0.55 }"},
      {"unknown load component", edited("component = \"r\"", "component = \"z\""),
       "loads[0].component: must be \"r\", \"y\" or \"theta\"", "component = \"z\""},
      {"unknown time function", edited("{ type = \"ramp\", value", "{ type = \"sine\", value"),
       "prescribed[0].velocity_y.type: must be \"constant\", \"ramp\", \"table\", \"harmonic\" or "
       "\"pulse_train\", got \"sine\"",
       "velocity_y ="},
      {"ramp of negative duration", edited("duration = 0.1 }", "duration = -0.1 }"),
       "prescribed[0].velocity_y.duration: must be > 0 s, got -0.1", "velocity_y ="},
      {"prescribed motion that prescribes nothing",
       edited("velocity_y = { type = \"ramp\", value = -0.01, duration = 0.1 }\n", ""),
       "prescribed[0].name: prescribes nothing", "name = \"top\""},
      {"courant number zero", edited("courant_number = 0.5", "courant_number = 0.0"),
       "solver.courant_number: must lie in (0, 2], got 0", "courant_number = 0.0"},
      {"gravity with three components",
       edited("gravity = [0.0, -9.81]", "gravity = [0.0, -9.81, 0.0]"),
       "solver.gravity: expected 2 numbers, got 3", "gravity = ["},
      {"no phases",
       edited("[[phases]]\nname = \"settle\"\nduration = 0.2\nlocal_damping = 0.7\nk0 = [{ body = "
              "\"block\", surface = 0.5, k0 = 0.5 }]\n",
              ""),
       "phases: missing (required)", ""},
      {"phase of zero duration", edited("duration = 0.2", "duration = 0.0"),
       "phases[0].duration: must be > 0 s, got 0", "duration = 0.0"},
      {"damping of 1.5", edited("local_damping = 0.7", "local_damping = 1.5"),
       "phases[0].local_damping: must lie in [0, 1)", "local_damping = 1.5"},
      {"K0 of an unknown body", edited("{ body = \"block\"", "{ body = \"ground\""),
       "phases[0].k0[0].body: no body named 'ground'", "k0 = [{"},
      {"motion in an unknown phase",
       edited("velocity_y = {", "phase = \"install\"\nvelocity_y = {"),
       "prescribed[0].phase: no phase named 'install'", "phase = \"install\""},
      {"negative surcharge",
       edited("surface = 0.5, k0 = 0.5 }", "surface = 0.5, k0 = 0.5, surcharge = -1e3 }"),
       "phases[0].k0[0].surcharge: must be >= 0 Pa, got -1000", "k0 = [{"},
      {"negative snapshot interval",
       edited("snapshot_interval = 0.05", "snapshot_interval = -0.05"),
       "output.snapshot_interval: must be >= 0 s, got -0.05", "snapshot_interval = -0.05"},
      {"theta velocity in plane strain",
       edited("geometry = \"axisymmetric\"\n", "geometry = \"plane_strain\"\n")
           .insert(valid_case.find("velocity_y = {"), "velocity_theta = 0.1\n"),
       "prescribed[0].velocity_theta: plane strain has no theta velocity", "velocity_theta = 0.1"},
      {"self-intersecting polygon",
       edited("region = { r = [0.0, 0.5], y = [0.0, 0.5] }",
              "region = { polygon = [[0.0, 0.0], [0.5, 0.5], [0.5, 0.0], [0.0, 0.5]] }"),
       "bodies[0].region.polygon: crosses itself: edges 0 and 2 meet", "region = {"},
      {"polygon of two vertices",
       edited("region = { r = [0.0, 0.5], y = [0.0, 0.5] }",
              "region = { polygon = [[0.0, 0.0], [0.5, 0.5]] }"),
       "bodies[0].region.polygon: needs at least 3 vertices, got 2", "region = {"},
      {"polygon of zero area",
       edited("region = { r = [0.0, 0.5], y = [0.0, 0.5] }",
              "region = { polygon = [[0.0, 0.0], [0.25, 0.25], [0.5, 0.5]] }"),
       "bodies[0].region.polygon: encloses no area", "region = {"},
      {"polygon vertex off the grid",
       edited("region = { r = [0.0, 0.5], y = [0.0, 0.5] }",
              "region = { polygon = [[0.0, 0.0], [0.5, 0.0], [0.5, 1.5]] }"),
       "bodies[0].region.polygon: vertex 2 (0.5, 1.5) lies outside the grid", "region = {"},
      {"polygon vertex not a pair",
       edited("region = { r = [0.0, 0.5], y = [0.0, 0.5] }",
              "region = { polygon = [[0.0, 0.0], [0.5, 0.0, 1.0], [0.5, 0.5]] }"),
       "bodies[0].region.polygon: expected [[r0, y0], [r1, y1], ...]: vertex 1 is not a pair",
       "region = {"},
      {"polygon behind the axis",
       edited("region = { r = [0.0, 0.5], y = [0.0, 0.5] }",
              "region = { polygon = [[-0.1, 0.0], [0.5, 0.0], [0.5, 0.5]] }"),
       "bodies[0].region.polygon: vertex 0 (-0.1, 0) lies behind the axis", "region = {"},
      {"circle of zero radius",
       edited("region = { r = [0.0, 0.5], y = [0.0, 0.5] }",
              "region = { circle = { centre = [0.3, 0.3], radius = 0.0 } }"),
       "bodies[0].region.circle.radius: must be > 0 m, got 0", "region = {"},
      {"circle reaching behind the axis",
       edited("region = { r = [0.0, 0.5], y = [0.0, 0.5] }",
              "region = { circle = { centre = [0.1, 0.3], radius = 0.2 } }"),
       "bodies[0].region.circle.radius: reaches behind the axis", "region = {"},
      {"circle off the grid",
       edited("region = { r = [0.0, 0.5], y = [0.0, 0.5] }",
              "region = { circle = { centre = [0.5, 0.9], radius = 0.2 } }"),
       "bodies[0].region.circle: reaches outside the grid", "region = {"},
      {"two shapes in one region",
       edited("region = { r = [0.0, 0.5], y = [0.0, 0.5] }",
              "region = { r = [0.0, 0.5], y = [0.0, 0.5], circle = { centre = [0.3, 0.3], "
              "radius = 0.1 } }"),
       "bodies[0].region.circle: give one shape, not several", "region = {"},
      {"misspelt shape",
       edited("region = { r = [0.0, 0.5], y = [0.0, 0.5] }",
              "region = { polygn = [[0.0, 0.0], [0.5, 0.0], [0.5, 0.5]] }"),
       "bodies[0].region.polygn: unknown key", "region = {"},
      {"region too small for its cells",
       edited("region = { r = [0.0, 0.5], y = [0.0, 0.5] }",
              "region = { circle = { centre = [0.0625, 0.0625], radius = 0.02 } }"),
       "bodies[0].region: body 'block' gets no particle", "region = {"},
      {"table times not increasing",
       edited("traction = -1000.0",
              "traction = { type = \"table\", points = [[0.0, 0.0], [0.0, 1.0]] }"),
       "loads[0].traction.points: table times must be strictly increasing", "traction = {"},
      {"table point without its value",
       edited("traction = -1000.0",
              "traction = { type = \"table\", points = [[0.0, 0.0], [1.0]] }"),
       "loads[0].traction.points: expected [[t0, value0], [t1, value1], ...] with numbers",
       "traction = {"},
      {"table point not a number",
       edited("traction = -1000.0",
              "traction = { type = \"table\", points = [[0.0, 0.0], [1.0, \"x\"]] }"),
       "loads[0].traction.points: expected [[t0, value0], [t1, value1], ...] with numbers",
       "traction = {"},
  };
}

// A soil block and a rigid pile in contact, for the contact and rigid-body keys.
const std::string contact_case = R"(title = "contact reader test"

[grid]
r = [{ start = 0.0, end = 1.0, cells = 10 }]
y = [{ start = 0.0, end = 1.0, cells = 10 }]

[materials.soil]
type = "linear_elastic"
young_modulus = 1e7
poisson_ratio = 0.3
density = 1800.0

[[bodies]]
name = "soil"
material = "soil"
region = { r = [0.0, 0.4], y = [0.0, 1.0] }

[[bodies]]
name = "pile"
material = "soil"
region = { r = [0.4, 0.6], y = [0.5, 1.0] }

[bodies.rigid]
mass = 650.0
angular_velocity = { type = "harmonic", amplitude = 0.1, frequency = 60.0 }
force_y = -8000.0
phase = "drive"

[[contact]]
structure = "pile"
friction = 0.4
adhesion = 0.0
surfaces = { bottom = "tip", left = "inner_shaft", right = "outer_shaft" }

[[phases]]
name = "settle"
duration = 0.1

[[phases]]
name = "drive"
duration = 0.1
)";

std::string contact_edited(const std::string& from, const std::string& to) {
  return edited_text(contact_case, from, to);
}

std::vector<BadInput> bad_contact_inputs() {
  return {
      {"contact with an unknown body",
       contact_edited("structure = \"pile\"", "structure = \"pipe\""),
       "contact[0].structure: no body named 'pipe'", "structure = "},
      {"negative friction", contact_edited("friction = 0.4", "friction = -0.4"),
       "contact[0].friction: must be >= 0", "friction = "},
      {"negative adhesion", contact_edited("adhesion = 0.0", "adhesion = -5.0"),
       "contact[0].adhesion: must be >= 0", "adhesion = "},
      {"unknown normals",
       contact_edited("adhesion = 0.0", "adhesion = 0.0\nnormals = \"geometric\""),
       "contact[0].normals: must be \"outline\" or \"mass_gradient\"", "normals = "},
      {"misspelt edge", contact_edited("bottom = \"tip\"", "botom = \"tip\""),
       "contact[0].surfaces.botom: unknown key", "surfaces = "},
      {"surface name with an outline",
       contact_edited("adhesion = 0.0", "adhesion = 0.0\nsurface = \"all\""),
       "contact[0].surface: an outline has four edges", "surface = \"all\""},
      {"two contact entries for one structure",
       contact_case + "\n[[contact]]\nstructure = \"pile\"\n", "already has a [[contact]] entry",
       ""},
      {"rigid body without contact",
       contact_edited(
           "[[contact]]\nstructure = \"pile\"\nfriction = 0.4\nadhesion = 0.0\n"
           "surfaces = { bottom = \"tip\", left = \"inner_shaft\", right = \"outer_shaft\" }\n",
           ""),
       "body 'pile' is rigid but has no [[contact]] entry", ""},
      {"both velocity and force on one DOF",
       contact_edited("force_y = -8000.0", "force_y = -8000.0\nvelocity_y = -0.02"),
       "bodies[1].rigid.force_y: give either velocity_y or force_y, not both", ""},
      {"radial drive in axisymmetry", contact_edited("force_y = -8000.0", "force_r = 1.0"),
       "bodies[1].rigid.force_r: an axisymmetric rigid body has no radial motion", "force_r"},
      {"negative rigid mass", contact_edited("mass = 650.0", "mass = -650.0"),
       "bodies[1].rigid.mass: must be > 0 kg/rad, got -650", "mass = -650.0"},
      {"drive phase unknown", contact_edited("phase = \"drive\"", "phase = \"install\""),
       "bodies[1].rigid.phase: no phase named 'install'", "phase = \"install\""},
      // Each mode's moment of inertia under its own key: the other mode's is named, not unknown.
      {"plane-strain inertia on an axisymmetric body",
       contact_edited("mass = 650.0", "mass = 650.0\ninertia = 3.0"),
       "bodies[1].rigid.inertia: plane-strain cases only: an axisymmetric body turns about the "
       "axis",
       "inertia = 3.0"},
      {"misspelt rigid key", contact_edited("mass = 650.0", "mas = 650.0"),
       "bodies[1].rigid.mas: unknown key", "mas = 650.0"},
      {"polygon structure with a rectangle's surfaces",
       contact_edited("region = { r = [0.4, 0.6], y = [0.5, 1.0] }",
                      "region = { polygon = [[0.4, 0.5], [0.6, 0.6], [0.6, 1.0], [0.4, 1.0]] }"),
       "contact[0].surfaces: expected an array of 4 surface names, one per edge of body 'pile'",
       "surfaces = "},
      {"polygon structure with too few surface names",
       edited_text(contact_edited("region = { r = [0.4, 0.6], y = [0.5, 1.0] }",
                                  "region = { polygon = [[0.4, 0.5], [0.6, 0.6], [0.6, 1.0], "
                                  "[0.4, 1.0]] }"),
                   "surfaces = { bottom = \"tip\", left = \"inner_shaft\", right = "
                   "\"outer_shaft\" }",
                   "surfaces = [\"tip\", \"outer_shaft\", \"\"]"),
       "contact[0].surfaces: expected an array of 4 surface names, one per edge of body 'pile' "
       "(edge k from vertex k to the next, the last closing the polygon; \"\" for an edge that is "
       "no contact surface), got 3 names",
       "surfaces = "},
      {"concave polygon structure with outline normals",
       contact_edited("region = { r = [0.4, 0.6], y = [0.5, 1.0] }",
                      "region = { polygon = [[0.4, 0.5], [0.6, 0.5], [0.5, 0.7], [0.6, 1.0], "
                      "[0.4, 1.0]] }"),
       "contact[0].structure: body 'pile' is a polygon that is not convex (it turns inwards at "
       "vertex 2)",
       "structure = "},
      {"circle structure with edge names",
       contact_edited("region = { r = [0.4, 0.6], y = [0.5, 1.0] }",
                      "region = { circle = { centre = [0.5, 0.75], radius = 0.1 } }"),
       "contact[0].surfaces: body 'pile' is a circle, outlined as one surface", "surfaces = "},
      {"CPT cone without a plan area",
       contact_case + "\n[output.cpt]\ncone = \"outer_shaft\"\nsleeve = \"inner_shaft\"\n",
       "output.cpt.cone: 'outer_shaft' is no surface of 'pile' with a plan area", "cone = "},
      {"CPT sleeve that is no surface",
       contact_case + "\n[output.cpt]\ncone = \"tip\"\nsleeve = \"sleeve\"\n",
       "output.cpt.sleeve: 'sleeve' is no surface of 'pile' with a side area", "sleeve = "},
      {"CPT body that is soil", contact_case + "\n[output.cpt]\nbody = \"soil\"\ncone = \"tip\"\n",
       "output.cpt.body: must name the contact structure that is the cone, with outline normals "
       "(got 'soil')",
       "body = \"soil\""},
      {"CPT cone named \"\", the name of an edge that is no surface",
       contact_case + "\n[output.cpt]\ncone = \"\"\nsleeve = \"outer_shaft\"\n",
       "output.cpt.cone: names no surface (\"\" marks an edge that is no contact surface)",
       "cone = "},
      {"CPT sleeve named \"\"", contact_case + "\n[output.cpt]\ncone = \"tip\"\nsleeve = \"\"\n",
       "output.cpt.sleeve: names no surface", "sleeve = "},
      {"CPT cone and sleeve one surface",
       contact_case + "\n[output.cpt]\ncone = \"tip\"\nsleeve = \"tip\"\n",
       "output.cpt.sleeve: must be another surface than the cone's ('tip')", "sleeve = "},
      {"misspelt CPT key", contact_case + "\n[output.cpt]\ncnoe = \"tip\"\n",
       "output.cpt.cnoe: unknown key", "cnoe = "},
      // It was refused as an unknown key of [output], whose list of keys holds it.
      {"penetration body without snapshot penetrations",
       contact_case + "\n[output]\npenetration_body = \"pile\"\n",
       "output.penetration_body: given without snapshot_penetrations", "penetration_body = "},
      {"prescribed motion on a rigid body",
       contact_case + "\n[[prescribed]]\nname = \"head\"\nbody = \"pile\"\nnodes = { y = 1.0 }\n"
                      "velocity_y = -0.01\n",
       "prescribed[0].body: 'pile' is rigid", "body = \"pile\"\nnodes"},
  };
}

void expect_rejected(const std::vector<BadInput>& table) {
  for (const BadInput& bad : table) {
    std::string message = "no error";
    try {
      read_case_text(bad.text, "case.toml");
    } catch (const CaseError& e) {
      message = e.what();
    }
    EXPECT_EQ(message.rfind("case.toml", 0), 0u) << bad.what << ": " << message;
    EXPECT_NE(message.find(bad.expected), std::string::npos)
        << bad.what << ": expected \"" << bad.expected << "\" in: " << message;
    if (!bad.line_text.empty()) {
      const int line = line_of(bad.text, bad.line_text);
      ASSERT_GT(line, 0) << bad.what;
      EXPECT_NE(message.find("case.toml:" + std::to_string(line) + ":"), std::string::npos)
          << bad.what << ": expected line " << line << " in: " << message;
    }
  }
}

std::string monopile_case() {
  return read_text(source / "tests/data/gdp_quick_flat.toml");
}

std::string monopile_edited(const std::string& from, const std::string& to) {
  return edited_text(monopile_case(), from, to);
}

/// The monopile case with a load test after its installation: `stop` and `drive` are the
/// load test phase's.
std::string with_load_test(const std::string& stop, const std::string& drive) {
  return monopile_edited("[output]",
                         "[[phases]]\nname = \"load_test\"\nduration = 5.0\nstop_at = " + stop +
                             "\ndrive = " + drive + "\n\n[output]");
}

std::vector<BadInput> bad_monopile_inputs() {
  const std::string push = "{ body = \"pile\", velocity_y = -0.02 }";
  return {
      {"settlement and penetration",
       with_load_test("{ body = \"pile\", settlement = 0.05, penetration = 0.15 }", push),
       "phases[2].stop_at.penetration: give either penetration (the total downward displacement) "
       "or settlement",
       "stop_at = { body = \"pile\", settlement"},
      {"settlement past the band's travel",
       with_load_test("{ body = \"pile\", settlement = 0.1 }", push),
       "phases[2].stop_at.settlement: with the 0.1 m an earlier phase stops at, reaches the "
       "travel of the moving band (0.2 m)",
       "stop_at = { body = \"pile\", settlement = 0.1 }"},
      {"phase drive of no rigid body",
       with_load_test("{ body = \"pile\", settlement = 0.05 }",
                      "{ body = \"soil plug\", velocity_y = -0.02 }"),
       "phases[2].drive.body: no rigid body named 'soil plug'", "drive = { body = \"soil plug\""},
      {"phase drive radial in axisymmetry",
       with_load_test("{ body = \"pile\", settlement = 0.05 }",
                      "{ body = \"pile\", velocity_r = 0.01 }"),
       "phases[2].drive.velocity_r: an axisymmetric rigid body has no radial motion",
       "drive = { body = \"pile\", velocity_r"},
      {"phase drive velocity and force",
       with_load_test("{ body = \"pile\", settlement = 0.05 }",
                      "{ body = \"pile\", velocity_y = -0.02, force_y = -1e3 }"),
       "phases[2].drive.force_y: give either velocity_y or force_y, not both",
       "drive = { body = \"pile\", velocity_y = -0.02, force_y"},
      {"absorbing monopile axis",
       monopile_edited("embedment = 3.0", "embedment = 3.0\nabsorbing = [\"r_min\", \"r_max\"]"),
       "monopile.absorbing: \"r_min\" is the axis here", "absorbing = ["},
      {"misspelt monopile key", monopile_edited("embedment = 3.0", "embedmnt = 3.0"),
       "monopile.embedmnt: unknown key", "embedmnt"},
      {"unknown soil material",
       monopile_edited("soil_material = \"sand\"", "soil_material = \"clay\""),
       "monopile.soil_material: no material named 'clay'", "soil_material"},
      {"missing pile material", monopile_edited("pile_material = \"steel\"\n", ""),
       "monopile.pile_material: missing (required)", ""},
      {"pile wider than the soil", monopile_edited("soil_width = 5.0", "soil_width = 0.3"),
       "monopile.soil_width: must exceed the pile's outer radius", "soil_width"},
      {"tip below the bottom", monopile_edited("embedment = 3.0", "embedment = 9.9"),
       "monopile.embedment: band_below: the moving band reaches the bottom of the soil "
       "(soil_depth - embedment - band_below must leave room for cells below it) (band_below = "
       "0.4, its default)",
       "embedment = 9.9"},
      // A mistyped extent: billions of cells, refused before any node list is built (it took
      // minutes and gigabytes).
      {"soil width of billions of cells",
       monopile_edited("soil_width = 5.0", "soil_width = 4294967304"),
       "monopile.soil_width: the grid could take up to 2.70124e+11 cells", "soil_width"},
      {"monopile cells past the memory budget",
       monopile_edited("fine_cell = ", "fine_cell = 1e-5 #"),
       "monopile.fine_cell: the case needs about", "fine_cell"},
      {"monopile cells past what an axis may hold",
       monopile_edited("fine_cell = ", "fine_cell = 1e-6 #"),
       "monopile.fine_cell: the grid could take up to 1.1e+07 cells of 1e-06 m across 11 m",
       "fine_cell"},
      {"tip below the soil", monopile_edited("embedment = 3.0", "embedment = 12.0"),
       "monopile.embedment: must be less than soil_depth (10 m): the tip would start below the "
       "soil",
       ""},
      {"embedment longer than the pile", monopile_edited("pile_length = 14.0", "pile_length = 2.0"),
       "monopile.embedment: must be less than pile_length", ""},
      {"wall thicker than the radius",
       monopile_edited("wall_thickness = 0.0159", "wall_thickness = 0.5"),
       "monopile.wall_thickness: must be positive and less than the radius", "wall_thickness"},
      {"negative friction", monopile_edited("friction = 0.4", "friction = -0.4"),
       "monopile.friction: must be >= 0", "friction = -0.4"},
      {"no cell across the wall",
       monopile_edited("friction = 0.4", "friction = 0.4\nwall_cells = 0"),
       "monopile.wall_cells: must lie between 1 and 16, got 0", "wall_cells = 0"},
      {"resolved wall whose cells do not fit in the band",
       monopile_edited("friction = 0.4", "friction = 0.4\nwall_cells = 4\nband_below = 0.3"),
       "monopile.wall_cells: the cells growing from the tip's to fine_cell take", ""},
      {"pile mass given",
       monopile_edited("phase = \"installation\"", "phase = \"installation\"\nmass = 650.0"),
       "monopile.drive.mass: the monopile's mass and polar inertia follow from", "mass = 650.0"},
      {"pile polar inertia given",
       monopile_edited("phase = \"installation\"", "phase = \"installation\"\npolar_inertia = 9.0"),
       "monopile.drive.polar_inertia: the monopile's mass and polar inertia follow from",
       "polar_inertia = 9.0"},
      {"grid given as well",
       "[grid]\nr = [{ start = 0.0, end = 5.0, cells = 10 }]\n" + monopile_case(),
       "grid: [monopile] builds the grid", ""},
      {"stop at an unknown body", monopile_edited("body = \"pile\"", "body = \"pipe\""),
       "phases[1].stop_at.body: no rigid body named 'pipe'", "stop_at"},
      {"K0 on an unknown material",
       monopile_edited("{ material = \"sand\"", "{ material = \"silt\""),
       "phases[0].k0[0].material: no body of material 'silt'", "k0 = "},
      {"negative snapshot penetration",
       monopile_edited("snapshot_penetrations = [0.05, 0.1]", "snapshot_penetrations = [-0.05]"),
       "output.snapshot_penetrations: penetrations must be positive", "snapshot_penetrations"},
      {"stop beyond the band's travel", monopile_edited("travel = 0.2", "travel = 0.05"),
       "phases[1].stop_at.penetration: reaches the travel of the moving band (0.05 m): below "
       "that depth the soil is seeded for coarser cells than the band's, and the step that "
       "reaches it carries the band past it; stop short of it or raise [monopile] travel",
       "stop_at"},
      // Equal fails too: the run would stop with the band past its travel in its last step.
      {"stop at the band's whole travel", monopile_edited("travel = 0.2", "travel = 0.1"),
       "phases[1].stop_at.penetration: reaches the travel of the moving band (0.1 m)", "stop_at"},
      {"non-positive travel", monopile_edited("travel = 0.2", "travel = 0.0"),
       "monopile.travel: must be > 0 m, got 0", "travel = 0.0"},
  };
}

TEST(CaseReader, TheMonopileCaseBuildsTheSeedGeometry) {
  const CaseSpec spec = read_case_text(monopile_case(), "case.toml");
  ASSERT_EQ(spec.bodies.size(), 4u);
  EXPECT_EQ(spec.bodies[3].name, "pile");
  ASSERT_TRUE(spec.bodies[3].rigid.has_value());
  // The whole 14 m pile: rho L (r2^2 - r1^2) / 2 per radian.
  EXPECT_NEAR(spec.bodies[3].rigid->mass, 8000.0 * 14.0 * (0.373 * 0.373 - 0.3571 * 0.3571) / 2.0,
              1e-9);
  EXPECT_DOUBLE_EQ(spec.bodies[3].region.bounds().y_min, 7.0); // the tip, 3 m below the surface
  ASSERT_EQ(spec.phases[0].k0.size(), 3u);                     // K0 on the three soil bodies
  ASSERT_TRUE(spec.moving_mesh.has_value());
  EXPECT_DOUBLE_EQ(spec.phases[1].stop_at->penetration, 0.1);
  // A moving mesh takes GIMP unless the case says otherwise (docs/design.md, "Shape functions").
  EXPECT_EQ(spec.solver.shape_functions, ShapeFunctions::gimp);
  // On a fixed grid, for comparison: no moving mesh, and bilinear weights by default.
  const CaseSpec fixed = read_case_text(
      monopile_edited("travel = 0.2", "travel = 0.2\nmoving_mesh = false"), "case.toml");
  EXPECT_FALSE(fixed.moving_mesh.has_value());
  EXPECT_EQ(fixed.solver.shape_functions, ShapeFunctions::linear);
  // Absorbing lateral face and base, switched on when the installation starts.
  EXPECT_TRUE(spec.absorbing.faces.empty());
  const CaseSpec absorbing = read_case_text(
      monopile_edited("travel = 0.2", "travel = 0.2\nabsorbing = [\"r_max\", \"y_min\"]\n"
                                      "absorbing_phase = \"installation\""),
      "case.toml");
  EXPECT_EQ(absorbing.absorbing.faces, (std::vector{GridFace::r_max, GridFace::y_min}));
  EXPECT_EQ(absorbing.absorbing.phase, "installation");
  // A load test after the installation: its own drive and a settlement stop.
  const CaseSpec load_test =
      read_case_text(with_load_test("{ body = \"pile\", settlement = 0.05 }",
                                    "{ body = \"pile\", velocity_y = -0.02 }"),
                     "case.toml");
  ASSERT_EQ(load_test.phases.size(), 3u);
  const PhaseSpec& last = load_test.phases[2];
  ASSERT_TRUE(last.stop_at && last.drive);
  EXPECT_DOUBLE_EQ(last.stop_at->settlement, 0.05);
  EXPECT_DOUBLE_EQ(last.stop_at->penetration, 0.15); // the installation's 0.1 m plus 0.05 m
  EXPECT_EQ(last.drive->body, "pile");
  ASSERT_TRUE(last.drive->drive[RIGID_Y].has_value());
  EXPECT_EQ(last.drive->drive[RIGID_Y]->kind, RigidDrive::Kind::velocity);
  EXPECT_FALSE(last.drive->drive[RIGID_ROTATION].has_value());
}

TEST(CaseReader, RejectsEachBadMonopileInputWithFileLineKeyAndReason) {
  expect_rejected(bad_monopile_inputs());
}

// MPILE_MEMORY_BUDGET_MIB bounds what a case may need below what the machine has (a shared
// machine, or a sanitizer build whose address space cannot be limited): the quick monopile case
// (about 2 MB) reads within 10 MiB and is refused at 1 MiB, at the key that drives it, naming the
// budget; an unreadable value is refused.
TEST(CaseReader, AMemoryBudgetSetForTheProcessBoundsTheCase) {
  const std::string text = monopile_edited("", "");
  struct Budget {
    explicit Budget(const char* mib) { setenv("MPILE_MEMORY_BUDGET_MIB", mib, 1); }
    ~Budget() { unsetenv("MPILE_MEMORY_BUDGET_MIB"); }
    Budget(const Budget&) = delete;
    Budget& operator=(const Budget&) = delete;
  };
  {
    Budget budget("10");
    EXPECT_NO_THROW(read_case_text(text, "case.toml"));
  }
  // A budget that does not parse is refused, naming it (before, it switched the budget off).
  for (const char* junk : {"junk", "2MiB", "0", "-2", "", "inf", "nan"}) {
    Budget budget(junk);
    try {
      read_case_text(text, "case.toml");
      ADD_FAILURE() << "accepted the budget '" << junk << "'";
    } catch (const CaseError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("case.toml: MPILE_MEMORY_BUDGET_MIB = '" +
                                                std::string(junk) + "' is not a memory budget",
                                            0),
                0u)
          << e.what();
    }
  }
  Budget budget("1");
  try {
    read_case_text(text, "case.toml");
    ADD_FAILURE() << "a case past the budget was read";
  } catch (const CaseError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("more than MPILE_MEMORY_BUDGET_MIB's 0.00105 GB"), std::string::npos)
        << message;
  }
}

TEST(CaseReader, TheContactCaseReads) {
  const CaseSpec spec = read_case_text(contact_case, "case.toml");
  ASSERT_EQ(spec.contacts.size(), 1u);
  EXPECT_DOUBLE_EQ(spec.contacts[0].friction, 0.4);
  EXPECT_EQ(spec.contacts[0].surfaces[0], "tip");
  EXPECT_EQ(spec.contacts[0].surfaces[2], ""); // the head is not a contact surface
  ASSERT_TRUE(spec.bodies[1].rigid.has_value());
  EXPECT_DOUBLE_EQ(spec.bodies[1].rigid->mass, 650.0);
  EXPECT_EQ(spec.bodies[1].rigid->drive[RIGID_Y]->kind, RigidDrive::Kind::force);
  EXPECT_EQ(spec.bodies[1].rigid->drive[RIGID_ROTATION]->kind, RigidDrive::Kind::velocity);
}

// Both modes of a vibrator at once: an axial force oscillating about a static weight beside a
// torsional drive, each a harmonic of its own frequency.
TEST(CaseReader, AnAxialHarmonicAboutAStaticWeightReadsBesideATorsionalOne) {
  const CaseSpec spec = read_case_text(
      contact_edited("force_y = -8000.0",
                     "force_y = { type = \"harmonic\", amplitude = 2e4, frequency = 25.0, "
                     "mean = -8e3 }"),
      "case.toml");
  const RigidSpec& rigid = *spec.bodies[1].rigid;
  const TimeFunction& axial = rigid.drive[RIGID_Y]->function;
  EXPECT_NEAR(axial.value(0.01), -8e3 + 2e4, 1e-9); // a quarter period: the weight plus the peak
  EXPECT_NEAR(axial.mean(0.0, 0.2), -8e3, 1e-9);    // five periods: the weight
  EXPECT_NEAR(rigid.drive[RIGID_ROTATION]->function.value(1.0 / 240.0), 0.1, 1e-12);
  // The mean belongs to the harmonic only.
  try {
    read_case_text(contact_edited("force_y = -8000.0",
                                  "force_y = { type = \"constant\", value = 1.0, mean = 2.0 }"),
                   "case.toml");
    ADD_FAILURE() << "a constant with a mean was accepted";
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("mean"), std::string::npos) << e.what();
  }
}

TEST(CaseReader, ACptOutputNamesTheConeAndSleeveSurfaces) {
  const CaseSpec spec = read_case_text(
      contact_case + "\n[output.cpt]\ncone = \"tip\"\nsleeve = \"outer_shaft\"\n", "case.toml");
  ASSERT_TRUE(spec.output.cpt.has_value());
  EXPECT_EQ(spec.output.cpt->body, "pile"); // the only outlined structure
  EXPECT_EQ(spec.output.cpt->cone, "tip");
  EXPECT_EQ(spec.output.cpt->sleeve, "outer_shaft");
}

TEST(CaseReader, APolygonStructureGivenClockwiseKeepsEachEdgeItsSurface) {
  // A pile with a slanted tip, given clockwise from its inner tip corner: the reader stores the
  // polygon counter-clockwise, and each edge must keep the name given for it.
  std::string text = contact_edited("region = { r = [0.4, 0.6], y = [0.5, 1.0] }",
                                    "region = { polygon = [[0.4, 0.5], [0.4, 1.0], [0.6, 1.0], "
                                    "[0.6, 0.6]] }");
  text = edited_text(text,
                     "surfaces = { bottom = \"tip\", left = \"inner_shaft\", right = "
                     "\"outer_shaft\" }",
                     "surfaces = [\"inner_shaft\", \"\", \"outer_shaft\", \"tip\"]");
  const CaseSpec spec = read_case_text(text, "case.toml");
  const Region& region = spec.bodies[1].region;
  ASSERT_EQ(region.shape(), Region::Shape::polygon);
  const std::vector<std::string> given{"inner_shaft", "", "outer_shaft", "tip"};
  const std::vector<Point> given_vertices{{0.4, 0.5}, {0.4, 1.0}, {0.6, 1.0}, {0.6, 0.6}};
  for (std::size_t k = 0; k < 4; ++k) {
    // Stored edge k runs from vertices()[k] to the next; the given edge with those end points
    // must carry the same name.
    const Point& a = region.vertices()[k];
    const Point& b = region.vertices()[(k + 1) % 4];
    std::size_t match = 4;
    for (std::size_t e = 0; e < 4; ++e) {
      const Point& ga = given_vertices[e];
      const Point& gb = given_vertices[(e + 1) % 4];
      if ((ga == a && gb == b) || (ga == b && gb == a)) {
        match = e;
      }
    }
    ASSERT_LT(match, 4u);
    EXPECT_EQ(spec.contacts[0].surfaces[k], given[match]) << "edge " << k;
  }
  // The built outline carries them as surface indices, the names in the order they appear.
  const std::unique_ptr<Scene> scene = build_scene(spec);
  const ContactPair& pair = scene->contacts.at(0);
  ASSERT_TRUE(pair.outline.has_value());
  ASSERT_EQ(pair.outline->vertices.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    const int surface = pair.outline->edge_surface[k];
    EXPECT_EQ(surface < 0 ? std::string() : pair.surfaces[static_cast<std::size_t>(surface)],
              spec.contacts[0].surfaces[k]);
  }
}

TEST(CaseReader, RejectsEachBadContactInputWithFileLineKeyAndReason) {
  expect_rejected(bad_contact_inputs());
}

TEST(CaseReader, APhaseStopsAtThePenetrationOfABodyDeclaredRigidInItsOwnTable) {
  // The phases are read before the [bodies.rigid] tables (a drive names its phase), so a stop
  // criterion or a moving mesh naming such a body must not depend on that order.
  const std::string stopping = contact_edited(
      "name = \"drive\"\nduration = 0.1",
      "name = \"drive\"\nduration = 0.1\nstop_at = { body = \"pile\", penetration = 0.02 }");
  const CaseSpec spec = read_case_text(stopping, "case.toml");
  ASSERT_TRUE(spec.phases[1].stop_at.has_value());
  EXPECT_EQ(spec.phases[1].stop_at->body, "pile");
  EXPECT_DOUBLE_EQ(spec.phases[1].stop_at->penetration, 0.02);
  // With a moving band that travels less than the stop asks, the stop is refused where it is
  // written, as for a [monopile] case.
  const std::string banded =
      stopping + "\n[moving_mesh]\nbody = \"pile\"\nband = [0.3, 0.7]\ntravel = 0.01\n";
  expect_rejected(
      {{"stop beyond the band's travel", banded,
        "phases[1].stop_at.penetration: reaches the travel of the moving band (0.01 m): below "
        "that depth the soil is seeded for coarser cells than the band's, and the step that "
        "reaches it carries the band past it; stop short of it or raise [moving_mesh] travel",
        "stop_at = {"}});
  // Stretch limits must be grid lines outside the band.
  const std::string stretched =
      contact_case + "\n[moving_mesh]\nbody = \"pile\"\nband = [0.3, 0.7]\nstretch = [0.1, 0.7]\n";
  expect_rejected({{"stretch limit on the band", stretched,
                    "moving_mesh.stretch: must be [y_bottom, y_top], both on y grid lines, below "
                    "and above the band",
                    "stretch = "}});
  expect_rejected(
      {{"stretch limit off the grid lines",
        replaced(stretched, "stretch = [0.1, 0.7]", "stretch = [0.1, 0.85]"),
        "moving_mesh.stretch: must be [y_bottom, y_top], both on y grid lines", "stretch = "}});
  EXPECT_NO_THROW(
      read_case_text(replaced(stretched, "stretch = [0.1, 0.7]", "stretch = [0.1, 0.9]"), "c"));
  // A body that is not rigid is still refused.
  expect_rejected({{"stop at a soil body",
                    contact_edited("name = \"drive\"\nduration = 0.1",
                                   "name = \"drive\"\nduration = 0.1\n"
                                   "stop_at = { body = \"soil\", penetration = 0.02 }"),
                    "phases[1].stop_at.body: no rigid body named 'soil'", "stop_at = {"}});
}

TEST(CaseReader, TheValidCaseReads) {
  const CaseSpec spec = read_case_text(valid_case, "case.toml");
  EXPECT_EQ(spec.title, "reader test");
  ASSERT_EQ(spec.bodies.size(), 1u);
  EXPECT_EQ(spec.bodies[0].particles_per_direction, 2);
  EXPECT_DOUBLE_EQ(spec.solver.gravity[1], -9.81);
  EXPECT_DOUBLE_EQ(spec.phases.at(0).local_damping, 0.7);
  ASSERT_EQ(spec.motions.size(), 1u);
  EXPECT_TRUE(spec.motions[0].velocity[1].has_value());
  EXPECT_FALSE(spec.motions[0].velocity[0].has_value());
}

TEST(CaseReader, RejectsEachBadInputWithFileLineKeyAndReason) {
  const auto table = bad_inputs();
  ASSERT_GE(table.size(), 25u);
  expect_rejected(table);
}

// A fixed monitor may name the material it reads, so that its point can lie where that soil
// arrives later; the name must be a deformable body's material, and a followed monitor reads its
// particle's.
TEST(CaseReader, AMonitorsMaterialIsASoilsAndOnlyAFixedMonitorNamesIt) {
  const std::string monitor = "[[output.monitor]]\nname = \"probe\"\nposition = [0.1, 0.9]\n";
  expect_rejected({
      {"a followed monitor with a material",
       valid_case + monitor + "material = \"soil\" # the probe's\n",
       "output.monitor[0].material: names the material of a fixed monitor (fixed = true)",
       "material = \"soil\" # the probe's"},
      {"a material no body is made of",
       valid_case + monitor + "fixed = true\nmaterial = \"steel\"\n" +
           "[materials.steel]\ntype = \"linear_elastic\"\nyoung_modulus = 2e11\n"
           "poisson_ratio = 0.3\ndensity = 7850.0\n",
       "output.monitor[0].material: no body that is not rigid is made of a material named 'steel'",
       "material = \"steel\""},
      {"a material named \"\"", valid_case + monitor + "fixed = true\nmaterial = \"\"\n",
       "output.monitor[0].material: names no material", "material = \"\""},
  });
  const CaseSpec spec =
      read_case_text(valid_case + monitor + "fixed = true\nmaterial = \"soil\"\n", "case.toml");
  ASSERT_EQ(spec.output.monitors.size(), 1u);
  EXPECT_EQ(spec.output.monitors[0].material, "soil");
}

TEST(CaseReader, NamesThatBecomeOneHistoryGroupAreRefusedWhereTheLaterIsWritten) {
  // "top cap" and "top_cap" both became /boundaries/top_cap in history.h5, their rows interleaved.
  const std::string two_motions =
      edited("[[prescribed]]\nname = \"top\"",
             "[[prescribed]]\nname = \"top cap\"\nnodes = { y = 0.5, r = [0.0, 0.25] }\n"
             "velocity_y = -0.01\n\n[[prescribed]]\nname = \"top_cap\"");
  const std::string first = std::to_string(line_of(two_motions, "name = \"top cap\""));
  std::string bodies = edited_text(contact_case, "name = \"soil\"", "name = \"pile-\"");
  bodies = edited_text(bodies, "name = \"pile\"", "name = \"pile_\"");
  bodies = edited_text(bodies, "structure = \"pile\"", "structure = \"pile_\"");
  const std::string surfaces = std::to_string(line_of(contact_case, "surfaces = {"));
  expect_rejected({
      {"two motions, one group", two_motions,
       "prescribed[1].name: 'top_cap' and 'top cap' (case.toml:" + first +
           ") are both written to /boundaries/top_cap in the history: give this one another name",
       "name = \"top_cap\""},
      {"a motion named like a constrained face", edited("name = \"top\"", "name = \"y min\""),
       "prescribed[0].name: 'y min' and 'y_min' (the condition of that face in [boundaries]) are "
       "both written to /boundaries/y_min",
       "name = \"y min\""},
      {"a motion named like the axis", edited("name = \"top\"", "name = \"axis\""),
       "prescribed[0].name: 'axis' and 'axis' (the axis, held by the grid starting on it) are "
       "both written to /boundaries/axis",
       "name = \"axis\""},
      {"two bodies, one group", bodies,
       "bodies[1].name: 'pile_' and 'pile-' (case.toml:" +
           std::to_string(line_of(bodies, "name = \"pile-\"")) +
           ") are both written to /bodies/pile_ in the history",
       "name = \"pile_\""},
      {"two surfaces, one group",
       contact_edited("left = \"inner_shaft\"", "left = \"outer shaft\""),
       "contact[0].surfaces: 'outer shaft' and 'outer_shaft' (case.toml:" + surfaces +
           ") are both written to /reactions/pile/outer_shaft in the history",
       "surfaces = {"},
      {"a monitor's name is its group as written",
       valid_case + "[[output.monitor]]\nname = \"top cap\"\nposition = [0.1, 0.1]\n",
       "output.monitor[0].name: use letters, digits and underscores", "name = \"top cap\""},
  });
  // Edges given one name are one surface.
  EXPECT_NO_THROW(read_case_text(contact_edited("left = \"inner_shaft\"", "left = \"outer_shaft\""),
                                 "case.toml"));
}

TEST(CaseReader, OverlappingBodiesAreRefusedWhereTheLaterIsWritten) {
  // A second body whose region covers part of the first would seed particles twice there.
  const std::string text =
      edited("region = { r = [0.0, 0.5], y = [0.0, 0.5] }",
             "region = { r = [0.0, 0.5], y = [0.0, 0.5] }\n\n[[bodies]]\nname = \"cap\"\n"
             "material = \"soil\"\nregion = { r = [0.25, 0.5], y = [0.25, 0.75] }");
  const CaseSpec spec = read_case_text(text, "case.toml");
  try {
    build_scene(spec);
    FAIL() << "overlapping bodies were accepted";
  } catch (const CaseError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("case.toml:", 0), 0u) << message;
    EXPECT_NE(message.find(": bodies[1].region: overlaps body 'block' (both seed a particle at "),
              std::string::npos)
        << message;
    // The line is that of the second body's region.
    const auto line =
        std::count(text.begin(),
                   text.begin() + static_cast<long>(text.find("region = { r = [0.25")), '\n') +
        1;
    EXPECT_EQ(message.rfind("case.toml:" + std::to_string(line) + ":", 0), 0u) << message;
  }
  // Touching regions share no particle position: accepted.
  const CaseSpec touching = read_case_text(
      edited("region = { r = [0.0, 0.5], y = [0.0, 0.5] }",
             "region = { r = [0.0, 0.5], y = [0.0, 0.5] }\n\n[[bodies]]\nname = \"cap\"\n"
             "material = \"soil\"\nregion = { r = [0.0, 0.5], y = [0.5, 0.75] }"),
      "case.toml");
  EXPECT_NO_THROW(build_scene(touching));
}

TEST(CaseReader, ARunThatWouldStepForEverOrNotAtAllIsRefusedBeforeAnythingIsWritten) {
  // Young's modulus 1e308 makes the step 1e-154 s (the run would never end); 1e-300 makes it
  // longer than the whole run (it ended "complete" in 0 steps); a density of 1e-300 is the first
  // case again. Each is refused by check and run with exit 2, and run writes nothing.
  const auto directory = std::filesystem::temp_directory_path() / "mpile_implausible_test";
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  // {text replaced, replacement, reason, the value as the message prints it}
  const std::vector<std::array<std::string, 4>> cases = {
      {"young_modulus = 1e7", "young_modulus = 1e308", "steps (more than 1e+09)",
       "young_modulus = 1e+308"},
      {"young_modulus = 1e7", "young_modulus = 1e-300", "longer than the whole run",
       "young_modulus = 1e-300"},
      {"density = 1800.0", "density = 1e-300", "steps (more than 1e+09)", "density = 1e-300"}};
  for (const auto& [from, to, reason, printed] : cases) {
    const std::string path = (directory / "case.toml").string();
    std::ofstream(path) << edited(from, to);
    RunOptions options;
    options.case_path = path;
    options.output_directory = (directory / "out").string();
    std::ostringstream out, err;
    EXPECT_EQ(check_case(options, out, err), exit_bad_input) << to;
    EXPECT_NE(err.str().find(reason), std::string::npos) << err.str();
    EXPECT_NE(err.str().find("material 'soil' (linear_elastic: "), std::string::npos) << err.str();
    EXPECT_NE(err.str().find(printed), std::string::npos) << err.str();
    std::ostringstream run_out, run_err;
    EXPECT_EQ(run_case(options, run_out, run_err), exit_bad_input) << to;
    EXPECT_NE(run_err.str().find(reason), std::string::npos) << run_err.str();
    EXPECT_FALSE(std::filesystem::exists(directory / "out")) << to;
  }
}

TEST(CaseReader, ASnapshotIntervalThatWouldSetTheStepIsRefusedBeforeAnythingIsWritten) {
  // Steps land on snapshot times: at 1e-12 s this case's 0.2 s would take 2e11 steps and write as
  // many snapshots (a run did start, cut to steps of 1e-12 s). The bound that refuses a mistyped
  // material's step count (max_run_steps) refuses it, naming the key; 1e-5 s, 2e4 steps of a
  // debugging run, is allowed.
  const auto directory = std::filesystem::temp_directory_path() / "mpile_snapshot_interval_test";
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  const std::string path = (directory / "case.toml").string();
  RunOptions options;
  options.case_path = path;
  options.output_directory = (directory / "out").string();
  std::ofstream(path) << edited("snapshot_interval = 0.05", "snapshot_interval = 1e-12");
  std::ostringstream out, err;
  EXPECT_EQ(check_case(options, out, err), exit_bad_input);
  EXPECT_NE(err.str().find("case.toml: output.snapshot_interval = 1e-12 s: steps land on "
                           "snapshot times"),
            std::string::npos)
      << err.str();
  EXPECT_NE(err.str().find("(more than 1e+09)"), std::string::npos) << err.str();
  std::ostringstream run_out, run_err;
  EXPECT_EQ(run_case(options, run_out, run_err), exit_bad_input);
  EXPECT_FALSE(std::filesystem::exists(directory / "out"));
  std::ofstream(path) << edited("snapshot_interval = 0.05", "snapshot_interval = 1e-5");
  const CaseSpec spec = read_case_file(path);
  const auto scene = build_scene(spec);
  EXPECT_NO_THROW(refuse_implausible_run(spec, *scene, 1e-3));
}

TEST(CaseReader, AnImplausibleRunBesideARigidBodyNamesTheCasesOwnMaterial) {
  // Found by tools/fuzz_cases.py: V7's block at young_modulus = 5e-324 beside its rigid incline.
  // Every crossing time is infinite, and the message looked up the rigid body's material (the
  // scene's, with no entry among the case's materials): SIGSEGV. It names the block now.
  const auto directory = std::filesystem::temp_directory_path() / "mpile_implausible_rigid_test";
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  const std::string path = (directory / "v7.toml").string();
  std::ofstream(path) << replaced(
      read_text(source / "cases/verification/v7_block_on_incline.toml"),
      "[materials.block]\ntype = \"linear_elastic\"\nyoung_modulus = 10e6",
      "[materials.block]\ntype = \"linear_elastic\"\nyoung_modulus = 5e-324");
  RunOptions options;
  options.case_path = path;
  std::ostringstream out, err;
  EXPECT_EQ(check_case(options, out, err), exit_bad_input);
  EXPECT_NE(err.str().find("longer than the whole run"), std::string::npos) << err.str();
  EXPECT_NE(err.str().find("of body 'block'"), std::string::npos) << err.str();
  EXPECT_NE(err.str().find("check materials.block"), std::string::npos) << err.str();
}

TEST(CaseReader, AnInitialStressPastAnyMaterialsIsRefusedNotIteratedForEver) {
  // VHS's K0 surcharge at 1e200 Pa: the principal stresses overflowed (a stress squared), the
  // Hardening Soil moduli fell to their floor, the first step looked plausible (1e-3 s) and each
  // of the first steps iterated on every particle (168 s for check and run of 32 particles; the
  // monopile's geostatic phase did not end in minutes and a SIGTERM waited for the step). Past a
  // terapascal a start is refused, naming the k0 keys.
  const auto directory = std::filesystem::temp_directory_path() / "mpile_initial_stress_test";
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  const std::string path = (directory / "vhs.toml").string();
  const std::string vhs = read_text(source / "cases/verification/hs_oedometer.toml");
  RunOptions options;
  options.case_path = path;
  options.output_directory = (directory / "out").string();
  const std::string k0 = "surcharge = 100e3, k0 = 0.5";
  for (const char* edit : {"surcharge = 1e200, k0 = 0.5", "surcharge = 1e13, k0 = 0.5",
                           "surcharge = 100e3, k0 = 1e300"}) {
    std::ofstream(path) << replaced(vhs, k0, edit);
    std::ostringstream out, err;
    EXPECT_EQ(check_case(options, out, err), exit_bad_input) << edit;
    EXPECT_NE(err.str().find("vhs.toml: an initial stress of -"), std::string::npos) << err.str();
    EXPECT_NE(err.str().find(" Pa, past any material's (more than 1e+12 Pa): check the phases' k0 "
                             "(its surcharge, surface and k0); found at the start in particle "),
              std::string::npos)
        << err.str();
    EXPECT_NE(err.str().find("of body 'sample' at (r, y) = ("), std::string::npos) << err.str();
    std::ostringstream run_out, run_err;
    EXPECT_EQ(run_case(options, run_out, run_err), exit_bad_input) << edit;
    EXPECT_FALSE(std::filesystem::exists(directory / "out")) << edit;
  }
  // A tenth of the bound is a start the model evaluates: checked, not refused.
  std::ofstream(path) << replaced(vhs, k0, "surcharge = 1e11, k0 = 0.5");
  std::ostringstream out, err;
  EXPECT_EQ(check_case(options, out, err), exit_success) << err.str();
}

TEST(CaseReader, ASnapshotIntervalThatWouldWriteMoreThanATenthOfAMillionFilesIsRefused) {
  // 1e-6 s over this case's 0.2 s: 2e5 steps, a run of seconds, but as many snapshot files (the
  // steps land on them); 5e-6 s, 4e4 files, is a debugging run's and allowed.
  const auto directory = std::filesystem::temp_directory_path() / "mpile_snapshot_count_test";
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  const std::string path = (directory / "case.toml").string();
  std::ofstream(path) << edited("snapshot_interval = 0.05", "snapshot_interval = 1e-6");
  RunOptions options;
  options.case_path = path;
  options.output_directory = (directory / "out").string();
  std::ostringstream out, err;
  EXPECT_EQ(check_case(options, out, err), exit_bad_input);
  EXPECT_NE(err.str().find("case.toml: output.snapshot_interval = 1e-06 s: the phases' 0.2 s "
                           "would write about 200000 snapshots (more than 100000"),
            std::string::npos)
      << err.str();
  std::ostringstream run_out, run_err;
  EXPECT_EQ(run_case(options, run_out, run_err), exit_bad_input);
  EXPECT_FALSE(std::filesystem::exists(directory / "out"));
  std::ofstream(path) << edited("snapshot_interval = 0.05", "snapshot_interval = 5e-6");
  const CaseSpec spec = read_case_file(path);
  const auto scene = build_scene(spec);
  EXPECT_NO_THROW(refuse_implausible_run(spec, *scene, 1e-3));
}

/// The reader's message for a case text, or "accepted".
std::string reader_verdict(const std::string& text) {
  try {
    read_case_text(text, "case.toml");
  } catch (const CaseError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(CaseReader, DeepNestingAndOverlongLinesAreRefusedBeforeTheParserSeesThem) {
  // 200 000 nested arrays or 20 000 nested inline tables overflowed the parser's stack (SIGSEGV);
  // a 435 kB line took 11 s (the parser is quadratic in a line's length).
  const auto message = reader_verdict;
  const std::string arrays = "x = " + std::string(200000, '[') + std::string(200000, ']') + "\n";
  EXPECT_EQ(message(arrays + valid_case),
            "case.toml:1: arrays and inline tables are nested more than 64 deep");
  std::string tables = "x = ";
  for (int k = 0; k < 20000; ++k) {
    tables += "{a=";
  }
  tables += "1" + std::string(20000, '}') + "\n";
  EXPECT_EQ(message(tables + valid_case),
            "case.toml:1: arrays and inline tables are nested more than 64 deep");
  // Brackets inside strings and comments do not count; 64 levels are allowed.
  const std::string quoted = "# [[[[ {{{{\ntitle = \"[[[[[\"\n";
  EXPECT_EQ(message(edited("title = \"reader test\"\n", quoted)), "accepted");
  const std::string deep_ok =
      "x = " + std::string(64, '[') + std::string(64, ']') + "\n" + valid_case;
  EXPECT_EQ(message(deep_ok).find("nested"), std::string::npos) << message(deep_ok);
  // A long array on one line is refused with its line; the same array over several lines reads.
  // (valid_case ends in its [output] table, which takes the array.)
  std::string one_line = "snapshot_times = [";
  std::string lines = "snapshot_times = [\n";
  for (int k = 1; k < 40000; ++k) {
    const std::string value = std::to_string(1e-7 * k);
    one_line += value + (k + 1 < 40000 ? ", " : "]\n");
    lines += value + (k + 1 < 40000 ? ",\n" : "]\n");
  }
  const std::string long_line = valid_case + one_line;
  const auto line = std::count(valid_case.begin(), valid_case.end(), '\n') + 1;
  EXPECT_EQ(message(long_line).rfind("case.toml:" + std::to_string(line) + ": the line is ", 0), 0u)
      << message(long_line);
  EXPECT_NE(message(long_line).find("(at most 16384): break long arrays over several lines"),
            std::string::npos);
  EXPECT_EQ(message(valid_case + lines), "accepted");
}

TEST(CaseReader, LongDottedKeysAreRefusedBeforeTheParserSeesThem) {
  // The parser's time grows like the cube of a dotted key's parts: 4 000 took 35 s and 600 MB.
  // A key of more than 64 parts (as deep as arrays may nest) is refused at its line, at once.
  const auto message = reader_verdict;
  auto dotted = [](int parts) {
    std::string key = "a";
    for (int k = 1; k < parts; ++k) {
      key += ".a";
    }
    return key;
  };
  const auto line = std::to_string(std::count(valid_case.begin(), valid_case.end(), '\n') + 1);
  const std::string refused = "case.toml:" + line + ": a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a" +
                              "...: a dotted key has more than 64 parts";
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(message(valid_case + dotted(4000) + " = 1\n"), refused);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
  // In a table header, an inline table (after a comma too), with blanks around the dots.
  EXPECT_EQ(message(valid_case + "[" + dotted(65) + "]\n"), refused);
  EXPECT_EQ(message(valid_case + "x = { b = 1, " + dotted(65) + " = 2 }\n"),
            "case.toml:" + line + ": " + dotted(20) + "...: a dotted key has more than 64 parts");
  EXPECT_NE(message(valid_case + replaced(dotted(65), ".", " . ") + " = 1\n")
                .find("a dotted key has more than 64 parts"),
            std::string::npos);
  // 64 parts reach the reader (an unknown key); dots in values, strings and comments do not count.
  EXPECT_EQ(message(valid_case + dotted(64) + " = 1\n").find("dotted"), std::string::npos);
  std::string values = "snapshot_times = [";
  for (int k = 1; k < 200; ++k) {
    values += "0." + std::to_string(k) + ", ";
  }
  values += "0.9] # " + dotted(100) + "\n";
  EXPECT_EQ(message(valid_case + values), "accepted");
  EXPECT_EQ(message(valid_case + "\"" + dotted(100) + "\" = 1\n").find("dotted"),
            std::string::npos);
}

TEST(CaseReader, RunExitsWithStatusTwoAndOneLineReasonOnBadInput) {
  const auto directory = std::filesystem::temp_directory_path() / "mpile_bad_input_test";
  std::filesystem::create_directories(directory);
  const std::string path = (directory / "bad.toml").string();
  std::ofstream(path) << edited("poisson_ratio = 0.3", "poisson_ratio = 0.7");
  RunOptions options;
  options.case_path = path;
  options.output_directory = (directory / "out").string();
  std::ostringstream out, err;
  EXPECT_EQ(run_case(options, out, err), exit_bad_input);
  EXPECT_NE(err.str().find(path + ":11: materials.soil.poisson_ratio"), std::string::npos)
      << err.str();
  EXPECT_FALSE(std::filesystem::exists(directory / "out" / "history.h5"));
  options.case_path = (directory / "missing.toml").string();
  EXPECT_EQ(run_case(options, out, err), exit_bad_input);
  EXPECT_NE(err.str().find("missing.toml: cannot open the case file: No such file or directory"),
            std::string::npos)
      << err.str();
}

TEST(CaseReader, OnlyARegularFileOfBoundedSizeIsReadAsACase) {
  // A directory read as an empty file ("grid: missing"), a FIFO blocked the reader for ever and
  // /dev/zero was read to 2 GB: each is refused before reading, with the reason.
  const auto directory = std::filesystem::temp_directory_path() / "mpile_case_file_test";
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  const auto refused = [](const std::string& path, const std::string& reason) {
    try {
      read_case_file(path);
      ADD_FAILURE() << path << " was read";
    } catch (const CaseError& e) {
      EXPECT_EQ(std::string(e.what()), path + ": " + reason);
    }
  };
  refused(directory.string(), "is a directory, not a case file");
  const std::string fifo = (directory / "fifo.toml").string();
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  refused(fifo, "is not a regular file (a case file is a TOML text file)");
  if (std::filesystem::exists("/dev/zero")) {
    refused("/dev/zero", "is not a regular file (a case file is a TOML text file)");
  }
  const std::string large = (directory / "large.toml").string();
  std::ofstream(large).close();
  std::filesystem::resize_file(large, max_case_file_bytes + 1); // sparse: no 16 MiB written
  refused(large, "is " + std::to_string(max_case_file_bytes + 1) +
                     " bytes; a case file is at most " + std::to_string(max_case_file_bytes) +
                     " bytes");
  std::filesystem::remove_all(directory);
}

TEST(CaseReader, XpicOrderIsReadForTheRunAndForAPhase) {
  const CaseSpec spec = read_case_text(
      edited_text(edited("courant_number = 0.5", "courant_number = 0.5\nxpic_order = 4"),
                  "local_damping = 0.7\n", "local_damping = 0.7\nxpic_order = 2\n"),
      "case.toml");
  EXPECT_EQ(spec.solver.xpic_order, 4);
  EXPECT_EQ(phase_settings(spec, spec.phases.at(0)).xpic_order, 2);
  EXPECT_EQ(read_case_text(valid_case, "case.toml").solver.xpic_order, 0); // off unless asked
}

} // namespace
} // namespace mpile
