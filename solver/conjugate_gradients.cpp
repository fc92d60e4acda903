#include "solver/conjugate_gradients.hpp"

#include <Eigen/IterativeLinearSolvers>

namespace mpile::passes {

ConjugateGradientResult solve_conjugate_gradients(const Eigen::SparseMatrix<double>& a,
                                                  const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                                  double tolerance) {
  // Both triangles are stored, so the product needs no symmetric view.
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> solver;
  solver.setTolerance(tolerance);
  solver.compute(a);
  x = solver.solveWithGuess(b, x);
  return {.iterations = static_cast<int>(solver.iterations()),
          .residual = solver.error(),
          .converged = solver.info() == Eigen::Success && x.allFinite()};
}

} // namespace mpile::passes
