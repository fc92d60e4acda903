#pragma once

// XPIC(m), the extended particle-in-cell velocity update (Hammerquist and Nairn 2017, CMAME 318).
//
// With S the particle-to-grid map (mass-weighted, divided by the nodal mass) and S+ the
// grid-to-particle interpolation, a particle velocity field v_p splits into the part the grid sees,
// S+ S v_p, and the null-space part the grid cannot represent. FLIP keeps both (and the null-space
// part grows with cell crossing); PIC keeps neither exactly (S+ S smears the visible part too).
// XPIC(m) sets the particle velocities to S+ (v^{n+1} + sum_{j=1}^{m-1} D_j) with
//   D_0 = v^L (the nodal velocity at the start of the step),  D_j = (I - S S+) D_{j-1},
// so that sum_{j=0}^{m-1} D_j = sum_{j<m} (I - S S+)^j v^L, the first m terms of the series of
// (S S+)^{-1} v^L: the particle field projected onto the grid's with a consistent mass. XPIC(1) is
// PIC. Each term costs one gather-scatter over the particles and conserves momentum (and the
// theta DOF's angular momentum, with m r^2 for m); a DOF whose velocity a support or the contact
// law decides keeps that velocity (its D_j are zero), as does every node of a rigid body.
//
// The theta DOF is the node's angular velocity omega with v_theta = r S+ omega, so its S S+ maps
// with the rotational inertia: (S S+ w)_i = sum_p N_ip m_p r_p^2 (sum_j N_jp w_j) / J_i.

#include "engine/scene.hpp"
#include "engine/shape_functions.hpp"
#include "solver/passes.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace mpile::passes {

using NodeVector = std::array<double, 3>;

/// Per velocity field: the correction sum_{j>=1} D_j that the grid-to-particle pass adds to the
/// nodal velocity, and the two scratch fields of the iteration. A field with no correction (a rigid
/// body's, or every field when XPIC is off) keeps empty vectors.
struct XpicFields {
  std::vector<std::vector<NodeVector>> correction;
  std::vector<std::vector<NodeVector>> term;
  std::vector<std::vector<NodeVector>> smoothed;
  /// Per field and node, the DOFs whose velocity is decided for the step (DofBit mask).
  std::vector<std::vector<std::uint8_t>> decided;

  /// The correction of a field, or nullptr where there is none.
  const NodeVector* correction_of(int field) const {
    const auto& c = correction[static_cast<std::size_t>(field)];
    return c.empty() ? nullptr : c.data();
  }
};

/// Fills `fields` with the XPIC(order) correction of every deformable field, from the nodal
/// velocity (momentum slot) and increment (force slot) after the momentum balance, constraints and
/// contact. Reads particle position, cell, mass and body; writes only `fields`.
template <GeometryMode mode, bool contact, ShapeFunctions shape>
void extrapolate_xpic(const Scene& scene, const ParticleBins& bins, int order,
                      const StepParameters& step, XpicFields& fields);

/// The pore water's own XPIC(m) over Grid::liquid (solver/water_xpic.cpp): the correction its
/// particles add to their water's interpolated nodal velocity, and the iteration's scratch.
struct WaterXpic {
  std::vector<NodeVector> correction;
  std::vector<NodeVector> term;
  std::vector<NodeVector> smoothed;
  /// Per node, the DOFs whose water velocity the step decided (DofBit mask).
  std::vector<std::uint8_t> decided;
};

/// Fills `water` with the XPIC(order) correction of the coupled soil's water, from its nodal
/// velocity and increment after update_water_velocities: the series above with the water's
/// weights, rho_w V = m_w / n a particle (r^2 times it for the theta DOF), as its nodal mass and
/// inertia sum them. Reads the coupled particles' position, cell, mass and porosity; writes only
/// `water`.
template <GeometryMode mode, ShapeFunctions shape>
void extrapolate_water_xpic(const Scene& scene, const ParticleBins& bins,
                            const std::vector<const LiquidPhase*>& phases, int order,
                            const StepParameters& step, WaterXpic& water);

} // namespace mpile::passes
