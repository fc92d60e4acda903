#include "cases/time_function_reader.hpp"

#include "cases/case_spec.hpp"

#include <stdexcept>
#include <utility>
#include <vector>

namespace mpile {

TimeFunction read_time_function(TomlTable& parent, const std::string& key) {
  const TomlValue& raw = parent.raw(key);
  if (raw.is_floating() || raw.is_integer()) {
    return TimeFunction::constant(parent.number(key));
  }
  TomlTable f = parent.table(key);
  using Keys = TimeFunctionKeys;
  Keys k;
  f.read_members(k, {&Keys::type});
  TimeFunction result;
  try {
    // Each type reads its own keys; another type's is left unread and refused by finish().
    if (k.type == "constant") {
      f.read_members(k, {&Keys::value});
      result = TimeFunction::constant(k.value);
    } else if (k.type == "ramp") {
      f.read_members(k, {&Keys::value, &Keys::duration});
      result = TimeFunction::ramp(k.value, k.duration);
    } else if (k.type == "table") {
      const TomlValue& points = f.raw("points");
      std::vector<std::pair<double, double>> table;
      bool ok = points.is_array() && !points.as_array().empty();
      if (ok) {
        for (const TomlValue& point : points.as_array()) {
          if (!point.is_array() || point.as_array().size() != 2) {
            ok = false;
            break;
          }
          const auto& pair = point.as_array();
          auto number = [&](const TomlValue& v) {
            if (v.is_integer()) {
              return static_cast<double>(v.as_integer());
            }
            if (!v.is_floating()) {
              ok = false;
              return 0.0;
            }
            return v.as_floating();
          };
          table.emplace_back(number(pair[0]), number(pair[1]));
        }
      }
      if (!ok) {
        f.fail("points", "expected [[t0, value0], [t1, value1], ...] with numbers");
      }
      try {
        result = TimeFunction::table(std::move(table));
      } catch (const std::invalid_argument& e) {
        f.fail("points", e.what());
      }
    } else if (k.type == "harmonic") {
      f.read_members(k, {&Keys::amplitude, &Keys::frequency, &Keys::phase, &Keys::mean});
      result = TimeFunction::harmonic(k.amplitude, k.frequency, k.phase, k.mean);
    } else { // "pulse_train", the last of the declared types
      f.read_members(k, {&Keys::amplitude, &Keys::duration, &Keys::interval});
      if (k.interval < k.duration) {
        f.fail(&Keys::interval, "must not be shorter than the pulse duration");
      }
      result = TimeFunction::pulse_train(k.amplitude, k.duration, k.interval);
    }
  } catch (const std::invalid_argument& e) {
    f.fail(&Keys::type, e.what());
  }
  f.finish();
  return result;
}

} // namespace mpile
