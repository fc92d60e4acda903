#pragma once

// The Hardening Soil model (Schanz, Vermeer and Bonnier 1999; PLAXIS form), as specified in the
// project's hardening_soil.md: stress-dependent hypoelastic unloading/reloading stiffness, a shear
// hardening surface in its yield-deviator form capped by Mohr-Coulomb failure, a volumetric cap
// whose shape alpha and modulus H are derived from K0nc and Eoed_ref, a tension cut-off with apex,
// and mobilised dilatancy. The return is implicit (closest point) in principal stress space on the
// full 3x3 stress, with active sets and corner returns.

#include "engine/materials/material.hpp"
#include "engine/parameter_range.hpp"

#include <array>
#include <span>
#include <string>
#include <vector>

namespace mpile {

/// The yield deviator min(q_y, qf) and its partial derivatives, for Newton's method in the return.
struct YieldDeviator {
  double value = 0.0;
  double by_gamma = 0.0; // d/d gamma_p
  double by_sigma = 0.0; // d/d sigma_3
};

struct HardeningSoilParameters {
  double e50_ref = 0.0;          // Pa, triaxial secant stiffness at p_ref
  double eoed_ref = 0.0;         // Pa, oedometer tangent stiffness at sigma_1 = p_ref
  double eur_ref = 0.0;          // Pa, unloading/reloading stiffness at p_ref
  double power = 0.5;            // m, stress dependency of stiffness
  double poisson_ur = 0.2;       // unloading/reloading Poisson ratio
  double k0_nc = 0.5;            // normally consolidated K0
  double failure_ratio = 0.9;    // Rf = qf / qa
  double p_ref = 100e3;          // Pa
  double friction_angle = 30.0;  // degrees
  double dilatancy_angle = 0.0;  // degrees (ultimate)
  double cohesion = 0.0;         // Pa
  double tension_limit = 0.0;    // Pa, sigma_i >= -tension_limit
  double stiffness_floor = 0.01; // lower bound of the stress ratio in the stiffness laws
  double cap_floor = 1e3;        // Pa, lower bound of the cap pressure p_p
  double ocr = 1.0;              // over-consolidation ratio of the initial state
  double pop = 0.0;              // Pa, pre-overburden pressure of the initial state
  double density = 0.0;          // kg/m^3
};

/// A parameter declared once: its key, its member (whose initialiser is an optional one's default),
/// unit, range and meaning. The material registry builds the case's keys from it; the constructor
/// checks each range through it. The cap's alpha and H are derived, never given
/// (docs/hardening-soil.md).
struct HardeningSoilField {
  const char* name;
  double HardeningSoilParameters::*member;
  bool optional;
  const char* unit;
  ParameterRange range;
  const char* meaning;
};
std::span<const HardeningSoilField> hardening_soil_fields();

class HardeningSoil final : public Material {
public:
  /// Validates the parameters and derives alpha and H (throws std::invalid_argument naming the
  /// parameter, or the stiffness ratios when no cap can reproduce K0nc and Eoed_ref).
  explicit HardeningSoil(const HardeningSoilParameters& parameters);

  std::string_view type() const override { return "hardening_soil"; }
  double density() const override { return parameters_.density; }
  std::span<const std::string> state_names() const override { return names_; }
  void initialise_state(const Stress& stress, double* state) const override;
  void update_stress(const StressUpdateBatch& batch) const override;
  double constrained_modulus(const Stress& stress, const double* state) const override;
  /// Eur(sigma_3) / (2 (1 + nu_ur)), the unloading-reloading shear stiffness.
  double shear_modulus(const Stress& stress, const double* state) const override;
  double elastic_energy_density(const Stress& stress, const double* state) const override;

  /// Advances one material point; returns the constrained modulus used.
  double update_point(Stress& stress, double* state, const StrainIncrement& strain) const;

  // Model functions, public for the element tests (compression positive, Pa).
  double alpha() const { return alpha_; }
  double cap_modulus() const { return cap_modulus_; }
  double unloading_modulus(double sigma_3) const;              // Eur(sigma_3)
  double secant_modulus(double sigma_3) const;                 // E50(sigma_3)
  double oedometer_modulus(double sigma_1) const;              // Eoed(sigma_1)
  double failure_deviator(double sigma_3) const;               // qf
  double yield_deviator(double gamma_p, double sigma_3) const; // min(q_y, qf)
  YieldDeviator yield_deviator_slopes(double gamma_p, double sigma_3) const;

  /// The stiffness laws' power of the stress ratio, ratio^m, where it was last evaluated. A point's
  /// update evaluates it again and again at nearly the same sigma_3 (the start's stiffness, the
  /// trial's yield deviator, each Newton iterate, the check of the result); near the remembered
  /// ratio a series replaces the power law, equal to it to rounding (stiffness_factor). One memo
  /// serves one batch's updates (neighbours in a block of the grid lie at similar sigma_3): it is
  /// never shared between threads.
  struct StiffnessFactorMemo {
    double ratio = 0.0, factor = 0.0;
  };
  /// update_point with the memo of the updates before it in the same batch.
  double update_point(Stress& stress, double* state, const StrainIncrement& strain,
                      StiffnessFactorMemo& memo) const;
  double yield_deviator(double gamma_p, double sigma_3, StiffnessFactorMemo& memo) const;
  YieldDeviator yield_deviator_slopes(double gamma_p, double sigma_3,
                                      StiffnessFactorMemo& memo) const;
  /// ratio^m: from the memo's series within 2^-6 of its ratio, else the power law, remembered.
  double stiffness_factor(double ratio, StiffnessFactorMemo& memo) const;
  double hardening_function(double q, double sigma_3) const;         // f-bar
  double cap_deviator(const std::array<double, 3>& principal) const; // q-tilde
  double cap_surface(const std::array<double, 3>& principal, double p_p) const;

  /// Indices of the state variables. LAST_ACTIVE_SET is the active set the last plastic return
  /// kept (0: none yet; 1 + 3 mechanism + corner, mechanisms 0 shear, 1 cap, 2 both, corners 0
  /// plane, 1 triaxial compression, 2 triaxial extension); the next return tries it first.
  enum : int { GAMMA_P = 0, P_P = 1, LAST_ACTIVE_SET = 2 };

private:
  /// One substep of update_point at Young's modulus `young` and mobilised dilatancy sin_psi: the
  /// elastic trial and, outside the surfaces, the return. Returns the constrained modulus.
  double substep(Stress& stress, double* state, const StrainIncrement& part, double young,
                 double sin_psi, StiffnessFactorMemo& memo) const;
  double unloading_modulus(double sigma_3, StiffnessFactorMemo& memo) const;
  double stress_ratio(double sigma) const;
  /// The yield deviator's hyperbola at sigma_3 (with qf > 0): the stiffnesses' stress ratio (raw
  /// and floored), A = 2 / E_i, B = 2 / Eur and the asymptote qa.
  struct YieldHyperbola {
    double raw_ratio, ratio, A, B, qa;
  };
  YieldHyperbola yield_hyperbola(double qf, double sigma_3, StiffnessFactorMemo& memo) const;
  void derive_cap();

  HardeningSoilParameters parameters_;
  std::vector<std::string> names_{"gamma_p", "p_p", "last_active_set"};
  double sin_phi_, cos_phi_, sin_psi_, a_, delta_, alpha_ = 1.0, cap_modulus_ = 0.0;
  std::array<double, 8> binomial_{}; // binomial(power, k), k = 1 .. 8 (stiffness_factor)
  // 1 / (c cos phi + p_ref sin phi), 2 sin phi / (1 - sin phi), 1 / Rf, (2 - Rf) / E50_ref,
  // 2 / Eur_ref and 1 / alpha^2: the laws' constants, as products (see the constructor).
  double inverse_ratio_denominator_ = 0.0, qf_coefficient_ = 0.0, inverse_failure_ratio_ = 0.0;
  double a_coefficient_ = 0.0, b_coefficient_ = 0.0, inverse_alpha2_ = 0.0;
};

} // namespace mpile
