#pragma once

#include "cases/case_spec.hpp"
#include "cases/dataset_name.hpp"
#include "io/hdf5_file.hpp"
#include "solver/explicit_solver.hpp"

#include <array>
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>

namespace mpile {

/// history.h5 of a run: extendible series of time, step size, energies and the reactions of every
/// named boundary condition and contact surface (with end resistances, and a CPT's q_c, f_s and
/// R_f), each with a units attribute and /time as their shared dimension scale; the root carries
/// the case text, program version, thread count, wall time and how the run ended. Rows are written
/// at least every two seconds of wall time, and the file is open only while they are written: an
/// interrupted run leaves a readable file, and a reader can open it while the run goes on.
class HistoryWriter {
public:
  /// A new history; with rows > 0, an existing one is reopened and cut to its first rows (restart).
  HistoryWriter(const std::string& path, const CaseSpec& spec, const Scene& scene, int threads,
                std::size_t rows = 0);

  /// Appends a row of the solver's state, with its energy balance (solver.energy_balance()).
  void record(const ExplicitSolver& solver, std::size_t phase, const EnergyBalance& energy);
  /// The table of phases, /phases/<index> with attributes name and start (s), and once the phase
  /// has ended end (s) and ended (why it ended).
  void phase_started(std::size_t index, const std::string& name, double start);
  void phase_ended(std::size_t index, double end, const std::string& why);
  std::size_t rows() const { return rows_; }
  void flush_if_due();
  /// Writes every buffered row to the file now (before a checkpoint counts them).
  void flush();
  /// Writes the closing attributes: wall time, status ("complete", "interrupted", ...) and the
  /// energy residual the run ended with and its peak past the start-up (with its time).
  struct ResidualSummary {
    double final = 0.0;
    double peak = 0.0;
    double peak_time = 0.0;
  };
  void close(double wall_seconds, const std::string& status, const ResidualSummary& residual);
  /// close() after an output failed: where the buffered rows find no room either, they are given
  /// up and the status alone is written into the little room it takes, so that a run stopped by a
  /// full disk does not read as still running. Throws only if even that cannot be written.
  void close_after_failure(double wall_seconds, const std::string& status,
                           const ResidualSummary& residual);

private:
  void write_closing_attributes(Hdf5File& file, double wall_seconds, const std::string& status,
                                const ResidualSummary& residual) const;
  /// Every outlined surface's plan and side areas as attributes and its vertical force over its
  /// plan area (where it has one) as unit_end_resistance; the CPT's series when asked.
  void add_unit_resistances(Hdf5File& file, const CaseSpec& spec, const Scene& scene);
  /// /monitors/<name>/...: the followed particle's id is an attribute, so a restart follows the
  /// same one; a monitor added on a restart starts with NaN rows.
  void add_monitors(Hdf5File& file, const CaseSpec& spec, const Scene& scene);
  /// At most the bytes the file grows by when the buffered rows are written.
  std::size_t growth_bound() const;
  Hdf5Series& series(Hdf5File& file, const std::string& name, const std::string& unit,
                     Hdf5Series::Stored stored = Hdf5Series::Stored::real);
  /// Opens the file with room for `growth` more bytes reserved on the disk (io/reserve_space.hpp),
  /// so that a full disk stops the run before the file is touched, not half way through a row.
  Hdf5File open(std::size_t growth) const;
  /// The root attributes and every series (created, or reopened after a restart).
  void write_header(const CaseSpec& spec, const Scene& scene, int threads, std::size_t rows);

  /// A surface's vertical force over one of its areas (Pa): a unit resistance.
  struct UnitResistance {
    std::string dataset;
    std::size_t pair = 0;
    std::size_t surface = 0;
    double area = 0.0;
    double of(const Scene& scene) const;
  };
  std::vector<UnitResistance> end_resistances_;
  std::optional<std::array<UnitResistance, 2>> cpt_; // q_c, f_s
  struct Monitor {
    std::string group;
    std::int32_t id = 0;
    std::uint16_t material = 0;
    std::optional<std::array<double, 2>> fixed_point; // a fixed monitor's point, else none
    std::vector<std::string> datasets;
  };
  std::vector<Monitor> monitors_;

  std::string path_;
  std::map<std::string, Hdf5Series> series_;
  std::vector<std::string> order_;
  std::size_t rows_ = 0;
  bool reopened_ = false;
  std::chrono::steady_clock::time_point last_flush_;
  // /wall_time: seconds of wall time since the run began, carried on across restarts.
  std::chrono::steady_clock::time_point wall_start_;
  double wall_offset_ = 0.0;
};

} // namespace mpile
