// A calibration chamber: the K0 procedure with a surcharge and gravity off gives a uniform stress
// (sigma_yy = -q, sigma_rr = sigma_thth = -K0 q) that, with the same surcharge applied as a
// traction on the surface and rollers on the side and the base, is an exact equilibrium. The
// stress must stay put and the boundaries must carry the closed-form resultants.
#include "tests/case_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace mpile {
namespace {

const std::string chamber = R"(title = "chamber"
geometry = "axisymmetric"

[grid]
r = [{ start = 0.0, end = 0.5, cells = 10 }]
y = [{ start = 0.0, end = 1.0, cells = 20 }]

[materials.sand]
type = "linear_elastic"
young_modulus = 50e6
poisson_ratio = 0.25
density = 1650.0

[[bodies]]
name = "sand"
material = "sand"
region = { r = [0.0, 0.5], y = [0.0, 1.0] }

[boundaries]
r_max = "roller"
y_min = "roller"

[[loads]]
name = "surcharge"
nodes = { y = 1.0 }
component = "y"
traction = -50e3

[solver]
gravity = [0.0, 0.0]

[[phases]]
name = "chamber"
duration = 0.02
local_damping = 0.7
k0 = [{ body = "sand", surface = 1.0, surcharge = 50e3, k0 = 0.5 }]
)";

TEST(Surcharge, AChamberUnderItsSurchargeStaysInEquilibrium) {
  CaseRun run(chamber);
  apply_k0(*run.scene, run.spec, run.spec.phases[0]);
  const double q = 50e3, k0 = 0.5;
  ASSERT_NEAR(run.scene->particles.stress[0][YY], -q, 1e-9); // the procedure sets the surcharge
  run.run([] {});
  const Particles& p = run.scene->particles;
  double volume = 0.0, vertical = 0.0, interior = 0.0, anywhere = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    volume += p.volume[i];
    vertical += p.volume[i] * p.stress[i][YY];
    const double deviation =
        std::max({std::abs(p.stress[i][YY] + q), std::abs(p.stress[i][RR] + k0 * q),
                  std::abs(p.stress[i][TT] + k0 * q), std::abs(p.stress[i][RY])});
    anywhere = std::max(anywhere, deviation);
    if (p.r[i] > 0.1 && p.r[i] < 0.4) {
      interior = std::max(interior, deviation);
    }
  }
  std::cout << "chamber: mean sigma_yy / q + 1 = " << vertical / volume / q + 1.0
            << ", largest deviation / q " << anywhere / q << " (" << interior / q
            << " two cells or more from the axis and the side)\n";
  // Statics: the volume integral of sigma_yy is the moment of the surface load, -q V: the mean
  // vertical stress is -q exactly once the chamber is at rest. Measured 1.2e-5 of q; 0.1 % leaves
  // room for what motion the damped phase has not yet taken out.
  EXPECT_NEAR(vertical / volume, -q, 1e-3 * q);
  // Away from the axis and the side the state stays the uniform one (0.5 % of q, the disturbance
  // travelling in from the corners in the 0.02 s). At the surface beside the axis it cannot: the
  // surcharge's nodal weights are the exact integrals of N r (h^2 / 6 at the axis node), while
  // the particles' stress reaches that node through the 2 x 2 sub-cell quadrature of the same
  // integrand, a quadratic (3 h^2 / 16): 12.5 % more, pushing the corner up. 10 % bounds it.
  EXPECT_LT(interior, 5e-3 * q);
  EXPECT_LT(anywhere, 0.1 * q);
}

} // namespace
} // namespace mpile
