// SparseCholesky on Eigen's SimplicialLLT (AMD ordering): the same simplicial LLᵀ as the CHOLMOD
// build, header-only, so a binary built with it depends on no sparse library (win64).
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <stdexcept>

#include "SparseCholesky.h"

namespace plate {

namespace {

// SimplicialLLT's analyzePattern keeps the column counts of L (strictly below the diagonal).
class SymbolicLLT : public Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> {
public:
    SymbolicFactor counts() const {
        SymbolicFactor s;
        for (Eigen::Index j = 0; j < m_nonZerosPerCol.size(); ++j) {
            const double c = m_nonZerosPerCol[j] + 1.0;  // with the diagonal
            s.nonZeros += static_cast<long long>(c);
            s.flops += c * c;
        }
        return s;
    }
};

}  // namespace

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

SymbolicFactor SparseCholesky::analyze(Eigen::Index n, const std::vector<int>& columnStart,
                                       const std::vector<int>& rowIndex) {
    const std::vector<double> ones(rowIndex.size(), 1.0);  // Eigen's pattern needs values
    const Eigen::Map<const Eigen::SparseMatrix<double>> lower(n, n, static_cast<Eigen::Index>(rowIndex.size()),
                                                              columnStart.data(), rowIndex.data(), ones.data());
    SymbolicLLT symbolic;
    symbolic.analyzePattern(Eigen::SparseMatrix<double>(lower));
    return symbolic.counts();
}

void SparseCholesky::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
    x.resize(n_);
    x = ws_->factor.solve(b);  // permutations and triangular solves in place in x
}

}  // namespace plate
