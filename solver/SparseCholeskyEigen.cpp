// SparseCholesky on Eigen's SimplicialLLT (AMD ordering): the same simplicial LLᵀ as the CHOLMOD
// build, header-only, so a binary built with it depends on no sparse library (win64).
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <stdexcept>

#include "SparseCholesky.h"

namespace plate {

struct SparseCholesky::Workspace {
    Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> factor;
};

SparseCholesky::SparseCholesky(const Eigen::SparseMatrix<double>& spd)
    : n_(spd.rows()), ws_(std::make_unique<Workspace>()) {
    ws_->factor.compute(spd);
    if (ws_->factor.info() != Eigen::Success) throw std::runtime_error("matrix is not positive definite (Eigen LLT)");
}

SparseCholesky::~SparseCholesky() = default;

long long SparseCholesky::factorNonZeros() const { return ws_->factor.matrixL().nestedExpression().nonZeros(); }

bool SparseCholesky::supernodal() const { return false; }

const char* SparseCholesky::backend() { return "Eigen"; }

void SparseCholesky::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
    x.resize(n_);
    x = ws_->factor.solve(b);  // permutations and triangular solves in place in x
}

}  // namespace plate
