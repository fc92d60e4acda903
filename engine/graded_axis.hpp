#pragma once

#include <span>
#include <vector>

namespace mpile {

/// A stretch of one grid direction divided into cells of equal size.
struct AxisZone {
  double start = 0.0;
  double end = 0.0;
  int cells = 0;
};

/// Node coordinates along one grid direction, graded by zones (fine at a pile wall, coarse far
/// away), with O(1) lookup of the cell that holds a coordinate: a table of buckets no larger than
/// the smallest cell maps a bucket to the first cell it touches, and at most one step corrects it.
class GradedAxis {
public:
  GradedAxis() = default;
  /// Zones must be contiguous (each starts where the previous ends), increasing, with cells > 0.
  /// Throws std::invalid_argument naming the zone and what is wrong.
  explicit GradedAxis(std::span<const AxisZone> zones);
  static GradedAxis uniform(double start, double end, int cells);

  int cell_count() const { return static_cast<int>(nodes_.size()) - 1; }
  int node_count() const { return static_cast<int>(nodes_.size()); }
  double node(int i) const { return nodes_[static_cast<std::size_t>(i)]; }
  double cell_size(int c) const { return node(c + 1) - node(c); }
  double start() const { return nodes_.front(); }
  double end() const { return nodes_.back(); }
  double min_cell_size() const { return min_cell_size_; }
  /// Half the smallest of cell c and its neighbours: the largest half-size a GIMP domain centred
  /// in cell c may have and still span at most two cells.
  double domain_reach(int c) const { return domain_reach_[static_cast<std::size_t>(c)]; }
  std::span<const double> nodes() const { return nodes_; }

  /// Index c of the cell with node(c) <= x < node(c + 1), or -1 when x lies outside [start, end).
  int locate(double x) const {
    if (!(x >= nodes_.front() && x < nodes_.back())) {
      return -1;
    }
    const auto bucket = static_cast<std::size_t>((x - nodes_.front()) * inverse_bucket_size_);
    int c = first_cell_of_bucket_[bucket < first_cell_of_bucket_.size()
                                      ? bucket
                                      : first_cell_of_bucket_.size() - 1];
    // Rounding at a bucket edge can put x one cell off either way.
    while (x < nodes_[static_cast<std::size_t>(c)]) {
      --c;
    }
    while (x >= nodes_[static_cast<std::size_t>(c) + 1]) {
      ++c;
    }
    return c;
  }

  /// Replaces the node coordinates (the moving mesh); they must stay strictly increasing.
  void set_nodes(std::vector<double> nodes);

private:
  void build_lookup();

  std::vector<double> nodes_;
  std::vector<int> first_cell_of_bucket_;
  std::vector<double> domain_reach_;
  double inverse_bucket_size_ = 0.0;
  double min_cell_size_ = 0.0;
};

} // namespace mpile
