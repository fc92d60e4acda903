#include "io/history_writer.hpp"

#include <cctype>

namespace mpile {

std::string dataset_name(const std::string& name) {
  std::string out;
  for (const char c : name) {
    out += std::isalnum(static_cast<unsigned char>(c)) != 0 ? c : '_';
  }
  return out;
}

namespace {

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
    : rows_(rows), reopened_(rows > 0), last_flush_(std::chrono::steady_clock::now()) {
  file_ =
      std::make_unique<Hdf5File>(path, reopened_ ? Hdf5File::Mode::append : Hdf5File::Mode::create);
  if (!reopened_) {
    file_->set_attribute("/", "case_file", spec.file);
    file_->set_attribute("/", "case_text", spec.text);
    file_->set_attribute("/", "title", spec.title);
    file_->set_attribute("/", "program", std::string("mpile ") + MPILE_VERSION);
    file_->set_attribute("/", "geometry",
                         spec.mode == GeometryMode::axisymmetric
                             ? "axisymmetric: extensive quantities per radian"
                             : "plane strain: extensive quantities per metre");
    file_->set_attribute("/", "status", "running");
  }
  file_->set_attribute("/", "threads", static_cast<double>(threads));
  const Units u = units_of(scene.mode);
  series("/time", "s");
  series("/dt", "s");
  series("/step", "-");
  series("/phase", "index into the case's [[phases]]");
  for (const char* name :
       {"/energy/external_work", "/energy/kinetic", "/energy/elastic", "/energy/plastic",
        "/energy/damping", "/energy/contact", "/energy/residual"}) {
    series(name, u.energy);
  }
  series("/energy/relative_residual", "-");
  for (const NodeConstraint& c : scene.boundaries.constraints) {
    const std::string base = "/boundaries/" + dataset_name(c.name);
    series(base + "/F_r", u.force);
    series(base + "/F_y", u.force);
    if (has_theta(scene.mode)) {
      series(base + "/F_theta", u.force);
      series(base + "/M_theta", u.moment);
    }
  }
  // Contact: the force of the soil on each surface of each structure, and the rigid DOFs.
  const bool theta = has_theta(scene.mode);
  for (const ContactPair& pair : scene.contacts) {
    for (const std::string& surface : pair.surfaces) {
      const std::string base =
          "/reactions/" + dataset_name(pair.name) + "/" + dataset_name(surface);
      series(base + "/F_r", u.force);
      series(base + "/F_y", u.force);
      if (theta) {
        series(base + "/F_theta", u.force);
        series(base + "/M_theta", u.moment);
      }
    }
  }
  for (const RigidBody& body : scene.rigid_bodies) {
    const std::string base = "/bodies/" + dataset_name(body.name);
    if (!theta) {
      series(base + "/u_r", "m");
      series(base + "/v_r", "m/s");
      series(base + "/contact_F_r", u.force);
      series(base + "/driving_F_r", u.force);
    }
    series(base + "/u_y", "m");
    series(base + "/v_y", "m/s");
    series(base + "/rotation", "rad");
    series(base + "/angular_velocity", "rad/s");
    series(base + "/contact_F_y", u.force);
    series(base + "/contact_torque", u.moment);
    series(base + "/driving_F_y", u.force);
    series(base + "/driving_torque", u.moment);
  }
  file_->flush();
}

Hdf5Series& HistoryWriter::series(const std::string& name, const std::string& unit) {
  auto found = series_.find(name);
  if (found == series_.end()) {
    found = reopened_ ? series_.emplace(name, Hdf5Series(*file_, name, rows_)).first
                      : series_.emplace(name, Hdf5Series(*file_, name, unit)).first;
    order_.push_back(name);
  }
  return found->second;
}

EnergyBalance HistoryWriter::record(const ExplicitSolver& solver, std::size_t phase) {
  const Scene& scene = solver.scene();
  series_.at("/time").append(solver.time());
  series_.at("/dt").append(solver.last_time_step());
  series_.at("/step").append(static_cast<double>(solver.step_count()));
  series_.at("/phase").append(static_cast<double>(phase));
  const EnergyBalance energy = solver.energy_balance();
  series_.at("/energy/external_work").append(energy.external_work);
  series_.at("/energy/kinetic").append(energy.kinetic);
  series_.at("/energy/elastic").append(energy.elastic);
  series_.at("/energy/plastic").append(energy.plastic);
  series_.at("/energy/damping").append(energy.damping);
  series_.at("/energy/contact").append(energy.contact);
  series_.at("/energy/residual").append(energy.residual);
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
    }
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
    series_.at(base + "/v_y").append(body.velocity[RIGID_Y]);
    series_.at(base + "/rotation").append(body.displacement[RIGID_ROTATION]);
    series_.at(base + "/angular_velocity").append(body.velocity[RIGID_ROTATION]);
    series_.at(base + "/contact_F_y").append(body.contact[RIGID_Y]);
    series_.at(base + "/contact_torque").append(body.contact[RIGID_ROTATION]);
    series_.at(base + "/driving_F_y").append(body.driving[RIGID_Y]);
    series_.at(base + "/driving_torque").append(body.driving[RIGID_ROTATION]);
  }
  ++rows_;
  flush_if_due();
  return energy;
}

void HistoryWriter::flush_if_due() {
  const auto now = std::chrono::steady_clock::now();
  if (now - last_flush_ < std::chrono::seconds(2)) {
    return;
  }
  for (const std::string& name : order_) {
    series_.at(name).flush();
  }
  file_->flush();
  last_flush_ = now;
}

void HistoryWriter::close(double wall_seconds, const std::string& status,
                          const ResidualSummary& residual) {
  for (const std::string& name : order_) {
    series_.at(name).flush();
  }
  file_->set_attribute("/", "wall_time", wall_seconds);
  file_->set_attribute("/", "status", status);
  file_->set_attribute("/", "energy_residual_final", residual.final);
  file_->set_attribute("/", "energy_residual_peak", residual.peak);
  file_->set_attribute("/", "energy_residual_peak_time", residual.peak_time);
  file_->flush();
}

} // namespace mpile
