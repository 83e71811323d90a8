#pragma once
// What an impact law contributes to one step of the Newmark–contact scheme (docs/theory.md
// §4–5, §11, §12): the forces it carries into the right-hand side, the bounds of the step's
// contact QP on the vertex values y⁺ = C w⁺, and the contact work and sums of the step. The
// stepper (NewmarkScheme) is the paper's step plus one of these; a new law is a new
// class here, not a flag inside the step, and what it keeps in the state it sizes and sets itself.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "plate/DiscretePlate.h"
#include "schemes/NewmarkState.h"
#include "plate/Obstacles.h"

namespace plate {

// The contact space's buffers of one step, owned by the stepper (allocated once).
struct ContactBuffers {
    Eigen::VectorXd yFree, y, yPrev, mu, lower, upper;  // per contact vertex
    const std::vector<int>* active = nullptr;  // the QP's active set (when it ran)
};

// What the contact phase of one step yields for the ledger and the port (§6, §14).
struct ContactWork {
    double dissipated = 0.0;  // ½ τᵀ(u⁻ − u⁺)/Δt²
    double onBase = 0.0;  // −Σ τ (z⁺ − z⁻)/(2Δt²): the contact force's work on the moving frame
    double sum[2] = {0.0, 0.0};  // Σ τ per obstacle (lower τ > 0, upper τ < 0), Δt²-scaled
    double moment = 0.0;  // Σ τ_i x_i
};

class ImpactLaw {
public:
    virtual ~ImpactLaw() = default;

    // Per step (NewmarkScheme::step), in this order:
    // Forces carried from earlier steps into this one's right-hand side (none by default).
    virtual void addCarried(const NewmarkState&, Eigen::VectorXd&) {}
    // The QP's bounds for the step to the base zNext, with the free solution's vertex values in
    // b.yFree (the law gathers them); true when an obstacle is violated (the QP must run).
    virtual bool bounds(const NewmarkState& s, const Eigen::VectorXd& wFree, double zNext, ContactBuffers& b) = 0;
    // The step's contact work from the multipliers b.mu on b.active (when violated).
    virtual ContactWork work(const NewmarkState& s, bool violated, double zNext, ContactBuffers& b) = 0;
    // The law's history in the state after the step (the carried impulses).
    virtual void commit(NewmarkState&) {}

    // The law's part of the state, for NewmarkScheme's initialize, setInitialContactForce
    // and setLoadAtStart (nothing by default):
    // A fresh state: the law's members of NewmarkState sized and zero (the carried impulses; their
    // size is the one the FMU state stores and NewmarkScheme::restoreState expects).
    virtual void initialize(NewmarkState&) {}
    // Before the first step: the contact forces λ0 (per contact vertex) that hold the initial
    // state's massless part in equilibrium (docs/theory.md §11), for a law that carries them.
    virtual void setInitialContactForce(NewmarkState&, const Eigen::VectorXd& /*force*/) {}
    // True when the load before t = 0 must stay the one the initial state was made with (its
    // massless part is in equilibrium with it, §11): the load at start then leaves the history alone.
    virtual bool keepsLoadBeforeStart() const { return false; }
    // The state was replaced: forget what was derived from the old one.
    virtual void reset() {}
};

// The laws of docs/theory.md, chosen by makeImpactLaw:
//   carryImpulses       → SingularMassImpact: the constraint on (u⁺ + e u⁻)/(1 + e), any e ≥ 0,
//                         with the contact impulses of the two previous steps carried (§11, §12);
//   restitution > 0     → RestitutionImpact: the constraint on (u⁺ + e u⁻)/(1 + e) (§12);
//   otherwise           → InelasticImpact: the paper's (e = 0, consistent mass: §4–5, with the
//                         free-flight bound that skips looking at the vertices).
std::unique_ptr<ImpactLaw> makeImpactLaw(const DiscretePlate& plate, const Obstacles& obstacles, double restitution,
                                         bool carryImpulses);

}  // namespace plate
