#include "app/progress_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iomanip>
#include <sstream>

namespace mpile {

namespace {

/// Samples closer than this in wall time (s) replace one another, and at most max_samples are kept
/// (every other dropped when there are more): a long phase costs no more than a short one.
constexpr double sample_gap = 0.02;
constexpr std::size_t max_samples = 512;
/// The equilibrium checks a trend is fitted to (one every 20 steps).
constexpr std::size_t trend_checks = 8;
/// Wall time (s) the later half of a phase must span before its own rate replaces the previous
/// phase's.
constexpr double own_rate_after = 0.5;
/// A range closer than this ratio is shown as one number.
constexpr double one_number = 1.25;

} // namespace

std::string format_eta(const EtaEstimate& eta) {
  std::ostringstream s;
  s << "ETA " << std::fixed << std::setprecision(0);
  if (!eta.known) {
    s << "-";
  } else if (eta.bound) {
    s << "<= " << eta.high << " s";
  } else if (eta.high <= one_number * eta.low || eta.high - eta.low < 1.0) {
    s << eta.high << " s";
  } else {
    s << eta.low << " to " << eta.high << " s";
  }
  return s.str();
}

void ProgressEstimator::observe(const std::string& phase, long steps, const PhaseGoal& goal,
                                double wall) {
  if (phase != phase_) {
    if (samples_.size() >= 2 && samples_.back().steps > samples_.front().steps &&
        samples_.back().time > samples_.front().time) {
      const Sample& a = samples_.front();
      const Sample& b = samples_.back();
      previous_per_step_ = (b.wall - a.wall) / static_cast<double>(b.steps - a.steps);
      previous_per_second_ = (b.wall - a.wall) / (b.time - a.time);
    }
    phase_ = phase;
    samples_.clear();
    checks_.clear();
  }
  goal_ = goal;
  if (!std::isnan(goal.equilibrium) && goal.equilibrium > 0.0) {
    checks_.push_back({steps, std::log(goal.equilibrium)});
    if (checks_.size() > trend_checks) {
      checks_.erase(checks_.begin());
    }
  }
  const Sample sample{wall, steps, goal.time, goal.value};
  const std::size_t n = samples_.size();
  if (n >= 2 && samples_[n - 1].wall - samples_[n - 2].wall < sample_gap) {
    samples_.back() = sample; // the latest always stands for now
  } else {
    samples_.push_back(sample);
  }
  if (samples_.size() > max_samples) {
    std::vector<Sample> kept;
    for (std::size_t i = 0; i + 1 < samples_.size(); i += 2) {
      kept.push_back(samples_[i]);
    }
    kept.push_back(samples_.back());
    samples_ = std::move(kept);
  }
}

void ProgressEstimator::rates(double& per_second, double& per_step) const {
  per_second = 0.0;
  per_step = 0.0;
  const Sample& first = samples_.front();
  const Sample& last = samples_.back();
  // The later half of the phase in simulated time.
  std::size_t from = 0;
  while (from + 1 < samples_.size() && samples_[from].time < 0.5 * (first.time + last.time)) {
    ++from;
  }
  from = std::min(from, samples_.size() >= 2 ? samples_.size() - 2 : 0);
  const Sample& a = samples_[from];
  const bool own = last.steps > a.steps && last.time > a.time &&
                   (last.wall - a.wall >= own_rate_after || !(previous_per_step_ > 0.0));
  if (own) {
    per_second = (last.wall - a.wall) / (last.time - a.time);
    per_step = (last.wall - a.wall) / static_cast<double>(last.steps - a.steps);
    return;
  }
  if (!(previous_per_step_ > 0.0)) {
    return;
  }
  // The previous phase's cost of a step, at this phase's step where it has made one.
  per_step = previous_per_step_;
  per_second = previous_per_second_;
  if (last.steps > first.steps && last.time > first.time) {
    per_second =
        per_step * static_cast<double>(last.steps - first.steps) / (last.time - first.time);
  }
}

EtaEstimate ProgressEstimator::estimate() const {
  EtaEstimate eta;
  if (samples_.empty()) {
    return eta;
  }
  double per_second = 0.0;
  double per_step = 0.0;
  rates(per_second, per_step);
  if (!(per_second > 0.0)) {
    return eta;
  }
  eta.known = true;
  const double to_end = std::max(goal_.end_time - goal_.time, 0.0) * per_second;
  const bool timed = goal_.quantity == "t";
  double low = to_end;
  double high = to_end;
  bool estimated = false;
  const auto consider = [&](double l, double h) {
    low = std::min(low, l);
    high = std::min(high, h);
    estimated = true;
  };
  // The goal's quantity: a quadratic fitted over the later half of the phase (simulated time)
  // gives its speed and acceleration now.
  if (!timed) {
    const Sample& first = samples_.front();
    const Sample& last = samples_.back();
    const double span = 0.5 * (last.time - first.time);
    double s[5] = {0, 0, 0, 0, 0}; // sums of x^k
    double r[3] = {0, 0, 0};       // sums of y x^k
    std::size_t count = 0;
    for (const Sample& p : samples_) {
      if (span > 0.0 && p.time >= last.time - span) {
        const double x = (p.time - last.time) / span;
        const double y = p.value - last.value;
        double xk = 1.0;
        for (int k = 0; k < 5; ++k) {
          s[k] += xk;
          if (k < 3) {
            r[k] += y * xk;
          }
          xk *= x;
        }
        ++count;
      }
    }
    if (count >= 3) {
      // Normal equations of y = c0 + c1 x + c2 x^2, by Cramer's rule.
      const auto det3 = [](double a, double b, double c, double d, double e, double f, double g,
                           double h, double i) {
        return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
      };
      const double d = det3(s[0], s[1], s[2], s[1], s[2], s[3], s[2], s[3], s[4]);
      if (std::abs(d) > 1e-12 * s[0] * s[2] * s[4]) {
        const double c1 = det3(s[0], r[0], s[2], s[1], r[1], s[3], s[2], r[2], s[4]) / d;
        const double c2 = det3(s[0], s[1], r[0], s[1], s[2], r[1], s[2], s[3], r[2]) / d;
        const double speed = c1 / span;                       // per simulated second
        const double acceleration = 2.0 * c2 / (span * span); // per simulated second squared
        const double left = std::max(goal_.target - goal_.value, 0.0);
        if (speed > 0.0) {
          const double at_speed = left / speed;
          const double accelerating =
              acceleration > 0.0
                  ? (-speed + std::sqrt(speed * speed + 2.0 * acceleration * left)) / acceleration
                  : at_speed;
          consider(accelerating * per_second, at_speed * per_second);
        }
      }
    }
  }
  // The equilibrium criterion's ratio, falling about exponentially: its trend over the last checks.
  if (checks_.size() >= 3 && per_step > 0.0) {
    double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    const double n = static_cast<double>(checks_.size());
    const double x0 = static_cast<double>(checks_.back().steps);
    for (const Check& c : checks_) {
      const double x = static_cast<double>(c.steps) - x0;
      sx += x;
      sy += c.log_ratio;
      sxx += x * x;
      sxy += x * c.log_ratio;
    }
    const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    if (slope < 0.0) {
      const double steps = std::max(checks_.back().log_ratio, 0.0) / -slope;
      consider(steps * per_step, steps * per_step);
    }
  }
  eta.bound = !estimated && (!timed || goal_.ends_at_equilibrium);
  eta.low = low;
  eta.high = high;
  return eta;
}

} // namespace mpile
