#include "plate/CondensedPlate.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "base/Errors.h"
#include "plate/CondensedSparse.h"
#include "plate/SparseCholesky.h"

namespace plate {

namespace {

// y = C x over the constraint rows: the contact vertices' values, then the extra functionals.
void gatherRows(const ClampedPlate& plate, const std::vector<ConstraintRow>& extra, const Eigen::VectorXd& x,
                double* y) {
    const std::size_t m = plate.contactDofs.size();
    for (std::size_t i = 0; i < m; ++i) y[i] = x[plate.contactDofs[i]];
    for (std::size_t k = 0; k < extra.size(); ++k) y[m + k] = extra[k].functional(x);
}

// Cᵀ e_i as a dense vector over the free dofs.
void rowDirection(const ClampedPlate& plate, const std::vector<ConstraintRow>& extra, std::size_t i,
                  Eigen::VectorXd& v) {
    v.setZero();
    const std::size_t m = plate.contactDofs.size();
    if (i < m) {
        v[plate.contactDofs[i]] = 1.0;
        return;
    }
    const PointProbe& f = extra[i - m].functional;
    for (std::size_t k = 0; k < f.dofs.size(); ++k) v[f.dofs[k]] += f.coefficients[k];
}

// T's eigenvalues (1/ω²) all well above roundoff: every massive function moves the plate.
void requireMassiveSpace(const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>& eigen, Eigen::Index nq) {
    if (eigen.info() == Eigen::Success && nq > 0 && eigen.eigenvalues()[0] > 1e-13 * eigen.eigenvalues()[nq - 1])
        return;
    throw ParameterError(
        "the singular mass's massive space is degenerate on this mesh (the massive flexibility Rᵀ K⁻¹ R is "
        "singular; allowed: a projection space whose functions the clamped plate can all move)");
}

// D positive definite: the massless space moves each constraint row on its own.
void requireDelassusPositive(const Eigen::MatrixXd& delassus, Eigen::Index rows) {
    const Eigen::LLT<Eigen::MatrixXd> check(delassus);
    if (check.info() == Eigen::Success) return;
    std::ostringstream msg;
    msg << "the massless space of the singular mass cannot move each of the " << rows
        << " constraint rows independently on this mesh (the massless Delassus operator is not positive "
           "definite); allowed: mass = singular_p0, or another mesh";
    throw ParameterError(msg.str());
}

// The complete dense solution of T (every massive mode, then the leading `kept`): what a coarse mesh,
// or one keeping most modes, pays least for.
void condenseDense(const ClampedPlate& plate, const Eigen::SparseMatrix<double>& root,
                   const std::vector<ConstraintRow>& extraRows, Eigen::Index kept, const SparseRows& recovery,
                   CondensedPlate& c) {
    const Eigen::Index n = plate.stiffness.rows(), nq = root.cols();
    const auto m = static_cast<Eigen::Index>(plate.contactDofs.size());
    const Eigen::Index rows = m + static_cast<Eigen::Index>(extraRows.size());
    const SparseCholesky stiffness(plate.stiffness);  // K, for the columns below only
    Eigen::VectorXd b(n), x(n);

    // T = Rᵀ K⁻¹ R (massive flexibility) and C K⁻¹ R, one solve per column of R.
    // The recovery functionals L ride along on the same solves (docs/theory.md §23).
    const Eigen::Index nl = recovery.rows();
    Eigen::MatrixXd flexibility(nq, nq), rowsOfMassive(rows, nq), recoveryOfMassive(nl, nq);
    for (Eigen::Index j = 0; j < nq; ++j) {
        b = root.col(j);
        stiffness.solve(b, x);
        flexibility.col(j).noalias() = root.transpose() * x;
        gatherRows(plate, extraRows, x, rowsOfMassive.col(j).data());
        if (nl > 0) recoveryOfMassive.col(j).noalias() = recovery * x;
    }
    // C K⁻¹ Cᵀ, one solve per row.
    Eigen::MatrixXd rowFlexibility(rows, rows), recoveryFlexibility(nl, rows);
    for (Eigen::Index i = 0; i < rows; ++i) {
        rowDirection(plate, extraRows, static_cast<std::size_t>(i), b);
        stiffness.solve(b, x);
        gatherRows(plate, extraRows, x, rowFlexibility.col(i).data());
        if (nl > 0) recoveryFlexibility.col(i).noalias() = recovery * x;
    }
    // The massive stiffness T⁻¹ = Φ Ω² Φᵀ: T's eigenvalues are 1/ω², largest first = lowest mode.
    flexibility = 0.5 * (flexibility + flexibility.transpose()).eval();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(flexibility);
    requireMassiveSpace(eigen, nq);
    const Eigen::VectorXd mu = eigen.eigenvalues().reverse();
    const Eigen::MatrixXd phi = eigen.eigenvectors().rowwise().reverse();
    const Eigen::VectorXd omega2All = mu.cwiseInverse();
    c.omega2 = omega2All.head(kept);
    // (C K⁻¹ R) Φ: the rows' response to each massive mode's flexibility; G = that · Ω².
    const Eigen::MatrixXd rowsPhi = rowsOfMassive * phi;
    c.rowModesT = (rowsPhi.leftCols(kept) * c.omega2.asDiagonal()).transpose();
    // D = C K⁻¹ Cᵀ − (C K⁻¹ R) T⁻¹ (C K⁻¹ R)ᵀ with every massive mode (the massless space is exact
    // whatever the reduction), symmetrized.
    c.delassus = rowFlexibility - rowsPhi * omega2All.asDiagonal() * rowsPhi.transpose();
    c.delassus = 0.5 * (c.delassus + c.delassus.transpose()).eval();

    // Loads through the same flexibilities: K⁻¹ v gives the rows' response C K⁻¹ v and the
    // massive part Rᵀ K⁻¹ v, whose modal coordinates are Ω² Φᵀ Rᵀ K⁻¹ v (= Vᵀ v).
    const auto modal = [&](const Eigen::VectorXd& v, Eigen::VectorXd& massive, double* rowResponse) {
        b = v;
        stiffness.solve(b, x);
        massive = phi.transpose() * (root.transpose() * x);  // Φᵀ Rᵀ K⁻¹ v
        if (rowResponse) gatherRows(plate, extraRows, x, rowResponse);
        return v.dot(x);
    };
    Eigen::VectorXd massive;
    c.rowLoad.resize(rows);
    const double loadFlexibilityFull = modal(plate.pressureLoad, massive, c.rowLoad.data());
    c.rowLoad.noalias() -= rowsPhi * omega2All.cwiseProduct(massive);
    c.loadFlexibility = loadFlexibilityFull - massive.dot(omega2All.cwiseProduct(massive));
    if (nl > 0) {
        // L V = (L K⁻¹ R) Φ Ω², and the massless parts as D and c_p above with L in place of C.
        const Eigen::MatrixXd recoveryPhi = recoveryOfMassive * phi;
        c.recoveryModes = recoveryPhi.leftCols(kept) * c.omega2.asDiagonal();
        c.recoveryRows = recoveryFlexibility - recoveryPhi * omega2All.asDiagonal() * rowsPhi.transpose();
        c.recoveryLoad = recovery * x - recoveryPhi * omega2All.cwiseProduct(massive);  // x = K⁻¹ F still
    }
    c.modalLoad = omega2All.head(kept).cwiseProduct(massive.head(kept));
    modal(plate.baseInertia, massive, nullptr);
    c.modalBaseInertia = omega2All.head(kept).cwiseProduct(massive.head(kept));
    modal(plate.rotationInertia, massive, nullptr);
    c.modalRotationInertia = omega2All.head(kept).cwiseProduct(massive.head(kept));
}

}  // namespace

bool denseCondensationServes(Eigen::Index massive, int modes) {
    const Eigen::Index kept = (modes <= 0 || modes >= massive) ? massive : modes;
    return kept == massive || 4 * kept > massive || massive <= kDenseCondensationLimit;
}

CondensedPlate condense(const ClampedPlate& plate, const Eigen::SparseMatrix<double>& root,
                        const std::vector<ConstraintRow>& extraRows, int modes, const SparseRows& recovery,
                        Condensation method) {
    const Eigen::Index nq = root.cols();
    const Eigen::Index kept = (modes <= 0 || modes >= nq) ? nq : modes;
    const bool sparse =
        method == Condensation::Sparse || (method == Condensation::Auto && !denseCondensationServes(nq, modes));
    if (sparse && kept == nq)
        throw std::invalid_argument("the sparse condensation keeps fewer modes than the massive space's " +
                                    std::to_string(nq));
    CondensedPlate c;
    c.massiveCount = static_cast<int>(nq);
    c.contactRows = static_cast<int>(plate.contactDofs.size());
    if (sparse)
        condenseSparse(plate, root, constraintRows(plate, extraRows), kept, recovery, c);
    else
        condenseDense(plate, root, extraRows, kept, recovery, c);
    const Eigen::Index rows = c.rows();
    requireDelassusPositive(c.delassus, rows);

    c.totalMass = plate.totalMass;
    c.totalMassMoment = plate.totalMassMoment;
    c.loadResultant = plate.loadResultant;
    c.loadMoment = plate.loadMoment;
    if (kept < nq) {  // the discarded modes move with the clamp (§17)
        c.clampMass = std::max(0.0, plate.totalMass - c.modalBaseInertia.squaredNorm());
        c.clampMassMoment = plate.totalMassMoment - c.modalRotationInertia.dot(c.modalBaseInertia);
    }
    c.rowAbscissae = plate.contactAbscissae;
    c.rowStops = plate.contactStops;
    for (const ConstraintRow& r : extraRows) {
        c.rowAbscissae.push_back(r.x);
        c.rowStops.push_back(r.stops);
    }
    if (rows > 0) c.rowModeNormMax = c.rowModesT.colwise().norm().maxCoeff();
    return c;
}

}  // namespace plate
