#pragma once

#include "engine/scene.hpp"

#include <cstddef>
#include <span>
#include <vector>

namespace mpile::passes {

/// The B-bar cell a particle belongs to: its cell in its block, per velocity field. A cell the
/// soil and a structure share holds two independent velocity fields: averaged together, the
/// structure's particles took the soil's volumetric strain (a steel pile tip entering a cell of
/// sand grew 1.4 GPa of hoop tension in 0.8 ms while moving inwards, and the run blew up).
template <bool contact> struct CellSlots {
  const Scene& scene;
  const Particles& p;
  int cr0, cy0, block_cells;
  bool mixed;
  std::size_t cells() const { return static_cast<std::size_t>(block_cells * block_cells); }
  std::size_t fields() const {
    return mixed ? static_cast<std::size_t>(scene.grid.field_count()) : 1;
  }
  std::size_t operator()(std::size_t i) const {
    std::size_t field = 0;
    if constexpr (contact) {
      field = mixed ? static_cast<std::size_t>(scene.field_of(p.body[i])) : 0;
    }
    return field * cells() +
           static_cast<std::size_t>((p.cell_r[i] - cr0) + block_cells * (p.cell_y[i] - cy0));
  }
};

/// The internal force that B-bar's strains are consistent with: B-bar takes each particle's
/// volumetric strain increment as its cell's volume-weighted mean, so the work sum V sigma : d eps
/// equals the nodal forces' work on the velocities only if the forces see each particle's mean
/// stress as its cell's volume-weighted mean (B-bar's transpose). Writes, for each of `particles`
/// (one block's), the shift of its normal stresses, (cell mean - own mean stress). Used with
/// [solver] bbar_consistent_force: without it the energy ledger of a frictionless pile jacked into
/// the sand lost 9 % of the work that drove it (physics.md section 4).
template <bool contact>
void bbar_mean_stress_shift(const Particles& p, std::span<const std::int32_t> particles,
                            const CellSlots<contact>& slot, std::vector<double>& shift) {
  thread_local std::vector<double> weighted_mean, volume;
  weighted_mean.assign(slot.fields() * slot.cells(), 0.0);
  volume.assign(slot.fields() * slot.cells(), 0.0);
  shift.resize(particles.size());
  // First each particle's stress trace, then the shift from its mean to its cell's.
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const auto i = static_cast<std::size_t>(particles[k]);
    const Stress& s = p.stress[i];
    const std::size_t c = slot(i);
    shift[k] = s[RR] + s[YY] + s[TT];
    weighted_mean[c] += p.volume[i] * shift[k] / 3.0;
    volume[c] += p.volume[i];
  }
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const std::size_t c = slot(static_cast<std::size_t>(particles[k]));
    shift[k] = weighted_mean[c] / volume[c] - shift[k] / 3.0;
  }
}

} // namespace mpile::passes
