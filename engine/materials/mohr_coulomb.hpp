#pragma once

// Mohr-Coulomb, elastic-perfectly plastic, with a Rankine tension cut-off and non-associated flow
// (dilatancy angle psi <= phi). The return is implicit and exact in principal stress space: every
// part of the yield surface is a plane there, so each return (to a plane, an edge or a corner) is
// one small linear solve, chosen by the consistency conditions (Clausen, Damkilde and Andersen 2006
// and 2007; de Souza Neto, Peric and Owen 2008, chapter 8).

#include "engine/materials/material.hpp"

#include <array>
#include <string>
#include <vector>

namespace mpile {

/// Mohr-Coulomb's own ranges (its elastic ones are material.hpp's), declared once: the registry's
/// keys and the constructor take them from here.
inline const ParameterRange cohesion_range = at_least(0.0);
inline const ParameterRange mohr_coulomb_friction_range = between(0.0, true, 90.0, false);
inline const ParameterRange tension_limit_range = at_least(0.0);

/// The part of the yield surface a stress is returned to. Edges and corners are named after the
/// triaxial states they hold, compression positive: triaxial compression has the axial stress
/// largest and sigma_2 = sigma_3, triaxial extension has sigma_1 = sigma_2. (In a tension-positive
/// ordering, as in de Souza Neto et al., the same edges appear with the indices reversed.)
enum class MohrCoulombRegion {
  elastic,
  shear_plane,                // sigma_1 - N_phi sigma_3 = 2 c sqrt(N_phi)
  compression_edge,           // shear plane with sigma_2 = sigma_3 (triaxial compression)
  extension_edge,             // shear plane with sigma_1 = sigma_2 (triaxial extension)
  tension_plane,              // sigma_3 = -tension_limit
  tension_edge,               // sigma_2 = sigma_3 = -tension_limit
  shear_tension_edge,         // shear plane meets the tension plane
  compression_tension_corner, // sigma_2 = sigma_3 at the cut-off, sigma_1 on the shear plane
  extension_tension_corner,   // sigma_1 = sigma_2 on the shear plane, sigma_3 at the cut-off
  apex                        // hydrostatic tension sigma_1 = sigma_2 = sigma_3 = -tension_limit
};

/// The result of a return in principal space (soil-mechanics convention, compression positive).
struct MohrCoulombReturn {
  std::array<double, 3> stress{};         // sigma_1 >= sigma_2 >= sigma_3 (Pa)
  std::array<double, 3> plastic_strain{}; // principal plastic strain increment, shear and tension
  double plastic_shear_strain = 0.0; // increment of epsilon_1^p - epsilon_3^p of the shear flow
  MohrCoulombRegion region = MohrCoulombRegion::elastic;
  /// True only when no return met every consistency condition to rounding and the nearest one was
  /// taken (then clipped onto the surface). Never expected; tests count it.
  bool nearest = false;
};

class MohrCoulomb final : public Material {
public:
  /// Angles in degrees. Throws std::invalid_argument naming the parameter for E <= 0, nu outside
  /// (-1, 0.5), density <= 0, c < 0, phi outside [0, 90), psi outside [0, phi], a negative tension
  /// limit, or c = phi = 0 (no shear strength). The tension limit is capped at c cot(phi), the apex
  /// of the Mohr-Coulomb cone.
  MohrCoulomb(double young_modulus, double poisson_ratio, double density, double cohesion,
              double friction_angle, double dilatancy_angle, double tension_limit);

  std::string_view type() const override { return "mohr_coulomb"; }
  double density() const override { return density_; }
  std::span<const std::string> state_names() const override;
  void initialise_state(const Stress& stress, double* state) const override;
  void update_stress(const StressUpdateBatch& batch) const override;
  double constrained_modulus(const Stress&, const double*) const override {
    return lambda_ + 2.0 * mu_;
  }
  double shear_modulus(const Stress&, const double*) const override { return mu_; }
  double elastic_energy_density(const Stress& stress, const double* state) const override;

  /// Return of a trial state given by its principal compressions (sorted, sigma_1 first).
  MohrCoulombReturn return_principal(const std::array<double, 3>& trial) const;

  /// Shear yield function f = sigma_1 - N_phi sigma_3 - 2 c sqrt(N_phi) (Pa) of sorted principal
  /// compressions; zero on the shear plane, negative inside.
  double shear_yield_function(const std::array<double, 3>& principal) const;

  double young_modulus() const { return young_; }
  double poisson_ratio() const { return poisson_; }
  using Material::shear_modulus;
  double shear_modulus() const { return mu_; }
  double lame_lambda() const { return lambda_; }
  double cohesion() const { return cohesion_; }
  double friction_angle() const { return friction_degrees_; }   // degrees
  double dilatancy_angle() const { return dilatancy_degrees_; } // degrees
  double tension_limit() const { return tension_; }             // after the cap (Pa)
  double flow_number() const { return n_phi_; } // N_phi = (1 + sin phi)/(1 - sin phi)

private:
  // A plane of the surface in sorted principal space: f = normal . sigma - level <= 0, with the
  // flow direction (gradient of the plastic potential) and the stress corrector D flow.
  struct Plane {
    std::array<double, 3> normal;
    double level;
    std::array<double, 3> flow;
    std::array<double, 3> corrector;
    bool shear;
  };
  // A return candidate: the planes active on it and, for a corner, its exact position. A corner
  // where more than three planes meet lists several triples; any one with non-negative multipliers
  // proves the trial lies in the corner's cone of correctors.
  struct Candidate {
    MohrCoulombRegion region;
    std::vector<std::array<std::size_t, 3>> plane_sets;
    std::size_t size;
    bool corner;
    std::array<double, 3> corner_stress;
  };

  double young_;
  double poisson_;
  double density_;
  double cohesion_;
  double friction_degrees_;
  double dilatancy_degrees_;
  double tension_;
  double lambda_;
  double mu_;
  double n_phi_;
  double n_psi_;
  double strength_; // 2 c sqrt(N_phi)
  std::array<Plane, 6> planes_;
  std::vector<Candidate> candidates_;
};

} // namespace mpile
