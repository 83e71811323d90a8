#pragma once
// A sparse SPD matrix factored once and solved many times without allocation (the per-step
// solve with A = M + βΔt²K of (3.6) is the floor of one time step): CHOLMOD's simplicial LLᵀ
// (SparseCholeskyCholmod.cpp), built from the pinned SuiteSparse source on every platform.
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
    ~SparseCholesky();
    SparseCholesky(const SparseCholesky&) = delete;
    SparseCholesky& operator=(const SparseCholesky&) = delete;

    Eigen::Index size() const { return n_; }
    long long factorNonZeros() const;
    bool supernodal() const;
    static const char* backend();  // "CHOLMOD" or "Eigen"

    // The symbolic analysis alone of a symmetric pattern given by its lower triangle in
    // compressed columns (columnStart has n + 1 entries; rows sorted within each column, the
    // diagonal stored). Memory O(nnz), no numeric work. Throws std::bad_alloc when out of memory.
    static SymbolicFactor analyze(Eigen::Index n, const std::vector<int>& columnStart,
                                  const std::vector<int>& rowIndex);

    // x = S^{-1} b. Reuses the backend's workspace: no allocation after the first call.
    // Not for concurrent use of one factor (each plate instance owns its factors).
    void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
    // X = S^{-1} B for a block of right-hand sides at once (one pass over L per four columns: the
    // condensation's many solves, CondensedSparse.cpp). Allocates: for the setup, not the step.
    void solve(const Eigen::MatrixXd& b, Eigen::MatrixXd& x) const;

private:
    struct Workspace;
    Eigen::Index n_;
    std::unique_ptr<Workspace> ws_;
};

}  // namespace plate
