#pragma once

// A case built from TOML text and stepped through its first phase by the tests, with the helpers
// they share for reading and editing case files.
#include "io/case_builder.hpp"
#include "io/case_spec.hpp"
#include "solver/explicit_solver.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

namespace mpile {

inline const std::filesystem::path source = MPILE_SOURCE_DIR;

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// An empty directory under the system's temporary directory, named mpile_test_<name>.
inline std::filesystem::path fresh_directory(const std::string& name) {
  const auto directory = std::filesystem::temp_directory_path() / ("mpile_test_" + name);
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  return directory;
}

/// The text with every occurrence of `from` replaced by `to` (at least one must exist).
inline std::string replaced(std::string text, const std::string& from, const std::string& to) {
  std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  while (at != std::string::npos) {
    text.replace(at, from.size(), to);
    at = text.find(from, at + to.size());
  }
  return text;
}

/// A case built from text and run through its single phase, with a callback after every step.
struct CaseRun {
  CaseSpec spec;
  std::unique_ptr<Scene> scene;
  RunLog log;
  std::unique_ptr<ExplicitSolver> solver;

  explicit CaseRun(const std::string& text) : spec(read_case_text(text, "test.toml")) {
    scene = build_scene(spec);
    solver = std::make_unique<ExplicitSolver>(*scene, phase_settings(spec, spec.phases[0]), log);
  }
  template <class F> void run(F&& after_step) {
    while (solver->time() < spec.phases[0].duration * (1.0 - 1e-12)) {
      solver->step(
          landing_step(spec.phases[0].duration - solver->time(), solver->stable_time_step()));
      after_step();
    }
  }
  const ContactPair& pair() const { return scene->contacts.at(0); }
  double surface_force(const std::string& surface, int component) const {
    for (std::size_t q = 0; q < pair().surfaces.size(); ++q) {
      if (pair().surfaces[q] == surface) {
        return pair().surface_force[q][static_cast<std::size_t>(component)];
      }
    }
    ADD_FAILURE() << "no surface " << surface;
    return 0.0;
  }
};

} // namespace mpile
