// The reach of each contact structure's field (NodeField::reach): the nodes its particles can
// touch until the particles are binned again. Blocks are tagged with the structure fields of their
// particles, and a field's reach is the hull of its blocks' nodes, widened by the one cell on
// either side a GIMP domain can reach. A block holding soil only lets the particle passes take the
// single-field path; a structure without particles gets an empty reach and costs nothing.
#include "solver/passes.hpp"

#include <algorithm>

namespace mpile::passes {

std::uint64_t structure_tag(int field) {
  return field == 0 ? 0 : std::uint64_t{1} << std::min(field - 1, 63);
}

NodeBox block_node_box(const Grid& grid, const ParticleBins& bins, int block) {
  const auto [cr, cy] = bins.block_origin(block);
  const int cells = bins.block_cells();
  // Cells [c, c + cells) reach nodes c - 1 to c + cells + 1.
  return {std::max(0, cr - 1), std::min(grid.nodes_r(), cr + cells + 2), std::max(0, cy - 1),
          std::min(grid.nodes_y(), cy + cells + 2)};
}

void find_structure_reach(Scene& scene, ParticleBins& bins) {
  Grid& grid = scene.grid;
  if (grid.structure_fields.empty()) {
    return;
  }
  const Particles& p = scene.particles;
  bins.tag_blocks([&](std::size_t i) { return structure_tag(scene.field_of(p.body[i])); });
  std::vector<NodeBox> reach(grid.structure_fields.size());
  for (const std::int32_t block : bins.non_empty_blocks()) {
    const std::uint64_t tag = bins.block_tag(block);
    if (tag == 0) {
      continue;
    }
    const NodeBox nodes = block_node_box(grid, bins, block);
    for (std::size_t f = 0; f < reach.size(); ++f) {
      if ((tag & structure_tag(static_cast<int>(f) + 1)) != 0) {
        reach[f] = NodeBox::hull(reach[f], nodes);
      }
    }
  }
  for (std::size_t f = 0; f < reach.size(); ++f) {
    grid.structure_fields[f].reach = reach[f];
  }
}

} // namespace mpile::passes
