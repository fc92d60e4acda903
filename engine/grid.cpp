#include "engine/grid.hpp"

#include <algorithm>

namespace mpile {

Grid::Grid(GradedAxis r_axis, GradedAxis y_axis)
    : r_axis_(std::move(r_axis)), y_axis_(std::move(y_axis)) {
  const auto count = static_cast<std::size_t>(nodes_r()) * static_cast<std::size_t>(nodes_y());
  nodes.assign(count, GridNode{});
  constrained.assign(count, 0);
  water_held.assign(count, 0);
  update_cell_sizes();
}

int Grid::add_structure_field() {
  NodeField field;
  field.nodes.assign(nodes.size(), GridNode{});
  field.constrained.assign(nodes.size(), 0);
  // The whole grid until the particles have been binned and the reach narrowed to them.
  field.reach = {0, nodes_r(), 0, nodes_y()};
  field.held = field.reach;
  structure_fields.push_back(std::move(field));
  return field_count() - 1;
}

void Grid::set_y_nodes(std::vector<double> y_nodes) {
  y_axis_.set_nodes(std::move(y_nodes));
  update_cell_sizes();
}

void Grid::update_cell_sizes() {
  inverse_size_r_.resize(static_cast<std::size_t>(cells_r()));
  for (int c = 0; c < cells_r(); ++c) {
    inverse_size_r_[static_cast<std::size_t>(c)] = 1.0 / r_axis_.cell_size(c);
  }
  inverse_size_y_.resize(static_cast<std::size_t>(cells_y()));
  for (int c = 0; c < cells_y(); ++c) {
    inverse_size_y_[static_cast<std::size_t>(c)] = 1.0 / y_axis_.cell_size(c);
  }
}

} // namespace mpile
