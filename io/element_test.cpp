#include "io/element_test.hpp"

#include "io/case_error.hpp"
#include "io/case_spec.hpp"
#include "io/run_command.hpp"
#include "io/toml_reader.hpp"

#include <Eigen/QR>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace mpile {

// ---------------------------------------------------------------------------------------------
// One material point under mixed control

ElementPoint::ElementPoint(const Material& material, const Stress& initial_stress,
                           const std::vector<std::pair<std::size_t, double>>& state_overrides)
    : material_(&material), stress_(initial_stress), state_(material.state_size(), 0.0) {
  material.initialise_state(stress_, state_.data());
  for (const auto& [index, value] : state_overrides) {
    state_.at(index) = value;
  }
}

Stress ElementPoint::trial(const StrainIncrement& strain, std::vector<double>& state) const {
  state = state_;
  Stress stress = stress_;
  update_single_point(*material_, stress, state.empty() ? nullptr : state.data(), strain);
  return stress;
}

void ElementPoint::apply(const MixedIncrement& increment) {
  std::vector<std::size_t> unknown;
  StrainIncrement de{};
  for (std::size_t c = 0; c < 6; ++c) {
    if (increment.stress_controlled[c]) {
      unknown.push_back(c);
      de[c] = previous_[c]; // a steady path repeats its last increment
    } else {
      de[c] = increment.value[c];
    }
  }
  std::vector<double> state;
  Stress stress = trial(de, state);
  iterations_ = 0;
  if (!unknown.empty()) {
    const auto n = static_cast<Eigen::Index>(unknown.size());
    auto residual = [&](const Stress& s) {
      Eigen::VectorXd r(n);
      for (Eigen::Index i = 0; i < n; ++i) {
        const std::size_t c = unknown[static_cast<std::size_t>(i)];
        r(i) = s[c] - increment.value[c];
      }
      return r;
    };
    // Stresses are met to 1e-12 of their size: far below anything a closed form is compared
    // with, yet well above the rounding of a material update (a few 1e-16). When rounding stops
    // the iterations first, 1e-9 of the size is still accepted.
    double size = 1.0;
    for (std::size_t c = 0; c < 6; ++c) {
      size = std::max({size, std::abs(stress_[c]), std::abs(increment.value[c])});
    }
    const double tolerance = 1e-12 * size;
    const double acceptable = 1e-9 * size;
    constexpr int max_iterations = 50;
    Eigen::VectorXd r = residual(stress);
    double norm = r.lpNorm<Eigen::Infinity>();
    while (norm > tolerance) {
      if (iterations_ == max_iterations) {
        std::ostringstream message;
        message << "the stress-controlled components did not converge in " << max_iterations
                << " iterations (residual " << norm << " Pa); the target may lie beyond what "
                << "the material can carry";
        throw std::runtime_error(message.str());
      }
      ++iterations_;
      // Forward differences: a step small next to the increment, so that the tangent is the one
      // on the side the increment goes (an elastic-plastic response has kinks), yet large enough
      // that the rounding of the stress stays small in the quotient.
      double strain_size = 0.0;
      for (const double v : de) {
        strain_size = std::max(strain_size, std::abs(v));
      }
      const double h = std::max(1e-9, 1e-6 * strain_size);
      Eigen::MatrixXd jacobian(n, n);
      std::vector<double> scratch;
      for (Eigen::Index j = 0; j < n; ++j) {
        StrainIncrement perturbed = de;
        perturbed[unknown[static_cast<std::size_t>(j)]] += h;
        jacobian.col(j) = (residual(trial(perturbed, scratch)) - r) / h;
      }
      // Minimum-norm step: on an edge of a perfectly plastic surface the tangent is singular
      // (sigma_rr and sigma_thth of a triaxial sample at failure can only move together), yet the
      // symmetric target is still reachable along the directions the tangent keeps.
      Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> decomposition;
      decomposition.setThreshold(1e-9);
      decomposition.compute(jacobian);
      if (decomposition.rank() == 0) {
        throw std::runtime_error("the material has no stiffness left in a stress-controlled "
                                 "direction; the target lies beyond what it can carry");
      }
      const Eigen::VectorXd step = decomposition.solve(-r);
      // Backtracking keeps Newton from overshooting across a kink of the response.
      double fraction = 1.0;
      bool improved = false;
      for (int halving = 0; halving < 40 && !improved; ++halving, fraction *= 0.5) {
        StrainIncrement candidate = de;
        for (Eigen::Index j = 0; j < n; ++j) {
          candidate[unknown[static_cast<std::size_t>(j)]] += fraction * step(j);
        }
        std::vector<double> candidate_state;
        const Stress candidate_stress = trial(candidate, candidate_state);
        const Eigen::VectorXd candidate_residual = residual(candidate_stress);
        const double candidate_norm = candidate_residual.lpNorm<Eigen::Infinity>();
        if (candidate_norm < norm) {
          de = candidate;
          stress = candidate_stress;
          state = std::move(candidate_state);
          r = candidate_residual;
          norm = candidate_norm;
          improved = true;
        }
      }
      if (!improved && norm <= acceptable) {
        break;
      }
      if (!improved) {
        std::ostringstream message;
        message << "the stress-controlled components stopped converging (residual " << norm
                << " Pa); the target may lie beyond what the material can carry";
        throw std::runtime_error(message.str());
      }
    }
  }
  stress_ = stress;
  state_ = std::move(state);
  for (std::size_t c = 0; c < 6; ++c) {
    strain_[c] += de[c];
  }
  previous_ = de;
}

// ---------------------------------------------------------------------------------------------
// Reading

namespace {

std::string format_number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

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
  TomlTable table = top.table("material");
  const MaterialSpec material = read_material_table(table, "material");
  spec.material_type = material.type;
  spec.parameters = material.parameters;
}

/// [initial_state]: state variables of the material by name, over its own initial state (for
/// example a Hardening Soil cap pushed far away, to test shear hardening alone).
void read_initial_state(TomlTable& top, ElementTestSpec& spec) {
  std::optional<TomlTable> table = top.optional_table("initial_state");
  if (!table) {
    return;
  }
  const auto material = create_material(spec.material_type, spec.parameters);
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
  const auto material = create_material(spec.material_type, spec.parameters);
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
  } else if (type == "strain_table") {
    spec.path = ElementPath::strain_table;
    const TomlValue& raw = table.raw("strain_increments");
    bool ok = raw.is_array() && !raw.as_array().empty();
    if (ok) {
      for (const TomlValue& row : raw.as_array()) {
        if (!row.is_array() || row.as_array().size() != 6) {
          ok = false;
          break;
        }
        std::array<double, 6> values{};
        for (std::size_t c = 0; c < 6 && ok; ++c) {
          const TomlValue& v = row.as_array()[c];
          ok = v.is_floating() || v.is_integer();
          if (ok) {
            values[c] = v.is_floating() ? v.as_floating() : static_cast<double>(v.as_integer());
            ok = std::isfinite(values[c]) && std::abs(values[c]) < 1.0;
          }
        }
        spec.strain_increments.push_back(values);
      }
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
                           "cyclic_torsion, strain_table)");
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
  std::ifstream in(path);
  if (!in) {
    throw CaseError(path + ": cannot open the element-test file");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return read_element_test_text(text.str(), path);
}

// ---------------------------------------------------------------------------------------------
// Running

std::size_t ElementTestTable::column(const std::string& name) const {
  const auto found = std::find(columns.begin(), columns.end(), name);
  if (found == columns.end()) {
    throw std::out_of_range("no column named '" + name + "'");
  }
  return static_cast<std::size_t>(found - columns.begin());
}

namespace {

class PathRunner {
public:
  PathRunner(const ElementTestSpec& spec, const Material& material)
      : spec_(spec), point_(material,
                            Stress{-spec.lateral_stress, -spec.vertical_stress,
                                   -spec.lateral_stress, 0.0, 0.0, 0.0},
                            spec.initial_state) {
    table_.columns = {"eps_1", "eps_v", "sigma_1", "sigma_3", "p", "q"};
    for (const std::string& name : material.state_names()) {
      table_.columns.push_back(name);
    }
    if (spec.path == ElementPath::cyclic_torsion) {
      table_.columns.push_back("gamma_ytheta");
      table_.columns.push_back("tau_ytheta");
    }
    record();
  }

  ElementTestTable run() {
    switch (spec_.path) {
    case ElementPath::triaxial:
      for (long k = 0; k < spec_.increments; ++k) {
        step(triaxial(spec_.axial_strain / static_cast<double>(spec_.increments)));
      }
      break;
    case ElementPath::oedometer:
      for (const double target : spec_.stress_targets) {
        const double start = vertical();
        for (long k = 1; k <= spec_.increments; ++k) {
          MixedIncrement increment; // lateral strain and shear strain zero
          increment.stress_controlled[YY] = true;
          increment.value[YY] = -(start + (target - start) * fraction(k));
          step(increment);
        }
      }
      break;
    case ElementPath::isotropic:
      for (const double target : spec_.stress_targets) {
        const Stress start = point_.stress();
        const double change = target - mean_pressure(start);
        for (long k = 1; k <= spec_.increments; ++k) {
          MixedIncrement increment; // equal changes of the three normal stresses
          for (Component c : {RR, YY, TT}) {
            increment.stress_controlled[c] = true;
            increment.value[c] = start[c] - change * fraction(k);
          }
          step(increment);
        }
      }
      break;
    case ElementPath::unload_reload:
      unload_reload();
      break;
    case ElementPath::cyclic_triaxial:
    case ElementPath::cyclic_torsion:
      cyclic();
      break;
    case ElementPath::strain_table:
      for (long r = 0; r < spec_.repeat; ++r) {
        for (const std::array<double, 6>& row : spec_.strain_increments) {
          MixedIncrement increment;
          for (std::size_t c = 0; c < 6; ++c) {
            increment.value[c] = -row[c]; // compression positive in the file
          }
          step(increment);
        }
      }
      break;
    }
    return std::move(table_);
  }

private:
  double fraction(long k) const {
    return static_cast<double>(k) / static_cast<double>(spec_.increments);
  }
  double vertical() const { return -point_.stress()[YY]; }
  double axial_strain() const { return -point_.strain()[YY]; }
  double deviator() const { return -point_.stress()[YY] + point_.stress()[RR]; }

  /// Drained triaxial: axial strain increment (compression positive), radial and hoop stress held
  /// at the initial lateral stress, no shear strain.
  MixedIncrement triaxial(double axial) const {
    MixedIncrement increment;
    increment.value[YY] = -axial;
    for (Component c : {RR, TT}) {
      increment.stress_controlled[c] = true;
      increment.value[c] = -spec_.lateral_stress;
    }
    return increment;
  }

  void step(const MixedIncrement& increment) {
    ++increments_;
    try {
      point_.apply(increment);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(spec_.path_where + ": increment " + std::to_string(increments_) +
                               ": " + e.what());
    }
    record();
  }

  void unload_reload() {
    const double d = spec_.axial_strain / static_cast<double>(spec_.increments);
    while (deviator() < spec_.deviator) {
      if (axial_strain() >= spec_.axial_strain) {
        throw std::runtime_error(spec_.path_where + ": deviator " + format_number(spec_.deviator) +
                                 " Pa not reached by the axial strain " +
                                 format_number(spec_.axial_strain) + " (it is " +
                                 format_number(deviator()) + " Pa there)");
      }
      step(triaxial(d));
    }
    const long limit = increments_ + 10 * spec_.increments;
    while (deviator() > spec_.unload_deviator) {
      if (increments_ >= limit) {
        throw std::runtime_error(spec_.path_where + ": unload_deviator " +
                                 format_number(spec_.unload_deviator) + " Pa not reached (it is " +
                                 format_number(deviator()) + " Pa after unloading by " +
                                 std::to_string(10 * spec_.increments) + " increments)");
      }
      step(triaxial(-d));
    }
    // Reload to the final axial strain; the last increment lands on it exactly.
    while (spec_.axial_strain - axial_strain() > 1e-12 * spec_.axial_strain) {
      step(triaxial(std::min(d, spec_.axial_strain - axial_strain())));
    }
  }

  void cyclic() {
    const bool torsion = spec_.path == ElementPath::cyclic_torsion;
    const Stress held = point_.stress();
    const long total = spec_.increments * spec_.cycles;
    auto wave = [&](long k) {
      return spec_.amplitude * std::sin(2.0 * std::numbers::pi * static_cast<double>(k) /
                                        static_cast<double>(spec_.increments));
    };
    for (long k = 1; k <= total; ++k) {
      const double change = wave(k) - wave(k - 1);
      if (torsion) {
        // Constant normal stresses, y-theta shear strain imposed: the principal axes rotate.
        MixedIncrement increment;
        for (Component c : {RR, YY, TT}) {
          increment.stress_controlled[c] = true;
          increment.value[c] = held[c];
        }
        increment.value[YT] = -change;
        step(increment);
      } else {
        step(triaxial(change));
      }
    }
  }

  void record() {
    // Soil-mechanics signs; 0 - x rather than -x, so that no "-0" reaches the file.
    auto compression = [](double x) { return 0.0 - x; };
    const Stress& s = point_.stress();
    const StrainIncrement& e = point_.strain();
    const double sigma_1 = compression(s[YY]), sigma_3 = compression(s[RR]);
    const double q = deviatoric_stress(s);
    std::vector<double> row = {
        compression(e[YY]),          compression(e[RR] + e[YY] + e[TT]), sigma_1, sigma_3,
        compression(trace(s) / 3.0), sigma_1 >= sigma_3 ? q : -q};
    row.insert(row.end(), point_.state().begin(), point_.state().end());
    if (spec_.path == ElementPath::cyclic_torsion) {
      row.push_back(compression(e[YT]));
      row.push_back(compression(s[YT]));
    }
    table_.rows.push_back(std::move(row));
  }

  const ElementTestSpec& spec_;
  ElementPoint point_;
  ElementTestTable table_;
  long increments_ = 0;
};

} // namespace

ElementTestTable run_element_test(const ElementTestSpec& spec) {
  const auto material = create_material(spec.material_type, spec.parameters);
  PathRunner runner(spec, *material);
  return runner.run();
}

void write_csv(const ElementTestTable& table, std::ostream& out) {
  for (std::size_t c = 0; c < table.columns.size(); ++c) {
    out << (c > 0 ? "," : "") << table.columns[c];
  }
  out << '\n';
  // Shortest representation that reads back to the same double: the file is exact.
  char buffer[64];
  for (const std::vector<double>& row : table.rows) {
    for (std::size_t c = 0; c < row.size(); ++c) {
      // Whole numbers (stresses given in round pascals) as integers, not as 1e+05.
      const double v = row[c];
      const bool whole = v == std::floor(v) && std::abs(v) < 1e15;
      const auto result =
          whole ? std::to_chars(buffer, buffer + sizeof buffer, static_cast<long long>(v))
                : std::to_chars(buffer, buffer + sizeof buffer, v);
      out << (c > 0 ? "," : "") << std::string_view(buffer, result.ptr);
    }
    out << '\n';
  }
}

int element_test_command(const ElementTestOptions& options, std::ostream& out, std::ostream& err) {
  ElementTestSpec spec;
  try {
    spec = read_element_test_file(options.file);
  } catch (const CaseError& e) {
    err << "mpile: " << e.what() << '\n';
    return exit_bad_input;
  } catch (const std::exception& e) {
    err << "mpile: " << options.file << ": " << e.what() << '\n';
    return exit_bad_input;
  }
  const std::filesystem::path csv =
      options.csv.empty() ? std::filesystem::path("out") /
                                (std::filesystem::path(options.file).stem().string() + ".csv")
                          : std::filesystem::path(options.csv);
  ElementTestTable table;
  try {
    table = run_element_test(spec);
  } catch (const std::exception& e) {
    err << "mpile: " << e.what() << '\n';
    return exit_failure;
  }
  try {
    if (csv.has_parent_path()) {
      std::filesystem::create_directories(csv.parent_path());
    }
    std::ofstream file(csv);
    write_csv(table, file);
    file.close();
    if (!file) {
      throw std::runtime_error("cannot write " + csv.string());
    }
  } catch (const std::exception& e) {
    err << "mpile: " << e.what() << '\n';
    return exit_failure;
  }
  const std::vector<double>& last = table.rows.back();
  out << spec.title << ": " << table.rows.size() - 1 << " increments of " << spec.material_type
      << " to " << csv.string() << "\n  end: eps_1 = " << last[0] << ", eps_v = " << last[1]
      << ", sigma_1 = " << last[2] << " Pa, sigma_3 = " << last[3] << " Pa, q = " << last[5]
      << " Pa\n";
  return exit_success;
}

} // namespace mpile
