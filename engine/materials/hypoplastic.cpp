// Hypoplasticity with intergranular strain (docs/hypoplasticity.md): the parameters' declaration,
// the rate of von Wolffersdorff's model with Niemunis and Herle's intergranular strain, and its
// integration over a strain increment by Heun's method in error-controlled substeps.
#include "engine/materials/hypoplastic.hpp"

#include "engine/angles.hpp"
#include "engine/materials/power_near_one.hpp"
#include "engine/materials/principal_stress.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

namespace mpile {

namespace {

/// A : B of two symmetric tensors stored as (rr, yy, thth, ry, ytheta, rtheta), tensor shear.
double contract(const Stress& a, const Stress& b) {
  return a[RR] * b[RR] + a[YY] * b[YY] + a[TT] * b[TT] +
         2.0 * (a[RY] * b[RY] + a[YT] * b[YT] + a[RT] * b[RT]);
}

double norm(const Stress& a) {
  return std::sqrt(contract(a, a));
}

/// tr(A^3) = A : (A A) of a symmetric tensor.
double trace_of_cube(const Stress& a) {
  Stress square;
  square[RR] = a[RR] * a[RR] + a[RY] * a[RY] + a[RT] * a[RT];
  square[YY] = a[RY] * a[RY] + a[YY] * a[YY] + a[YT] * a[YT];
  square[TT] = a[RT] * a[RT] + a[YT] * a[YT] + a[TT] * a[TT];
  square[RY] = a[RR] * a[RY] + a[RY] * a[YY] + a[RT] * a[YT];
  square[YT] = a[RY] * a[RT] + a[YY] * a[YT] + a[YT] * a[TT];
  square[RT] = a[RR] * a[RT] + a[RY] * a[YT] + a[RT] * a[TT];
  return contract(a, square);
}

/// The hypoplastic tangent at a state: L : X = c (F^2 X + a^2 s (s : X)) and N = n_scale (s + s*),
/// with s = sigma / tr(sigma) and s* its deviator.
struct Tangent {
  Stress s{};
  Stress n{}; // N
  double c = 0.0;
  double f2 = 0.0;                      // F^2
  double a2 = 0.0;                      // a^2
  double s_norm2 = 0.0;                 // s : s
  Stress apply(const Stress& x) const { // L : X
    const double sx = a2 * contract(s, x);
    Stress out;
    for (std::size_t k = 0; k < 6; ++k) {
      out[k] = c * (f2 * x[k] + sx * s[k]);
    }
    return out;
  }
};

/// What the rate needs of the state besides the stress's direction: Bauer's factor and the
/// barotropy and pycnotropy factors at (p, e), and rho^chi and rho^beta_R at |h|.
struct StateFactors {
  double p = 0.0;       // mean pressure where they hold (compression positive)
  double e = 0.0;       // void ratio where they hold
  double ratio_n = 0.0; // (3 p / h_s)^n
  double bauer = 0.0;   // exp(-(3 p / h_s)^n): e_x = e_x0 bauer
  double f_b = 0.0;
  double f_e = 0.0;
  double density = 0.0; // (e - e_d) / (e_c - e_d), at least zero
  double f_d = 0.0;     // density^alpha
  double h_norm = 0.0;  // |h|
  double rho = 0.0;     // min(|h| / R, 1)
  double log_rho = 0.0;
  double rho_chi = 0.0;
  double rho_beta = 0.0; // NaN: not evaluated, exp(beta_R log_rho)
};

} // namespace

std::span<const HypoplasticField> hypoplastic_fields() {
  // Ranges: the model's own (von Wolffersdorff 1996; Herle and Gudehus 1999 give the parameters'
  // meaning and typical values), and the intergranular strain's (Niemunis and Herle 1997: m_R >=
  // m_T > 1, R of order 1e-5 to 1e-4). R is bounded below an order under the smallest published
  // calibration: at R = 1e-100 the intergranular strain's substeps, error relative to R, fell to
  // their floor and one simple-shear path ran past a minute (at 1e-20, 0.17 s). m_R and m_T are
  // bounded above at 20, four times the largest published (5 and 2, Niemunis and Herle 1997; the
  // Karlsruhe fine sand's 2.2 and 1.1): the explicit step shrinks as 1 / sqrt(m_R), so a misplaced
  // digit (m_R = 1e5) would make a run 140 times longer than 5 does and look hung.
  static const HypoplasticField fields[] = {
      {"critical_friction_angle", &HypoplasticParameters::critical_friction_angle, false, "degrees",
       between(10.0, true, 60.0, true), "phi_c, the critical state friction angle"},
      {"granular_hardness", &HypoplasticParameters::granular_hardness, false, "Pa", above(0.0),
       "h_s, the granulate hardness of Bauer's compression law"},
      {"exponent", &HypoplasticParameters::exponent, false, "-", between(0.0, false, 1.0, true),
       "n, the exponent of Bauer's compression law"},
      {"e_d0", &HypoplasticParameters::e_d0, false, "-", above(0.0),
       "minimum void ratio at zero pressure (densest packing)"},
      {"e_c0", &HypoplasticParameters::e_c0, false, "-", above(0.0),
       "critical void ratio at zero pressure, between e_d0 and e_i0"},
      {"e_i0", &HypoplasticParameters::e_i0, false, "-", above(0.0),
       "maximum void ratio at zero pressure (isotropic compression of the loosest state)"},
      {"alpha", &HypoplasticParameters::alpha, false, "-", between(0.0, false, 1.0, true),
       "pycnotropy exponent of f_d: the peak friction and dilatancy of dense sand"},
      {"beta", &HypoplasticParameters::beta, false, "-", between(0.0, false, 10.0, true),
       "pycnotropy exponent of f_e: the stiffness of dense sand"},
      {"void_ratio", &HypoplasticParameters::void_ratio, false, "-", above(0.0),
       "e0, the initial void ratio, at most e_i0"},
      {"intergranular_strain", &HypoplasticParameters::intergranular_strain, true, "-",
       between(0.0, true, 1.0, true), "1: with the intergranular strain, 0: without"},
      {"r_max", &HypoplasticParameters::r_max, true, "-", between(1e-6, true, 1e-2, true),
       "R, the size of the intergranular strain's elastic range"},
      {"m_r", &HypoplasticParameters::m_r, true, "-", between(1.0, true, 20.0, true),
       "m_R, the stiffness multiplier after a 180 degree reversal, at least m_T"},
      {"m_t", &HypoplasticParameters::m_t, true, "-", between(1.0, true, 20.0, true),
       "m_T, the stiffness multiplier after a 90 degree change of direction"},
      {"beta_r", &HypoplasticParameters::beta_r, true, "-", above(0.0),
       "beta_R, the evolution exponent of the intergranular strain"},
      {"chi", &HypoplasticParameters::chi, true, "-", above(0.0),
       "chi, the interpolation exponent between the reversal's and the hypoplastic stiffness"},
      {"tolerance", &HypoplasticParameters::tolerance, true, "-", between(1e-10, true, 0.1, true),
       "relative error allowed per substep of the integration"},
      {"minimum_pressure", &HypoplasticParameters::minimum_pressure, true, "Pa", above(0.0),
       "mean pressure below which the stress is set isotropic at it (sand carries no tension)"},
      {"density", &HypoplasticParameters::density, false, "kg/m^3", above(0.0),
       "initial bulk density"},
  };
  return fields;
}

Hypoplastic::Hypoplastic(const HypoplasticParameters& p) : parameters_(p) {
  for (const HypoplasticField& f : hypoplastic_fields()) {
    require_in_range(f.name, f.range, p.*f.member);
  }
  auto require = [](bool ok, const std::string& message) {
    if (!ok) {
      throw std::invalid_argument(message);
    }
  };
  // Each message begins with the key to blame, so that the case reader points at its line.
  require(p.e_d0 < p.e_c0,
          "e_d0 must be below e_c0: the limit void ratios need e_d0 < e_c0 < e_i0");
  require(p.e_c0 < p.e_i0, "e_i0 must exceed e_c0: the limit void ratios need e_d0 < e_c0 < e_i0");
  require(p.void_ratio <= p.e_i0, "void_ratio must be at most e_i0 (no looser state exists)");
  require(p.m_r >= p.m_t, "m_r must be at least m_t");
  require(p.intergranular_strain == 0.0 || p.intergranular_strain == 1.0,
          "intergranular_strain must be 0 or 1");
  const double sin_phi = std::sin(radians(p.critical_friction_angle));
  a_ = std::sqrt(3.0) * (3.0 - sin_phi) / (2.0 * std::sqrt(2.0) * sin_phi);
  const double f_b_divisor =
      3.0 + a_ * a_ -
      a_ * std::sqrt(3.0) * std::pow((p.e_i0 - p.e_d0) / (p.e_c0 - p.e_d0), p.alpha);
  // Below zero the isotropic compression's stiffness f_b would change sign (Herle and Gudehus
  // 1999): such parameters describe no granular material.
  require(f_b_divisor > 0.0,
          "alpha makes 3 + a^2 - a sqrt(3) ((e_i0 - e_d0) / (e_c0 - e_d0))^alpha "
          "<= 0: lower alpha or widen e_c0 - e_d0");
  f_b_scale_ = p.granular_hardness / p.exponent * std::pow(p.e_i0 / p.e_c0, p.beta) / f_b_divisor;
}

double Hypoplastic::limit_void_ratio(double e_x0, double p) const {
  return e_x0 * std::exp(-std::pow(3.0 * p / parameters_.granular_hardness, parameters_.exponent));
}

double Hypoplastic::critical_stress_ratio() const {
  const double sin_phi = std::sin(radians(parameters_.critical_friction_angle));
  return 6.0 * sin_phi / (3.0 - sin_phi);
}

namespace {

/// f_b from 3 p / h_s, its n-th power and Bauer's factor (no power of its own).
double barotropy(const HypoplasticParameters& q, double f_b_scale, double ratio, double ratio_n,
                 double bauer) {
  const double e_i = q.e_i0 * bauer;
  return f_b_scale * (1.0 + e_i) / e_i * (ratio / ratio_n);
}

/// rho^chi from log(rho) (zero at h = 0); rho^beta_R is left to the rate, which needs it only
/// when loading along h.
void intergranular_factors(const HypoplasticParameters& q, StateFactors& f) {
  f.log_rho = f.rho > 0.0 ? std::log(f.rho) : -std::numeric_limits<double>::infinity();
  f.rho_chi = std::exp(q.chi * f.log_rho);
  f.rho_beta = std::numeric_limits<double>::quiet_NaN();
}

/// The factors at (p, e, |h|) from their definitions.
StateFactors exact_factors(const HypoplasticParameters& q, double f_b_scale, double p, double e,
                           double h_norm) {
  StateFactors f;
  f.p = p;
  f.e = e;
  const double ratio = 3.0 * p / q.granular_hardness;
  // (3 p / h_s)^n once: Bauer's exponent and, divided into 3 p / h_s, f_b's (3 p / h_s)^(1 - n).
  f.ratio_n = std::pow(ratio, q.exponent);
  f.bauer = std::exp(-f.ratio_n);
  f.f_b = barotropy(q, f_b_scale, ratio, f.ratio_n, f.bauer);
  const double e_c = q.e_c0 * f.bauer;
  const double e_d = q.e_d0 * f.bauer;
  // pow(x, 1) is x exactly: a sand with beta = 1 (the seed's) skips a third of the pows here.
  f.f_e = q.beta == 1.0 ? e_c / e : std::pow(e_c / e, q.beta);
  // Denser than e_d the model has no state: f_d is held at zero there (no dilatancy term).
  f.density = std::max(e - e_d, 0.0) / (e_c - e_d);
  f.f_d = std::pow(f.density, q.alpha);
  f.h_norm = h_norm;
  if (q.intergranular_strain != 0.0) {
    f.rho = std::min(h_norm / q.r_max, 1.0);
    intergranular_factors(q, f);
  }
  return f;
}

/// The factors at (p, e, |h|) near `base`'s point, where each power is base's times a power of a
/// number near one (power_near_one; std::pow where the numbers are not near one). Equal to
/// exact_factors to a few units of rounding: it only evaluates the same functions more cheaply.
StateFactors factors_near(const HypoplasticParameters& q, double f_b_scale,
                          const StateFactors& base, double p, double e, double h_norm) {
  StateFactors f;
  f.p = p;
  f.e = e;
  const double ratio = 3.0 * p / q.granular_hardness;
  f.ratio_n = base.ratio_n * power_near_one(p / base.p - 1.0, q.exponent);
  f.bauer = base.bauer * exp_near_zero(base.ratio_n - f.ratio_n);
  f.f_b = barotropy(q, f_b_scale, ratio, f.ratio_n, f.bauer);
  const double e_c = q.e_c0 * f.bauer;
  const double e_d = q.e_d0 * f.bauer;
  f.f_e = q.beta == 1.0
              ? e_c / e
              : base.f_e * power_near_one((f.bauer * base.e) / (base.bauer * e) - 1.0, q.beta);
  f.density = std::max(e - e_d, 0.0) / (e_c - e_d);
  f.f_d = base.density > 0.0 && f.density > 0.0
              ? base.f_d * power_near_one(f.density / base.density - 1.0, q.alpha)
              : std::pow(f.density, q.alpha);
  f.h_norm = h_norm;
  if (q.intergranular_strain != 0.0) {
    f.rho = std::min(h_norm / q.r_max, 1.0);
    // Where |h| changed by more than NEAR_ONE of itself (as it does near h = 0), one logarithm
    // and two exponentials rather than two powers.
    const double delta = base.rho > 0.0 ? f.rho / base.rho - 1.0 : 1.0;
    if (std::abs(delta) <= NEAR_ONE) {
      f.rho_chi = base.rho_chi * power_near_one(delta, q.chi);
      f.rho_beta = std::isnan(base.rho_beta) ? std::numeric_limits<double>::quiet_NaN()
                                             : base.rho_beta * power_near_one(delta, q.beta_r);
      f.log_rho = base.log_rho + log_near_one(delta);
    } else {
      intergranular_factors(q, f);
    }
  }
  return f;
}

/// The tangent of von Wolffersdorff's model at stress `stress` (p > 0) from the state's factors.
Tangent hypoplastic_tangent(double a, const Stress& stress, const StateFactors& factors) {
  Tangent t;
  const double trace = stress[RR] + stress[YY] + stress[TT]; // < 0 in compression
  const double inverse_trace = 1.0 / trace;
  for (std::size_t k = 0; k < 6; ++k) {
    t.s[k] = stress[k] * inverse_trace;
  }
  Stress deviator = t.s;
  for (std::size_t k = 0; k < 3; ++k) {
    deviator[k] -= 1.0 / 3.0;
  }
  t.s_norm2 = contract(t.s, t.s);
  const double deviator_norm2 = contract(deviator, deviator);
  const double tan_psi = std::sqrt(3.0 * deviator_norm2);
  // Lode's angle; F does not depend on it when the deviator vanishes (tan psi = 0 gives F = 1).
  double cos_3theta = 1.0;
  if (deviator_norm2 > 1e-24) {
    cos_3theta =
        -std::sqrt(6.0) * trace_of_cube(deviator) / (deviator_norm2 * std::sqrt(deviator_norm2));
    cos_3theta = std::clamp(cos_3theta, -1.0, 1.0);
  }
  const double tan2 = tan_psi * tan_psi;
  const double f =
      std::sqrt(tan2 / 8.0 + (2.0 - tan2) / (2.0 + std::sqrt(2.0) * tan_psi * cos_3theta)) -
      tan_psi / (2.0 * std::sqrt(2.0));
  t.c = factors.f_b * factors.f_e / t.s_norm2;
  t.f2 = f * f;
  t.a2 = a * a;
  const double n_scale = t.c * factors.f_d * f * a;
  for (std::size_t k = 0; k < 6; ++k) {
    t.n[k] = n_scale * (t.s[k] + deviator[k]);
  }
  return t;
}

/// True when every principal compression is at least `margin` (Pa): -sigma - margin 1 is positive
/// semidefinite (Sylvester's test on all its principal minors). Von Wolffersdorff's F is defined
/// strictly inside the compression octant: with a tensile principal stress tan psi may pass
/// sqrt(2) in extension, and at its uniaxial corner (two principal stresses zero) F's denominator
/// 2 + sqrt(2) tan psi cos 3 theta is zero with its numerator (F's limit there is 1, but 0 / 0 is
/// what the formula gives).
bool compressive(const Stress& s, double margin) {
  const double a = -s[RR] - margin, b = -s[YY] - margin, c = -s[TT] - margin;
  const double ab = -s[RY], bc = -s[YT], ac = -s[RT];
  const double minor_ab = a * b - ab * ab, minor_ac = a * c - ac * ac, minor_bc = b * c - bc * bc;
  const double determinant = a * minor_bc - ab * (ab * c - bc * ac) + ac * (ab * bc - b * ac);
  return a >= 0.0 && b >= 0.0 && c >= 0.0 && minor_ab >= 0.0 && minor_ac >= 0.0 &&
         minor_bc >= 0.0 && determinant >= 0.0;
}

/// Sand carries no tension in any direction: a principal compression below the margin is raised
/// to the floor pressure along its direction (the others untouched; a change of p_min, negligible
/// beside the stresses that give such states), and what is left below the floor on average is
/// set isotropic at it, as a tensile mean stress is.
void cut_tension(Stress& s, double p_min) {
  PrincipalStress principal = principal_compression(s);
  for (double& value : principal.values) {
    if (value < 1e-3 * p_min) { // compression positive
      value = p_min;
    }
  }
  s = compose_from_principal(principal.values, principal.directions);
  if (mean_pressure(s) < p_min) {
    s = Stress{-p_min, -p_min, -p_min, 0.0, 0.0, 0.0};
  }
}

/// The small-strain stiffness's multiple of L: m_R after a reversal, with the intergranular strain.
double reversal_multiplier(const HypoplasticParameters& q) {
  return q.intergranular_strain != 0.0 ? q.m_r : 1.0;
}

/// An upper bound on the constrained modulus of a tangent: the largest eigenvalue of F^2 I + a^2 s
/// (x) s is F^2 + a^2 s:s; N adds at most |N| per unit |D|; after a reversal the stiffness is m_R
/// times L.
double modulus_bound(const HypoplasticParameters& q, const Tangent& t) {
  return reversal_multiplier(q) * t.c * (t.f2 + t.a2 * t.s_norm2) + norm(t.n);
}

} // namespace

namespace {

/// The model's rate at `at` (whose factors `f` are) per unit of D: HypoplasticPoint::rate. Sets
/// f.rho_beta where it evaluates it.
HypoplasticPoint hypoplastic_rate(const HypoplasticParameters& q, double a,
                                  const HypoplasticPoint& at, StateFactors& f, const Stress& d,
                                  double* modulus) {
  const Tangent t = hypoplastic_tangent(a, at.stress, f);
  if (modulus != nullptr) {
    *modulus = modulus_bound(q, t);
  }
  HypoplasticPoint out;
  out.e = (1.0 + at.e) * (d[RR] + d[YY] + d[TT]);
  const Stress ld = t.apply(d);
  if (q.intergranular_strain == 0.0) {
    const double d_norm = norm(d);
    for (std::size_t k = 0; k < 6; ++k) {
      out.stress[k] = ld[k] + t.n[k] * d_norm;
    }
    return out;
  }
  Stress direction{}; // h / |h|; zero at h = 0 (rho = 0: the stiffness is m_R L whatever D)
  if (f.h_norm > 0.0) {
    const double inverse_norm = 1.0 / f.h_norm;
    for (std::size_t k = 0; k < 6; ++k) {
      direction[k] = at.h[k] * inverse_norm;
    }
  }
  const double along = contract(direction, d); // h_hat : D
  const double blend = f.rho_chi * q.m_t + (1.0 - f.rho_chi) * q.m_r;
  const Stress lh = t.apply(direction);
  if (along > 0.0) {
    // Loading along the intergranular strain: towards the hypoplastic response as rho -> 1.
    if (std::isnan(f.rho_beta)) {
      f.rho_beta = std::exp(q.beta_r * f.log_rho);
    }
    const double rho_beta = f.rho_beta;
    for (std::size_t k = 0; k < 6; ++k) {
      out.stress[k] = blend * ld[k] + f.rho_chi * ((1.0 - q.m_t) * lh[k] + t.n[k]) * along;
      out.h[k] = d[k] - rho_beta * direction[k] * along;
    }
  } else {
    // Reversal or neutral: stiff (m_R L after 180 degrees, m_T L after 90 degrees at rho = 1).
    for (std::size_t k = 0; k < 6; ++k) {
      out.stress[k] = blend * ld[k] + f.rho_chi * (q.m_r - q.m_t) * lh[k] * along;
      out.h[k] = d[k];
    }
  }
  return out;
}

} // namespace

namespace {

/// The intergranular strain's rate per unit of D at h: D - rho^beta_R (h_hat : D) h_hat when
/// loading along h, D otherwise (hypoplastic_rate's out.h, which it must equal).
Stress intergranular_rate(const HypoplasticParameters& q, const Stress& h, const Stress& d) {
  const double h_norm = norm(h);
  if (!(h_norm > 0.0)) {
    return d;
  }
  const double inverse_norm = 1.0 / h_norm;
  Stress direction;
  for (std::size_t k = 0; k < 6; ++k) {
    direction[k] = h[k] * inverse_norm;
  }
  const double along = contract(direction, d);
  if (!(along > 0.0)) {
    return d;
  }
  // rho^beta_R by the series about one, where the loaded intergranular strain spends its time.
  const double rho_beta = power_near_one(std::min(h_norm / q.r_max, 1.0) - 1.0, q.beta_r);
  Stress out;
  for (std::size_t k = 0; k < 6; ++k) {
    out[k] = d[k] - rho_beta * direction[k] * along;
  }
  return out;
}

/// h after `fraction` of the increment D from `h`, by Heun's method with Euler's embedded error
/// to the tolerance relative to R, in substeps of its own (`step`: the last accepted one, in
/// units of the increment, kept between calls). h's rate depends on h and D alone: an evaluation
/// costs a few dozen operations, where the full rate costs the tangent and the state's powers.
/// Integrated with the stress, h's accuracy set the stress's substeps: 4.0 an increment while
/// the quick GDP pile is driven, where the stress's own error asks 1.19.
Stress advance_intergranular_strain(const HypoplasticParameters& q, Stress h, const Stress& d,
                                    double fraction, double& step, const Stress& rate_at_h) {
  // The smallest substep, of the increment: a bounded cost where the error will not fall.
  constexpr double smallest = 1e-6;
  double t = 0.0;
  int guard = 0;
  while (t < fraction) {
    step = std::min(step, fraction - t);
    // The rate at the start is the stress's first rate's (hypoplastic_rate's out.h): at rest, where
    // one step of h does, an evaluation of two.
    const Stress k1 = t == 0.0 ? rate_at_h : intergranular_rate(q, h, d);
    Stress euler;
    for (std::size_t k = 0; k < 6; ++k) {
      euler[k] = h[k] + step * k1[k];
    }
    const Stress k2 = intergranular_rate(q, euler, d);
    Stress next, difference;
    for (std::size_t k = 0; k < 6; ++k) {
      next[k] = h[k] + 0.5 * step * (k1[k] + k2[k]);
      difference[k] = next[k] - euler[k];
    }
    const double error = norm(difference) / q.r_max;
    if (step > smallest && !(error <= q.tolerance) && ++guard < 10000) {
      step *= std::max(0.2, 0.9 * std::sqrt(q.tolerance / error));
      continue;
    }
    h = next;
    // h stays within its sphere |h| <= R (its rate keeps it there; rounding may not).
    const double h_norm = norm(h);
    if (h_norm > q.r_max) {
      for (double& component : h) {
        component *= q.r_max / h_norm;
      }
    }
    t += step;
    step *= error > 0.0 ? std::clamp(0.9 * std::sqrt(q.tolerance / error), 0.2, 4.0) : 4.0;
  }
  return h;
}

} // namespace

HypoplasticPoint Hypoplastic::rate(const HypoplasticPoint& at, const Stress& d,
                                   double* modulus) const {
  StateFactors f =
      exact_factors(parameters_, f_b_scale_, mean_pressure(at.stress), at.e, norm(at.h));
  return hypoplastic_rate(parameters_, a_, at, f, d, modulus);
}

void Hypoplastic::initialise_state(const Stress& /*stress*/, double* state) const {
  // Called at the particles' creation and again after a K0 procedure: the void ratio is set once
  // (later calls find it set and keep what the soil has become); h starts at zero, so that the
  // first loading meets the small-strain stiffness m_R L.
  if (state[VOID_RATIO] <= 0.0) {
    state[VOID_RATIO] = parameters_.void_ratio;
    for (int k = 0; k < 6; ++k) {
      state[H_FIRST + k] = 0.0;
    }
    state[SUBSTEP] = 1.0;
    state[GAP_RATIO] = 0.0;
  }
}

Material::Inadmissible Hypoplastic::inadmissible_state(const Stress& stress,
                                                       const double* state) const {
  // e_i(p) bounds every state the model's equations reach from an admissible one (the loosest
  // state's compression test checks it); a start above it, as a void ratio meant for shallower
  // ground or a stress a thousand times too large, has no meaning in them. A start on e_i written
  // to six digits lies up to 5e-7 above it: within 1e-5, the integration's own accuracy there
  // (that test's path stays within 6e-7), it counts as on it.
  const double p = mean_pressure(stress);
  const double e_i = limit_void_ratio(parameters_.e_i0, std::max(p, 0.0));
  const double e = state[VOID_RATIO];
  if (!(e <= e_i * (1.0 + 1e-5))) {
    std::ostringstream s;
    s << "void_ratio " << e << " is looser than the loosest state at the mean stress p = " << p
      << " Pa, e_i = e_i0 exp(-(3 p / h_s)^n) = " << e_i
      << ": no sand exists there (lower void_ratio, or check the stress)";
    return {"void_ratio", s.str()};
  }
  return {};
}

void Hypoplastic::update_stress(const StressUpdateBatch& batch) const {
  for (std::size_t k = 0; k < batch.particles.size(); ++k) {
    const auto i = static_cast<std::size_t>(batch.particles[k]);
    batch.constrained_modulus[k] = update_point(
        batch.stress[i], batch.state + i * static_cast<std::size_t>(batch.state_stride),
        batch.strain[k]);
  }
}

double Hypoplastic::update_point(Stress& stress, double* state,
                                 const StrainIncrement& strain) const {
  const HypoplasticParameters& q = parameters_;
  const double p_min = q.minimum_pressure;
  if (state[VOID_RATIO] <= 0.0) {
    initialise_state(stress, state); // a particle no K0 procedure or water set up
  }
  HypoplasticPoint point;
  point.stress = stress;
  point.e = state[VOID_RATIO];
  // Open gaps (stretched at the floor pressure past e_i, below) close before any grain is pressed:
  // while they are open the particle is a loose cluster at the floor, and the increment only
  // widens or narrows them (the apparent void ratio e + g follows the volume). Forgotten, a
  // stretched particle pressed back compacted its grains from e_i: beside a resolved pile wall
  // one reached e = 0.28 (below e_d) at 0.39 of its density, carried 18 MPa of hoop stress and
  // set a 1.5e-6 s step (docs/hypoplasticity.md, "Void ratio").
  double gap = state[GAP_RATIO];
  double share = 1.0; // the part of the increment the grains take
  if (gap > 0.0) {
    const double opening = (1.0 + point.e + gap) * (strain[RR] + strain[YY] + strain[TT]);
    if (gap + opening > 0.0) {
      state[GAP_RATIO] = gap + opening;
      stress = Stress{-p_min, -p_min, -p_min, 0.0, 0.0, 0.0};
      return constrained_modulus(stress, state);
    }
    share = 1.0 - gap / -opening;
    gap = 0.0;
  }
  const Stress d{share * strain[RR],       share * strain[YY],       share * strain[TT],
                 share * 0.5 * strain[RY], share * 0.5 * strain[YT], share * 0.5 * strain[RT]};
  for (int k = 0; k < 6; ++k) {
    point.h[static_cast<std::size_t>(k)] = state[H_FIRST + k];
  }
  // Sand carries no tension: below p_min the stress is set isotropic at p_min, so that s = sigma /
  // tr(sigma) stays defined (docs/hypoplasticity.md, "Low pressure").
  // True where it changed the stress.
  auto floor_pressure = [p_min](Stress& s) {
    if (mean_pressure(s) < p_min) {
      s = Stress{-p_min, -p_min, -p_min, 0.0, 0.0, 0.0};
      return true;
    }
    if (!compressive(s, 1e-3 * p_min)) {
      cut_tension(s, p_min);
      return true;
    }
    return false;
  };
  floor_pressure(point.stress);
  // Substeps as fractions of the increment, Heun's method with Euler's embedded error; the last
  // increment's final substep is this one's first guess.
  // At most a thousand substeps an increment: a bounded cost where the error will not fall (the
  // substep is then accepted at its smallest); no shipped path comes near it.
  constexpr double smallest = 1e-3;
  double t = 0.0;
  double dt = std::clamp(state[SUBSTEP], smallest, 1.0);
  // The time step's modulus from the last accepted substep's second tangent (at its Euler state,
  // within the substep of the end): a third tangent at the final state cost a third of the update.
  // NaN where that substep ended at the floor or was cut: the tangent is then taken at the end.
  double modulus = std::numeric_limits<double>::quiet_NaN();
  // The rate at a substep's start is kept while the substep is retried smaller; the rate at its
  // Euler state takes its factors from the start's (factors_near: the same values, cheaper).
  bool start_rate_known = false;
  double h_step = 1.0; // advance_intergranular_strain's substep, in units of the increment
  StateFactors start{};
  HypoplasticPoint k1;
  while (t < 1.0) {
    dt = std::min(dt, 1.0 - t);
    if (!start_rate_known) {
      start = exact_factors(q, f_b_scale_, mean_pressure(point.stress), point.e, norm(point.h));
      k1 = hypoplastic_rate(q, a_, point, start, d, nullptr);
      start_rate_known = true;
    }
    HypoplasticPoint euler = point;
    for (std::size_t k = 0; k < 6; ++k) {
      euler.stress[k] += dt * k1.stress[k];
    }
    euler.e += dt * k1.e;
    // h to its own accuracy over the substep (advance_intergranular_strain): the second rate reads
    // it there, so the stress's error below includes what h's change does to the stress.
    if (q.intergranular_strain != 0.0) {
      euler.h = advance_intergranular_strain(q, point.h, d, dt, h_step, k1.h);
    }
    // Below the floor pressure the sand has let go (a tension cut): the substep ends there, at
    // the floor, without an error estimate. Shrinking the substep instead cost a hundred
    // rejected substeps per update at a free surface, whose particles sit at the floor.
    HypoplasticPoint next = euler;
    double error = 0.0;
    double attempt_modulus = std::numeric_limits<double>::quiet_NaN();
    if (mean_pressure(euler.stress) >= p_min && compressive(euler.stress, 1e-3 * p_min)) {
      StateFactors at_euler =
          factors_near(q, f_b_scale_, start, mean_pressure(euler.stress), euler.e, norm(euler.h));
      const HypoplasticPoint k2 = hypoplastic_rate(q, a_, euler, at_euler, d, &attempt_modulus);
      Stress stress_error{};
      next = point;
      next.h = euler.h;
      for (std::size_t k = 0; k < 6; ++k) {
        next.stress[k] += 0.5 * dt * (k1.stress[k] + k2.stress[k]);
        stress_error[k] = next.stress[k] - euler.stress[k];
      }
      next.e += 0.5 * dt * (k1.e + k2.e);
      error = norm(stress_error) / std::max(norm(next.stress), 3.0 * p_min);
    }
    // !(error <= tolerance): a rate that is not finite is refused as a large error is.
    if (dt > smallest && !(error <= q.tolerance)) {
      dt *= std::max(0.2, 0.9 * std::sqrt(q.tolerance / error));
      continue;
    }
    point = next;
    start_rate_known = false;
    modulus =
        floor_pressure(point.stress) ? std::numeric_limits<double>::quiet_NaN() : attempt_modulus;
    // No state is looser than e_i(p): sand stretched past it at the floor pressure (beside a
    // cone's shoulder) opens gaps, not pores; they are kept in GAP_RATIO and close first when
    // pressed (above). Unbounded, its void ratio reached 15 in the CPT chamber and f_e = (e_c /
    // e)^beta took its stiffness away (docs/hypoplasticity.md).
    // Only there: elsewhere the equations keep e below e_i themselves (the loosest state's
    // compression test checks it).
    if (mean_pressure(point.stress) <= p_min) {
      const double e_loosest = limit_void_ratio(q.e_i0, p_min);
      if (point.e > e_loosest) {
        gap += point.e - e_loosest;
        point.e = e_loosest;
      }
    }
    // h stays within its sphere |h| <= R (its rate keeps it there; rounding may not).
    const double h_norm = norm(point.h);
    if (q.intergranular_strain != 0.0 && h_norm > q.r_max) {
      for (double& component : point.h) {
        component *= q.r_max / h_norm;
      }
    }
    t += dt;
    if (error > 0.0) {
      dt *= std::clamp(0.9 * std::sqrt(q.tolerance / error), 0.2, 4.0);
    } else {
      dt *= 4.0;
    }
  }
  stress = point.stress;
  state[VOID_RATIO] = point.e;
  for (int k = 0; k < 6; ++k) {
    state[H_FIRST + k] = point.h[static_cast<std::size_t>(k)];
  }
  state[SUBSTEP] = std::min(dt, 1.0);
  state[GAP_RATIO] = gap;
  return std::isnan(modulus) ? constrained_modulus(stress, state) : modulus;
}

namespace {

/// The tangent at a stress raised to the floor pressure where it lies below it, and at the
/// particle's void ratio (the initial one before the state is set): what the time step, the
/// absorbing faces and the ledger read.
Tangent floored_tangent(const HypoplasticParameters& q, double a, double f_b_scale, Stress s,
                        const double* state) {
  if (mean_pressure(s) < q.minimum_pressure) {
    const double p = q.minimum_pressure;
    s = Stress{-p, -p, -p, 0.0, 0.0, 0.0};
  }
  const double e = state[Hypoplastic::VOID_RATIO];
  return hypoplastic_tangent(
      a, s, exact_factors(q, f_b_scale, mean_pressure(s), e > 0.0 ? e : q.void_ratio, 0.0));
}

} // namespace

double Hypoplastic::constrained_modulus(const Stress& stress, const double* state) const {
  return modulus_bound(parameters_, floored_tangent(parameters_, a_, f_b_scale_, stress, state));
}

double Hypoplastic::shear_modulus(const Stress& stress, const double* state) const {
  const Tangent t = floored_tangent(parameters_, a_, f_b_scale_, stress, state);
  return reversal_multiplier(parameters_) * 0.5 * t.c * t.f2;
}

double Hypoplastic::elastic_energy_density(const Stress& stress, const double* state) const {
  const double p = mean_pressure(stress);
  if (p < parameters_.minimum_pressure) {
    return 0.0;
  }
  const Tangent t = floored_tangent(parameters_, a_, f_b_scale_, stress, state);
  const double multiplier = reversal_multiplier(parameters_);
  return isotropic_elastic_energy_density(stress, multiplier * t.c * (t.f2 + t.a2 / 3.0) / 3.0,
                                          multiplier * 0.5 * t.c * t.f2);
}

} // namespace mpile
