#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <stdexcept>
#include <string>

namespace plate {

namespace detail {
// Eigen's GeneralizedSelfAdjointEigenSolver on column-major n×n arrays (DenseEigenproblem.cpp): a
// plain-array interface, so that the instrumented build can compile that file apart, with
// Eigen's templates in a namespace of their own (solver/CMakeLists.txt).
bool denseEigenproblem(std::ptrdiff_t n, const double* a, const double* b, double* values, double* vectors);
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
    values.resize(a.rows());
    vectors.resize(a.rows(), a.rows());
    return detail::denseEigenproblem(a.rows(), a.data(), b.data(), values.data(), vectors.data());
}

}  // namespace plate
