#pragma once

#include "engine/parallel.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace mpile {

/// Particles binned into square blocks of cells, and the blocks coloured so that two blocks of one
/// colour share no grid node: the colour of block (bi, bj) is (bi mod 2) + 2 (bj mod 2). A scatter
/// runs one colour at a time with the blocks of that colour in parallel, so no two tasks write the
/// same node; no atomics, locks or per-thread grids. Within a block, particles are visited in a
/// fixed order, so every nodal sum is formed in the same order for any thread count and results
/// are bitwise identical.
class ParticleBins {
public:
  static constexpr int max_block_cells = 16;

  void configure(int cells_r, int cells_y, int block_cells);

  int block_cells() const { return block_cells_; }
  int block_count() const { return blocks_r_ * blocks_y_; }
  std::span<const std::int32_t> non_empty_blocks() const { return non_empty_blocks_; }
  int block_of(int cr, int cy) const { return cr / block_cells_ + blocks_r_ * (cy / block_cells_); }
  /// First cell (cr, cy) of a block.
  std::array<int, 2> block_origin(int block) const {
    return {(block % blocks_r_) * block_cells_, (block / blocks_r_) * block_cells_};
  }

  /// Rebuilds the bins from the particles' cells by a stable counting sort on the block, done in
  /// parallel over a fixed number of chunks (independent of the thread count).
  void rebuild(std::span<const std::int32_t> cell_r, std::span<const std::int32_t> cell_y);

  /// The order that sorts particles by block and, within a block, by cell (stable); used to
  /// physically reorder the particle arrays, after which reset_to_identity() applies.
  std::vector<std::int32_t> cell_sorted_order(std::span<const std::int32_t> cell_r,
                                              std::span<const std::int32_t> cell_y) const;
  void reset_to_identity();

  /// Marks every block with the bitwise OR of tag(particle) over its particles (0 for an empty
  /// block), for passes that can take a shorter path through blocks of one kind. Valid until the
  /// next rebuild; a permutation of the particles (reset_to_identity) keeps it.
  template <class Tag> void tag_blocks(Tag&& tag) {
    block_tag_.assign(static_cast<std::size_t>(block_count()), 0);
    parallel_for(non_empty_blocks_.size(), [&](std::size_t k) {
      const int block = non_empty_blocks_[k];
      std::uint64_t t = 0;
      for (const std::int32_t q : particles_in(block)) {
        t |= tag(static_cast<std::size_t>(q));
      }
      block_tag_[static_cast<std::size_t>(block)] = t;
    });
  }
  /// A block's tag; every bit set while the blocks are untagged, so that a pass never takes a
  /// block for one kind it has not been shown to be.
  std::uint64_t block_tag(int block) const {
    return block_tag_.empty() ? ~std::uint64_t{0} : block_tag_[static_cast<std::size_t>(block)];
  }

  /// Number of places where the visiting order jumps in memory; many jumps mean the particle arrays
  /// should be physically re-sorted to keep the passes streaming through memory.
  std::size_t order_breaks() const;

  std::span<const std::int32_t> particles_in(int block) const {
    const auto b = static_cast<std::size_t>(block);
    return {order_.data() + block_start_[b],
            static_cast<std::size_t>(block_start_[b + 1] - block_start_[b])};
  }

  /// Calls f(block, particles) for every non-empty block, in parallel. For passes that write only
  /// to their own particles and to cells of their own block.
  template <class F> void for_each_block(F&& f) const { run_blocks(non_empty_blocks_, f); }

  /// Calls f(block, particles) colour by colour; blocks of one colour run in parallel. For passes
  /// that scatter to grid nodes.
  template <class F> void for_each_block_colored(F&& f) const {
    for (const auto& blocks : colored_blocks_) {
      run_blocks(blocks, f);
    }
  }

private:
  template <class F> void run_blocks(const std::vector<std::int32_t>& blocks, F& f) const {
    parallel_for(blocks.size(), [&](std::size_t i) { f(blocks[i], particles_in(blocks[i])); });
  }

  int block_cells_ = 8;
  int blocks_r_ = 0;
  int blocks_y_ = 0;
  std::vector<std::int32_t> order_;
  std::vector<std::int32_t> block_start_;
  std::vector<std::int32_t> non_empty_blocks_;
  std::array<std::vector<std::int32_t>, 4> colored_blocks_;
  std::vector<std::uint64_t> block_tag_;
};

} // namespace mpile
