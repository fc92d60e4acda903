#include "io/history_writer.hpp"

#include "cases/case_composition.hpp"
#include "io/monitor_points.hpp"
#include "io/reserve_space.hpp"
#include "io/source_commit.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace mpile {

namespace {

// Room for what a write adds besides the series' chunks: groups, attributes, the file's own
// metadata.
constexpr std::size_t metadata_margin = 64 * 1024;

struct Units {
  std::string energy, force, moment;
};

Units units_of(GeometryMode mode) {
  if (mode == GeometryMode::axisymmetric) {
    return {"J/rad", "N/rad", "N m/rad"};
  }
  return {"J/m", "N/m", "N m/m"};
}

} // namespace

HistoryWriter::HistoryWriter(const std::string& path, const CaseSpec& spec, const Scene& scene,
                             int threads, std::size_t rows)
    : path_(path), rows_(rows), reopened_(rows > 0), last_flush_(std::chrono::steady_clock::now()),
      wall_start_(last_flush_) {
  if (reopened_) {
    write_header(spec, scene, threads, rows);
    return;
  }
  try {
    Hdf5File(path, Hdf5File::Mode::create).close();
    write_header(spec, scene, threads, rows);
  } catch (const std::exception&) {
    // A file without its series (no /time) is not a history: leave none rather than one that a
    // reader takes for a run that wrote nothing.
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
    throw;
  }
}

void HistoryWriter::write_header(const CaseSpec& spec, const Scene& scene, int threads,
                                 std::size_t rows) {
  const std::string& path = path_;
  // The series' headers and the case's text (twice: as written and resolved), with room to spare.
  Hdf5File file = open(16 * metadata_margin + 2 * (spec.text.size() + spec.resolved.size()));
  if (!reopened_) {
    file.set_attribute("/", "case_file", spec.file);
    file.set_attribute("/", "title", spec.title);
    file.set_attribute("/", "program", std::string("mpile ") + MPILE_VERSION);
    file.set_attribute("/", "commit", std::string(source_commit()));
    file.set_attribute("/", "geometry",
                       spec.mode == GeometryMode::axisymmetric
                           ? "axisymmetric: extensive quantities per radian"
                           : "plane strain: extensive quantities per metre");
  } else if (H5Aexists_by_name(file.id(), "/", "case_resolved", H5P_DEFAULT) > 0) {
    // A restart continues its own case's history, never one another run left in the directory;
    // the checkpoint has judged which changes (outputs, end criteria) the continuation makes.
    const std::vector<std::string> changed =
        restart_changes(file.string_attribute("/", "case_resolved"), spec.resolved, 0, path);
    if (!changed.empty()) {
      std::string list;
      for (const std::string& key : changed) {
        list += (list.empty() ? "" : ", ") + key;
      }
      const std::string before = H5Aexists_by_name(file.id(), "/", "restarts", H5P_DEFAULT) > 0
                                     ? file.string_attribute("/", "restarts") + "\n"
                                     : "";
      file.set_attribute("/", "restarts", before + "row " + std::to_string(rows) + ": " + list);
    }
  } else if (file.string_attribute("/", "case_text") != spec.text) {
    throw std::runtime_error(path + " is the history of another case (or " + spec.file +
                             " was edited since it was written)");
  }
  // Running again after a restart: the status the last part closed with ("interrupted at ...")
  // would tell a reader of the growing file that nothing more is coming.
  file.set_attribute("/", "status", "running");
  // The case that runs from here on: its file, its bases merged and --set applied.
  file.set_attribute("/", "case_text", spec.text);
  file.set_attribute("/", "case_resolved", spec.resolved);
  std::string overrides;
  for (const std::string& assignment : spec.overrides) {
    overrides += (overrides.empty() ? "" : "\n") + assignment;
  }
  file.set_attribute("/", "overrides", overrides);
  std::string bases;
  for (const std::string& base : spec.bases) {
    bases += (bases.empty() ? "" : "\n") + base;
  }
  file.set_attribute("/", "base_files", bases);
  file.set_attribute("/", "threads", static_cast<double>(threads));
  const Units u = units_of(scene.mode);
  series(file, "/time", "s");
  series(file, "/dt", "s");
  // Not "s since ...": CF readers (xarray) take a unit with "since" for a calendar date.
  series(file, "/wall_time", "s");
  file.set_attribute("/wall_time", "long_name",
                     "wall time since the run began (a restart carries it on)");
  if (reopened_) {
    const std::vector<double> wall = file.read_doubles("/wall_time");
    wall_offset_ =
        rows > 0 && rows <= wall.size() && std::isfinite(wall[rows - 1]) ? wall[rows - 1] : 0.0;
  }
  series(file, "/step", "-", Hdf5Series::Stored::integer);
  series(file, "/phase", "index into the case's [[phases]] and /phases",
         Hdf5Series::Stored::integer);
  for (const char* name :
       {"/energy/external_work", "/energy/kinetic", "/energy/elastic", "/energy/plastic",
        "/energy/damping", "/energy/contact", "/energy/transfer", "/energy/residual"}) {
    series(file, name, u.energy);
  }
  if (!scene.boundaries.absorbing.empty()) {
    // Only a scene with absorbing faces radiates.
    series(file, "/energy/radiated", u.energy);
  }
  if (has_coupled_water(scene)) {
    // Only a scene with coupled soil has water flowing through its skeleton.
    series(file, "/energy/drag", u.energy);
  }
  series(file, "/energy/relative_residual", "-");
  for (const NodeConstraint& c : scene.boundaries.constraints) {
    const std::string base = "/boundaries/" + dataset_name(c.name);
    series(file, base + "/F_r", u.force);
    series(file, base + "/F_y", u.force);
    if (has_theta(scene.mode)) {
      series(file, base + "/F_theta", u.force);
      series(file, base + "/M_theta", u.moment);
    }
  }
  // Contact: the force of the soil on each surface of each structure, and the rigid DOFs.
  const bool theta = has_theta(scene.mode);
  for (const ContactPair& pair : scene.contacts) {
    for (const std::string& surface : pair.surfaces) {
      const std::string base =
          "/reactions/" + dataset_name(pair.name) + "/" + dataset_name(surface);
      series(file, base + "/F_r", u.force);
      series(file, base + "/F_y", u.force);
      if (theta) {
        series(file, base + "/F_theta", u.force);
        series(file, base + "/M_theta", u.moment);
      }
      if (has_pore_water(scene)) {
        // The pore water's pressure on the surface and the rest, the effective stress's.
        for (const char* part : {"/pore_F_r", "/pore_F_y", "/effective_F_r", "/effective_F_y"}) {
          series(file, base + part, u.force);
        }
      }
    }
  }
  add_unit_resistances(file, spec, scene);
  add_monitors(file, spec, scene);
  for (const RigidBody& body : scene.rigid_bodies) {
    const std::string base = "/bodies/" + dataset_name(body.name);
    if (!theta) {
      series(file, base + "/u_r", "m");
      series(file, base + "/v_r", "m/s");
      series(file, base + "/contact_F_r", u.force);
      series(file, base + "/driving_F_r", u.force);
    }
    series(file, base + "/u_y", "m");
    // What stop criteria and snapshot_penetrations count: the body's total downward displacement.
    series(file, base + "/penetration", "m");
    series(file, base + "/v_y", "m/s");
    series(file, base + "/rotation", "rad");
    series(file, base + "/angular_velocity", "rad/s");
    series(file, base + "/contact_F_y", u.force);
    series(file, base + "/contact_torque", u.moment);
    series(file, base + "/driving_F_y", u.force);
    series(file, base + "/driving_torque", u.moment);
  }
  file.close();
}

Hdf5File HistoryWriter::open(std::size_t growth) const {
  reserve_space(path_, growth + metadata_margin);
  return Hdf5File(path_, Hdf5File::Mode::append);
}

void HistoryWriter::add_unit_resistances(Hdf5File& file, const CaseSpec& spec, const Scene& scene) {
  const std::string area_unit = scene.mode == GeometryMode::axisymmetric ? "m^2/rad" : "m^2/m";
  for (std::size_t p = 0; p < scene.contacts.size(); ++p) {
    const ContactPair& pair = scene.contacts[p];
    if (!pair.outline) {
      continue;
    }
    const std::vector<SurfaceAreas> areas =
        surface_areas(*pair.outline, pair.surfaces.size(), scene.mode);
    for (std::size_t q = 0; q < pair.surfaces.size(); ++q) {
      const std::string base =
          "/reactions/" + dataset_name(pair.name) + "/" + dataset_name(pair.surfaces[q]);
      if (!reopened_) {
        file.set_attribute(base, "plan_area", areas[q].plan);
        file.set_attribute(base, "side_area", areas[q].side);
        file.set_attribute(base, "area_unit", area_unit);
      }
      if (areas[q].plan > 0.0) {
        end_resistances_.push_back({base + "/unit_end_resistance", p, q, areas[q].plan});
        series(file, end_resistances_.back().dataset, "Pa");
      }
    }
    if (spec.output.cpt && spec.output.cpt->body == pair.name) {
      const auto index = [&](const std::string& name) {
        return static_cast<std::size_t>(
            std::find(pair.surfaces.begin(), pair.surfaces.end(), name) - pair.surfaces.begin());
      };
      // The reader checked both surfaces and their areas.
      const std::size_t cone = index(spec.output.cpt->cone);
      const std::size_t sleeve = index(spec.output.cpt->sleeve);
      cpt_ = {UnitResistance{"/cpt/q_c", p, cone, areas[cone].plan},
              UnitResistance{"/cpt/f_s", p, sleeve, areas[sleeve].side}};
      series(file, "/cpt/q_c", "Pa");
      series(file, "/cpt/f_s", "Pa");
      series(file, "/cpt/R_f", "-");
    }
  }
}

void HistoryWriter::add_monitors(Hdf5File& file, const CaseSpec& spec, const Scene& scene) {
  for (const MonitorSpec& spec_monitor : spec.output.monitors) {
    Monitor monitor;
    monitor.group = "/monitors/" + spec_monitor.name;
    if (spec_monitor.fixed) {
      monitor.fixed_point = spec_monitor.position;
    }
    const bool known = reopened_ && file.exists(monitor.group + "/r");
    if (known) {
      monitor.id = static_cast<std::int32_t>(file.number_attribute(monitor.group, "particle_id"));
      monitor.material =
          static_cast<std::uint16_t>(file.number_attribute(monitor.group, "material"));
    } else {
      monitor.id = monitored_particle(spec_monitor, scene);
      monitor.material = monitored_material(spec_monitor, scene, monitor.id);
    }
    const std::vector<MonitorQuantity> quantities = monitor_quantities(scene, monitor.material);
    for (const MonitorQuantity& q : quantities) {
      const std::string name = monitor.group + "/" + q.name;
      monitor.datasets.push_back(name);
      // On a restart a monitor new to the history starts with NaN rows (series() makes them).
      series(file, name, q.unit);
    }
    if (!known) {
      file.set_attribute(monitor.group, "particle_id", static_cast<double>(monitor.id));
      file.set_attribute(monitor.group, "material", static_cast<double>(monitor.material));
      file.set_attribute(monitor.group, "material_name", scene.material_names[monitor.material]);
      file.set_attribute(monitor.group, "followed_from_row", static_cast<double>(rows_));
      // A fixed monitor samples its named material, else that of the particle nearest its point
      // at the start (particle_id -1: it follows none).
      file.set_attribute(monitor.group, "fixed", spec_monitor.fixed ? 1.0 : 0.0);
      if (spec_monitor.position) {
        std::ostringstream position;
        position << "[" << (*spec_monitor.position)[0] << ", " << (*spec_monitor.position)[1]
                 << "] m";
        file.set_attribute(monitor.group, "position", position.str());
      }
    }
    monitors_.push_back(std::move(monitor));
  }
}

double HistoryWriter::UnitResistance::of(const Scene& scene) const {
  return scene.contacts[pair].surface_force[surface][1] / area;
}

Hdf5Series& HistoryWriter::series(Hdf5File& file, const std::string& name, const std::string& unit,
                                  Hdf5Series::Stored stored) {
  auto found = series_.find(name);
  if (found == series_.end()) {
    if (reopened_ && file.exists(name)) {
      found = series_.emplace(name, Hdf5Series(file, name, rows_)).first;
    } else if (reopened_) {
      // A series this version records and the one that began the history did not: its earlier
      // rows are NaN.
      found = series_.emplace(name, Hdf5Series(file, name, unit, stored)).first;
      file.attach_dimension_scale(name, "/time");
      for (std::size_t row = 0; row < rows_; ++row) {
        found->second.append(std::numeric_limits<double>::quiet_NaN());
      }
    } else {
      found = series_.emplace(name, Hdf5Series(file, name, unit, stored)).first;
      // Every series runs along /time: xarray and netCDF readers see one shared dimension.
      if (name == "/time") {
        file.make_dimension_scale(name, "time");
      } else {
        file.attach_dimension_scale(name, "/time");
      }
    }
    order_.push_back(name);
  }
  return found->second;
}

void HistoryWriter::record(const ExplicitSolver& solver, std::size_t phase,
                           const EnergyBalance& energy) {
  const Scene& scene = solver.scene();
  series_.at("/time").append(solver.time());
  series_.at("/dt").append(solver.last_time_step());
  series_.at("/wall_time")
      .append(
          wall_offset_ +
          std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count());
  series_.at("/step").append(static_cast<double>(solver.step_count()));
  series_.at("/phase").append(static_cast<double>(phase));
  series_.at("/energy/external_work").append(energy.external_work);
  series_.at("/energy/kinetic").append(energy.kinetic);
  series_.at("/energy/elastic").append(energy.elastic);
  series_.at("/energy/plastic").append(energy.plastic);
  series_.at("/energy/damping").append(energy.damping);
  series_.at("/energy/contact").append(energy.contact);
  series_.at("/energy/transfer").append(energy.transfer);
  series_.at("/energy/residual").append(energy.residual);
  if (!scene.boundaries.absorbing.empty()) {
    series_.at("/energy/radiated").append(energy.radiated);
  }
  if (has_coupled_water(scene)) {
    series_.at("/energy/drag").append(energy.drag);
  }
  series_.at("/energy/relative_residual").append(energy.relative_residual);
  for (const NodeConstraint& c : scene.boundaries.constraints) {
    const std::string base = "/boundaries/" + dataset_name(c.name);
    series_.at(base + "/F_r").append(c.reaction[0]);
    series_.at(base + "/F_y").append(c.reaction[1]);
    if (has_theta(scene.mode)) {
      series_.at(base + "/F_theta").append(c.reaction[2]);
      series_.at(base + "/M_theta").append(c.torque);
    }
  }
  const bool theta = has_theta(scene.mode);
  for (const ContactPair& pair : scene.contacts) {
    for (std::size_t q = 0; q < pair.surfaces.size(); ++q) {
      const std::string base =
          "/reactions/" + dataset_name(pair.name) + "/" + dataset_name(pair.surfaces[q]);
      series_.at(base + "/F_r").append(pair.surface_force[q][0]);
      series_.at(base + "/F_y").append(pair.surface_force[q][1]);
      if (theta) {
        series_.at(base + "/F_theta").append(pair.surface_force[q][2]);
        series_.at(base + "/M_theta").append(pair.surface_torque[q]);
      }
      if (has_pore_water(scene)) {
        const auto& pore = pair.surface_pore_force[q];
        series_.at(base + "/pore_F_r").append(pore[0]);
        series_.at(base + "/pore_F_y").append(pore[1]);
        series_.at(base + "/effective_F_r").append(pair.surface_force[q][0] - pore[0]);
        series_.at(base + "/effective_F_y").append(pair.surface_force[q][1] - pore[1]);
      }
    }
  }
  for (const UnitResistance& end : end_resistances_) {
    series_.at(end.dataset).append(end.of(scene));
  }
  if (cpt_) {
    const double q_c = (*cpt_)[0].of(scene);
    const double f_s = (*cpt_)[1].of(scene);
    series_.at("/cpt/q_c").append(q_c);
    series_.at("/cpt/f_s").append(f_s);
    // No ratio before the cone bears.
    series_.at("/cpt/R_f").append(q_c > 0.0 ? f_s / q_c : std::numeric_limits<double>::quiet_NaN());
  }
  for (const RigidBody& body : scene.rigid_bodies) {
    const std::string base = "/bodies/" + dataset_name(body.name);
    if (!theta) {
      series_.at(base + "/u_r").append(body.displacement[RIGID_X]);
      series_.at(base + "/v_r").append(body.velocity[RIGID_X]);
      series_.at(base + "/contact_F_r").append(body.contact[RIGID_X]);
      series_.at(base + "/driving_F_r").append(body.driving[RIGID_X]);
    }
    series_.at(base + "/u_y").append(body.displacement[RIGID_Y]);
    series_.at(base + "/penetration").append(-body.displacement[RIGID_Y]);
    series_.at(base + "/v_y").append(body.velocity[RIGID_Y]);
    series_.at(base + "/rotation").append(body.displacement[RIGID_ROTATION]);
    series_.at(base + "/angular_velocity").append(body.velocity[RIGID_ROTATION]);
    series_.at(base + "/contact_F_y").append(body.contact[RIGID_Y]);
    series_.at(base + "/contact_torque").append(body.contact[RIGID_ROTATION]);
    series_.at(base + "/driving_F_y").append(body.driving[RIGID_Y]);
    series_.at(base + "/driving_torque").append(body.driving[RIGID_ROTATION]);
  }
  for (const Monitor& monitor : monitors_) {
    const std::vector<double> values =
        monitor.fixed_point ? fixed_point_values(scene, *monitor.fixed_point, monitor.material)
                            : monitor_values(scene, monitor.id, monitor.material);
    for (std::size_t k = 0; k < values.size(); ++k) {
      series_.at(monitor.datasets[k]).append(values[k]);
    }
  }
  ++rows_;
  flush_if_due();
}

void HistoryWriter::phase_started(std::size_t index, const std::string& name, double start) {
  const std::string group = "/phases/" + std::to_string(index);
  Hdf5File file = open(name.size());
  file.parent_group(group + "/name");
  file.set_attribute(group, "name", name);
  file.set_attribute(group, "start", start);
  file.close();
}

void HistoryWriter::phase_ended(std::size_t index, double end, const std::string& why) {
  const std::string group = "/phases/" + std::to_string(index);
  Hdf5File file = open(why.size());
  file.parent_group(group + "/name");
  file.set_attribute(group, "end", end);
  file.set_attribute(group, "ended", why);
  file.close();
}

void HistoryWriter::flush_if_due() {
  if (std::chrono::steady_clock::now() - last_flush_ >= std::chrono::seconds(2)) {
    flush();
  }
}

std::size_t HistoryWriter::growth_bound() const {
  std::size_t bytes = 0;
  for (const auto& [name, series] : series_) {
    bytes += series.growth_bound();
  }
  return bytes;
}

void HistoryWriter::flush() {
  Hdf5File file = open(growth_bound());
  for (const std::string& name : order_) {
    series_.at(name).flush(file);
  }
  file.close();
  last_flush_ = std::chrono::steady_clock::now();
}

void HistoryWriter::close_after_failure(double wall_seconds, const std::string& status,
                                        const ResidualSummary& residual) {
  try {
    close(wall_seconds, status, residual);
    return;
  } catch (const NoRoomForOutput&) {
    // The rows since the last flush have no room: the file keeps the whole rows it has.
  }
  reserve_space(path_, status.size() + 4096); // the attributes' few hundred bytes, and their heap
  Hdf5File file(path_, Hdf5File::Mode::append);
  write_closing_attributes(file, wall_seconds, status, residual);
  file.close();
}

void HistoryWriter::close(double wall_seconds, const std::string& status,
                          const ResidualSummary& residual) {
  Hdf5File file = open(growth_bound() + status.size());
  for (const std::string& name : order_) {
    series_.at(name).flush(file);
  }
  write_closing_attributes(file, wall_seconds, status, residual);
  file.close();
}

void HistoryWriter::write_closing_attributes(Hdf5File& file, double wall_seconds,
                                             const std::string& status,
                                             const ResidualSummary& residual) const {
  // The whole run's, as /wall_time carries it across restarts (this process's alone would make a
  // restarted run look cheap in an error-against-run-time study).
  file.set_attribute("/", "wall_time", wall_offset_ + wall_seconds);
  file.set_attribute("/", "status", status);
  file.set_attribute("/", "energy_residual_final", residual.final);
  file.set_attribute("/", "energy_residual_peak", residual.peak);
  file.set_attribute("/", "energy_residual_peak_time", residual.peak_time);
}

} // namespace mpile
