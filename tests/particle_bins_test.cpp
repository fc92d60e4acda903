#include "engine/particle_bins.hpp"

#include <gtest/gtest.h>

#include <mutex>
#include <random>
#include <set>

namespace mpile {
namespace {

// Nodes touched by the cells of a block (bilinear: a cell touches its four corner nodes).
std::set<std::pair<int, int>> nodes_of_block(const ParticleBins& bins, int block, int cells_r,
                                             int cells_y) {
  std::set<std::pair<int, int>> nodes;
  const auto [cr0, cy0] = bins.block_origin(block);
  for (int cy = cy0; cy < std::min(cy0 + bins.block_cells(), cells_y); ++cy) {
    for (int cr = cr0; cr < std::min(cr0 + bins.block_cells(), cells_r); ++cr) {
      for (int b = 0; b < 2; ++b) {
        for (int a = 0; a < 2; ++a) {
          nodes.insert({cr + a, cy + b});
        }
      }
    }
  }
  return nodes;
}

struct RandomCells {
  std::vector<std::int32_t> r, y;
};

RandomCells random_cells(std::size_t n, int cells_r, int cells_y, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> cr(0, cells_r - 1), cy(0, cells_y - 1);
  RandomCells cells;
  for (std::size_t i = 0; i < n; ++i) {
    cells.r.push_back(cr(random));
    cells.y.push_back(cy(random));
  }
  return cells;
}

TEST(ParticleBins, BlocksOfOneColorShareNoNode) {
  for (const int block_cells : {1, 2, 3, 8}) {
    constexpr int cells_r = 23, cells_y = 17;
    ParticleBins bins;
    bins.configure(cells_r, cells_y, block_cells);
    // One particle per cell, so that every block is non-empty.
    RandomCells cells;
    for (int cy = 0; cy < cells_y; ++cy) {
      for (int cr = 0; cr < cells_r; ++cr) {
        cells.r.push_back(cr);
        cells.y.push_back(cy);
      }
    }
    bins.rebuild(cells.r, cells.y);
    std::vector<int> visits(static_cast<std::size_t>(bins.block_count()), 0);
    std::mutex guard;
    bins.for_each_block_colored([&](int block, std::span<const std::int32_t>) {
      std::lock_guard lock(guard);
      ++visits[static_cast<std::size_t>(block)];
    });
    for (int v : visits) {
      EXPECT_EQ(v, 1); // every block exactly once
    }
    // The colouring rule itself: same parity in both block indices means same colour.
    const int blocks_r = (cells_r + block_cells - 1) / block_cells;
    for (int a = 0; a < bins.block_count(); ++a) {
      for (int b = a + 1; b < bins.block_count(); ++b) {
        const bool same_color =
            (a % blocks_r) % 2 == (b % blocks_r) % 2 && (a / blocks_r) % 2 == (b / blocks_r) % 2;
        if (!same_color) {
          continue;
        }
        const auto na = nodes_of_block(bins, a, cells_r, cells_y);
        const auto nb = nodes_of_block(bins, b, cells_r, cells_y);
        for (const auto& node : na) {
          ASSERT_EQ(nb.count(node), 0u)
              << "blocks " << a << " and " << b << " of one colour share a node";
        }
      }
    }
  }
}

TEST(ParticleBins, RebuildIsAStableSortByBlock) {
  constexpr int cells_r = 40, cells_y = 30;
  const RandomCells cells = random_cells(50000, cells_r, cells_y, 3);
  ParticleBins bins;
  bins.configure(cells_r, cells_y, 4);
  bins.rebuild(cells.r, cells.y);
  std::size_t total = 0;
  for (int block = 0; block < bins.block_count(); ++block) {
    const auto particles = bins.particles_in(block);
    total += particles.size();
    for (std::size_t k = 0; k < particles.size(); ++k) {
      const auto p = static_cast<std::size_t>(particles[k]);
      ASSERT_EQ(bins.block_of(cells.r[p], cells.y[p]), block);
      if (k > 0) {
        ASSERT_LT(particles[k - 1], particles[k]); // stable: index order within a block
      }
    }
  }
  EXPECT_EQ(total, cells.r.size());
}

TEST(ParticleBins, CellSortedOrderSortsWithinBlocks) {
  constexpr int cells_r = 20, cells_y = 20;
  const RandomCells cells = random_cells(8000, cells_r, cells_y, 5);
  ParticleBins bins;
  bins.configure(cells_r, cells_y, 8);
  bins.rebuild(cells.r, cells.y);
  const auto order = bins.cell_sorted_order(cells.r, cells.y);
  ASSERT_EQ(order.size(), cells.r.size());
  std::vector<int> seen(order.size(), 0);
  for (std::size_t k = 0; k < order.size(); ++k) {
    ++seen[static_cast<std::size_t>(order[k])];
  }
  for (const int s : seen) {
    ASSERT_EQ(s, 1); // a permutation
  }
  auto key = [&](std::int32_t p) {
    const auto q = static_cast<std::size_t>(p);
    const int block = bins.block_of(cells.r[q], cells.y[q]);
    const auto [cr0, cy0] = bins.block_origin(block);
    return std::tuple(block, (cells.r[q] - cr0) + 8 * (cells.y[q] - cy0), p);
  };
  for (std::size_t k = 1; k < order.size(); ++k) {
    ASSERT_LT(key(order[k - 1]), key(order[k]));
  }
}

} // namespace
} // namespace mpile
