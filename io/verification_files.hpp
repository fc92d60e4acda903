#pragma once

// The verification cases of `mpile verify`: those built in C++ (cases/verification/) and those that
// run from a case file (V7 and V9, their TOML built into the program), in one list.

#include "cases/verification/verification_case.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace mpile {

/// The case files, as built into the program (io/verification_texts.cpp.in).
extern const std::string_view v7_block_on_incline_toml;
extern const std::string_view v9_torsion_adhesion_toml;

/// The case text with every grid zone's cell count (`cells = n`) multiplied by the refinement,
/// for `mpile verify --refinement` on a case file.
std::string refined(std::string_view text, int refinement);

/// Every verification case, by id (V1 ... V9, V4p, V8k0, VHS).
const std::vector<verification::Case>& verification_cases();
const verification::Case* find_verification_case(const std::string& id);

/// V7 (cases/verification/v7_block_on_incline.toml): the block's mean slide after 1 s against
/// Coulomb's s = g (sin a - mu cos a) t^2 / 2.
verification::Report run_block_on_incline(const verification::Options& options);
/// V9 (cases/verification/v9_torsion_adhesion.toml): the theta reactions on the pile's three
/// surfaces, averaged over 0.5 to 1 s, against the adhesion limit c_a times each surface.
verification::Report run_torsion_with_adhesion(const verification::Options& options);

} // namespace mpile
