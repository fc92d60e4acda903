// V7 (v7_block_on_incline.toml): a block sliding on a rigid incline (plane strain, gravity tilted
// by the incline's angle a) against Coulomb's s = g (sin a - mu cos a) t^2 / 2.
#include "cases/verification/case_file_run.hpp"
#include "cases/verification/verification_cases.hpp"

#include <cmath>

namespace mpile::verification {

Report run_block_on_incline(const Options& options) {
  CaseFileRun run("v7_block_on_incline.toml", options);
  // The file's gravity is tilted by the incline's angle a: g sin a along it, g cos a into it.
  const double g_along = std::abs(run.spec().solver.gravity[0]);
  const double g_normal = std::abs(run.spec().solver.gravity[1]);
  const double mu = run.spec().contacts.at(0).friction;
  const double rho = run.parameter(run.spec().bodies.at(0).material, "density");
  const double top = run.spec().bodies.at(0).region.bounds().y_max;
  // The block starts in the equilibrium of an infinitely long layer (zero at its top): released
  // unstressed it would bounce on the incline, and the normal force would dip below what holds it.
  Particles& p = run.scene().particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] == 0) {
      p.stress[i][YY] = -rho * g_normal * (top - p.y[i]);
      p.stress[i][RY] = rho * g_along * (top - p.y[i]);
    }
  }
  Report report = run.run("V7", "block sliding on a rigid incline, Coulomb friction");
  double mass = 0.0, moment = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] == 0) {
      mass += p.mass[i];
      moment += p.mass[i] * (p.r[i] - p.r0[i]);
    }
  }
  // 3 %: the tolerance of the block-on-incline test at mu = 0.3 (the block's start and the
  // contact's one-step lag at release, docs/verification.md V7).
  const double t = run.spec().phases[0].duration;
  const double slide = 0.5 * (g_along - mu * g_normal) * t * t;
  report.checks.push_back(
      {"mean slide of the block after 1 s", "m", moment / mass, slide, slide, 0.03});
  return report;
}

} // namespace mpile::verification
