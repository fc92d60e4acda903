#pragma once

#include <stdexcept>

namespace mpile {

/// A run that cannot go on (a particle left the grid, the time step collapsed); the message names
/// the cause, the step and where.
class SimulationError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

} // namespace mpile
