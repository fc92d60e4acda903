#pragma once

#include <iosfwd>
#include <string>

namespace mpile {

struct SweepOptions {
  std::string file;             // the sweep file (TOML)
  std::string output_directory; // empty: out/sweeps/<sweep file stem>
  int cores = 0;                // cores Snakemake may fill with runs; 0: all
  bool prepare = false;         // write the workflow and say how to run it, run nothing
  std::string profile;          // a Snakemake profile (a cluster's submission settings)
  bool strict = false;          // refuse the sweep on any variant's plausibility warning of units
};

/// `mpile sweep`: reads and validates a sweep file, writes its workflow (sweep.toml, Snakefile)
/// into the output directory, runs the variants through Snakemake (a finished variant is not
/// rerun; a failing one does not stop the others) and gathers their histories into results.csv
/// and results.nc with the Python package. Reports every variant that did not finish with the
/// end of its log. Returns an ExitStatus: success only when every variant finished.
int sweep_command(const SweepOptions& options, std::ostream& out, std::ostream& err);

} // namespace mpile
