#pragma once

#include <optional>
#include <utility>
#include <variant>
#include <vector>

namespace mpile {

/// A scalar function of time for loads and prescribed motions, zero before its start time (0 unless
/// moved with starting_at): constant, piecewise-linear table
/// (a ramp is a two-point table), harmonic mean + A sin(2 pi f t + phase) (a vibrator's force about
/// a static load, say), and a train of half-sine pulses
/// (amplitude, pulse duration, interval between pulse starts). Each has an exact integral, so that
/// a prescribed velocity or load applied as its mean over a time step gives the exact displacement
/// or impulse whatever the step size.
class TimeFunction {
public:
  TimeFunction() : TimeFunction(constant(0.0)) {}

  static TimeFunction constant(double value);
  /// Linear from 0 at t = 0 to value at t = duration, then held.
  static TimeFunction ramp(double value, double duration);
  /// Points (t, value) with increasing t; the first value holds before, the last after.
  static TimeFunction table(std::vector<std::pair<double, double>> points);
  static TimeFunction harmonic(double amplitude, double frequency, double phase = 0.0,
                               double mean = 0.0);
  static TimeFunction pulse_train(double amplitude, double pulse_duration, double interval);

  /// The same function started at time start: zero before it, f(t - start) after.
  TimeFunction starting_at(double start) const;
  double start() const { return start_; }

  double value(double t) const;
  /// The period of a harmonic (1 / f) or a pulse train (its interval); none for the others.
  std::optional<double> period() const;
  /// Integral of the function from 0 to t.
  double primitive(double t) const;
  /// Mean value over [t0, t1] (the value at t0 when the interval is empty).
  double mean(double t0, double t1) const;

private:
  struct Constant {
    double value;
  };
  struct Table {
    std::vector<std::pair<double, double>> points;
  };
  struct Harmonic {
    double amplitude, frequency, phase, mean;
  };
  struct PulseTrain {
    double amplitude, duration, interval;
  };
  using Variant = std::variant<Constant, Table, Harmonic, PulseTrain>;
  explicit TimeFunction(Variant function) : function_(std::move(function)) {}

  double local_value(double t) const;
  double local_primitive(double t) const;

  Variant function_;
  double start_ = 0.0;
};

} // namespace mpile
