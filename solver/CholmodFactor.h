#pragma once
// A sparse SPD matrix factored once with CHOLMOD and solved many times without allocation
// (the per-step solve with A = M + βΔt²K of (3.6) is the floor of one time step).
#include <Eigen/Core>
#include <Eigen/Sparse>
#include <memory>

namespace plate {

class CholmodFactor {
public:
    // Factors the symmetric matrix (both triangles stored; the lower one is read).
    // Throws std::runtime_error if the matrix is not positive definite.
    explicit CholmodFactor(const Eigen::SparseMatrix<double>& spd);
    ~CholmodFactor();
    CholmodFactor(const CholmodFactor&) = delete;
    CholmodFactor& operator=(const CholmodFactor&) = delete;

    Eigen::Index size() const { return n_; }
    long long factorNonZeros() const;
    bool supernodal() const;

    // x = S^{-1} b. Reuses CHOLMOD's workspace: no allocation after the first call.
    // Not for concurrent use of one factor (each plate instance owns its factors).
    void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;

private:
    struct Workspace;
    Eigen::Index n_;
    std::unique_ptr<Workspace> ws_;
};

}  // namespace plate
