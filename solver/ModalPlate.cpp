#include "ModalPlate.h"

#include <Eigen/Eigenvalues>
#include <stdexcept>

#include "CholmodFactor.h"
#include "Kernels.h"

namespace plate {

namespace {

// Dense generalized eigensolver: fine up to a few thousand dofs (O(n³) once at start).
constexpr Eigen::Index kDenseLimit = 3000;

void denseModes(const ClampedPlate& plate, Eigen::Index modes, Eigen::MatrixXd& phi,
                Eigen::VectorXd& omega2) {
    const Eigen::MatrixXd k = Eigen::MatrixXd(plate.stiffness);
    const Eigen::MatrixXd m = Eigen::MatrixXd(plate.mass);
    // Eigen normalizes the eigenvectors to Φᵀ M Φ = I and sorts the eigenvalues ascending.
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(k, m);
    if (eig.info() != Eigen::Success) throw std::runtime_error("modal analysis failed");
    phi = eig.eigenvectors().leftCols(modes);
    omega2 = eig.eigenvalues().head(modes);
}

// Subspace iteration X ← K⁻¹ M X with Rayleigh–Ritz, p = m + guard vectors: converges like
// (ω_m / ω_{p+1})^{2k}; stop when the m Ritz values settle to 1e-12.
void subspaceModes(const ClampedPlate& plate, Eigen::Index modes, Eigen::MatrixXd& phi,
                   Eigen::VectorXd& omega2) {
    const Eigen::Index n = plate.mass.rows();
    const Eigen::Index p = std::min<Eigen::Index>(n, std::max<Eigen::Index>(2 * modes, modes + 16));
    const CholmodFactor kFactor(plate.stiffness);
    Eigen::MatrixXd x(n, p);
    for (Eigen::Index j = 0; j < p; ++j)
        for (Eigen::Index i = 0; i < n; ++i) x(i, j) = std::sin(1.0 + 0.7 * i * (j + 1) + 0.3 * j);
    Eigen::VectorXd previous = Eigen::VectorXd::Zero(modes), col;
    for (int it = 0; it < 300; ++it) {
        const Eigen::MatrixXd mx = plate.mass * x;
        for (Eigen::Index j = 0; j < p; ++j) {
            kFactor.solve(mx.col(j), col);
            x.col(j) = col;
        }
        const Eigen::MatrixXd kr = x.transpose() * (plate.stiffness * x);
        const Eigen::MatrixXd mr = x.transpose() * (plate.mass * x);
        Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ritz(
            0.5 * (kr + kr.transpose()), 0.5 * (mr + mr.transpose()));
        x = x * ritz.eigenvectors();  // M-orthonormal Ritz vectors, ascending
        omega2 = ritz.eigenvalues().head(modes);
        if (it > 2 && ((omega2 - previous).cwiseAbs().array() <= 1e-12 * omega2.array()).all()) break;
        previous = omega2;
    }
    phi = x.leftCols(modes);
}

}  // namespace

void lowestModes(const ClampedPlate& plate, int modes, Eigen::MatrixXd& phi,
                 Eigen::VectorXd& omega2) {
    const Eigen::Index n = plate.mass.rows();
    const Eigen::Index m = (modes <= 0 || modes >= n) ? n : modes;
    if (n <= kDenseLimit)
        denseModes(plate, m, phi, omega2);
    else if (m < n)
        subspaceModes(plate, m, phi, omega2);
    else
        throw std::runtime_error("a complete modal basis needs a space of at most 3000 dofs");
}

ModalPlate::ModalPlate(std::shared_ptr<const FiniteElementSpace> space,
                       std::shared_ptr<const ClampedPlate> plate, double dt, double beta,
                       int modes)
    : space_(std::move(space)), plate_(std::move(plate)) {
    lowestModes(*plate_, modes, phi_, omega2_);
    complete_ = phi_.cols() == plate_->mass.rows();
    inverseStep_ = (1.0 + beta * dt * dt * omega2_.array()).inverse().matrix();
    const auto& dofs = plate_->contactDofs;
    contactModesT_.resize(phi_.cols(), static_cast<Eigen::Index>(dofs.size()));
    for (std::size_t i = 0; i < dofs.size(); ++i) contactModesT_.col(i) = phi_.row(dofs[i]).transpose();
    pressureLoad_ = phi_.transpose() * plate_->pressureLoad;
    baseInertia_ = phi_.transpose() * plate_->baseInertia;
}

void ModalPlate::applyStiffness(const Eigen::VectorXd& w, Eigen::VectorXd& out) const {
    out = omega2_.cwiseProduct(w);
}

void ModalPlate::applyMass(const Eigen::VectorXd& w, Eigen::VectorXd& out) const { out = w; }

void ModalPlate::solveStepMatrix(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
    x = inverseStep_.cwiseProduct(b);
}

DiscretePlate::Solver ModalPlate::stiffnessSolver() const {
    return [omega2 = omega2_](const Eigen::VectorXd& b, Eigen::VectorXd& x) {
        x = b.cwiseQuotient(omega2);
    };
}

void ModalPlate::gatherContact(const Eigen::VectorXd& w, Eigen::VectorXd& y) const {
    multiplyTransposed(contactModesT_, w, y);
}

void ModalPlate::stepMatrixContactColumn(int j, Eigen::VectorXd& z) const {
    z = inverseStep_.cwiseProduct(contactModesT_.col(j));
}

PointProbe ModalPlate::probe(double x, double y) const {
    const PointProbe full = plate_->probe(*space_, x, y);
    Eigen::VectorXd row = Eigen::VectorXd::Zero(phi_.cols());
    for (std::size_t k = 0; k < full.dofs.size(); ++k)
        row += full.coefficients[k] * phi_.row(full.dofs[k]).transpose();
    PointProbe modal;
    for (Eigen::Index k = 0; k < row.size(); ++k) {
        modal.dofs.push_back(k);
        modal.coefficients.push_back(row[k]);
    }
    return modal;
}

Eigen::VectorXd ModalPlate::fromFullSpace(const Eigen::VectorXd& w) const {
    return phi_.transpose() * (plate_->mass * w);
}

}  // namespace plate
