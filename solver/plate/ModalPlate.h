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

// The clamped plate's lowest M-orthonormal modes and what they make of the contact vertices and the
// loads: all of ModalPlate but Δt, β and the damping, so that instances of one plate at other steps
// or damping share it (DiscretizationCache).
struct ModalBasis {
    // modes ≤ 0 or ≥ the dof count: complete basis. Throws std::runtime_error if the eigen
    // solution fails. `whole`: the plate's complete basis, whose leading modes these are where the
    // dense solution serves (Spectrum.h: bit for bit), instead of a solve.
    ModalBasis(const ClampedPlate& plate, int modes, const ModalBasis* whole = nullptr);
    bool complete = false;
    Eigen::MatrixXd phi;  // free dofs x modes
    Eigen::VectorXd omega2;  // Ω²
    Eigen::MatrixXd contactModesT;  // (CΦ)ᵀ: column j = mode shapes at contact vertex j
    Eigen::VectorXd pressureLoad, baseInertia, rotationInertia;
    double contactRowNormMax = 0.0;  // max_i ‖(CΦ)_i‖₂
};

class ModalPlate : public DiscretePlate {
public:
    // The step of the law's Δt, β and damping on a basis shared (DiscretizationCache).
    ModalPlate(std::shared_ptr<const FiniteElementSpace> space, std::shared_ptr<const ClampedPlate> plate,
               std::shared_ptr<const ModalBasis> basis, const LawParameters& law);

    Eigen::Index size() const override { return basis_->omega2.size(); }
    void applyStiffness(const Eigen::VectorXd& w, Eigen::VectorXd& out) const override;
    void applyMass(const Eigen::VectorXd& w, Eigen::VectorXd& out) const override;
    void solveStepMatrix(const Eigen::VectorXd& b, Eigen::VectorXd& x) const override;
    Solver stiffnessSolver() const override;
    int contactCount() const override { return static_cast<int>(basis_->contactModesT.cols()); }
    void gatherContact(const Eigen::VectorXd& w, Eigen::VectorXd& y) const override;
    void stepMatrixContactColumn(int j, Eigen::VectorXd& z) const override;
    void contactDirection(int j, Eigen::VectorXd& c) const override { c = basis_->contactModesT.col(j); }
    void scatterContact(const Eigen::VectorXd& y, Eigen::VectorXd& w) const override {
        w.noalias() += basis_->contactModesT * y;
    }
    double contactRowNormBound() const override { return basis_->contactRowNormMax; }
    const Eigen::VectorXd& pressureLoad() const override { return basis_->pressureLoad; }
    const Eigen::VectorXd& baseInertia() const override { return basis_->baseInertia; }
    double totalMass() const override { return plate_->totalMass; }
    const Eigen::VectorXd& rotationInertia() const override { return basis_->rotationInertia; }
    const ClampedPlate& clamped() const override { return *plate_; }
    PointProbe probe(double x, double y) const override;
    LinearRows rows(const SparseRows& functionals) const override { return {{}, DenseRows(functionals * basis_->phi)}; }

    bool complete() const { return basis_->complete; }
    // Squared circular frequencies ω_k² of the retained modes, ascending.
    const Eigen::VectorXd& omega2() const { return basis_->omega2; }
    // Modal coordinates of a full-space field: α = Φᵀ M w (exact for the complete basis, the
    // M-orthogonal projection otherwise).
    Eigen::VectorXd fromFullSpace(const Eigen::VectorXd& w) const;

private:
    std::shared_ptr<const FiniteElementSpace> space_;
    std::shared_ptr<const ClampedPlate> plate_;
    std::shared_ptr<const ModalBasis> basis_;
    Eigen::VectorXd inverseStep_;  // 1 / (1 + βΔt²ω²), damped: 1 / (1 + aΔt/2 + (βΔt² + bΔt/2)ω²)
};

}  // namespace plate
