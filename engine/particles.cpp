#include "engine/particles.hpp"

#include "engine/parallel.hpp"

#include <array>

namespace mpile {

void Particles::add(double r_pos, double y_pos, double particle_mass, double particle_volume,
                    double half_r_size, double half_y_size, std::uint16_t material_index,
                    std::uint16_t body_index) {
  r.push_back(r_pos);
  y.push_back(y_pos);
  r0.push_back(r_pos);
  y0.push_back(y_pos);
  v_r.push_back(0.0);
  v_y.push_back(0.0);
  if (has_theta(mode)) {
    v_theta.push_back(0.0);
    u_theta.push_back(0.0);
  }
  mass.push_back(particle_mass);
  volume.push_back(particle_volume);
  half_r.push_back(half_r_size);
  half_y.push_back(half_y_size);
  stress.push_back(Stress{});
  state.resize(state.size() + static_cast<std::size_t>(state_stride), 0.0);
  id.push_back(next_id++);
  material.push_back(material_index);
  body.push_back(body_index);
  cell_r.push_back(-1);
  cell_y.push_back(-1);
  du_r.push_back(0.0);
  du_y.push_back(0.0);
}

namespace {

/// Every per-particle array of doubles with one value per particle (theta ones empty in plane
/// strain), so that copying, reordering and counting cannot miss one.
template <class P> auto scalar_fields(P& p) {
  return std::array{&p.r,       &p.y,    &p.r0,     &p.y0,     &p.v_r,    &p.v_y,  &p.v_theta,
                    &p.u_theta, &p.mass, &p.volume, &p.half_r, &p.half_y, &p.du_r, &p.du_y};
}

template <class T>
void permute_array(std::vector<T>& values, std::span<const std::int32_t> order, std::size_t width) {
  if (values.empty()) {
    return;
  }
  std::vector<T> sorted(order.size() * width);
  parallel_for(order.size(), [&](std::size_t k) {
    const auto from = static_cast<std::size_t>(order[k]) * width;
    for (std::size_t j = 0; j < width; ++j) {
      sorted[k * width + j] = values[from + j];
    }
  });
  values.swap(sorted);
}

} // namespace

std::size_t Particles::duplicate(std::size_t i) {
  for (std::vector<double>* field : scalar_fields(*this)) {
    if (!field->empty()) {
      field->push_back((*field)[i]);
    }
  }
  stress.push_back(stress[i]);
  const auto stride = static_cast<std::size_t>(state_stride);
  for (std::size_t k = 0; k < stride; ++k) {
    state.push_back(state[i * stride + k]);
  }
  id.push_back(next_id++);
  material.push_back(material[i]);
  body.push_back(body[i]);
  cell_r.push_back(cell_r[i]);
  cell_y.push_back(cell_y[i]);
  return r.size() - 1;
}

void Particles::permute(std::span<const std::int32_t> order) {
  for (std::vector<double>* field : scalar_fields(*this)) {
    permute_array(*field, order, 1);
  }
  permute_array(stress, order, 1);
  permute_array(state, order, static_cast<std::size_t>(state_stride));
  permute_array(id, order, 1);
  permute_array(material, order, 1);
  permute_array(body, order, 1);
  permute_array(cell_r, order, 1);
  permute_array(cell_y, order, 1);
}

std::size_t Particles::bytes() const {
  std::size_t total = 0;
  for (const std::vector<double>* field : scalar_fields(*this)) {
    total += field->capacity() * sizeof(double);
  }
  total += state.capacity() * sizeof(double);
  total += stress.capacity() * sizeof(Stress);
  total += (material.capacity() + body.capacity()) * sizeof(std::uint16_t);
  total += (id.capacity() + cell_r.capacity() + cell_y.capacity()) * sizeof(std::int32_t);
  return total;
}

double cross_section(const Particles& p, std::uint16_t body, double at) {
  double area = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] == body && p.y[i] - p.half_y[i] <= at && at < p.y[i] + p.half_y[i]) {
      area += p.volume[i] / (2.0 * p.half_y[i]);
    }
  }
  return area;
}

} // namespace mpile
