#pragma once

#include "engine/scene.hpp"

namespace mpile {

/// Running sums of the energy balance (docs/design.md, "Energy balance"), kept by the solver from
/// the start of the run (J, per radian in axisymmetric mode).
struct EnergyLedger {
  /// Work of gravity, loads and supports on the soil (the rigid bodies keep their own).
  double external_work = 0.0;
  /// sum over steps and particles of V sigma : d eps: stored elastic energy plus plastic work.
  double internal_work = 0.0;
  /// Taken by local damping.
  double damping = 0.0;
  /// Taken by the contact correction (friction and the inelastic normal approach).
  double contact = 0.0;
  /// Kinetic and elastic energy the balance starts from; a phase that changes the mass scaling or
  /// resets the stresses moves them, so the balance carries on across the change.
  double kinetic_reference = 0.0;
  double elastic_reference = 0.0;
  /// Taken by the particle velocity update against FLIP: the numerical dissipation of a FLIP/PIC
  /// blend or of XPIC (0 with pure FLIP).
  double transfer = 0.0;
  /// Taken out of the model by the dashpots of absorbing faces: the energy radiated away.
  double radiated = 0.0;
  /// Taken by Darcy's drag between the pore water and the skeleton (coupled soil).
  double drag = 0.0;
};

/// What one pass of a step adds to the ledger (J, per radian in axisymmetric mode). Each pass
/// returns its own; the step adds them in pass order.
struct EnergyIncrement {
  double external_work = 0.0;
  double internal_work = 0.0;
  double damping = 0.0;
  double contact = 0.0;
  double transfer = 0.0;
  double radiated = 0.0;
  double drag = 0.0;
};

EnergyLedger& operator+=(EnergyLedger& ledger, const EnergyIncrement& increment);

/// The balance at one instant: external work = (kinetic - its reference) + internal work +
/// damping + contact + transfer + radiated + drag + residual, with internal work = (elastic - its
/// reference) + plastic.
struct EnergyBalance {
  double external_work = 0.0;
  double kinetic = 0.0; // with the mass scaling's inertia, the energy the dynamics conserve
  double elastic = 0.0;
  double plastic = 0.0;
  double damping = 0.0;
  double contact = 0.0;
  double transfer = 0.0;
  double radiated = 0.0;
  double drag = 0.0;
  double residual = 0.0;
  /// The residual over the largest energy in play: |external work|, the kinetic energy now or at
  /// the reference, the stored elastic energy, |internal work|, or the dissipated sum (a state
  /// held at rest by its initial stresses is measured against what it stores, not against the
  /// round-off of a work that is nearly zero); 0 when there is none.
  double relative_residual = 0.0;
};

/// The ledger's external work plus the rigid bodies' (their drives and weights).
double total_external_work(const Scene& scene, const EnergyLedger& ledger);

/// Evaluates the balance of a scene whose inertia is scaled by mass_scaling.
EnergyBalance energy_balance(const Scene& scene, const EnergyLedger& ledger, double mass_scaling);

} // namespace mpile
