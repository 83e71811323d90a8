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
// the augmented Lagrangian iteration on the factor of K_ρ = K + ρ M_s.
class MasslessFlexibility {
public:
    MasslessFlexibility(const Eigen::SparseMatrix<double>& stiffness, const Eigen::SparseMatrix<double>& root)
        : root_(root), rho_(penalty(stiffness, root)), augmented_(augment(stiffness, root, rho_)) {}

    // X = Q0 S⁻¹ Q0ᵀ V. Each solve gives x for the current multipliers λ and their update, about λ's
    // error (the contraction is ~1e-5: Argyris P0, 14x5 to 56x20): x is returned once that update
    // is below kTolerance of λ in every column — three solves — or stops shrinking (the solves'
    // roundoff, ~3e-10 of λ with kPenalty = 1e3) where that is below 1e-6.
    void apply(const Eigen::MatrixXd& v, Eigen::MatrixXd& x) const {
        Eigen::MatrixXd lambda = Eigen::MatrixXd::Zero(root_.cols(), v.cols()), update;
        augmented_.solve(v, x);
        double previous = HUGE_VAL;
        for (int it = 0; it < kMaxIterations; ++it) {
            update.noalias() = rho_ * (root_.transpose() * x);
            lambda += update;
            double change = 0.0;  // the largest relative update over the block's columns
            for (Eigen::Index j = 0; j < v.cols(); ++j) {
                const double size = lambda.col(j).norm();
                if (size > 0.0) change = std::max(change, update.col(j).norm() / size);
            }
            if (it > 0 && (change <= kTolerance || (change >= previous && change <= 1e-6))) return;
            if (change >= previous) break;
            previous = change;
            augmented_.solve(v - root_ * lambda, x);
        }
        throw std::runtime_error(
            "the massless flexibility of the singular mass did not converge (augmented Lagrangian iteration)");
    }

private:
    static constexpr int kMaxIterations = 60;
    static constexpr double kTolerance = 1e-9;
    // ρ over the element-level ω² scale: the contraction per step is 1/(1 + ρ/ω²) at the highest
    // massive ω² (measured ~7e-6), and the factor of K_ρ loses about log10(kPenalty) digits to ρ
    // (the floor above; 1e2: contraction 7e-5, floor 3e-11, four solves; 1e4: floor 3e-9).
    static constexpr double kPenalty = 1e3;

    // max_i K_ii / M_s,ii: the element-level ω² scale, the order of the highest massive ω².
    static double penalty(const Eigen::SparseMatrix<double>& stiffness, const Eigen::SparseMatrix<double>& root) {
        const Eigen::VectorXd massDiagonal = root.cwiseAbs2() * Eigen::VectorXd::Ones(root.cols());
        double scale = 0.0;
        for (Eigen::Index i = 0; i < massDiagonal.size(); ++i)
            if (massDiagonal[i] > 0.0) scale = std::max(scale, stiffness.coeff(i, i) / massDiagonal[i]);
        return kPenalty * scale;
    }
    static Eigen::SparseMatrix<double> augment(const Eigen::SparseMatrix<double>& stiffness,
                                               const Eigen::SparseMatrix<double>& root, double rho) {
        const Eigen::SparseMatrix<double> mass = root * root.transpose();
        return stiffness + rho * mass;
    }

    const Eigen::SparseMatrix<double>& root_;
    double rho_;
    SparseCholesky augmented_;
};

// Right-hand sides per block: the solves' four-column passes, and n × kBlock doubles at a time.
constexpr Eigen::Index kBlock = 32;

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
    {
        // The lowest modes: T's largest eigenvalues μ = 1/ω², Φ orthonormal; V = K⁻¹ R Φ Ω².
        const SparseCholesky stiffness(plate.stiffness);
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
    // The massless part, every massive mode excluded: D = C Q0 S⁻¹ Q0ᵀ Cᵀ block by block, the
    // recovery functionals on the same solves, then the load.
    const MasslessFlexibility massless(plate.stiffness, root);
    c.delassus.resize(r, r);
    if (nl > 0) c.recoveryRows.resize(nl, r);
    Eigen::MatrixXd x;
    for (Eigen::Index first = 0; first < r; first += kBlock) {
        const Eigen::Index k = std::min(kBlock, r - first);
        massless.apply(Eigen::MatrixXd(rows.middleRows(first, k).transpose()), x);
        c.delassus.middleCols(first, k).noalias() = rows * x;
        if (nl > 0) c.recoveryRows.middleCols(first, k).noalias() = recovery * x;
    }
    c.delassus = 0.5 * (c.delassus + c.delassus.transpose()).eval();
    massless.apply(Eigen::MatrixXd(plate.pressureLoad), x);
    c.rowLoad = rows * x;
    c.loadFlexibility = plate.pressureLoad.dot(x.col(0));
    if (nl > 0) c.recoveryLoad = recovery * x;
}

}  // namespace plate
