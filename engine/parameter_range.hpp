#pragma once

// The interval a parameter may take, declared with the parameter (cases/case_format.hpp for case
// keys, engine/materials/material_registry.hpp for material parameters) and checked by the readers.

#include <optional>
#include <string>

namespace mpile {

struct Bound {
  double value = 0.0;
  bool inclusive = true;
};

struct ParameterRange {
  std::optional<Bound> lower;
  std::optional<Bound> upper;

  bool contains(double x) const;
  /// "> 0", ">= 1", "<= 2", "in (0, 2]", empty without bounds. Integer ranges read "1 to 8".
  std::string text(bool integer = false) const;
  /// What a value outside the range is told: "must lie in (0, 2]", "must lie between 1 and 8"
  /// (integers), "must be > 0".
  std::string requirement(bool integer = false) const;
};

/// The ranges declarations are written with: x < value, x >= value, and between two bounds.
inline ParameterRange above(double x) {
  return {Bound{x, false}, std::nullopt};
}
inline ParameterRange at_least(double x) {
  return {Bound{x, true}, std::nullopt};
}
inline ParameterRange between(double low, bool low_inclusive, double high, bool high_inclusive) {
  return {Bound{low, low_inclusive}, Bound{high, high_inclusive}};
}

/// Throws std::invalid_argument "<name> <requirement>, got <value>" for a value outside the range
/// or not finite: a model's constructor checks its declared parameters with it.
void require_in_range(const char* name, const ParameterRange& range, double value);

/// A number in the shortest form that reads back to the same double, whole numbers as integers
/// (100000, not 1e+05): for declared bounds and for exact output (the element tests' CSV).
std::string format_bound(double x);

} // namespace mpile
