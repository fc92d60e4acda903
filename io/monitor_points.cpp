#include "io/monitor_points.hpp"

#include "cases/case_error.hpp"
#include "engine/tensor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace mpile {

namespace {

std::size_t index_of(const Particles& p, std::int32_t id) {
  // A linear search: a few monitors per history row cost less than keeping an index map current
  // through every re-sort and split.
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.id[i] == id) {
      return i;
    }
  }
  return p.size();
}

} // namespace

std::int32_t monitored_particle(const MonitorSpec& monitor, const Scene& scene) {
  const Particles& p = scene.particles;
  const std::string where = monitor.where + ": ";
  if (monitor.fixed && !monitor.material.empty()) {
    return -1; // it reads the named material wherever that is; no particle marks its place
  }
  if (monitor.particle) {
    if (index_of(p, static_cast<std::int32_t>(*monitor.particle)) == p.size()) {
      throw CaseError(where + "no particle has id " + std::to_string(*monitor.particle) +
                      " (the case makes " + std::to_string(p.size()) +
                      " particles; ids are in the snapshots' id array)");
    }
    return static_cast<std::int32_t>(*monitor.particle);
  }
  const std::vector<char> rigid = scene.rigid_materials();
  const auto [r, y] = *monitor.position;
  std::size_t nearest = p.size();
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double d = std::hypot(p.r[i] - r, p.y[i] - y);
    if (rigid[p.material[i]] == 0 && d < best) {
      best = d;
      nearest = i;
    }
  }
  if (nearest == p.size() || best > 2.0 * std::hypot(p.half_r[nearest], p.half_y[nearest])) {
    std::ostringstream s;
    s << where << "no soil particle near position [" << r << ", " << y << "]";
    if (nearest < p.size()) {
      s << " (the nearest is " << best << " m away, at [" << p.r[nearest] << ", " << p.y[nearest]
        << "])";
    }
    throw CaseError(s.str());
  }
  return p.id[nearest];
}

std::uint16_t monitored_material(const MonitorSpec& monitor, const Scene& scene, std::int32_t id) {
  if (!monitor.material.empty()) {
    const auto& names = scene.material_names;
    return static_cast<std::uint16_t>(std::find(names.begin(), names.end(), monitor.material) -
                                      names.begin());
  }
  const Particles& p = scene.particles;
  return p.material[index_of(p, id)];
}

std::vector<MonitorQuantity> monitor_quantities(const Scene& scene, std::uint16_t material) {
  const bool theta = has_theta(scene.mode);
  std::vector<MonitorQuantity> q{{"r", "m"},   {"y", "m"},     {"u_r", "m"},
                                 {"u_y", "m"}, {"v_r", "m/s"}, {"v_y", "m/s"}};
  if (theta) {
    q.push_back({"u_theta", "m"});
    q.push_back({"v_theta", "m/s"});
  }
  const char* stress[] = {"sigma_rr", "sigma_yy",     "sigma_thth",
                          "sigma_ry", "sigma_ytheta", "sigma_rtheta"};
  for (int c = 0; c < (theta ? 6 : 4); ++c) {
    q.push_back({stress[c], "Pa"});
  }
  q.push_back({"p", "Pa"});
  q.push_back({"q", "Pa"});
  q.push_back({"volumetric_strain", "- (V/V0 - 1, expansion positive)"});
  for (const std::string& name : scene.materials[material]->state_names()) {
    q.push_back({name, "state variable of " + scene.material_names[material]});
  }
  return q;
}

namespace {

/// The quantities of particle i, in monitor_quantities' order.
std::vector<double> particle_values(const Scene& scene, std::size_t i, std::uint16_t material) {
  const Particles& p = scene.particles;
  const bool theta = has_theta(scene.mode);
  std::vector<double> v{p.r[i], p.y[i], p.r[i] - p.r0[i], p.y[i] - p.y0[i], p.v_r[i], p.v_y[i]};
  if (theta) {
    v.push_back(p.u_theta[i]);
    v.push_back(p.v_theta[i]);
  }
  const Material& model = *scene.materials[material];
  const Stress stress = model.reported_stress(p.stress[i]);
  for (int c = 0; c < (theta ? 6 : 4); ++c) {
    v.push_back(stress[static_cast<std::size_t>(c)]);
  }
  v.push_back(mean_pressure(stress));
  v.push_back(deviatoric_stress(stress));
  // The initial volume is the mass over the material's density (both per radian in axisymmetry).
  const double initial_volume = p.mass[i] / scene.materials[material]->density();
  v.push_back(p.volume[i] / initial_volume - 1.0);
  const std::size_t states = model.state_size();
  for (std::size_t s = 0; s < states; ++s) {
    v.push_back(model.reported_state(static_cast<int>(s),
                                     p.state[i * static_cast<std::size_t>(p.state_stride) + s]));
  }
  return v;
}

} // namespace

std::vector<double> monitor_values(const Scene& scene, std::int32_t id, std::uint16_t material) {
  const std::size_t i = index_of(scene.particles, id);
  if (i == scene.particles.size()) {
    return std::vector<double>(monitor_quantities(scene, material).size(),
                               std::numeric_limits<double>::quiet_NaN());
  }
  return particle_values(scene, i, material);
}

std::vector<double> fixed_point_values(const Scene& scene, std::array<double, 2> point,
                                       std::uint16_t material) {
  const Particles& p = scene.particles;
  const Grid& grid = scene.grid;
  // The tent of the grid cell the point lies in, one cell wide each way: the reach of the linear
  // shape functions, through which the solver itself sees the particles at a node there.
  const double reach_r = grid.r_axis().cell_size(grid.r_axis().locate(point[0]));
  const double reach_y = grid.y_axis().cell_size(grid.y_axis().locate(point[1]));
  std::vector<double> sum(monitor_quantities(scene, material).size(), 0.0);
  double weights = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double wr = 1.0 - std::abs(p.r[i] - point[0]) / reach_r;
    const double wy = 1.0 - std::abs(p.y[i] - point[1]) / reach_y;
    if (p.material[i] != material || wr <= 0.0 || wy <= 0.0) {
      continue;
    }
    // Volume-weighted, so that a particle stands for the soil it holds (a stretched one for more).
    const double w = p.volume[i] * wr * wy;
    const std::vector<double> v = particle_values(scene, i, material);
    for (std::size_t k = 0; k < v.size(); ++k) {
      sum[k] += w * v[k];
    }
    weights += w;
  }
  for (double& value : sum) {
    value = weights > 0.0 ? value / weights : std::numeric_limits<double>::quiet_NaN();
  }
  return sum;
}

} // namespace mpile
