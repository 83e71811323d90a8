#pragma once
// What the Newmark–contact stepper needs of a discretized clamped plate: the linear algebra of
// (3.6) in some coordinates w (the full FE space, or a modal basis), nothing about elements.
#include <Eigen/Core>
#include <functional>

#include "fe/Assembly.h"
#include "plate/LinearRows.h"
#include "plate/PlateParameters.h"

namespace plate {

class DiscretePlate {
public:
    virtual ~DiscretePlate() = default;

    // The time step and β the step matrix A = M + βΔt²K was factored with: the one place the
    // scheme's Δt and β live (the stepper and the impact laws read them here).
    double dt() const { return law_.dt; }
    double beta() const { return law_.beta; }
    // The law its step matrix was made for (Δt, β, the damping) and the scheme steps it with (restitution).
    const LawParameters& law() const { return law_; }

    virtual Eigen::Index size() const = 0;
    virtual void applyStiffness(const Eigen::VectorXd& w, Eigen::VectorXd& out) const = 0;
    virtual void applyMass(const Eigen::VectorXd& w, Eigen::VectorXd& out) const = 0;
    // x = A⁻¹ b with A = M + βΔt²K, factored once (docs/theory.md: never a refactorization per step);
    // with Rayleigh damping C = a M + b K, A = (1 + aΔt/2) M + (βΔt² + bΔt/2) K (docs/theory.md §13).
    virtual void solveStepMatrix(const Eigen::VectorXd& b, Eigen::VectorXd& x) const = 0;

    // A solver x = K⁻¹ b for the static problem of the initial state (§5.2); it owns whatever
    // factor it needs, used a few times at initialization and then dropped.
    using Solver = std::function<void(const Eigen::VectorXd& b, Eigen::VectorXd& x)>;
    virtual Solver stiffnessSolver() const = 0;

    // Contact: vertex values y = C w of the vertices carrying a bound, and A⁻¹Cᵀe_j.
    virtual int contactCount() const = 0;
    virtual void gatherContact(const Eigen::VectorXd& w, Eigen::VectorXd& y) const = 0;
    virtual void stepMatrixContactColumn(int j, Eigen::VectorXd& z) const = 0;
    virtual void contactDirection(int j, Eigen::VectorXd& c) const = 0;  // Cᵀ e_j
    virtual void scatterContact(const Eigen::VectorXd& y, Eigen::VectorXd& w) const = 0;  // w += Cᵀ y
    // max_i ‖C_i‖₂ over the rows of C, when gathering y = C w is expensive enough that a step
    // should first bound how far the vertices can have moved (|Δy_i| ≤ ‖C_i‖₂ ‖Δw‖₂); 0 when
    // the gather is as cheap as that bound.
    virtual double contactRowNormBound() const { return 0.0; }

    virtual const Eigen::VectorXd& pressureLoad() const = 0;  // F (unit pressure)
    virtual const Eigen::VectorXd& baseInertia() const = 0;  // (M·1)_free
    virtual double totalMass() const = 0;  // 1ᵀM1
    // The port (docs/theory.md §14): (M·X)_free for the rotation X about the clamp line in these
    // coordinates, the clamped plate's rigid-motion sums, and each contact vertex's lever arm x.
    virtual const Eigen::VectorXd& rotationInertia() const = 0;
    virtual const ClampedPlate& clamped() const = 0;
    const std::vector<double>& contactAbscissae() const { return clamped().contactAbscissae; }

    // Point evaluation of w (relative to the base) in these coordinates.
    virtual PointProbe probe(double x, double y) const = 0;
    // Functionals L over the free dofs (probes, stress samples: docs/theory.md §23) in these coordinates.
    virtual LinearRows rows(const SparseRows& functionals) const = 0;

protected:
    explicit DiscretePlate(const LawParameters& law) : law_(law) {}

private:
    LawParameters law_;
};

}  // namespace plate
