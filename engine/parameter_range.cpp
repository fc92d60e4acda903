#include "engine/parameter_range.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace mpile {

bool ParameterRange::contains(double x) const {
  if (std::isnan(x)) {
    return false;
  }
  if (lower && (lower->inclusive ? x < lower->value : x <= lower->value)) {
    return false;
  }
  return !(upper && (upper->inclusive ? x > upper->value : x >= upper->value));
}

std::string format_bound(double x) {
  if (x == std::trunc(x) && std::abs(x) < 1e15) {
    return std::to_string(static_cast<long long>(x)); // 100000, not 1e+05
  }
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, result.ptr);
}

std::string ParameterRange::text(bool integer) const {
  if (lower && upper) {
    if (integer && lower->inclusive && upper->inclusive) {
      return format_bound(lower->value) + " to " + format_bound(upper->value);
    }
    return std::string("in ") + (lower->inclusive ? "[" : "(") + format_bound(lower->value) + ", " +
           format_bound(upper->value) + (upper->inclusive ? "]" : ")");
  }
  if (lower) {
    return (lower->inclusive ? ">= " : "> ") + format_bound(lower->value);
  }
  if (upper) {
    return (upper->inclusive ? "<= " : "< ") + format_bound(upper->value);
  }
  return "";
}

std::string ParameterRange::requirement(bool integer) const {
  if (lower && upper) {
    if (integer) {
      return "must lie between " + format_bound(lower->value) + " and " +
             format_bound(upper->value);
    }
    return "must lie " + text();
  }
  return "must be " + text();
}

void require_in_range(const char* name, const ParameterRange& range, double value) {
  if (!std::isfinite(value)) {
    throw std::invalid_argument(std::string(name) + " must be a finite number, got " +
                                format_bound(value));
  }
  if (!range.contains(value)) {
    throw std::invalid_argument(std::string(name) + " " + range.requirement() + ", got " +
                                format_bound(value));
  }
}

} // namespace mpile
