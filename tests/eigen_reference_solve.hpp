#pragma once

// Eigen's own conjugate gradients (Jacobi preconditioned, its serial product), the reference the
// engine's parallel product is held to bit for bit.

#include <Eigen/SparseCore>

namespace mpile {

/// Solves a x = b from x = 0 to `tolerance` relative to |b|; `iterations` receives Eigen's count.
Eigen::VectorXd eigen_conjugate_gradients(const Eigen::SparseMatrix<double>& a,
                                          const Eigen::VectorXd& b, double tolerance,
                                          int& iterations);

} // namespace mpile
