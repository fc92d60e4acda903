#include "app/verify_command.hpp"

#include <iomanip>
#include <ostream>
#include <stdexcept>

namespace mpile {

int run_verification(const std::vector<std::string>& ids, const verification::Options& options,
                     std::ostream& out, bool csv) {
  std::vector<const verification::Case*> cases;
  for (const std::string& id : ids) {
    if (id == "all") {
      for (const auto& c : verification::all_cases()) {
        cases.push_back(&c);
      }
    } else if (const auto* c = verification::find_case(id)) {
      cases.push_back(c);
    } else {
      throw std::invalid_argument("unknown verification case '" + id +
                                  "' (see mpile verify --list)");
    }
  }
  int failed = 0;
  if (csv) {
    out << "case,quantity,measured,reference,unit,error,tolerance,particles,steps,wall_seconds\n";
  }
  for (const auto* c : cases) {
    const verification::Report report = c->run(options);
    failed += report.passed() ? 0 : 1;
    if (csv) {
      out << std::setprecision(10);
      for (const verification::Check& check : report.checks) {
        out << report.id << ",\"" << check.quantity << "\"," << check.measured << ','
            << check.reference << ",\"" << check.unit << "\"," << check.error() << ','
            << check.tolerance << ',' << report.particles << ',' << report.steps << ','
            << report.wall_seconds << '\n';
      }
      continue;
    }
    out << report.id << "  " << report.title << "  (" << report.particles << " particles, "
        << report.steps << " steps, " << std::fixed << std::setprecision(2) << report.wall_seconds
        << " s)\n";
    for (const std::string& warning : report.warnings) {
      out << "    warning: " << warning << '\n';
    }
    for (const verification::Check& check : report.checks) {
      out << "    " << (check.passed() ? "ok  " : "FAIL") << "  " << std::left << std::setw(62)
          << check.quantity << std::right << std::scientific << std::setprecision(5)
          << std::setw(13) << check.measured << "  ref " << std::setw(13) << check.reference << "  "
          << check.unit << "  error " << std::setprecision(2) << std::setw(9) << check.error()
          << " (tol " << check.tolerance << ")\n";
    }
    out.unsetf(std::ios::floatfield);
  }
  if (csv) {
    return failed;
  }
  out << (cases.size() - static_cast<std::size_t>(failed)) << " of " << cases.size()
      << " verification cases within tolerance\n";
  return failed;
}

} // namespace mpile
