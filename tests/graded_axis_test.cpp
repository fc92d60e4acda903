#include "engine/graded_axis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace mpile {
namespace {

// Brute-force reference for locate(): the last node at or below x.
int locate_by_search(const GradedAxis& axis, double x) {
  if (x < axis.start() || x >= axis.end()) {
    return -1;
  }
  int c = 0;
  while (c + 1 < axis.cell_count() && axis.node(c + 1) <= x) {
    ++c;
  }
  return c;
}

TEST(GradedAxis, ZonesGiveTheirCellSizes) {
  const AxisZone zones[] = {{0.0, 0.5, 10}, {0.5, 2.0, 3}, {2.0, 2.1, 4}};
  const GradedAxis axis(zones);
  ASSERT_EQ(axis.cell_count(), 17);
  EXPECT_DOUBLE_EQ(axis.cell_size(0), 0.05);
  EXPECT_DOUBLE_EQ(axis.cell_size(10), 0.5);
  EXPECT_NEAR(axis.cell_size(16), 0.025, 1e-15);
  EXPECT_NEAR(axis.min_cell_size(), 0.025, 1e-15);
  EXPECT_DOUBLE_EQ(axis.end(), 2.1);
}

TEST(GradedAxis, LocateMatchesSearchEverywhereIncludingNodesAndEdges) {
  const AxisZone zones[] = {{-1.0, 0.0, 3}, {0.0, 0.3, 30}, {0.3, 5.0, 7}};
  const GradedAxis axis(zones);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> x(-1.5, 5.5);
  for (int k = 0; k < 100000; ++k) {
    const double point = x(random);
    ASSERT_EQ(axis.locate(point), locate_by_search(axis, point)) << "x = " << point;
  }
  for (int i = 0; i < axis.node_count(); ++i) {
    ASSERT_EQ(axis.locate(axis.node(i)), locate_by_search(axis, axis.node(i))) << "node " << i;
    const double below = std::nextafter(axis.node(i), -1e9);
    ASSERT_EQ(axis.locate(below), locate_by_search(axis, below)) << "below node " << i;
  }
  EXPECT_EQ(axis.locate(5.0), -1);
  EXPECT_EQ(axis.locate(std::nan("")), -1);
}

TEST(GradedAxis, ATinyCellBesideAHugeZoneLocatesWithoutAHugeTable) {
  // A lookup sized by extent over the smallest cell would be 1e14 buckets here (a mistyped zone
  // end took 15 GB); the capped table still finds every point's cell.
  const AxisZone zones[] = {{0.0, 1e-6, 1}, {1e-6, 0.06, 4}, {0.06, 1e8, 1000}};
  const GradedAxis axis(zones);
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> exponent(-7.0, 8.0);
  for (int k = 0; k < 20000; ++k) {
    const double point = std::pow(10.0, exponent(random));
    ASSERT_EQ(axis.locate(point), locate_by_search(axis, point)) << "x = " << point;
  }
  for (int i = 0; i < axis.node_count(); ++i) {
    ASSERT_EQ(axis.locate(axis.node(i)), locate_by_search(axis, axis.node(i))) << "node " << i;
  }
}

TEST(GradedAxis, MovedNodesRebuildTheLookup) {
  GradedAxis axis = GradedAxis::uniform(0.0, 1.0, 4);
  axis.set_nodes({0.0, 0.1, 0.15, 0.9, 1.0});
  EXPECT_EQ(axis.locate(0.12), 1);
  EXPECT_EQ(axis.locate(0.5), 2);
  EXPECT_NEAR(axis.min_cell_size(), 0.05, 1e-15);
}

TEST(GradedAxis, RejectsBadZonesWithAReason) {
  const AxisZone gap[] = {{0.0, 1.0, 2}, {1.5, 2.0, 2}};
  EXPECT_THROW(
      {
        try {
          GradedAxis axis(gap);
        } catch (const std::invalid_argument& e) {
          EXPECT_NE(std::string(e.what()).find("zone 1"), std::string::npos) << e.what();
          throw;
        }
      },
      std::invalid_argument);
  const AxisZone zero_cells[] = {{0.0, 1.0, 0}};
  EXPECT_THROW(GradedAxis{zero_cells}, std::invalid_argument);
  const AxisZone backwards[] = {{1.0, 0.0, 3}};
  EXPECT_THROW(GradedAxis{backwards}, std::invalid_argument);
  GradedAxis axis = GradedAxis::uniform(0.0, 1.0, 2);
  EXPECT_THROW(axis.set_nodes({0.0, 0.6, 0.5}), std::invalid_argument);
}

} // namespace
} // namespace mpile
