#include "engine/time_function.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace mpile {

TimeFunction TimeFunction::constant(double value) {
  return TimeFunction(Constant{value});
}

TimeFunction TimeFunction::ramp(double value, double duration) {
  if (!(duration > 0.0)) {
    throw std::invalid_argument("ramp duration must be positive");
  }
  return table({{0.0, 0.0}, {duration, value}});
}

TimeFunction TimeFunction::table(std::vector<std::pair<double, double>> points) {
  if (points.empty()) {
    throw std::invalid_argument("a table needs at least one point");
  }
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (!(points[i].first > points[i - 1].first)) {
      throw std::invalid_argument("table times must be strictly increasing");
    }
  }
  return TimeFunction(Table{std::move(points)});
}

TimeFunction TimeFunction::harmonic(double amplitude, double frequency, double phase, double mean) {
  if (!(frequency > 0.0)) {
    throw std::invalid_argument("harmonic frequency must be positive");
  }
  return TimeFunction(Harmonic{amplitude, frequency, phase, mean});
}

TimeFunction TimeFunction::pulse_train(double amplitude, double pulse_duration, double interval) {
  if (!(pulse_duration > 0.0) || !(interval >= pulse_duration)) {
    throw std::invalid_argument("pulse train needs 0 < pulse duration <= interval");
  }
  return TimeFunction(PulseTrain{amplitude, pulse_duration, interval});
}

namespace {

// Integral of a piecewise-linear table from its first time to t (t may precede it).
double table_primitive(const std::vector<std::pair<double, double>>& p, double t) {
  if (t <= p.front().first) {
    return p.front().second * (t - p.front().first);
  }
  double sum = 0.0;
  for (std::size_t i = 1; i < p.size(); ++i) {
    const auto [t0, v0] = p[i - 1];
    const auto [t1, v1] = p[i];
    if (t <= t1) {
      const double v = v0 + (v1 - v0) * (t - t0) / (t1 - t0);
      return sum + 0.5 * (v0 + v) * (t - t0);
    }
    sum += 0.5 * (v0 + v1) * (t1 - t0);
  }
  return sum + p.back().second * (t - p.back().first);
}

} // namespace

std::optional<double> TimeFunction::period() const {
  if (const auto* h = std::get_if<Harmonic>(&function_); h != nullptr && h->frequency > 0.0) {
    return 1.0 / h->frequency;
  }
  if (const auto* p = std::get_if<PulseTrain>(&function_); p != nullptr && p->interval > 0.0) {
    return p->interval;
  }
  return std::nullopt;
}

TimeFunction TimeFunction::starting_at(double start) const {
  TimeFunction shifted = *this;
  shifted.start_ = start;
  return shifted;
}

double TimeFunction::value(double t) const {
  return t < start_ ? 0.0 : local_value(t - start_);
}

double TimeFunction::primitive(double t) const {
  return t < start_ ? 0.0 : local_primitive(t - start_);
}

double TimeFunction::local_value(double t) const {
  return std::visit(
      [t](const auto& f) -> double {
        using T = std::decay_t<decltype(f)>;
        if constexpr (std::is_same_v<T, Constant>) {
          return f.value;
        } else if constexpr (std::is_same_v<T, Table>) {
          const auto& p = f.points;
          if (t <= p.front().first) {
            return p.front().second;
          }
          for (std::size_t i = 1; i < p.size(); ++i) {
            if (t <= p[i].first) {
              const auto [t0, v0] = p[i - 1];
              const auto [t1, v1] = p[i];
              return v0 + (v1 - v0) * (t - t0) / (t1 - t0);
            }
          }
          return p.back().second;
        } else if constexpr (std::is_same_v<T, Harmonic>) {
          return f.mean +
                 f.amplitude * std::sin(2.0 * std::numbers::pi * f.frequency * t + f.phase);
        } else {
          const double local = std::fmod(t, f.interval);
          return t >= 0.0 && local <= f.duration
                     ? f.amplitude * std::sin(std::numbers::pi * local / f.duration)
                     : 0.0;
        }
      },
      function_);
}

double TimeFunction::local_primitive(double t) const {
  return std::visit(
      [t](const auto& f) -> double {
        using T = std::decay_t<decltype(f)>;
        if constexpr (std::is_same_v<T, Constant>) {
          return f.value * t;
        } else if constexpr (std::is_same_v<T, Table>) {
          return table_primitive(f.points, t) - table_primitive(f.points, 0.0);
        } else if constexpr (std::is_same_v<T, Harmonic>) {
          const double w = 2.0 * std::numbers::pi * f.frequency;
          return f.mean * t + f.amplitude / w * (std::cos(f.phase) - std::cos(w * t + f.phase));
        } else {
          if (t <= 0.0) {
            return 0.0;
          }
          const double pulse_area = 2.0 * f.amplitude * f.duration / std::numbers::pi;
          const double pulses = std::floor(t / f.interval);
          const double local = t - pulses * f.interval;
          const double partial = local < f.duration
                                     ? f.amplitude * f.duration / std::numbers::pi *
                                           (1.0 - std::cos(std::numbers::pi * local / f.duration))
                                     : pulse_area;
          return pulses * pulse_area + partial;
        }
      },
      function_);
}

double TimeFunction::mean(double t0, double t1) const {
  if (!(t1 > t0)) {
    return value(t0);
  }
  return (primitive(t1) - primitive(t0)) / (t1 - t0);
}

} // namespace mpile
