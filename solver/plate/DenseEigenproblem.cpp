// Eigen's dense generalized eigensolver behind a plain-array interface (DenseEigenproblem.h).
// The instrumented build (PLATEIMPACT_SANITIZE) compiles this file without the sanitizers'
// instrumentation and with -DEigen=<a name of its own>: a library's O(n³) kernel, 85 % of a plate's
// setup under ASan + UBSan (12.7 s of CPU for the default plate against 0.6 s in the release
// build), is then checked no more than libstdc++ is, while the solver's own code and every Eigen
// function it calls stay instrumented — the renamed namespace keeps this file's uninstrumented
// copies of Eigen's templates from standing in for theirs at link time (solver/CMakeLists.txt).
// Nothing here but the solve: the caller checks the sizes and copies the results out
// (DenseEigenproblem.h), instrumented. The release builds compile it as any other file.
#include "plate/DenseEigenproblem.h"

#include <Eigen/Eigenvalues>

namespace plate::detail {

struct DenseEigenSolve::Solver {
    Solver(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) : eig(a, b) {}
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig;
};

DenseEigenSolve::DenseEigenSolve(std::ptrdiff_t n, const double* a, const double* b)
    : solver_(std::make_unique<Solver>(Eigen::Map<const Eigen::MatrixXd>(a, n, n),
                                       Eigen::Map<const Eigen::MatrixXd>(b, n, n))) {}

DenseEigenSolve::~DenseEigenSolve() = default;

bool DenseEigenSolve::succeeded() const { return solver_->eig.info() == Eigen::Success; }
const double* DenseEigenSolve::values() const { return solver_->eig.eigenvalues().data(); }
const double* DenseEigenSolve::vectors() const { return solver_->eig.eigenvectors().data(); }

}  // namespace plate::detail
