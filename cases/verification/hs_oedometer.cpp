// VHS (hs_oedometer.toml): Hardening Soil in a full run against its own element test. The sample
// of the seed's sand starts from its normally consolidated K0 state and is compressed
// oedometrically to eps_y = -0.5 %, primary loading on the cap. The state stays homogeneous, so
// every particle must follow the single-point oedometer path: the reference integrates the same
// model along eps_y alone in 20 000 equal increments (the element test's own integration, which
// the hardening-soil tests pin to the published curves). What the run adds, and what the error
// measures, is the dynamics of the loading and the time step.
#include "cases/verification/case_file_run.hpp"
#include "cases/verification/verification_cases.hpp"

#include <cmath>
#include <memory>
#include <vector>

namespace mpile::verification {

std::unique_ptr<Material> seed_sand() {
  const CaseSpec spec = read_verification_case("hs_oedometer.toml", {});
  return create_material(spec.materials.at(0).type, spec.materials.at(0).parameters);
}

Report run_hs_oedometer(const Options& options) {
  CaseFileRun run("hs_oedometer.toml", options);
  const double height = run.spec().bodies.at(0).region.bounds().y_max;
  const double radius = run.spec().bodies.at(0).region.bounds().r_max;
  const double strain = travel_of(*run.spec().motions.at(0).velocity[1], run.spec()) / height;
  const K0Spec& k0 = run.spec().phases[0].k0.at(0);
  const Stress initial{-k0.k0 * k0.surcharge, -k0.surcharge, -k0.k0 * k0.surcharge, 0.0, 0.0, 0.0};

  Report report = run.run("VHS", "Hardening Soil oedometer under a platen");

  // The single-point reference along the same oedometric path.
  const Material& sand = *run.scene().materials.at(0);
  Stress reference = initial;
  std::vector<double> state(sand.state_size());
  sand.initialise_state(reference, state.data());
  constexpr int increments = 20000;
  for (int k = 0; k < increments; ++k) {
    update_single_point(sand, reference, state.data(),
                        {0.0, strain / increments, 0.0, 0.0, 0.0, 0.0});
  }

  const Particles& p = run.scene().particles;
  double mean_axial = 0.0, mean_lateral = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    mean_axial += p.stress[i][YY] / static_cast<double>(p.size());
    mean_lateral += 0.5 * (p.stress[i][RR] + p.stress[i][TT]) / static_cast<double>(p.size());
  }
  const double reaction = run.scene().boundaries.constraint("top platen").reaction[1];
  const double increment = reference[YY] - initial[YY]; // errors are relative to the change
  report.checks = {
      {"mean sigma_yy", "Pa", mean_axial, reference[YY], std::abs(increment), 0.01},
      {"mean lateral stress", "Pa", mean_lateral, reference[RR],
       std::abs(reference[RR] - initial[RR]), 0.01},
      {"platen force", "N/rad", reaction, reference[YY] * radius * radius / 2.0,
       std::abs(increment) * radius * radius / 2.0, 0.01},
      run.equilibrium(),
  };
  return report;
}

} // namespace mpile::verification
