// Case composition: a base file under the case, --set values on top, and what a restart may change.
#include "app/run_command.hpp"
#include "cases/case_composition.hpp"
#include "cases/case_spec.hpp"
#include "tests/case_run.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace mpile {
namespace {

// A base with everything but the phases and outputs, as the monopile cases share one.
const char* base_text = R"(title = "column base"
[grid]
r = [{ start = 0.0, end = 1.0, cells = 4 }]
y = [{ start = 0.0, end = 1.0, cells = 4 }]
[materials.soil]
type = "linear_elastic"
young_modulus = 2e6
poisson_ratio = 0.3
density = 1800.0
[[bodies]]
name = "column"
material = "soil"
region = { r = [0.0, 1.0], y = [0.0, 1.0] }
[boundaries]
y_min = "fixed"
[solver]
gravity = [0.0, -9.81]
[[phases]]
name = "settle"
duration = 0.1
)";

// The case: its own title and one material parameter over the base's, its own phases.
const char* case_text = R"(base = "shared/base.toml"
title = "column"
[materials.soil]
young_modulus = 4e6
[[phases]]
name = "settle"
duration = 0.2
[[phases]]
name = "rest"
duration = 0.05
)";

// The same case written out in full: what the composition must read as.
const char* flat_text = R"(title = "column"
[grid]
r = [{ start = 0.0, end = 1.0, cells = 4 }]
y = [{ start = 0.0, end = 1.0, cells = 4 }]
[materials.soil]
type = "linear_elastic"
young_modulus = 4e6
poisson_ratio = 0.3
density = 1800.0
[[bodies]]
name = "column"
material = "soil"
region = { r = [0.0, 1.0], y = [0.0, 1.0] }
[boundaries]
y_min = "fixed"
[solver]
gravity = [0.0, -9.81]
[[phases]]
name = "settle"
duration = 0.2
[[phases]]
name = "rest"
duration = 0.05
)";

struct Files {
  std::filesystem::path directory, base, case_file;
};

Files write_files(const std::string& name, const std::string& base = base_text,
                  const std::string& top = case_text) {
  Files f;
  f.directory = fresh_directory(name);
  std::filesystem::create_directories(f.directory / "shared");
  f.base = f.directory / "shared" / "base.toml";
  f.case_file = f.directory / "case.toml";
  std::ofstream(f.base) << base;
  std::ofstream(f.case_file) << top;
  return f;
}

std::string composition_error_of(const std::string& path,
                                 const std::vector<std::string>& overrides = {}) {
  try {
    read_case_file(path, overrides);
  } catch (const CaseError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(CaseComposition, ABaseMergesUnderTheCaseTableByTableAndArraysAreReplaced) {
  const Files f = write_files("merge");
  const CaseSpec spec = read_case_file(f.case_file.string());
  const CaseSpec flat = read_case_text(flat_text, "flat.toml");
  // Equal trees format to equal text (keys sorted), so the composed case is the flat one exactly.
  EXPECT_EQ(spec.resolved, flat.resolved);
  EXPECT_EQ(spec.title, "column");
  EXPECT_EQ(spec.materials.at(0).parameters.at("young_modulus"), 4e6);
  EXPECT_EQ(spec.materials.at(0).parameters.at("density"), 1800.0); // from the base
  ASSERT_EQ(spec.phases.size(), 2u); // the case's [[phases]] replace the base's
  EXPECT_EQ(spec.phases[0].duration, 0.2);
  ASSERT_EQ(spec.bases.size(), 1u);
  EXPECT_TRUE(std::filesystem::equivalent(spec.bases[0], f.base));
  EXPECT_EQ(spec.text, case_text); // the case file's own text, for the record
}

TEST(CaseComposition, AnErrorInABaseValueNamesTheBaseFileAndLine) {
  const Files f =
      write_files("base_error", replaced(base_text, "poisson_ratio = 0.3", "poisson_ratio = 0.7"));
  const std::string error = composition_error_of(f.case_file.string());
  // Line 8 of the base holds poisson_ratio.
  EXPECT_EQ(
      error.rfind(f.base.lexically_normal().string() + ":8: materials.soil.poisson_ratio:", 0), 0u)
      << error;
  // The case that was read is named too: its own value may be the cause (a phase it renamed
  // that the base refers to).
  const std::string suffix = " (read as a base of " + f.case_file.string() + ")";
  ASSERT_GE(error.size(), suffix.size());
  EXPECT_EQ(error.substr(error.size() - suffix.size()), suffix) << error;
}

// A monopile over a base, as the shipped cases are written: the case overrides one key.
const char* monopile_base = R"(geometry = "axisymmetric"
[materials.sand]
type = "mohr_coulomb"
young_modulus = 20e6
poisson_ratio = 0.3
density = 1650.0
cohesion = 1e3
friction_angle = 30.0
dilatancy_angle = 20.0
[materials.steel]
type = "linear_elastic"
young_modulus = 210e9
poisson_ratio = 0.3
density = 7850.0
[monopile]
soil_width = 5.0
soil_material = "sand"
pile_material = "steel"
[[phases]]
name = "settle"
duration = 0.1
)";

// A check between keys refuses the key the case wrote, not the one its base gave: a diameter in
// mm is refused by soil_width's check (the pile wider than the soil), and was blamed on the base's
// soil_width; a friction angle below the base's dilatancy angle was blamed on dilatancy_angle.
TEST(CaseComposition, ACheckBetweenKeysNamesTheKeyTheCaseWrote) {
  const auto error_with = [](const std::string& name, const std::string& top,
                             const std::vector<std::string>& overrides = {}) {
    const Files f = write_files(name, monopile_base, "base = \"shared/base.toml\"\n" + top);
    return std::pair{composition_error_of(f.case_file.string(), overrides), f};
  };
  {
    const auto [error, f] = error_with("blame_diameter", "[monopile]\ndiameter = 746\n");
    EXPECT_EQ(error.rfind(f.case_file.string() + ":3: monopile.diameter: soil_width must exceed "
                                                 "the pile's outer radius",
                          0),
              0u)
        << error;
    // The other side of the check: its value and where the base wrote it.
    EXPECT_NE(error.find("(soil_width = 5.0 at " + f.base.lexically_normal().string() + ":16)"),
              std::string::npos)
        << error;
  }
  {
    const auto [error, f] = error_with("blame_diameter_set", "", {"monopile.diameter=746"});
    EXPECT_EQ(
        error.rfind("--set monopile.diameter:1: monopile.diameter: soil_width must exceed", 0), 0u)
        << error;
  }
  {
    // Both in the case: the check's own key, as before.
    const auto [error, f] =
        error_with("blame_soil_width", "[monopile]\ndiameter = 1.0\nsoil_width = 0.6\n");
    EXPECT_EQ(error.rfind(f.case_file.string() + ":4: monopile.soil_width: must exceed", 0), 0u)
        << error;
  }
  {
    const auto [error, f] =
        error_with("blame_friction_angle", "[materials.sand]\nfriction_angle = 10.0\n");
    EXPECT_EQ(error.rfind(f.case_file.string() +
                              ":3: materials.sand.friction_angle: mohr_coulomb: dilatancy_angle "
                              "must lie between 0 and friction_angle",
                          0),
              0u)
        << error;
    EXPECT_NE(
        error.find("(dilatancy_angle = 20.0 at " + f.base.lexically_normal().string() + ":9)"),
        std::string::npos)
        << error;
  }
  {
    // An angle in radians: the key with its hint.
    const auto [error, f] =
        error_with("blame_radians", "[materials.sand]\nfriction_angle = 0.65\n");
    EXPECT_EQ(error.rfind(f.case_file.string() + ":3: materials.sand.friction_angle: ", 0), 0u)
        << error;
    EXPECT_NE(error.find("did you mean 0.65 rad = 37.2 degrees?"), std::string::npos) << error;
  }
}

TEST(CaseComposition, BadBasesAreRefusedWithTheLineThatNamesThem) {
  Files f = write_files("missing_base", base_text, replaced(case_text, "shared/base", "nowhere"));
  std::string error = composition_error_of(f.case_file.string());
  EXPECT_EQ(error.rfind(f.case_file.string() + ":1: base: " +
                            (f.directory / "nowhere.toml").string() + ": cannot open the case file",
                        0),
            0u)
      << error;
  // An empty path names the case's own directory.
  f = write_files("empty_base", base_text, replaced(case_text, "shared/base.toml", ""));
  error = composition_error_of(f.case_file.string());
  EXPECT_EQ(error.rfind(f.case_file.string() + ":1: base: ", 0), 0u) << error;
  EXPECT_NE(error.find("is a directory, not a case file"), std::string::npos) << error;

  // A base that names the case again: a cycle.
  f = write_files("cycle", std::string("base = \"../case.toml\"\n") + base_text);
  error = composition_error_of(f.case_file.string());
  EXPECT_NE(error.find(":1: base: "), std::string::npos) << error;
  EXPECT_NE(error.find("is already in this chain of bases (a cycle)"), std::string::npos) << error;

  f = write_files("base_type", base_text, replaced(case_text, "\"shared/base.toml\"", "3"));
  EXPECT_EQ(composition_error_of(f.case_file.string()),
            f.case_file.string() +
                ":1: base: expected the path of a base case file (a string) or a list of them");
  f = write_files("base_empty_list", base_text, replaced(case_text, "\"shared/base.toml\"", "[]"));
  EXPECT_EQ(composition_error_of(f.case_file.string()),
            f.case_file.string() + ":1: base: the list of base files is empty");
  // The system reads a path up to a NUL: "shared/base.toml\u0000junk" read shared/base.toml.
  f = write_files("base_nul", base_text,
                  replaced(case_text, "\"shared/base.toml\"", "\"shared/base.toml\\u0000junk\""));
  EXPECT_EQ(composition_error_of(f.case_file.string()),
            f.case_file.string() + ":1: base: a path cannot hold a NUL character (\\u0000)");
}

// A second base, a sand of another model: a case takes a mesh from one base and a material from
// another, as the monopile cases take the seed's sand in hypoplasticity.
const char* sand_text = R"([materials.soil]
type = "mohr_coulomb"
young_modulus = 3e6
poisson_ratio = 0.25
friction_angle = 30.0
cohesion = 0.0
dilatancy_angle = 0.0
density = 1700.0
)";

TEST(CaseComposition, AListOfBasesMergesInOrderAndATableOfAnotherTypeReplacesTheBases) {
  Files f = write_files("base_list", base_text,
                        replaced(case_text, "base = \"shared/base.toml\"",
                                 "base = [\"shared/base.toml\", \"shared/sand.toml\"]"));
  std::ofstream(f.directory / "shared" / "sand.toml") << sand_text;
  const CaseSpec spec = read_case_file(f.case_file.string());
  // The sand's base replaces the soil's table whole (another type): none of the linear elastic
  // keys survive, so the strict reader accepts it; the case's young_modulus then merges over the
  // sand's (same type, key by key).
  const auto& soil = spec.materials.at(0);
  EXPECT_EQ(soil.type, "mohr_coulomb");
  EXPECT_EQ(soil.parameters.at("young_modulus"), 4e6);
  EXPECT_EQ(soil.parameters.at("density"), 1700.0);
  EXPECT_EQ(soil.parameters.at("friction_angle"), 30.0);
  EXPECT_EQ(spec.title, "column");
  ASSERT_EQ(spec.bases.size(), 2u);
  EXPECT_TRUE(std::filesystem::equivalent(spec.bases[1], f.directory / "shared" / "sand.toml"));
  // In the other order the mesh's linear elastic soil lies over the sand and replaces it.
  f = write_files("base_list_reversed", base_text,
                  replaced(case_text, "base = \"shared/base.toml\"",
                           "base = [\"shared/sand.toml\", \"shared/base.toml\"]"));
  std::ofstream(f.directory / "shared" / "sand.toml") << sand_text;
  EXPECT_EQ(read_case_file(f.case_file.string()).materials.at(0).type, "linear_elastic");
  // A file may appear in two branches (not a cycle), but not under itself.
  f = write_files("base_list_cycle",
                  std::string("base = [\"sand.toml\", \"../case.toml\"]\n") + base_text);
  std::ofstream(f.directory / "shared" / "sand.toml") << sand_text;
  EXPECT_NE(composition_error_of(f.case_file.string())
                .find("is already in this chain of bases (a cycle)"),
            std::string::npos)
      << composition_error_of(f.case_file.string());
}

TEST(CaseComposition, SetReplacesOneValueAnywhereAndIsRecorded) {
  const Files f = write_files("set");
  const std::vector<std::string> overrides{"materials.soil.density=2000", "phases.1.duration=0.5",
                                           "title=\"set from the command line\""};
  const CaseSpec spec = read_case_file(f.case_file.string(), overrides);
  EXPECT_EQ(spec.materials.at(0).parameters.at("density"), 2000.0);
  EXPECT_EQ(spec.phases.at(1).duration, 0.5);
  EXPECT_EQ(spec.phases.at(0).duration, 0.2);
  EXPECT_EQ(spec.title, "set from the command line");
  EXPECT_EQ(spec.overrides, overrides);
  // The record of what ran holds the values set, and only the case file's text is its own.
  EXPECT_NE(spec.resolved.find("density = 2000"), std::string::npos) << spec.resolved;
  EXPECT_EQ(spec.text, case_text);
  // A table made on the way: [output] is absent from both files.
  EXPECT_EQ(read_case_file(f.case_file.string(), {"output.history_interval=0.01"})
                .output.history_interval,
            0.01);
}

// An element of an array of tables by its name as well as by its index: phases.rest is phases.1;
// a name it does not have lists those it has and the nearest.
TEST(CaseComposition, SetTakesAnArrayElementByItsName) {
  const Files f = write_files("set_by_name");
  const CaseSpec spec = read_case_file(f.case_file.string(), {"phases.rest.duration=0.07"});
  EXPECT_EQ(spec.phases.at(1).duration, 0.07);
  EXPECT_EQ(spec.phases.at(0).duration, 0.2);
  EXPECT_EQ(composition_error_of(f.case_file.string(), {"phases.rst.duration=1"}),
            "--set phases.rst.duration=1: phases.rst: no element is named 'rst' (names: settle, "
            "rest); did you mean 'rest'?");
  EXPECT_EQ(composition_error_of(f.case_file.string(), {"phases.consolidation.duration=1"}),
            "--set phases.consolidation.duration=1: phases.consolidation: no element is named "
            "'consolidation' (names: settle, rest)");
}

TEST(CaseComposition, BadSetValuesAreRefusedNamingTheAssignment) {
  const Files f = write_files("set_errors");
  const std::string path = f.case_file.string();
  // An unknown key is caught by the strict reader, which names the --set it came from.
  EXPECT_EQ(composition_error_of(path, {"materials.soil.densty=2000"})
                .rfind("--set materials.soil.densty:1: materials.soil.densty: unknown key", 0),
            0u)
      << composition_error_of(path, {"materials.soil.densty=2000"});
  // A value of the wrong type too.
  EXPECT_EQ(
      composition_error_of(path, {"materials.soil.density=\"dense\""})
          .rfind("--set materials.soil.density:1: materials.soil.density: expected a number", 0),
      0u)
      << composition_error_of(path, {"materials.soil.density=\"dense\""});
  EXPECT_EQ(composition_error_of(path, {"materials.soil.density"}),
            "--set materials.soil.density: expected key.path=value");
  EXPECT_EQ(composition_error_of(path, {"materials..density=1"}),
            "--set materials..density=1: 'materials..density' is not a key path (keys joined by "
            "dots, like monopile.embedment)");
  EXPECT_EQ(composition_error_of(path, {"phases.2.duration=1"}),
            "--set phases.2.duration=1: phases.2: the array has 2 elements, numbered from 0");
  EXPECT_EQ(composition_error_of(path, {"title.text=1"}),
            "--set title.text=1: title is not a table");
  EXPECT_EQ(composition_error_of(path, {"base=\"other.toml\""}),
            "--set base=\"other.toml\": base is the file a case builds on; name it in the case "
            "file");
  // Text after a line break was parsed as keys of its own and dropped; a value over several
  // lines is still one value.
  EXPECT_EQ(composition_error_of(path, {"phases.0.duration=2.0\nphases = 3"}),
            "--set phases.0.duration: the value must be one TOML value; it goes on after a line "
            "break (give each assignment its own --set)");
  EXPECT_EQ(composition_error_of(path, {"phases.0.duration=2.0\n[solver]\ngravity = [0.0, 0.0]"}),
            composition_error_of(path, {"phases.0.duration=2.0\nphases = 3"}));
  EXPECT_EQ(composition_error_of(path, {"solver.gravity=[0.0,\n-9.81] # a comment\n"}), "accepted");
  // An element replaced by a non-table, and a table a --set path made, were blamed on the case
  // file's array and its first line.
  EXPECT_EQ(composition_error_of(path, {"phases.0=1"}),
            "--set phases.0:1: phases[0]: expected a table, found an integer");
  EXPECT_EQ(
      composition_error_of(path, {"output.monitor.0.name=\"x\""})
          .rfind("--set output.monitor.0.name:1: output.monitor: expected an array of tables", 0),
      0u)
      << composition_error_of(path, {"output.monitor.0.name=\"x\""});
  const std::string unquoted = composition_error_of(path, {"title=a column"});
  EXPECT_EQ(unquoted.rfind("--set title=a column: the value is not TOML (text needs quotes: "
                           "title=\"text\"):",
                           0),
            0u)
      << unquoted;
}

TEST(CaseComposition, ASetKeyOfMoreThanSixtyFourPartsIsRefused) {
  // 12 000 parts made 12 000 nested tables, and the program crashed (SIGSEGV) writing them out.
  const Files f = write_files("set_long_key");
  std::string key = "a";
  for (int k = 1; k < 12000; ++k) {
    key += ".a";
  }
  EXPECT_EQ(composition_error_of(f.case_file.string(), {key + "=1"}),
            "--set " + key.substr(0, 39) +
                "...: the key has 12000 parts; a dotted key has at "
                "most 64");
  RunOptions options;
  options.case_path = f.case_file.string();
  options.overrides = {key + "=1"};
  options.output_directory = (f.directory / "out").string();
  std::ostringstream out, err;
  EXPECT_EQ(run_case(options, out, err), exit_bad_input);
  EXPECT_EQ(err.str().find('\n'), err.str().size() - 1) << err.str(); // one line
  // 64 parts reach the reader, which names the unknown key.
  std::string fits = "a";
  for (int k = 1; k < 64; ++k) {
    fits += ".a";
  }
  EXPECT_NE(composition_error_of(f.case_file.string(), {fits + "=1"}).find("unknown key"),
            std::string::npos);
}

TEST(CaseComposition, DifferingKeysNameTheChangedValuesAndPhases) {
  const TomlValue before = parse_toml(flat_text, "a");
  const TomlValue after = parse_toml(
      replaced(replaced(flat_text, "duration = 0.05", "duration = 0.07"), "density = 1800.0\n", ""),
      "b");
  EXPECT_EQ(differing_keys(before, after),
            (std::vector<std::string>{"materials.soil.density", "phases.1.duration"}));
  const TomlValue more = parse_toml(std::string(flat_text) + "[[phases]]\nname = \"x\"\n"
                                                             "duration = 1.0\n",
                                    "c");
  EXPECT_EQ(differing_keys(before, more), (std::vector<std::string>{"phases.2"}));
  EXPECT_TRUE(differing_keys(before, before).empty());
}

TEST(CaseComposition, ARestartMayChangeOutputsAndEndCriteriaButNotPhysics) {
  const std::string before = read_case_text(flat_text, "a").resolved;
  const auto with = [&](const std::string& from, const std::string& to) {
    return read_case_text(replaced(flat_text, from, to), "b").resolved;
  };
  // Stopped in phase 1 ("rest"): its duration may change, and outputs.
  EXPECT_EQ(restart_changes(before, with("duration = 0.05", "duration = 0.5"), 1, "c.h5"),
            (std::vector<std::string>{"phases.1.duration"}));
  EXPECT_EQ(restart_changes(before,
                            with("title = \"column\"", "title = \"longer\"\n[output]\n"
                                                       "history_interval = 0.01"),
                            1, "c.h5"),
            (std::vector<std::string>{"title", "output"}));
  // Complete (phase = 2 of 2): the last phase may still be extended.
  EXPECT_EQ(restart_changes(before, with("duration = 0.05", "duration = 0.5"), 2, "c.h5").size(),
            1u);
  // Phase 0 has ended: its duration is history.
  EXPECT_THROW(restart_changes(before, with("duration = 0.2", "duration = 0.3"), 1, "c.h5"),
               CaseError);
  // Physics: refused with the key and both values.
  try {
    restart_changes(before, with("young_modulus = 4e6", "young_modulus = 5e6"), 1, "c.h5");
    FAIL() << "a changed Young's modulus was accepted";
  } catch (const CaseError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("c.h5: cannot continue with this case: "
                                          "materials.soil.young_modulus changed (was 4000000.0, "
                                          "now 5000000.0).",
                                          0),
              0u)
        << e.what();
  }
  // A phase's name (drives and loads name their phase) is not an end criterion.
  EXPECT_THROW(restart_changes(before, with("name = \"rest\"", "name = \"pause\""), 1, "c.h5"),
               CaseError);
  // Stopped in phase 0: phase 1 has not begun, so its settings and drive may change, not its name
  // or K0 (the seabed of a saturated body comes from the first K0 procedure it gets).
  const std::string damped = with("duration = 0.05", "duration = 0.05\nlocal_damping = 0.5");
  EXPECT_EQ(restart_changes(before, damped, 0, "c.h5"),
            (std::vector<std::string>{"phases.1.local_damping"}));
  EXPECT_EQ(restart_changes(before,
                            with("duration = 0.05", "duration = 0.05\nmass_scaling = 10.0\n"
                                                    "flip_fraction = 0.5"),
                            0, "c.h5")
                .size(),
            2u);
  EXPECT_THROW(restart_changes(before, with("name = \"rest\"", "name = \"pause\""), 0, "c.h5"),
               CaseError);
  EXPECT_THROW(restart_changes(before,
                               with("duration = 0.05", "duration = 0.05\nk0 = [{ body = "
                                                       "\"column\", surface = 1.0, k0 = 0.5 }]"),
                               0, "c.h5"),
               CaseError);
  // Once the phase has begun, its settings are part of the state.
  EXPECT_THROW(restart_changes(before, damped, 1, "c.h5"), CaseError);
  // Complete: no phase is left unbegun.
  EXPECT_THROW(restart_changes(before, damped, 2, "c.h5"), CaseError);
}

} // namespace
} // namespace mpile
