#pragma once
// The per-step contact problem of (3.6) in the contact space.
//
// The step minimizes ½ wᵀS w − wᵀb over lower ≤ C w ≤ upper, with C picking the vertex
// values and S SPD and factored once (S = A = M + βΔt²K in time, S = K for the initial static
// state). With w_free = S⁻¹b the solution is w = w_free + S⁻¹Cᵀμ, and y = C w solves
//     y = y_free + W μ,  lower ≤ y ≤ upper,  μ ≥ 0 ⊥ y − lower ≥ 0,  μ ≤ 0 ⊥ upper − y ≥ 0,
// with W = C S⁻¹ Cᵀ small, dense, SPD and constant (docs/theory.md). Only the columns of W (and of
// S⁻¹Cᵀ) of vertices that ever touch an obstacle are computed, once, when first needed. A W that is
// already a dense matrix (the condensed schemes') is read in place, possibly as its leading
// count × count block (the rows a contact step can touch, docs/theory.md §24): no copy, no allocation.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <functional>
#include <vector>

namespace plate {

class ContactColumns {
public:
    using ColumnFn = std::function<void(int j, Eigen::VectorXd& z)>;  // z = S⁻¹ Cᵀ e_j
    using GatherFn = std::function<void(const Eigen::VectorXd& z, Eigen::VectorXd& y)>;  // y = C z

    ContactColumns(int count, ColumnFn column, GatherFn gather);
    // W given whole: its columns as they are (column() is not available).
    explicit ContactColumns(const Eigen::MatrixXd& w) : count_(int(w.cols())), dense_(&w) {}

    int count() const { return count_; }
    // Dense W only: from now on W is its leading count × count block (count ≤ its size). The solver
    // reading it must forget its factor when the block's values change (BoxQP::forgetFactor).
    void useLeading(int count) { count_ = count; }
    const Eigen::VectorXd& column(int j) {
        ensure(j);
        return z_[j];
    }
    Eigen::Map<const Eigen::VectorXd> contactColumn(int j) {  // C z_j = W e_j
        if (dense_) return {dense_->col(j).data(), count_};
        ensure(j);
        return {w_[j].data(), w_[j].size()};
    }

private:
    void ensure(int j);
    int count_;
    ColumnFn columnFn_;
    GatherFn gatherFn_;
    std::vector<Eigen::VectorXd> z_, w_;
    const Eigen::MatrixXd* dense_ = nullptr;
};

struct QPResult {
    bool converged = false;
    int iterations = 0;
    double kktResidual = 0.0;  // relative: feasibility, stationarity, sign, complementarity
};

// Contact-space box QP: primal–dual active set (Hintermüller–Ito–Kunisch) warm-started from
// the previous step's set, with a primal active-set method (finite termination for SPD W) as
// the fallback if the PDAS iteration cycles.
class BoxQP {
public:
    // maxPdasIterations = 0 runs the primal active-set method alone (tests check both paths).
    explicit BoxQP(ContactColumns& columns, int maxPdasIterations = 30);

    // state[i]: −1 on the lower bound, +1 on the upper bound, 0 free. In: warm start; out: the
    // solution's set. mu and y are overwritten (mu zero off the active set). The vectors may be
    // longer than count(): the entries past it are not read, and are left as yFree's and zero.
    QPResult solve(const Eigen::VectorXd& yFree, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                   std::vector<signed char>& state, Eigen::VectorXd& mu, Eigen::VectorXd& y);

    // Active indices of the last solution.
    const std::vector<int>& active() const { return active_; }
    // W's values changed (ContactColumns::useLeading): the kept factor no longer holds.
    void forgetFactor() { factoredSet_.clear(); }

private:
    // Solves W_SS μ_S = target_S − yFree_S on the current active list; fills y (all entries).
    // False if W_SS is singular (dependent constraints, possible only for a reduced plate).
    bool solveOnActive(const Eigen::VectorXd& yFree, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                       const std::vector<signed char>& state, Eigen::VectorXd& mu, Eigen::VectorXd& y);
    bool primalActiveSet(const Eigen::VectorXd& yFree, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                         std::vector<signed char>& state, Eigen::VectorXd& mu, Eigen::VectorXd& y, int& iterations);
    double kktResidual(const Eigen::VectorXd& yFree, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                       const std::vector<signed char>& state, const Eigen::VectorXd& mu,
                       const Eigen::VectorXd& y) const;

    ContactColumns& columns_;
    int maxPdasIterations_;
    std::vector<int> active_;
    std::vector<int> factoredSet_;  // the set whose W_SS is factored in wss_
    Eigen::MatrixXd wss_;  // capacity count x count; top-left block in use
    Eigen::VectorXd rhs_;
    Eigen::VectorXd residualOnActive_;  // y_S − target_S before snapping (for the KKT check)
    Eigen::VectorXd yTrial_, current_;  // the primal method's trial and iterate
};

}  // namespace plate
