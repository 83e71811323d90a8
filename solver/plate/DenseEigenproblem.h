#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>

namespace plate {

namespace detail {
// Eigen's GeneralizedSelfAdjointEigenSolver on column-major n×n arrays (DenseEigenproblem.cpp),
// its results read back through pointers: a plain-array interface, so that the instrumented build
// can compile that file apart, without the sanitizers and with Eigen's templates in a namespace of
// their own (solver/CMakeLists.txt) — the solve is the library's code; every read and write of
// our own, the copies below included, stays instrumented.
class DenseEigenSolve {
public:
    DenseEigenSolve(std::ptrdiff_t n, const double* a, const double* b);
    ~DenseEigenSolve();
    DenseEigenSolve(const DenseEigenSolve&) = delete;
    DenseEigenSolve& operator=(const DenseEigenSolve&) = delete;
    bool succeeded() const;
    const double* values() const;  // n, ascending
    const double* vectors() const;  // n × n, column-major, B-orthonormal

private:
    struct Solver;
    std::unique_ptr<Solver> solver_;
};
}  // namespace detail

// The dense symmetric-definite generalized eigenproblem A x = λ B x (A symmetric, B symmetric
// positive definite; the modal analysis of docs/theory.md §4 and the Rayleigh–Ritz step of the
// subspace iteration): every eigenvalue, ascending, and B-orthonormal eigenvectors (Xᵀ B X = I).
// Throws std::invalid_argument unless A and B are square and of one size; false where Eigen's
// solver fails (B not positive definite, no convergence).
inline bool solveDenseEigenproblem(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, Eigen::VectorXd& values,
                                   Eigen::MatrixXd& vectors) {
    if (a.rows() != a.cols() || b.rows() != b.cols() || a.rows() != b.rows())
        throw std::invalid_argument("dense eigenproblem: A is " + std::to_string(a.rows()) + "x" +
                                    std::to_string(a.cols()) + ", B " + std::to_string(b.rows()) + "x" +
                                    std::to_string(b.cols()) + " (both square, of one size)");
    const Eigen::Index n = a.rows();
    const detail::DenseEigenSolve solve(n, a.data(), b.data());
    if (!solve.succeeded()) return false;
    values = Eigen::Map<const Eigen::VectorXd>(solve.values(), n);
    vectors = Eigen::Map<const Eigen::MatrixXd>(solve.vectors(), n, n);
    return true;
}

}  // namespace plate
