#include "cases/absorbing_reader.hpp"

#include "cases/face_list_reader.hpp"

#include <algorithm>

namespace mpile {

void read_absorbing_faces(TomlTable& table, CaseSpec& spec, bool grid_starts_on_axis) {
  if (!table.has("absorbing")) {
    if (table.has(&CaseSpec::Absorbing::phase)) {
      table.fail(&CaseSpec::Absorbing::phase,
                 "given without `absorbing`, the faces it switches on");
    }
    return;
  }
  spec.absorbing.faces =
      read_face_list(table, "absorbing", grid_starts_on_axis ? "where no wave leaves" : "");
  table.read_into(spec.absorbing);
}

void check_absorbing_phase(const TomlTable& table, const CaseSpec& spec) {
  const std::string& phase = spec.absorbing.phase;
  if (!phase.empty() && std::none_of(spec.phases.begin(), spec.phases.end(),
                                     [&](const PhaseSpec& p) { return p.name == phase; })) {
    table.fail(&CaseSpec::Absorbing::phase, "no phase named '" + phase + "' in [[phases]]");
  }
}

} // namespace mpile
