#pragma once
// A sparse SPD matrix factored once and solved many times without allocation (the per-step
// solve with A = M + βΔt²K of (3.6) is the floor of one time step): CHOLMOD's simplicial LLᵀ
// (SparseCholeskyCholmod.cpp), built from the pinned SuiteSparse source on every platform; and a
// symmetric indefinite one as L D Lᵀ in an elimination order given with it (the saddle-point
// matrix of the condensed plate's massless part, CondensedSparse.cpp).
#include <Eigen/Core>
#include <Eigen/Sparse>
#include <memory>
#include <vector>

namespace plate {

// What the symbolic analysis of a pattern knows before any numeric work, with the same
// fill-reducing ordering the factorization uses: the nonzeros of L and the flops of the
// numeric factorization (docs/performance.md, resources).
struct SymbolicFactor {
    long long nonZeros = 0;
    double flops = 0.0;
};

class SparseCholesky {
public:
    // Factors the symmetric matrix (both triangles stored; the lower one is read).
    // Throws std::runtime_error if the matrix is not positive definite.
    explicit SparseCholesky(const Eigen::SparseMatrix<double>& spd);
    // Factors the symmetric (possibly indefinite) matrix as L D Lᵀ without pivoting, eliminating
    // row ordering[k] k-th (CHOLMOD postorders the elimination tree, which keeps every row after
    // those it is coupled to earlier): for matrices whose order keeps each pivot away from zero,
    // such as a saddle point [[K, B], [Bᵀ, 0]] with K SPD, B of full column rank and each
    // multiplier after the rows of its column of B. Throws std::runtime_error on a zero pivot.
    SparseCholesky(const Eigen::SparseMatrix<double>& symmetric, const std::vector<int>& ordering);
    ~SparseCholesky();
    SparseCholesky(const SparseCholesky&) = delete;
    SparseCholesky& operator=(const SparseCholesky&) = delete;

    Eigen::Index size() const { return n_; }
    long long factorNonZeros() const;
    std::vector<int> ordering() const;  // the fill-reducing order: row ordering()[k] eliminated k-th
    std::vector<int> positions() const;  // its inverse: row i eliminated positions()[i]-th

    // The symbolic analysis alone of a symmetric pattern given by its lower triangle in
    // compressed columns (columnStart has n + 1 entries; rows sorted within each column, the
    // diagonal stored). Memory O(nnz), no numeric work. Throws std::bad_alloc when out of memory.
    static SymbolicFactor analyze(Eigen::Index n, const std::vector<int>& columnStart,
                                  const std::vector<int>& rowIndex);

    // x = S^{-1} b. Reuses the backend's workspace: no allocation after the first call.
    // Not for concurrent use of one factor (each plate instance owns its factors).
    void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
    // X = S^{-1} B for a block of right-hand sides at once (one pass over L for the block: the
    // condensation's many solves, CondensedSparse.cpp); the forward sweep skips the rows where the
    // whole block is still zero (unit right-hand sides touch only their elimination-tree paths:
    // fewest when the block's nonzeros are eliminated near each other, positions()).
    // Allocates: for the setup, not the step.
    void solve(const Eigen::MatrixXd& b, Eigen::MatrixXd& x) const;
    // The same in the factor's order, without the permutations: row k of w is row ordering()[k]
    // of B and X (for callers that fill and read a few rows of many, positions()). Only the rows
    // from `from` on are solved (a row's solution needs only the rows eliminated after it); the
    // ones before are left as the forward sweep made them.
    using RowBlock = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    void solveInOrder(RowBlock& w, Eigen::Index from = 0) const;

private:
    struct Workspace;
    void factor(const Eigen::SparseMatrix<double>& symmetric, const std::vector<int>* ordering);
    Eigen::Index n_;
    std::unique_ptr<Workspace> ws_;
};

}  // namespace plate
