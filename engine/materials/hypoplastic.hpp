#pragma once

// Hypoplasticity for sand: von Wolffersdorff (1996, Mech. Cohes.-Frict. Mater. 1:251-271) with
// Bauer's compression law for the limit void ratios e_d, e_c, e_i, and the intergranular strain of
// Niemunis and Herle (1997, Mech. Cohes.-Frict. Mater. 2:279-299), which keeps small cycles from
// ratcheting and gives the stiffness after a reversal. A rate form without a yield surface: each
// strain increment is integrated by Heun's method with its embedded Euler error, in substeps sized
// to a relative tolerance (docs/hypoplasticity.md). State: the void ratio and the intergranular
// strain tensor h (all six components, theta included).

#include "engine/materials/material.hpp"
#include "engine/parameter_range.hpp"

#include <span>
#include <string>
#include <vector>

namespace mpile {

struct HypoplasticParameters {
  double critical_friction_angle = 0.0; // phi_c, degrees
  double granular_hardness = 0.0;       // h_s, Pa
  double exponent = 0.0;                // n
  double e_d0 = 0.0;                    // minimum void ratio at zero pressure
  double e_c0 = 0.0;                    // critical void ratio at zero pressure
  double e_i0 = 0.0;                    // maximum void ratio at zero pressure
  double alpha = 0.0;                   // pycnotropy exponent of f_d (peak, dilatancy)
  double beta = 0.0;                    // pycnotropy exponent of f_e (stiffness)
  double void_ratio = 0.0;              // e0, the initial void ratio
  // Intergranular strain; intergranular_strain = 0 switches it off (pure hypoplasticity).
  double intergranular_strain = 1.0; // 1: on, 0: off
  double r_max = 1e-4;               // R, the radius of the elastic range in strain
  double m_r = 5.0;                  // stiffness multiplier after a 180 degree reversal
  double m_t = 2.0;                  // stiffness multiplier after a 90 degree change of direction
  double beta_r = 0.5;               // evolution exponent of h
  double chi = 6.0;                  // interpolation exponent between m_R L and the hypoplastic M
  double tolerance = 1e-5;           // relative error per substep of the integration
  double minimum_pressure = 100.0;   // Pa: p below it is raised to it, isotropically (no tension)
  double density = 0.0;              // kg/m^3, initial bulk density
};

/// A parameter declared once, as Hardening Soil's are: key, member, optional (the member's
/// initialiser is then its default), unit, range and meaning.
struct HypoplasticField {
  const char* name;
  double HypoplasticParameters::*member;
  bool optional;
  const char* unit;
  ParameterRange range;
  const char* meaning;
};
std::span<const HypoplasticField> hypoplastic_fields();

/// One material point's state in tensor form (tension positive), for the rate and its tests.
struct HypoplasticPoint {
  Stress stress{}; // sigma (rr, yy, thth, ry, ytheta, rtheta)
  double e = 0.0;  // void ratio
  Stress h{};      // intergranular strain, tensor components (not engineering shear)
};

class Hypoplastic final : public Material {
public:
  /// Validates the parameters (throws std::invalid_argument naming the key and its range).
  explicit Hypoplastic(const HypoplasticParameters& parameters);

  std::string_view type() const override { return "hypoplastic"; }
  double density() const override { return parameters_.density; }
  std::span<const std::string> state_names() const override { return names_; }
  int void_ratio_index() const override { return VOID_RATIO; }
  void initialise_state(const Stress& stress, double* state) const override;
  Inadmissible inadmissible_state(const Stress& stress, const double* state) const override;
  void update_stress(const StressUpdateBatch& batch) const override;
  /// The largest normal stiffness of the tangent after a reversal, m_R (L_yyyy + |N|): the time
  /// step's modulus.
  double constrained_modulus(const Stress& stress, const double* state) const override;
  /// The small-strain shear modulus m_R f_b f_e F^2 / (2 s:s).
  double shear_modulus(const Stress& stress, const double* state) const override;
  /// A hypoplastic material has no elastic potential: the energy of an isotropic linear material
  /// with the small-strain bulk and shear moduli at this stress (for the energy ledger only).
  double elastic_energy_density(const Stress& stress, const double* state) const override;

  /// Advances one point by a strain increment (engineering shear); returns the constrained modulus.
  double update_point(Stress& stress, double* state, const StrainIncrement& strain) const;

  /// The rate (per unit of the strain-rate tensor D, tension positive, tensor shear) of stress,
  /// void ratio and intergranular strain at a state: the model's equations. With `modulus`, also
  /// the bound on the constrained modulus constrained_modulus gives, from the same tangent.
  HypoplasticPoint rate(const HypoplasticPoint& at, const Stress& d,
                        double* modulus = nullptr) const;

  /// Bauer's limit void ratio e_x0 exp(-(3 p / h_s)^n) at mean pressure p (compression positive).
  double limit_void_ratio(double e_x0, double p) const;
  /// M_c = 6 sin phi_c / (3 - sin phi_c), the critical stress ratio q / p in compression.
  double critical_stress_ratio() const;

  /// GAP_RATIO: the void ratio of the gaps a particle stretched at the floor pressure has opened
  /// beyond e_i(p_min), which hold no grains in contact; the particle's volume is that of 1 + e +
  /// gap_ratio solid volumes.
  enum : int { VOID_RATIO = 0, H_FIRST = 1, SUBSTEP = 7, GAP_RATIO = 8 };

private:
  HypoplasticParameters parameters_;
  std::vector<std::string> names_{"void_ratio", "h_rr",     "h_yy",    "h_thth",   "h_ry",
                                  "h_ytheta",   "h_rtheta", "substep", "gap_ratio"};
  double a_ = 0.0; // von Wolffersdorff's a from phi_c
  // f_b's constant factor: h_s / n (e_i0 / e_c0)^beta / (3 + a^2 - a sqrt(3) ((e_i0 - e_d0) /
  // (e_c0 - e_d0))^alpha).
  double f_b_scale_ = 0.0;
};

} // namespace mpile
