#include "engine/moving_mesh.hpp"

#include <sstream>
#include <stdexcept>

namespace mpile {

std::vector<double> MovingMesh::lines_at(double offset) const {
  // A zone is allowed to shrink to a tenth of its size: the cells in it would otherwise limit
  // the time step to nothing before they collapse.
  constexpr double least_share = 0.1;
  if (travel > 0.0 && std::abs(offset) > travel) {
    std::ostringstream s;
    s << "the moving mesh band has moved " << offset << " m, beyond its travel of " << travel
      << " m: the soil there was seeded for coarser cells than the band's, and rows of empty "
         "cells would disconnect it; raise the travel (and with it the fine zone)";
    throw std::runtime_error(s.str());
  }
  const double bottom = lower_limit();
  const double top = upper_limit();
  const double below = reference_y[index(band_bottom)] - bottom;
  const double above = top - reference_y[index(band_top)];
  if (below + offset < least_share * below || above - offset < least_share * above) {
    std::ostringstream s;
    s << "the moving mesh band has moved " << offset
      << " m and squeezed the cells between it and the " << (offset < 0.0 ? "bottom" : "top")
      << " of the stretch zone (" << (offset < 0.0 ? bottom : top)
      << " m) to a tenth of their size; "
      << "make the grid deeper or the band smaller";
    throw std::runtime_error(s.str());
  }
  std::vector<double> lines(reference_y.size());
  const double stretch_below = (below + offset) / below;
  const double stretch_above = (above - offset) / above;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const double y = reference_y[i];
    if (i < lower_index() || i > upper_index()) {
      lines[i] = y;
    } else if (i < index(band_bottom)) {
      lines[i] = bottom + (y - bottom) * stretch_below;
    } else if (i <= index(band_top)) {
      lines[i] = y + offset;
    } else {
      lines[i] = top - (top - y) * stretch_above;
    }
  }
  return lines;
}

} // namespace mpile
