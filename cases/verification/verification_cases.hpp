#pragma once

// The verification cases of `mpile verify` (docs/verification.md), in one list. Each runs its case
// file (cases/verification/*.toml, built into the program) through the phase runner, as `mpile
// run` runs it, and measures the run against the case's closed form or reference.

#include "cases/verification/verification_case.hpp"
#include "engine/materials/material.hpp"

#include <memory>
#include <string>
#include <vector>

namespace mpile::verification {

/// Every verification case, by id, in the order of docs/verification.md: V1 ... V9, each variant
/// after its case (V4p, V8k0), VHS last.
const std::vector<Case>& all_cases();
const Case* find_case(const std::string& id);

Report run_vibrating_bar(const Options& options);          // V1, vibrating_bar.toml
Report run_single_point(const Options& options);           // V2, single_point.toml
Report run_lame_cylinder(const Options& options);          // V3, lame_cylinder.toml
Report run_radial_patch(const Options& options);           // V4, radial_patch.toml
Report run_plane_strain_patch(const Options& options);     // V4p, plane_strain_patch.toml
Report run_uniaxial_cylinder(const Options& options);      // V5, uniaxial_cylinder.toml
Report run_shaft_torsion(const Options& options);          // V6, shaft_torsion.toml
Report run_elastic_couette(const Options& options);        // V6c, elastic_couette.toml
Report run_block_on_incline(const Options& options);       // V7, v7_block_on_incline.toml
Report run_self_weight_column(const Options& options);     // V8, self_weight_column.toml
Report run_k0_column(const Options& options);              // V8k0, k0_column.toml
Report run_torsion_with_adhesion(const Options& options);  // V9, v9_torsion_adhesion.toml
Report run_terzaghi_consolidation(const Options& options); // V10, terzaghi_consolidation.toml
Report run_hs_oedometer(const Options& options);           // VHS, hs_oedometer.toml

/// The seed paper's dry sand (Hardening Soil, its Table 5), as hs_oedometer.toml declares it.
std::unique_ptr<Material> seed_sand();
/// Karlsruhe fine sand (hypoplastic, e0 = 0.85, dry), as hypoplastic_torsion_ring.toml declares it.
std::unique_ptr<Material> karlsruhe_fine_sand();

} // namespace mpile::verification
