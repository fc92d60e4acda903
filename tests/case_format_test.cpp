// The case format's one declaration (cases/case_format.cpp): the reader takes defaults, ranges and
// choices from it, reading an undeclared key is caught, docs/case-format.md is generated from it.
#include "app/describe_command.hpp"
#include "cases/case_error.hpp"
#include "cases/case_format.hpp"
#include "cases/case_spec.hpp"
#include "cases/monopile_geometry.hpp"
#include "cases/toml_reader.hpp"
#include "engine/materials/material_registry.hpp"
#include "solver/solver_settings.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <variant>

namespace mpile {
namespace {

// A plane-strain block on a 2 x 2 grid: the smallest case the reader accepts.
const std::string block = R"(
geometry = "plane_strain"
[grid]
r = [{ start = 0.0, end = 1.0, cells = 2 }]
y = [{ start = 0.0, end = 1.0, cells = 2 }]
[materials.steel]
type = "linear_elastic"
young_modulus = 1e6
poisson_ratio = 0.3
density = 1000.0
[materials.wood]
type = "linear_elastic"
young_modulus = 1e6
poisson_ratio = 0.3
density = 1000.0
[[bodies]]
name = "soil"
material = "steel"
region = { r = [0.0, 1.0], y = [0.0, 0.5] }
[[bodies]]
name = "block"
material = "wood"
region = { r = [0.0, 1.0], y = [0.5, 1.0] }
[[phases]]
name = "run"
duration = 1e-3
)";

std::string format_error_of(const std::string& text) {
  try {
    read_case_text(text, "case.toml");
  } catch (const CaseError& e) {
    return e.what();
  }
  return "";
}

TEST(CaseFormat, EveryDefaultHasTheTypeOfItsKeyAndLiesInItsRange) {
  for (const TableSpec& t : case_format()) {
    for (const KeySpec& k : t.keys) {
      SCOPED_TRACE(t.path + "." + k.name);
      EXPECT_FALSE(k.meaning.empty());
      EXPECT_FALSE(k.required && !std::holds_alternative<std::monostate>(k.fallback));
      if (const double* x = std::get_if<double>(&k.fallback)) {
        EXPECT_EQ(k.kind, ValueKind::number);
        EXPECT_TRUE(k.range.contains(*x));
      }
      if (const long* x = std::get_if<long>(&k.fallback)) {
        EXPECT_EQ(k.kind, ValueKind::integer);
        EXPECT_TRUE(k.range.contains(static_cast<double>(*x)));
      }
      if (std::holds_alternative<bool>(k.fallback)) {
        EXPECT_EQ(k.kind, ValueKind::boolean);
      }
      if (const std::string* x = std::get_if<std::string>(&k.fallback)) {
        EXPECT_EQ(k.kind, ValueKind::string);
        if (!k.choices.empty()) {
          EXPECT_NE(std::find(k.choices.begin(), k.choices.end(), *x), k.choices.end());
        }
      }
      // Tables a key holds are declared under its path.
      if (k.kind == ValueKind::table || k.kind == ValueKind::tables) {
        EXPECT_NE(find_table_spec(t.path.empty() ? k.name : t.path + "." + k.name), nullptr);
      }
    }
  }
  for (const MaterialType& type : material_types()) {
    for (const MaterialParameterSpec& p : type.parameters) {
      SCOPED_TRACE(type.name + "." + p.name);
      EXPECT_FALSE(p.range.text().empty()) << "every material parameter declares its range";
      if (p.default_value) {
        EXPECT_TRUE(p.range.contains(*p.default_value));
      }
    }
  }
}

TEST(CaseFormat, TheReaderTakesTheDeclaredDefaults) {
  std::string text = block + "[[contact]]\nstructure = \"block\"\n";
  const CaseSpec spec = read_case_text(text, "case.toml");
  // [[contact]] friction and adhesion default to 0, [monopile]'s friction to the seed's 0.4: two
  // declarations, each read from cases/case_format.cpp.
  EXPECT_EQ(spec.contacts.at(0).friction,
            std::get<double>(find_table_spec("contact")->key("friction")->fallback));
  EXPECT_EQ(spec.contacts.at(0).friction, 0.0);
  EXPECT_EQ(std::get<double>(find_table_spec("monopile")->key("friction")->fallback), 0.4);
  EXPECT_TRUE(spec.contacts.at(0).outline);
  EXPECT_EQ(spec.bodies.at(0).particles_per_direction, 2);
  EXPECT_EQ(spec.phases.at(0).local_damping, 0.0);
  EXPECT_TRUE(spec.phases.at(0).gravity);
}

// Each numerical setting is declared once (solver/solver_settings.cpp): its [solver] key (or its
// [[phases]] key, and every phase override of it) has the declaration's range and
// SolverSettings' default, a value set in a case reaches its member, and SolverSettings::validate
// refuses a value outside that same range, naming it.
TEST(CaseFormat, EachSolverSettingIsDeclaredOnceAndBoundToItsMember) {
  const SolverSettings defaults;
  const TableSpec& solver = *find_table_spec("solver");
  const TableSpec& phases = *find_table_spec("phases");
  for (const SolverParameter& p : solver_parameters()) {
    SCOPED_TRACE(p.name);
    const KeySpec* key = (p.per_phase ? phases : solver).key(p.name);
    ASSERT_NE(key, nullptr);
    EXPECT_EQ(key->range.text(), p.range.text());
    if (const KeySpec* override_key = phases.key(p.name); !p.per_phase && override_key) {
      EXPECT_EQ(override_key->range.text(), p.range.text());
    }
    std::visit(
        [&](auto member) {
          const double value = static_cast<double>(defaults.*member);
          if (p.computed_default.empty()) {
            const double declared = std::visit(
                [](auto x) -> double {
                  if constexpr (std::is_arithmetic_v<decltype(x)>) {
                    return static_cast<double>(x);
                  } else {
                    return std::nan("");
                  }
                },
                key->fallback);
            EXPECT_EQ(declared, value);
          }
          if (p.per_phase) {
            return;
          }
          // A value other than the default, read from a case, lands in the member.
          const bool integer = std::is_same_v<decltype(member), int SolverSettings::*>;
          const bool flag = std::is_same_v<decltype(member), bool SolverSettings::*>;
          const std::string written =
              flag ? (value != 0.0 ? "false" : "true")
                   : format_bound(p.range.upper && p.range.upper->inclusive
                                      ? p.range.upper->value
                                      : (p.range.lower ? p.range.lower->value : 0.0) + 1.0);
          std::string text = block + "[solver]\n" + p.name + " = " + written + "\n";
          if (p.name == "implicit_pore_pressure" || p.name == "cell_mean_pore_pressure" ||
              p.name == "hold_wall_cells") {
            // Each needs pore water to act on.
            const std::string wood = "[materials.wood]\n";
            text.insert(text.find(wood) + wood.size(), "drainage = \"undrained\"\n");
          }
          if (p.name == "hold_wall_cells") {
            text += "implicit_pore_pressure = true\n"; // it acts in that solve
          }
          if (p.name == "energy_residual_warning") {
            text += "energy_residual_limit = 5.0\n";
          }
          const CaseSpec spec = read_case_text(text, "case.toml");
          const double read = static_cast<double>(spec.solver.*member);
          EXPECT_EQ(read, flag ? (value != 0.0 ? 0.0 : 1.0) : std::stod(written)) << written;
          if (!flag && p.range.lower) {
            SolverSettings bad;
            bad.*member = static_cast<std::remove_reference_t<decltype(bad.*member)>>(
                p.range.lower->value - (integer ? 1.0 : 0.5));
            try {
              bad.validate();
              ADD_FAILURE() << "validate() let " << p.name << " below its range through";
            } catch (const std::invalid_argument& e) {
              EXPECT_NE(std::string(e.what()).find(p.name), std::string::npos) << e.what();
            }
          }
        },
        p.member);
  }
}

// One name per key: every scalar key of the case format is bound to the field it is read into,
// so its name, unit, range and default are written once, in the declaration, and an error names
// the key the user wrote. The exceptions read a value before the case is composed or take more
// than one form.
TEST(CaseFormat, EveryScalarKeyIsBoundToItsField) {
  const std::set<std::string> unbound{
      ".base", // the composition's include, resolved before the tables are read
  };
  for (const TableSpec& table : case_format()) {
    for (const KeySpec& key : table.keys) {
      const bool scalar = key.kind == ValueKind::number || key.kind == ValueKind::integer ||
                          key.kind == ValueKind::boolean || key.kind == ValueKind::string;
      if (scalar && unbound.count(table.path + "." + key.name) == 0) {
        EXPECT_NE(key.bound_to, nullptr) << "[" << table.path << "] " << key.name;
      }
    }
  }
}

// A key bound to its field (KeySpec::into) is read through its declaration: a value given lands
// in its field, an absent one leaves the field's initialiser, which is the declared default, and
// an absent required one is refused at its table.
TEST(CaseFormat, BoundKeysReachTheirFieldsThroughTheDeclaration) {
  const CaseSpec spec =
      read_case_text(block + "k0 = [{ body = \"soil\", surface = 0.5, k0 = 0.4 }]\n" +
                         "[[contact]]\nstructure = \"block\"\nadhesion = 5e3\n",
                     "case.toml");
  const K0Spec& k0 = spec.phases.at(0).k0.at(0);
  EXPECT_EQ(k0.surface, 0.5);
  EXPECT_EQ(k0.k0, 0.4);
  EXPECT_EQ(k0.surcharge,
            std::get<double>(find_table_spec("phases.k0")->key("surcharge")->fallback));
  EXPECT_EQ(spec.contacts.at(0).adhesion, 5e3);
  EXPECT_EQ(spec.contacts.at(0).friction,
            std::get<double>(find_table_spec("contact")->key("friction")->fallback));
  const MonopileParameters pile;
  EXPECT_EQ(pile.travel, std::get<double>(find_table_spec("monopile")->key("travel")->fallback));
  EXPECT_EQ(pile.wall_cells,
            std::get<long>(find_table_spec("monopile")->key("wall_cells")->fallback));
  EXPECT_NE(format_error_of(block + "k0 = [{ body = \"soil\", k0 = 0.4 }]\n")
                .find("case.toml:27: phases[0].k0[0].surface: missing"),
            std::string::npos)
      << format_error_of(block + "k0 = [{ body = \"soil\", k0 = 0.4 }]\n");
}

TEST(CaseFormat, ARangeOrChoiceOutsideTheDeclarationNamesFileLineKeyAndBound) {
  EXPECT_EQ(format_error_of(block + "[solver]\ncourant_number = 3.0\n"),
            "case.toml:28: solver.courant_number: must lie in (0, 2], got 3");
  EXPECT_EQ(format_error_of(block + "[solver]\nxpic_order = 17\n"),
            "case.toml:28: solver.xpic_order: must lie between 0 and 16, got 17");
  EXPECT_EQ(format_error_of(block + "[solver]\nscheme = \"rk4\"\n"),
            "case.toml:28: solver.scheme: must be \"musl\" or \"usl\", got \"rk4\"");
  EXPECT_EQ(format_error_of(block + "[[contact]]\nstructure = \"block\"\nadhesion = -1.0\n"),
            "case.toml:29: contact[0].adhesion: must be >= 0 Pa, got -1");
  // A material parameter's range comes from the registry.
  std::string bad = block;
  bad.replace(bad.find("poisson_ratio = 0.3"), 19, "poisson_ratio = 0.7");
  EXPECT_EQ(format_error_of(bad), "case.toml:9: materials.steel.poisson_ratio: linear_elastic: "
                                  "poisson_ratio must lie in (-1, 0.5), got 0.7");
}

TEST(CaseFormat, AnUnknownKeyListsTheKeysOfItsTable) {
  const std::string message =
      format_error_of(block + "[[contact]]\nstructure = \"block\"\nfricton = 0.3\n");
  EXPECT_EQ(message, "case.toml:29: contact[0].fricton: unknown key ([[contact]] has structure, "
                     "friction, adhesion, normals, gap, surfaces, surface)");
}

TEST(CaseFormat, ReadingAnUndeclaredKeyIsAProgrammingError) {
  const TomlValue root = parse_toml("courant_number = 0.5\n", "x.toml");
  TomlTable solver(root, "solver", "x.toml", find_table_spec("solver"));
  EXPECT_EQ(solver.number("courant_number"), 0.5);
  EXPECT_THROW(solver.number("courant"), std::logic_error);
  EXPECT_THROW(solver.number_or("flip_fraction", 1.0), std::logic_error)
      << "a caller's fallback for a declared default is a second declaration";
  EXPECT_EQ(solver.number("flip_fraction"), 1.0);
}

TEST(CaseFormat, TheDocumentIsGeneratedFromTheDeclaration) {
  const std::string path = std::string(MPILE_SOURCE_DIR) + "/docs/case-format.md";
  std::ifstream in(path);
  ASSERT_TRUE(in) << path;
  std::ostringstream text;
  text << in.rdbuf();
  const bool up_to_date = regenerate_doc(text.str(), path) == text.str();
  EXPECT_TRUE(up_to_date)
      << "docs/case-format.md is stale: run mpile describe --update-doc docs/case-format.md";
  // A block for each table and material type, and none for what is not declared.
  std::string without_solver = text.str();
  without_solver.replace(without_solver.find("<!-- keys solver -->"), 20, "");
  EXPECT_THROW(regenerate_doc(without_solver, "doc.md"), CaseError);
  EXPECT_THROW(regenerate_doc(text.str() + "<!-- keys nothing -->\n<!-- end keys -->\n", "doc.md"),
               CaseError);
}

TEST(CaseFormat, DescribeNamesATableOrRefuses) {
  const std::string stop = describe_tables("[phases.stop_at]");
  EXPECT_NE(stop.find("penetration  (number, m; default none; > 0)"), std::string::npos) << stop;
  EXPECT_NE(
      describe_tables("hardening_soil").find("k0_nc  (number, -; default required; in (0, 1))"),
      std::string::npos);
  EXPECT_THROW(describe_tables("solvers"), CaseError);
}

} // namespace
} // namespace mpile
