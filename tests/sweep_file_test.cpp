// Sweep files: the variants they expand to, the values --set receives, and bad inputs refused
// with the file, line and key before anything runs.
#include "app/sweep_command.hpp"
#include "cases/case_error.hpp"
#include "cases/sweep_file.hpp"
#include "tests/case_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

namespace mpile {
namespace {

// A sweep of the shipped single-point case (V2), written beside a copy of it.
std::string write_sweep(const std::string& name, const std::string& text) {
  const auto directory = fresh_directory("sweep_file_" + name);
  std::filesystem::copy_file(source / "cases/verification/single_point.toml",
                             directory / "point.toml");
  const auto path = directory / "sweep.toml";
  std::ofstream(path) << text;
  return path.string();
}

const char* good = R"(title = "point"
case = "point.toml"
set = ["phases.0.duration=0.5"]
[parameters]
"materials.spring.young_modulus" = { from = 1.0, to = 100.0, count = 3, scale = "log" }
"bodies.0.velocity" = [[0.1, 0.0, 0.0], [0.3, 0.0, 0.0]]
"solver.courant_number" = [0.1]
[[gather]]
name = "kinetic_start"
series = "energy/kinetic"
at_time = 0.0
)";

TEST(SweepFile, ExpandsTheProductWithTheFirstParameterSlowest) {
  const SweepSpec sweep = read_sweep_file(write_sweep("good", good));
  ASSERT_EQ(sweep.variants.size(), 6u); // 3 x 2 x 1
  EXPECT_EQ(sweep.variants.front().id, "v01");
  EXPECT_EQ(sweep.variants.back().id, "v06");
  // A log range of 3 from 1 to 100: 1, 10, 100; its ends exactly as written.
  EXPECT_EQ(sweep.parameters[0].values, (std::vector<std::string>{"1.0", "10.0", "100.0"}));
  // The fixed --set first, then the parameters in the file's order; floats in their shortest form
  // that reads back exactly (0.1, not 0.10000000000000001).
  EXPECT_EQ(
      sweep.variants[1].sets,
      (std::vector<std::string>{"phases.0.duration=0.5", "materials.spring.young_modulus=1.0",
                                "bodies.0.velocity=[0.3, 0.0, 0.0]", "solver.courant_number=0.1"}));
  EXPECT_EQ(sweep.variants[2].values[0], "10.0");
  EXPECT_NO_THROW(validate_sweep(sweep));
}

// Each bad sweep file and the start of the message it must give after the file name.
struct BadSweep {
  const char* what;
  std::string from;
  std::string to;
  std::string message;
};

TEST(SweepFile, BadInputsAreRefusedWithFileLineAndKey) {
  const std::vector<BadSweep> bad = {
      {"no case", "case = \"point.toml\"\n", "", ":1: case: missing (required)"},
      {"a NUL in the case's path", "case = \"point.toml\"", "case = \"point.toml\\u0000x\"",
       ":2: case: a path cannot hold a NUL character (\\u0000)"},
      {"an unknown key", "title = \"point\"", "title = \"point\"\ncores = 2",
       ":2: cores: unknown key"},
      {"set not a list", "set = [\"phases.0.duration=0.5\"]", "set = \"x=1\"",
       ":3: set: expected an array of \"key.path=value\" strings"},
      {"set without =", "set = [\"phases.0.duration=0.5\"]", "set = [\"phases\"]",
       ":3: set: expected an array"},
      {"an empty list", "\"solver.courant_number\" = [0.1]", "\"solver.courant_number\" = []",
       ":7: parameters.\"solver.courant_number\": the list of values is empty"},
      {"a value that is not a list", "\"solver.courant_number\" = [0.1]",
       "\"solver.courant_number\" = 0.1",
       ":7: parameters.\"solver.courant_number\": expected a list of values or a range"},
      {"a key path with a gap", "\"solver.courant_number\"", "\"solver..courant_number\"",
       ":7: parameters.\"solver..courant_number\": not a key path"},
      {"a range of one", "count = 3", "count = 1",
       ":5: parameters.materials.spring.young_modulus.count: must be from 2 to 10000"},
      {"a log range through zero", "from = 1.0", "from = 0.0",
       ":5: parameters.materials.spring.young_modulus.from: a log range needs from and to above "
       "zero"},
      {"an unknown scale", "scale = \"log\"", "scale = \"cubic\"",
       ":5: parameters.materials.spring.young_modulus.scale: must be \"linear\" or \"log\""},
      {"a range key misspelt", "count = 3", "cuont = 3",
       ":5: parameters.materials.spring.young_modulus.cuont: unknown key; did you mean 'count'?"},
      {"too many variants", "count = 3", "count = 10000",
       ":4: parameters: the values make more than 10000 variants"},
      {"a gather with two ways", "at_time = 0.0", "at_time = 0.0\nreduce = \"max\"",
       ":10: gather[0].series: give exactly one of at_penetration, at_time or reduce"},
      {"a gather with none", "at_time = 0.0\n", "",
       ":10: gather[0].series: give exactly one of at_penetration, at_time or reduce"},
      {"an unknown reduction", "at_time = 0.0", "reduce = \"median\"",
       ":11: gather[0].reduce: must be last, max, min, mean or max_abs"},
      {"a name with a space", "name = \"kinetic_start\"", "name = \"kinetic start\"",
       ":9: gather[0].name: \"kinetic start\" cannot name a column"},
      // results.nc is HDF5: '/' separates its groups, and the gathering died after every
      // variant had run.
      {"a name with a slash", "name = \"kinetic_start\"", "name = \"tip/F_y\"",
       ":9: gather[0].name: \"tip/F_y\" cannot name a column"},
      {"a name starting with a dot", "name = \"kinetic_start\"", "name = \".kinetic\"",
       ":9: gather[0].name: \".kinetic\" cannot name a column"},
      {"a name every table has", "name = \"kinetic_start\"", "name = \"status\"",
       ":9: gather[0].name: \"status\" is a column of every sweep's table already"},
      {"at_penetration without a body", "at_time = 0.0", "at_penetration = 0.1",
       ":8: gather[0].body: missing (required): (the rigid body"},
      {"a series with a leading slash", "series = \"energy/kinetic\"", "series = \"/energy\"",
       ":10: gather[0].series: a path in history.h5"},
      {"a phase without reduce", "at_time = 0.0", "at_time = 0.0\nphase = \"vibrate\"",
       ":12: gather[0].phase: only reduce takes a phase"},
      {"a negative time", "at_time = 0.0", "at_time = -1.0",
       ":11: gather[0].at_time: must be a time from zero on, s"},
      {"a penetration of nan", "at_time = 0.0", "at_penetration = nan\nbody = \"pile\"",
       ":11: gather[0].at_penetration: must be a finite number"},
      {"a penetration of zero", "at_time = 0.0", "at_penetration = 0.0\nbody = \"pile\"",
       ":11: gather[0].at_penetration: must be a penetration above zero, m"},
      {"threads zero", "title = \"point\"", "title = \"point\"\nthreads = 0",
       ":2: threads: threads per run must be from 1 to 1024"},
      // A value listed twice ran its variants twice, and a key both swept and set took whichever
      // was applied last.
      {"a value twice", "\"solver.courant_number\" = [0.1]",
       "\"solver.courant_number\" = [0.1, 0.2, 0.1]",
       ":7: parameters.\"solver.courant_number\": the value 0.1 is listed twice: its variants "
       "would run twice"},
      // Its ratio past the largest double: refused as a variant's inf, not at the range.
      {"a log range overflowing", "from = 1.0, to = 100.0, count = 3",
       "from = 1e-300, to = 1e300, count = 3",
       ":5: parameters.materials.spring.young_modulus.to: the range from 1e-300 to 1e+300 "
       "overflows between its ends"},
      // One value written two ways ran identical variants under two labels.
      {"a value twice in two spellings", "\"solver.courant_number\" = [0.1]",
       "\"solver.courant_number\" = [1, 0.5, 1.0]",
       ":7: parameters.\"solver.courant_number\": the value 1.0 is listed twice (as 1): its "
       "variants would run twice"},
      {"a vector twice, zero signed", "\"bodies.0.velocity\" = [[0.1, 0.0, 0.0], [0.3, 0.0, 0.0]]",
       "\"bodies.0.velocity\" = [[0.1, 0.0, 0.0], [0.1, -0.0, 0.0]]",
       ":6: parameters.\"bodies.0.velocity\": the value [0.1, -0.0, 0.0] is listed twice (as "
       "[0.1, 0.0, 0.0]): its variants would run twice"},
      {"a swept key also set", "\"solver.courant_number\" = [0.1]",
       "\"phases.0\" = [{ name = \"a\", duration = 0.1 }]",
       ":7: parameters.\"phases.0\": overlaps set's \"phases.0.duration=0.5\": a swept key is not "
       "also set for every variant"},
  };
  for (const BadSweep& b : bad) {
    const std::string text = replaced(good, b.from, b.to);
    const std::string path = write_sweep("bad", text);
    try {
      read_sweep_file(path);
      ADD_FAILURE() << b.what << ": accepted";
    } catch (const CaseError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(path + b.message, 0), 0u) << b.what << ": " << e.what();
    }
  }
}

TEST(SweepFile, TwoParametersSweepingOneKeyAreRefused) {
  // bodies.0.velocity and one of its components: whichever the reader meets second is named.
  const std::string path =
      write_sweep("overlap", replaced(good, "\"solver.courant_number\" = [0.1]",
                                      "\"bodies.0.velocity.1\" = [0.0, -0.1]"));
  try {
    read_sweep_file(path);
    ADD_FAILURE() << "accepted";
  } catch (const CaseError& e) {
    const std::string error = e.what();
    EXPECT_NE(error.find(": overlaps the parameter \"bodies.0.velocity"), std::string::npos)
        << error;
    EXPECT_NE(error.find("a key is swept by one entry only"), std::string::npos) << error;
  }
}

TEST(SweepFile, OneKeyWrittenTwoWaysIsOneKey) {
  // V2's phase 0 is "vibrate": phases.vibrate.duration and phases.0.duration (or phases.00) set
  // one value, so variants labelled 2.0 ran 1.0 and the table mislabelled them. The reader alone
  // cannot know the names; the sweep's check against the case refuses them at the later line.
  const auto refused = [](const std::string& name, const std::string& from, const std::string& to,
                          const std::string& message) {
    const std::string path = write_sweep(name, replaced(good, from, to));
    const SweepSpec sweep = read_sweep_file(path);
    try {
      validate_sweep(sweep);
      ADD_FAILURE() << name << ": accepted";
    } catch (const CaseError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(path + message, 0), 0u) << name << ": " << e.what();
    }
  };
  refused("by_name", "\"solver.courant_number\" = [0.1]",
          "\"solver.courant_number\" = [0.1]\n\"phases.vibrate.duration\" = [1.0, 2.0]",
          ":8: parameters.\"phases.vibrate.duration\": overlaps set's \"phases.0.duration=0.5\": "
          "a swept key is not also set for every variant");
  const std::string unset = replaced(good, "set = [\"phases.0.duration=0.5\"]\n", "");
  for (const char* second : {"phases.00.duration", "phases.vibrate.duration"}) {
    const std::string path = write_sweep(
        "two_ways", replaced(unset, "\"solver.courant_number\" = [0.1]",
                             "\"solver.courant_number\" = [0.1]\n\"phases.0.duration\" = [1.0, "
                             "2.0]\n\"" +
                                 std::string(second) + "\" = [1.0, 3.0]"));
    try {
      validate_sweep(read_sweep_file(path));
      ADD_FAILURE() << second << ": accepted";
    } catch (const CaseError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(path + ":8: parameters.\"" + second +
                                                "\": overlaps the parameter \"phases.0.duration\": "
                                                "a key is swept by one entry only",
                                            0),
                0u)
          << e.what();
    }
  }
}

// A variant's implausible value is warned of before anything runs, naming the variants that have
// it; a warning of the case itself is every variant's; `mpile sweep --strict` refuses the sweep.
TEST(SweepFile, TheVariantsWarningsAreShownOnceWithTheVariantsAndStrictRefusesThem) {
  const auto directory = fresh_directory("sweep_file_warnings");
  const auto path = directory / "sweep.toml";
  std::ofstream(path) << "case = \"" << (source / "cases/monopile/gdp_quick.toml").string()
                      << "\"\n[parameters]\n\"monopile.friction\" = [0.4, 21.8, 0.3]\n";
  const std::vector<CaseWarning> warnings = validate_sweep(read_sweep_file(path.string()));
  std::string units, notes;
  for (const CaseWarning& w : warnings) {
    (w.kind == CaseWarning::Kind::units ? units : notes) += w.text + "\n";
  }
  EXPECT_NE(units.find("monopile.friction: friction = 21.8 is a coefficient mu = tan(delta)"),
            std::string::npos)
      << units;
  EXPECT_NE(units.find("did you mean tan(21.8 deg) = 0.40? [variant v02]\n"), std::string::npos)
      << units;
  EXPECT_EQ(std::count(units.begin(), units.end(), '\n'), 1) << units;
  // The quick case's one-cell wall is noted for all three.
  EXPECT_NE(notes.find("the wall is one cell wide"), std::string::npos) << notes;
  EXPECT_NE(notes.find("[every variant]\n"), std::string::npos) << notes;

  SweepOptions options;
  options.file = path.string();
  options.output_directory = (directory / "out").string();
  options.strict = true;
  std::ostringstream out, err;
  EXPECT_EQ(sweep_command(options, out, err), 2) << err.str();
  EXPECT_NE(err.str().find("mpile: error (--strict): "), std::string::npos) << err.str();
  EXPECT_FALSE(std::filesystem::exists(directory / "out")); // refused before anything is written
}

// A directory another sweep is running in (Snakemake's lock present) is named with what to do, and
// nothing of the running workflow is rewritten.
TEST(SweepFile, ASweepIntoABusyDirectoryIsRefusedBeforeItRewritesTheWorkflow) {
  const std::string path = write_sweep("busy", good);
  const auto directory = std::filesystem::path(path).parent_path() / "out";
  std::filesystem::create_directories(directory / ".snakemake" / "locks");
  std::ofstream(directory / ".snakemake" / "locks" / "0.input.lock") << "variants/v01/finished\n";
  std::ofstream(directory / "Snakefile") << "# the running sweep's\n";
  SweepOptions options;
  options.file = path;
  options.output_directory = directory.string();
  std::ostringstream out, err;
  EXPECT_EQ(sweep_command(options, out, err), 1);
  EXPECT_NE(err.str().find(": another sweep is running in this directory (Snakemake's lock in "
                           ".snakemake/locks); wait for it to end, or"),
            std::string::npos)
      << err.str();
  EXPECT_NE(err.str().find(" --unlock\n"), std::string::npos) << err.str();
  EXPECT_EQ(read_text(directory / "Snakefile"), "# the running sweep's\n");
}

TEST(SweepFile, AVariantTheCaseRefusesNamesTheParameterLineAndItsValues) {
  // The case file is read with each variant's --set values before anything runs: a key the case
  // does not have, or a value it refuses, names the sweep file's line and the variant.
  const std::vector<BadSweep> bad = {
      {"an unknown key path", "\"solver.courant_number\"", "\"solver.courant_numbr\"",
       ":7: parameters.\"solver.courant_numbr\": variant v01 "},
      {"a value out of range", "[[0.1, 0.0, 0.0], [0.3, 0.0, 0.0]]", "[[0.1, 0.0, 0.0], [0.3]]",
       ":6: parameters.\"bodies.0.velocity\": variant v02 (materials.spring.young_modulus = 1.0, "
       "bodies.0.velocity = [0.3], solver.courant_number = 0.1) cannot run: "},
      {"a case file that is not there", "case = \"point.toml\"", "case = \"nothing.toml\"",
       ":5: parameters.\"materials.spring.young_modulus\": variant v01 "},
      {"a gathered phase the case lacks", "at_time = 0.0", "reduce = \"max\"\nphase = \"shake\"",
       ":9: gather[0].phase: the case "},
  };
  for (const BadSweep& b : bad) {
    const std::string path = write_sweep("variant", replaced(good, b.from, b.to));
    try {
      validate_sweep(read_sweep_file(path));
      ADD_FAILURE() << b.what << ": accepted";
    } catch (const CaseError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(path + b.message, 0), 0u) << b.what << ": " << e.what();
    }
  }
}

} // namespace
} // namespace mpile
