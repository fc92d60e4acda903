// The verification cases run from their case files (cases/verification/*.toml): the program
// carries the repository's files, `mpile verify` lists V1 to V9, and V7 meets Coulomb's closed form
// through the same phase runner as `mpile run`. V9 at the case file's resolution is
// V9TorsionWithAdhesion.RigidPileAtTheCaseFileResolution (contact_test.cpp); the other cases are
// verification_test.cpp.
#include "case_run.hpp"
#include "cases/verification/case_file_run.hpp"
#include "cases/verification/case_texts.hpp"
#include "cases/verification/verification_cases.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mpile {
namespace {

TEST(VerificationFiles, TheProgramCarriesTheRepositorysCaseFiles) {
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(source / "cases/verification")) {
    if (entry.path().extension() == ".toml") {
      ++files;
      EXPECT_EQ(std::string(verification::case_text(entry.path().filename().string())),
                read_text(entry.path()))
          << entry.path();
    }
  }
  EXPECT_EQ(verification::case_texts().size(), files);
  EXPECT_THROW(verification::case_text("no_such_case.toml"), std::logic_error);
}

TEST(VerificationFiles, VerifyListsEveryCaseFromV1ToV9InOrder) {
  std::vector<std::string> ids;
  for (const verification::Case& c : verification::all_cases()) {
    ids.push_back(c.id);
  }
  const std::vector<std::string> expected{"V1",  "V2", "V3", "V4",   "V4p", "V5",  "V6",
                                          "V6c", "V7", "V8", "V8k0", "V9",  "V10", "VHS"};
  EXPECT_EQ(ids, expected);
  EXPECT_NE(verification::find_case("V7"), nullptr);
  EXPECT_EQ(verification::find_case("V11"), nullptr);
}

TEST(VerificationFiles, RefinementMultipliesEveryZonesCells) {
  using verification::refined;
  EXPECT_EQ(refined("r = [{ start = 0.0, end = 5.0, cells = 50 }]\n"
                    "y = [{ start = 0, end = 1, cells = 3 }, { start = 1, end = 2, cells = 12 }]",
                    3),
            "r = [{ start = 0.0, end = 5.0, cells = 150 }]\n"
            "y = [{ start = 0, end = 1, cells = 9 }, { start = 1, end = 2, cells = 36 }]");
  using verification::refined;
  EXPECT_EQ(refined("no grid here", 2), "no grid here");
}

// An [affine_motion] does work on the soil as a support does: against a steady field, the work of
// the internal forces. The patch's balance then closes to the quadrature error of the stress
// power over the steps (the stress at the start of each step, growing linearly from zero, so the
// work falls short of the stored energy by a share 1 / steps; measured 1 / steps to five digits),
// which halves with the step. (The residual was the whole energy: the motion's work was not
// booked.)
TEST(VerificationFiles, AnAffineMotionsWorkIsTheStoredEnergyToFirstOrderInTheStep) {
  std::vector<double> shares;
  for (const char* courant : {"0.8", "0.4"}) {
    std::string text(verification::case_text("radial_patch.toml"));
    text += std::string("\n[solver]\ncourant_number = ") + courant + "\n";
    CaseRun run(text);
    run.run([] {});
    const EnergyBalance balance = run.solver->energy_balance();
    const double steps = static_cast<double>(run.solver->step_count());
    EXPECT_NEAR(balance.residual / balance.elastic, -1.0 / steps, 0.1 / steps) << courant;
    shares.push_back(balance.residual / balance.elastic);
  }
  EXPECT_NEAR(shares[1] / shares[0], 0.5, 0.05);
}

TEST(VerificationFiles, V7BlockSlidesAsCoulombFrictionSays) {
  // mu = 0.3 on 30 degrees: s(1 s) = g (sin a - mu cos a) / 2 = 1.1781 m within the case's 3 %.
  const verification::Report report = verification::run_block_on_incline({});
  ASSERT_EQ(report.checks.size(), 1u);
  EXPECT_NEAR(report.checks[0].reference, 1.17814, 1e-5);
  EXPECT_TRUE(report.passed()) << report.checks[0].measured;
}

} // namespace
} // namespace mpile
