#include "tests/eigen_reference_solve.hpp"

#include <Eigen/IterativeLinearSolvers>

#include <stdexcept>

namespace mpile {

Eigen::VectorXd eigen_conjugate_gradients(const Eigen::SparseMatrix<double>& a,
                                          const Eigen::VectorXd& b, double tolerance,
                                          int& iterations) {
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> solver;
  solver.setTolerance(tolerance);
  solver.compute(a);
  const Eigen::VectorXd x = solver.solveWithGuess(b, Eigen::VectorXd::Zero(b.size()));
  if (solver.info() != Eigen::Success) {
    throw std::runtime_error("Eigen's conjugate gradients did not converge");
  }
  iterations = static_cast<int>(solver.iterations());
  return x;
}

} // namespace mpile
