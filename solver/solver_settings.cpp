#include "solver/solver_settings.hpp"

#include "engine/particle_bins.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace mpile {

namespace {
void require(bool condition, const std::string& message) {
  if (!condition) {
    throw std::invalid_argument(message);
  }
}
} // namespace

namespace {
SolverParameter setting(std::string name, std::string unit, std::string meaning,
                        decltype(SolverParameter::member) member, ParameterRange range,
                        std::string computed_default = "", bool per_phase = false) {
  return {std::move(name), std::move(unit),  std::move(meaning),
          member,          std::move(range), std::move(computed_default),
          per_phase};
}
} // namespace

const std::vector<SolverParameter>& solver_parameters() {
  using S = SolverSettings;
  const auto open = [](double x) { return Bound{x, false}; };
  const auto closed = [](double x) { return Bound{x, true}; };
  static const std::vector<SolverParameter> parameters{
      setting("courant_number", "-", "dt = C min over particles of h_cell / (c_p + |v_p|)",
              &S::courant_number, {open(0.0), closed(2.0)}),
      setting("max_time_step", "s", "upper bound on dt", &S::max_time_step, {open(0.0), {}},
              "none"),
      setting("flip_fraction", "-", "particle velocity update: 1 = FLIP, 0 = PIC, between: blend",
              &S::flip_fraction, {closed(0.0), closed(1.0)}),
      setting("xpic_order", "",
              "0: the FLIP/PIC blend; m >= 1: XPIC(m); excludes flip_fraction < 1", &S::xpic_order,
              {closed(0.0), closed(S::max_xpic_order)}),
      setting("bbar", "", "B-bar: cell-mean volumetric strain increment", &S::bbar, {}),
      setting("bbar_consistent_force", "",
              "B-bar's transpose in the internal force: the cell-mean mean stress and pore "
              "pressure, so that the forces do the work the strains store (needs bbar)",
              &S::bbar_consistent_force, {}),
      setting(
          "cell_mean_pore_pressure", "",
          "each cell's saturated particles share their volume-weighted mean excess pore pressure "
          "after every stress update",
          &S::cell_mean_pore_pressure, {}),
      setting("implicit_pore_pressure", "",
              "saturated soil's pore pressure increment solved on the grid each step, implicit in "
              "K_w: the step follows the skeleton (MUSL only)",
              &S::implicit_pore_pressure, {}),
      setting("hold_wall_cells", "",
              "with implicit_pore_pressure: coupled soil's cells at a structure's wall held at the "
              "cavitation limit in the solve as the others; false caps their particles after it "
              "(the treatment before, kept for the cases measured so)",
              &S::hold_wall_cells, {}),
      setting("jaumann_rate", "", "co-rotate stress with the in-plane spin", &S::jaumann_rate, {}),
      setting("split_particles", "", "split a particle grown longer than its cell into halves",
              &S::split_particles, {}),
      setting(
          "stress_free_inside_rigid", "",
          "soil stretched below half its density inside a rigid body carries no stress and sets no "
          "step",
          &S::stress_free_inside_rigid, {}),
      setting("mass_scaling", "-", "inertia multiplier for quasi-static work", &S::mass_scaling,
              {closed(1.0), {}}),
      setting("block_cells", "", "cells per side of a scatter block; at least 3 with GIMP",
              &S::block_cells, {closed(1.0), closed(ParticleBins::max_block_cells)}),
      setting("min_time_step", "s", "a run whose stable step falls below it stops as collapsed",
              &S::min_time_step, {open(0.0), {}}, "a thousandth of the first step"),
      setting("energy_residual_warning", "-",
              "the log warns when the energy residual exceeds this fraction of the energy in play",
              &S::energy_residual_warning, {open(0.0), {}}),
      setting("energy_residual_limit", "-",
              "past this fraction for 100 steps the run stops as unstable; above the warning",
              &S::energy_residual_limit, {open(0.0), {}}),
      setting("local_damping", "-", "Cundall damping alpha (about 0.7 for quasi-static phases)",
              &S::local_damping, {closed(0.0), open(1.0)}, "", true),
  };
  return parameters;
}

const SolverParameter& solver_parameter(std::string_view name) {
  for (const SolverParameter& p : solver_parameters()) {
    if (p.name == name) {
      return p;
    }
  }
  throw std::logic_error("no solver setting named " + std::string(name));
}

void SolverSettings::validate() const {
  const SolverSettings defaults;
  for (const SolverParameter& p : solver_parameters()) {
    std::visit(
        [&](auto member) {
          const double value = static_cast<double>(this->*member);
          // A computed default's sentinel stands for the value the solver will choose.
          const bool sentinel = !p.computed_default.empty() && this->*member == defaults.*member;
          require(sentinel || p.range.contains(value),
                  p.name + " " +
                      p.range.requirement(std::is_same_v<decltype(member), int SolverSettings::*>) +
                      ", got " + format_bound(value));
        },
        p.member);
  }
  require(xpic_order == 0 || flip_fraction == 1.0, "xpic_order " + std::to_string(xpic_order) +
                                                       " replaces the FLIP/PIC blend: leave "
                                                       "flip_fraction at 1 (got " +
                                                       std::to_string(flip_fraction) + ")");
  require(std::isfinite(gravity[0]) && std::isfinite(gravity[1]), "gravity must be finite");
  require(std::isfinite(min_time_step), "min_time_step must be finite");
  require(energy_residual_limit > energy_residual_warning,
          "energy_residual_limit must exceed energy_residual_warning (" +
              std::to_string(energy_residual_warning) + "), got " +
              std::to_string(energy_residual_limit));
  require(!bbar_consistent_force || bbar,
          "bbar_consistent_force is B-bar's transpose: it needs bbar = true");
  require(!implicit_pore_pressure || musl,
          "implicit_pore_pressure corrects the remapped velocities: it needs MUSL");
  // Two blocks of one colour are a block apart; a GIMP particle writes to nodes one cell outside
  // its block, so a block of 2 cells would let two blocks of one colour share a node.
  require(shape_functions == ShapeFunctions::linear || block_cells >= 3,
          "block_cells must be at least 3 with GIMP shape functions, got " +
              std::to_string(block_cells));
}

} // namespace mpile
