#include "plate/CondensedSparse.h"

#include <Spectra/SymEigsSolver.h>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "plate/SparseCholesky.h"
#include "plate/Spectrum.h"

namespace plate {

namespace {

// The Ritz pairs' tolerance: Spectra accepts a pair once its residual ‖T φ − μ φ‖ is below it times
// μ; the eigenvalues come out to about its square over the gap (measured: within 1e-13 of the dense
// solution's on 14x5 and 28x10).
constexpr double kRitzTolerance = 1e-12;
// Lanczos vectors beyond the kept modes: as many again, at least 80. 56x20's 100 lowest of 2240
// converge in the first 200 products, no restart (measured: 80 more, 180; 120 more, 220; 50 more, 200
// over 3 restarts); on 250 modes the setup is the same either way (11.3 s with 80 more, 11.5 s with
// 250 more: the restarts cost little, tools/fine_mesh_setup.py).
Eigen::Index lanczosVectors(Eigen::Index kept) { return kept + std::max<Eigen::Index>(80, kept); }

// T = Rᵀ K⁻¹ R as Spectra's operator: one solve with the factor of K per product.
class MassiveFlexibility {
public:
    using Scalar = double;
    MassiveFlexibility(const SparseCholesky& stiffness, const Eigen::SparseMatrix<double>& root)
        : stiffness_(stiffness), root_(root) {}
    Eigen::Index rows() const { return root_.cols(); }
    Eigen::Index cols() const { return root_.cols(); }
    void perform_op(const double* in, double* out) const {
        b_.noalias() = root_ * Eigen::Map<const Eigen::VectorXd>(in, root_.cols());
        stiffness_.solve(b_, x_);
        Eigen::Map<Eigen::VectorXd>(out, root_.cols()).noalias() = root_.transpose() * x_;
    }

private:
    const SparseCholesky& stiffness_;
    const Eigen::SparseMatrix<double>& root_;
    mutable Eigen::VectorXd b_, x_;  // Spectra calls perform_op on a const operator
};

// The `kept` largest eigenpairs of T by Spectra's implicitly restarted Lanczos (README: why Spectra),
// from the deterministic start vector (the same bits on every CPU): μ descending, Φ orthonormal.
// T's largest eigenvalues are 1/ω² of the lowest modes, which fall off like 1/i²: the basis
// (q × 2 kept) stays small against the dense T (q × q).
void largestFlexibilities(const SparseCholesky& stiffness, const Eigen::SparseMatrix<double>& root, Eigen::Index kept,
                          Eigen::VectorXd& mu, Eigen::MatrixXd& phi) {
    const Eigen::Index nq = root.cols();
    MassiveFlexibility op(stiffness, root);
    Spectra::SymEigsSolver<MassiveFlexibility> eigs(op, kept, std::min(nq, lanczosVectors(kept)));
    Eigen::VectorXd start(nq);
    for (Eigen::Index i = 0; i < nq; ++i) start[i] = startEntry(i, 0);
    eigs.init(start.data());
    eigs.compute(Spectra::SortRule::LargestAlge, 1000, kRitzTolerance, Spectra::SortRule::LargestAlge);
    if (eigs.info() != Spectra::CompInfo::Successful)
        throw std::runtime_error("the lowest massive modes did not converge (Spectra's Lanczos, " +
                                 std::to_string(eigs.num_iterations()) + " restarts)");
    mu = eigs.eigenvalues();
    phi = eigs.eigenvectors();
}

// The massless flexibility Q0 S⁻¹ Q0ᵀ applied to blocks of right-hand sides (CondensedSparse.h):
// the displacement block of the saddle-point problem's solution,
//
//   [K  R] [w]   [v]
//   [Rᵀ 0] [μ] = [0],     w = Q0 S⁻¹ Q0ᵀ v  (the static response to v with Rᵀw = 0, §17),
//
// one solve per right-hand side with an L D Lᵀ factor of the saddle-point matrix (n + q rows). Its
// order is K's fill-reducing one with each multiplier μ_e right after the last dof of its column of
// R: every pivot is then that of a leading block [[K_EE, R_E], [R_Eᵀ, 0]] with K_EE SPD and R_E of
// full column rank — positive for the dofs, negative for the multipliers, never zero. μ_e's column
// of L is about as long as its last dof's, long where that dof lies on a separator: nnz(L) 1.92 M
// against K's 1.13 M on 56x20 (14 MFlop per right-hand side for three solves with K + ρM_s of the
// augmented Lagrangian iteration it replaces, 7.7 MFlop here, and exact).
class MasslessFlexibility {
public:
    // stiffnessOrder: the fill-reducing order of K's factor.
    MasslessFlexibility(const std::vector<int>& stiffnessOrder, const Eigen::SparseMatrix<double>& k,
                        const Eigen::SparseMatrix<double>& root)
        : n_(k.rows()),
          q_(root.cols()),
          saddle_(saddlePoint(k, root), saddleOrder(stiffnessOrder, root)),
          at_(saddle_.positions()) {}

    // A block of functionals as loads: F (rows `which` of `loads`) in, Q0 S⁻¹ Q0ᵀ Fᵀ solved in the
    // saddle factor's order from row `from` on (SparseCholesky::solveInOrder), read by response().
    void solve(const SparseRows& loads, const std::vector<Eigen::Index>& which, Eigen::Index from = 0) const {
        const auto k = static_cast<Eigen::Index>(which.size());
        w_.setZero(n_ + q_, k);
        for (Eigen::Index j = 0; j < k; ++j)
            for (SparseRows::InnerIterator it(loads, which[std::size_t(j)]); it; ++it)
                w_(at_[std::size_t(it.col())], j) += it.value();
        saddle_.solveInOrder(w_, from);
    }
    // f_i Q0 S⁻¹ Q0ᵀ Fᵀ for the block last solved (1 × block): row i of the functionals f, whose dofs
    // must all be eliminated from the solve's `from` on. Only the rows f_i touches are read: no
    // permutation of the whole block, no n × block displacement.
    template <class Row>
    void response(const SparseRows& f, Eigen::Index i, Row&& out) const {
        out.setZero();
        for (SparseRows::InnerIterator it(f, i); it; ++it) out += it.value() * w_.row(at_[std::size_t(it.col())]);
    }

    // The functionals (rows over the dofs) by where their first dof is eliminated, with that place:
    // blocks of neighbours in this order share most of their forward sweeps' paths, and every later
    // functional lies wholly after an earlier one's first place.
    struct Eliminated {
        int first;
        Eigen::Index row;
        bool operator<(const Eliminated& o) const { return first != o.first ? first < o.first : row < o.row; }
    };
    std::vector<Eliminated> byElimination(const SparseRows& f) const {
        std::vector<Eliminated> order;
        for (Eigen::Index i = 0; i < f.rows(); ++i) {
            int first = static_cast<int>(n_ + q_);
            for (SparseRows::InnerIterator it(f, i); it; ++it) first = std::min(first, at_[std::size_t(it.col())]);
            order.push_back({first, i});
        }
        std::sort(order.begin(), order.end());
        return order;
    }

private:
    // [[K, R], [Rᵀ, 0]], both triangles.
    static Eigen::SparseMatrix<double> saddlePoint(const Eigen::SparseMatrix<double>& k,
                                                   const Eigen::SparseMatrix<double>& root) {
        const Eigen::Index n = k.rows(), q = root.cols();
        std::vector<Eigen::Triplet<double>> entries;
        entries.reserve(static_cast<std::size_t>(k.nonZeros() + 2 * root.nonZeros()));
        for (Eigen::Index j = 0; j < k.outerSize(); ++j)
            for (Eigen::SparseMatrix<double>::InnerIterator it(k, j); it; ++it)
                entries.emplace_back(it.row(), it.col(), it.value());
        for (Eigen::Index e = 0; e < q; ++e)
            for (Eigen::SparseMatrix<double>::InnerIterator it(root, e); it; ++it) {
                entries.emplace_back(it.row(), n + e, it.value());
                entries.emplace_back(n + e, it.row(), it.value());
            }
        Eigen::SparseMatrix<double> a(n + q, n + q);
        a.setFromTriplets(entries.begin(), entries.end());
        return a;
    }
    // K's order with each multiplier after the last of its dofs (a column of R without any: last).
    static std::vector<int> saddleOrder(const std::vector<int>& stiffnessOrder,
                                        const Eigen::SparseMatrix<double>& root) {
        const auto n = static_cast<int>(root.rows()), q = static_cast<int>(root.cols());
        const Eigen::SparseMatrix<double, Eigen::RowMajor> byDof = root;
        std::vector<int> remaining(static_cast<std::size_t>(q)), order;
        order.reserve(static_cast<std::size_t>(n + q));
        for (int e = 0; e < q; ++e) remaining[std::size_t(e)] = static_cast<int>(root.col(e).nonZeros());
        for (int d : stiffnessOrder) {
            order.push_back(d);
            for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(byDof, d); it; ++it)
                if (--remaining[std::size_t(it.col())] == 0) order.push_back(n + static_cast<int>(it.col()));
        }
        for (int e = 0; e < q; ++e)
            if (root.col(e).nonZeros() == 0) order.push_back(n + e);
        return order;
    }

    Eigen::Index n_, q_;
    SparseCholesky saddle_;
    std::vector<int> at_;  // where each row of the saddle point is eliminated
    mutable SparseCholesky::RowBlock w_;  // the block being solved (one instance, one thread: the condensation's)
};

// Right-hand sides per block: one pass over the factor each, (n + q) × kBlock doubles at a time
// (56x20, 100 modes, plate_bench init_only CPU: 16, 2.3-2.6 s; 32, 2.3-2.9 s; 64, 2.0-2.2 s; 128, 2.3 s).
constexpr Eigen::Index kBlock = 64;

}  // namespace

SparseRows constraintRows(const ClampedPlate& plate, const std::vector<ConstraintRow>& extraRows) {
    const auto m = static_cast<Eigen::Index>(plate.contactDofs.size());
    std::vector<Eigen::Triplet<double>> entries;
    for (Eigen::Index i = 0; i < m; ++i) entries.emplace_back(i, plate.contactDofs[std::size_t(i)], 1.0);
    for (std::size_t k = 0; k < extraRows.size(); ++k) {
        const PointProbe& f = extraRows[k].functional;
        for (std::size_t j = 0; j < f.dofs.size(); ++j)
            entries.emplace_back(m + static_cast<Eigen::Index>(k), f.dofs[j], f.coefficients[j]);
    }
    SparseRows c(m + static_cast<Eigen::Index>(extraRows.size()), plate.stiffness.rows());
    c.setFromTriplets(entries.begin(), entries.end());  // sums a probe's repeated dofs
    return c;
}

void condenseSparse(const ClampedPlate& plate, const Eigen::SparseMatrix<double>& root, const SparseRows& rows,
                    Eigen::Index kept, const SparseRows& recovery, CondensedPlate& c) {
    const Eigen::Index r = rows.rows(), nl = recovery.rows();
    std::vector<int> stiffnessOrder;
    {
        const SparseCholesky stiffness(plate.stiffness);
        stiffnessOrder = stiffness.ordering();
        // The lowest modes: T's largest eigenvalues μ = 1/ω², Φ orthonormal; V = K⁻¹ R Φ Ω².
        Eigen::VectorXd mu;
        Eigen::MatrixXd phi;
        largestFlexibilities(stiffness, root, kept, mu, phi);
        if (!(mu[kept - 1] > 0.0)) throw std::runtime_error("the massive flexibility is not positive definite");
        c.omega2 = mu.cwiseInverse();
        Eigen::MatrixXd modes;  // V
        stiffness.solve(Eigen::MatrixXd(root * phi), modes);
        modes *= c.omega2.asDiagonal();
        c.rowModesT = (rows * modes).transpose();
        c.modalLoad = modes.transpose() * plate.pressureLoad;
        c.modalBaseInertia = modes.transpose() * plate.baseInertia;
        c.modalRotationInertia = modes.transpose() * plate.rotationInertia;
        if (nl > 0) c.recoveryModes = recovery * modes;
    }
    // The massless part, every massive mode excluded: D = C Q0 S⁻¹ Q0ᵀ Cᵀ block by block, rows
    // eliminated near each other together (docs/theory.md §17).
    const MasslessFlexibility massless(stiffnessOrder, plate.stiffness, root);
    const std::vector<MasslessFlexibility::Eliminated> order = massless.byElimination(rows);
    // Few recovery functionals (no stress_outputs): D's triangle alone — block b's solve stops at its
    // first row's place, since every later block's rows lie after it (60 % of the full sweeps' work on
    // 112x40, measured) — and the functionals on solves of their own, D being symmetric. Many: they
    // ride on the rows' full solves.
    const bool triangle = 4 * nl <= r;
    Eigen::MatrixXd sortedT(r, r);  // sortedT(j, i) = D(order[i], order[j]) (the triangle: j ≤ i's block)
    if (nl > 0) c.recoveryRows.resize(nl, r);
    std::vector<Eigen::Index> block;
    for (Eigen::Index first = 0; first < r; first += kBlock) {
        const Eigen::Index k = std::min(r - first, kBlock);
        block.clear();
        for (Eigen::Index j = first; j < first + k; ++j) block.push_back(order[std::size_t(j)].row);
        massless.solve(rows, block, triangle ? order[std::size_t(first)].first : 0);
        for (Eigen::Index i = triangle ? first : 0; i < r; ++i)
            massless.response(rows, order[std::size_t(i)].row, sortedT.col(i).segment(first, k).transpose());
        // L's rows are stored row-major: written in the blocks' order, each row permuted below.
        if (!triangle)
            for (Eigen::Index l = 0; l < nl; ++l)
                massless.response(recovery, l, c.recoveryRows.row(l).segment(first, k));
    }
    if (triangle) {
        for (Eigen::Index j = 0; j < r; ++j) sortedT.col(j).tail(r - j - 1) = sortedT.row(j).tail(r - j - 1);
    } else {
        sortedT = 0.5 * (sortedT + sortedT.transpose()).eval();
        Eigen::RowVectorXd sorted;
        for (Eigen::Index l = 0; l < nl; ++l) {
            sorted = c.recoveryRows.row(l);
            for (Eigen::Index j = 0; j < r; ++j) c.recoveryRows(l, order[std::size_t(j)].row) = sorted[j];
        }
    }
    c.delassus.resize(r, r);
    for (Eigen::Index j = 0; j < r; ++j)
        for (Eigen::Index i = 0; i < r; ++i)
            c.delassus(order[std::size_t(i)].row, order[std::size_t(j)].row) = sortedT(j, i);
    if (triangle)  // L Q0 S⁻¹ Q0ᵀ Cᵀ = (C Q0 S⁻¹ Q0ᵀ Lᵀ)ᵀ: the functionals as loads, read at the rows
        for (Eigen::Index first = 0; first < nl; first += kBlock) {
            const Eigen::Index k = std::min(nl - first, kBlock);
            block.clear();
            for (Eigen::Index l = first; l < first + k; ++l) block.push_back(l);
            massless.solve(recovery, block);
            for (Eigen::Index i = 0; i < r; ++i)
                massless.response(rows, i, c.recoveryRows.col(i).segment(first, k).transpose());
        }
    // The load: F as a one-row functional, read by C, by F itself and by the recovery functionals.
    const SparseRows load = plate.pressureLoad.sparseView().transpose();
    massless.solve(load, {0});
    c.rowLoad.resize(r);
    c.recoveryLoad.resize(nl);
    for (Eigen::Index i = 0; i < r; ++i) massless.response(rows, i, c.rowLoad.segment(i, 1));
    for (Eigen::Index l = 0; l < nl; ++l) massless.response(recovery, l, c.recoveryLoad.segment(l, 1));
    Eigen::Matrix<double, 1, 1> flexibility;
    massless.response(load, 0, flexibility);
    c.loadFlexibility = flexibility[0];
}

}  // namespace plate
