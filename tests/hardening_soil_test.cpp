// Hardening Soil against the reference numbers of hardening_soil.md section 3 (computed there with
// an independent rate-form driver), for the seed paper's parameter set. Single material point,
// small strain increments; the tolerances are the ones that document suggests for engine tests:
// 0.5 % on strains at a given q, 1e-3 on moduli, K0 within 0.002.
#include "engine/materials/hardening_soil.hpp"
#include "engine/materials/material_registry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <numbers>
#include <random>

#include <Eigen/Geometry>

#include "engine/materials/principal_stress.hpp"

namespace mpile {
namespace {

constexpr double kPa = 1e3;

HardeningSoilParameters seed_parameters() {
  HardeningSoilParameters p;
  p.e50_ref = 44000 * kPa;
  p.eoed_ref = 44000 * kPa;
  p.eur_ref = 132000 * kPa;
  p.power = 0.47;
  p.poisson_ur = 0.2;
  p.k0_nc = 0.5;
  p.failure_ratio = 0.91;
  p.p_ref = 100 * kPa;
  p.friction_angle = 37.5;
  p.dilatancy_angle = 0.0;
  p.stiffness_floor = 1e-4; // the reference numbers use no floors
  p.cap_floor = 1.0;
  p.density = 1656.25;
  return p;
}

/// One material point under a mixed-control path, in engine convention (tension positive).
struct Point {
  const HardeningSoil& model;
  Stress stress{};
  std::array<double, 3> state{};

  // Compression-positive views.
  double axial() const { return -stress[YY]; }
  double lateral() const { return -stress[RR]; }

  void strain(const StrainIncrement& de) { model.update_point(stress, state.data(), de); }

  /// Axial strain increment (compression positive) at constant lateral stress: the lateral strain
  /// is found by a secant iteration on copies of the point.
  void triaxial(double axial_strain) {
    const double target = stress[RR];
    auto lateral_error = [&](double lateral_strain) {
      Point copy = *this;
      copy.strain({lateral_strain, -axial_strain, lateral_strain, 0.0, 0.0, 0.0});
      return copy.stress[RR] - target;
    };
    double x0 = 0.0, f0 = lateral_error(x0);
    double x1 = 0.2 * axial_strain, f1 = lateral_error(x1);
    for (int k = 0; k < 60 && std::abs(f1) > 1e-7; ++k) {
      const double x2 = x1 - f1 * (x1 - x0) / (f1 - f0);
      x0 = x1;
      f0 = f1;
      x1 = x2;
      f1 = lateral_error(x1);
    }
    strain({x1, -axial_strain, x1, 0.0, 0.0, 0.0});
    axial_strain_total += axial_strain;
    volumetric_strain_total += axial_strain - 2.0 * x1;
  }

  double axial_strain_total = 0.0;
  double volumetric_strain_total = 0.0;
};

TEST(HardeningSoil, AFailureRatioWhoseAsymptoteOverflowsIsRefused) {
  // R_f = 1e-308 made q_a = q_f / R_f infinite and every return slow (found by the fuzz run).
  HardeningSoilParameters p = seed_parameters();
  p.failure_ratio = 1e-308;
  EXPECT_THROW(HardeningSoil{p}, std::invalid_argument);
  p.failure_ratio = 1e-3;
  EXPECT_NO_THROW(HardeningSoil{p});
}

// Each parameter's range is declared once (hardening_soil_fields) and the constructor checks it
// there: a value just outside either bound is refused with the parameter's name and that range,
// the bound itself (where the range includes it) accepted; the registry's keys carry the same
// range.
TEST(HardeningSoil, TheConstructorChecksEachDeclaredRange) {
  const MaterialType* registered = nullptr;
  for (const MaterialType& type : material_types()) {
    registered = type.name == "hardening_soil" ? &type : registered;
  }
  ASSERT_NE(registered, nullptr);
  for (const HardeningSoilField& f : hardening_soil_fields()) {
    SCOPED_TRACE(f.name);
    const auto key = std::find_if(registered->parameters.begin(), registered->parameters.end(),
                                  [&](const MaterialParameterSpec& p) { return p.name == f.name; });
    ASSERT_NE(key, registered->parameters.end());
    EXPECT_EQ(key->range.text(), f.range.text());
    for (const auto& [bound, outside] :
         {std::pair{f.range.lower, -1.0}, std::pair{f.range.upper, 1.0}}) {
      if (!bound) {
        continue;
      }
      HardeningSoilParameters p = seed_parameters();
      p.*f.member = bound->value + outside * std::max(1e-6, 1e-6 * std::abs(bound->value));
      try {
        HardeningSoil model(p);
        ADD_FAILURE() << f.name << " = " << p.*f.member << " was accepted";
      } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find(std::string(f.name) + " " + f.range.requirement()),
                  std::string::npos)
            << e.what();
      }
    }
  }
}

TEST(HardeningSoil, CapShapeAndModulusFollowFromK0ncAndEoedRef) {
  const HardeningSoil model(seed_parameters());
  EXPECT_NEAR(model.alpha(), 1.0198, 5e-4);            // hardening_soil.md 1.6
  EXPECT_NEAR(model.cap_modulus() / kPa, 89247, 89.0); // 1e-3 relative
}

TEST(HardeningSoil, StiffnessLawsAtTheReferenceStresses) {
  const HardeningSoil model(seed_parameters());
  EXPECT_NEAR(model.unloading_modulus(50 * kPa) / kPa, 95299, 95.0);
  EXPECT_NEAR(model.secant_modulus(200 * kPa) / kPa, 60945, 61.0);
  EXPECT_NEAR(model.oedometer_modulus(100 * kPa) / kPa, 44000, 1e-6);
  EXPECT_NEAR(model.failure_deviator(100 * kPa) / kPa, 311.20, 0.01);
}

TEST(HardeningSoil, InitialStateOfNormallyConsolidatedK0Ground) {
  HardeningSoilParameters parameters = seed_parameters();
  const HardeningSoil model(parameters);
  // hardening_soil.md 1.8: depth, sigma_v (kPa), p_p0 (kPa), gamma_p0.
  const double rows[][4] = {{0.5, 8.125, 6.72, 3.64e-4},
                            {1.0, 16.25, 13.45, 5.25e-4},
                            {5.0, 81.24, 67.23, 1.23e-3},
                            {10.0, 162.5, 134.5, 1.78e-3},
                            {20.0, 325.0, 268.9, 2.57e-3}};
  for (const auto& row : rows) {
    const double v = row[1] * kPa;
    double state[3];
    model.initialise_state(Stress{-0.5 * v, -v, -0.5 * v, 0.0, 0.0, 0.0}, state);
    // The table has three significant figures: 0.5 % covers its rounding.
    EXPECT_NEAR(state[HardeningSoil::P_P] / kPa, row[2], 0.005 * row[2]) << "z = " << row[0];
    EXPECT_NEAR(state[HardeningSoil::GAMMA_P], row[3], 0.005 * row[3]) << "z = " << row[0];
  }
}

TEST(HardeningSoil, DrainedTriaxialFollowsTheHyperbolaWithTheCapInactive) {
  const HardeningSoil model(seed_parameters());
  // sigma_3 (kPa), then (q/qf, eps_1 %, eps_v %) from hardening_soil.md 3.1a.
  struct Row {
    double fraction, axial, volumetric;
  };
  const std::vector<std::pair<double, std::vector<Row>>> table = {
      {50, {{0.25, 0.0864, 0.0245}, {0.5, 0.2449, 0.0490}, {0.9, 1.3274, 0.0882}}},
      {100, {{0.25, 0.1247, 0.0354}, {0.5, 0.3536, 0.0707}, {0.9, 1.9167, 0.1273}}},
      {200, {{0.25, 0.1801, 0.0511}, {0.5, 0.5106, 0.1021}, {0.9, 2.7675, 0.1838}}}};
  for (const auto& [confinement, rows] : table) {
    const double sigma_3 = confinement * kPa;
    Point point{model, Stress{-sigma_3, -sigma_3, -sigma_3, 0.0, 0.0, 0.0}, {0.0, 1e12}};
    const double qf = model.failure_deviator(sigma_3);
    std::size_t next = 0;
    double previous_q = 0.0, previous_axial = 0.0, previous_volumetric = 0.0;
    while (next < rows.size()) {
      point.triaxial(2e-6);
      const double q = point.axial() - point.lateral();
      while (next < rows.size() && q >= rows[next].fraction * qf) {
        // Interpolate the strains at the tabulated deviator.
        const double w = (rows[next].fraction * qf - previous_q) / (q - previous_q);
        const double axial = previous_axial + w * (point.axial_strain_total - previous_axial);
        const double volumetric =
            previous_volumetric + w * (point.volumetric_strain_total - previous_volumetric);
        EXPECT_NEAR(axial * 100, rows[next].axial, 0.005 * rows[next].axial)
            << "sigma_3 = " << confinement << ", q/qf = " << rows[next].fraction;
        EXPECT_NEAR(volumetric * 100, rows[next].volumetric, 0.005 * rows[next].volumetric)
            << "sigma_3 = " << confinement << ", q/qf = " << rows[next].fraction;
        ++next;
      }
      previous_q = q;
      previous_axial = point.axial_strain_total;
      previous_volumetric = point.volumetric_strain_total;
      ASSERT_LT(point.axial_strain_total, 0.1);
    }
  }
}

TEST(HardeningSoil, TriaxialFailureAtTheMohrCoulombDeviator) {
  const HardeningSoil model(seed_parameters());
  const double sigma_3 = 100 * kPa;
  Point point{model, Stress{-sigma_3, -sigma_3, -sigma_3, 0.0, 0.0, 0.0}, {0.0, 1e12}};
  for (int k = 0; k < 1500; ++k) {
    point.triaxial(1e-4); // to 15 % axial strain, well past failure (4.3 %)
  }
  const double q = point.axial() - point.lateral();
  EXPECT_NEAR(q / kPa, 311.20, 0.3112); // qf, 1e-3 relative
}

TEST(HardeningSoil, TriaxialUnloadingIsElasticWithEur) {
  const HardeningSoil model(seed_parameters());
  const double sigma_3 = 100 * kPa;
  Point point{model, Stress{-sigma_3, -sigma_3, -sigma_3, 0.0, 0.0, 0.0}, {0.0, 1e12}};
  const double half = 0.5 * model.failure_deviator(sigma_3);
  while (point.axial() - point.lateral() < half) {
    point.triaxial(1e-6);
  }
  const double q_before = point.axial() - point.lateral();
  const double axial_before = point.axial_strain_total;
  point.triaxial(-1e-5);
  const double slope =
      (q_before - (point.axial() - point.lateral())) / (axial_before - point.axial_strain_total);
  EXPECT_NEAR(slope / kPa, 132000, 132.0); // Eur at sigma_3 = 100 kPa, 1e-3 relative
  while (point.axial() - point.lateral() > 0.0) {
    point.triaxial(-1e-6);
  }
  // Residual axial strain after unloading from qf/2: 0.2358 % (hardening_soil.md 3.3).
  EXPECT_NEAR(point.axial_strain_total * 100, 0.2358, 0.005 * 0.2358);
}

TEST(HardeningSoil, OedometerGivesK0ncEoedAndTheReferenceState) {
  const HardeningSoil model(seed_parameters());
  Point point{model, Stress{-0.5 * kPa, -1.0 * kPa, -0.5 * kPa, 0.0, 0.0, 0.0}, {}};
  model.initialise_state(point.stress, point.state.data());
  // sigma_1 (kPa), eps_1 from 1 kPa (%), tangent Eoed (kPa).
  const double rows[][3] = {{50, 0.2597, 31766}, {100, 0.3915, 44000}, {200, 0.5819, 60945}};
  double axial = 0.0;
  for (const auto& row : rows) {
    const double target = row[0] * kPa;
    double previous_sigma = point.axial(), previous_axial = axial;
    while (point.axial() < target) {
      previous_sigma = point.axial();
      previous_axial = axial;
      point.strain({0.0, -2e-6, 0.0, 0.0, 0.0, 0.0});
      axial += 2e-6;
    }
    const double w = (target - previous_sigma) / (point.axial() - previous_sigma);
    const double axial_at = previous_axial + w * (axial - previous_axial);
    EXPECT_NEAR(axial_at * 100, row[1], 0.005 * row[1]) << "sigma_1 = " << row[0];
    EXPECT_NEAR(point.lateral() / point.axial(), 0.5, 0.002) << "sigma_1 = " << row[0];
    const double tangent = (point.axial() - previous_sigma) / 2e-6;
    EXPECT_NEAR(tangent / kPa, row[2], 2e-3 * row[2]) << "sigma_1 = " << row[0];
    if (row[0] == 100) {
      EXPECT_NEAR(point.state[HardeningSoil::P_P] / kPa, 82.77, 0.005 * 82.77);
      EXPECT_NEAR(point.state[HardeningSoil::GAMMA_P], 1.3755e-3, 0.005 * 1.3755e-3);
    }
  }
  // Unloading from sigma_1 = 200 kPa (sigma_3 = 100 kPa) starts elastic.
  const double sigma_1 = point.axial(), sigma_3 = point.lateral();
  point.strain({0.0, 1e-6, 0.0, 0.0, 0.0, 0.0});
  const double modulus = (sigma_1 - point.axial()) / 1e-6;
  EXPECT_NEAR(modulus / (1.1111111 * model.unloading_modulus(sigma_3)), 1.0, 1e-3);
  EXPECT_NEAR((sigma_3 - point.lateral()) / (sigma_1 - point.axial()), 0.25, 1e-3);
}

TEST(HardeningSoil, YieldDeviatorSlopesAreItsDerivatives) {
  // The return's Newton iteration takes its Jacobian from these slopes. Central differences with a
  // step of 1e-6 of the variable have a truncation error of about 1e-12 and a rounding error of
  // about 1e-10 relative, so 1e-6 relative separates a right slope from a wrong term by far.
  const HardeningSoil model(seed_parameters());
  for (const double sigma_3 : {0.5 * kPa, 5 * kPa, 50 * kPa, 100 * kPa, 800 * kPa}) {
    for (const double gamma : {1e-6, 1e-4, 1e-3, 2e-2}) {
      const YieldDeviator y = model.yield_deviator_slopes(gamma, sigma_3);
      EXPECT_EQ(y.value, model.yield_deviator(gamma, sigma_3));
      const double dg = 1e-6 * gamma, ds = 1e-6 * sigma_3;
      const double by_gamma =
          (model.yield_deviator(gamma + dg, sigma_3) - model.yield_deviator(gamma - dg, sigma_3)) /
          (2.0 * dg);
      const double by_sigma =
          (model.yield_deviator(gamma, sigma_3 + ds) - model.yield_deviator(gamma, sigma_3 - ds)) /
          (2.0 * ds);
      const double at_failure = y.value == model.failure_deviator(sigma_3) ? 1.0 : 0.0;
      EXPECT_NEAR(y.by_gamma, by_gamma, 1e-6 * std::abs(by_gamma) + 1e-9 * at_failure)
          << "sigma_3 = " << sigma_3 << ", gamma = " << gamma;
      EXPECT_NEAR(y.by_sigma, by_sigma, 1e-6 * std::abs(by_sigma))
          << "sigma_3 = " << sigma_3 << ", gamma = " << gamma;
    }
  }
  // Below the stiffness floor the factor is constant: only qa carries the stress.
  HardeningSoilParameters floored = seed_parameters();
  floored.stiffness_floor = 0.2;
  const HardeningSoil low(floored);
  const double sigma_3 = 5 * kPa, gamma = 1e-4, ds = 1e-6 * sigma_3;
  const double by_sigma =
      (low.yield_deviator(gamma, sigma_3 + ds) - low.yield_deviator(gamma, sigma_3 - ds)) /
      (2.0 * ds);
  EXPECT_NEAR(low.yield_deviator_slopes(gamma, sigma_3).by_sigma, by_sigma, 1e-6 * by_sigma);
}

TEST(HardeningSoil, TheStiffnessFactorsSeriesIsThePowerLawToRounding) {
  // Near a remembered ratio the update takes ratio^m from a binomial series to x^8 (x the relative
  // distance, |x| <= 2^-6) instead of std::pow. The series' remainder is below 7e-18 of the factor
  // (stiffness_factor's comment); Horner's rule, the quotient x and the last product round at
  // about an ulp, and std::pow is within one: 4 ulps (8.9e-16 relative) is the bound asked. A wrong
  // coefficient or sign shows by orders of magnitude, and so would the series used out to 2^-4
  // (its next term alone is about 1e-13 there).
  std::mt19937 random(68);
  for (const double power : {0.1, 0.47, 0.5, 0.75, 0.99}) {
    HardeningSoilParameters parameters = seed_parameters();
    parameters.power = power;
    const HardeningSoil model(parameters);
    // Offsets to four times the series' range, so that a series used too far would show too.
    std::uniform_real_distribution<double> anchor(0.01, 20.0), offset(-0x1p-4, 0x1p-4);
    const double edge = (1.0 - 1e-9) * 0x1p-6; // just inside the range (rounding of the ratio)
    for (int k = 0; k < 4000; ++k) {
      HardeningSoil::StiffnessFactorMemo memo;
      const double remembered = anchor(random);
      // The first evaluation is the power law itself, and the same ratio gives it again.
      ASSERT_EQ(model.stiffness_factor(remembered, memo), std::pow(remembered, power));
      ASSERT_EQ(model.stiffness_factor(remembered, memo), std::pow(remembered, power));
      const double x = k % 100 == 0 ? (k % 200 == 0 ? edge : -edge) : offset(random);
      const double ratio = remembered * (1.0 + x);
      const double exact = std::pow(ratio, power);
      ASSERT_NEAR(model.stiffness_factor(ratio, memo), exact, 8.9e-16 * exact)
          << "m = " << power << ", ratio " << remembered << " * (1 + " << x << ")";
      if (std::abs(x) <= edge) {
        ASSERT_EQ(memo.ratio, remembered); // the series does not move what it is anchored at
      }
    }
    // Farther away the power law is evaluated and remembered.
    HardeningSoil::StiffnessFactorMemo memo;
    model.stiffness_factor(1.0, memo);
    EXPECT_EQ(model.stiffness_factor(1.1, memo), std::pow(1.1, power));
    EXPECT_EQ(memo.ratio, 1.1);
  }
}

TEST(HardeningSoil, IsotropicCompressionTangentOnTheCap) {
  const HardeningSoil model(seed_parameters());
  const double p = 100 * kPa;
  Point point{model, Stress{-p, -p, -p, 0.0, 0.0, 0.0}, {}};
  model.initialise_state(point.stress, point.state.data());
  // Load a little first so the cap is active, then measure dp/deps_v at p = 100 kPa.
  double previous = point.axial();
  for (int k = 0; k < 3; ++k) {
    previous = point.axial();
    point.strain({-1e-7, -1e-7, -1e-7, 0.0, 0.0, 0.0});
  }
  const double tangent = (point.axial() - previous) / 3e-7;
  EXPECT_NEAR(tangent / kPa, 40256, 40.256); // hardening_soil.md 3.3, 1e-3 relative
}

} // namespace
} // namespace mpile

namespace mpile {
namespace {

/// Largest violation of the shear, cap and tension conditions at a state, relative to the stress
/// level (p_ref or the major principal stress, whichever is larger).
double violation(const HardeningSoil& model, const Stress& stress, const double* state,
                 double p_ref) {
  const PrincipalStress principal = principal_compression(stress);
  const auto& s = principal.values;
  const double shear = s[0] - s[2] - model.yield_deviator(state[HardeningSoil::GAMMA_P], s[2]);
  const double cap = model.cap_surface(s, state[HardeningSoil::P_P]);
  const double tension = -s[2];
  return std::max({shear, cap, tension, 0.0}) / std::max(p_ref, std::abs(s[0]));
}

/// Strain increments of log-uniform size in random directions of all six components (theta shears
/// included, so the trials rotate as under torsion), with a compressive bias so that a walk keeps
/// visiting confined states and not only the apex.
class RandomIncrements {
public:
  RandomIncrements(double smallest, double largest, unsigned seed)
      : random_(seed), exponent_(std::log10(smallest), std::log10(largest)) {}
  StrainIncrement next() {
    StrainIncrement de;
    const double size = std::pow(10.0, exponent_(random_));
    for (double& c : de) {
      c = size * direction_(random_);
    }
    de[RR] -= 0.3 * size;
    de[YY] -= 0.3 * size;
    de[TT] -= 0.3 * size;
    return de;
  }

private:
  std::mt19937_64 random_;
  std::uniform_real_distribution<double> direction_{-1.0, 1.0};
  std::uniform_real_distribution<double> exponent_;
};

/// A random walk of strain increments (RandomIncrements). Returns the worst violation.
double random_walk(const HardeningSoil& model, double p_ref, int increments, double smallest,
                   double largest, unsigned seed) {
  RandomIncrements increment(smallest, largest, seed);
  Stress stress{-50 * kPa, -100 * kPa, -50 * kPa, 0.0, 0.0, 0.0};
  double state[3];
  model.initialise_state(stress, state);
  double worst = 0.0;
  for (int k = 0; k < increments; ++k) {
    const StrainIncrement de = increment.next();
    model.update_point(stress, state, de);
    for (const double c : stress) {
      EXPECT_TRUE(std::isfinite(c)) << "increment " << k;
      if (!std::isfinite(c)) {
        return 1e300;
      }
    }
    worst = std::max(worst, violation(model, stress, state, p_ref));
    if (-(stress[RR] + stress[YY] + stress[TT]) / 3.0 > 50e6) {
      // Keep the walk in the range of soil stresses: restart from a K0 state.
      stress = Stress{-50 * kPa, -100 * kPa, -50 * kPa, 0.0, 0.0, 0.0};
      model.initialise_state(stress, state);
    }
  }
  return worst;
}

TEST(HardeningSoil, AMillionRandomIncrementsStayOnOrInsideTheSurfaces) {
  const HardeningSoilParameters parameters = seed_parameters();
  const HardeningSoil model(parameters);
  // Increments of the size explicit MPM produces (1e-8 to 1e-4). hardening_soil.md asks for
  // f <= 1e-8 p_ref after every return; at stresses of tens of MPa the return itself is solved to
  // 1e-10 of the stress, so the criterion is taken relative to the stress level.
  EXPECT_LE(random_walk(model, parameters.p_ref, 1000000, 1e-8, 1e-4, 2024), 1e-8);
}

TEST(HardeningSoil, VeryLargeIncrementsStayOnOrInsideTheSurfaces) {
  const HardeningSoilParameters parameters = seed_parameters();
  const HardeningSoil model(parameters);
  // Strain increments up to 10 %: substepping and the sequential fallback keep the state
  // admissible.
  EXPECT_LE(random_walk(model, parameters.p_ref, 5000, 1e-4, 1e-1, 7), 1e-8);
}

// Each plastic return first tries the active set the particle's last return kept, and keeps its
// state if it satisfies every surface and the principal order (a corner variant only at its
// corner). That must be the state the ordered search alone finds: every increment of a random walk
// is taken twice from the same state, once as stored and once with the last active set cleared.
TEST(HardeningSoil, TheLastActiveSetGivesTheOrderedSearchsState) {
  const HardeningSoilParameters parameters = seed_parameters();
  const HardeningSoil model(parameters);
  RandomIncrements increment(1e-7, 1e-4, 11);
  Stress stress{-50 * kPa, -100 * kPa, -50 * kPa, 0.0, 0.0, 0.0};
  double state[3];
  model.initialise_state(stress, state);
  double worst_stress = 0.0, worst_gamma = 0.0, worst_cap = 0.0;
  int kept = 0;
  for (int k = 0; k < 200000; ++k) {
    const StrainIncrement de = increment.next();
    Stress searched = stress;
    double searched_state[3] = {state[0], state[1], 0.0};
    model.update_point(searched, searched_state, de);
    const double before = state[HardeningSoil::LAST_ACTIVE_SET];
    model.update_point(stress, state, de);
    const bool plastic = state[HardeningSoil::GAMMA_P] != searched_state[HardeningSoil::GAMMA_P] ||
                         searched_state[HardeningSoil::LAST_ACTIVE_SET] != 0.0;
    kept += plastic && before != 0.0 && state[HardeningSoil::LAST_ACTIVE_SET] == before ? 1 : 0;
    double level = parameters.p_ref;
    for (const double c : searched) {
      level = std::max(level, std::abs(c));
    }
    for (std::size_t c = 0; c < 6; ++c) {
      worst_stress = std::max(worst_stress, std::abs(stress[c] - searched[c]) / level);
    }
    worst_gamma = std::max(worst_gamma, std::abs(state[0] - searched_state[0]) /
                                            std::max(searched_state[0], 1e-6));
    worst_cap = std::max(worst_cap, std::abs(state[1] - searched_state[1]) / searched_state[1]);
    if (-(stress[RR] + stress[YY] + stress[TT]) / 3.0 > 50e6) {
      stress = Stress{-50 * kPa, -100 * kPa, -50 * kPa, 0.0, 0.0, 0.0};
      model.initialise_state(stress, state);
    }
  }
  std::cout << kept << " returns kept the last active set; largest differences from the ordered "
            << "search: stress " << worst_stress << ", gamma_p " << worst_gamma << ", p_p "
            << worst_cap << " (relative)\n";
  // Both solve the same surfaces to 1e-10 of the stress level, so where two active sets meet
  // within that their states may differ by the tolerance over the return's conditioning: up to
  // 1e-8 was measured on the quick GDP scene (docs/hardening-soil.md), 1.5e-15 on this walk.
  // Without the rule that a corner variant counts only at its corner the walk differs by 4e-2.
  EXPECT_GT(kept, 10000);
  EXPECT_LE(worst_stress, 1e-8);
  EXPECT_LE(worst_gamma, 1e-8);
  EXPECT_LE(worst_cap, 1e-8);
}

TEST(HardeningSoil, ResponseDoesNotDependOnTheFrame) {
  const HardeningSoil model(seed_parameters());
  const Stress start{-50 * kPa, -100 * kPa, -50 * kPa, 0.0, 0.0, 0.0};
  // The same physical path in the (r, y, theta) frame and in a rotated frame.
  const Eigen::Matrix3d rotation =
      (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, 0.5).normalized())).toRotationMatrix();
  Stress a = start;
  Stress b = from_matrix(rotation * to_matrix(start) * rotation.transpose());
  double state_a[3], state_b[3];
  model.initialise_state(a, state_a);
  model.initialise_state(b, state_b);
  const StrainIncrement step{2e-5, -6e-5, 1e-5, 3e-5, -2e-5, 4e-5};
  const StrainIncrement rotated =
      from_matrix(rotation * to_matrix(step, true) * rotation.transpose(), true);
  for (int k = 0; k < 400; ++k) {
    model.update_point(a, state_a, step);
    model.update_point(b, state_b, rotated);
  }
  const auto pa = principal_compression(a).values;
  const auto pb = principal_compression(b).values;
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(pa[i], pb[i], 1e-6 * kPa); // rounding of the rotations only
  }
  EXPECT_NEAR(state_a[0], state_b[0], 1e-12);
  EXPECT_NEAR(state_a[1], state_b[1], 1e-6);
}

TEST(HardeningSoil, TensionGoesToTheApexAndZeroConfinementStaysFinite) {
  const HardeningSoil model(seed_parameters());
  Stress stress{-10 * kPa, -20 * kPa, -10 * kPa, 0.0, 0.0, 0.0};
  double state[3];
  model.initialise_state(stress, state);
  model.update_point(stress, state, {1e-2, 1e-2, 1e-2, 0.0, 0.0, 0.0}); // large extension
  for (const double c : stress) {
    EXPECT_EQ(c, 0.0); // c = 0, no tension: the apex is the stress-free state
  }
  // Shearing the stress-free point leaves it stress free (no strength at zero confinement).
  model.update_point(stress, state, {0.0, 0.0, 0.0, 1e-3, 1e-3, 0.0});
  for (const double c : stress) {
    EXPECT_NEAR(c, 0.0, 1e-6);
  }
}

TEST(HardeningSoil, MobilisedDilatancyExpandsTheSampleNearFailure) {
  HardeningSoilParameters parameters = seed_parameters();
  parameters.dilatancy_angle = 10.0;
  const HardeningSoil model(parameters);
  const double sigma_3 = 100 * kPa;
  Point point{model, Stress{-sigma_3, -sigma_3, -sigma_3, 0.0, 0.0, 0.0}, {0.0, 1e12}};
  double smallest_volumetric = 1.0;
  for (int k = 0; k < 1000; ++k) {
    point.triaxial(1e-4);
    smallest_volumetric = std::min(smallest_volumetric, point.volumetric_strain_total);
  }
  // At failure (sin phi_m = sin phi) Rowe's law gives sin psi_m = sin psi: the rate of volumetric
  // strain against axial strain tends to -2 sin psi / (1 - sin psi) for the plastic part.
  Point late = point;
  const double before = late.volumetric_strain_total;
  late.triaxial(1e-3);
  const double rate = (late.volumetric_strain_total - before) / 1e-3;
  const double s = std::sin(10.0 * std::numbers::pi / 180.0);
  EXPECT_NEAR(rate, -2.0 * s / (1.0 - s), 0.02);
  EXPECT_LT(point.volumetric_strain_total, smallest_volumetric + 1e-12); // still dilating
}

} // namespace
} // namespace mpile

namespace mpile {
namespace {

TEST(HardeningSoil, OverconsolidatedInitialStateSitsOnTheSurfacesOfItsPreconsolidation) {
  // sigma_v = 100 kPa with OCR = 2 (or POP = 100 kPa) remembers sigma_p = 200 kPa on the NC line:
  // the cap and shear surfaces of the NC oedometer state at sigma_1 = 200 kPa, which the oedometer
  // test above reaches with p_p = 165.57 kPa and gamma_p = 1.9865e-3.
  for (const auto& [ocr, pop] : {std::pair{2.0, 0.0}, std::pair{1.0, 100e3}}) {
    HardeningSoilParameters parameters = seed_parameters();
    parameters.ocr = ocr;
    parameters.pop = pop;
    const HardeningSoil model(parameters);
    double state[3];
    model.initialise_state(Stress{-50 * kPa, -100 * kPa, -50 * kPa, 0.0, 0.0, 0.0}, state);
    EXPECT_NEAR(state[HardeningSoil::P_P] / kPa, 165.57, 0.005 * 165.57) << "OCR " << ocr;
    EXPECT_NEAR(state[HardeningSoil::GAMMA_P], 1.9865e-3, 0.005 * 1.9865e-3) << "OCR " << ocr;
    // Reloading from the overconsolidated state is elastic: neither surface moves.
    const double cap_before = state[HardeningSoil::P_P];
    const double gamma_before = state[HardeningSoil::GAMMA_P];
    Stress stress{-50 * kPa, -100 * kPa, -50 * kPa, 0.0, 0.0, 0.0};
    model.update_point(stress, state, {0.0, -1e-5, 0.0, 0.0, 0.0, 0.0});
    EXPECT_EQ(state[HardeningSoil::P_P], cap_before);
    EXPECT_EQ(state[HardeningSoil::GAMMA_P], gamma_before);
    EXPECT_LT(stress[YY], -100 * kPa); // it did load
  }
}

} // namespace
} // namespace mpile
