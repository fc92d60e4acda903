#pragma once

#include <array>

namespace mpile {

/// The fraction of each tangential relative velocity a contact node keeps after its Coulomb
/// correction (physics.md section 5): 0 where it sticks.
struct SlipKept {
  double plane = 0.0; // of the r-y tangential slip
  double theta = 0.0; // of the theta slip
};

/// Coulomb friction at a contact node whose tangential DOFs have different inertias: the r-y ones
/// the node's mass m, the theta one J / r^2 in axisymmetric mode (the node's unknown is its angular
/// velocity). slip_plane and slip_theta are the magnitudes of the tangential relative velocities
/// before the correction, limit the largest tangential impulse (mu times the normal impulse plus
/// c_a A dt). The node sticks when the impulse that stops both slips is within the limit. Otherwise
/// it slides and the friction impulse F, of magnitude limit, opposes the slip s that is left
/// (s = t - F / m per DOF): s_d = t_d x / (x + c_d) with c_d = limit / m_d and |s| = x the root of
/// sum t_d^2 / (x + c_d)^2 = 1. With equal inertias x = |t| - c, the isotropic rule.
SlipKept coulomb_slip(double slip_plane, double slip_theta, double mass, double theta_mass,
                      double limit);

/// The contact law at one node (physics.md section 5), as a change of the soil's velocity. The
/// soil's velocity relative to the structure is `relative` (r, y, theta) and n the structure's
/// outward unit normal in r-y; the node's soil has mass m (r-y DOFs) and theta_mass (J / r^2).
/// The approach along n is removed (no interpenetration; the caller decides separation), and the
/// tangential slip (r-y and theta together) is reduced by Coulomb friction on that normal impulse
/// plus an adhesive impulse (c_a A dt / beta): mu max(m |v_n| + pore_impulse, 0) +
/// adhesion_impulse. The friction acts on the effective normal impulse: pore_impulse is the pore
/// water's share of it with its sign, p A dt / beta (p tension positive, so compressed water
/// lessens the friction); 0 for a dry or drained soil.
struct ContactCorrection {
  std::array<double, 3> change{}; // soil velocity change (r, y, theta)
  SlipKept keep;                  // fractions of the tangential slips left (0: sticks)
};
ContactCorrection contact_correction(const std::array<double, 3>& relative,
                                     const std::array<double, 2>& n, double mass, double theta_mass,
                                     double friction, double adhesion_impulse,
                                     double pore_impulse = 0.0);

} // namespace mpile
