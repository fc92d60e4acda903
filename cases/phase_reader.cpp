#include "cases/phase_reader.hpp"

#include <algorithm>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <utility>

namespace mpile {

void read_phases(TomlTable& top, CaseSpec& spec, const RigidNames& declared_rigid) {
  std::set<std::string> names;
  for (TomlTable& table : top.tables("phases")) {
    PhaseSpec phase;
    table.read_into(phase);
    // The name heads the phase's log lines and outputs, and `--set phases.<name>` finds it.
    if (phase.name.empty()) {
      table.fail<PhaseSpec>(&PhaseSpec::name, "a phase needs a name (\"\" names none)");
    }
    if (!names.insert(phase.name).second) {
      table.fail<PhaseSpec>(&PhaseSpec::name, "a phase named '" + phase.name + "' already exists");
    }
    {
      // XPIC replaces the FLIP/PIC blend: the phase may not end up with both.
      const int order = phase.xpic_order.value_or(spec.solver.xpic_order);
      const double flip = phase.flip_fraction.value_or(spec.solver.flip_fraction);
      if (order > 0 && flip != 1.0) {
        table.fail(phase.flip_fraction ? table.key_of(&PhaseSpec::flip_fraction)
                                       : table.key_of(&PhaseSpec::xpic_order),
                   "the phase would run XPIC(" + std::to_string(order) + ") with flip_fraction " +
                       format_number(flip) +
                       ": XPIC replaces the FLIP/PIC blend, so set xpic_order = 0 for a blend or "
                       "leave flip_fraction at 1");
      }
    }
    for (TomlTable& k0 : table.tables("k0")) {
      // One body, or every body of one material (the monopile's three soil bodies).
      const bool by_material = k0.has(k0.key_of(&K0Spec::material));
      if (by_material == k0.has(k0.key_of(&K0Spec::body))) {
        k0.fail(&K0Spec::body, "give either body or material (every body of that material)");
      }
      K0Spec init;
      k0.read_into(init);
      k0.finish();
      const auto named = by_material ? &K0Spec::material : &K0Spec::body;
      const std::string name = init.*named;
      bool found = false;
      for (const BodySpec& body : spec.bodies) {
        if ((by_material ? body.material : body.name) == name) {
          init.body = body.name;
          phase.k0.push_back(init);
          found = true;
        }
      }
      if (!found) {
        k0.fail(named,
                "no body " + std::string(by_material ? "of material '" : "named '") + name + "'");
      }
    }
    if (std::optional<TomlTable> stop = table.optional_table("stop_at")) {
      PenetrationStop s;
      stop->read_into(s);
      check_rigid_body_name(*stop, stop->key_of(&PenetrationStop::body), s.body, spec,
                            declared_rigid, "");
      const std::string& penetration = stop->key_of(&PenetrationStop::penetration);
      const std::string& settlement_key = stop->key_of(&PenetrationStop::settlement);
      const bool settlement = stop->has(settlement_key);
      if (settlement == stop->has(penetration)) {
        stop->fail(penetration, "give either penetration (the total downward displacement) or "
                                "settlement (the displacement since the phase started)");
      }
      if (settlement) {
        // The deepest an earlier phase stops at, plus the settlement: how far the band must go
        // at least (an at-rest stop may overshoot; the run then ends the phase at the travel).
        double before = 0.0;
        for (const PhaseSpec& earlier : spec.phases) {
          if (earlier.stop_at && earlier.stop_at->body == s.body) {
            before = std::max(before, earlier.stop_at->penetration);
          }
        }
        s.penetration = before + s.settlement;
      }
      if (spec.moving_mesh && spec.moving_mesh->travel > 0.0 &&
          s.penetration >= spec.moving_mesh->travel) {
        // Equal is refused too: the phase stops after the step that reaches the depth, and that
        // step has already carried the band past its travel.
        std::ostringstream why;
        if (settlement) {
          why << "with the " << s.penetration - s.settlement
              << " m an earlier phase stops at, reaches the travel of the moving band ("
              << spec.moving_mesh->travel << " m); settle less";
        } else {
          why << "reaches the travel of the moving band (" << spec.moving_mesh->travel
              << " m): below that depth the soil is seeded for coarser cells than the band's, and "
                 "the step that reaches it carries the band past it; stop short of it";
        }
        why << " or raise " << (top.has("monopile") ? "[monopile]" : "[moving_mesh]") << " travel";
        stop->fail(settlement ? settlement_key : penetration, why.str());
      }
      stop->finish();
      phase.stop_at = s;
    }
    if (std::optional<TomlTable> drive = table.optional_table("drive")) {
      PhaseDrive d;
      drive->read_into(d);
      check_rigid_body_name(*drive, drive->key_of(&PhaseDrive::body), d.body, spec, declared_rigid,
                            "");
      d.drive = read_drives(*drive, spec, spec.warnings);
      drive->finish();
      phase.drive = d;
    }
    table.finish();
    spec.phases.push_back(std::move(phase));
  }
  if (spec.phases.empty()) {
    top.missing("phases", "at least one [[phases]] table with a duration");
  }
}

} // namespace mpile
