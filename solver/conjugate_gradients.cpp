#include "solver/conjugate_gradients.hpp"

#include "engine/parallel.hpp"

#include <Eigen/IterativeLinearSolvers>

namespace mpile::passes {
class SymmetricProduct;
} // namespace mpile::passes

namespace Eigen::internal {
// Eigen's matrix-free solvers take an operator with the traits of a sparse matrix.
template <> struct traits<mpile::passes::SymmetricProduct> : traits<Eigen::SparseMatrix<double>> {};
} // namespace Eigen::internal

namespace mpile::passes {

/// A symmetric sparse matrix whose product with a vector runs in parallel over its rows. The
/// conjugate gradients' product is most of the solve, and Eigen's own is serial. Each row is
/// summed as Eigen's row-major product sums it (column i's stored entries in order, the matrix
/// being symmetric with both triangles stored), so the solve is bitwise the one Eigen's own
/// product gives, on any number of threads.
class SymmetricProduct : public Eigen::EigenBase<SymmetricProduct> {
public:
  using Scalar = double;
  using RealScalar = double;
  using StorageIndex = int;
  enum {
    ColsAtCompileTime = Eigen::Dynamic,
    MaxColsAtCompileTime = Eigen::Dynamic,
    IsRowMajor = false
  };

  explicit SymmetricProduct(const Eigen::SparseMatrix<double>& a) : a_(a) {}

  Eigen::Index rows() const { return a_.rows(); }
  Eigen::Index cols() const { return a_.cols(); }
  const Eigen::SparseMatrix<double>& matrix() const { return a_; }

  template <class Rhs>
  Eigen::Product<SymmetricProduct, Rhs, Eigen::AliasFreeProduct>
  operator*(const Eigen::MatrixBase<Rhs>& x) const {
    return Eigen::Product<SymmetricProduct, Rhs, Eigen::AliasFreeProduct>(*this, x.derived());
  }

  /// y += alpha A x.
  template <class Dest, class Rhs> void add_product(Dest& y, const Rhs& x, double alpha) const {
    parallel_for(static_cast<std::size_t>(a_.outerSize()), [&](std::size_t row) {
      const auto i = static_cast<Eigen::Index>(row);
      double sum = 0.0;
      for (Eigen::SparseMatrix<double>::InnerIterator it(a_, i); it; ++it) {
        sum += it.value() * x.coeff(it.index());
      }
      y.coeffRef(i) += alpha * sum;
    });
  }

private:
  const Eigen::SparseMatrix<double>& a_;
};

/// Eigen's Jacobi preconditioner, set up from the matrix the operator wraps.
class JacobiPreconditioner : public Eigen::DiagonalPreconditioner<double> {
public:
  template <class Operator> JacobiPreconditioner& analyzePattern(const Operator&) { return *this; }
  JacobiPreconditioner& factorize(const SymmetricProduct& a) {
    Eigen::DiagonalPreconditioner<double>::factorize(a.matrix());
    return *this;
  }
  JacobiPreconditioner& compute(const SymmetricProduct& a) { return factorize(a); }
};

} // namespace mpile::passes

namespace Eigen::internal {
template <class Rhs>
struct generic_product_impl<mpile::passes::SymmetricProduct, Rhs, SparseShape, DenseShape,
                            GemvProduct>
    : generic_product_impl_base<mpile::passes::SymmetricProduct, Rhs,
                                generic_product_impl<mpile::passes::SymmetricProduct, Rhs>> {
  template <class Dest>
  static void scaleAndAddTo(Dest& y, const mpile::passes::SymmetricProduct& a, const Rhs& x,
                            const double& alpha) {
    a.add_product(y, x, alpha);
  }
};
} // namespace Eigen::internal

namespace mpile::passes {

ConjugateGradientResult solve_conjugate_gradients(const Eigen::SparseMatrix<double>& a,
                                                  const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                                  double tolerance) {
  const SymmetricProduct product(a);
  Eigen::ConjugateGradient<SymmetricProduct, Eigen::Lower | Eigen::Upper, JacobiPreconditioner>
      solver;
  solver.setTolerance(tolerance);
  solver.compute(product);
  x = solver.solveWithGuess(b, x);
  return {.iterations = static_cast<int>(solver.iterations()),
          .residual = solver.error(),
          .converged = solver.info() == Eigen::Success && x.allFinite()};
}

} // namespace mpile::passes
