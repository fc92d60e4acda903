#include "cases/element_test_file.hpp"

#include "cases/case_composition.hpp"
#include "cases/case_error.hpp"
#include "cases/case_spec.hpp"
#include "cases/toml_reader.hpp"
#include "engine/parameter_range.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace mpile {

namespace {

std::string where(const TomlTable& table, const std::string& key) {
  return table.file() + ":" + std::to_string(table.line_of(key)) + ": " + table.key_path(key);
}

/// One number or an array of them (targets visited in turn).
std::vector<double> targets(TomlTable& table, const std::string& key) {
  const TomlValue& raw = table.raw(key);
  if (raw.is_floating() || raw.is_integer()) {
    return {table.number(key)};
  }
  std::vector<double> values = table.numbers(key);
  if (values.empty()) {
    table.fail(key, "needs at least one value");
  }
  for (const double v : values) {
    if (!std::isfinite(v)) {
      table.fail(key, "values must be finite numbers");
    }
  }
  return values;
}

/// The most increments a whole path may take (a CSV of about a gigabyte).
constexpr double max_total_increments = 1e7;

long count(TomlTable& table, const std::string& key, long fallback, long minimum) {
  const long value = table.integer_or(key, fallback);
  if (value < minimum || value > 10000000) {
    table.fail(key, "must lie between " + std::to_string(minimum) + " and 10000000, got " +
                        std::to_string(value));
  }
  return value;
}

void read_material(TomlTable& top, ElementTestSpec& spec) {
  // Read against a case's [materials.<name>] declaration: its model, drainage and pore water.
  top.table("material"); // a table, or refused
  TomlTable table(top.raw("material"), top.key_path("material"), top.file(),
                  find_table_spec("materials.*"));
  const MaterialSpec material = read_material_table(table, "material");
  spec.material_type = material.type;
  spec.parameters = material.parameters;
  spec.water = material.water;
}

/// [initial_state]: state variables of the material by name, over its own initial state (for
/// example a Hardening Soil cap pushed far away, to test shear hardening alone).
void read_initial_state(TomlTable& top, ElementTestSpec& spec) {
  std::optional<TomlTable> table = top.optional_table("initial_state");
  if (!table) {
    return;
  }
  const auto material = create_material(spec.material_type, spec.parameters, spec.water);
  const auto names = material->state_names();
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (table->has(names[k])) {
      spec.initial_state.emplace_back(k, table->number(names[k]));
    }
  }
  table->finish();
}

void read_initial_stress(TomlTable& top, ElementTestSpec& spec) {
  TomlTable table = top.table("initial_stress");
  std::string checked_key;
  if (table.has("isotropic")) {
    if (table.has("vertical") || table.has("lateral")) {
      table.fail("isotropic", "give either isotropic or vertical and lateral, not both");
    }
    spec.vertical_stress = spec.lateral_stress = table.number("isotropic");
    checked_key = "isotropic";
  } else {
    if (!table.has("vertical") && !table.has("lateral")) {
      top.fail("initial_stress", "needs isotropic = <Pa>, or vertical = <Pa> and lateral = <Pa> "
                                 "(compression positive)");
    }
    spec.vertical_stress = table.number("vertical");
    spec.lateral_stress = table.number("lateral");
    checked_key = "vertical";
  }
  table.finish();

  // The material must accept the initial stress as it is: a zero increment may not move it.
  const auto material = create_material(spec.material_type, spec.parameters, spec.water);
  const Stress initial{
      -spec.lateral_stress, -spec.vertical_stress, -spec.lateral_stress, 0.0, 0.0, 0.0};
  ElementPoint point(*material, initial, spec.initial_state);
  std::vector<double> state;
  const Stress after = point.trial(StrainIncrement{}, state);
  const double size =
      std::max({1.0, std::abs(spec.vertical_stress), std::abs(spec.lateral_stress)});
  for (std::size_t c = 0; c < 6; ++c) {
    if (std::abs(after[c] - initial[c]) > 1e-9 * size) {
      table.fail(checked_key, "lies outside the yield surface of the material: it returns to "
                              "sigma_1 = " +
                                  format_number(-after[YY]) +
                                  " Pa, sigma_3 = " + format_number(-after[RR]) + " Pa");
    }
  }
  const Material::Inadmissible why = material->inadmissible_state(initial, point.state().data());
  if (!why.key.empty()) {
    table.fail(checked_key, "gives a state the material does not admit: " + why.reason);
  }
}

void read_path(TomlTable& top, ElementTestSpec& spec) {
  TomlTable table = top.table("path");
  spec.path_where = where(top, "path");
  const std::string type = table.string("type");
  if (type == "triaxial") {
    spec.path = ElementPath::triaxial;
    spec.axial_strain = table.number("axial_strain");
    if (spec.axial_strain == 0.0 || std::abs(spec.axial_strain) >= 1.0) {
      table.fail("axial_strain", "must be non-zero and smaller than 1 in size (a fraction), got " +
                                     format_number(spec.axial_strain));
    }
    spec.increments = count(table, "increments", 100, 1);
  } else if (type == "oedometer") {
    spec.path = ElementPath::oedometer;
    spec.stress_targets = targets(table, "vertical_stress");
    spec.increments = count(table, "increments", 100, 1);
  } else if (type == "isotropic") {
    spec.path = ElementPath::isotropic;
    spec.stress_targets = targets(table, "mean_stress");
    spec.increments = count(table, "increments", 100, 1);
  } else if (type == "unload_reload") {
    spec.path = ElementPath::unload_reload;
    spec.deviator = table.number("deviator");
    spec.unload_deviator = table.number("unload_deviator");
    spec.axial_strain = table.positive("axial_strain");
    if (spec.axial_strain >= 1.0) {
      table.fail("axial_strain",
                 "must be smaller than 1 (a fraction), got " + format_number(spec.axial_strain));
    }
    spec.increments = count(table, "increments", 1000, 1);
    const double initial = spec.vertical_stress - spec.lateral_stress;
    if (!(spec.deviator > initial)) {
      table.fail("deviator", "must exceed the initial deviator sigma_1 - sigma_3 = " +
                                 format_number(initial) + " Pa");
    }
    if (!(spec.unload_deviator < spec.deviator)) {
      table.fail("unload_deviator",
                 "must be below deviator (" + format_number(spec.deviator) + " Pa)");
    }
  } else if (type == "cyclic_triaxial" || type == "cyclic_torsion") {
    const bool torsion = type == "cyclic_torsion";
    spec.path = torsion ? ElementPath::cyclic_torsion : ElementPath::cyclic_triaxial;
    const std::string key = torsion ? "shear_strain_amplitude" : "axial_strain_amplitude";
    spec.amplitude = table.positive(key);
    if (spec.amplitude >= 1.0) {
      table.fail(key, "must be smaller than 1 (a fraction), got " + format_number(spec.amplitude));
    }
    spec.cycles = count(table, "cycles", 1, 1);
    spec.increments = count(table, "increments", 100, 4);
  } else if (type == "cyclic_deviator" || type == "cyclic_simple_shear") {
    const bool shear = type == "cyclic_simple_shear";
    spec.path = shear ? ElementPath::cyclic_simple_shear : ElementPath::cyclic_deviator;
    spec.amplitude = table.positive(shear ? "shear_stress_amplitude" : "deviator_amplitude");
    spec.cycles = count(table, "cycles", 1, 1);
    spec.increments = count(table, "increments", 100, 4);
    spec.liquefaction_strain = table.number_or("liquefaction_strain", 0.05);
    if (!(spec.liquefaction_strain > 0.0) || spec.liquefaction_strain >= 1.0) {
      table.fail("liquefaction_strain",
                 "must lie in (0, 1) (a fraction), got " + format_number(spec.liquefaction_strain));
    }
  } else if (type == "strain_table") {
    spec.path = ElementPath::strain_table;
    const auto rows = table.number_rows("strain_increments", 6);
    bool ok = rows.has_value();
    for (std::size_t r = 0; ok && r < rows->size(); ++r) {
      std::array<double, 6> values{};
      for (std::size_t c = 0; c < 6 && ok; ++c) {
        values[c] = (*rows)[r][c];
        ok = std::isfinite(values[c]) && std::abs(values[c]) < 1.0;
      }
      spec.strain_increments.push_back(values);
    }
    if (!ok) {
      table.fail("strain_increments",
                 "expected [[rr, yy, thth, ry, ytheta, rtheta], ...]: rows of 6 numbers, strain "
                 "increments smaller than 1 in size (compression positive, engineering shear)");
    }
    spec.repeat = count(table, "repeat", 1, 1);
  } else {
    table.fail("type", "unknown path '" + type +
                           "' (triaxial, oedometer, isotropic, unload_reload, cyclic_triaxial, "
                           "cyclic_torsion, cyclic_deviator, cyclic_simple_shear, strain_table)");
  }
  // Each count is bounded, but their product is the number of increments (and CSV rows): 1e7
  // cycles of 1e7 increments ran on for ever with growing memory.
  const double stages = static_cast<double>(std::max<std::size_t>(1, spec.stress_targets.size()));
  const double total =
      spec.path == ElementPath::strain_table
          ? static_cast<double>(spec.repeat) * static_cast<double>(spec.strain_increments.size())
          : stages * static_cast<double>(spec.increments) *
                static_cast<double>(std::max<long>(1, spec.cycles));
  if (total > max_total_increments) {
    const char* key = spec.path == ElementPath::strain_table ? "repeat"
                      : spec.cycles > 1                      ? "cycles"
                                                             : "increments";
    std::ostringstream why;
    why << "the path takes " << total << " increments in all (more than " << max_total_increments
        << ")";
    table.fail(key, why.str());
  }
  table.finish();
}

} // namespace

ElementTestSpec read_element_test_text(const std::string& text, const std::string& file) {
  const TomlValue root = parse_toml(text, file);
  TomlTable top(root, "", file);
  ElementTestSpec spec;
  spec.file = file;
  spec.title = top.string_or("title", std::filesystem::path(file).stem().string());
  read_material(top, spec);
  read_initial_state(top, spec);
  read_initial_stress(top, spec);
  read_path(top, spec);
  top.finish();
  return spec;
}

ElementTestSpec read_element_test_file(const std::string& path) {
  return read_element_test_text(read_case_text_file(path, "element-test file"), path);
}

void write_csv(const ElementTestTable& table, std::ostream& out) {
  for (std::size_t c = 0; c < table.columns.size(); ++c) {
    out << (c > 0 ? "," : "") << table.columns[c];
  }
  out << '\n';
  for (const std::vector<double>& row : table.rows) {
    for (std::size_t c = 0; c < row.size(); ++c) {
      out << (c > 0 ? "," : "") << format_bound(row[c]);
    }
    out << '\n';
  }
}

} // namespace mpile
