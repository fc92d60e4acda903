// Grid-to-particle. Reads node velocity v^{n+1} and velocity increment; writes particle velocity
// (FLIP/PIC blend), the position increment du (applied after the stress update, so that every pass
// of the step uses the shape functions at x^n) and the circumferential displacement. The theta DOF
// is the node's angular velocity: a particle moves at v_theta = r_p sum N omega, so the angular
// momentum sum m r v_theta the nodes held is handed back exactly (sum_p m r_p^2 N = the inertia).
// With XPIC (solver/xpic.hpp) the particle velocity is interpolated from the nodal velocity plus
// the field's XPIC correction; the position increment stays the nodal velocity's. Returns the
// kinetic energy the update took against FLIP's (J [/rad], the numerical dissipation of PIC, a
// blend or XPIC; 0 for FLIP), for the energy balance.
#include "engine/materials/pore_water.hpp"
#include "engine/shape_functions.hpp"
#include "solver/particle_fields.hpp"
#include "solver/passes.hpp"
#include "solver/xpic.hpp"

#include <optional>

namespace mpile::passes {

template <GeometryMode mode, bool contact, ShapeFunctions shape>
double grid_to_particle(Scene& scene, const ParticleBins& bins, const SolverSettings& settings,
                        const StepParameters& step, const XpicFields* xpic) {
  Grid& grid = scene.grid;
  Particles& p = scene.particles;
  const double flip = settings.flip_fraction;
  const double pic = 1.0 - flip;
  const double dt = step.dt;
  // Pure FLIP takes no energy: the velocity change is the grid's.
  const bool dissipative = xpic != nullptr || flip < 1.0;
  [[maybe_unused]] const auto fields =
      contact ? std::optional<ParticleFields>(std::in_place, grid, scene) : std::nullopt;
  // A rigid body's particles carry no kinetic energy of their own (kinetic_energy).
  const std::vector<char> rigid_material = scene.rigid_materials();
  // The share of a particle's mass that moves at its velocity v: a coupled soil's water moves at
  // its own w (solver/pore_water_passes.cpp books its share).
  const std::vector<const LiquidPhase*> water = passes::liquid_phases(scene);
  const auto moving_fraction = [&](std::size_t i) {
    const LiquidPhase* phase = water[p.material[i]];
    return phase == nullptr ? 1.0
                            : 1.0 - phase->water_fraction(passes::water_porosity(p, i, *phase));
  };
  // One sum per block, added in block order afterwards: the same for any thread count.
  std::vector<double> block_loss(dissipative ? static_cast<std::size_t>(bins.block_count()) : 0);
  bins.for_each_block([&](int block, std::span<const std::int32_t> particles) {
    // A block of soil particles only gathers from field 0.
    [[maybe_unused]] const bool mixed = contact && bins.block_tag(block) != 0;
    double loss = 0.0;
    for (const std::int32_t q : particles) {
      const auto i = static_cast<std::size_t>(q);
      const GridNode* nodes = grid.nodes.data();
      if constexpr (contact) {
        if (mixed) {
          nodes = fields->nodes(p.body[i]);
        }
      }
      const auto w = particle_weights<shape>(grid, p, i);
      double velocity[3] = {0.0, 0.0, 0.0};
      double increment[3] = {0.0, 0.0, 0.0};
      constexpr int dofs = has_theta(mode) ? 3 : 2;
      for (int k = 0; k < w.size; ++k) {
        const GridNode& node = nodes[static_cast<std::size_t>(w.node[k])];
        for (int d = 0; d < dofs; ++d) {
          velocity[d] += w.N[k] * node.velocity()[d];
          increment[d] += w.N[k] * node.velocity_increment()[d];
        }
      }
      const double r = has_theta(mode) ? p.r[i] : 0.0;
      // What FLIP would give, and what this update gives (theta as v_theta).
      const double v_flip[3] = {p.v_r[i] + increment[0], p.v_y[i] + increment[1],
                                has_theta(mode) ? p.v_theta[i] + r * increment[2] : 0.0};
      double v_new[3] = {0.0, 0.0, 0.0};
      if (xpic != nullptr) {
        // XPIC: v_p = S+ (v^{n+1} + correction); a rigid body's field has no correction.
        const NodeVector* correction = xpic->correction_of(contact ? scene.field_of(p.body[i]) : 0);
        double filtered[3] = {velocity[0], velocity[1], velocity[2]};
        if (correction != nullptr) {
          for (int k = 0; k < w.size; ++k) {
            const NodeVector& c = correction[static_cast<std::size_t>(w.node[k])];
            for (int d = 0; d < dofs; ++d) {
              filtered[d] += w.N[k] * c[d];
            }
          }
        }
        v_new[0] = filtered[0];
        v_new[1] = filtered[1];
        v_new[2] = r * filtered[2];
      } else {
        v_new[0] = flip * v_flip[0] + pic * velocity[0];
        v_new[1] = flip * v_flip[1] + pic * velocity[1];
        v_new[2] = flip * v_flip[2] + pic * r * velocity[2];
      }
      if (dissipative && rigid_material[p.material[i]] == 0) {
        // The kinetic energy the update takes from what FLIP would have kept.
        double drop = 0.0;
        for (int d = 0; d < dofs; ++d) {
          drop += v_flip[d] * v_flip[d] - v_new[d] * v_new[d];
        }
        loss += 0.5 * p.mass[i] * drop * moving_fraction(i);
      }
      p.v_r[i] = v_new[0];
      p.v_y[i] = v_new[1];
      p.du_r[i] = dt * velocity[0];
      p.du_y[i] = dt * velocity[1];
      if constexpr (has_theta(mode)) {
        p.v_theta[i] = v_new[2];
        p.u_theta[i] += dt * r * velocity[2];
      }
    }
    if (dissipative) {
      block_loss[static_cast<std::size_t>(block)] = loss;
    }
  });
  double total = 0.0;
  for (const double loss : block_loss) {
    total += loss;
  }
  return total;
}

template double grid_to_particle<GeometryMode::axisymmetric, false, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&, const XpicFields*);
template double grid_to_particle<GeometryMode::axisymmetric, false, ShapeFunctions::gimp>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&, const XpicFields*);
template double grid_to_particle<GeometryMode::axisymmetric, true, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&, const XpicFields*);
template double grid_to_particle<GeometryMode::axisymmetric, true, ShapeFunctions::gimp>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&, const XpicFields*);
template double grid_to_particle<GeometryMode::plane_strain, false, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&, const XpicFields*);
template double grid_to_particle<GeometryMode::plane_strain, false, ShapeFunctions::gimp>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&, const XpicFields*);
template double grid_to_particle<GeometryMode::plane_strain, true, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&, const XpicFields*);
template double grid_to_particle<GeometryMode::plane_strain, true, ShapeFunctions::gimp>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&, const XpicFields*);

} // namespace mpile::passes
