#include "engine/absorbing_boundary.hpp"

#include "engine/scene.hpp"

#include <algorithm>
#include <cmath>

namespace mpile {

double along_face(const Grid& grid, const AbsorbingFace& face, std::size_t k) {
  const int node = face.nodes[k];
  return face_normal(face.face) == 0 ? grid.node_y(node) : grid.node_r(node);
}

std::vector<std::array<double, 2>> segment_weights(const Grid& grid, const AbsorbingFace& face,
                                                   int power) {
  std::vector<std::array<double, 2>> weights;
  if (face.nodes.size() < 2) {
    return weights;
  }
  weights.resize(face.nodes.size() - 1);
  const bool r_face = face_normal(face.face) == 0;
  const double face_r = r_face ? grid.node_r(face.nodes.front()) : 0.0;
  for (std::size_t j = 0; j + 1 < face.nodes.size(); ++j) {
    const double a0 = along_face(grid, face, j);
    const double a1 = along_face(grid, face, j + 1);
    const double length = a1 - a0;
    if (r_face) {
      // r is constant along an r face: each node takes half the segment.
      const double w = 0.5 * length * std::pow(face_r, power);
      weights[j] = {w, w};
      continue;
    }
    // Along a y face r is the coordinate: three-point Gauss integrates N r^power exactly for
    // power <= 4.
    constexpr double xi[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
    constexpr double w[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    std::array<double, 2> sum{0.0, 0.0};
    for (int g = 0; g < 3; ++g) {
      const double upper_share = 0.5 * (1.0 + xi[g]);
      const double r = a0 + upper_share * length;
      const double integrand = 0.5 * length * w[g] * std::pow(r, power);
      sum[0] += (1.0 - upper_share) * integrand;
      sum[1] += upper_share * integrand;
    }
    weights[j] = sum;
  }
  return weights;
}

void sample_face_impedance(const Scene& scene, AbsorbingFace& face) {
  const Grid& grid = scene.grid;
  const std::size_t segments = face.nodes.empty() ? 0 : face.nodes.size() - 1;
  face.edges.resize(face.nodes.size());
  for (std::size_t k = 0; k < face.nodes.size(); ++k) {
    face.edges[k] = along_face(grid, face, k);
  }
  std::vector<double> mass(segments, 0.0), p_sum(segments, 0.0), s_sum(segments, 0.0);
  // The row or column of cells along the face, and which cell index counts along it.
  const bool r_face = face_normal(face.face) == 0;
  const int beside = face.face == GridFace::r_min   ? 0
                     : face.face == GridFace::r_max ? grid.cells_r() - 1
                     : face.face == GridFace::y_min ? 0
                                                    : grid.cells_y() - 1;
  const Particles& p = scene.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int across = r_face ? p.cell_r[i] : p.cell_y[i];
    const int along = r_face ? p.cell_y[i] : p.cell_r[i];
    if (across != beside || along < 0 || static_cast<std::size_t>(along) >= segments) {
      continue;
    }
    const Material& material = *scene.materials[p.material[i]];
    if (material.is_rigid() || !(p.volume[i] > 0.0)) {
      continue;
    }
    const double* state =
        p.state.empty() ? nullptr : p.state.data() + i * static_cast<std::size_t>(p.state_stride);
    const double density = p.mass[i] / p.volume[i];
    const double m = material.constrained_modulus(p.stress[i], state);
    const double g = material.shear_modulus(p.stress[i], state);
    const auto j = static_cast<std::size_t>(along);
    mass[j] += p.mass[i];
    p_sum[j] += p.mass[i] * std::sqrt(density * m);
    s_sum[j] += p.mass[i] * std::sqrt(density * g);
  }
  face.p_impedance.assign(segments, 0.0);
  face.s_impedance.assign(segments, 0.0);
  for (std::size_t j = 0; j < segments; ++j) {
    if (mass[j] > 0.0) {
      face.p_impedance[j] = p_sum[j] / mass[j];
      face.s_impedance[j] = s_sum[j] / mass[j];
    }
  }
}

std::array<double, 2> segment_impedance(const Grid& grid, const AbsorbingFace& face,
                                        std::size_t k) {
  const double middle = 0.5 * (along_face(grid, face, k) + along_face(grid, face, k + 1));
  // The segment of the sampled profile that holds the midpoint (on a fixed grid, segment k).
  const auto upper = std::upper_bound(face.edges.begin(), face.edges.end(), middle);
  const std::size_t last = face.p_impedance.size() - 1;
  const std::size_t j =
      upper == face.edges.begin()
          ? 0
          : std::min(static_cast<std::size_t>(upper - face.edges.begin()) - 1, last);
  return {face.p_impedance[j], face.s_impedance[j]};
}

std::array<double, 3> holding_traction_now(const Grid& grid, const AbsorbingFace& face,
                                           std::size_t k) {
  const double a = along_face(grid, face, k);
  if (a == face.edges[k]) {
    return face.holding_traction[k]; // the node has not moved along the face
  }
  const auto upper = std::upper_bound(face.edges.begin(), face.edges.end(), a);
  if (upper == face.edges.begin()) {
    return face.holding_traction.front();
  }
  if (upper == face.edges.end()) {
    return face.holding_traction.back();
  }
  const auto j = static_cast<std::size_t>(upper - face.edges.begin());
  const double share = (a - face.edges[j - 1]) / (face.edges[j] - face.edges[j - 1]);
  std::array<double, 3> t{};
  for (std::size_t d = 0; d < 3; ++d) {
    t[d] = (1.0 - share) * face.holding_traction[j - 1][d] + share * face.holding_traction[j][d];
  }
  return t;
}

} // namespace mpile
