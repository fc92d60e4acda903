// Values that read but are most likely in the wrong unit must be named before the run, with the
// file, line and key and the likely mistake; --strict refuses them; no shipped case has one.
#include "app/run_command.hpp"
#include "cases/case_error.hpp"
#include "cases/case_spec.hpp"
#include "tests/case_run.hpp"
#include "tests/saturated_column.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <stdexcept>

namespace mpile {
namespace {

/// The GDP quick case as one file (tests/data/), with the first `from` replaced by `to`.
std::string gdp_edited(const std::string& from, const std::string& to) {
  std::string text = read_text(source / "tests/data/gdp_quick_flat.toml");
  const auto at = text.find(from);
  if (at == std::string::npos) {
    throw std::logic_error("test edit does not apply: " + from);
  }
  return text.replace(at, from.size(), to);
}

/// The warnings of units the reader finds in a case text, one per line.
std::string units_warnings(const std::string& text) {
  std::string found;
  for (const CaseWarning& w : read_case_text(text, "case.toml").warnings) {
    if (w.kind == CaseWarning::Kind::units) {
      found += w.text + "\n";
    }
  }
  return found;
}

/// One units warning, at `where`, saying each of `says` (the suspicion and the likely mistake).
void expect_one_warning(const std::string& text, const std::string& where,
                        std::initializer_list<std::string> says) {
  const std::string found = units_warnings(text);
  EXPECT_EQ(found.rfind(where, 0), 0u) << found;
  for (const std::string& part : says) {
    EXPECT_NE(found.find(part), std::string::npos) << part << "\n" << found;
  }
  EXPECT_EQ(std::count(found.begin(), found.end(), '\n'), 1) << found;
}

TEST(CaseWarnings, TheGdpCaseAsShippedHasNone) {
  EXPECT_EQ(units_warnings(gdp_edited("", "")), "");
}

TEST(CaseWarnings, ATorqueInKilonewtonMetres) {
  expect_one_warning(gdp_edited("amplitude = 414500.0", "amplitude = 414.5"),
                     "case.toml:49: monopile.drive.torque: ",
                     {"torque amplitude 414.5 N m/rad is below 10 kN m/rad, less than turns the "
                      "monopile",
                      "did you mean 414.5 kN m/rad = 414500?"});
  // A torque of thousands written in kN m (1.2 MN m/rad as 1200) is caught on the monopile too.
  expect_one_warning(
      gdp_edited("amplitude = 414500.0", "amplitude = 1200.0"),
      "case.toml:49: monopile.drive.torque: ", {"did you mean 1200 kN m/rad = 1.2e+06?"});
}

TEST(CaseWarnings, ASteelModulusInMegapascals) {
  expect_one_warning(gdp_edited("young_modulus = 220e9", "young_modulus = 210000.0"),
                     "case.toml:25: materials.steel.young_modulus: ",
                     {"for a material of density 8000 kg/m^3 (a metal) is below any metal's",
                      "did you mean 210000 MPa = 2.1e+11?"});
}

TEST(CaseWarnings, GravityAlongTheRadius) {
  expect_one_warning(gdp_edited("gravity = [0.0, -9.81]", "gravity = [-9.81, 0.0]"),
                     "case.toml:53: solver.gravity: ",
                     {"gravity has a component along r (g_r = -9.81), which the axisymmetric "
                      "geometry (r about a vertical axis) cannot have: did you mean [0, -9.81]?"});
}

TEST(CaseWarnings, AGridZoneInMillimetres) {
  std::string text = read_text(source / "cases/verification/terzaghi_consolidation.toml");
  const std::string from = "y = [{ start = 0.0, end = 1.05, cells = 42 }]";
  ASSERT_NE(text.find(from), std::string::npos);
  // A zone above the column typed in mm: 1.05 to 50 000 m for 1.05 to 50 m.
  text.replace(text.find(from), from.size(),
               "y = [{ start = 0.0, end = 1.05, cells = 42 }, { start = 1.05, end = 50000.0, "
               "cells = 1 }]");
  const std::string found = units_warnings(text);
  EXPECT_NE(found.find("case.toml:15: grid.y[1].end: a zone from 1.05 to 50000 m reaches beyond "
                       "10 km, more than any soil block modelled: did you mean mm (0.00105 to 50 "
                       "m)?"),
            std::string::npos)
      << found;
}

TEST(CaseWarnings, ThePoreWatersKeysInTheWrongUnits) {
  // The seed's sand saturated (grain density 2650: n = 0.375), each water key in a slipped unit.
  const auto saturated = [](const std::string& keys) {
    return gdp_edited("density = 1656.25",
                      "density = 1656.25\ndrainage = \"coupled\"\nhydraulic_conductivity = "
                      "1e-4\ngrain_density = 2650.0\n" +
                          keys);
  };
  EXPECT_EQ(units_warnings(saturated("")), "");
  expect_one_warning(
      saturated("water_density = 1.0"), "case.toml:25: materials.sand.water_density: ",
      {"water_density = 1 kg/m^3 is not water's", "did you mean 1000 (g/cm^3 given)?"});
  expect_one_warning(saturated("water_bulk_modulus = 2.2"),
                     "case.toml:25: materials.sand.water_bulk_modulus: ",
                     {"is not water's (K_w = 2.2e9 Pa): did you mean 2.2 GPa = 2.2e+09?"});
  expect_one_warning(saturated("water_bulk_modulus = 2200.0"),
                     "case.toml:25: ", {"did you mean 2200 MPa = 2.2e+09?"});
  // Grains lighter than the dry soil leave no pores: refused, with the hint.
  std::string grams = saturated("");
  grams.replace(grams.find("grain_density = 2650.0"), 22, "grain_density = 2.65");
  try {
    read_case_text(grams, "case.toml");
    ADD_FAILURE() << "grain_density = 2.65 accepted";
  } catch (const CaseError& e) {
    const std::string error = e.what();
    EXPECT_EQ(error.rfind("case.toml:24: materials.sand.grain_density: ", 0), 0u) << error;
    EXPECT_NE(error.find("did you mean 2650 (g/cm^3 given)?"), std::string::npos) << error;
  }
  expect_one_warning(gdp_edited("density = 1656.25",
                                "density = 1656.25\ndrainage = \"coupled\"\n"
                                "hydraulic_conductivity = 100.0\ngrain_density = 2650.0"),
                     "case.toml:23: materials.sand.hydraulic_conductivity: ",
                     {"is above any soil's", "did you mean 100 cm/s = 1 or mm/s = 0.1 m/s?"});
}

TEST(CaseWarnings, AModelRefusingASlippedUnitBlamesItsKeyWithTheHint) {
  // Hardening Soil fits its cap to k0_nc and eoed_ref; with phi in radians or E50 in kPa no cap
  // fits and the model refuses the set as a whole. The key of the likely slip is named.
  const auto error_of = [](const std::string& text) {
    try {
      read_case_text(text, "case.toml");
    } catch (const CaseError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  std::string error = error_of(gdp_edited("friction_angle = 37.5", "friction_angle = 0.6545"));
  EXPECT_EQ(error.rfind("case.toml:19: materials.sand.friction_angle: hardening_soil: ", 0), 0u)
      << error;
  EXPECT_NE(error.find("did you mean 0.6545 rad = 37.5 degrees?"), std::string::npos) << error;
  error = error_of(gdp_edited("e50_ref = 44e6", "e50_ref = 44e3"));
  EXPECT_EQ(error.rfind("case.toml:", 0), 0u) << error;
  EXPECT_NE(error.find("materials.sand.e50_ref: hardening_soil: "), std::string::npos) << error;
  EXPECT_NE(error.find("did you mean 44000 kPa = 4.4e+07?"), std::string::npos) << error;
}

TEST(CaseWarnings, AFrictionCoefficientGivenAsAnAngle) {
  expect_one_warning(
      gdp_edited("friction = 0.4", "friction = 21.8"), "case.toml:38: monopile.friction: ",
      {"friction = 21.8 is a coefficient mu = tan(delta)", "did you mean tan(21.8 deg) = 0.40?"});
}

TEST(CaseWarnings, AContactFrictionGivenAsAnAngle) {
  const CaseSpec spec =
      read_case_file((source / "cases/verification/v7_block_on_incline.toml").string(),
                     {"contact.0.friction=21.8"});
  ASSERT_EQ(spec.warnings.size(), 1u);
  EXPECT_NE(
      spec.warnings[0].text.find("friction = 21.8 is a coefficient mu = tan(delta), above any "
                                 "soil on steel or soil (0 to 1.2): did you mean tan(21.8 "
                                 "deg) = 0.40?"),
      std::string::npos)
      << spec.warnings[0].text;
}

TEST(CaseWarnings, ADensityInGramsPerCubicCentimetre) {
  expect_one_warning(gdp_edited("density = 1656.25", "density = 1.65625"),
                     "case.toml:21: materials.sand.density: ",
                     {"density = 1.65625 kg/m^3 is lighter than any soil or steel",
                      "did you mean 1656.25 (g/cm^3 given)?"});
  // A unit weight in kN/m^3 is named as well.
  expect_one_warning(gdp_edited("density = 1656.25", "density = 16.25"), "case.toml",
                     {"or 1656 (a unit weight in kN/m^3 given)?"});
}

TEST(CaseWarnings, AReferencePressureInKilopascals) {
  expect_one_warning(gdp_edited("p_ref = 100e3", "p_ref = 100"),
                     "case.toml:18: materials.sand.p_ref: ",
                     {"p_ref = 100 Pa is far below the 100 kPa taken by convention (Schanz et al. "
                      "1999): did you mean 100 kPa = 100000?"});
}

TEST(CaseWarnings, GravityPointingUp) {
  expect_one_warning(gdp_edited("gravity = [0.0, -9.81]", "gravity = [0.0, 9.81]"),
                     "case.toml:53: solver.gravity: ",
                     {"gravity points up (g_y = 9.81 > 0; y is up): did you mean [0, -9.81]?"});
  expect_one_warning(gdp_edited("gravity = [0.0, -9.81]", "gravity = [0.0, -9810.0]"),
                     "case.toml:53: solver.gravity: ", {"did you mean 9.81 (mm/s^2 given)?"});
}

TEST(CaseWarnings, AModulusInKilopascals) {
  expect_one_warning(
      gdp_edited("young_modulus = 220e9", "young_modulus = 2e3"),
      "case.toml:25: materials.steel.young_modulus: ",
      {"young_modulus = 2000 Pa is below any soil's", "did you mean 2000 kPa = 2e+06?"});
}

TEST(CaseWarnings, AFrictionAngleInRadians) {
  // On a Mohr-Coulomb pile material (Hardening Soil refuses the sand's k0_nc with phi in radians).
  expect_one_warning(gdp_edited("type = \"linear_elastic\"",
                                "type = \"mohr_coulomb\"\ncohesion = 0.0\nfriction_angle = 0.6545"),
                     "case.toml:26: materials.steel.friction_angle: ",
                     {"did you mean 0.6545 rad = 37.5 degrees?"});
}

TEST(CaseWarnings, AScaledMaterialIsNotJudged) {
  // The verification cases' bar: E = 100 Pa and rho = 1 kg/m^3, units of its own.
  const CaseSpec spec = read_case_file((source / "cases/verification/single_point.toml").string());
  EXPECT_TRUE(spec.warnings.empty());
}

/// A case file written for the command tests: the GDP case with its sand's density in g/cm^3.
std::filesystem::path density_in_grams(const std::string& name) {
  const auto directory = std::filesystem::temp_directory_path() / name;
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  const auto path = directory / "case.toml";
  std::ofstream(path) << gdp_edited("density = 1656.25", "density = 1.65625");
  return path;
}

TEST(CaseWarnings, CheckPrintsThemAndStrictRefusesWithStatusTwo) {
  const auto path = density_in_grams("mpile_warnings_check");
  RunOptions options;
  options.case_path = path.string();
  std::ostringstream out, err;
  ASSERT_EQ(check_case(options, out, err), exit_success) << err.str();
  EXPECT_NE(err.str().find("mpile: warning: " + path.string() + ":21: materials.sand.density: "),
            std::string::npos)
      << err.str();
  options.strict = true;
  std::ostringstream strict_out, strict_err;
  EXPECT_EQ(check_case(options, strict_out, strict_err), exit_bad_input);
  EXPECT_NE(strict_err.str().find("mpile: error (--strict): " + path.string() + ":21:"),
            std::string::npos)
      << strict_err.str();
}

TEST(CaseWarnings, StrictRefusesARunBeforeAnythingIsWritten) {
  const auto path = density_in_grams("mpile_warnings_run");
  RunOptions options;
  options.case_path = path.string();
  options.output_directory = (path.parent_path() / "out").string();
  options.strict = true;
  std::ostringstream out, err;
  EXPECT_EQ(run_case(options, out, err), exit_bad_input);
  EXPECT_NE(err.str().find("materials.sand.density"), std::string::npos) << err.str();
  EXPECT_FALSE(std::filesystem::exists(path.parent_path() / "out"));
}

TEST(CaseWarnings, ARunWritesThemToItsLog) {
  const auto path = density_in_grams("mpile_warnings_log");
  RunOptions options;
  options.case_path = path.string();
  options.output_directory = (path.parent_path() / "out").string();
  options.stop_after_steps = 1;
  std::ostringstream out, err;
  ASSERT_EQ(run_case(options, out, err), exit_interrupted) << err.str();
  EXPECT_NE(err.str().find("mpile: warning: " + path.string() + ":21: materials.sand.density"),
            std::string::npos)
      << err.str();
  const std::string log = read_text(path.parent_path() / "out" / "run.log");
  EXPECT_NE(log.find("mpile: warning: " + path.string() + ":21: materials.sand.density"),
            std::string::npos)
      << log;
}

// The deliberately extreme cases of cases/stability/ are left out: they push values to the edge
// on purpose.
TEST(CaseWarnings, NoShippedCaseHasOne) {
  int files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(source / "cases")) {
    const std::string folder = entry.path().parent_path().filename().string();
    if (entry.path().extension() != ".toml" || folder == "element_tests" || folder == "sweeps" ||
        folder == "base" || folder == "stability") {
      continue;
    }
    ++files;
    const CaseSpec spec = read_case_file(entry.path().string());
    for (const CaseWarning& w : spec.warnings) {
      EXPECT_NE(w.kind, CaseWarning::Kind::units) << w.text;
    }
  }
  EXPECT_GE(files, 20);
}

TEST(CaseWarnings, AOneCellWallIsANoteThatStrictLetsPass) {
  for (const char* name : {"jacked_quick", "gdp_quick", "impact_paper", "gdp829_paper"}) {
    const CaseSpec spec =
        read_case_file((source / "cases/monopile" / (std::string(name) + ".toml")).string());
    ASSERT_EQ(spec.warnings.size(), 1u) << name;
    EXPECT_EQ(spec.warnings[0].kind, CaseWarning::Kind::resolution);
    EXPECT_NE(spec.warnings[0].text.find("monopile.wall_cells: the wall is one cell wide: tip and "
                                         "shaft forces depend on where the grid lines fall"),
              std::string::npos)
        << spec.warnings[0].text;
  }
  // As the resolution study sets it (cases/sweeps/jacked_resolution.toml).
  const CaseSpec resolved = read_case_file((source / "cases/monopile/jacked_quick.toml").string(),
                                           {"monopile.band_below=0.5", "monopile.band_above=0.5",
                                            "monopile.travel=0.4", "monopile.wall_cells=3"});
  EXPECT_TRUE(resolved.warnings.empty());

  RunOptions options;
  options.case_path = (source / "cases/monopile/jacked_quick.toml").string();
  options.strict = true;
  std::ostringstream out, err;
  EXPECT_EQ(check_case(options, out, err), exit_success) << err.str();
  EXPECT_NE(err.str().find("mpile: note: "), std::string::npos) << err.str();
  EXPECT_EQ(err.str().find("--strict"), std::string::npos) << err.str();
}

// Saturated soil under pure FLIP gets a note (never an error) at its drainage key; with XPIC(2),
// a FLIP/PIC blend or the implicit pore pressure with the cell-mean one, none.
TEST(CaseWarnings, SaturatedSoilUnderPureFlipIsNoted) {
  const std::string column =
      replaced(read_text(source / "cases/verification/absorbing_column.toml"), "density = 2000.0",
               "density = 2000.0\ndrainage = \"undrained\"");
  const auto notes = [](const std::string& text) {
    std::string found;
    for (const CaseWarning& w : read_case_text(text, "case.toml").warnings) {
      if (w.kind == CaseWarning::Kind::resolution &&
          w.text.find("pure FLIP") != std::string::npos) {
        found += w.text + "\n";
      }
    }
    return found;
  };
  const auto at = column.find("drainage =");
  const auto line = 1 + std::count(column.begin(), column.begin() + static_cast<long>(at), '\n');
  EXPECT_EQ(
      notes(column).rfind("case.toml:" + std::to_string(line) + ": materials.soil.drainage: ", 0),
      0u)
      << notes(column);
  EXPECT_EQ(notes(column + "[solver]\nxpic_order = 2\n"), "");
  EXPECT_EQ(notes(column + "[solver]\nflip_fraction = 0.99\n"), "");
  // The implicit pore pressure with one excess pore pressure per cell: no note; either alone:
  // the note.
  const std::string wave = saturated_wave_column("drainage = \"undrained\"");
  EXPECT_NE(notes(wave), "");
  EXPECT_NE(notes(wave + "[solver]\nimplicit_pore_pressure = true\n"), "");
  EXPECT_NE(notes(wave + "[solver]\ncell_mean_pore_pressure = true\n"), "");
  EXPECT_EQ(
      notes(wave + "[solver]\nimplicit_pore_pressure = true\ncell_mean_pore_pressure = true\n"),
      "");
}

// A drained face lets the water out at p = 0 beyond it: under gravity a hydrostatic column drains
// through it (measured: 6 mm/s of outflow at the base of a 5 m column, k = 1e-3 m/s), which the
// reader notes at the key; without gravity it is the consolidation tests' boundary, and no note.
TEST(CaseWarnings, ADrainedFaceUnderGravityIsNoted) {
  const std::string column = replaced(
      saturated_column(5.0, 20, 0.2,
                       "type = \"linear_elastic\"\nyoung_modulus = 50e6\npoisson_ratio = 0.3\n"
                       "density = 1600.0\ndrainage = \"coupled\"\nhydraulic_conductivity = 1e-3\n"),
      "y_min = \"fixed\"\n", "y_min = \"fixed\"\ndrained = [\"y_min\"]\n");
  const auto notes = [](const std::string& text) {
    std::string found;
    for (const CaseWarning& w : read_case_text(text, "case.toml").warnings) {
      if (w.text.find("a drained face has p = 0") != std::string::npos) {
        found += w.text + "\n";
      }
    }
    return found;
  };
  EXPECT_EQ(notes(replaced(column, "gravity = [0.0, -9.81]", "gravity = [0.0, 0.0]")), "");
  // Drained into the far field's water, the face holds the column's water at rest: no note.
  EXPECT_EQ(notes(replaced(column, "drained = [\"y_min\"]\n",
                           "drained = [\"y_min\"]\ndrained_pressure = \"hydrostatic\"\n")),
            "");
  const auto at = column.find("drained =");
  const auto line = 1 + std::count(column.begin(), column.begin() + static_cast<long>(at), '\n');
  EXPECT_EQ(notes(column).rfind("case.toml:" + std::to_string(line) + ": boundaries.drained: ", 0),
            0u)
      << notes(column);
}

// Dry sand resting on saturated sand (a water table inside the soil) without [water] table: the K0
// procedure would start the saturated body's water and vertical stress from its own k0 surface
// without the dry layer's weight. The same column split at 3 m into a dry top and a saturated
// bottom is noted at the dry body's material; the column saturated whole, or dry whole, is not,
// nor the split column with the table given (Sea.AWaterTableInsideTheSoil... checks its start),
// nor a rigid body resting on the saturated sand (a pile: it carries no K0 state).
TEST(CaseWarnings, DrySoilOnSaturatedSoilWithoutAWaterTableIsNoted) {
  const std::string saturated =
      "type = \"linear_elastic\"\nyoung_modulus = 50e6\npoisson_ratio = 0.3\n"
      "density = 1600.0\ndrainage = \"coupled\"\nhydraulic_conductivity = 1e-3\n";
  const std::string column = saturated_column(5.0, 20, 0.2, saturated);
  std::string split = replaced(column, "region = { r = [0.0, 0.5], y = [0.0, 5] }",
                               "region = { r = [0.0, 0.5], y = [0.0, 3.0] }\n[[bodies]]\n"
                               "name = \"crust\"\nmaterial = \"dry\"\n"
                               "region = { r = [0.0, 0.5], y = [3.0, 5.0] }");
  split = replaced(split, "[[bodies]]\nname = \"column\"",
                   "[materials.dry]\ntype = \"linear_elastic\"\nyoung_modulus = 50e6\n"
                   "poisson_ratio = 0.3\ndensity = 1600.0\n[[bodies]]\nname = \"column\"");
  split = replaced(split, "k0 = [{ body = \"column\", surface = 5, k0 = 0.5 }]",
                   "k0 = [{ body = \"column\", surface = 3.0, k0 = 0.5 }, "
                   "{ body = \"crust\", surface = 5.0, k0 = 0.5 }]");
  const auto notes = [](const std::string& text) {
    std::string found;
    for (const CaseWarning& w : read_case_text(text, "case.toml").warnings) {
      if (w.text.find("without [water] table the K0 procedure") != std::string::npos) {
        found += w.text + "\n";
      }
    }
    return found;
  };
  const std::string noted = notes(split);
  EXPECT_NE(noted.find(": bodies[1].material: dry 'dry' rests on saturated 'sand' (body 'column')"),
            std::string::npos)
      << noted;
  EXPECT_EQ(notes(column), "");
  EXPECT_EQ(notes(replaced(split, "material = \"dry\"", "material = \"sand\"")), "");
  EXPECT_EQ(notes(split + "[water]\ntable = 3.0\n"), "");
  std::string pile = replaced(split, "region = { r = [0.0, 0.5], y = [3.0, 5.0] }",
                              "region = { r = [0.0, 0.1], y = [3.0, 5.0] }\n[bodies.rigid]\n"
                              "mass = 100.0");
  pile = replaced(pile, ", { body = \"crust\", surface = 5.0, k0 = 0.5 }", "");
  EXPECT_EQ(notes(pile + "[[contact]]\nstructure = \"crust\"\n"), "");
}

} // namespace
} // namespace mpile
