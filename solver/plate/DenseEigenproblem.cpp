// Eigen's dense generalized eigensolver behind a plain-array interface (DenseEigenproblem.h).
// The instrumented build (PLATEIMPACT_SANITIZE) compiles this file without the sanitizers'
// instrumentation and with -DEigen=<a name of its own>: a library's O(n³) kernel, 85 % of a plate's
// setup under ASan + UBSan (12.7 s of CPU for the default plate against 0.6 s in the release
// build), is then checked no more than libstdc++ is, while the solver's own code and every Eigen
// function it calls stay instrumented — the renamed namespace keeps this file's uninstrumented
// copies of Eigen's templates from standing in for theirs at link time (solver/CMakeLists.txt).
// The release builds compile it as any other file.
#include <Eigen/Eigenvalues>
#include <cstddef>

namespace plate::detail {

bool denseEigenproblem(std::ptrdiff_t n, const double* a, const double* b, double* values, double* vectors) {
    using Matrix = Eigen::MatrixXd;
    const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> eig(Matrix(Eigen::Map<const Matrix>(a, n, n)),
                                                               Matrix(Eigen::Map<const Matrix>(b, n, n)));
    if (eig.info() != Eigen::Success) return false;
    Eigen::Map<Eigen::VectorXd>(values, n) = eig.eigenvalues();
    Eigen::Map<Matrix>(vectors, n, n) = eig.eigenvectors();
    return true;
}

}  // namespace plate::detail
