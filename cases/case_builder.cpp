#include "cases/case_builder.hpp"

#include "cases/case_error.hpp"
#include "engine/materials/pore_water.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

namespace mpile {

namespace {

std::vector<int> line_nodes(const Grid& grid, const NodeLineSpec& line) {
  const double tolerance = 1e-9;
  if (line.along_y) {
    for (int ir = 0; ir < grid.nodes_r(); ++ir) {
      if (std::abs(grid.r_axis().node(ir) - line.at) <=
          tolerance * std::max(1.0, std::abs(line.at))) {
        return nodes_on_r_line(grid, ir, line.from - tolerance, line.to + tolerance);
      }
    }
  } else {
    for (int iy = 0; iy < grid.nodes_y(); ++iy) {
      if (std::abs(grid.y_axis().node(iy) - line.at) <=
          tolerance * std::max(1.0, std::abs(line.at))) {
        return nodes_on_y_line(grid, iy, line.from - tolerance, line.to + tolerance);
      }
    }
  }
  return {};
}

/// Index of a body's material in the case (and in the scene, which adds them in the same order);
/// the reader has checked that it exists.
std::uint16_t material_of(const CaseSpec& spec, const BodySpec& body) {
  std::uint16_t index = 0;
  for (std::size_t m = 0; m < spec.materials.size(); ++m) {
    if (spec.materials[m].name == body.material) {
      index = static_cast<std::uint16_t>(m);
    }
  }
  return index;
}

std::size_t phase_of(const CaseSpec& spec, const std::string& name) {
  for (std::size_t p = 0; p < spec.phases.size(); ++p) {
    if (spec.phases[p].name == name) {
      return p;
    }
  }
  return 0;
}

/// Seeds a body's region pass by pass: seed(y_lines, band) seeds the part of the region within the
/// band on the grid with those y-lines (nullptr: the grid as it starts) and returns how many
/// particles that gave. A cell finer than the spacing of the particles seeded in it can be left
/// empty, which disconnects the soil above it from the soil below (it falls); so every point is
/// seeded for the finest cells it will sit in while the band travels down. Above the band's start
/// those are the cells of the start (lines there only stretch). Below it, a point the band reaches
/// sits in the band's cells: the soil the band passes through is seeded in slices of the band's
/// height, each for the band carried down onto it. Below the band's whole travel, a point's cells
/// only get finer as the compressed lines drag finer cells into it: it is seeded for the band
/// carried all the way down. Every split is a y-line of the grids on both sides, so no particle
/// position lies on one.
///
/// A graded band (a resolved pile tip: its finest cells at the tip, growing away from it) is
/// different: a point the tip passes meets the band's finest cell, which the band's start or end
/// would not seed it for. The soil the finest cell passes through is seeded slice by slice, each
/// slice the finest cell with the band carried down by whole finest cells; above that the start,
/// below it the band's whole travel (the cells below the tip only get finer as it approaches).
template <typename Seed> std::size_t seed_graded_band(const MovingMesh& mesh, Seed&& seed) {
  const auto y = [&](int line) { return mesh.reference_y[static_cast<std::size_t>(line)]; };
  int finest = mesh.band_bottom; // the lowest cell of the smallest size (below the tip)
  for (int c = mesh.band_bottom; c < mesh.band_top; ++c) {
    if (y(c + 1) - y(c) < (y(finest + 1) - y(finest)) * (1.0 - 1e-9)) {
      finest = c;
    }
  }
  const double h = y(finest + 1) - y(finest);
  std::size_t added =
      seed(nullptr, SeedBand{y(finest + 1), std::numeric_limits<double>::infinity()});
  double split = y(finest + 1);
  for (int k = 0; k * h <= mesh.travel * (1.0 + 1e-12); ++k) {
    const std::vector<double> lines = mesh.lines_at(-k * h);
    const double bottom = lines[static_cast<std::size_t>(finest)];
    added += seed(&lines, SeedBand{bottom, split});
    split = bottom;
  }
  const std::vector<double> lines = mesh.lines_at(-mesh.travel);
  return added + seed(&lines, SeedBand{-std::numeric_limits<double>::infinity(), split});
}

template <typename Seed>
std::size_t seed_in_passes(const std::optional<MovingMesh>& mesh, const BodySpec& body,
                           Seed&& seed) {
  if (!mesh || mesh->travel == 0.0) {
    return seed(nullptr, SeedBand{});
  }
  const auto cell = [&](int c) {
    return mesh->reference_y[static_cast<std::size_t>(c + 1)] -
           mesh->reference_y[static_cast<std::size_t>(c)];
  };
  for (int c = mesh->band_bottom + 1; c < mesh->band_top; ++c) {
    if (std::abs(cell(c) - cell(mesh->band_bottom)) > 1e-9 * cell(mesh->band_bottom)) {
      return seed_graded_band(*mesh, seed);
    }
  }
  const double split = mesh->reference_y[static_cast<std::size_t>(mesh->band_bottom)];
  const double height = mesh->reference_y[static_cast<std::size_t>(mesh->band_top)] - split;
  const Rectangle& bounds = body.region.bounds();
  std::size_t added = 0;
  for (int slice = 1;; ++slice) {
    // The band carried down `slice` heights (its travel at most) covers the slice below `top`.
    const double top = split - (slice - 1) * height;
    const double offset = std::max(-slice * height, -mesh->travel);
    const bool lowest = offset <= -mesh->travel;
    const SeedBand band{lowest ? -std::numeric_limits<double>::infinity() : split + offset, top};
    if (bounds.y_min < band.y_to && bounds.y_max > band.y_from) {
      const std::vector<double> lines = mesh->lines_at(offset);
      added += seed(&lines, band);
    }
    if (lowest) {
      break;
    }
  }
  if (bounds.y_max > split) {
    added += seed(nullptr, SeedBand{split, std::numeric_limits<double>::infinity()});
  }
  return added;
}

std::size_t seed_body(Scene& scene, const BodySpec& body, std::uint16_t material,
                      std::uint16_t index) {
  const std::optional<MovingMesh>& mesh = scene.moving_mesh;
  return seed_in_passes(mesh, body, [&](const std::vector<double>* y_lines, SeedBand band) {
    if (y_lines != nullptr) {
      scene.grid.set_y_nodes(*y_lines);
    }
    const std::size_t added = fill_region(scene, body.region, body.particles_per_direction,
                                          material, index, band, body.cut_cells);
    if (y_lines != nullptr) {
      scene.grid.set_y_nodes(mesh->reference_y);
    }
    return added;
  });
}

/// Surface index of each edge of a structure's outline; edges that share a name form one surface
/// (pair.surfaces gets the names in the order they first appear).
std::vector<int> edge_surfaces(const std::vector<std::string>& names, ContactPair& pair) {
  std::vector<int> surface;
  for (const std::string& name : names) {
    if (name.empty()) {
      surface.push_back(-1);
      continue;
    }
    const auto found = std::find(pair.surfaces.begin(), pair.surfaces.end(), name);
    surface.push_back(static_cast<int>(found - pair.surfaces.begin()));
    if (found == pair.surfaces.end()) {
      pair.surfaces.push_back(name);
    }
  }
  return surface;
}

} // namespace

MovingMesh moving_mesh_of(const MovingMeshSpec& spec, const GradedAxis& y) {
  MovingMesh mesh;
  mesh.reference_y.assign(y.nodes().begin(), y.nodes().end());
  // The reader has checked that the band's ends are grid lines.
  const auto nearest = [&](double at) {
    int best = 0;
    for (int i = 0; i < y.node_count(); ++i) {
      if (std::abs(y.node(i) - at) < std::abs(y.node(best) - at)) {
        best = i;
      }
    }
    return best;
  };
  mesh.band_bottom = nearest(spec.band_bottom);
  mesh.band_top = nearest(spec.band_top);
  if (spec.stretch) {
    mesh.stretch_bottom = nearest((*spec.stretch)[0]);
    mesh.stretch_top = nearest((*spec.stretch)[1]);
  }
  const double cell = y.cell_size(mesh.band_bottom);
  mesh.travel = spec.travel > 0.0 ? std::ceil(spec.travel / cell - 1e-9) * cell : 0.0;
  // A travel of whole cells rounds to itself within 1e-9 of a cell, which can come out a hair
  // below the travel as written (cells of 0.05 m computed as 0.04999999999999982): the band must
  // still reach that, or a case driving the pile the whole travel is refused as going beyond it.
  mesh.travel = std::max(mesh.travel, spec.travel);
  return mesh;
}

std::size_t count_body_particles(const CaseSpec& spec, const BodySpec& body) {
  const GradedAxis r_axis(spec.r_zones);
  const GradedAxis y_axis(spec.y_zones);
  std::optional<MovingMesh> mesh;
  if (spec.moving_mesh) {
    mesh = moving_mesh_of(*spec.moving_mesh, y_axis);
  }
  return seed_in_passes(mesh, body, [&](const std::vector<double>* y_lines, SeedBand band) {
    GradedAxis y = y_axis;
    if (y_lines != nullptr) {
      y.set_nodes(*y_lines);
    }
    return count_region_seeds(r_axis, y, body.region, body.particles_per_direction, band);
  });
}

namespace {

/// Two bodies whose regions share a particle position would be seeded twice there (double mass
/// and stress): refused, naming the later body, the earlier one and a position they share.
void refuse_overlapping_bodies(const Scene& scene, const CaseSpec& spec) {
  const Particles& p = scene.particles;
  // Positions on a 1e-9 m lattice: seeds of one grid are equal to the last bit, or far apart.
  struct Seed {
    long long r, y;
    std::uint16_t body;
    std::size_t index;
  };
  std::vector<Seed> seeds(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    seeds[i] = {std::llround(p.r[i] * 1e9), std::llround(p.y[i] * 1e9), p.body[i], i};
  }
  std::sort(seeds.begin(), seeds.end(), [](const Seed& a, const Seed& b) {
    return a.y != b.y ? a.y < b.y : a.r != b.r ? a.r < b.r : a.body < b.body;
  });
  for (std::size_t k = 1; k < seeds.size(); ++k) {
    const Seed& a = seeds[k - 1];
    const Seed& b = seeds[k];
    if (a.r == b.r && a.y == b.y && a.body != b.body) {
      const BodySpec& later = spec.bodies[std::max(a.body, b.body)];
      const BodySpec& earlier = spec.bodies[std::min(a.body, b.body)];
      std::ostringstream s;
      s << spec.file << ":" << later.line << ": "
        << (later.key.empty() ? "body '" + later.name + "'" : later.key) << ": overlaps body '"
        << earlier.name << "' (both seed a particle at (r, y) = (" << p.r[a.index] << ", "
        << p.y[a.index] << ")): its particles would be doubled there; make the regions "
        << "disjoint (a polygon can leave out another body's region)";
      throw CaseError(s.str());
    }
  }
}

} // namespace

std::unique_ptr<Scene> build_scene(const CaseSpec& spec) {
  auto scene =
      std::make_unique<Scene>(spec.mode, Grid(GradedAxis(spec.r_zones), GradedAxis(spec.y_zones)));
  for (const MaterialSpec& material : spec.materials) {
    scene->add_material(create_material(material.type, material.parameters, material.water),
                        material.name);
  }
  if (spec.moving_mesh) {
    scene->moving_mesh = moving_mesh_of(*spec.moving_mesh, scene->grid.y_axis());
  }
  for (const BodySpec& body : spec.bodies) {
    const std::uint16_t material = material_of(spec, body);
    const std::uint16_t index = scene->add_body(body.name);
    const std::size_t first = scene->particles.size();
    const std::size_t added = seed_body(*scene, body, material, index);
    scene->cut_cell_bodies.resize(scene->body_names.size(), 0);
    scene->cut_cell_bodies[index] = body.cut_cells ? 1 : 0;
    if (added == 0) {
      throw CaseError(spec.file + ": body '" + body.name +
                      "': its region holds no particle position (smaller than a cell?)");
    }
    Particles& p = scene->particles;
    for (std::size_t i = first; i < p.size(); ++i) {
      std::array<double, 3> v = body.velocity;
      if (body.velocity_profile) {
        const VelocityProfile& profile = *body.velocity_profile;
        v[static_cast<std::size_t>(profile.component)] +=
            profile.function.value(profile.along_y ? p.y[i] : p.r[i]);
      }
      p.v_r[i] = v[0];
      p.v_y[i] = v[1];
      if (has_theta(spec.mode)) {
        p.v_theta[i] = v[2];
      }
    }
    if (const LiquidPhase* water = scene->materials[material]->liquid_phase()) {
      // A body set moving moves whole: its pore water with its grains.
      for (std::size_t i = first; i < p.size(); ++i) {
        double* w =
            p.state.data() + i * static_cast<std::size_t>(p.state_stride) + water->velocity_slot;
        w[0] = p.v_r[i];
        w[1] = p.v_y[i];
        w[2] = has_theta(spec.mode) ? p.v_theta[i] : 0.0;
      }
    }
  }
  refuse_overlapping_bodies(*scene, spec);

  for (const ContactSpec& contact : spec.contacts) {
    std::uint16_t b = 0;
    while (scene->body_names[b] != contact.structure) {
      ++b;
    }
    const BodySpec& body = spec.bodies[b];
    ContactPair& pair = scene->add_contact_structure(b);
    pair.friction = contact.friction;
    pair.adhesion = contact.adhesion;
    pair.surface_gap_at_node = contact.surface_gap;
    if (contact.outline) {
      pair.outline = region_outline(body.region, spec.mode, edge_surfaces(contact.surfaces, pair));
    } else {
      pair.surfaces = {contact.surfaces[0]};
    }
    if (body.rigid) {
      const double density = scene->materials[material_of(spec, body)]->density();
      scene->make_rigid(b, density, body.rigid->mass,
                        spec.mode == GeometryMode::plane_strain ? body.rigid->inertia
                                                                : body.rigid->polar_inertia);
    }
  }

  if (spec.water) {
    // The sea's pressure on the seabed acts on a structure through it as on the soil, but the
    // pore pressures the contact sees are relative to it: the uplift on the structure's
    // cross-section at the seabed is what they leave out (physics.md section 9c).
    for (RigidBody& rigid : scene->rigid_bodies) {
      rigid.water_load[RIGID_Y] = spec.water->column_pressure *
                                  cross_section(scene->particles, rigid.body, spec.water->seabed);
    }
  }

  if (scene->moving_mesh) {
    for (std::size_t k = 0; k < scene->rigid_bodies.size(); ++k) {
      if (scene->rigid_bodies[k].name == spec.moving_mesh->body) {
        scene->moving_mesh->rigid_body = static_cast<int>(k);
      }
    }
  }

  if (spec.velocity_gradient) {
    const std::array<double, 4> L = *spec.velocity_gradient;
    scene->velocity_field = [L](double r, double y, double) {
      return std::array<double, 3>{L[0] * r + L[1] * y, L[2] * r + L[3] * y, 0.0};
    };
  }

  Boundaries& boundaries = scene->boundaries;
  const GridFace faces[] = {GridFace::r_min, GridFace::r_max, GridFace::y_min, GridFace::y_max};
  for (std::size_t f = 0; f < 4; ++f) {
    if (spec.faces[f] != FaceCondition::free) {
      boundaries.constraints.push_back(
          face_constraint(scene->grid, spec.mode, faces[f], spec.faces[f]));
      boundaries.constraints.back().drained =
          std::find(spec.drained_faces.begin(), spec.drained_faces.end(), faces[f]) !=
          spec.drained_faces.end();
      if (boundaries.constraints.back().drained && spec.drained_water) {
        DrainedFaceWater water;
        water.face = faces[f];
        water.nodes = boundaries.constraints.back().nodes;
        water.surface = spec.drained_water->surface;
        water.density = spec.drained_water->density;
        boundaries.drained_water.push_back(std::move(water));
      }
    }
  }
  if (spec.mode == GeometryMode::axisymmetric && scene->grid.r_axis().start() == 0.0) {
    boundaries.constraints.push_back(axis_constraint(scene->grid));
  }
  for (const GridFace face : spec.absorbing.faces) {
    AbsorbingFace absorbing;
    absorbing.face = face;
    absorbing.nodes = nodes_on_face(scene->grid, face);
    boundaries.absorbing.push_back(std::move(absorbing));
  }
  for (const MotionSpec& motion : spec.motions) {
    NodeConstraint c;
    c.name = motion.name;
    c.nodes = line_nodes(scene->grid, motion.nodes);
    for (std::size_t d = 0; d < 3; ++d) {
      if (motion.velocity[d]) {
        c.dofs |= static_cast<std::uint8_t>(1u << d);
        c.velocity[d] = motion.velocity[d];
      }
    }
    c.theta_is_rotation = motion.theta_is_rotation;
    if (!motion.body.empty()) {
      for (std::uint16_t b = 0; b < scene->body_names.size(); ++b) {
        if (scene->body_names[b] == motion.body) {
          c.field = scene->field_of(b);
        }
      }
    }
    boundaries.constraints.push_back(std::move(c));
  }
  for (const LoadSpec& load : spec.loads) {
    boundaries.loads.push_back(line_load(scene->grid, spec.mode,
                                         line_nodes(scene->grid, load.nodes), load.component,
                                         load.traction, load.name));
  }
  // Until their phase starts, motions hold their DOFs at rest and loads are off.
  activate_phase_boundaries(*scene, spec, 0, 0.0);
  return scene;
}

void activate_phase_boundaries(Scene& scene, const CaseSpec& spec, std::size_t phase_index,
                               double start_time) {
  constexpr double never = 1e300;
  for (const MotionSpec& motion : spec.motions) {
    const std::size_t starts = phase_of(spec, motion.phase);
    for (NodeConstraint& c : scene.boundaries.constraints) {
      if (c.name != motion.name) {
        continue;
      }
      for (std::size_t d = 0; d < 3; ++d) {
        if (motion.velocity[d] && (starts == phase_index || phase_index == 0)) {
          c.velocity[d] =
              motion.velocity[d]->starting_at(starts == phase_index ? start_time : never);
        }
      }
    }
  }
  for (const BodySpec& body : spec.bodies) {
    if (!body.rigid) {
      continue;
    }
    const std::size_t starts = phase_of(spec, body.rigid->phase);
    if (starts != phase_index && phase_index != 0) {
      continue;
    }
    const bool active = starts == phase_index;
    for (RigidBody& rigid : scene.rigid_bodies) {
      if (rigid.name != body.name) {
        continue;
      }
      for (std::size_t d = 0; d < 3; ++d) {
        const auto& drive = body.rigid->drive[d];
        if (!active) {
          // Held at rest until the drives' phase starts.
          rigid.drive[d] = RigidDrive{RigidDrive::Kind::velocity, TimeFunction::constant(0.0)};
        } else if (drive) {
          rigid.drive[d] = RigidDrive{drive->kind, drive->function.starting_at(start_time)};
        } else {
          rigid.drive[d] = RigidDrive{RigidDrive::Kind::force, TimeFunction::constant(0.0)};
        }
      }
    }
  }
  // A phase's own drive replaces the body's from the phase's start (after the body's drives,
  // which phase 0 sets: the phase's drive wins).
  if (const auto& phase_drive = spec.phases[phase_index].drive) {
    for (RigidBody& rigid : scene.rigid_bodies) {
      if (rigid.name != phase_drive->body) {
        continue;
      }
      for (std::size_t d = 0; d < 3; ++d) {
        const auto& drive = phase_drive->drive[d];
        rigid.drive[d] = drive ? RigidDrive{drive->kind, drive->function.starting_at(start_time)}
                               : RigidDrive{RigidDrive::Kind::force, TimeFunction::constant(0.0)};
      }
    }
  }
  for (const LoadSpec& spec_load : spec.loads) {
    const std::size_t starts = phase_of(spec, spec_load.phase);
    for (NodalLoad& load : scene.boundaries.loads) {
      if (load.name == spec_load.name && (starts == phase_index || phase_index == 0)) {
        load.traction = spec_load.traction.starting_at(starts == phase_index ? start_time : never);
      }
    }
  }
}

void switch_on_absorbing_faces(ExplicitSolver& solver, const CaseSpec& spec,
                               std::size_t phase_index) {
  const std::string& phase = spec.absorbing.phase;
  const bool starts = phase.empty() ? phase_index == 0 : spec.phases[phase_index].name == phase;
  if (starts && !spec.absorbing.faces.empty()) {
    std::vector<std::size_t> faces(spec.absorbing.faces.size());
    std::iota(faces.begin(), faces.end(), std::size_t{0});
    solver.switch_on_absorbing(faces);
  }
}

namespace {

/// With a water table: the ground of a phase's K0 bodies as layers, each body's region and unit
/// weight, and the heights where one may end (its bounds' edges), gathered once per phase.
struct Layers {
  std::vector<std::pair<const Region*, double>> weight; // region, unit weight
  std::vector<double> edges;
};

Layers k0_layers(const Scene& scene, const CaseSpec& spec, const PhaseSpec& phase, double g) {
  Layers layers;
  for (const K0Spec& k0 : phase.k0) {
    for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
      if (spec.bodies[b].name == k0.body) {
        const Rectangle& bounds = spec.bodies[b].region.bounds();
        layers.edges.push_back(bounds.y_min);
        layers.edges.push_back(bounds.y_max);
        layers.weight.emplace_back(&spec.bodies[b].region,
                                   scene.materials[material_of(spec, spec.bodies[b])]->density() *
                                       g);
      }
    }
  }
  return layers;
}

/// The total vertical stress's magnitude at (r, y) from `k0`'s surface down, plus its surcharge:
/// each layer's unit weight over the part of the vertical through (r, y) its region holds (the
/// layers' edges split the vertical; a part no body holds weighs nothing).
double layered_overburden(const Layers& layers, const K0Spec& k0, double r, double y) {
  std::vector<double> edges{y, k0.surface};
  for (const double edge : layers.edges) {
    if (edge > y && edge < k0.surface) {
      edges.push_back(edge);
    }
  }
  std::sort(edges.begin(), edges.end());
  double weight = k0.surcharge;
  for (std::size_t e = 1; e < edges.size(); ++e) {
    const double middle = 0.5 * (edges[e - 1] + edges[e]);
    for (const auto& [region, unit_weight] : layers.weight) {
      if (region->contains(r, middle)) {
        weight += unit_weight * (edges[e] - edges[e - 1]);
        break;
      }
    }
  }
  return weight;
}

} // namespace

void apply_k0(Scene& scene, const CaseSpec& spec, const PhaseSpec& phase) {
  const double g = std::hypot(spec.solver.gravity[0], spec.solver.gravity[1]);
  if (spec.water && spec.water->phreatic) {
    const Layers layers = k0_layers(scene, spec, phase, g);
    for (const K0Spec& k0 : phase.k0) {
      for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
        if (spec.bodies[b].name == k0.body) {
          initialise_layered_geostatic_stress(
              scene, static_cast<std::uint16_t>(b),
              [&](double r, double y) { return layered_overburden(layers, k0, r, y); },
              spec.water->table, g, k0.k0);
        }
      }
    }
    return;
  }
  for (const K0Spec& k0 : phase.k0) {
    // Scene bodies are the case's bodies, in order.
    for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
      if (spec.bodies[b].name == k0.body) {
        const double unit_weight =
            scene.materials[material_of(spec, spec.bodies[b])]->density() * g;
        initialise_geostatic_stress(scene, static_cast<std::uint16_t>(b), k0.surface, unit_weight,
                                    k0.k0, k0.surcharge);
      }
    }
  }
}

SolverSettings phase_settings(const CaseSpec& spec, const PhaseSpec& phase) {
  SolverSettings s = spec.solver;
  s.local_damping = phase.local_damping;
  if (!phase.gravity) {
    s.gravity = {0.0, 0.0};
  }
  if (phase.flip_fraction) {
    s.flip_fraction = *phase.flip_fraction;
  }
  if (phase.xpic_order) {
    s.xpic_order = *phase.xpic_order;
  }
  if (phase.mass_scaling) {
    s.mass_scaling = *phase.mass_scaling;
  }
  if (phase.courant_number) {
    s.courant_number = *phase.courant_number;
  }
  return s;
}

} // namespace mpile
