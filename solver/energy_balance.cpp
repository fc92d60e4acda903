#include "solver/energy_balance.hpp"

#include "solver/diagnostics.hpp"

#include <algorithm>
#include <cmath>

namespace mpile {

EnergyLedger& operator+=(EnergyLedger& ledger, const EnergyIncrement& increment) {
  ledger.external_work += increment.external_work;
  ledger.internal_work += increment.internal_work;
  ledger.damping += increment.damping;
  ledger.contact += increment.contact;
  ledger.transfer += increment.transfer;
  ledger.radiated += increment.radiated;
  ledger.drag += increment.drag;
  return ledger;
}

double total_external_work(const Scene& scene, const EnergyLedger& ledger) {
  double work = ledger.external_work;
  for (const RigidBody& body : scene.rigid_bodies) {
    work += body.external_work;
  }
  return work;
}

EnergyBalance energy_balance(const Scene& scene, const EnergyLedger& ledger, double mass_scaling) {
  EnergyBalance b;
  b.external_work = total_external_work(scene, ledger);
  b.kinetic = mass_scaling * kinetic_energy(scene);
  b.elastic = elastic_energy(scene);
  b.plastic = ledger.internal_work - (b.elastic - ledger.elastic_reference);
  b.damping = ledger.damping;
  b.contact = ledger.contact;
  b.transfer = ledger.transfer;
  b.radiated = ledger.radiated;
  b.drag = ledger.drag;
  b.residual = b.external_work - (b.kinetic - ledger.kinetic_reference) - ledger.internal_work -
               b.damping - b.contact - b.transfer - b.radiated - b.drag;
  const double scale =
      std::max({std::abs(b.external_work), b.kinetic, ledger.kinetic_reference, b.elastic,
                std::abs(ledger.internal_work),
                std::abs(b.damping + b.contact + b.transfer + b.radiated + b.drag)});
  b.relative_residual = scale > 0.0 ? std::abs(b.residual) / scale : 0.0;
  return b;
}

} // namespace mpile
