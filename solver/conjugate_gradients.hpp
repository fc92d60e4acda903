#pragma once

// A symmetric positive definite sparse system solved by Eigen's conjugate gradients (Jacobi
// preconditioned), the pore pressure's on the grid, with the matrix's product run over the rows in
// parallel: bitwise Eigen's own serial solve, on any number of threads.

#include <Eigen/SparseCore>

namespace mpile::passes {

struct ConjugateGradientResult {
  int iterations = 0;
  double residual = 0.0; // relative to the right-hand side
  bool converged = false;
};

/// Solves a x = b to `tolerance` relative to |b|, starting from x as given.
ConjugateGradientResult solve_conjugate_gradients(const Eigen::SparseMatrix<double>& a,
                                                  const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                                  double tolerance);

} // namespace mpile::passes
