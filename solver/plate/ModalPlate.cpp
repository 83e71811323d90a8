#include "plate/ModalPlate.h"

#include <stdexcept>

#include "plate/Kernels.h"
#include "plate/Spectrum.h"

namespace plate {

ModalPlate::ModalPlate(std::shared_ptr<const FiniteElementSpace> space, std::shared_ptr<const ClampedPlate> plate,
                       double dt, double beta, int modes, double dampingMass, double dampingStiffness)
    : DiscretePlate(dt, beta), space_(std::move(space)), plate_(std::move(plate)) {
    lowestModes(*plate_, modes, phi_, omega2_);
    complete_ = phi_.cols() == plate_->mass.rows();
    // Rayleigh damping is diagonal in modal coordinates (§13): ζ_k = a/(2ω_k) + bω_k/2.
    if (dampingMass == 0.0 && dampingStiffness == 0.0)
        inverseStep_ = (1.0 + beta * dt * dt * omega2_.array()).inverse().matrix();
    else
        inverseStep_ =
            ((1.0 + 0.5 * dampingMass * dt) + (beta * dt * dt + 0.5 * dampingStiffness * dt) * omega2_.array())
                .inverse()
                .matrix();
    const auto& dofs = plate_->contactDofs;
    contactModesT_.resize(phi_.cols(), static_cast<Eigen::Index>(dofs.size()));
    for (std::size_t i = 0; i < dofs.size(); ++i) contactModesT_.col(i) = phi_.row(dofs[i]).transpose();
    if (contactModesT_.cols() > 0) contactRowNormMax_ = contactModesT_.colwise().norm().maxCoeff();
    pressureLoad_ = phi_.transpose() * plate_->pressureLoad;
    baseInertia_ = phi_.transpose() * plate_->baseInertia;
    rotationInertia_ = phi_.transpose() * plate_->rotationInertia;
}

void ModalPlate::applyStiffness(const Eigen::VectorXd& w, Eigen::VectorXd& out) const { out = omega2_.cwiseProduct(w); }

void ModalPlate::applyMass(const Eigen::VectorXd& w, Eigen::VectorXd& out) const { out = w; }

void ModalPlate::solveStepMatrix(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
    x = inverseStep_.cwiseProduct(b);
}

DiscretePlate::Solver ModalPlate::stiffnessSolver() const {
    return [omega2 = omega2_](const Eigen::VectorXd& b, Eigen::VectorXd& x) { x = b.cwiseQuotient(omega2); };
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
    for (std::size_t k = 0; k < full.dofs.size(); ++k) row += full.coefficients[k] * phi_.row(full.dofs[k]).transpose();
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
