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
      const auto rows = f.number_rows("points", 2);
      if (!rows) {
        f.fail("points", "expected [[t0, value0], [t1, value1], ...] with numbers");
      }
      std::vector<std::pair<double, double>> table;
      for (const std::vector<double>& row : *rows) {
        table.emplace_back(row[0], row[1]);
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
