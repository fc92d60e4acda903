#include "app/element_test_command.hpp"

#include "app/run_command.hpp"
#include "cases/case_error.hpp"
#include "cases/element_test_file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>

namespace mpile {

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
  // Each failure with the system's reason: a directory, a path that cannot be written, a parent
  // that is a regular file.
  std::error_code error;
  if (csv.has_parent_path()) {
    std::filesystem::create_directories(csv.parent_path(), error);
    if (error) {
      err << "mpile: cannot write " << csv.string() << ": cannot make its directory "
          << csv.parent_path().string() << ": " << error.message() << '\n';
      return exit_failure;
    }
  }
  errno = 0;
  std::ofstream file(csv);
  if (file) {
    write_csv(table, file);
    file.close();
  }
  if (!file) {
    const int reason = errno;
    err << "mpile: cannot write " << csv.string() << ": "
        << (reason != 0 ? std::strerror(reason) : "the write failed") << '\n';
    return exit_failure;
  }
  const std::vector<double>& last = table.rows.back();
  out << spec.title << ": " << table.rows.size() - 1 << " increments of " << spec.material_type
      << " to " << csv.string() << "\n  end: eps_1 = " << last[0] << ", eps_v = " << last[1]
      << ", sigma_1 = " << last[2] << " Pa, sigma_3 = " << last[3] << " Pa, q = " << last[5]
      << " Pa\n";
  if (spec.path == ElementPath::cyclic_deviator || spec.path == ElementPath::cyclic_simple_shear) {
    if (table.cycles_to_liquefaction > 0.0) {
      out << "  liquefied (double amplitude of "
          << (spec.path == ElementPath::cyclic_deviator ? "axial" : "shear") << " strain "
          << spec.liquefaction_strain << ") after " << table.cycles_to_liquefaction << " cycles\n";
    } else {
      out << "  not liquefied after " << spec.cycles << " cycles\n";
    }
  }
  return exit_success;
}

} // namespace mpile
