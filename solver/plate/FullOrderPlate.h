#pragma once
// The plate in the full C1 finite element space (exact mode, modes = 0).
#include <memory>

#include "fe/Assembly.h"
#include "plate/SparseCholesky.h"
#include "plate/DiscretePlate.h"

namespace plate {

class FullOrderPlate : public DiscretePlate {
public:
    // The step matrix of the law's Δt, β and damping factored.
    FullOrderPlate(std::shared_ptr<const FiniteElementSpace> space, std::shared_ptr<const ClampedPlate> plate,
                   const LawParameters& law);

    Eigen::Index size() const override { return plate_->mass.rows(); }
    void applyStiffness(const Eigen::VectorXd& w, Eigen::VectorXd& out) const override;
    void applyMass(const Eigen::VectorXd& w, Eigen::VectorXd& out) const override;
    void solveStepMatrix(const Eigen::VectorXd& b, Eigen::VectorXd& x) const override;
    Solver stiffnessSolver() const override;
    int contactCount() const override { return static_cast<int>(plate_->contactDofs.size()); }
    void gatherContact(const Eigen::VectorXd& w, Eigen::VectorXd& y) const override;
    void stepMatrixContactColumn(int j, Eigen::VectorXd& z) const override;
    void contactDirection(int j, Eigen::VectorXd& c) const override;
    void scatterContact(const Eigen::VectorXd& y, Eigen::VectorXd& w) const override;
    const Eigen::VectorXd& pressureLoad() const override { return plate_->pressureLoad; }
    const Eigen::VectorXd& baseInertia() const override { return plate_->baseInertia; }
    double totalMass() const override { return plate_->totalMass; }
    const Eigen::VectorXd& rotationInertia() const override { return plate_->rotationInertia; }
    const ClampedPlate& clamped() const override { return *plate_; }
    PointProbe probe(double x, double y) const override { return plate_->probe(*space_, x, y); }
    LinearRows rows(const SparseRows& functionals) const override { return {functionals, {}}; }

private:
    std::shared_ptr<const FiniteElementSpace> space_;
    std::shared_ptr<const ClampedPlate> plate_;
    SparseCholesky stepFactor_;
    // Upper triangles in row storage for the per-step product K w and the energy's M v
    // (Kernels.h); every row starts with its diagonal entry.
    Eigen::SparseMatrix<double, Eigen::RowMajor> stiffnessUpper_, massUpper_;
};

}  // namespace plate
