#include "plate/ModalPlate.h"

#include <stdexcept>

#include "plate/Kernels.h"
#include "plate/Spectrum.h"

namespace plate {

ModalBasis::ModalBasis(const ClampedPlate& plate, int modes, const ModalBasis* whole) {
    if (whole)
        leadingModes(whole->phi, whole->omega2, modes, phi, omega2);
    else
        lowestModes(plate, modes, phi, omega2);
    complete = phi.cols() == plate.mass.rows();
    const auto& dofs = plate.contactDofs;
    contactModesT.resize(phi.cols(), static_cast<Eigen::Index>(dofs.size()));
    for (std::size_t i = 0; i < dofs.size(); ++i) contactModesT.col(i) = phi.row(dofs[i]).transpose();
    if (contactModesT.cols() > 0) contactRowNormMax = contactModesT.colwise().norm().maxCoeff();
    pressureLoad = phi.transpose() * plate.pressureLoad;
    baseInertia = phi.transpose() * plate.baseInertia;
    rotationInertia = phi.transpose() * plate.rotationInertia;
}

ModalPlate::ModalPlate(std::shared_ptr<const FiniteElementSpace> space, std::shared_ptr<const ClampedPlate> plate,
                       std::shared_ptr<const ModalBasis> basis, const LawParameters& law)
    : DiscretePlate(law), space_(std::move(space)), plate_(std::move(plate)), basis_(std::move(basis)) {
    // Rayleigh damping is diagonal in modal coordinates (§13): ζ_k = a/(2ω_k) + bω_k/2. Undamped, the
    // terms of a and b add exact zeros (no contraction: -ffp-contract=off): the undamped bits.
    const double dt = law.dt;
    inverseStep_ = ((1.0 + 0.5 * law.dampingMass * dt) +
                    (law.beta * dt * dt + 0.5 * law.dampingStiffness * dt) * basis_->omega2.array())
                       .inverse()
                       .matrix();
}

void ModalPlate::applyStiffness(const Eigen::VectorXd& w, Eigen::VectorXd& out) const {
    out = basis_->omega2.cwiseProduct(w);
}

void ModalPlate::applyMass(const Eigen::VectorXd& w, Eigen::VectorXd& out) const { out = w; }

void ModalPlate::solveStepMatrix(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
    x = inverseStep_.cwiseProduct(b);
}

DiscretePlate::Solver ModalPlate::stiffnessSolver() const {
    return [omega2 = basis_->omega2](const Eigen::VectorXd& b, Eigen::VectorXd& x) { x = b.cwiseQuotient(omega2); };
}

void ModalPlate::gatherContact(const Eigen::VectorXd& w, Eigen::VectorXd& y) const {
    multiplyTransposed(basis_->contactModesT, w, y);
}

void ModalPlate::stepMatrixContactColumn(int j, Eigen::VectorXd& z) const {
    z = inverseStep_.cwiseProduct(basis_->contactModesT.col(j));
}

PointProbe ModalPlate::probe(double x, double y) const {
    const PointProbe full = plate_->probe(*space_, x, y);
    Eigen::VectorXd row = Eigen::VectorXd::Zero(basis_->phi.cols());
    for (std::size_t k = 0; k < full.dofs.size(); ++k)
        row += full.coefficients[k] * basis_->phi.row(full.dofs[k]).transpose();
    PointProbe modal;
    for (Eigen::Index k = 0; k < row.size(); ++k) {
        modal.dofs.push_back(k);
        modal.coefficients.push_back(row[k]);
    }
    return modal;
}

Eigen::VectorXd ModalPlate::fromFullSpace(const Eigen::VectorXd& w) const {
    return basis_->phi.transpose() * (plate_->mass * w);
}

}  // namespace plate
