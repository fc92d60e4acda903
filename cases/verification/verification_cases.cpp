#include "cases/verification/verification_cases.hpp"

namespace mpile::verification {

const std::vector<Case>& all_cases() {
  static const std::vector<Case> cases = {
      {"V1", "axial vibrating bar (axisymmetric)", run_vibrating_bar},
      {"V2", "single material point vibration", run_single_point},
      {"V3", "Lame thick cylinder under internal pressure", run_lame_cylinder},
      {"V4", "radial patch test through the axis", run_radial_patch},
      {"V4p", "plane-strain patch test", run_plane_strain_patch},
      {"V5", "solid cylinder in uniaxial compression", run_uniaxial_cylinder},
      {"V6", "shaft torsion", run_shaft_torsion},
      {"V6c", "elastic Couette flow in an annulus", run_elastic_couette},
      {"V7", "block sliding on a rigid incline (plane strain)", run_block_on_incline},
      {"V8", "self-weight column, gravity loading", run_self_weight_column},
      {"V8k0", "self-weight column, K0 state stays put", run_k0_column},
      {"V9", "seed torsion with adhesion", run_torsion_with_adhesion},
      {"V10", "Terzaghi consolidation (coupled soil)", run_terzaghi_consolidation},
      {"VHS", "Hardening Soil oedometer under a platen", run_hs_oedometer},
  };
  return cases;
}

const Case* find_case(const std::string& id) {
  for (const Case& c : all_cases()) {
    if (c.id == id) {
      return &c;
    }
  }
  return nullptr;
}

} // namespace mpile::verification
