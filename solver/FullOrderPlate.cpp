#include "FullOrderPlate.h"

#include "Kernels.h"

namespace plate {

FullOrderPlate::FullOrderPlate(std::shared_ptr<const FiniteElementSpace> space,
                               std::shared_ptr<const ClampedPlate> plate, double dt, double beta)
    : space_(std::move(space)),
      plate_(std::move(plate)),
      stepFactor_(Eigen::SparseMatrix<double>(plate_->mass + (beta * dt * dt) * plate_->stiffness)),
      stiffnessRows_(plate_->stiffness),
      massRows_(plate_->mass) {}

void FullOrderPlate::applyStiffness(const Eigen::VectorXd& w, Eigen::VectorXd& out) const {
    multiplyRows(stiffnessRows_, w, out);
}

void FullOrderPlate::applyMass(const Eigen::VectorXd& w, Eigen::VectorXd& out) const {
    multiplyRows(massRows_, w, out);
}

void FullOrderPlate::solveStepMatrix(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
    stepFactor_.solve(b, x);
}

DiscretePlate::Solver FullOrderPlate::stiffnessSolver() const {
    auto factor = std::make_shared<const CholmodFactor>(plate_->stiffness);
    return [factor](const Eigen::VectorXd& b, Eigen::VectorXd& x) { factor->solve(b, x); };
}

void FullOrderPlate::gatherContact(const Eigen::VectorXd& w, Eigen::VectorXd& y) const {
    const auto& dofs = plate_->contactDofs;
    y.resize(static_cast<Eigen::Index>(dofs.size()));
    for (std::size_t i = 0; i < dofs.size(); ++i) y[i] = w[dofs[i]];
}

void FullOrderPlate::contactDirection(int j, Eigen::VectorXd& c) const {
    c = Eigen::VectorXd::Zero(size());
    c[plate_->contactDofs[j]] = 1.0;
}

void FullOrderPlate::stepMatrixContactColumn(int j, Eigen::VectorXd& z) const {
    Eigen::VectorXd c;
    contactDirection(j, c);
    stepFactor_.solve(c, z);
}

}  // namespace plate
