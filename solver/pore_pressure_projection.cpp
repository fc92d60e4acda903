#include "solver/pore_pressure_projection.hpp"

#include "engine/materials/pore_water.hpp"
#include "engine/parallel.hpp"
#include "solver/conjugate_gradients.hpp"
#include "solver/rigid_interiors.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>

namespace mpile::passes {

namespace {

/// The solve's tolerance, relative to its right-hand side: the pressure's error is then a small
/// fraction of the step's increment, far below what the skeleton's explicit update leaves.
constexpr double tolerance = 1e-10;

/// Each material's PoreStorage when the solver finds its pore pressure (null for every other).
std::vector<const PoreStorage*> implicit_storages(const Scene& scene) {
  std::vector<const PoreStorage*> storages;
  for (const auto& material : scene.materials) {
    storages.push_back(material->implicit_pore_storage());
  }
  return storages;
}

/// A particle made stress-free inside a rigid body carries no pore pressure: it takes none.
bool stress_free(const Particles& p, std::size_t i, const PoreStorage& storage) {
  const auto stride = static_cast<std::size_t>(p.state_stride);
  return p.stress[i] == Stress{} &&
         p.state[i * stride + static_cast<std::size_t>(storage.pore_slot)] == 0.0;
}

/// One node DOF's response to a force f from the pressure increment over the step: the
/// skeleton's velocity changes by skeleton f, the water's by water f, and the pore water's volume
/// flux by weight f.
struct DofResponse {
  double skeleton = 0.0;
  double water = 0.0;
  double weight = 0.0;
  double flux = 0.0;
};

/// Coupled soil: the water's balance with the drag at the new velocities, (M_w + dt Q) dw =
/// dt f + dt Q dv, put into the mixture's, M_s dv + M_nw dw = dt f, as couple_phases folds it:
/// dv = dt (1 - M_nw / D) f / M*, dw = dt (f + Q dv) / D, D = M_w + dt Q, M* = M_s + M_nw dt Q / D.
DofResponse coupled_response(const LiquidNode& water, double v, double w, bool skeleton_held,
                             bool water_held, double dt_over_beta) {
  // Mass scaling beta multiplies both phases' inertia: divided through by it, each dt is dt/beta.
  const double share = water.share;
  const double porosity = share / water.mass;
  const double d = water.mass + dt_over_beta * water.drag;
  DofResponse r;
  if (skeleton_held) {
    r.water = water_held ? 0.0 : dt_over_beta / d; // through a drained face, against the drag alone
  } else if (water_held) {
    r.skeleton = dt_over_beta / water.mixture_mass; // the phases move as one
    r.water = r.skeleton;
  } else {
    const double skeleton_mass = water.mixture_mass - share;
    const double effective = skeleton_mass + share * dt_over_beta * water.drag / d;
    r.skeleton = dt_over_beta * (1.0 - share / d) / effective;
    r.water = dt_over_beta * (1.0 + water.drag * r.skeleton) / d;
  }
  r.weight = (1.0 - porosity) * r.skeleton + porosity * r.water;
  r.flux = (1.0 - porosity) * v + porosity * w;
  return r;
}

/// Whether a structure occupies any of cell (cr, cy)'s four nodes.
bool at_structure(const Grid& grid, int cr, int cy, double mass_floor) {
  const int nodes_r = grid.nodes_r();
  for (int dy = 0; dy < 2; ++dy) {
    for (int dr = 0; dr < 2; ++dr) {
      const auto node = static_cast<std::size_t>(cr + dr + nodes_r * (cy + dy));
      if (grid.structure_occupies(node, mass_floor)) {
        return true;
      }
    }
  }
  return false;
}

/// Darcy's drag over the step, n Q (w - v)^2 dt summed over the nodes' r and y DOFs, at the
/// corrected velocities: those whose divergences the pore pressure's work is booked on.
double darcy_dissipation(const Grid& grid, const StepParameters& step) {
  return parallel_reduce(
      grid.nodes.size(), 0.0,
      [&](std::size_t begin, std::size_t end, double sum) {
        for (std::size_t i = begin; i < end; ++i) {
          const LiquidNode& water = grid.liquid[i];
          if (!(water.mass > 0.0) || !(grid.nodes[i].mass > step.mass_floor)) {
            continue;
          }
          const double porosity = water.share / water.mass;
          for (int d = 0; d < 2; ++d) {
            const double relative = water.velocity()[d] - grid.nodes[i].velocity()[d];
            sum += porosity * water.drag * relative * relative * step.dt;
          }
        }
        return sum;
      },
      std::plus<>(), true);
}

} // namespace

template <GeometryMode mode, ShapeFunctions shape>
ProjectionResult PorePressureProjection::project(Scene& scene, const ParticleBins& bins,
                                                 const SolverSettings& settings,
                                                 const StepParameters& step) {
  ProjectionResult result;
  result.cells = assemble<mode, shape>(scene, bins, settings, step);
  if (result.cells == 0 ||
      !solve_with_cavitation(scene.grid, step, settings.hold_wall_cells, result)) {
    return result;
  }
  correct_velocities(scene.grid, step, result);
  hand_back_to_particles<shape>(scene, bins, step);
  return result;
}

template <GeometryMode mode, ShapeFunctions shape>
Eigen::Index PorePressureProjection::assemble(Scene& scene, const ParticleBins& bins,
                                              const SolverSettings& settings,
                                              const StepParameters& step) {
  Grid& grid = scene.grid;
  Particles& p = scene.particles;
  const auto stride = static_cast<std::size_t>(p.state_stride);
  const std::vector<const PoreStorage*> storages = implicit_storages(scene);
  const int cells_r = grid.cells_r();
  const int nodes_r = grid.nodes_r();
  const int nodes_y = grid.nodes_y();
  const auto cell_count =
      static_cast<std::size_t>(cells_r) * static_cast<std::size_t>(grid.cells_y());
  cells_.resize(cell_count);
  std::memset(static_cast<void*>(cells_.data()), 0, cells_.size() * sizeof(CellSums));
  takes_increment_.assign(p.size(), 0);
  // Soil the stress pass will make stress-free inside a rigid body carries no pore pressure.
  const std::optional<RigidInteriors> interiors = kept_rigid_interiors(scene, settings);
  const auto storage_of = [&](std::size_t i) -> const PoreStorage* {
    const PoreStorage* storage = storages[p.material[i]];
    if (storage == nullptr || scene.field_of(p.body[i]) != 0 ||
        (interiors && interiors->holds_soil(p, i))) {
      return nullptr;
    }
    return storage;
  };

  // Each cell's divergence operator and storage, its particles' sums. A block holds every
  // particle of its cells, so each cell is one block's work: the sums are the same for any
  // thread count.
  bins.for_each_block([&](int block, std::span<const std::int32_t> particles) {
    const auto [cr0, cy0] = bins.block_origin(block);
    const int block_cells = bins.block_cells();
    for (const std::int32_t q : particles) {
      const auto i = static_cast<std::size_t>(q);
      const PoreStorage* storage = storage_of(i);
      if (storage == nullptr) {
        continue;
      }
      const int cr = p.cell_r[i];
      const int cy = p.cell_y[i];
      if (cr < cr0 || cr >= cr0 + block_cells || cy < cy0 || cy >= cy0 + block_cells) {
        throw std::logic_error("project_pore_pressure: a particle is not binned in its cell's "
                               "block");
      }
      takes_increment_[i] = 1;
      CellSums& cell = cells_[static_cast<std::size_t>(cr + cells_r * cy)];
      const double volume = p.volume[i];
      const double* state = p.state.data() + i * stride;
      const double stored = volume * storage->compressibility(state);
      cell.storage += stored;
      cell.headroom += stored * (storage->pore_limit - state[storage->pore_slot]);
      if (storage->porosity_slot >= 0) {
        cell.flowing += volume;
      }
      const double hoop = has_theta(mode) ? volume / p.r[i] : 0.0;
      const auto weights = particle_weights<shape>(grid, p, i);
      for (int k = 0; k < weights.size; ++k) {
        const int node = weights.node[k];
        const int lr = node % nodes_r - (cr - 1);
        const int ly = node / nodes_r - (cy - 1);
        if (lr < 0 || lr > 3 || ly < 0 || ly > 3) {
          throw std::logic_error("project_pore_pressure: a particle reaches beyond the nodes of "
                                 "its cell's neighbours");
        }
        double* c = cell.coefficient[lr + 4 * ly];
        c[0] += volume * weights.dN_dr[k] + hoop * weights.N[k];
        c[1] += volume * weights.dN_dy[k];
      }
    }
  });

  // The unknowns: the cells that hold saturated soil, in cell order.
  unknown_of_cell_.assign(cell_count, -1);
  cell_of_unknown_.clear();
  for (std::size_t c = 0; c < cell_count; ++c) {
    if (cells_[c].storage > 0.0) {
      unknown_of_cell_[c] = static_cast<int>(cell_of_unknown_.size());
      cell_of_unknown_.push_back(static_cast<int>(c));
    }
  }
  const auto unknowns = static_cast<Eigen::Index>(cell_of_unknown_.size());
  particle_increment_.assign(p.size(), 0.0);
  particle_cavitated_.assign(p.size(), 0);
  if (unknowns == 0) {
    return 0;
  }

  // Each node DOF's response to the pressure's force, and the flux it carries.
  const std::size_t dofs = 2 * grid.nodes.size();
  response_.assign(dofs, 0.0);
  water_response_.assign(dofs, 0.0);
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(dofs));
  Eigen::VectorXd flux = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(dofs));
  const bool structures = !grid.structure_fields.empty();
  const bool coupled = !grid.liquid.empty();
  const double dt_over_beta = step.dt / settings.mass_scaling;
  parallel_for(grid.nodes.size(), [&](std::size_t i) {
    const GridNode& node = grid.nodes[i];
    if (!(node.mass > step.mass_floor)) {
      return;
    }
    // Where a structure occupies the node the pressure moves the soil too: held there for the
    // contact's sake, the soil at the wall would take the water's stiffness explicitly, and under a
    // cone's tip its pore water ran away in tension within ten steps. The contact corrects what
    // the pressure pushes into the structure in the next step. The water keeps to the skeleton
    // there, as the phases are tied at a wall (couple_phases).
    const bool at_wall = structures && grid.structure_occupies(i, step.mass_floor);
    const bool liquid = coupled && grid.liquid[i].mass > 0.0 && grid.liquid[i].mixture_mass > 0.0;
    for (int d = 0; d < 2; ++d) {
      const bool held = (grid.constrained[i] & (1u << d)) != 0;
      DofResponse r;
      if (liquid) {
        const bool along_wall = (grid.liquid[i].wall_free & (1u << d)) != 0;
        const bool water_held = (at_wall && !along_wall) || (grid.water_held[i] & (1u << d)) != 0;
        r = coupled_response(grid.liquid[i], node.velocity()[d], grid.liquid[i].velocity()[d], held,
                             water_held, dt_over_beta);
      } else {
        r.skeleton = held ? 0.0 : dt_over_beta / node.mass;
        r.weight = r.skeleton;
        r.flux = node.velocity()[d];
      }
      const std::size_t dof = 2 * i + static_cast<std::size_t>(d);
      response_[dof] = r.skeleton;
      water_response_[dof] = r.water;
      weight[static_cast<Eigen::Index>(dof)] = r.weight;
      flux[static_cast<Eigen::Index>(dof)] = r.flux;
    }
  });

  // G, row by row (each row's columns in increasing order).
  divergence_.resize(unknowns, static_cast<Eigen::Index>(dofs));
  divergence_.setZero();
  divergence_.reserve(Eigen::VectorXi::Constant(unknowns, 32));
  storage_.resize(unknowns);
  for (Eigen::Index u = 0; u < unknowns; ++u) {
    const int c = cell_of_unknown_[static_cast<std::size_t>(u)];
    const CellSums& cell = cells_[static_cast<std::size_t>(c)];
    storage_[u] = cell.storage;
    const int cr = c % cells_r;
    const int cy = c / cells_r;
    for (int ly = 0; ly < 4; ++ly) {
      const int ny = cy - 1 + ly;
      for (int lr = 0; lr < 4; ++lr) {
        const int nr = cr - 1 + lr;
        if (ny < 0 || ny >= nodes_y || nr < 0 || nr >= nodes_r) {
          continue;
        }
        const Eigen::Index node = nr + static_cast<Eigen::Index>(nodes_r) * ny;
        for (int d = 0; d < 2; ++d) {
          const double value = cell.coefficient[lr + 4 * ly][d];
          if (value != 0.0) {
            divergence_.insert(u, 2 * node + d) = value;
          }
        }
      }
    }
  }
  divergence_.makeCompressed();

  // (S + dt G H G^T) dp = dt G u*, in m^3: S dp is the water's volume change.
  system_ = step.dt * (divergence_ * weight.asDiagonal() * divergence_.transpose());
  Eigen::SparseMatrix<double> diagonal(unknowns, unknowns);
  diagonal.reserve(Eigen::VectorXi::Constant(unknowns, 1));
  for (Eigen::Index u = 0; u < unknowns; ++u) {
    diagonal.insert(u, u) = storage_[u];
  }
  system_ += diagonal;
  rhs_ = step.dt * (divergence_ * flux);
  return unknowns;
}

bool PorePressureProjection::solve_with_cavitation(const Grid& grid, const StepParameters& step,
                                                   bool hold_wall_cells, ProjectionResult& result) {
  const auto unknowns = static_cast<Eigen::Index>(cell_of_unknown_.size());
  const int cells_r = grid.cells_r();
  const bool structures = !grid.structure_fields.empty();
  increment_ = Eigen::VectorXd::Zero(unknowns);
  const ConjugateGradientResult solved =
      solve_conjugate_gradients(system_, rhs_, increment_, tolerance);
  result.iterations = solved.iterations;
  result.residual = solved.residual;
  result.converged = solved.converged;
  if (!result.converged) {
    return false;
  }

  // The cut-off: each cell's increment to its limit (infinite without one). A cell of coupled soil
  // with a node a structure occupies is not held: held, the impact pile's wall cells (the plug's
  // below the tip) went unstable in the consolidation after the driving, and capped after a solve
  // whose other cells took their uncut increment (the velocities then took the cut pressure
  // there alone) the water, light against the skeleton, flowed on the unbalanced pressure and the
  // ledger ran 17 % out. There the particles are capped after the solve
  // (apply_pore_pressure_from_flow). Undrained soil at a wall is held like any other: left out,
  // the velocities took the suction the capped stress did not keep, and a dilative undrained cone
  // went unstable within 1 cm. With hold_wall_cells coupled wall cells are held too; under XPIC(2)
  // and damping after the installation the quick capacity runs stay stable with them held
  // (docs/saturated.md, "Holding the wall cells").
  Eigen::VectorXd limit_increment(unknowns);
  bool cut_off = false;
  for (Eigen::Index u = 0; u < unknowns; ++u) {
    const int c = cell_of_unknown_[static_cast<std::size_t>(u)];
    const CellSums& cell = cells_[static_cast<std::size_t>(c)];
    limit_increment[u] = cell.headroom / cell.storage;
    if (!hold_wall_cells && cell.flowing > 0.0 && std::isfinite(limit_increment[u]) && structures &&
        at_structure(grid, c % cells_r, c / cells_r, step.mass_floor)) {
      limit_increment[u] = std::numeric_limits<double>::infinity();
    }
    cut_off = cut_off || std::isfinite(limit_increment[u]);
  }
  held_.assign(static_cast<std::size_t>(unknowns), 0);
  if (cut_off) {
    // A primal-dual active set: hold the cells whose increment passes the limit, free the held
    // cells whose vapour (the volume change the held pressure does not store, the system's
    // residual there) would be negative. Freeing stops after a few passes, so that the set only
    // grows and the loop ends.
    constexpr int passes_freeing = 8;
    Eigen::VectorXd vapour = Eigen::VectorXd::Zero(unknowns);
    for (int pass = 1;; ++pass) {
      bool changed = false;
      for (Eigen::Index u = 0; u < unknowns; ++u) {
        auto& held = held_[static_cast<std::size_t>(u)];
        if (held == 0 && increment_[u] > limit_increment[u]) {
          held = 1;
          changed = true;
        } else if (held != 0 && vapour[u] < 0.0 && pass <= passes_freeing) {
          held = 0;
          changed = true;
        }
      }
      if (!changed) {
        break;
      }
      if (!solve_held(rhs_, limit_increment, increment_, result)) {
        return false;
      }
      vapour = rhs_ - system_ * increment_;
      for (Eigen::Index u = 0; u < unknowns; ++u) {
        if (held_[static_cast<std::size_t>(u)] == 0) {
          vapour[u] = 0.0;
        }
      }
    }
    for (Eigen::Index u = 0; u < unknowns; ++u) {
      if (held_[static_cast<std::size_t>(u)] != 0) {
        result.vapour_work += increment_[u] * vapour[u];
      }
    }
  }
  return true;
}

void PorePressureProjection::correct_velocities(Grid& grid, const StepParameters& step,
                                                ProjectionResult& result) {
  const std::size_t dofs = 2 * grid.nodes.size();
  const bool coupled = !grid.liquid.empty();
  // The correction: the pressure's force f = -G^T dp on every node DOF the pressure moves.
  const Eigen::VectorXd force = -(divergence_.transpose() * increment_);
  correction_.assign(dofs, 0.0);
  water_correction_.assign(dofs, 0.0);
  // Backward Euler's damping, dp^2 S / 2: what the water's pressure increment stores beyond what
  // its trapezoidal work on the step's volume change books (physics.md section 9d). The
  // correction's kinetic energy is not dissipated: in slow consolidation the step's momentum
  // balance, taken at p^n, accelerates what the correction stops again in every step, work that
  // no pass books (booked as damping, a column consolidating under its own weight ran 30 % out of
  // balance, and under pure FLIP the energy guard stopped it).
  parallel_for(grid.nodes.size(), [&](std::size_t i) {
    const bool liquid = coupled && grid.liquid[i].mass > 0.0;
    for (int d = 0; d < 2; ++d) {
      const std::size_t dof = 2 * i + static_cast<std::size_t>(d);
      const double f = force[static_cast<Eigen::Index>(dof)];
      correction_[dof] = response_[dof] * f;
      grid.nodes[i].velocity()[d] += correction_[dof];
      if (liquid) {
        water_correction_[dof] = water_response_[dof] * f;
        grid.liquid[i].velocity()[d] += water_correction_[dof];
        if (!grid.water_drained.empty() && (grid.water_drained[i] & (1u << d)) != 0) {
          grid.drain_water_velocity[i][static_cast<std::size_t>(d)] = grid.liquid[i].velocity()[d];
        }
      }
    }
  });
  result.dissipated = 0.5 * increment_.dot(storage_.cwiseProduct(increment_));
  if (coupled) {
    result.drag = darcy_dissipation(grid, step);
  }
}

template <ShapeFunctions shape>
void PorePressureProjection::hand_back_to_particles(Scene& scene, const ParticleBins& bins,
                                                    const StepParameters& step) {
  const Grid& grid = scene.grid;
  Particles& p = scene.particles;
  const auto stride = static_cast<std::size_t>(p.state_stride);
  const std::vector<const LiquidPhase*> phases = liquid_phases(scene);
  const int cells_r = grid.cells_r();
  const bool coupled = !grid.liquid.empty();
  // The particles' velocities take the nodes' corrections (as FLIP and PIC both would); each
  // saturated particle keeps its cell's increment for after the stress pass.
  bins.for_each_block([&](int, std::span<const std::int32_t> particles) {
    for (const std::int32_t q : particles) {
      const auto i = static_cast<std::size_t>(q);
      if (scene.field_of(p.body[i]) != 0) {
        continue;
      }
      const auto weights = particle_weights<shape>(grid, p, i);
      double dv[2] = {0.0, 0.0}, dw[2] = {0.0, 0.0};
      for (int k = 0; k < weights.size; ++k) {
        const auto dof = 2 * static_cast<std::size_t>(weights.node[k]);
        dv[0] += weights.N[k] * correction_[dof];
        dv[1] += weights.N[k] * correction_[dof + 1];
        if (coupled) {
          dw[0] += weights.N[k] * water_correction_[dof];
          dw[1] += weights.N[k] * water_correction_[dof + 1];
        }
      }
      p.v_r[i] += dv[0];
      p.v_y[i] += dv[1];
      // The particle moves with the corrected velocity, the one the stress pass takes its strain
      // from (and gravity's work is booked on).
      p.du_r[i] += step.dt * dv[0];
      p.du_y[i] += step.dt * dv[1];
      if (const LiquidPhase* phase = phases[p.material[i]]) {
        double* w = p.state.data() + i * stride + static_cast<std::size_t>(phase->velocity_slot);
        w[0] += dw[0];
        w[1] += dw[1];
      }
      if (takes_increment_[i] != 0) {
        const auto c = static_cast<std::size_t>(p.cell_r[i] + cells_r * p.cell_y[i]);
        const int u = unknown_of_cell_[c];
        particle_increment_[i] = increment_[u];
        particle_cavitated_[i] = held_[static_cast<std::size_t>(u)];
      }
    }
  });
}

bool PorePressureProjection::solve_held(const Eigen::VectorXd& rhs,
                                        const Eigen::VectorXd& limit_increment,
                                        Eigen::VectorXd& increment, ProjectionResult& result) {
  // K' = K with each held cell's row and column its diagonal alone; b' = b - K x_held on the free
  // rows, K_cc d_c on the held ones, so that the solve returns d_c there.
  Eigen::VectorXd fixed = Eigen::VectorXd::Zero(rhs.size());
  for (Eigen::Index u = 0; u < rhs.size(); ++u) {
    if (held_[static_cast<std::size_t>(u)] != 0) {
      fixed[u] = limit_increment[u];
    }
  }
  Eigen::VectorXd held_rhs = rhs - system_ * fixed;
  held_system_ = system_;
  for (Eigen::Index column = 0; column < held_system_.outerSize(); ++column) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(held_system_, column); it; ++it) {
      const bool row_held = held_[static_cast<std::size_t>(it.row())] != 0;
      const bool column_held = held_[static_cast<std::size_t>(it.col())] != 0;
      if (it.row() == it.col()) {
        if (row_held) {
          held_rhs[it.row()] = it.value() * fixed[it.row()];
        }
      } else if (row_held || column_held) {
        it.valueRef() = 0.0;
      }
    }
  }
  const ConjugateGradientResult solved =
      solve_conjugate_gradients(held_system_, held_rhs, increment, tolerance);
  result.iterations += solved.iterations;
  result.residual = std::max(result.residual, solved.residual);
  result.converged = solved.converged;
  return result.converged;
}

double apply_projected_pore_pressure(Scene& scene, const ParticleBins& bins,
                                     const std::vector<double>& increment,
                                     const std::vector<std::uint8_t>& cavitated,
                                     bool some_made_stress_free) {
  Particles& p = scene.particles;
  const auto stride = static_cast<std::size_t>(p.state_stride);
  const std::vector<const PoreStorage*> storages = implicit_storages(scene);
  std::vector<double> block_work(static_cast<std::size_t>(bins.block_count()), 0.0);
  bins.for_each_block([&](int block, std::span<const std::int32_t> particles) {
    double work = 0.0;
    for (const std::int32_t q : particles) {
      const auto i = static_cast<std::size_t>(q);
      const PoreStorage* storage = storages[p.material[i]];
      // Coupled soil takes its increment with its flow's (apply_pore_pressure_from_flow).
      if (storage == nullptr || storage->porosity_slot >= 0 ||
          (increment[i] == 0.0 && cavitated[i] == 0) ||
          (some_made_stress_free && stress_free(p, i, *storage))) {
        continue;
      }
      double* state = p.state.data() + i * stride;
      double& pore = state[storage->pore_slot];
      // The stress pass booked p^n times the volume change; the trapezoid's other half is dp / 2
      // times it, and the volume change is what the solve stored, n dp / K_w. In a held cell the
      // water goes to its limit (the vapour's work is the solve's); elsewhere a particle above
      // its cell's mean may still reach it, and what it would have stored beyond is dissipated.
      const double applied = cavitated[i] != 0 ? storage->pore_limit - pore
                                               : std::min(increment[i], storage->pore_limit - pore);
      work += p.volume[i] * 0.5 * applied * storage->compressibility(state) * increment[i];
      pore += applied;
      state[storage->pore_slot + 1] += applied;
      Stress& s = p.stress[i];
      s[RR] += applied;
      s[YY] += applied;
      s[TT] += applied;
    }
    block_work[static_cast<std::size_t>(block)] = work;
  });
  double total = 0.0;
  for (const std::int32_t block : bins.non_empty_blocks()) {
    total += block_work[static_cast<std::size_t>(block)];
  }
  return total;
}

#define MPILE_PROJECTION(MODE, SHAPE)                                                              \
  template ProjectionResult PorePressureProjection::project<MODE, SHAPE>(                          \
      Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&);
MPILE_PROJECTION(GeometryMode::axisymmetric, ShapeFunctions::linear)
MPILE_PROJECTION(GeometryMode::axisymmetric, ShapeFunctions::gimp)
MPILE_PROJECTION(GeometryMode::plane_strain, ShapeFunctions::linear)
MPILE_PROJECTION(GeometryMode::plane_strain, ShapeFunctions::gimp)
#undef MPILE_PROJECTION

} // namespace mpile::passes
