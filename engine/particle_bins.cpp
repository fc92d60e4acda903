#include "engine/particle_bins.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace mpile {

namespace {

// The chunking of the counting sort depends on the particle count only, never on the thread count.
constexpr std::size_t max_chunks = 64;
constexpr std::size_t min_chunk_size = 4096;

} // namespace

void ParticleBins::configure(int cells_r, int cells_y, int block_cells) {
  if (block_cells < 1 || block_cells > max_block_cells) {
    throw std::invalid_argument("block size must be between 1 and 16 cells");
  }
  block_cells_ = block_cells;
  blocks_r_ = (cells_r + block_cells - 1) / block_cells;
  blocks_y_ = (cells_y + block_cells - 1) / block_cells;
  block_start_.assign(static_cast<std::size_t>(block_count()) + 1, 0);
}

void ParticleBins::rebuild(std::span<const std::int32_t> cell_r,
                           std::span<const std::int32_t> cell_y) {
  const std::size_t n = cell_r.size();
  const auto blocks = static_cast<std::size_t>(block_count());
  const std::size_t chunks = std::clamp<std::size_t>(n / min_chunk_size, 1, max_chunks);
  const std::size_t chunk_size = (n + chunks - 1) / chunks;

  // Histogram per chunk; counts[c * blocks + b].
  std::vector<std::int32_t> counts(chunks * blocks, 0);
  parallel_for(chunks, [&](std::size_t c) {
    std::int32_t* count = counts.data() + c * blocks;
    const std::size_t end = std::min(n, (c + 1) * chunk_size);
    for (std::size_t p = c * chunk_size; p < end; ++p) {
      ++count[block_of(cell_r[p], cell_y[p])];
    }
  });

  // Exclusive scan, block-major then chunk: offsets where each chunk writes its particles of a
  // block, so particles of a block stay in index order (a stable sort).
  std::int32_t running = 0;
  for (std::size_t b = 0; b < blocks; ++b) {
    block_start_[b] = running;
    for (std::size_t c = 0; c < chunks; ++c) {
      const std::int32_t count = counts[c * blocks + b];
      counts[c * blocks + b] = running;
      running += count;
    }
  }
  block_start_[blocks] = running;

  order_.resize(n);
  parallel_for(chunks, [&](std::size_t c) {
    std::int32_t* offset = counts.data() + c * blocks;
    const std::size_t end = std::min(n, (c + 1) * chunk_size);
    for (std::size_t p = c * chunk_size; p < end; ++p) {
      order_[static_cast<std::size_t>(offset[block_of(cell_r[p], cell_y[p])]++)] =
          static_cast<std::int32_t>(p);
    }
  });

  block_tag_.clear();
  non_empty_blocks_.clear();
  for (auto& list : colored_blocks_) {
    list.clear();
  }
  for (int b = 0; b < block_count(); ++b) {
    if (block_start_[static_cast<std::size_t>(b) + 1] ==
        block_start_[static_cast<std::size_t>(b)]) {
      continue;
    }
    non_empty_blocks_.push_back(b);
    const int color = (b % blocks_r_) % 2 + 2 * ((b / blocks_r_) % 2);
    colored_blocks_[static_cast<std::size_t>(color)].push_back(b);
  }
}

std::vector<std::int32_t>
ParticleBins::cell_sorted_order(std::span<const std::int32_t> cell_r,
                                std::span<const std::int32_t> cell_y) const {
  std::vector<std::int32_t> sorted(order_.size());
  const int cells_per_block = block_cells_ * block_cells_;
  for_each_block([&](int block, std::span<const std::int32_t> particles) {
    // Stable counting sort of one block's particles by their cell within the block.
    const auto [cr0, cy0] = block_origin(block);
    std::array<std::int32_t, max_block_cells * max_block_cells + 1> start{};
    for (const std::int32_t p : particles) {
      const auto q = static_cast<std::size_t>(p);
      ++start[static_cast<std::size_t>((cell_r[q] - cr0) + block_cells_ * (cell_y[q] - cy0) + 1)];
    }
    std::partial_sum(start.begin(), start.begin() + cells_per_block + 1, start.begin());
    const std::size_t base =
        static_cast<std::size_t>(block_start_[static_cast<std::size_t>(block)]);
    for (const std::int32_t p : particles) {
      const auto q = static_cast<std::size_t>(p);
      const auto local =
          static_cast<std::size_t>((cell_r[q] - cr0) + block_cells_ * (cell_y[q] - cy0));
      sorted[base + static_cast<std::size_t>(start[local]++)] = p;
    }
  });
  return sorted;
}

void ParticleBins::reset_to_identity() {
  std::iota(order_.begin(), order_.end(), 0);
}

std::size_t ParticleBins::order_breaks() const {
  return parallel_reduce(
      order_.size(), std::size_t{0},
      [&](std::size_t begin, std::size_t end, std::size_t breaks) {
        for (std::size_t k = std::max<std::size_t>(begin, 1); k < end; ++k) {
          breaks += order_[k] != order_[k - 1] + 1 ? 1 : 0;
        }
        return breaks;
      },
      [](std::size_t a, std::size_t b) { return a + b; });
}

} // namespace mpile
