#include "io/checkpoint.hpp"

#include "cases/case_composition.hpp"
#include "cases/case_error.hpp"
#include "io/hdf5_file.hpp"
#include "io/replace_file.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

namespace mpile {

namespace {

constexpr const char* format_version = "mpile checkpoint 4";

/// A rigid body's state as one row: velocity, displacement, centre, contact, driving, work.
std::vector<double> rigid_state(const RigidBody& b) {
  std::vector<double> row;
  for (const auto* part : {&b.velocity, &b.displacement, &b.contact, &b.driving}) {
    row.insert(row.end(), part->begin(), part->end());
  }
  row.insert(row.end(), b.centre.begin(), b.centre.end());
  row.push_back(b.external_work);
  return row;
}

void restore_rigid_state(RigidBody& b, const std::vector<double>& row) {
  std::size_t k = 0;
  for (auto* part : {&b.velocity, &b.displacement, &b.contact, &b.driving}) {
    for (double& value : *part) {
      value = row.at(k++);
    }
  }
  for (double& value : b.centre) {
    value = row.at(k++);
  }
  b.external_work = row.at(k);
}

// Every per-particle double array, by name; the order is the file's layout.
template <class P> auto double_fields(P& p) {
  return std::vector<std::pair<const char*, decltype(&p.r)>>{
      {"r", &p.r},         {"y", &p.y},           {"r0", &p.r0},           {"y0", &p.y0},
      {"v_r", &p.v_r},     {"v_y", &p.v_y},       {"v_theta", &p.v_theta}, {"u_theta", &p.u_theta},
      {"mass", &p.mass},   {"volume", &p.volume}, {"half_r", &p.half_r},   {"half_y", &p.half_y},
      {"state", &p.state}, {"du_r", &p.du_r},     {"du_y", &p.du_y}};
}

} // namespace

void write_checkpoint(const std::string& path, const CaseSpec& spec, const Scene& scene,
                      const SolverState& solver, const RunProgress& progress) {
  const std::string temporary = path + ".tmp";
  try {
    Hdf5File file(temporary, Hdf5File::Mode::create);
    file.set_attribute("/", "format", format_version);
    file.set_attribute("/", "program", std::string("mpile ") + MPILE_VERSION);
    file.set_attribute("/", "case_text", spec.text);
    file.set_attribute("/", "case_resolved", spec.resolved);
    const Particles& p = scene.particles;
    for (const auto& [name, field] : double_fields(p)) {
      file.write(std::string("/particles/") + name, *field, "SI");
    }
    const std::vector<double> stress(p.stress.front().data(),
                                     p.stress.front().data() + 6 * p.size());
    file.write("/particles/stress", stress, "Pa", {p.size(), 6});
    file.write("/particles/id", p.id);
    file.write("/particles/material", p.material);
    file.write("/particles/body", p.body);
    file.write("/particles/cell_r", p.cell_r);
    file.write("/particles/cell_y", p.cell_y);
    file.write(
        "/grid/y_nodes",
        std::vector<double>(scene.grid.y_axis().nodes().begin(), scene.grid.y_axis().nodes().end()),
        "m");
    if (!scene.grid.drain_water_velocity.empty()) {
      std::vector<double> kept;
      for (const auto& w : scene.grid.drain_water_velocity) {
        kept.insert(kept.end(), w.begin(), w.end());
      }
      file.write("/grid/drain_water_velocity", kept, "m/s (r, y, theta per node; NaN: none kept)");
    }
    for (std::size_t k = 0; k < scene.rigid_bodies.size(); ++k) {
      file.write("/rigid_bodies/" + std::to_string(k), rigid_state(scene.rigid_bodies[k]),
                 "velocity (3), displacement (3), contact (3), driving (3), centre (2), work");
    }
    for (std::size_t k = 0; k < scene.boundaries.absorbing.size(); ++k) {
      // An absorbing face switched on keeps what it sampled then; one still off keeps nothing.
      const AbsorbingFace& face = scene.boundaries.absorbing[k];
      if (!face.active) {
        continue;
      }
      const std::string base = "/absorbing/" + std::to_string(k);
      file.write(base + "/edges", face.edges, "m");
      file.write(base + "/p_impedance", face.p_impedance, "Pa s/m");
      file.write(base + "/s_impedance", face.s_impedance, "Pa s/m");
      std::vector<double> holding;
      for (const auto& t : face.holding_traction) {
        holding.insert(holding.end(), t.begin(), t.end());
      }
      file.write(base + "/holding_traction", holding, "Pa (r, y, theta per node)");
    }
    for (std::size_t k = 0; k < scene.contacts.size(); ++k) {
      const ContactPair& pair = scene.contacts[k];
      const std::string base = "/contacts/" + std::to_string(k);
      std::vector<double> forces;
      for (std::size_t q = 0; q < pair.surfaces.size(); ++q) {
        forces.insert(forces.end(), pair.surface_force[q].begin(), pair.surface_force[q].end());
        forces.push_back(pair.surface_torque[q]);
      }
      file.write(base + "/surface_forces", forces, "F_r, F_y, F_theta, M_theta per surface");
      if (has_pore_water(scene)) {
        std::vector<double> pore;
        for (const auto& f : pair.surface_pore_force) {
          pore.insert(pore.end(), f.begin(), f.end());
        }
        file.write(base + "/surface_pore_forces", pore, "the pore water's F_r, F_y per surface");
      }
      if (pair.outline) {
        std::vector<double> vertices;
        for (const auto& v : pair.outline->vertices) {
          vertices.insert(vertices.end(), v.begin(), v.end());
        }
        file.write(base + "/outline", vertices, "m");
      }
    }
    file.write("/solver/state",
               std::vector<double>{solver.time, static_cast<double>(solver.steps), solver.stable_dt,
                                   solver.last_dt, solver.min_dt},
               "time, steps, stable dt, last dt, dt floor");
    const EnergyLedger& e = solver.energy;
    file.write("/solver/energy",
               std::vector<double>{e.external_work, e.internal_work, e.damping, e.contact,
                                   e.kinetic_reference, e.elastic_reference, e.transfer, e.radiated,
                                   e.drag},
               "external work, internal work, damping, contact, kinetic and elastic references, "
               "transfer, radiated, drag");
    file.write("/run/counters",
               std::vector<double>{static_cast<double>(progress.phase),
                                   static_cast<double>(progress.history_rows),
                                   progress.next_history_time, progress.next_snapshot_time,
                                   static_cast<double>(progress.next_listed_snapshot),
                                   progress.next_checkpoint_time, progress.peak_residual,
                                   progress.peak_residual_time},
               "phase, history rows, next history time, next snapshot time, next listed "
               "snapshot, next checkpoint time, peak energy residual, its time");
    file.write("/run/phase_starts", progress.phase_starts, "s");
    file.write("/run/phase_start_depths", progress.phase_start_depths, "m");
    std::vector<double> snapshot_times;
    std::string snapshot_files;
    for (const auto& [time, name] : progress.snapshots) {
      snapshot_times.push_back(time);
      snapshot_files += name + "\n";
    }
    file.write("/run/snapshot_times", snapshot_times, "s");
    file.set_attribute("/run/snapshot_times", "files", snapshot_files);
    // A checkpoint the disk could not hold must not replace the one before it.
    file.close();
  } catch (const std::runtime_error& e) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error("cannot write " + path + ": " + e.what());
  }
  replace_file(temporary, path);
}

namespace {

std::optional<CheckpointCase> stored_case(const Hdf5File& file) {
  if (H5Aexists_by_name(file.id(), "/", "case_resolved", H5P_DEFAULT) <= 0) {
    return std::nullopt;
  }
  return CheckpointCase{file.string_attribute("/", "case_resolved"),
                        static_cast<std::size_t>(file.read_doubles("/run/counters").at(0))};
}

Checkpoint read_checkpoint_file(const std::string& path, const CaseSpec& spec, Scene& scene) {
  Hdf5File file(path, Hdf5File::Mode::read);
  auto refuse = [&](const std::string& why) { throw CaseError(path + ": cannot restart: " + why); };
  if (!file.exists("/particles/r")) {
    refuse("not an mpile checkpoint");
  }
  if (file.string_attribute("/", "format") != format_version) {
    refuse("written in another checkpoint format");
  }
  if (file.string_attribute("/", "program") != std::string("mpile ") + MPILE_VERSION) {
    refuse("written by " + file.string_attribute("/", "program") + ", this is mpile " +
           MPILE_VERSION);
  }
  Checkpoint checkpoint;
  if (const std::optional<CheckpointCase> stored = stored_case(file)) {
    // The phase the run stopped in decides which end criteria may still change.
    checkpoint.changed_keys = restart_changes(stored->resolved, spec.resolved, stored->phase, path);
  } else if (file.string_attribute("/", "case_text") != spec.text) {
    refuse("it belongs to another case (or " + spec.file + " was edited since)");
  }
  Particles& p = scene.particles;
  const std::size_t n = file.read_doubles("/particles/r").size();
  // A run drops the particles of a rigid body that leave the grid, so a checkpoint may hold fewer
  // than the case makes, by at most the rigid bodies' particles; and it splits particles that grow
  // larger than their cells, so it may hold more (bounded here, before anything is read).
  std::size_t rigid = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    rigid += scene.materials[p.material[i]]->is_rigid() ? 1 : 0;
  }
  constexpr std::size_t most_halves = 64;
  if (n > most_halves * p.size() || n + rigid < p.size()) {
    refuse("it holds " + std::to_string(n) + " particles, the case makes " +
           std::to_string(p.size()) + " (of which " + std::to_string(rigid) +
           " of rigid bodies, which a run may drop; a run may split particles, but not into " +
           std::to_string(most_halves) + " times as many)");
  }
  // Each array holds as many values per particle as the case's own (the material state: as many
  // as its materials keep, which a checkpoint of another build of the material models may not).
  const std::size_t made = p.size();
  p.stress.resize(n);
  for (const auto& [name, field] : double_fields(p)) {
    const std::size_t per_particle = made > 0 ? field->size() / made : 0;
    *field = file.read_doubles(std::string("/particles/") + name);
    if (field->size() != per_particle * n) {
      refuse("its particles' " + std::string(name) + " holds " + std::to_string(field->size()) +
             " values for " + std::to_string(n) + " particles, this case keeps " +
             std::to_string(per_particle) + " per particle");
    }
  }
  const std::vector<double> stress = file.read_doubles("/particles/stress");
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t c = 0; c < 6; ++c) {
      p.stress[i][c] = stress[6 * i + c];
    }
  }
  if (file.exists("/particles/id")) {
    p.id = file.read_int32("/particles/id");
  } else {
    // A checkpoint written before particles had ids: number them as they stand.
    p.id.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      p.id[i] = static_cast<std::int32_t>(i);
    }
  }
  p.next_id = p.id.empty() ? 0 : *std::max_element(p.id.begin(), p.id.end()) + 1;
  p.material = file.read_uint16("/particles/material");
  p.body = file.read_uint16("/particles/body");
  p.cell_r = file.read_int32("/particles/cell_r");
  p.cell_y = file.read_int32("/particles/cell_y");
  scene.grid.set_y_nodes(file.read_doubles("/grid/y_nodes"));
  if (file.exists("/grid/drain_water_velocity")) {
    // A drained face's water velocities (Grid::drain_water_velocity); a checkpoint without them
    // restarts its drains from the particles' water, as the first step does.
    const auto kept = file.read_doubles("/grid/drain_water_velocity");
    if (kept.size() != 3 * scene.grid.nodes.size()) {
      refuse("the drained faces' water velocities do not fit the case's grid");
    }
    scene.grid.drain_water_velocity.resize(scene.grid.nodes.size());
    for (std::size_t i = 0; i < scene.grid.nodes.size(); ++i) {
      scene.grid.drain_water_velocity[i] = {kept[3 * i], kept[3 * i + 1], kept[3 * i + 2]};
    }
  }

  for (std::size_t k = 0; k < scene.rigid_bodies.size(); ++k) {
    restore_rigid_state(scene.rigid_bodies[k],
                        file.read_doubles("/rigid_bodies/" + std::to_string(k)));
  }
  for (std::size_t k = 0; k < scene.boundaries.absorbing.size(); ++k) {
    AbsorbingFace& face = scene.boundaries.absorbing[k];
    const std::string base = "/absorbing/" + std::to_string(k);
    if (!file.exists(base)) {
      continue; // not yet switched on
    }
    face.active = true;
    face.edges = file.read_doubles(base + "/edges");
    face.p_impedance = file.read_doubles(base + "/p_impedance");
    face.s_impedance = file.read_doubles(base + "/s_impedance");
    const auto holding = file.read_doubles(base + "/holding_traction");
    const std::size_t count = face.nodes.size();
    if (face.edges.size() != count || face.p_impedance.size() + 1 != count ||
        face.s_impedance.size() + 1 != count || holding.size() != 3 * count) {
      refuse("absorbing face " + std::to_string(k) + " does not fit the case's grid");
    }
    face.holding_traction.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      face.holding_traction[i] = {holding[3 * i], holding[3 * i + 1], holding[3 * i + 2]};
    }
  }
  scene.boundaries.release_absorbing_supports();
  for (std::size_t k = 0; k < scene.contacts.size(); ++k) {
    ContactPair& pair = scene.contacts[k];
    const std::string base = "/contacts/" + std::to_string(k);
    const auto forces = file.read_doubles(base + "/surface_forces");
    pair.surface_force.resize(pair.surfaces.size());
    pair.surface_torque.resize(pair.surfaces.size());
    for (std::size_t q = 0; q < pair.surfaces.size(); ++q) {
      pair.surface_force[q] = {forces.at(4 * q), forces.at(4 * q + 1), forces.at(4 * q + 2)};
      pair.surface_torque[q] = forces.at(4 * q + 3);
    }
    pair.surface_pore_force.assign(pair.surfaces.size(), {0.0, 0.0});
    if (file.exists(base + "/surface_pore_forces")) {
      const auto pore = file.read_doubles(base + "/surface_pore_forces");
      for (std::size_t q = 0; q < pair.surfaces.size(); ++q) {
        pair.surface_pore_force[q] = {pore.at(2 * q), pore.at(2 * q + 1)};
      }
    }
    if (pair.outline) {
      const auto vertices = file.read_doubles(base + "/outline");
      for (std::size_t v = 0; v < pair.outline->vertices.size(); ++v) {
        pair.outline->vertices[v] = {vertices.at(2 * v), vertices.at(2 * v + 1)};
      }
    }
  }

  const auto s = file.read_doubles("/solver/state");
  const auto e = file.read_doubles("/solver/energy");
  checkpoint.solver = {s.at(0),
                       static_cast<long>(s.at(1)),
                       s.at(2),
                       s.at(3),
                       s.at(4),
                       EnergyLedger{e.at(0), e.at(1), e.at(2), e.at(3), e.at(4), e.at(5),
                                    // A checkpoint written before the transfer term
                                    // was kept had none to keep (pure FLIP runs).
                                    e.size() > 6 ? e[6] : 0.0, e.size() > 7 ? e[7] : 0.0,
                                    e.size() > 8 ? e[8] : 0.0}};
  const auto c = file.read_doubles("/run/counters");
  RunProgress& progress = checkpoint.progress;
  progress.phase = static_cast<std::size_t>(c.at(0));
  progress.history_rows = static_cast<std::size_t>(c.at(1));
  progress.next_history_time = c.at(2);
  progress.next_snapshot_time = c.at(3);
  progress.next_listed_snapshot = static_cast<std::size_t>(c.at(4));
  progress.next_checkpoint_time = c.at(5);
  progress.peak_residual = c.at(6);
  progress.peak_residual_time = c.at(7);
  progress.phase_starts = file.read_doubles("/run/phase_starts");
  if (file.exists("/run/phase_start_depths")) {
    progress.phase_start_depths = file.read_doubles("/run/phase_start_depths");
  }
  const auto times = file.read_doubles("/run/snapshot_times");
  const std::string files = file.string_attribute("/run/snapshot_times", "files");
  std::size_t position = 0;
  for (const double time : times) {
    const std::size_t end = files.find('\n', position);
    progress.snapshots.emplace_back(time, files.substr(position, end - position));
    position = end + 1;
  }
  return checkpoint;
}

} // namespace

Checkpoint read_checkpoint(const std::string& path, const CaseSpec& spec, Scene& scene) {
  if (!std::filesystem::exists(path)) {
    throw CaseError(path + ": no such checkpoint");
  }
  try {
    return read_checkpoint_file(path, spec, scene);
  } catch (const CaseError&) {
    throw;
  } catch (const std::runtime_error& e) {
    // HDF5 could not read it (cut short, overwritten, a checksum that does not match): say so and
    // what the user can do, not only HDF5's words.
    throw CaseError(path + ": cannot restart: the checkpoint cannot be read (" + e.what() +
                    "); it was cut short or damaged. Restart from another checkpoint, or run the "
                    "case afresh without --restart or --continue");
  }
}

std::optional<CheckpointCase> checkpoint_case(const std::string& path) {
  return stored_case(Hdf5File(path, Hdf5File::Mode::read));
}

} // namespace mpile
