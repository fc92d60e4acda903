// The Hardening Soil model (docs/hardening-soil.md): stiffness that grows with confinement, a shear
// surface that hardens with plastic shear strain and a cap that hardens with compaction.
//
// Outline:
//   helpers: root finders (decreasing_root, root_from_zero), surface_tolerance, the elastic
//     constants of a (sub)step, the mechanisms (three shear planes and the cap), ReturnState
//   HardeningSoil: the constructor (parameters checked), moduli and surfaces (stress ratio, E_ur,
//     E_50, E_oed, q_f, the stiffness factor's memo, the yield hyperbola and its slopes, the
//     hardening function, the cap),
//     derive_cap, the state's start, the elastic moduli and energy, update_stress (a batch)
//   HardeningSoilReturn: one implicit return with frozen moduli and directions: residuals, shear
//     multipliers split over planes and corners, linearised states, Newton's method on a shear
//     plane or corner, on the cap and on both, and the bracketed returns behind them
//   the choice of return: shear_alone_can_hold, ordered, substep_count, mobilised_dilatancy,
//     return_to_surfaces (the last active set, then every set in order, then alternation)
//   HardeningSoil::update_point and substep: one point's update, split into substeps
#include "engine/materials/hardening_soil.hpp"

#include "engine/angles.hpp"
#include "engine/materials/principal_stress.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>

namespace mpile {

namespace {

using Principal = std::array<double, 3>;

double mean(const Principal& s) {
  return (s[0] + s[1] + s[2]) / 3.0;
}

/// Root of a function that decreases on [low, high], with f(low) > 0 >= f(high) = f_high: the
/// Illinois variant of regula falsi, which keeps the bracket and converges superlinearly.
template <class F>
double decreasing_root(F f, double low, double f_low, double high, double f_high,
                       double tolerance) {
  if (f_low <= 0.0) {
    return low;
  }
  int side = 0;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double x = (low * f_high - high * f_low) / (f_high - f_low);
    const double fx = f(x);
    if (std::abs(fx) <= tolerance || high - low <= 1e-15 * std::abs(high)) {
      return x;
    }
    if (fx > 0.0) {
      low = x;
      f_low = fx;
      if (side == 1) {
        f_high *= 0.5;
      }
      side = 1;
    } else {
      high = x;
      f_high = fx;
      if (side == -1) {
        f_low *= 0.5;
      }
      side = -1;
    }
  }
  return 0.5 * (low + high);
}

/// Root of a function that decreases from f(0) = f_zero > 0: the bracket's upper end grows from
/// high by a factor until f is no longer positive there (at most max_growth times), and its value
/// there is passed on rather than evaluated again (each evaluation may be a whole inner return).
template <class F>
double root_from_zero(F f, double f_zero, double high, double factor, int max_growth,
                      double tolerance) {
  double f_high = f(high);
  for (int k = 0; k < max_growth && f_high > 0.0; ++k) {
    high *= factor;
    f_high = f(high);
  }
  return decreasing_root(f, 0.0, f_zero, high, f_high, tolerance);
}

/// How far outside a surface a stress may lie and count as on it: 1e-10 of the larger of p_ref and
/// the largest principal stress.
double surface_tolerance(const Principal& s, double p_ref) {
  double largest = p_ref;
  for (const double value : s) {
    largest = std::max(largest, std::abs(value));
  }
  return 1e-10 * largest;
}

/// Elastic constants of one (sub)step, frozen at its start.
struct Elasticity {
  double bulk, shear, lambda;
};

/// The plastic mechanisms of the return: three shear planes (pairs of principal stresses) and the
/// cap. A shear plane (i, j) has the potential (sigma_i - sigma_j)/2 - (sigma_i + sigma_j)/2 sin
/// psi.
enum Mechanism : int { S13 = 0, S12 = 1, S23 = 2, CAP = 3 };

struct ReturnState {
  Principal stress{};
  double gamma = 0.0;
  double cap_pressure = 0.0;
};

} // namespace

std::span<const HardeningSoilField> hardening_soil_fields() {
  static const HardeningSoilField fields[] = {
      {"e50_ref", &HardeningSoilParameters::e50_ref, false, "Pa", above(0.0),
       "triaxial secant stiffness E50 at p_ref"},
      {"eoed_ref", &HardeningSoilParameters::eoed_ref, false, "Pa", above(0.0),
       "oedometer tangent stiffness at sigma_1 = p_ref"},
      {"eur_ref", &HardeningSoilParameters::eur_ref, false, "Pa", above(0.0),
       "unloading/reloading stiffness at p_ref, above 2 E50 / (2 - Rf)"},
      {"power", &HardeningSoilParameters::power, false, "-", between(0.0, true, 1.0, false),
       "m, the stress dependency of stiffness"},
      {"poisson_ur", &HardeningSoilParameters::poisson_ur, true, "-",
       between(-1.0, false, 0.5, false), "unloading/reloading Poisson ratio"},
      {"k0_nc", &HardeningSoilParameters::k0_nc, false, "-", between(0.0, false, 1.0, false),
       "K0 of normally consolidated soil"},
      // Below 1e-3 the hyperbola's asymptote q_a = q_f / R_f is a thousand times the strength or
      // more (typical R_f: 0.75 to 1), and at 1e-308 it overflows: every return then fell back to
      // its bracketed roots, and `mpile check` ran for minutes.
      {"failure_ratio", &HardeningSoilParameters::failure_ratio, true, "-",
       between(1e-3, true, 1.0, false), "Rf = qf / qa"},
      {"p_ref", &HardeningSoilParameters::p_ref, true, "Pa", above(0.0),
       "reference stress of the stiffness laws"},
      {"friction_angle", &HardeningSoilParameters::friction_angle, false, "degrees",
       between(0.0, false, 90.0, false), "friction angle phi"},
      {"dilatancy_angle", &HardeningSoilParameters::dilatancy_angle, true, "degrees", at_least(0.0),
       "ultimate dilatancy angle psi, at most phi"},
      {"cohesion", &HardeningSoilParameters::cohesion, true, "Pa", at_least(0.0), "cohesion c"},
      {"tension_limit", &HardeningSoilParameters::tension_limit, true, "Pa", at_least(0.0),
       "tension cut-off"},
      {"stiffness_floor", &HardeningSoilParameters::stiffness_floor, true, "-",
       between(0.0, false, 1.0, true), "lower bound of the stress ratio in the stiffness laws"},
      {"cap_floor", &HardeningSoilParameters::cap_floor, true, "Pa", above(0.0),
       "lower bound of the cap pressure p_p"},
      {"ocr", &HardeningSoilParameters::ocr, true, "-", at_least(1.0),
       "over-consolidation ratio of the initial state"},
      {"pop", &HardeningSoilParameters::pop, true, "Pa", at_least(0.0),
       "pre-overburden pressure of the initial state"},
      {"density", &HardeningSoilParameters::density, false, "kg/m^3", above(0.0),
       "initial density"},
  };
  return fields;
}

HardeningSoil::HardeningSoil(const HardeningSoilParameters& p) : parameters_(p) {
  auto require = [](bool ok, const std::string& message) {
    if (!ok) {
      throw std::invalid_argument(message);
    }
  };
  for (const HardeningSoilField& f : hardening_soil_fields()) {
    require_in_range(f.name, f.range, p.*f.member);
  }
  require(p.dilatancy_angle <= p.friction_angle, "dilatancy_angle must lie in [0, friction_angle]");
  sin_phi_ = std::sin(radians(p.friction_angle));
  cos_phi_ = std::cos(radians(p.friction_angle));
  sin_psi_ = std::sin(radians(p.dilatancy_angle));
  a_ = p.cohesion > 0.0 ? p.cohesion * cos_phi_ / sin_phi_ : 0.0;
  delta_ = (3.0 + sin_phi_) / (3.0 - sin_phi_);
  // The hyperbola needs Eur > Ei = 2 E50 / (2 - Rf); otherwise f-bar is not monotonic.
  require(p.eur_ref > 2.0 * p.e50_ref / (2.0 - p.failure_ratio),
          "eur_ref must exceed 2 e50_ref / (2 - failure_ratio)");
  // Reciprocals and coefficients of the laws evaluated at every iteration of a return: products
  // where the return would divide (each division costs several multiplications' time).
  inverse_ratio_denominator_ = 1.0 / (p.cohesion * cos_phi_ + p.p_ref * sin_phi_);
  qf_coefficient_ = 2.0 * sin_phi_ / (1.0 - sin_phi_);
  inverse_failure_ratio_ = 1.0 / p.failure_ratio;
  a_coefficient_ = (2.0 - p.failure_ratio) / p.e50_ref;
  b_coefficient_ = 2.0 / p.eur_ref;
  derive_cap();
  inverse_alpha2_ = 1.0 / (alpha_ * alpha_);
  double binomial = 1.0; // binomial(m, k), k = 1 .. 8: the stiffness factor's series
  for (std::size_t k = 1; k <= binomial_.size(); ++k) {
    binomial *= (p.power - static_cast<double>(k - 1)) / static_cast<double>(k);
    binomial_[k - 1] = binomial;
  }
}

double HardeningSoil::stress_ratio(double sigma) const {
  const double ratio =
      (parameters_.cohesion * cos_phi_ + sigma * sin_phi_) * inverse_ratio_denominator_;
  return std::max(ratio, parameters_.stiffness_floor);
}

double HardeningSoil::unloading_modulus(double sigma_3) const {
  return parameters_.eur_ref * std::pow(stress_ratio(sigma_3), parameters_.power);
}

double HardeningSoil::secant_modulus(double sigma_3) const {
  return parameters_.e50_ref * std::pow(stress_ratio(sigma_3), parameters_.power);
}

double HardeningSoil::oedometer_modulus(double sigma_1) const {
  return parameters_.eoed_ref * std::pow(stress_ratio(sigma_1), parameters_.power);
}

double HardeningSoil::failure_deviator(double sigma_3) const {
  return qf_coefficient_ * std::max(sigma_3 + a_, 0.0);
}

double HardeningSoil::unloading_modulus(double sigma_3, StiffnessFactorMemo& memo) const {
  return parameters_.eur_ref * stiffness_factor(stress_ratio(sigma_3), memo);
}

double HardeningSoil::stiffness_factor(double ratio, StiffnessFactorMemo& memo) const {
  // Within 2^-6 of the remembered ratio, (1 + x)^m is its binomial series to x^8: the remainder,
  // binomial(m, 9) x^9 (1 + xi)^(m - 9) with |binomial(m, 9)| <= m / 9 < 1/9 for m in [0, 1), is
  // below 0.13 * 2^-54 = 7e-18 of the factor, a thirtieth of an ulp. With Horner's rounding the
  // factor is the power law's to about an ulp, and exactly it at the remembered ratio (x = 0; the
  // difference of two ratios within a factor two of each other is exact).
  if (memo.ratio > 0.0) {
    const double x = (ratio - memo.ratio) / memo.ratio;
    if (std::abs(x) <= 0x1p-6) {
      double series = 0.0;
      for (auto c = binomial_.rbegin(); c != binomial_.rend(); ++c) {
        series = x * (*c + series);
      }
      return memo.factor * (1.0 + series);
    }
  }
  memo = {ratio, std::pow(ratio, parameters_.power)};
  return memo.factor;
}

HardeningSoil::YieldHyperbola HardeningSoil::yield_hyperbola(double qf, double sigma_3,
                                                             StiffnessFactorMemo& memo) const {
  // E50 and Eur share the stress factor, so the power law is evaluated once, and near the memo's
  // ratio not at all: it dominated the cost of the return, which needs the yield deviator at every
  // iteration. A = 2 / E_i with E_i = 2 E50 / (2 - Rf), and B = 2 / Eur: coefficients over it.
  YieldHyperbola h;
  h.raw_ratio = (parameters_.cohesion * cos_phi_ + sigma_3 * sin_phi_) * inverse_ratio_denominator_;
  h.ratio = std::max(h.raw_ratio, parameters_.stiffness_floor);
  const double inverse_factor = 1.0 / stiffness_factor(h.ratio, memo);
  h.A = a_coefficient_ * inverse_factor;
  h.B = b_coefficient_ * inverse_factor;
  h.qa = qf * inverse_failure_ratio_;
  return h;
}

double HardeningSoil::yield_deviator(double gamma_p, double sigma_3) const {
  StiffnessFactorMemo none;
  return yield_deviator(gamma_p, sigma_3, none);
}

YieldDeviator HardeningSoil::yield_deviator_slopes(double gamma_p, double sigma_3) const {
  StiffnessFactorMemo none;
  return yield_deviator_slopes(gamma_p, sigma_3, none);
}

double HardeningSoil::yield_deviator(double gamma_p, double sigma_3,
                                     StiffnessFactorMemo& memo) const {
  // The value alone (the residual checks of every candidate state need no slopes), by the same
  // operations as yield_deviator_slopes, so the two agree to the bit.
  const double qf = failure_deviator(sigma_3);
  if (qf <= 0.0 || gamma_p <= 0.0) {
    return 0.0;
  }
  const YieldHyperbola h = yield_hyperbola(qf, sigma_3, memo);
  const double b = (h.A - h.B) * h.qa + gamma_p;
  const double root = std::sqrt(b * b + 4.0 * h.B * gamma_p * h.qa);
  return std::min(2.0 * gamma_p * h.qa * (1.0 / (b + root)), qf);
}

YieldDeviator HardeningSoil::yield_deviator_slopes(double gamma_p, double sigma_3,
                                                   StiffnessFactorMemo& memo) const {
  const double qf = failure_deviator(sigma_3);
  if (qf <= 0.0) {
    return {};
  }
  // q_y inverts f-bar(q) = gamma without the 1/(qa - q) singularity (hardening_soil.md 1.3). The
  // slopes are exact derivatives of the same closed form and cost no further power law.
  const double qf_slope = qf_coefficient_;
  const YieldHyperbola h = yield_hyperbola(qf, sigma_3, memo);
  const double ratio = h.ratio;
  const double ratio_slope =
      h.raw_ratio > parameters_.stiffness_floor ? sin_phi_ * inverse_ratio_denominator_ : 0.0;
  const double A = h.A;
  const double B = h.B;
  const double qa = h.qa;
  if (gamma_p <= 0.0) {
    // q_y = gamma / (A - B) near gamma = 0: its slope there starts a Newton iteration from zero.
    return {0.0, 1.0 / (A - B), 0.0};
  }
  const double b = (A - B) * qa + gamma_p;
  const double root = std::sqrt(b * b + 4.0 * B * gamma_p * qa);
  const double inverse_denominator = 1.0 / (b + root);
  const double q_y = 2.0 * gamma_p * qa * inverse_denominator; // as yield_deviator has it
  if (q_y >= qf) {
    return {qf, 0.0, qf_slope};
  }
  // d/d sigma_3 through qa and the stiffness factor (A and B scale with 1 / factor).
  const double factor_slope = parameters_.power * ratio_slope / ratio; // (d factor / factor)
  const double qa_slope = qf_slope * inverse_failure_ratio_;
  const double b_by_sigma = -(A - B) * factor_slope * qa + (A - B) * qa_slope;
  const double bq_by_sigma = -B * factor_slope * qa + B * qa_slope; // d(B qa)
  const double inverse_root = 1.0 / root;
  const double root_by_sigma = (b * b_by_sigma + 2.0 * gamma_p * bq_by_sigma) * inverse_root;
  const double root_by_gamma = (b + 2.0 * B * qa) * inverse_root;
  YieldDeviator y;
  y.value = q_y;
  y.by_gamma = (2.0 * qa - q_y * (1.0 + root_by_gamma)) * inverse_denominator;
  y.by_sigma =
      (2.0 * gamma_p * qa_slope - q_y * (b_by_sigma + root_by_sigma)) * inverse_denominator;
  return y;
}

double HardeningSoil::hardening_function(double q, double sigma_3) const {
  const double qa = failure_deviator(sigma_3) / parameters_.failure_ratio;
  if (q <= 0.0) {
    return 0.0;
  }
  if (q >= qa) {
    return std::numeric_limits<double>::infinity();
  }
  const double initial = 2.0 * secant_modulus(sigma_3) / (2.0 - parameters_.failure_ratio);
  return 2.0 / initial * q / (1.0 - q / qa) - 2.0 * q / unloading_modulus(sigma_3);
}

double HardeningSoil::cap_deviator(const Principal& s) const {
  return s[0] + (delta_ - 1.0) * s[1] - delta_ * s[2];
}

double HardeningSoil::cap_surface(const Principal& s, double p_p) const {
  const double q = cap_deviator(s);
  const double p = mean(s);
  return std::sqrt(q * q * inverse_alpha2_ + p * p) - p_p;
}

void HardeningSoil::derive_cap() {
  // hardening_soil.md 1.6: at sigma_1 = p_ref, sigma_3 = K0nc p_ref on the normally consolidated K0
  // path both mechanisms are active, and the path is self-similar, so alpha and H follow from
  // matching K0nc and Eoed_ref at that one point.
  const HardeningSoilParameters& P = parameters_;
  const double k0 = P.k0_nc, nu = P.poisson_ur, m = P.power;
  const double sigma_1 = P.p_ref, sigma_3 = k0 * P.p_ref;
  const double q = sigma_1 - sigma_3, p = (sigma_1 + 2.0 * sigma_3) / 3.0;
  const double dq = 1.0 - k0, dp = (1.0 + 2.0 * k0) / 3.0;
  const double dgamma = (1.0 - m) * hardening_function(q, sigma_3) / (sigma_1 + a_);
  const double e = unloading_modulus(sigma_3);
  const double de1 = (1.0 - 2.0 * nu * k0) / e;
  const double de3 = (k0 - nu * (1.0 + k0)) / e;
  const double r1 = 1.0 / P.eoed_ref - de1 - dgamma / 2.0;
  const double r3 = -de3 + dgamma / 4.0;
  const double x = (2.0 * p / 3.0) * (r1 - r3) / (q * (2.0 * r3 + r1));
  const double mu = r3 / (2.0 * p / 3.0 - q * x);
  const double pp = std::sqrt(p * p + q * q * x);
  const double h = (q * x * dq + p * dp) / (2.0 * p * pp * mu * std::pow(pp / P.p_ref, m));
  if (!(x > 0.0) || !(mu > 0.0) || !(h > 0.0)) {
    throw std::invalid_argument(
        "no cap reproduces k0_nc and eoed_ref with these stiffnesses (e50_ref, eoed_ref, eur_ref "
        "and k0_nc are not compatible)");
  }
  alpha_ = 1.0 / std::sqrt(x);
  cap_modulus_ = h;
}

void HardeningSoil::initialise_state(const Stress& stress, double* state) const {
  const PrincipalStress principal = principal_compression(stress);
  const Principal& s = principal.values;
  // Reference (preconsolidation) state on the NC K0 line: sigma_p = OCR sigma_1 + POP.
  const double sigma_p = parameters_.ocr * std::max(s[0], 0.0) + parameters_.pop;
  const Principal reference{sigma_p, parameters_.k0_nc * sigma_p, parameters_.k0_nc * sigma_p};
  const double cap_reference = cap_surface(reference, 0.0);
  const double cap_current = cap_surface(s, 0.0);
  state[P_P] = std::max({cap_reference, cap_current, parameters_.cap_floor});
  const double gamma_reference = hardening_function(reference[0] - reference[2], reference[2]);
  const double gamma_current = hardening_function(s[0] - s[2], s[2]);
  double gamma = std::max(gamma_reference, gamma_current);
  if (!std::isfinite(gamma)) {
    gamma = 1.0; // at or beyond failure: the surface is the Mohr-Coulomb limit anyway
  }
  state[GAMMA_P] = std::max(gamma, 0.0);
  state[LAST_ACTIVE_SET] = 0.0;
}

double HardeningSoil::constrained_modulus(const Stress& stress, const double*) const {
  const PrincipalValues principal = principal_compression_values(stress);
  const double e = unloading_modulus(principal.values[2]);
  const double nu = parameters_.poisson_ur;
  return e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
}

double HardeningSoil::shear_modulus(const Stress& stress, const double*) const {
  const PrincipalValues principal = principal_compression_values(stress);
  return unloading_modulus(principal.values[2]) / (2.0 * (1.0 + parameters_.poisson_ur));
}

double HardeningSoil::elastic_energy_density(const Stress& stress, const double*) const {
  // Recoverable energy at the current unloading stiffness (the hypoelastic law has no exact
  // potential; this is the energy an unloading at fixed moduli would return).
  const double e = unloading_modulus(principal_compression_values(stress).values[2]);
  const double nu = parameters_.poisson_ur;
  return isotropic_elastic_energy_density(stress, e / (3.0 * (1.0 - 2.0 * nu)),
                                          e / (2.0 * (1.0 + nu)));
}

void HardeningSoil::update_stress(const StressUpdateBatch& batch) const {
  // One memo for the batch: a batch is a run of particles in a block of cells, the same for any
  // thread count, so the results do not depend on it.
  StiffnessFactorMemo memo;
  for (std::size_t k = 0; k < batch.particles.size(); ++k) {
    const auto i = static_cast<std::size_t>(batch.particles[k]);
    batch.constrained_modulus[k] = update_point(
        batch.stress[i], batch.state + i * static_cast<std::size_t>(batch.state_stride),
        batch.strain[k], memo);
  }
}

namespace {

/// One implicit return of the Hardening Soil model with frozen moduli and directions.
class HardeningSoilReturn {
public:
  HardeningSoilReturn(const HardeningSoil& model, const HardeningSoilParameters& parameters,
                      const Elasticity& elastic, double sin_psi_mobilised, double delta,
                      double alpha, double cap_modulus_now, const Principal& trial, double gamma,
                      double cap_pressure, HardeningSoil::StiffnessFactorMemo& memo)
      : model_(model), elastic_(elastic), sin_psi_(sin_psi_mobilised), delta_(delta), alpha_(alpha),
        cap_modulus_(cap_modulus_now), trial_(trial), gamma_n_(gamma), cap_n_(cap_pressure),
        memo_(memo) {
    inverse_alpha2_ = 1.0 / (alpha_ * alpha_);
    p_trial_ = mean(trial_); // every map of the multipliers starts from it
    sin_psi_third_ = sin_psi_ / 3.0;
    tolerance_ = surface_tolerance(trial, parameters.p_ref);
    // Every return starts from zero multipliers, where each map gives the trial's mean plus its
    // deviator: the same numbers for every plane, corner and mechanism. The yield deviator and its
    // slopes there are evaluated once, for the trial's residual and every Newton iteration's first.
    const double p = p_trial_;
    at_zero_sigma_3_ = p + (trial_[2] - p);
    at_zero_ = model_.yield_deviator_slopes(gamma_n_, at_zero_sigma_3_, memo_);
  }

  double tolerance() const { return tolerance_; }
  /// The cap's modulus, where the trial's residuals were decided before it was needed.
  void set_cap_modulus(double cap_modulus_now) { cap_modulus_ = cap_modulus_now; }

  /// The shear residual at zero multipliers (the trial's, at the state every return starts from).
  double shear_residual_at_zero() const {
    const double p = p_trial_;
    return (p + (trial_[0] - p)) - at_zero_sigma_3_ - at_zero_.value;
  }

  /// Residual of the governing shear plane (1, 3); at a corner its two planes have equal stresses,
  /// so this plane speaks for both.
  double shear_residual(const ReturnState& r) const {
    const Principal& s = r.stress;
    return s[0] - s[2] - model_.yield_deviator(r.gamma, s[2], memo_);
  }

  double cap_residual(const ReturnState& r) const {
    return model_.cap_surface(r.stress, r.cap_pressure);
  }

  /// The shear multipliers (S13, S12, S23) that a sum `total` takes on a plane (corner 0) or is
  /// split into at a corner (1: triaxial compression, sigma_2 = sigma_3; 2: triaxial extension,
  /// sigma_1 = sigma_2), and their derivatives with respect to the sum.
  struct ShearSplit {
    std::array<double, 3> multiplier{};
    std::array<double, 3> slope{};
  };

  ShearSplit split(int corner, double total) const {
    ShearSplit out;
    if (corner == 0) {
      out.multiplier[S13] = total;
      out.slope[S13] = 1.0;
      return out;
    }
    const double s = sin_psi_;
    const double K = elastic_.bulk, G = elastic_.shear;
    const double lame = K - 2.0 * G / 3.0;
    const Principal& t = trial_;
    // The split makes the corner's two stresses end equal (exact without the cap, and with the
    // corner's symmetric cap direction); unclamped, half of an increment of the sum goes to each
    // plane.
    const int other = corner == 1 ? S12 : S23;
    double wanted = 0.0;
    if (corner == 1) {
      const double g2 = G * (1.0 + s);
      const double level = (t[1] + t[2] + total * (g2 + 2.0 * lame * s)) / 2.0;
      wanted = (level - t[1] - total * lame * s) / g2;
    } else {
      const double g1 = G * (1.0 - s);
      const double level = (t[0] + t[1] - total * (g1 - 2.0 * lame * s)) / 2.0;
      wanted = (t[1] + total * lame * s - level) / g1;
    }
    const auto o = static_cast<std::size_t>(other);
    out.multiplier[o] = std::clamp(wanted, 0.0, total);
    out.slope[o] = wanted < 0.0 ? 0.0 : wanted > total ? 1.0 : 0.5;
    out.multiplier[S13] = total - out.multiplier[o];
    out.slope[S13] = 1.0 - out.slope[o];
    return out;
  }

  /// The trial's deviator after shear multipliers, and its derivative with respect to their sum.
  struct ShearedDeviator {
    Principal value{}, by_shear{};
  };

  ShearedDeviator sheared_deviator(const ShearSplit& shear) const {
    const double s = sin_psi_;
    const std::array<double, 3>& m = shear.multiplier;
    const double shear_sum = m[S13] + m[S12] + m[S23];
    // Flow of each shear plane, with trace -sin psi each.
    const Principal g13{(1.0 - s) / 2.0, 0.0, -(1.0 + s) / 2.0};
    const Principal g12{(1.0 - s) / 2.0, -(1.0 + s) / 2.0, 0.0};
    const Principal g23{0.0, (1.0 - s) / 2.0, -(1.0 + s) / 2.0};
    const double G = elastic_.shear;
    const double p_trial = p_trial_;
    ShearedDeviator out;
    for (std::size_t k = 0; k < 3; ++k) {
      const double shear_flow =
          m[S13] * g13[k] + m[S12] * g12[k] + m[S23] * g23[k] + sin_psi_third_ * shear_sum;
      const double flow_slope = shear.slope[S13] * g13[k] + shear.slope[S12] * g12[k] +
                                shear.slope[S23] * g23[k] + sin_psi_third_;
      out.value[k] = trial_[k] - p_trial - 2.0 * G * shear_flow;
      out.by_shear[k] = -2.0 * G * flow_slope;
    }
    return out;
  }

  /// A state after multipliers with its derivatives with respect to the shear sum and the cap
  /// multiplier: the Jacobian of Newton's method, exact (the map is rational in the multipliers).
  struct Linearised {
    ReturnState state;
    Principal stress_by_shear{}, stress_by_cap{};
    double cap_pressure_by_shear = 0.0, cap_pressure_by_cap = 0.0;
  };

  /// The stress, hardening and cap pressure after shear multipliers (S13, S12, S23) and a cap
  /// multiplier from the trial state; the cap's flow direction n is (1, delta - 1, -delta) or a
  /// corner average.
  Linearised linearised(const ShearSplit& shear, double lambda_c, const Principal& n) const {
    const double s = sin_psi_;
    const std::array<double, 3>& m = shear.multiplier;
    const double shear_sum = m[S13] + m[S12] + m[S23];
    const double K = elastic_.bulk, G = elastic_.shear;
    const double inverse_volumetric = 1.0 / (1.0 + 2.0 * K * lambda_c);
    const double p = (p_trial_ + K * s * shear_sum) * inverse_volumetric;
    const double p_by_shear = K * s * inverse_volumetric; // the slopes of a split sum to one
    const double p_by_cap = -2.0 * K * p * inverse_volumetric;
    const ShearedDeviator sheared = sheared_deviator(shear);
    const Principal& a = sheared.value;
    const Principal& a_by_shear = sheared.by_shear;
    const double n2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    const double flow = 4.0 * G * inverse_alpha2_;
    const double cap_stiffness = flow * n2;
    const double inverse_deviatoric = 1.0 / (1.0 + cap_stiffness * lambda_c);
    const double q_cap = (n[0] * a[0] + n[1] * a[1] + n[2] * a[2]) * inverse_deviatoric;
    const double q_cap_by_shear =
        (n[0] * a_by_shear[0] + n[1] * a_by_shear[1] + n[2] * a_by_shear[2]) * inverse_deviatoric;
    const double q_cap_by_cap = -cap_stiffness * q_cap * inverse_deviatoric;
    Linearised l;
    for (std::size_t k = 0; k < 3; ++k) {
      l.state.stress[k] = p + a[k] - flow * lambda_c * q_cap * n[k];
      l.stress_by_shear[k] = p_by_shear + a_by_shear[k] - flow * lambda_c * q_cap_by_shear * n[k];
      l.stress_by_cap[k] = p_by_cap - flow * (q_cap + lambda_c * q_cap_by_cap) * n[k];
    }
    l.state.gamma = gamma_n_ + shear_sum;
    l.state.cap_pressure = cap_n_ + cap_modulus_ * 2.0 * p * lambda_c;
    l.cap_pressure_by_shear = cap_modulus_ * 2.0 * lambda_c * p_by_shear;
    l.cap_pressure_by_cap = cap_modulus_ * 2.0 * (p + lambda_c * p_by_cap);
    return l;
  }

  /// The state after shear multipliers alone and its derivative with respect to their sum: the
  /// general map at a zero cap multiplier, where its cap terms vanish exactly, by the same
  /// operations otherwise, so the shear return's results are the general iteration's to the bit
  /// at a third of its arithmetic.
  struct ShearLinearised {
    ReturnState state;
    Principal stress_by_shear{};
  };

  ShearLinearised shear_linearised(const ShearSplit& shear) const {
    const std::array<double, 3>& m = shear.multiplier;
    const double shear_sum = m[S13] + m[S12] + m[S23];
    const double K = elastic_.bulk;
    const double p = p_trial_ + K * sin_psi_ * shear_sum;
    const double p_by_shear = K * sin_psi_;
    const ShearedDeviator sheared = sheared_deviator(shear);
    ShearLinearised l;
    for (std::size_t k = 0; k < 3; ++k) {
      l.state.stress[k] = p + sheared.value[k];
      l.stress_by_shear[k] = p_by_shear + sheared.by_shear[k];
    }
    l.state.gamma = gamma_n_ + shear_sum;
    l.state.cap_pressure = cap_n_;
    return l;
  }

  ReturnState state_after(const std::array<double, 4>& multiplier, const Principal& n) const {
    ShearSplit shear;
    shear.multiplier = {multiplier[S13], multiplier[S12], multiplier[S23]};
    return linearised(shear, multiplier[CAP], n).state;
  }

  Principal cap_direction(int corner) const {
    if (corner == 1) {
      return {1.0, -0.5, -0.5}; // triaxial compression corner: sigma_2 = sigma_3
    }
    if (corner == 2) {
      return {delta_ / 2.0, delta_ / 2.0, -delta_}; // triaxial extension corner
    }
    return {1.0, delta_ - 1.0, -delta_};
  }

  /// The largest shear sum a plane or corner can take: without the cap the deviator vanishes
  /// there, and the cap only lowers it further, so the shear residual is <= 0 there.
  double shear_limit(int corner) const {
    const double s = sin_psi_, G = elastic_.shear;
    const Principal& t = trial_;
    const double high = corner == 1   ? (t[0] - 0.5 * (t[1] + t[2])) / (G * (1.5 - s / 2.0))
                        : corner == 2 ? (0.5 * (t[0] + t[1]) - t[2]) / (G * (1.5 + s / 2.0))
                                      : (t[0] - t[2]) / (2.0 * G);
    return std::max(high, 1e-300);
  }

  /// The shear plane or corner alone by Newton's method on its residual in the shear sum, from
  /// zero. Each iteration costs one power law (the yield deviator with its slopes); the residual
  /// is convex in the shear sum, so the iterates approach its root from below. Returns nothing if
  /// it does not converge within the iterations allowed; the bracketed return then takes over.
  /// The same iteration, convergence test and last step as combined_newton with the cap inactive.
  std::optional<ReturnState> shear_newton(int corner) const {
    const double limit = shear_limit(corner);
    double total = 0.0;
    for (int iteration = 0; iteration < 40; ++iteration) {
      const ShearLinearised l = shear_linearised(split(corner, total));
      const Principal& st = l.state.stress;
      const YieldDeviator y =
          iteration == 0 ? at_zero_ : model_.yield_deviator_slopes(l.state.gamma, st[2], memo_);
      double residual = st[0] - st[2] - y.value;
      double slope = l.stress_by_shear[0] - l.stress_by_shear[2] - y.by_gamma -
                     y.by_sigma * l.stress_by_shear[2];
      if (total == 0.0 && residual <= tolerance_) {
        residual = 0.0, slope = 1.0; // not violated at zero: the plane is inactive
      }
      const bool converged = std::abs(residual) <= tolerance_;
      if (!(std::abs(slope) > 0.0) || !std::isfinite(slope)) {
        return converged ? std::optional<ReturnState>(l.state) : std::nullopt;
      }
      const double next = total - residual / slope;
      if (!std::isfinite(next)) {
        return std::nullopt;
      }
      if (converged) {
        // One more step costs no power law: the state is a rational function of the multiplier
        // alone, so the result satisfies the surface to rounding rather than to the tolerance,
        // and is a smooth function of the strain (mixed-control drivers differentiate it).
        return next >= 0.0 ? shear_linearised(split(corner, next)).state : l.state;
      }
      total = std::max(next, 0.0);
      if (total > limit) {
        total = 0.5 * (total + limit);
      }
    }
    return std::nullopt;
  }

  /// Newton's method on the residuals of the shear plane or corner and the cap together in their
  /// multipliers (the shear sum of the corner, the cap multiplier), from zero, with the
  /// complementarity of each: a multiplier stays non-negative, and one at zero whose surface is
  /// not violated there drops out of the system (as the bracketed returns find a root only where
  /// the residual at zero is positive). Returns nothing if it does not converge within the
  /// iterations allowed; the bracketed returns then take over.
  std::optional<ReturnState> combined_newton(int corner) const {
    const Principal n = cap_direction(corner);
    const double limit = shear_limit(corner);
    double total = 0.0, lambda_c = 0.0;
    for (int iteration = 0; iteration < 40; ++iteration) {
      const Linearised l = linearised(split(corner, total), lambda_c, n);
      const Principal& st = l.state.stress;
      // Rows of the residuals and their derivatives (j: d/d shear sum, d/d cap multiplier).
      const YieldDeviator y =
          iteration == 0 ? at_zero_ : model_.yield_deviator_slopes(l.state.gamma, st[2], memo_);
      double r1 = st[0] - st[2] - y.value;
      double j11 = l.stress_by_shear[0] - l.stress_by_shear[2] - y.by_gamma -
                   y.by_sigma * l.stress_by_shear[2];
      double j12 = l.stress_by_cap[0] - l.stress_by_cap[2] - y.by_sigma * l.stress_by_cap[2];
      const double q = model_.cap_deviator(st);
      const double p = mean(st);
      const double norm = std::sqrt(q * q * inverse_alpha2_ + p * p);
      const double inverse_norm = norm > 0.0 ? 1.0 / norm : 0.0;
      auto cap_slope = [&](const Principal& ds, double d_cap_pressure) {
        const double dq = model_.cap_deviator(ds);
        const double dp = mean(ds);
        return (q * dq * inverse_alpha2_ + p * dp) * inverse_norm - d_cap_pressure;
      };
      double r2 = norm - l.state.cap_pressure;
      double j21 = cap_slope(l.stress_by_shear, l.cap_pressure_by_shear);
      double j22 = cap_slope(l.stress_by_cap, l.cap_pressure_by_cap);
      // A mechanism at zero multiplier that its surface does not call for is inactive: its
      // variable stays zero and its row is the identity.
      const bool shear_active = !(total == 0.0 && r1 <= tolerance_);
      const bool cap_active = !(lambda_c == 0.0 && r2 <= tolerance_);
      if (!shear_active) {
        r1 = 0.0, j11 = 1.0, j12 = 0.0, j21 = 0.0;
      }
      if (!cap_active) {
        r2 = 0.0, j22 = 1.0, j21 = 0.0, j12 = 0.0;
      }
      const bool converged = std::abs(r1) <= tolerance_ && std::abs(r2) <= tolerance_;
      const double determinant = j11 * j22 - j12 * j21;
      if (!(std::abs(determinant) > 0.0) || !std::isfinite(determinant)) {
        return converged ? std::optional<ReturnState>(l.state) : std::nullopt;
      }
      const double next_total = total - (r1 * j22 - r2 * j12) / determinant;
      const double next_cap = lambda_c - (j11 * r2 - j21 * r1) / determinant;
      if (!std::isfinite(next_total) || !std::isfinite(next_cap)) {
        return std::nullopt;
      }
      if (converged) {
        // One more step costs no power law: the state is a rational function of the multipliers
        // alone, so the result satisfies the surfaces to rounding rather than to the tolerance,
        // and is a smooth function of the strain (mixed-control drivers differentiate it).
        if (next_total >= 0.0 && next_cap >= 0.0) {
          return linearised(split(corner, next_total), next_cap, n).state;
        }
        return l.state;
      }
      total = std::max(next_total, 0.0);
      if (total > limit) {
        total = 0.5 * (total + limit);
      }
      lambda_c = std::max(next_cap, 0.0);
    }
    return std::nullopt;
  }

  /// The cap alone by Newton's method, on its scalar residual in the cap multiplier. Without shear
  /// the trial's deviator a only shrinks along the cap direction n, and the isotropic part drops
  /// out of the cap deviator, so q-tilde = q-tilde(a) - (4 G / alpha^2) lambda_c q_n(lambda_c)
  /// q-tilde(n) and p = p_trial / (1 + 2 K lambda_c): a residual of a few operations, where the
  /// general iteration rebuilds the whole state. The state is built once, at the end, as the
  /// general return builds it. Same convergence test and last step as combined_newton.
  std::optional<ReturnState> cap_newton(int corner) const {
    const Principal n = cap_direction(corner);
    const double K = elastic_.bulk, G = elastic_.shear;
    const double p_trial = p_trial_;
    const Principal a{trial_[0] - p_trial, trial_[1] - p_trial, trial_[2] - p_trial};
    const double n2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    const double inverse_alpha2 = 1.0 / (alpha_ * alpha_);
    const double cap_stiffness = 4.0 * G * n2 * inverse_alpha2;
    const double flow = 4.0 * G * inverse_alpha2;
    const double q_a = n[0] * a[0] + n[1] * a[1] + n[2] * a[2];
    const double deviator_a = model_.cap_deviator(a);
    const double deviator_n = model_.cap_deviator(n);
    double lambda_c = 0.0;
    for (int iteration = 0; iteration < 40; ++iteration) {
      const double volumetric = 1.0 + 2.0 * K * lambda_c;
      const double p = p_trial / volumetric;
      const double p_slope = -2.0 * K * p / volumetric;
      const double deviatoric = 1.0 + cap_stiffness * lambda_c;
      const double q_cap = q_a / deviatoric;
      const double q_cap_slope = -cap_stiffness * q_cap / deviatoric;
      const double q = deviator_a - flow * lambda_c * q_cap * deviator_n;
      const double q_slope = -flow * deviator_n * (q_cap + lambda_c * q_cap_slope);
      const double norm = std::sqrt(q * q * inverse_alpha2 + p * p);
      const double residual = norm - (cap_n_ + cap_modulus_ * 2.0 * p * lambda_c);
      const double slope =
          (norm > 0.0 ? (q * q_slope * inverse_alpha2 + p * p_slope) / norm : 0.0) -
          cap_modulus_ * 2.0 * (p + lambda_c * p_slope);
      // At zero the cap is inactive if not violated there (it is, or this return is not tried).
      const bool converged =
          std::abs(residual) <= tolerance_ || (lambda_c == 0.0 && residual <= tolerance_);
      if (!(std::abs(slope) > 0.0) || !std::isfinite(slope)) {
        return converged ? std::optional<ReturnState>(state_after({0.0, 0.0, 0.0, lambda_c}, n))
                         : std::nullopt;
      }
      const double next = lambda_c - residual / slope;
      if (!std::isfinite(next)) {
        return std::nullopt;
      }
      if (converged) {
        return state_after({0.0, 0.0, 0.0, next >= 0.0 && lambda_c > 0.0 ? next : lambda_c}, n);
      }
      lambda_c = std::max(next, 0.0);
    }
    return std::nullopt;
  }

  /// Scalar return on one shear plane or a corner (both planes, equal stresses), psi explicit,
  /// with a given cap multiplier lambda_c acting at the same time (0: shear alone): a bracketed
  /// root, slower than Newton's method but sure to converge.
  ReturnState bracketed_shear_return(int corner, double lambda_c = 0.0, int cap_corner = 0) const {
    const Principal n = cap_direction(cap_corner);
    auto make = [&](double total) { return linearised(split(corner, total), lambda_c, n).state; };
    // At a corner the two planes have equal stresses, so the (1, 3) plane speaks for both; with
    // the split clamped (one multiplier zero) it is the plane itself.
    auto residual = [&](double total) { return shear_residual(make(total)); };
    return make(root_from_zero(residual, residual(0.0), shear_limit(corner), 2.0, 60, tolerance_));
  }

  ReturnState shear_return(int corner) const {
    if (auto r = shear_newton(corner)) {
      return *r;
    }
    return bracketed_shear_return(corner);
  }

  /// Shear (plane or corner) and cap together. Newton's method on both multipliers; if it fails,
  /// for each cap multiplier the shear multiplier is the scalar shear root, and the cap
  /// multiplier is the root of the cap residual along that curve.
  ReturnState combined_return(int corner) const {
    if (auto r = combined_newton(corner)) {
      return *r;
    }
    auto along = [&](double lambda_c) { return bracketed_shear_return(corner, lambda_c, corner); };
    auto residual = [&](double lambda_c) { return cap_residual(along(lambda_c)); };
    return along(root_from_zero(residual, residual(0.0), 1e-9, 4.0, 200, tolerance_));
  }

  /// The cap alone, with the cap direction of a corner if given.
  ReturnState cap_return(int corner) const {
    if (auto r = cap_newton(corner)) {
      return *r;
    }
    const Principal n = cap_direction(corner);
    auto make = [&](double lambda_c) { return state_after({0.0, 0.0, 0.0, lambda_c}, n); };
    auto residual = [&](double lambda_c) { return cap_residual(make(lambda_c)); };
    return make(root_from_zero(residual, residual(0.0), 1e-9, 4.0, 200, tolerance_));
  }

private:
  const HardeningSoil& model_;
  Elasticity elastic_;
  double sin_psi_;
  double delta_;
  double alpha_;
  double inverse_alpha2_ = 0.0;
  double p_trial_ = 0.0;
  double sin_psi_third_ = 0.0; // a shear plane's flow has trace -sin psi: a third on each axis
  double cap_modulus_;
  Principal trial_;
  double gamma_n_;
  double cap_n_;
  double tolerance_ = 0.0;
  double at_zero_sigma_3_ = 0.0;
  YieldDeviator at_zero_;
  // The power law of the stiffnesses where it was last evaluated: the trial's residual, the
  // iterations near convergence and the check of a result evaluate it at nearly the same sigma_3.
  HardeningSoil::StiffnessFactorMemo& memo_;
};

/// Whether a shear return without the cap, on any plane or corner, can end inside the cap. With
/// psi = 0 it keeps p at the trial's, raises sigma_3 and gamma_p, and ends with q = Q(gamma_p,
/// sigma_3) >= Q(gamma_n, t_3) (Q grows with both); an ordered result has q-tilde >= q. So if
/// even q-tilde = Q(gamma_n, t_3) lies outside the cap at the trial's p, every shear-only return
/// is inadmissible, and solving them would only confirm it. Q(gamma_n, t_3) is the trial's
/// deviator less its shear residual. Results are those of the full search, at a fraction of the
/// cost: on the quick GDP scene most plastic points end on both surfaces.
bool shear_alone_can_hold(const Principal& trial, double shear_residual, double cap_pressure,
                          double sin_psi, double alpha, double delta, double tolerance) {
  if (sin_psi != 0.0) {
    return true;
  }
  // An accepted result may lie outside its shear surface by the tolerance and out of order by it
  // (sigma_2 below sigma_3, which lowers q-tilde by (delta - 1) times that): the bound keeps both.
  const double least_deviator =
      std::max(trial[0] - trial[2] - shear_residual - (1.0 + delta) * tolerance, 0.0);
  const double p = mean(trial);
  return std::sqrt(least_deviator * least_deviator / (alpha * alpha) + p * p) - cap_pressure <=
         tolerance;
}

bool ordered(const Principal& s, double tolerance) {
  return s[0] >= s[1] - tolerance && s[1] >= s[2] - tolerance;
}

/// Substeps that keep each trial increment small against the confinement, so that moduli frozen
/// at the start of a substep stay accurate (hardening_soil.md 2.2): the size of the elastic trial
/// increment at the start's moduli over a tenth of the confinement (sigma_3 + a plus the
/// stiffness floor's stress), between 1 and 100.
int substep_count(const StrainIncrement& strain, double young, double nu, double sigma_3,
                  double confinement_offset) {
  const double shear = young / (2.0 * (1.0 + nu));
  const double lame = young * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  const double volumetric = strain[RR] + strain[YY] + strain[TT];
  double trial_size = 0.0;
  for (int c = 0; c < 3; ++c) {
    const double normal = lame * volumetric + 2.0 * shear * strain[c];
    trial_size += normal * normal;
  }
  for (int c = 3; c < 6; ++c) {
    const double shear_stress = shear * strain[c];
    trial_size += 2.0 * shear_stress * shear_stress;
  }
  trial_size = std::sqrt(trial_size);
  const double scale = 0.1 * (std::max(sigma_3, 0.0) + confinement_offset);
  // Bounded before the cast: an infinite or huge ratio converted to int is undefined (on x86 it
  // read INT_MIN and took one substep where 100 were asked); a NaN ratio takes one.
  const double count = std::ceil(trial_size / scale);
  if (count >= 100.0) {
    return 100;
  }
  return count > 1.0 ? static_cast<int>(count) : 1;
}

/// Mobilised dilatancy (Rowe, as in PLAXIS), explicit from the start of the step: sin psi_m from
/// the mobilised and the critical-state friction, zero below three quarters of the peak.
double mobilised_dilatancy(const Principal& s, double a, double sin_phi, double sin_psi) {
  const double denominator = s[0] + s[2] + 2.0 * a;
  const double sin_phi_mobilised = denominator > 0.0 ? (s[0] - s[2]) / denominator : 0.0;
  if (sin_psi > 0.0 && sin_phi_mobilised >= 0.75 * sin_phi) {
    const double sin_phi_cv = (sin_phi - sin_psi) / (1.0 - sin_phi * sin_psi);
    return std::max((sin_phi_mobilised - sin_phi_cv) / (1.0 - sin_phi_mobilised * sin_phi_cv), 0.0);
  }
  return 0.0;
}

/// What a substep needs of the stress it starts from: sigma_3 (the stiffness) and the mobilised
/// dilatancy. With psi = 0 the latter is zero whatever the stress, and sigma_3 alone is needed.
struct SubstepStart {
  double sigma_3, sin_psi;
};

SubstepStart substep_start(const Stress& stress, double a, double sin_phi, double sin_psi) {
  if (sin_psi > 0.0) {
    const PrincipalValues now = principal_compression_values(stress);
    return {now.values[2], mobilised_dilatancy(now.values, a, sin_phi, sin_psi)};
  }
  return {principal_compression_minor(stress), 0.0};
}

/// The return of a trial outside the surfaces: the active set the particle's last return kept,
/// if it holds; else active sets in the order shear, cap, shear + cap, each with its corner
/// variants, keeping the first that satisfies every surface and the principal order; failing all,
/// alternate projections. `returner_at(state)` makes the return from another starting state (the
/// alternation's). `last_active_set` (HardeningSoil::LAST_ACTIVE_SET's code) is read and set to
/// the active set kept, 0 where the alternation ended the return.
template <class ReturnerAt>
ReturnState return_to_surfaces(const HardeningSoilReturn& returner, const ReturnState& trial_state,
                               double shear_trial, double cap_trial, bool shear_may_hold,
                               ReturnerAt&& returner_at, int& last_active_set) {
  const double tolerance = returner.tolerance();
  auto admissible = [&](const ReturnState& r) {
    return ordered(r.stress, tolerance) && returner.shear_residual(r) <= tolerance &&
           returner.cap_residual(r) <= tolerance;
  };
  // Whether the ordered search below tries a mechanism at all.
  auto tried = [&](int mechanism) {
    return mechanism == 0   ? shear_trial > tolerance && shear_may_hold
           : mechanism == 1 ? cap_trial > tolerance
                            : true;
  };
  if (last_active_set >= 1 && last_active_set <= 9 && tried((last_active_set - 1) / 3)) {
    // A particle loaded on, it tends to stay on the same surfaces: on the quick GDP scene the
    // last active set holds for 96 % of plastic substeps, where the ordered search tries three
    // variants on average (docs/hardening-soil.md). A corner variant's flow (the corner's cap
    // direction, the split shear) belongs only to a state at its corner, so a corner variant whose
    // split clamped it off the corner does not count: the search decides there. What the last set
    // gives is then the ordered search's state to the tolerance of the surfaces
    // (`HardeningSoil.TheLastActiveSetGivesTheOrderedSearchsState`).
    const int mechanism = (last_active_set - 1) / 3, corner = (last_active_set - 1) % 3;
    const ReturnState r = mechanism == 0   ? returner.shear_return(corner)
                          : mechanism == 1 ? returner.cap_return(corner)
                                           : returner.combined_return(corner);
    const bool at_corner = corner == 0 ||
                           (corner == 1 && std::abs(r.stress[1] - r.stress[2]) <= tolerance) ||
                           (corner == 2 && std::abs(r.stress[0] - r.stress[1]) <= tolerance);
    if (at_corner && admissible(r)) {
      return r;
    }
  }
  ReturnState result = trial_state;
  bool found = false;
  // What an ordered but inadmissible variant says about the variants after it.
  enum class OrderedMiss { ends_at_plane, ends_at_any, says_nothing };
  int mechanism = 0;
  auto attempt = [&](auto&& make, OrderedMiss ordered_miss) {
    for (int corner = 0; corner < 3 && !found; ++corner) {
      const ReturnState r = make(corner);
      if (admissible(r)) {
        result = r;
        last_active_set = 1 + 3 * mechanism + corner;
        found = true;
      } else if (ordered(r.stress, tolerance) &&
                 (ordered_miss == OrderedMiss::ends_at_any ||
                  (ordered_miss == OrderedMiss::ends_at_plane && corner == 0))) {
        break;
      }
    }
  };
  if (shear_trial > tolerance && shear_may_hold) {
    // The shear corners split the multiplier so that two principal stresses end equal, and clamp
    // to the plane's return while the plane keeps the order: after an ordered miss of the plane
    // they would only repeat its (inadmissible) state.
    mechanism = 0;
    attempt([&](int corner) { return returner.shear_return(corner); }, OrderedMiss::ends_at_plane);
  }
  if (!found && cap_trial > tolerance) {
    // A cap variant whose result is ordered but outside the shear surface shows that the cap
    // alone cannot hold the point: the return ends on both surfaces. The corner directions only
    // exist to restore an order the plane's direction breaks; trying them past an ordered miss
    // cost 38 % of the cap returns on the quick GDP scene (ordered misses at the plane,
    // or at the compression corner after the plane broke the order) and found an admissible
    // cap-only state once in 80 000 returns, where the combined return finds another.
    mechanism = 1;
    attempt([&](int corner) { return returner.cap_return(corner); }, OrderedMiss::ends_at_any);
  }
  if (!found) {
    mechanism = 2;
    attempt([&](int corner) { return returner.combined_return(corner); },
            OrderedMiss::says_nothing);
  }
  if (found) {
    return result;
  }
  last_active_set = 0;
  // Near a triaxial corner the cap's own direction can break the principal order while the
  // corner directions leave a shear plane open. Project in turn: the cap (first ordered variant),
  // then the shear planes from there; with psi = 0 the shear return lowers the cap deviator at
  // constant p, so the cap stays closed.
  ReturnState r = trial_state;
  for (int pass = 0; pass < 4 && !admissible(r); ++pass) {
    const HardeningSoilReturn from_cap = returner_at(r);
    if (from_cap.cap_residual(r) > tolerance) {
      for (int corner = 0; corner < 3; ++corner) {
        r = from_cap.cap_return(corner);
        if (ordered(r.stress, tolerance)) {
          break;
        }
      }
    }
    const HardeningSoilReturn from_shear = returner_at(r);
    if (from_shear.shear_residual(r) > tolerance) {
      for (int corner = 0; corner < 3; ++corner) {
        r = from_shear.shear_return(corner);
        if (ordered(r.stress, tolerance)) {
          break;
        }
      }
    }
  }
  return r;
}

} // namespace

double HardeningSoil::update_point(Stress& stress, double* state,
                                   const StrainIncrement& strain) const {
  StiffnessFactorMemo memo;
  return update_point(stress, state, strain, memo);
}

double HardeningSoil::update_point(Stress& stress, double* state, const StrainIncrement& strain,
                                   StiffnessFactorMemo& memo) const {
  const HardeningSoilParameters& P = parameters_;
  SubstepStart now = substep_start(stress, a_, sin_phi_, sin_psi_);
  // The stiffness at the start, the trial's and the return's evaluations lie close together in
  // sigma_3 (stiffness_factor), and often near the last point's.
  const double e_start = unloading_modulus(now.sigma_3, memo);
  const int substeps =
      substep_count(strain, e_start, P.poisson_ur, now.sigma_3, a_ + P.stiffness_floor * P.p_ref);
  StrainIncrement part = strain;
  for (double& c : part) {
    c /= substeps;
  }
  double modulus = 0.0;
  for (int step = 0; step < substeps; ++step) {
    if (step > 0) {
      now = substep_start(stress, a_, sin_phi_, sin_psi_);
    }
    const double e = step == 0 ? e_start : unloading_modulus(now.sigma_3, memo);
    modulus = substep(stress, state, part, e, now.sin_psi, memo);
  }
  return modulus;
}

double HardeningSoil::substep(Stress& stress, double* state, const StrainIncrement& part,
                              double young, double sin_psi, StiffnessFactorMemo& memo) const {
  const HardeningSoilParameters& P = parameters_;
  const double nu = P.poisson_ur;
  const Elasticity elastic{young / (3.0 * (1.0 - 2.0 * nu)), young / (2.0 * (1.0 + nu)),
                           young * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))};
  const double modulus = elastic.lambda + 2.0 * elastic.shear;
  // Elastic trial on the full tensor (engine convention, tension positive).
  Stress trial_stress = stress;
  add_isotropic_elastic_increment(trial_stress, part, elastic.lambda, elastic.shear);
  const double gamma_n = state[GAMMA_P];
  const double cap_n = std::max(state[P_P], P.cap_floor);

  // Tension: the apex (isotropic, so no directions are needed).
  if (trace(trial_stress) / 3.0 >= P.tension_limit) {
    stress = {P.tension_limit, P.tension_limit, P.tension_limit, 0.0, 0.0, 0.0};
    return modulus;
  }
  // Most steps are elastic, and an elastic step needs neither the principal directions nor the
  // return: the trial stands if it lies inside both surfaces by more than the uncertainty of its
  // principal values (the cubic's, or the theta shears' bound on the block's) can move the
  // residuals (their slopes: 1 + dq_f/dsigma_3 < 10 for shear, (1 + delta) / alpha for the cap).
  // The stress then carries no rounding of a recomposition.
  const PrincipalEstimate estimate = principal_compression_estimate(trial_stress);
  const Principal& t = estimate.values.values;
  const double margin = surface_tolerance(t, P.p_ref) -
                        10.0 * estimate.values.uncertainty * std::max(1.0, (1.0 + delta_) / alpha_);
  if (t[0] - t[2] - yield_deviator(gamma_n, t[2], memo) <= margin &&
      cap_surface(t, cap_n) <= margin) {
    state[P_P] = cap_n;
    stress = trial_stress;
    return modulus;
  }

  const PrincipalStress trial = principal_compression(
      trial_stress,
      estimate.bounded ? principal_compression_values(trial_stress) : estimate.values);
  // The cap's modulus is a power law the residuals below do not need: it is set only once the
  // trial is known to be outside (a sixth of the trials decomposed here turn out inside).
  double cap_hardening = 0.0;
  auto returner_at = [&](const ReturnState& from) {
    return HardeningSoilReturn(*this, P, elastic, sin_psi, delta_, alpha_, cap_hardening,
                               from.stress, from.gamma, from.cap_pressure, memo);
  };
  const ReturnState trial_state{trial.values, gamma_n, cap_n};
  HardeningSoilReturn returner = returner_at(trial_state);
  const double tolerance = returner.tolerance();
  // The trial's residuals, once: they decide both whether it stands and which mechanisms to try.
  const double shear_trial = returner.shear_residual_at_zero();
  const double cap_trial = returner.cap_residual(trial_state);
  if (shear_trial <= tolerance && cap_trial <= tolerance) {
    // Inside after all (the quick test keeps a margin; the decomposition's values are ordered).
    state[P_P] = cap_n;
    stress = trial_stress;
    return modulus;
  }
  cap_hardening = cap_modulus_ * std::pow((cap_n + a_) / (P.p_ref + a_), P.power);
  returner.set_cap_modulus(cap_hardening);
  const bool shear_may_hold =
      shear_trial > tolerance &&
      shear_alone_can_hold(trial.values, shear_trial, cap_n, sin_psi, alpha_, delta_, tolerance);
  // A code that is not one of the nine (a state set by hand) only means: no active set to try.
  const double stored = state[LAST_ACTIVE_SET];
  int last_active_set = stored >= 1.0 && stored <= 9.0 ? static_cast<int>(stored) : 0;
  const ReturnState result = return_to_surfaces(returner, trial_state, shear_trial, cap_trial,
                                                shear_may_hold, returner_at, last_active_set);
  state[LAST_ACTIVE_SET] = last_active_set;
  Principal out = result.stress;
  // Tension beyond the cut-off after the return: with c = 0 the shear planes meet the tension
  // planes only at the apex.
  if (out[2] < -P.tension_limit - tolerance) {
    out = {-P.tension_limit, -P.tension_limit, -P.tension_limit};
  }
  state[GAMMA_P] = std::max(result.gamma, gamma_n);
  state[P_P] = std::max(result.cap_pressure, cap_n);
  stress = compose_from_principal(out, trial.directions);
  return modulus;
}

} // namespace mpile
