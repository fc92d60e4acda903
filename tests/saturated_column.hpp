#pragma once

// The saturated columns of the undrained, coupled and sea tests: one driven by a velocity step at
// its base (uniaxial strain, no gravity): 30 m of linear elastic sand (E = 100 MPa, nu = 0.25, dry
// density 1600 kg/m^3) in 0.05 m cells, its water's keys given by the test; one at rest under
// gravity after the K0 procedure.

#include "engine/particles.hpp"
#include "tests/case_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>
#include <string>

namespace mpile {

inline std::string saturated_wave_column(const std::string& water_keys) {
  return R"(title = "saturated wave"
geometry = "axisymmetric"
[grid]
r = [{ start = 0.0, end = 0.1, cells = 2 }]
y = [{ start = 0.0, end = 30.0, cells = 600 }]
[materials.sand]
type = "linear_elastic"
young_modulus = 100e6
poisson_ratio = 0.25
density = 1600.0
)" + water_keys +
         R"(
[[bodies]]
name = "column"
material = "sand"
region = { r = [0.0, 0.1], y = [0.0, 30.0] }
[boundaries]
r_max = "roller"
[[prescribed]]
name = "piston"
nodes = { y = 0.0 }
velocity_y = 0.01
[[phases]]
name = "wave"
duration = 0.015
gravity = false
)";
}

/// A saturated column `height` m tall in `cells` cells (0.5 m wide, rollers at r_max, fixed at its
/// base, gravity 9.81) of material `material` (its keys), K0 = 0.5 from its top in one phase.
inline std::string saturated_column(double height, int cells, double duration,
                                    const std::string& material) {
  std::ostringstream s;
  s << "title = \"saturated column\"\n[grid]\nr = [{ start = 0.0, end = 0.5, cells = 2 }]\n"
    << "y = [{ start = 0.0, end = " << height << ", cells = " << cells << " }]\n"
    << "[materials.sand]\n"
    << material << "[[bodies]]\nname = \"column\"\nmaterial = \"sand\"\n"
    << "region = { r = [0.0, 0.5], y = [0.0, " << height << "] }\n"
    << "[boundaries]\nr_max = \"roller\"\ny_min = \"fixed\"\n[solver]\ngravity = [0.0, -9.81]\n"
    << "[[phases]]\nname = \"rest\"\nduration = " << duration << "\n"
    << "k0 = [{ body = \"column\", surface = " << height << ", k0 = 0.5 }]\n";
  return s.str();
}

/// The seed's torsion check (V9) with friction 0.4 instead of adhesion, in saturated soil (n =
/// 0.396; `drainage` its keys) under gravity, K0 = 0.5 from the surface at y = 1 m, on `cells` x
/// `cells` cells, one phase of `duration`. Torsion does not change the soil's volume, so the
/// water's stiffness does not enter: it is lowered to 0.1 GPa for a longer step.
inline std::string spun_pile_text(int cells, const std::string& drainage, double duration) {
  std::string text = read_text(source / "cases/verification/v9_torsion_adhesion.toml");
  text = replaced(text, "cells = 40", "cells = " + std::to_string(cells));
  text = replaced(text, "[materials.soil]\ntype = \"linear_elastic\"",
                  "[materials.soil]\ntype = \"linear_elastic\"\n" + drainage +
                      "\nwater_bulk_modulus = 1e8");
  text = replaced(text, "young_modulus = 100e6\npoisson_ratio = 0.0\ndensity = 2000.0\n\n# The",
                  "young_modulus = 100e6\npoisson_ratio = 0.0\ndensity = 1600.0\n\n# The");
  text = replaced(text, "friction = 0.0\nadhesion = 10e3   # Pa", "friction = 0.4\nadhesion = 0.0");
  std::ostringstream phase;
  phase << "duration = " << duration << "\nk0 = [{ material = \"soil\", surface = 1.0, k0 = 0.5 }]";
  text = replaced(text, "duration = 1.0", phase.str());
  return replaced(text, "[boundaries]", "[solver]\ngravity = [0.0, -9.81]\n\n[boundaries]");
}

/// The highest particle moving at half the piston's velocity or more: the front.
inline double wave_front(const CaseRun& run) {
  const Particles& p = run.scene->particles;
  double y = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.v_y[i] >= 0.005) {
      y = std::max(y, p.y[i]);
    }
  }
  return y;
}

/// The undrained P-wave's speed in the column, c = sqrt((M + K_w / n) / rho_sat), 1 685.7 m/s,
/// against the front's speed between 6 and 12 ms; 2 % is what a 0.05 m cell and half a cell of
/// front position allow over the 10 m the front runs between them.
inline void expect_undrained_p_wave(CaseRun& run) {
  const double n = 1.0 - 1600.0 / 2650.0;
  const double rho_sat = 1600.0 + n * 1000.0;
  const double m = 100e6 * 0.75 / (1.25 * 0.5);
  const double c = std::sqrt((m + 2.2e9 / n) / rho_sat);
  run.solver->advance_to(0.006);
  const double y1 = wave_front(run);
  run.solver->advance_to(0.012);
  const double y2 = wave_front(run);
  EXPECT_NEAR((y2 - y1) / 0.006, c, 0.02 * c) << "front at " << y1 << " and " << y2 << " m";
  std::cout << "undrained P wave: " << (y2 - y1) / 0.006 << " m/s against " << c << " m/s\n";
}

} // namespace mpile
