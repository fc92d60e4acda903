// Karlsruhe fine sand's hypoplastic skeleton as the sand ring's case file declares it
// (hypoplastic_torsion_ring.toml; docs/hypoplasticity.md gives each parameter's source): the
// cyclic sand of the benchmark's hypoplastic scene, from the one place that declares it.
#include "cases/verification/case_file_run.hpp"
#include "cases/verification/verification_cases.hpp"

#include <memory>

namespace mpile::verification {

std::unique_ptr<Material> karlsruhe_fine_sand() {
  const CaseSpec spec = read_verification_case("hypoplastic_torsion_ring.toml", {});
  return create_material(spec.materials.at(0).type, spec.materials.at(0).parameters);
}

} // namespace mpile::verification
