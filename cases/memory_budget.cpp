#include "cases/memory_budget.hpp"

#include "cases/case_error.hpp"
#include "cases/monopile_geometry.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <sstream>
#include <string>

namespace mpile {

void refuse_past_memory_budget(TomlTable& top, const CaseSpec& spec, const GradedAxis& r_axis,
                               const GradedAxis& y_axis, std::vector<TomlTable>& body_tables) {
  // Per node: the 64-byte node and its constraint mask, per field; a contact pair's arrays take
  // about 100 bytes more. Per particle: its arrays with a Hardening Soil state, about 300 bytes.
  constexpr double node_bytes = 65.0, pair_node_bytes = 100.0, particle_bytes = 300.0;
  const double nodes =
      static_cast<double>(r_axis.node_count()) * static_cast<double>(y_axis.node_count());
  const auto structures = static_cast<double>(spec.contacts.size());
  const double grid_bytes =
      nodes * (node_bytes * (1.0 + structures) + pair_node_bytes * structures);
  // Particles: the cells of each region's bounding box times the particles per cell (an upper
  // bound short of the graded band's extra seeding).
  std::vector<double> body_bytes;
  double particles_bytes = 0.0;
  for (const BodySpec& body : spec.bodies) {
    const Rectangle& box = body.region.bounds();
    auto cells = [](const GradedAxis& axis, double from, double to) {
      const double a = std::max(from, axis.start()), b = std::min(to, axis.end());
      if (!(b > a)) {
        return 0.0;
      }
      const int first = axis.locate(a);
      const int last = b >= axis.end() ? axis.cell_count() - 1 : axis.locate(b);
      return static_cast<double>(last - first + 1);
    };
    const double n = cells(r_axis, box.r_min, box.r_max) * cells(y_axis, box.y_min, box.y_max) *
                     body.particles_per_direction * body.particles_per_direction;
    body_bytes.push_back(n * particle_bytes);
    particles_bytes += body_bytes.back();
  }
  double physical =
      static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGESIZE));
  // A process limited in address space (ulimit -v, a batch system's memory limit) has less: the
  // budget is three quarters of the limit, the rest left to the program, its libraries and the
  // threads' stacks.
  std::string whose = "this machine's";
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY &&
      0.75 * static_cast<double>(limit.rlim_cur) < physical) {
    physical = 0.75 * static_cast<double>(limit.rlim_cur);
    whose = "three quarters of this process's address-space limit,";
  }
  // A budget set for this process (a machine shared with others, or a sanitizer build, whose
  // address space cannot be limited) bounds it further.
  if (const char* budget = std::getenv("MPILE_MEMORY_BUDGET_MIB")) {
    char* end = nullptr;
    const double mib = std::strtod(budget, &end);
    // A budget that does not parse is an error, not no budget: "2MiB" or "0" switched it off
    // without a word.
    if (end == budget || *end != '\0' || !std::isfinite(mib) || !(mib > 0.0)) {
      throw CaseError(top.file() + ": MPILE_MEMORY_BUDGET_MIB = '" + budget +
                      "' is not a memory budget: give a number of MiB above zero (for example "
                      "2048), or unset it for none");
    }
    if (mib * 1048576.0 < physical) {
      physical = mib * 1048576.0;
      whose = "MPILE_MEMORY_BUDGET_MIB's";
    }
  }
  const double total = grid_bytes + particles_bytes;
  if (!(physical > 0.0) || total <= physical) {
    return;
  }
  std::ostringstream why;
  why << std::setprecision(3) << "the case needs about " << total / 1e9 << " GB ("
      << r_axis.cell_count() << " x " << y_axis.cell_count() << " cells: " << grid_bytes / 1e9
      << " GB; particles: " << particles_bytes / 1e9 << " GB), more than " << whose << " "
      << physical / 1e9 << " GB";
  if (grid_bytes >= particles_bytes || grid_bytes > physical) {
    if (top.has("monopile")) {
      top.table("monopile")
          .fail(&MonopileParameters::fine_cell, why.str() + "; check the cell sizes and extents");
    }
    const bool r_larger = r_axis.cell_count() >= y_axis.cell_count();
    top.table("grid").fail(r_larger ? "r" : "y", why.str() + "; check the zones' cells and ends");
  }
  const auto largest = static_cast<std::size_t>(
      std::max_element(body_bytes.begin(), body_bytes.end()) - body_bytes.begin());
  if (largest < body_tables.size()) {
    body_tables[largest].fail("region",
                              why.str() + "; body '" + spec.bodies[largest].name +
                                  "' takes the most: check its region, the cells there and "
                                  "particles_per_cell");
  }
  top.table("monopile").fail(&MonopileSetup::particles_per_cell, why.str());
}

} // namespace mpile
