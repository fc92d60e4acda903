#include "io/absorbing_reader.hpp"

#include <algorithm>

namespace mpile {

void read_absorbing_faces(TomlTable& table, CaseSpec& spec, bool grid_starts_on_axis) {
  if (!table.has("absorbing")) {
    if (table.has("absorbing_phase")) {
      table.fail("absorbing_phase", "given without `absorbing`, the faces it switches on");
    }
    return;
  }
  const TomlValue& list = table.raw("absorbing");
  const char* names[] = {"r_min", "r_max", "y_min", "y_max"};
  const std::string expected =
      "must be a list of grid faces, each \"r_min\", \"r_max\", \"y_min\" or \"y_max\" once";
  if (!list.is_array() || list.as_array().empty()) {
    table.fail("absorbing", expected);
  }
  for (const TomlValue& entry : list.as_array()) {
    if (!entry.is_string()) {
      table.fail("absorbing", expected);
    }
    const std::string name = entry.as_string();
    const auto found = std::find(std::begin(names), std::end(names), name);
    if (found == std::end(names)) {
      table.fail("absorbing", expected + ", got \"" + name + "\"");
    }
    const auto face = static_cast<GridFace>(found - std::begin(names));
    if (std::find(spec.absorbing.faces.begin(), spec.absorbing.faces.end(), face) !=
        spec.absorbing.faces.end()) {
      table.fail("absorbing", "lists \"" + name + "\" twice");
    }
    if (face == GridFace::r_min && grid_starts_on_axis) {
      table.fail("absorbing", "\"r_min\" is the axis here, where no wave leaves");
    }
    spec.absorbing.faces.push_back(face);
  }
  spec.absorbing.phase = table.string_or("absorbing_phase", "");
}

void check_absorbing_phase(const TomlTable& table, const CaseSpec& spec) {
  const std::string& phase = spec.absorbing.phase;
  if (!phase.empty() && std::none_of(spec.phases.begin(), spec.phases.end(),
                                     [&](const PhaseSpec& p) { return p.name == phase; })) {
    table.fail("absorbing_phase", "no phase named '" + phase + "' in [[phases]]");
  }
}

} // namespace mpile
