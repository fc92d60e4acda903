#pragma once

#include "cases/verification/verification_cases.hpp"

#include <iosfwd>
#include <string>
#include <vector>

namespace mpile {

/// Runs verification cases by id ("all" for every one) and prints, for each, the compared
/// quantities with their reference, error and tolerance (or, with csv, one CSV row per
/// quantity). Returns the number of failed cases.
int run_verification(const std::vector<std::string>& ids, const verification::Options& options,
                     std::ostream& out, bool csv = false);

} // namespace mpile
