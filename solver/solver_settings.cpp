#include "solver/solver_settings.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace mpile {

namespace {
void require(bool condition, const std::string& message) {
  if (!condition) {
    throw std::invalid_argument(message);
  }
}
} // namespace

void SolverSettings::validate() const {
  require(courant_number > 0.0 && courant_number <= 2.0,
          "courant_number must lie in (0, 2], got " + std::to_string(courant_number));
  require(max_time_step > 0.0, "max_time_step must be positive");
  require(flip_fraction >= 0.0 && flip_fraction <= 1.0,
          "flip_fraction must lie in [0, 1], got " + std::to_string(flip_fraction));
  require(xpic_order >= 0 && xpic_order <= max_xpic_order,
          "xpic_order must lie in [0, " + std::to_string(max_xpic_order) + "], got " +
              std::to_string(xpic_order));
  require(xpic_order == 0 || flip_fraction == 1.0, "xpic_order " + std::to_string(xpic_order) +
                                                       " replaces the FLIP/PIC blend: leave "
                                                       "flip_fraction at 1 (got " +
                                                       std::to_string(flip_fraction) + ")");
  require(local_damping >= 0.0 && local_damping < 1.0,
          "local_damping must lie in [0, 1), got " + std::to_string(local_damping));
  require(mass_scaling >= 1.0,
          "mass_scaling must be at least 1, got " + std::to_string(mass_scaling));
  require(std::isfinite(gravity[0]) && std::isfinite(gravity[1]), "gravity must be finite");
  require(min_time_step >= 0.0 && std::isfinite(min_time_step),
          "min_time_step must be >= 0, got " + std::to_string(min_time_step));
  require(energy_residual_warning > 0.0, "energy_residual_warning must be positive, got " +
                                             std::to_string(energy_residual_warning));
  require(energy_residual_limit > energy_residual_warning,
          "energy_residual_limit must exceed energy_residual_warning (" +
              std::to_string(energy_residual_warning) + "), got " +
              std::to_string(energy_residual_limit));
  require(block_cells >= 1 && block_cells <= 16,
          "block_cells must lie in [1, 16], got " + std::to_string(block_cells));
  // Two blocks of one colour are a block apart; a GIMP particle writes to nodes one cell outside
  // its block, so a block of 2 cells would let two blocks of one colour share a node.
  require(shape_functions == ShapeFunctions::linear || block_cells >= 3,
          "block_cells must be at least 3 with GIMP shape functions, got " +
              std::to_string(block_cells));
}

} // namespace mpile
