#include "plate/FullOrderPlate.h"

#include "plate/Kernels.h"

#include <stdexcept>

namespace plate {

FullOrderPlate::FullOrderPlate(std::shared_ptr<const FiniteElementSpace> space,
                               std::shared_ptr<const ClampedPlate> plate, const LawParameters& law)
    : DiscretePlate(law),
      space_(std::move(space)),
      plate_(std::move(plate)),
      // A = (1 + aΔt/2) M + (βΔt² + bΔt/2) K with Rayleigh damping a M + b K (§13); undamped, the terms of a
      // and b are exact zeros (no contraction: -ffp-contract=off) and A = M + βΔt²K bit for bit.
      stepFactor_((1.0 + 0.5 * law.dampingMass * law.dt) * plate_->mass +
                  (law.beta * law.dt * law.dt + 0.5 * law.dampingStiffness * law.dt) * plate_->stiffness),
      stiffnessUpper_(plate_->stiffness.triangularView<Eigen::Upper>()),
      massUpper_(plate_->mass.triangularView<Eigen::Upper>()) {
    // The kernel reads each row's diagonal first: it must be stored, even where it is zero.
    for (const auto* m : {&stiffnessUpper_, &massUpper_})
        for (Eigen::Index i = 0; i < m->rows(); ++i)
            if (m->outerIndexPtr()[i] == m->outerIndexPtr()[i + 1] || m->innerIndexPtr()[m->outerIndexPtr()[i]] != i)
                throw std::runtime_error("sparse matrix without a stored diagonal");
}

void FullOrderPlate::applyStiffness(const Eigen::VectorXd& w, Eigen::VectorXd& out) const {
    multiplySymmetricUpper(stiffnessUpper_, w, out);
}

void FullOrderPlate::applyMass(const Eigen::VectorXd& w, Eigen::VectorXd& out) const {
    multiplySymmetricUpper(massUpper_, w, out);
}

void FullOrderPlate::solveStepMatrix(const Eigen::VectorXd& b, Eigen::VectorXd& x) const { stepFactor_.solve(b, x); }

DiscretePlate::Solver FullOrderPlate::stiffnessSolver() const {
    auto factor = std::make_shared<const SparseCholesky>(plate_->stiffness);
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

void FullOrderPlate::scatterContact(const Eigen::VectorXd& y, Eigen::VectorXd& w) const {
    const auto& dofs = plate_->contactDofs;
    for (std::size_t i = 0; i < dofs.size(); ++i) w[dofs[i]] += y[static_cast<Eigen::Index>(i)];
}

void FullOrderPlate::stepMatrixContactColumn(int j, Eigen::VectorXd& z) const {
    Eigen::VectorXd c;
    contactDirection(j, c);
    stepFactor_.solve(c, z);
}

}  // namespace plate
