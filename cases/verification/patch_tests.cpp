// V4 (radial_patch.toml) and V4p (plane_strain_patch.toml): every grid node moves with v = L x
// ([affine_motion]) for the phase's duration t, so every particle, wherever it sits in its cell,
// must reach the uniform strain L t and the stress of linear elasticity for it, with and without
// B-bar. In axisymmetry the hoop strain is u_r / r = L_rr t.
#include "cases/verification/case_file_run.hpp"
#include "cases/verification/verification_cases.hpp"

#include <algorithm>
#include <cmath>

namespace mpile::verification {

namespace {

/// The strain the file's motion imposes over its phase (engineering shear).
struct PatchStrain {
  double rr, yy, tt, ry;
};

PatchStrain imposed_strain(const CaseSpec& spec) {
  const std::array<double, 4> L = spec.velocity_gradient.value();
  const double t = spec.phases.at(0).duration;
  const double hoop = spec.mode == GeometryMode::axisymmetric ? L[0] * t : 0.0;
  return {L[0] * t, L[3] * t, hoop, (L[1] + L[2]) * t};
}

Stress elastic_stress(double young, double nu, const PatchStrain& e) {
  const double lambda = young * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  const double mu = young / (2.0 * (1.0 + nu));
  const double volumetric = e.rr + e.yy + e.tt;
  return {lambda * volumetric + 2.0 * mu * e.rr,
          lambda * volumetric + 2.0 * mu * e.yy,
          lambda * volumetric + 2.0 * mu * e.tt,
          mu * e.ry,
          0.0,
          0.0};
}

/// The stress every particle of the file's patch must reach: its material's, at the strain the
/// motion imposes.
Stress patch_stress(const CaseFileRun& run) {
  return elastic_stress(run.parameter("elastic", "young_modulus"),
                        run.parameter("elastic", "poisson_ratio"), imposed_strain(run.spec()));
}

} // namespace

Report run_radial_patch(const Options& options) {
  CaseFileRun run("radial_patch.toml", options);
  const Stress exact = patch_stress(run);
  Report report = run.run("V4", "radial patch test through the axis");
  double err_rr = 0.0, err_tt = 0.0, err_yy = 0.0, err_shear = 0.0;
  for (const Stress& s : run.scene().particles.stress) {
    err_rr = std::max(err_rr, std::abs(s[RR] - exact[RR]));
    err_tt = std::max(err_tt, std::abs(s[TT] - exact[TT]));
    err_yy = std::max(err_yy, std::abs(s[YY] - exact[YY]));
    err_shear = std::max({err_shear, std::abs(s[RY]), std::abs(s[YT]), std::abs(s[RT])});
  }
  // Each check holds the largest deviation over all particles.
  const double radial = exact[RR], axial = exact[YY];
  report.checks = {
      {"max |sigma_rr - 2(lambda+mu) eps|", "Pa", radial + err_rr, radial, radial, 0.005},
      {"max |sigma_thth - 2(lambda+mu) eps|", "Pa", radial + err_tt, radial, radial, 0.005},
      {"max |sigma_yy - 2 lambda eps|", "Pa", axial + err_yy, axial, axial, 0.005},
      {"max |shear stress|", "Pa", err_shear, 0.0, radial, 0.005},
  };
  return report;
}

Report run_plane_strain_patch(const Options& options) {
  CaseFileRun run("plane_strain_patch.toml", options);
  const Stress exact = patch_stress(run);
  Report report = run.run("V4p", "plane-strain patch test");
  double worst = 0.0;
  for (const Stress& s : run.scene().particles.stress) {
    for (std::size_t c = 0; c < 6; ++c) {
      worst = std::max(worst, std::abs(s[c] - exact[c]));
    }
  }
  report.checks = {
      {"max stress deviation from C:eps", "Pa", worst, 0.0, std::abs(exact[RR]), 0.005}};
  return report;
}

} // namespace mpile::verification
