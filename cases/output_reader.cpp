#include "cases/output_reader.hpp"

#include "engine/structures/contact.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace mpile {

namespace {

/// [output.cpt]: the cone and sleeve must be surfaces of a structure's outline with the areas
/// their resistances are quoted over.
OutputSpec::Cpt read_cpt_output(TomlTable& table, const CaseSpec& spec) {
  OutputSpec::Cpt cpt;
  std::vector<std::string> outlined;
  for (const ContactSpec& c : spec.contacts) {
    if (c.outline) {
      outlined.push_back(c.structure);
    }
  }
  table.read_into(cpt);
  if (!table.has(&OutputSpec::Cpt::body)) {
    cpt.body = outlined.size() == 1 ? outlined[0] : "";
  }
  table.finish(); // a misspelt key is named before what its absence caused
  // "" marks an edge that is no contact surface: a cone named so would read the force on none.
  for (std::string OutputSpec::Cpt::*surface : {&OutputSpec::Cpt::cone, &OutputSpec::Cpt::sleeve}) {
    if ((cpt.*surface).empty()) {
      table.fail(surface, "names no surface (\"\" marks an edge that is no contact surface)");
    }
  }
  if (spec.mode != GeometryMode::axisymmetric) {
    table.fail(&OutputSpec::Cpt::cone, "a cone penetration test is axisymmetric: set geometry to "
                                       "\"axisymmetric\"");
  }
  const auto contact = std::find_if(spec.contacts.begin(), spec.contacts.end(),
                                    [&](const ContactSpec& c) { return c.structure == cpt.body; });
  if (contact == spec.contacts.end() || !contact->outline) {
    table.fail(&OutputSpec::Cpt::body,
               "must name the contact structure that is the cone, with outline normals" +
                   std::string(cpt.body.empty() ? "" : " (got '" + cpt.body + "')"));
  }
  if (cpt.cone == cpt.sleeve) {
    table.fail(&OutputSpec::Cpt::sleeve,
               "must be another surface than the cone's ('" + cpt.cone + "')");
  }
  // Surface 0 is the cone, 1 the sleeve, -1 every other edge.
  std::vector<int> edges;
  for (const std::string& name : contact->surfaces) {
    edges.push_back(name == cpt.cone ? 0 : name == cpt.sleeve ? 1 : -1);
  }
  const BodySpec& body = *std::find_if(spec.bodies.begin(), spec.bodies.end(),
                                       [&](const BodySpec& b) { return b.name == cpt.body; });
  const std::vector<SurfaceAreas> areas =
      surface_areas(region_outline(body.region, spec.mode, edges), 2, spec.mode);
  if (!(areas[0].plan > 0.0)) {
    table.fail(&OutputSpec::Cpt::cone,
               "'" + cpt.cone + "' is no surface of '" + cpt.body +
                   "' with a plan area (its horizontal projection, over which q_c is "
                   "quoted)");
  }
  if (!(areas[1].side > 0.0)) {
    table.fail(&OutputSpec::Cpt::sleeve,
               "'" + cpt.sleeve + "' is no surface of '" + cpt.body +
                   "' with a side area (its vertical projection, over which f_s is "
                   "quoted)");
  }
  return cpt;
}

MonitorSpec read_monitor(TomlTable& table, const GradedAxis& r_axis, const GradedAxis& y_axis,
                         const CaseSpec& spec, const std::vector<MonitorSpec>& earlier) {
  MonitorSpec monitor;
  table.read_into(monitor); // its name and particle
  const bool dataset_safe =
      !monitor.name.empty() && std::all_of(monitor.name.begin(), monitor.name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
      });
  if (!dataset_safe) {
    table.fail(&MonitorSpec::name, "use letters, digits and underscores (it names "
                                   "/monitors/<name> in history.h5)");
  }
  for (const MonitorSpec& other : earlier) {
    if (other.name == monitor.name) {
      table.fail(&MonitorSpec::name, "another monitor is named '" + monitor.name + "'");
    }
  }
  const std::string& particle = table.key_of(&MonitorSpec::particle);
  if (table.has("position") == table.has(particle)) {
    table.fail("position", "give either position = [r, y] (the soil particle nearest it at the "
                           "start) or particle = <id>");
  }
  const std::string key = monitor.particle ? particle : "position";
  if (!monitor.particle) {
    const std::vector<double> at = table.numbers("position", 2);
    if (!(at[0] >= r_axis.start() && at[0] <= r_axis.end() && at[1] >= y_axis.start() &&
          at[1] <= y_axis.end())) {
      table.fail("position", "lies outside the grid");
    }
    monitor.position = std::array<double, 2>{at[0], at[1]};
  } else if (*monitor.particle > std::numeric_limits<std::int32_t>::max()) {
    table.fail(particle,
               "must be a particle id (0 or more), got " + std::to_string(*monitor.particle));
  }
  if (monitor.fixed && monitor.particle) {
    table.fail(table.key_of(&MonitorSpec::fixed),
               "a fixed monitor is a point in space: give position = [r, y], not particle");
  }
  if (table.has(&MonitorSpec::material) && monitor.material.empty()) {
    table.fail(&MonitorSpec::material, "names no material (leave it out for the one nearest "
                                       "position at the start)");
  }
  if (!monitor.material.empty()) {
    if (!monitor.fixed) {
      table.fail(&MonitorSpec::material,
                 "names the material of a fixed monitor (fixed = true); a followed one reads its "
                 "particle's");
    }
    // Only a deformable body's particles carry the stress and state a monitor records.
    const bool soil = std::any_of(spec.bodies.begin(), spec.bodies.end(), [&](const BodySpec& b) {
      return b.material == monitor.material && !b.rigid;
    });
    if (!soil) {
      table.fail(&MonitorSpec::material, "no body that is not rigid is made of a material named '" +
                                             monitor.material + "'");
    }
  }
  monitor.where = table.location(key) + ": " + table.key_path(key);
  table.finish();
  return monitor;
}

} // namespace

void read_output(TomlTable& top, CaseSpec& spec, const GradedAxis& r_axis,
                 const GradedAxis& y_axis) {
  std::optional<TomlTable> table = top.optional_table("output");
  if (!table) {
    return;
  }
  OutputSpec& out = spec.output;
  table->read_into(out);
  table->check_path(&OutputSpec::directory, out.directory);
  out.snapshot_times = table->numbers_or("snapshot_times", {});
  for (const double t : out.snapshot_times) {
    if (t < 0.0) {
      table->fail("snapshot_times", "times must not be negative");
    }
  }
  out.snapshot_penetrations = table->numbers_or("snapshot_penetrations", {});
  if (!out.snapshot_penetrations.empty()) {
    for (const double depth : out.snapshot_penetrations) {
      if (!(depth > 0.0)) {
        table->fail("snapshot_penetrations", "penetrations must be positive (m)");
      }
    }
    std::sort(out.snapshot_penetrations.begin(), out.snapshot_penetrations.end());
    std::vector<std::string> rigid;
    for (const BodySpec& body : spec.bodies) {
      if (body.rigid) {
        rigid.push_back(body.name);
      }
    }
    if (!table->has(&OutputSpec::penetration_body)) {
      out.penetration_body = rigid.size() == 1 ? rigid[0] : "";
    }
    if (std::find(rigid.begin(), rigid.end(), out.penetration_body) == rigid.end()) {
      table->fail(&OutputSpec::penetration_body,
                  "must name the rigid body whose penetration counts");
    }
  } else if (table->has(&OutputSpec::penetration_body)) {
    table->fail(&OutputSpec::penetration_body,
                "given without snapshot_penetrations, the penetrations it counts");
  }
  if (std::optional<TomlTable> cpt = table->optional_table("cpt")) {
    out.cpt = read_cpt_output(*cpt, spec);
  }
  for (TomlTable& monitor : table->tables("monitor")) {
    out.monitors.push_back(read_monitor(monitor, r_axis, y_axis, spec, out.monitors));
  }
  table->finish();
}

} // namespace mpile
