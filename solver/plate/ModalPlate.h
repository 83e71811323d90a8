#pragma once
// The clamped plate in M-orthonormal modal coordinates w = Φ α (Φᵀ M Φ = I, Φᵀ K Φ = Ω²).
//
// With the complete basis this is the exact scheme (3.6) in other coordinates: A becomes the
// diagonal I + βΔt²Ω², so the per-step "solve" is a division and the only non-diagonal work is
// the vertex values y = (CΦ) α, a small dense product. With the m lowest modes it is the
// reduced model of the `modes` parameter; contact stays enforced at every vertex, through the
// constant contact operator CΦ.
#include <memory>

#include "fe/Assembly.h"
#include "plate/DiscretePlate.h"

namespace plate {

class ModalPlate : public DiscretePlate {
public:
    // modes ≤ 0 or ≥ the dof count: complete basis. Throws std::runtime_error if the eigen
    // solution fails.
    ModalPlate(std::shared_ptr<const FiniteElementSpace> space, std::shared_ptr<const ClampedPlate> plate, double dt,
               double beta, int modes, double dampingMass = 0.0, double dampingStiffness = 0.0);

    Eigen::Index size() const override { return omega2_.size(); }
    void applyStiffness(const Eigen::VectorXd& w, Eigen::VectorXd& out) const override;
    void applyMass(const Eigen::VectorXd& w, Eigen::VectorXd& out) const override;
    void solveStepMatrix(const Eigen::VectorXd& b, Eigen::VectorXd& x) const override;
    Solver stiffnessSolver() const override;
    int contactCount() const override { return static_cast<int>(contactModesT_.cols()); }
    void gatherContact(const Eigen::VectorXd& w, Eigen::VectorXd& y) const override;
    void stepMatrixContactColumn(int j, Eigen::VectorXd& z) const override;
    void contactDirection(int j, Eigen::VectorXd& c) const override { c = contactModesT_.col(j); }
    void scatterContact(const Eigen::VectorXd& y, Eigen::VectorXd& w) const override {
        w.noalias() += contactModesT_ * y;
    }
    double contactRowNormBound() const override { return contactRowNormMax_; }
    const Eigen::VectorXd& pressureLoad() const override { return pressureLoad_; }
    const Eigen::VectorXd& baseInertia() const override { return baseInertia_; }
    double totalMass() const override { return plate_->totalMass; }
    const Eigen::VectorXd& rotationInertia() const override { return rotationInertia_; }
    const ClampedPlate& clamped() const override { return *plate_; }
    PointProbe probe(double x, double y) const override;
    LinearRows rows(const SparseRows& functionals) const override { return {{}, DenseRows(functionals * phi_)}; }

    bool complete() const { return complete_; }
    // Squared circular frequencies ω_k² of the retained modes, ascending.
    const Eigen::VectorXd& omega2() const { return omega2_; }
    // Modal coordinates of a full-space field: α = Φᵀ M w (exact for the complete basis, the
    // M-orthogonal projection otherwise).
    Eigen::VectorXd fromFullSpace(const Eigen::VectorXd& w) const;

private:
    std::shared_ptr<const FiniteElementSpace> space_;
    std::shared_ptr<const ClampedPlate> plate_;
    bool complete_ = false;
    Eigen::MatrixXd phi_;  // free dofs x modes
    Eigen::VectorXd omega2_;  // Ω²
    Eigen::VectorXd inverseStep_;  // 1 / (1 + βΔt²ω²), damped: 1 / (1 + aΔt/2 + (βΔt² + bΔt/2)ω²)
    Eigen::MatrixXd contactModesT_;  // (CΦ)ᵀ: column j = mode shapes at contact vertex j
    Eigen::VectorXd pressureLoad_, baseInertia_, rotationInertia_;
    double contactRowNormMax_ = 0.0;  // max_i ‖(CΦ)_i‖₂
};

}  // namespace plate
