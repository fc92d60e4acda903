#include "solver/element_point.hpp"

#include <Eigen/QR>

#include <cmath>
#include <stdexcept>
#include <string>

namespace mpile {

ElementPoint::ElementPoint(const Material& material, const Stress& initial_stress,
                           const std::vector<std::pair<std::size_t, double>>& state_overrides)
    : material_(&material), stress_(initial_stress), state_(material.state_size(), 0.0) {
  material.initialise_state(stress_, state_.data());
  for (const auto& [index, value] : state_overrides) {
    state_.at(index) = value;
  }
}

Stress ElementPoint::trial(const StrainIncrement& strain, std::vector<double>& state) const {
  state = state_;
  Stress stress = stress_;
  update_single_point(*material_, stress, state.empty() ? nullptr : state.data(), strain);
  return stress;
}

void ElementPoint::apply(const MixedIncrement& increment) {
  std::vector<std::size_t> unknown;
  StrainIncrement de{};
  for (std::size_t c = 0; c < 6; ++c) {
    if (increment.stress_controlled[c]) {
      unknown.push_back(c);
      de[c] = previous_[c]; // a steady path repeats its last increment
    } else {
      de[c] = increment.value[c];
    }
  }
  std::vector<double> state;
  Stress stress = trial(de, state);
  iterations_ = 0;
  if (!unknown.empty()) {
    const auto n = static_cast<Eigen::Index>(unknown.size());
    auto residual = [&](const Stress& s) {
      Eigen::VectorXd r(n);
      for (Eigen::Index i = 0; i < n; ++i) {
        const std::size_t c = unknown[static_cast<std::size_t>(i)];
        r(i) = s[c] - increment.value[c];
      }
      return r;
    };
    // Stresses are met to 1e-12 of their size: far below anything a closed form is compared
    // with, yet well above the rounding of a material update (a few 1e-16). When rounding stops
    // the iterations first, 1e-9 of the size is still accepted.
    double size = 1.0;
    for (std::size_t c = 0; c < 6; ++c) {
      size = std::max({size, std::abs(stress_[c]), std::abs(increment.value[c])});
    }
    const double tolerance = 1e-12 * size;
    const double acceptable = 1e-9 * size;
    constexpr int max_iterations = 50;
    Eigen::VectorXd r = residual(stress);
    double norm = r.lpNorm<Eigen::Infinity>();
    while (norm > tolerance) {
      if (iterations_ == max_iterations) {
        std::ostringstream message;
        message << "the stress-controlled components did not converge in " << max_iterations
                << " iterations (residual " << norm << " Pa); the target may lie beyond what "
                << "the material can carry";
        throw std::runtime_error(message.str());
      }
      ++iterations_;
      // Forward differences: a step small next to the increment, so that the tangent is the one
      // on the side the increment goes (an elastic-plastic response has kinks), yet large enough
      // that the rounding of the stress stays small in the quotient.
      double strain_size = 0.0;
      for (const double v : de) {
        strain_size = std::max(strain_size, std::abs(v));
      }
      const double h = std::max(1e-9, 1e-6 * strain_size);
      Eigen::MatrixXd jacobian(n, n);
      std::vector<double> scratch;
      for (Eigen::Index j = 0; j < n; ++j) {
        StrainIncrement perturbed = de;
        perturbed[unknown[static_cast<std::size_t>(j)]] += h;
        jacobian.col(j) = (residual(trial(perturbed, scratch)) - r) / h;
      }
      // Minimum-norm step: on an edge of a perfectly plastic surface the tangent is singular
      // (sigma_rr and sigma_thth of a triaxial sample at failure can only move together), yet the
      // symmetric target is still reachable along the directions the tangent keeps.
      Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> decomposition;
      decomposition.setThreshold(1e-9);
      decomposition.compute(jacobian);
      if (decomposition.rank() == 0) {
        throw std::runtime_error("the material has no stiffness left in a stress-controlled "
                                 "direction; the target lies beyond what it can carry");
      }
      const Eigen::VectorXd step = decomposition.solve(-r);
      // Backtracking keeps Newton from overshooting across a kink of the response.
      double fraction = 1.0;
      bool improved = false;
      for (int halving = 0; halving < 40 && !improved; ++halving, fraction *= 0.5) {
        StrainIncrement candidate = de;
        for (Eigen::Index j = 0; j < n; ++j) {
          candidate[unknown[static_cast<std::size_t>(j)]] += fraction * step(j);
        }
        std::vector<double> candidate_state;
        const Stress candidate_stress = trial(candidate, candidate_state);
        const Eigen::VectorXd candidate_residual = residual(candidate_stress);
        const double candidate_norm = candidate_residual.lpNorm<Eigen::Infinity>();
        if (candidate_norm < norm) {
          de = candidate;
          stress = candidate_stress;
          state = std::move(candidate_state);
          r = candidate_residual;
          norm = candidate_norm;
          improved = true;
        }
      }
      if (!improved && norm <= acceptable) {
        break;
      }
      if (!improved) {
        std::ostringstream message;
        message << "the stress-controlled components stopped converging (residual " << norm
                << " Pa); the target may lie beyond what the material can carry";
        throw std::runtime_error(message.str());
      }
    }
  }
  // A stiffness near the largest double overflows the update: its NaN stresses were written to
  // the end of the path with exit status 0.
  for (const double component : stress) {
    if (!std::isfinite(component)) {
      throw std::runtime_error("the stress is not finite (a stiffness or strength beyond what a "
                               "double carries); check the material's parameters");
    }
  }
  stress_ = stress;
  state_ = std::move(state);
  for (std::size_t c = 0; c < 6; ++c) {
    strain_[c] += de[c];
  }
  previous_ = de;
}

} // namespace mpile
