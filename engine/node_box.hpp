#pragma once

#include "engine/parallel.hpp"

#include <algorithm>
#include <cstddef>

namespace mpile {

/// A rectangle of grid nodes, [r_begin, r_end) x [y_begin, y_end) in node columns and rows, with
/// nodes numbered r-fastest (node = ir + nodes_r * iy). A contact structure's field is confined to
/// one (NodeField::reach), so that its passes cost in proportion to the structure, not the grid.
struct NodeBox {
  int r_begin = 0, r_end = 0;
  int y_begin = 0, y_end = 0;

  bool empty() const { return r_end <= r_begin || y_end <= y_begin; }
  std::size_t count() const {
    return empty() ? 0 : static_cast<std::size_t>(r_end - r_begin) * (y_end - y_begin);
  }
  bool contains(int ir, int iy) const {
    return ir >= r_begin && ir < r_end && iy >= y_begin && iy < y_end;
  }
  bool contains_node(std::size_t node, int nodes_r) const {
    if (empty()) {
      return false;
    }
    const auto n = static_cast<int>(node);
    return contains(n % nodes_r, n / nodes_r);
  }
  bool intersects(const NodeBox& other) const {
    return !empty() && !other.empty() && r_begin < other.r_end && other.r_begin < r_end &&
           y_begin < other.y_end && other.y_begin < y_end;
  }
  /// The smallest box holding both.
  static NodeBox hull(const NodeBox& a, const NodeBox& b) {
    if (a.empty()) {
      return b;
    }
    if (b.empty()) {
      return a;
    }
    return {std::min(a.r_begin, b.r_begin), std::max(a.r_end, b.r_end),
            std::min(a.y_begin, b.y_begin), std::max(a.y_end, b.y_end)};
  }
  bool operator==(const NodeBox&) const = default;

  /// f(node) for the k-th to (k_end - 1)-th nodes of the box, row by row: one division for the
  /// whole range, so that a parallel loop over count() can hand out chunks of it.
  template <class F> void visit(std::size_t k, std::size_t k_end, int nodes_r, F&& f) const {
    if (k >= k_end) {
      return;
    }
    const auto width = static_cast<std::size_t>(r_end - r_begin);
    if (r_begin == 0 && r_end == nodes_r) {
      // Whole rows: one contiguous range of nodes.
      const std::size_t first = static_cast<std::size_t>(nodes_r) * y_begin;
      for (; k != k_end; ++k) {
        f(first + k);
      }
      return;
    }
    int ir = r_begin + static_cast<int>(k % width);
    int iy = y_begin + static_cast<int>(k / width);
    for (; k != k_end; ++k) {
      f(static_cast<std::size_t>(ir + nodes_r * iy));
      if (++ir == r_end) {
        ir = r_begin;
        ++iy;
      }
    }
  }
};

/// f(node) for every node of the box, in parallel.
template <class F> void parallel_for_box(const NodeBox& box, int nodes_r, F&& f) {
  parallel_for_chunks(
      box.count(), [&](std::size_t begin, std::size_t end) { box.visit(begin, end, nodes_r, f); });
}

} // namespace mpile
