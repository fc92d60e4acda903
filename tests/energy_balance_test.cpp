// The energy balance against exact answers: an undamped elastic bar keeps its energy, a damped
// column settling under its weight dissipates half the work gravity did (Clapeyron: a linear
// elastic body stores half the work of a load applied at once), and a block sliding down a rigid
// incline loses mu N s to friction, and a rough footing pushed into clay books the friction and
// adhesion on the slip the particles make.
#include "case_run.hpp"
#include "solver/diagnostics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <utility>
#include <vector>

namespace mpile {
namespace {

/// The largest relative residual of the V1 bar over its three periods at a Courant number, and
/// the step it ran with.
std::pair<double, double> bar_residual(const std::string& courant) {
  CaseRun run(replaced(read_text(source / "cases/verification/vibrating_bar.toml"),
                       "courant_number = 0.8", "courant_number = " + courant));
  const double start = run.solver->energy_balance().kinetic;
  EXPECT_NEAR(start, 0.03125, 0.03125 * 0.01); // rho A L v0^2 / 4 with the particles' quadrature
  double worst = 0.0;
  run.run([&] {
    const EnergyBalance b = run.solver->energy_balance();
    worst = std::max(worst, b.relative_residual);
    // Linear elastic: no plastic work. The stored energy is counted on the current volume and the
    // work on the mean volume of each step, a difference of order eps w V with the strain
    // amplitude eps = v0 / c = 1 %: 0.5 % of the energy bounds it.
    EXPECT_LT(std::abs(b.plastic), 0.005 * start);
    EXPECT_EQ(b.external_work, 0.0); // a roller base does no work
    EXPECT_EQ(b.damping, 0.0);
  });
  return {worst, run.solver->stable_time_step()}; // the last step was cut to land on the end
}

TEST(EnergyBalance, UndampedElasticBarKeepsItsEnergyToFirstOrderInDt) {
  // MUSL updates velocities first, then positions with the new velocities (symplectic Euler): it
  // conserves a modified energy, and the true energy oscillates about it with relative amplitude
  // omega dt / 2 at twice the frequency, without drift. The residual must stay within that bound
  // (10 % over the leading-order estimate) and halve with the step.
  const double omega = std::numbers::pi / 50.0 * 10.0; // pi / (2 L) sqrt(E / rho)
  const auto [coarse, dt_coarse] = bar_residual("0.8");
  const auto [fine, dt_fine] = bar_residual("0.4");
  EXPECT_LT(coarse, 1.1 * omega * dt_coarse / 2.0);
  EXPECT_LT(fine, 1.1 * omega * dt_fine / 2.0);
  EXPECT_NEAR(coarse / fine, 2.0, 0.2);
}

// PIC and XPIC take kinetic energy from the particles that FLIP would keep (the velocity update's
// numerical dissipation); the balance books it as transfer and closes as tightly as with FLIP.
TEST(EnergyBalance, TheVelocityUpdatesDissipationIsBookedAsTransfer) {
  const double omega = std::numbers::pi / 50.0 * 10.0;
  for (const std::string update : {"flip_fraction = 0.0", "xpic_order = 2"}) {
    CaseRun run(replaced(read_text(source / "cases/verification/vibrating_bar.toml"),
                         "flip_fraction = 1.0", update));
    const double start = run.solver->energy_balance().kinetic;
    double worst = 0.0;
    run.run([&] { worst = std::max(worst, run.solver->energy_balance().relative_residual); });
    const EnergyBalance end = run.solver->energy_balance();
    // The bound FLIP keeps (UndampedElasticBarKeepsItsEnergyToFirstOrderInDt).
    const double bound = 1.1 * omega * run.solver->stable_time_step() / 2.0;
    EXPECT_LT(worst, bound) << update;
    EXPECT_GE(end.transfer, 0.0) << update;
    if (update == "flip_fraction = 0.0") {
      // PIC loses about 8 % of the energy per period on this mesh: far more than the bound, so a
      // balance that did not book it would fail above.
      EXPECT_GT(end.transfer, 0.1 * start);
      EXPECT_GT(end.transfer / start, 3.0 * bound);
    }
  }
}

TEST(EnergyBalance, DampedColumnDissipatesHalfTheWorkOfGravity) {
  CaseRun run(read_text(source / "cases/verification/self_weight_column.toml"));
  run.run([] {});
  const EnergyBalance b = run.solver->energy_balance();
  ASSERT_GT(b.external_work, 0.0);
  // At rest: kinetic ~ 0, stored = W/2 exactly for linear elasticity, damping took the rest.
  EXPECT_LT(b.kinetic, 1e-4 * b.external_work);
  EXPECT_NEAR(b.elastic / b.external_work, 0.5, 0.01);
  EXPECT_NEAR(b.damping / b.external_work, 0.5, 0.01);
  EXPECT_LT(b.relative_residual, 0.01);
}

TEST(EnergyBalance, SlidingBlockLosesMuNsToFriction) {
  CaseRun run(read_text(source / "cases/verification/v7_block_on_incline.toml"));
  run.run([] {});
  const Particles& p = run.scene->particles;
  double mass = 0.0, slide = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] == 0) {
      mass += p.mass[i];
      slide += p.mass[i] * (p.r[i] - p.r0[i]);
    }
  }
  slide /= mass;
  const double normal = mass * 8.49571; // m g cos 30 deg per metre
  const EnergyBalance b = run.solver->energy_balance();
  // The contact pass also removes the normal approach of each step (g cos a dt per step, a loss
  // of order m (g dt)^2 per step, a few 1e-4 of the total) and the block rings elastically, so
  // the friction loss matches mu N s to 1 %.
  EXPECT_NEAR(b.contact / (0.3 * normal * slide), 1.0, 0.01);
  EXPECT_LT(b.relative_residual, 0.01);
}

TEST(EnergyBalance, AnElasticFootingUnderXpicBooksNoContactDissipation) {
  // cases/verification/footing_tresca.toml with the clay elastic (c = 1e12 Pa), XPIC(2) as the
  // case, smooth, to 0.55 s (0.025 m): nothing dissipates, so the work of the push goes into
  // elastic energy (the internal work meets the external to 0.2 %). XPIC pulls the particles
  // beside the base off the footing's velocity, so each step the nodes there bring an approach
  // that the contact closes. Charged at the step's mean relative velocity, that correction booked
  // the clay's resistance times half the approach as well: 64 J of 660 (contact), a residual of
  // 9.8 %, growing as the step shrinks. Booked as the approach's own m r0^2 / 2, the contact's
  // share is 0.02 % and the residual at most 0.49 % past the ramp (0.23 % at the end; FLIP's 0.2
  // %). 1 % bounds both with room for the FLIP-level noise of the particles' kinetic energy
  // against the grid's.
  const std::string text =
      replaced(replaced(read_text(source / "cases/verification/footing_tresca.toml"),
                        "duration = 4.05", "duration = 0.55"),
               "cohesion = 20e3", "cohesion = 1e12");
  CaseRun run(text);
  double worst = 0.0;
  run.run([&] {
    if (run.solver->time() > 0.25) { // past the ramp, whose residual is of little energy
      worst = std::max(worst, run.solver->energy_balance().relative_residual);
    }
  });
  const EnergyBalance b = run.solver->energy_balance();
  std::cout << "external work " << b.external_work << ", elastic " << b.elastic << ", contact "
            << b.contact << ", transfer " << b.transfer << ", largest relative residual " << worst
            << "\n";
  EXPECT_LT(b.contact, 0.01 * b.external_work);
  EXPECT_LT(worst, 0.01);
}

} // namespace
} // namespace mpile

namespace mpile {
namespace {

TEST(EnergyBalance, TorqueDrivenPileAgainstAdhesionCloses) {
  // V9's pile driven by a harmonic torque instead of a constant spin (as the GDP cases are): the
  // torque's work must match the pile's kinetic energy, the soil's and what the adhesive interface
  // takes, with the rigid body's work and the contact's loss taken at the mean velocity over each
  // step (a 20 Hz torque changes the spin a lot within one step).
  std::string text = read_text(source / "cases/verification/v9_torsion_adhesion.toml");
  text = replaced(text, "cells = 40", "cells = 10");
  text = replaced(text, "angular_velocity = { type = \"constant\", value = 0.02 }",
                  "torque = { type = \"harmonic\", amplitude = 8000.0, frequency = 20.0 }");
  text = replaced(text, "duration = 1.0", "duration = 0.2");
  CaseRun run(text);
  run.run([] {});
  const EnergyBalance b = run.solver->energy_balance();
  EXPECT_GT(b.contact, 0.5 * b.external_work); // the interface slides and takes most of it
  // Measured 0.12 %. It was 1.4 % while the soil at a sticking node took the pile's predicted
  // velocity, before the pile felt the contact's reaction, which created energy in the first
  // milliseconds; the torque-driven spin and its contact are now solved together (docs/design.md).
  // 0.5 % leaves room for the rounding of the step's quadrature, not for that start.
  EXPECT_LT(b.relative_residual, 0.005);
}

TEST(EnergyBalance, RoughFootingBooksFrictionOnTheSlipTheParticlesMake) {
  // cases/verification/strip_footing.toml to 1 s (0.045 m, past the peak of the load): a rigid
  // strip footing whose base drags the clay by adhesion (the case) or by friction, and the
  // smooth one. Friction and adhesion were booked on the slip of the first contact pass, which a
  // node the step's force has just accelerated makes but the remapped velocities, which strain the
  // clay, do not: past the ramp the rough footing's balance then lacked up to 5.2 % of the energy
  // in play (adhesion) and 7.7 % (friction), about as much as was booked to contact. The smooth
  // footing, with no tangential work, closes to 0.76 %; the rough ones must close as well, within
  // 1 % (0.46 % and 0.67 %).
  const std::string text = replaced(read_text(source / "cases/verification/strip_footing.toml"),
                                    "duration = 2.05", "duration = 1.0");
  for (const auto& [label, edit] : std::vector<std::pair<std::string, std::string>>{
           {"adhesion", "adhesion = 20e3"},
           {"friction", "friction = 1.0\nadhesion = 0.0"},
           {"smooth", "adhesion = 0.0"}}) {
    CaseRun run(replaced(replaced(text, "friction = 0.0\n", ""), "adhesion = 20e3", edit));
    double worst = 0.0;
    run.run([&] {
      if (run.solver->time() > 0.25) { // past the ramp, whose residual is of little energy
        worst = std::max(worst, run.solver->energy_balance().relative_residual);
      }
    });
    const EnergyBalance b = run.solver->energy_balance();
    std::cout << label << ": external work " << b.external_work << ", contact " << b.contact
              << ", largest relative residual " << worst << "\n";
    EXPECT_LT(worst, 0.01) << label;
    if (label != "smooth") {
      EXPECT_GT(b.contact, 0.01 * b.external_work) << label; // the interface does dissipate
    }
  }
}

} // namespace
} // namespace mpile
