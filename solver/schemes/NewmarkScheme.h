#pragma once
// The Newmark (γ = ½, β) scheme with contact of §3.2, three-level form (3.3)/(3.6), in the
// relative displacement w = u − z(t)·1 of the clamped plate (docs/theory.md §3–4):
//
//   M d + Δt² K (w + β d) = Δt² p^{nβ} F − (M·1)(z⁺ − 2z + z⁻) + Cᵀμ,   d = w⁺ − 2w + w⁻,
//   lower − z⁺ ≤ C w⁺ ≤ upper − z⁺,  μ the contact multipliers of the step's QP.
//
// Beyond the paper (the plate's law and SchemeOptions, all off by default: then the step is the above,
// bit for bit): the restitution law on (u⁺ + e u⁻)/(1 + e) (§12), Rayleigh damping (§13), and with a singular
// mass the contact impulses of the two previous steps on the right-hand side, which keep the
// massless part in equilibrium at every t_n (§11).
//
// Each step: one solve with the factor of A = M + βΔt²K for the free solution, a look at the
// contact vertices, and the contact-space QP (BoxQP) only where an obstacle is violated.
#include <Eigen/Core>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "schemes/Armature.h"
#include "plate/BoxQP.h"
#include "plate/DiscretePlate.h"
#include "schemes/ImpactLaw.h"
#include "schemes/Scheme.h"
#include "schemes/NewmarkState.h"
#include "plate/Obstacles.h"

namespace plate {

struct SchemeOptions {
    // The plate's mass is singular: carry the contact impulses (docs/theory.md §11). It only
    // chooses the law (makeImpactLaw: SingularMassImpact, which keeps the impulses in the state;
    // no obstacle, no law: nothing carried). Off with a singular mass gives the plain Newmark
    // step with M_s (kept to measure what it changes).
    bool singularMass = false;
    // The clamp carried by an armature or a line end inside the step (docs/theory.md §18–19): step()
    // then takes the carrier's drive force in place of the base position.
    bool carried = false;
    CarrierOptions carrier;
};

// Where the outputs are read: corner_1 (length, 0), corner_2 (length, width) and free_edge_mid
// (length, width/2), and how many mesh vertices vertex_displacement has. Empty: no outputs but
// the ledger (the unit tests).
struct OutputPoints {
    double length = 0.0, width = 0.0;
    int vertexCount = 0;
};

class NewmarkScheme final : public Scheme {
public:
    // Δt, β, the damping and the restitution are the plate's law (DiscretePlate::law: its step matrix was
    // factored with them).
    NewmarkScheme(std::shared_ptr<const DiscretePlate> plate, Obstacles obstacles, SchemeOptions options = {},
                  OutputPoints points = {});

    // The plate at rest for t ≤ 0 in the shape w0 with the clamp at z0, pressure p0.
    void initialize(const Eigen::VectorXd& w0, double z0, double p0);
    // Singular mass: the contact forces λ0 (per contact vertex) that hold the initial state's
    // massless part in equilibrium; the impulse history becomes βΔt²λ0 at t_0 and t_{−1} (the
    // law's: ImpactLaw::setInitialContactForce; ignored by a law that carries nothing).
    void setInitialContactForce(const Eigen::VectorXd& force);

    // The load input at t = 0, known only when the master starts stepping: the history holds
    // it for t ≤ 0 (docs/theory.md: the load acts from t = 0 on; the initial load only shapes u⁰).
    // Only before the first step, and not when the law keeps the initial load (ImpactLaw::
    // keepsLoadBeforeStart: a singular mass, §11).
    void setLoadAtStart(double p0) override;
    // The clamp's load at t = 0: the initial static state's reaction (force N, moment N·m).
    void setInitialReaction(double force, double moment) {
        initialForce_ = force;
        initialMoment_ = moment;
    }

    std::vector<double> vertexDisplacements() const override;
    void recover(Eigen::Index first, int level, Eigen::Ref<Eigen::VectorXd> out) const override {
        const NewmarkState& st = state_;
        recovery_.apply(first, atLevel(level, st.w, st.wPrev, st.wPrev2), out);
    }
    // The recovery functionals in the plate's coordinates (DiscretePlate::rows; docs/theory.md §23).
    void setRecovery(LinearRows rows) { recovery_ = std::move(rows); }
    std::vector<double> saveState() const override { return serialize(state_); }
    void restoreState(const std::vector<double>& state) override;
    std::string name() const override;
    double firstFrequency() const override;
    double kappa() const override;

    // Discrete energy E^{n−½} (docs/theory.md), absolute velocity in the kinetic part.
    double energy() const;

    const NewmarkState& state() const { return state_; }
    void setState(const NewmarkState& s) {
        state_ = s;
        if (law_) law_->reset();  // e.g. the free-flight bound restarts from a full look
        massVelocityValid_ = false;
        energyStep_ = -1;
    }
    const DiscretePlate& plate() const { return *plate_; }
    double beta() const { return plate_->beta(); }
    const SchemeOptions& options() const { return options_; }
    Armature* carrier() override { return armature_.get(); }  // nullptr unless options().carried
    using Scheme::carrier;
    CarrierOutputs carrierOutputs() const override;

private:
    // The step of (3.6) (docs/theory.md §3–4): the free solution, the law's contact phase, the ledger.
    void advance(double zNext, double pNext) override;
    const SchemeState& shared() const override { return state_; }
    double pointHeight(int k, int level) const override;
    double outputEnergy() const override;  // energy(), once per step
    void clampLoad(double& force, double& moment) const override;  // (T.14a, b)
    void stepCarried(double fNext, double pNext);  // step() with the carrier (Armature.cpp)
    void assembleRightHandSide(double baseJump, double pBeta);  // rhs_ of (3.6) for d
    // The contact phase (§3.4 + the law): the QP where an obstacle is violated, wNext_ corrected.
    ContactWork resolveContact(double zNext, int& iterations, double& kkt, int& contactCount);
    double dampingWork();  // the step's Rayleigh dissipation (§13); also M(w⁺ − w) for the next step
    // After the contact phase: K w⁺, the damping work and Fᵀw⁺, (M·1)ᵀw⁺ (§6); a non-finite step
    // throws StepError.
    struct SolvedStep {
        double damped, pressureWork, baseCoupling;
    };
    SolvedStep finishSolve();
    double inputWork(double zNext, double baseJump, double pBeta, double sNext, double tNext,
                     const ContactWork& contact) const;
    void commit(double zNext, double pNext, double sNext, double tNext, const ContactWork& contact, double damped,
                double work, int iterations, double kkt, int contactCount);

    std::shared_ptr<const DiscretePlate> plate_;
    SchemeOptions options_;
    NewmarkState state_;
    // Contact machinery exists only when an obstacle does (no obstacle → no QP, no law).
    std::unique_ptr<ContactColumns> columns_;
    std::unique_ptr<BoxQP> qp_;
    std::unique_ptr<ImpactLaw> law_;
    ContactBuffers contact_;
    // Step buffers, allocated once.
    Eigen::VectorXd rhs_, d_, wNext_, kwNext_, dampingBuffer_;
    // Mass-proportional damping: M(w − w⁻), a function of the state, computed once per step (at
    // the end of the previous one) and recomputed after setState/initialize.
    Eigen::VectorXd massVelocity_, massVelocityNext_;
    bool massVelocityValid_ = false;
    std::vector<signed char> trialState_;
    std::unique_ptr<Armature> armature_;
    double carrierShift_ = 0.0;  // the contact phase's change of z⁺ (carrier only)
    mutable Eigen::VectorXd scratch_, dwScratch_;
    // The outputs (docs/theory.md §14): the probes, the initial reaction, the energy of the last
    // step read and κ_h once computed.
    int vertexCount_;
    PointProbe corner1_, corner2_, freeEdgeMid_;
    LinearRows recovery_;  // probes and stress samples (§23)
    double initialForce_ = 0.0, initialMoment_ = 0.0;
    mutable long long energyStep_ = -1;
    mutable double energyCache_ = 0.0, kappa_ = -1.0;
};

}  // namespace plate
