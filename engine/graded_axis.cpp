#include "engine/graded_axis.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace mpile {

GradedAxis::GradedAxis(std::span<const AxisZone> zones) {
  if (zones.empty()) {
    throw std::invalid_argument("an axis needs at least one zone");
  }
  std::vector<double> nodes{zones.front().start};
  for (std::size_t z = 0; z < zones.size(); ++z) {
    const AxisZone& zone = zones[z];
    const std::string where = "zone " + std::to_string(z);
    if (zone.cells <= 0) {
      throw std::invalid_argument(where + ": cells must be positive, got " +
                                  std::to_string(zone.cells));
    }
    if (!(zone.end > zone.start)) {
      throw std::invalid_argument(where + ": end must be greater than start");
    }
    // Zones must abut; a gap or overlap would silently change cell sizes.
    if (std::abs(zone.start - nodes.back()) > 1e-12 * std::max(1.0, std::abs(zone.start))) {
      throw std::invalid_argument(where + ": starts at " + std::to_string(zone.start) +
                                  " but the previous zone ends at " + std::to_string(nodes.back()));
    }
    const double h = (zone.end - zone.start) / zone.cells;
    for (int c = 1; c < zone.cells; ++c) {
      nodes.push_back(zone.start + c * h);
    }
    nodes.push_back(zone.end);
  }
  set_nodes(std::move(nodes));
}

GradedAxis GradedAxis::uniform(double start, double end, int cells) {
  const AxisZone zone{start, end, cells};
  return GradedAxis(std::span<const AxisZone>(&zone, 1));
}

void GradedAxis::set_nodes(std::vector<double> nodes) {
  if (nodes.size() < 2) {
    throw std::invalid_argument("an axis needs at least two nodes");
  }
  for (std::size_t i = 1; i < nodes.size(); ++i) {
    if (!(nodes[i] > nodes[i - 1])) {
      throw std::invalid_argument("axis nodes must be strictly increasing (node " +
                                  std::to_string(i) + ")");
    }
  }
  nodes_ = std::move(nodes);
  build_lookup();
}

void GradedAxis::build_lookup() {
  min_cell_size_ = cell_size(0);
  for (int c = 1; c < cell_count(); ++c) {
    min_cell_size_ = std::min(min_cell_size_, cell_size(c));
  }
  domain_reach_.resize(static_cast<std::size_t>(cell_count()));
  for (int c = 0; c < cell_count(); ++c) {
    double smallest = cell_size(c);
    if (c > 0) {
      smallest = std::min(smallest, cell_size(c - 1));
    }
    if (c + 1 < cell_count()) {
      smallest = std::min(smallest, cell_size(c + 1));
    }
    domain_reach_[static_cast<std::size_t>(c)] = 0.5 * smallest;
  }
  // Buckets of at most the smallest cell size: a bucket then spans at most two cells, so locate()
  // needs at most one correction step (the loop there also absorbs rounding at bucket edges).
  // The table is capped at 64 buckets per cell: a grid whose smallest cell is tiny against its
  // extent (a mistyped zone) then walks a few cells more in locate() instead of allocating
  // gigabytes here; ordinary graded grids stay far below the cap.
  const double length = end() - start();
  const double wanted = std::ceil(length / min_cell_size_) + 1.0;
  const double cap = 64.0 * cell_count() + 1024.0;
  const auto buckets = static_cast<std::size_t>(std::min(wanted, cap));
  inverse_bucket_size_ = static_cast<double>(buckets) / length;
  first_cell_of_bucket_.assign(buckets, 0);
  int c = 0;
  for (std::size_t b = 0; b < buckets; ++b) {
    const double x = start() + static_cast<double>(b) / inverse_bucket_size_;
    while (c + 1 < cell_count() && x >= node(c + 1)) {
      ++c;
    }
    first_cell_of_bucket_[b] = c;
  }
}

} // namespace mpile
