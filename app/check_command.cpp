#include "app/run_command.hpp"
#include "app/run_estimate.hpp"
#include "cases/case_builder.hpp"
#include "cases/case_error.hpp"
#include "cases/case_phases.hpp"
#include "cases/case_warnings.hpp"
#include "cases/plausibility.hpp"
#include "engine/materials/undrained_soil.hpp"
#include "io/monitor_points.hpp"
#include "solver/explicit_solver.hpp"

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <sstream>

namespace mpile {

namespace {

void print_axis(std::ostream& out, const char* name, const GradedAxis& axis) {
  double largest = 0.0;
  for (int c = 0; c < axis.cell_count(); ++c) {
    largest = std::max(largest, axis.cell_size(c));
  }
  out << "  " << name << ": " << axis.start() << " to " << axis.end() << " m, " << axis.cell_count()
      << " cells, sizes " << axis.min_cell_size() << " to " << largest << " m\n";
}

} // namespace

namespace {

/// A phase's end criteria in words: what ends it first, and its duration as the latest end.
std::string how_it_stops(const PhaseSpec& phase) {
  std::ostringstream s;
  s << std::setprecision(4);
  if (phase.stop_at) {
    if (phase.stop_at->settlement > 0.0) {
      s << "at " << phase.stop_at->body << " settlement " << phase.stop_at->settlement
        << " m since the phase began";
    } else {
      s << "at " << phase.stop_at->body << " penetration " << phase.stop_at->penetration << " m";
    }
    s << (phase.stop_at->at_rest ? " once at rest" : "") << ", ";
  }
  if (phase.equilibrium_tolerance) {
    s << "at equilibrium (out-of-balance force and kinetic energy ratios below "
      << *phase.equilibrium_tolerance << "), ";
  }
  if (phase.stop_at || phase.equilibrium_tolerance) {
    s << "else ";
  }
  s << "after " << phase.duration << " s";
  return s.str();
}

/// Seconds since this process started (from Linux's /proc; 0 where unknown): loading the shared
/// libraries, which a run pays as well, before any of its own work.
double process_age() {
  std::ifstream stat("/proc/self/stat");
  std::string text;
  std::getline(stat, text);
  const std::size_t name_end = text.rfind(')'); // the command name may hold spaces
  if (name_end == std::string::npos) {
    return 0.0;
  }
  std::istringstream fields(text.substr(name_end + 1));
  std::string field;
  for (int i = 3; i <= 22 && fields >> field; ++i) { // field 22: start time in clock ticks
  }
  std::ifstream uptime_file("/proc/uptime");
  double uptime = 0.0;
  if (!(uptime_file >> uptime) || field.empty()) {
    return 0.0;
  }
  const double started =
      std::strtod(field.c_str(), nullptr) / static_cast<double>(::sysconf(_SC_CLK_TCK));
  return std::max(uptime - started, 0.0);
}

/// Each saturated material's porosity and water stiffness, and what they make of the skeleton at
/// the first phase's initial stresses: Skempton's B and the undrained Poisson ratio over its
/// particles (a reduced K_w shows here as a B below 1).
void print_pore_water(std::ostream& out, const CaseSpec& spec, const Scene& scene) {
  const Particles& p = scene.particles;
  for (std::size_t m = 0; m < spec.materials.size(); ++m) {
    const auto* soil = dynamic_cast<const UndrainedSoil*>(scene.materials[m].get());
    if (soil == nullptr) {
      continue;
    }
    const PoreWater& water = spec.materials[m].water;
    double b_low = 1.0, b_high = 0.0, nu_low = 0.5, nu_high = -1.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.material[i] != m) {
        continue;
      }
      const UndrainedResponse r = soil->response(
          p.stress[i], p.state.data() + i * static_cast<std::size_t>(p.state_stride));
      b_low = std::min(b_low, r.skempton_b);
      b_high = std::max(b_high, r.skempton_b);
      nu_low = std::min(nu_low, r.poisson_ratio);
      nu_high = std::max(nu_high, r.poisson_ratio);
    }
    out << std::defaultfloat << std::setprecision(4) << "material " << spec.materials[m].name
        << ": " << drainage_names()[static_cast<std::size_t>(soil->drainage())] << ", porosity "
        << soil->porosity() << ", saturated density " << soil->density() << " kg/m^3, K_w "
        << water.bulk_modulus << " Pa"
        << (water.bulk_modulus < PoreWater{}.bulk_modulus ? " (reduced from water's 2.2e9)" : "")
        << ", K_w / n " << soil->water_stiffness() << " Pa";
    if (soil->drainage() == Drainage::coupled) {
      out << ", k " << water.hydraulic_conductivity << " m/s";
    }
    if (std::isfinite(water.cavitation_stress)) {
      out << ", cavitates at " << water.cavitation_stress << " Pa of tension";
    }
    if (water.implicit_pressure) {
      out << "; its pore pressure solved on the grid (implicit_pore_pressure): the step follows "
             "the skeleton";
    }
    out << "\n";
    if (b_high >= b_low) {
      out << "  at the first phase's initial stresses: Skempton B " << b_low << " to " << b_high
          << ", undrained Poisson ratio " << nu_low << " to " << nu_high << "\n";
    }
  }
}

/// The sea: its pressure on the seabed and what it lifts each rigid body through the seabed by.
void print_sea(std::ostream& out, const CaseSpec& spec, const Scene& scene) {
  if (!spec.water) {
    return;
  }
  if (spec.water->phreatic) {
    out << std::defaultfloat << std::setprecision(4) << "water table: at " << spec.water->table
        << " m, the soil dry above it and its pores' water hydrostatic from it below\n";
    return;
  }
  out << std::defaultfloat << std::setprecision(4) << "sea: level " << spec.water->level
      << " m over the seabed at " << spec.water->seabed << " m, its pressure there "
      << spec.water->column_pressure << " Pa (outputs add it to the pore pressures)";
  for (const RigidBody& body : scene.rigid_bodies) {
    out << "; uplift on " << body.name << " " << body.water_load[RIGID_Y]
        << (spec.mode == GeometryMode::axisymmetric ? " N/rad" : " N/m");
  }
  out << "\n";
}

/// Runs the case for options.pilot_seconds of wall time in a temporary directory (the run's own
/// path: phases, stop criteria, outputs) and prints the run time estimated from it.
int run_pilot(const RunOptions& options, const CaseSpec& spec, double start_up, std::ostream& out,
              std::ostream& err) {
  std::error_code error;
  const auto directory =
      std::filesystem::temp_directory_path(error) / ("mpile-pilot-" + std::to_string(::getpid()));
  RunOptions pilot = options;
  pilot.output_directory = directory.string();
  pilot.stop_after_seconds = options.pilot_seconds;
  pilot.restart.clear();
  std::ostringstream pilot_out, pilot_err;
  const auto begun = std::chrono::steady_clock::now();
  const int status = run_case(pilot, pilot_out, pilot_err);
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begun).count();
  int result = exit_success;
  if (status != exit_success && status != exit_interrupted) {
    err << "mpile: the pilot run failed:\n" << pilot_err.str();
    result = exit_failure;
  } else {
    const PilotRecord record = read_pilot((directory / "history.h5").string(), spec);
    std::vector<PhaseEstimate> phases = estimate_phases(spec, record);
    // What the history's wall time leaves out: starting the program, reading the case, building
    // the scene, and the last outputs; small against a long run, most of a run of a second.
    PhaseEstimate overhead;
    overhead.name = "start-up and final output";
    overhead.wall = start_up + std::max(elapsed - record.wall.back(), 0.0);
    overhead.low = overhead.wall;
    overhead.basis = "measured in the pilot";
    phases.push_back(overhead);
    double total = 0.0;
    double low = 0.0;
    bool bound = false;
    for (const PhaseEstimate& e : phases) {
      total += e.wall;
      low += e.low;
      bound = bound || e.bound;
    }
    // "120 to 180 s": from the pile gathering speed as over the pilot's later half, to its
    // present speed (the progress line's range); one number where they are within a tenth.
    const auto figure = [](double l, double h) {
      std::ostringstream s;
      s << std::defaultfloat << std::setprecision(3);
      if (l < 0.9 * h) {
        s << l << " to ";
      }
      s << h;
      return s.str();
    };
    out << std::defaultfloat << std::setprecision(3) << "pilot: " << record.wall.back()
        << " s of wall time, to t = " << record.time.back() << " s in phase "
        << spec.phases[static_cast<std::size_t>(record.phase.back())].name
        << (record.complete ? " (the whole run)" : "") << "\n";
    out << "estimated run time: " << (bound ? "at most " : "") << figure(low, total) << " s on "
        << options.threads << " threads\n";
    for (const PhaseEstimate& e : phases) {
      out << "  " << e.name << ": " << (e.bound ? "at most " : "") << figure(e.low, e.wall)
          << " s, " << e.basis << "\n";
    }
  }
  std::filesystem::remove_all(directory, error);
  return result;
}

} // namespace

int check_case(const RunOptions& options, std::ostream& out, std::ostream& err) {
  const double start_up = process_age();
  CaseSpec spec;
  std::unique_ptr<Scene> scene;
  try {
    spec = read_case_file(options.case_path, options.overrides);
    scene = build_scene(spec);
    for (const MonitorSpec& monitor : spec.output.monitors) {
      monitored_particle(monitor, *scene);
    }
  } catch (const std::exception&) {
    return refuse_case(err, options.case_path);
  }
  print_case_warnings(err, spec.warnings, options.strict);
  if (options.strict && refused_when_strict(spec.warnings)) {
    return exit_bad_input;
  }
  if (options.print_resolved) {
    // What the history's case_resolved will hold: a file that runs as this case on its own.
    out << spec.resolved;
    return exit_success;
  }
  out << spec.file << ": " << spec.title << " ("
      << (spec.mode == GeometryMode::axisymmetric ? "axisymmetric" : "plane strain") << ")\n";
  out << "grid: " << scene->grid.cells_r() << " x " << scene->grid.cells_y() << " cells, "
      << scene->grid.node_count() << " nodes\n";
  print_axis(out, "r", scene->grid.r_axis());
  print_axis(out, "y", scene->grid.y_axis());
  out << "particles: " << scene->particles.size() << "\n";
  for (std::size_t b = 0; b < scene->body_names.size(); ++b) {
    std::size_t count = 0;
    for (const auto body : scene->particles.body) {
      count += body == b ? 1 : 0;
    }
    out << "  " << scene->body_names[b] << ": " << count << " (material " << spec.bodies[b].material
        << (spec.bodies[b].rigid ? ", rigid" : "") << ")\n";
  }
  for (const ContactPair& pair : scene->contacts) {
    out << "contact: soil with " << pair.name << " (mu " << pair.friction << ", adhesion "
        << pair.adhesion << " Pa, " << (pair.outline ? "outline" : "mass-gradient")
        << " normals), surfaces:";
    for (const std::string& surface : pair.surfaces) {
      out << " " << surface;
    }
    out << "\n";
  }
  for (const RigidBody& body : scene->rigid_bodies) {
    out << "rigid body " << body.name << ": mass " << body.mass << ", inertia " << body.inertia
        << (scene->mode == GeometryMode::axisymmetric ? " (per radian)" : " (per metre)") << "\n";
  }
  out << "boundary conditions: " << scene->boundaries.constraints.size()
      << " node sets, loads: " << scene->boundaries.loads.size() << "\n";

  RunLog log(&out);
  try {
    // The first phase set up as `mpile run` sets it up: the trial steps below are the run's.
    RunProgress progress;
    const std::unique_ptr<ExplicitSolver> solver = CasePhases(spec, *scene).start(progress, log);
    print_pore_water(out, spec, *scene);
    print_sea(out, spec, *scene);
    const double dt = solver->stable_time_step();
    refuse_implausible_run(spec, *scene, dt);
    const double steps = spec.end_time() / dt;
    // A short trial run on a copy of the particles measures this machine's step rate.
    const auto start = std::chrono::steady_clock::now();
    int trial = 0;
    while (trial < 20 &&
           std::chrono::steady_clock::now() - start < std::chrono::milliseconds(1500)) {
      solver->step();
      ++trial;
    }
    const double per_step =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / trial;
    const double memory = static_cast<double>(scene->particles.bytes()) +
                          static_cast<double>(scene->grid.node_count()) * (sizeof(GridNode) + 1) +
                          4.0 * static_cast<double>(scene->particles.size());
    out << "time step: " << std::setprecision(4) << dt << " s (Courant number "
        << spec.solver.courant_number << ")\n";
    out << "phases: " << spec.phases.size() << ", " << spec.end_time()
        << " s of simulated time at most\n";
    for (const PhaseSpec& phase : spec.phases) {
      out << "  " << phase.name << ": " << how_it_stops(phase) << "\n";
    }
    // An upper bound: a phase that stops at equilibrium or at a penetration usually ends sooner,
    // by how much only running it tells (the progress line's ETA does, from the measured rate).
    out << "steps at most: " << std::setprecision(3) << steps << " (at the first step's size)\n";
    out << "run time at most: " << std::setprecision(3) << steps * per_step << " s ("
        << per_step * 1e3 << " ms per step measured over " << trial << " steps)\n";
    out << "estimated memory: " << std::setprecision(3) << memory / 1048576.0 << " MiB ("
        << std::setprecision(0) << std::fixed
        << memory / static_cast<double>(scene->particles.size()) << " bytes per particle)\n";
  } catch (const CaseError& e) {
    err << "mpile: " << e.what() << '\n';
    return exit_bad_input;
  } catch (const std::exception& e) {
    err << "mpile: " << spec.file << ": " << e.what() << '\n';
    return exit_bad_input;
  }
  return options.pilot_seconds > 0.0 ? run_pilot(options, spec, start_up, out, err) : exit_success;
}

} // namespace mpile
