#include "solver/explicit_solver.hpp"

#include "engine/parallel.hpp"
#include "engine/particle_split.hpp"
#include "solver/contact_passes.hpp"
#include "solver/diagnostics.hpp"
#include "solver/passes.hpp"
#include "solver/run_log.hpp"
#include "solver/xpic.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iterator>
#include <limits>
#include <sstream>

namespace mpile {

ExplicitSolver::ExplicitSolver(Scene& scene, SolverSettings settings, RunLog& log)
    : scene_(scene), settings_(settings), log_(log) {
  prepare();
  sort_particles_by_cell();
  stable_dt_ = std::min(settings_.courant_number * first_crossing_time(), settings_.max_time_step);
  // A thousandth of the first step: a run that needs steps that short has gone wrong.
  min_dt_ = settings_.min_time_step > 0.0 ? settings_.min_time_step : 1e-3 * stable_dt_;
  step_report_below_ = 0.5 * stable_dt_;
  energy_.kinetic_reference = settings_.mass_scaling * kinetic_energy(scene_);
  energy_.elastic_reference = elastic_energy(scene_);
  report_settings();
}

ExplicitSolver::ExplicitSolver(Scene& scene, SolverSettings settings, RunLog& log,
                               const SolverState& restored)
    : scene_(scene), settings_(settings), log_(log) {
  prepare();
  time_ = restored.time;
  steps_ = restored.steps;
  stable_dt_ = restored.stable_dt;
  last_dt_ = restored.last_dt;
  min_dt_ = restored.min_dt;
  step_report_below_ = 0.5 * stable_dt_;
  energy_ = restored.energy;
  report_settings();
}

void ExplicitSolver::prepare() {
  settings_.validate();
  Particles& p = scene_.particles;
  if (p.size() == 0) {
    throw std::invalid_argument("the scene has no particles");
  }
  double min_mass = p.mass[0];
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!(p.mass[i] > 0.0) || !(p.volume[i] > 0.0)) {
      throw std::invalid_argument(particle_position(p, i) + " has no mass or volume");
    }
    if (scene_.mode == GeometryMode::axisymmetric && !(p.r[i] > 0.0)) {
      throw std::invalid_argument(particle_position(p, i) +
                                  " lies on or behind the axis (r must be > 0)");
    }
    min_mass = std::min(min_mass, p.mass[i]);
  }
  // A node holding less than this is empty: its velocity would be noise divided by nearly zero.
  mass_floor_ = 1e-9 * min_mass;
  if (scene_.has_contact()) {
    passes::prepare_contact(scene_);
  }
  water_ = PoreWaterCoupling::of(scene_, bins_, settings_, timings_);
  scene_.boundaries.mark_constrained_dofs(scene_.grid);
  if (scene_.moving_mesh) {
    // A restored run continues on the mesh of its rigid body's restored position.
    const MovingMesh& mesh = *scene_.moving_mesh;
    const RigidBody& body = scene_.rigid_bodies[static_cast<std::size_t>(mesh.rigid_body)];
    scene_.grid.set_y_nodes(mesh.lines_at(body.displacement[RIGID_Y]));
    signal_speed_.assign(p.size(), 0.0);
  }
  bins_.configure(scene_.grid.cells_r(), scene_.grid.cells_y(), settings_.block_cells);
  locate_all_particles();
  rebin();
}

double ExplicitSolver::external_work() const {
  return total_external_work(scene_, energy_);
}

EnergyBalance ExplicitSolver::energy_balance() const {
  return mpile::energy_balance(scene_, energy_, settings_.mass_scaling);
}

void ExplicitSolver::account_for_stress_reset(double elastic_before) {
  energy_.elastic_reference += elastic_energy(scene_) - elastic_before;
}

void ExplicitSolver::report_settings() {
  if (settings_.mass_scaling != 1.0) {
    std::ostringstream s;
    s << "mass scaling x" << settings_.mass_scaling
      << " is on: inertia is distorted (dt grows by sqrt of it); valid for quasi-static work only";
    log_.warn(s.str());
  }
}

void ExplicitSolver::change_settings(const SolverSettings& settings) {
  settings.validate();
  if (water_) {
    water_->check(settings);
  }
  const bool rebin_needed = settings.block_cells != settings_.block_cells;
  const bool scaling_changed = settings.mass_scaling != settings_.mass_scaling;
  if (scaling_changed) {
    // The same motion now carries beta times the kinetic energy; the balance starts from there.
    energy_.kinetic_reference +=
        (settings.mass_scaling - settings_.mass_scaling) * kinetic_energy(scene_);
  }
  settings_ = settings;
  if (settings_.min_time_step > 0.0) {
    min_dt_ = settings_.min_time_step;
  }
  if (rebin_needed) {
    bins_.configure(scene_.grid.cells_r(), scene_.grid.cells_y(), settings_.block_cells);
    rebin();
  }
  stable_dt_ = std::min(settings_.courant_number * first_crossing_time(), settings_.max_time_step);
  // A fall is measured from the new phase's own step: mass scaling or another Courant number moves
  // the step at once, and a fall from there would otherwise go unreported.
  step_report_below_ = 0.5 * stable_dt_;
  if (scaling_changed) {
    report_settings();
  }
}

void ExplicitSolver::locate_all_particles() {
  Particles& p = scene_.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int cr = scene_.grid.r_axis().locate(p.r[i]);
    const int cy = scene_.grid.y_axis().locate(p.y[i]);
    if (cr < 0 || cy < 0) {
      throw std::invalid_argument(particle_position(p, i) + " lies outside the grid");
    }
    p.cell_r[i] = cr;
    p.cell_y[i] = cy;
  }
}

double ExplicitSolver::move_mesh() {
  const MovingMesh& mesh = *scene_.moving_mesh;
  const RigidBody& body = scene_.rigid_bodies[static_cast<std::size_t>(mesh.rigid_body)];
  try {
    scene_.grid.set_y_nodes(mesh.lines_at(body.displacement[RIGID_Y]));
  } catch (const std::runtime_error& e) {
    std::ostringstream s;
    s << at_step(steps_, time_) << e.what();
    throw SimulationError(s.str());
  }
  // Particles keep their positions; the lines moved under them, so their cells may have changed.
  // The same loop takes the crossing time of the moved cells from the signal speeds the stress
  // pass kept (before rebinning, which may reorder the particles).
  struct Relocation {
    std::int64_t first_outside = -1;
    double crossing_time = std::numeric_limits<double>::infinity();
  };
  Particles& p = scene_.particles;
  const GradedAxis& y_axis = scene_.grid.y_axis();
  const Relocation relocation = parallel_reduce(
      p.size(), Relocation{},
      [&](std::size_t begin, std::size_t end, Relocation r) {
        for (std::size_t i = begin; i != end; ++i) {
          const int cy = y_axis.locate(p.y[i]);
          p.cell_y[i] = cy;
          if (cy < 0) {
            r.first_outside = lowest_found(r.first_outside, static_cast<std::int64_t>(i));
            continue;
          }
          r.crossing_time = std::min(r.crossing_time,
                                     scene_.grid.cell_min_size(p.cell_r[i], cy) / signal_speed_[i]);
        }
        return r;
      },
      [](const Relocation& a, const Relocation& b) {
        return Relocation{lowest_found(a.first_outside, b.first_outside),
                          std::min(a.crossing_time, b.crossing_time)};
      });
  if (relocation.first_outside >= 0) {
    std::ostringstream s;
    s << at_step(steps_, time_)
      << particle_position(p, static_cast<std::size_t>(relocation.first_outside))
      << " left the grid";
    throw SimulationError(s.str());
  }
  rebin();
  return relocation.crossing_time;
}

void ExplicitSolver::set_stable_time_step(double step_crossing_time, double crossing_time,
                                          double dt_taken) {
  // The Courant number the step just taken has against the material as it is now, in the cells
  // the step was computed in: above 1, the waves crossed more than a cell in one step (a
  // stiffening or a runaway velocity), and the explicit integration is no longer stable. A particle
  // that has just moved into a smaller cell (or a cell the moving mesh squeezed) is not judged by
  // it: that cell sets the next step, not the one taken.
  const double courant = dt_taken / step_crossing_time;
  if (courant > 1.0) {
    std::ostringstream s;
    s << at_step(steps_, time_) << "the Courant number reached " << courant << " (dt = " << dt_taken
      << " s against a crossing time of " << step_crossing_time
      << " s): above 1 the explicit step is unstable; lower courant_number or max_time_step";
    throw SimulationError(s.str());
  }
  stable_dt_ = std::min(settings_.courant_number * crossing_time, settings_.max_time_step);
  if (stable_dt_ < min_dt_) {
    std::ostringstream s;
    s << at_step(steps_, time_) << "the time step collapsed to " << stable_dt_
      << " s, below the floor of " << min_dt_
      << " s (min_time_step): a particle's wave speed or velocity has run away";
    throw SimulationError(s.str());
  }
  if (stable_dt_ < step_report_below_) {
    report_step_limit(2.0 * step_report_below_);
    step_report_below_ = 0.5 * stable_dt_;
  }
}

double ExplicitSolver::first_crossing_time() const {
  const double crossing_time = passes::min_crossing_time(scene_, settings_);
  if (!std::isnan(crossing_time)) {
    return crossing_time;
  }
  // A NaN would pass every std::min after it and the step would come from the other particles:
  // the particle would then fail in the stress pass, or run on with a stiffness nobody checked.
  const passes::StepLimit limit = passes::step_limit(scene_, settings_);
  const Particles& p = scene_.particles;
  const std::size_t i = limit.particle;
  const Material& material = *scene_.materials[p.material[i]];
  std::ostringstream s;
  s << at_step(steps_, time_) << particle_position(p, i) << " of body '"
    << scene_.body_names.at(p.body[i])
    << "' has no finite crossing time, so the stable time step cannot be set: wave speed "
    << limit.wave_speed << " m/s from its material's (" << material.type()
    << ") constrained modulus of "
    << material.constrained_modulus(p.stress[i],
                                    p.state.data() + i * static_cast<std::size_t>(p.state_stride))
    << " Pa at its stress, velocity " << limit.speed << " m/s";
  throw SimulationError(s.str());
}

void ExplicitSolver::report_step_limit(double earlier_step) {
  // A step that halves costs twice the steps from here on: say which particle sets it and why (a
  // stretched particle's density falls, so its wave speed grows; a fast one carries its velocity).
  const passes::StepLimit limit = passes::step_limit(scene_, settings_);
  const Particles& p = scene_.particles;
  const std::size_t i = limit.particle;
  const Material& material = *scene_.materials[p.material[i]];
  std::ostringstream s;
  s << at_step(steps_, time_) << "the stable step fell to " << stable_dt_ << " s, under half of "
    << earlier_step << " s; it is set by " << particle_position(p, i) << " of body '"
    << scene_.body_names.at(p.body[i]) << "' in a cell of " << limit.cell << " m: wave speed "
    << limit.wave_speed << " m/s at a density of " << limit.density << " kg/m^3 (its material's "
    << material.density() << "), velocity " << limit.speed << " m/s";
  log_.info(s.str());
}

void ExplicitSolver::rebin() {
  bins_.rebuild(scene_.particles.cell_r, scene_.particles.cell_y);
  passes::find_structure_reach(scene_, bins_);
  // Physically re-sort once the visiting order jumps around in memory too often (on average
  // less than 32 particles in a row), so that the passes keep streaming through the arrays.
  if (bins_.order_breaks() * 32 > scene_.particles.size()) {
    sort_particles_by_cell();
  }
}

void ExplicitSolver::drop_rigid_particles_outside() {
  Particles& p = scene_.particles;
  std::vector<std::int32_t> kept;
  kept.reserve(p.size());
  std::vector<std::size_t> dropped(scene_.body_names.size(), 0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.cell_r[i] >= 0) {
      kept.push_back(static_cast<std::int32_t>(i));
    } else {
      ++dropped[p.body[i]];
    }
  }
  p.permute(kept);
  if (!signal_speed_.empty()) {
    std::vector<double> speed(kept.size());
    for (std::size_t k = 0; k < kept.size(); ++k) {
      speed[k] = signal_speed_[static_cast<std::size_t>(kept[k])];
    }
    signal_speed_.swap(speed);
  }
  for (std::size_t b = 0; b < dropped.size(); ++b) {
    if (dropped[b] > 0) {
      std::ostringstream s;
      s << at_step(steps_ + 1, time_) << dropped[b] << " particles of rigid body '"
        << scene_.body_names[b]
        << "' left the grid and were dropped (the body moves on; they no longer mark its nodes)";
      log_.info(s.str());
    }
  }
}

bool ExplicitSolver::split_oversized() {
  Particles& p = scene_.particles;
  const Grid& grid = scene_.grid;
  const bool any = parallel_reduce(
      p.size(), false,
      [&](std::size_t begin, std::size_t end, bool found) {
        for (std::size_t i = begin; i != end && !found; ++i) {
          found = oversized(p, grid, i);
        }
        return found;
      },
      [](bool a, bool b) { return a || b; });
  if (!any) {
    return false;
  }
  const std::size_t before = p.size();
  const std::vector<std::int32_t> parents = split_oversized_particles(p, grid, scene_.mode);
  if (parents.empty()) {
    return false;
  }
  if (!signal_speed_.empty()) {
    for (const std::int32_t parent : parents) {
      signal_speed_.push_back(signal_speed_[static_cast<std::size_t>(parent)]);
    }
  }
  std::ostringstream s;
  const auto first = static_cast<std::size_t>(parents.front());
  s << at_step(steps_ + 1, time_) << parents.size()
    << " particle halves made where particles grew longer than their cells (now " << p.size()
    << " particles, " << before << " before; the first: body '" << scene_.body_names[p.body[first]]
    << "' near (r, y) = (" << p.r[first] << ", " << p.y[first] << "))";
  log_.info(s.str());
  return true;
}

void ExplicitSolver::sort_particles_by_cell() {
  const auto order = bins_.cell_sorted_order(scene_.particles.cell_r, scene_.particles.cell_y);
  scene_.particles.permute(order);
  bins_.reset_to_identity();
}

double ExplicitSolver::unbalanced_force_ratio() {
  particle_to_grid();
  // Node forces are f_ext - f_int (gravity included); loads are added here as in a step.
  const passes::StepParameters now{time_, 0.0, mass_floor_};
  passes::apply_nodal_loads(scene_, now);
  const Grid& grid = scene_.grid;
  // The holding forces of absorbing faces, like loads, are part of f_ext and among the forces
  // that hold the state.
  const double holding_squared =
      passes::apply_holding_tractions(scene_, passes::absorbing_face_terms(scene_), now);
  const int dofs = has_theta(scene_.mode) ? 3 : 2;
  const double g2 =
      settings_.gravity[0] * settings_.gravity[0] + settings_.gravity[1] * settings_.gravity[1];
  struct Sums {
    double free = 0.0, held = 0.0;
  };
  Sums sums = parallel_reduce(
      grid.nodes.size(), Sums{},
      [&](std::size_t begin, std::size_t end, Sums s) {
        for (std::size_t i = begin; i != end; ++i) {
          const GridNode& node = grid.nodes[i];
          if (node.mass <= mass_floor_) {
            continue;
          }
          s.held += node.mass * node.mass * g2;
          // A node a structure also occupies is held by the contact force, as a support holds.
          const bool touches_structure = grid.structure_occupies(i, mass_floor_);
          for (int d = 0; d < dofs; ++d) {
            // The theta row is a torque: as a force it acts at the node's radius of gyration
            // sqrt(J / m) (so that f^2 / m = torque^2 / J), which is > 0 on the axis too.
            const double to_force2 = d == 2 ? node.mass / node.inertia : 1.0;
            const double f2 = node.force[d] * node.force[d] * to_force2;
            const bool held = touches_structure || (grid.constrained[i] & (1u << d)) != 0;
            (held ? s.held : s.free) += f2;
          }
        }
        return s;
      },
      [](Sums a, Sums b) {
        return Sums{a.free + b.free, a.held + b.held};
      },
      true);
  for (const NodalLoad& load : scene_.boundaries.loads) {
    const double traction = load.traction.value(time_);
    for (std::size_t k = 0; k < load.nodes.size(); ++k) {
      // The load is part of f_ext already; count it among the forces that hold the state too
      // (a theta load's torque as a force at the radius of gyration, as above).
      const GridNode& node = grid.nodes[static_cast<std::size_t>(load.nodes[k])];
      const double f = load.weight[k] * traction;
      const bool torque = load.component == 2 && node.inertia > 0.0;
      sums.held += f * f * (torque ? node.mass / node.inertia : 1.0);
    }
  }
  sums.held += holding_squared;
  return sums.held > 0.0 ? std::sqrt(sums.free / sums.held) : 0.0;
}

void ExplicitSolver::switch_on_absorbing(const std::vector<std::size_t>& faces) {
  if (faces.empty()) {
    return;
  }
  particle_to_grid();
  const passes::StepParameters now{time_, 0.0, mass_floor_};
  passes::apply_nodal_loads(scene_, now);
  passes::apply_holding_tractions(scene_, passes::absorbing_face_terms(scene_), now);
  passes::switch_on_absorbing_faces(scene_, faces, now);
  static const char* names[] = {"r_min", "r_max", "y_min", "y_max"};
  for (const std::size_t f : faces) {
    const AbsorbingFace& face = scene_.boundaries.absorbing[f];
    std::vector<double> soil; // the segments with soil beside them
    std::copy_if(face.p_impedance.begin(), face.p_impedance.end(), std::back_inserter(soil),
                 [](double z) { return z > 0.0; });
    std::ostringstream s;
    s << "absorbing face " << names[static_cast<int>(face.face)] << " switched on at t = " << time_
      << " s: its support gives way to dashpots";
    if (soil.empty()) {
      s << ", but no soil lies beside it";
    } else {
      const auto [low, high] = std::minmax_element(soil.begin(), soil.end());
      s << ", rho c_p from " << std::setprecision(3) << *low << " to " << *high
        << " Pa s/m where soil lies beside it";
    }
    log_.info(s.str());
  }
}

void ExplicitSolver::particle_to_grid() {
  const auto map = [this]<GeometryMode mode, bool contact>() {
    settings_.shape_functions == ShapeFunctions::gimp
        ? passes::particle_to_grid<mode, contact, ShapeFunctions::gimp>(scene_, bins_, settings_)
        : passes::particle_to_grid<mode, contact, ShapeFunctions::linear>(scene_, bins_, settings_);
  };
  const bool contact = scene_.has_contact();
  if (scene_.mode == GeometryMode::axisymmetric) {
    contact ? map.template operator()<GeometryMode::axisymmetric, true>()
            : map.template operator()<GeometryMode::axisymmetric, false>();
  } else {
    contact ? map.template operator()<GeometryMode::plane_strain, true>()
            : map.template operator()<GeometryMode::plane_strain, false>();
  }
}

double landing_step(double remaining, double stable_dt) {
  // A remainder within this fraction beyond one step is taken in one (slightly longer) step.
  constexpr double merge_fraction = 1e-6;
  if (remaining <= stable_dt * (1.0 + merge_fraction)) {
    return remaining;
  }
  if (remaining < 2.0 * stable_dt) {
    return 0.5 * remaining;
  }
  return std::numeric_limits<double>::infinity();
}

void ExplicitSolver::advance_to(double end_time) {
  while (time_ < end_time * (1.0 - 1e-15)) {
    step(landing_step(end_time - time_, stable_dt_));
  }
}

} // namespace mpile
