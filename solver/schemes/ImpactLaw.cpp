#include "schemes/ImpactLaw.h"

#include "schemes/FreeFlightBound.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace plate {

namespace {

// The paper's law (§4–5): the constraint on u⁺ itself, contact work only where the QP ran.
// Free flight without looking at every vertex (complete modal basis: the look is a dense
// product): FreeFlightBound.
class InelasticImpact final : public ImpactLaw {
public:
    InelasticImpact(const DiscretePlate& plate, const Obstacles& obstacles) : plate_(plate) {
        obstacles.rowBounds(plate.clamped().contactStops, rowLower_, rowUpper_);
        freeFlight_.setup(plate.size(), plate.contactRowNormBound());
    }

    bool bounds(const NewmarkState&, const Eigen::VectorXd& wFree, double zNext, ContactBuffers& b) override {
        bool violated = false;
        if (!freeFlight_.holds(wFree, zNext)) {
            plate_.gatherContact(wFree, b.yFree);
            double margin = std::numeric_limits<double>::infinity();
            for (int i = 0; i < b.yFree.size(); ++i) {
                const double lo = rowLower_[i] - zNext, hi = rowUpper_[i] - zNext;
                violated = violated || b.yFree[i] < lo || b.yFree[i] > hi;
                margin = std::min(margin, std::min(b.yFree[i] - lo, hi - b.yFree[i]));
            }
            freeFlight_.reset();
            if (!violated) freeFlight_.restart(wFree, zNext, 0.0, margin);
        }
        if (violated) {
            b.lower.array() = rowLower_.array() - zNext;
            b.upper.array() = rowUpper_.array() - zNext;
        }
        return violated;
    }

    // Loss ½ λᵀ(u⁻ − u⁺) on the active vertices (§6), absolute heights. Each term is ≥ 0 in
    // exact arithmetic (u⁺ on the obstacle, u⁻ not past it). A vertex that stays on the obstacle
    // has u⁻ there only up to the roundoff of w + Σ μ_j A⁻¹Cᵀe_j (~1e-17 m), which can make its
    // term ~1e-13 J negative: that is no physical work at all, so it is dropped —
    // energy_dissipated never decreases, energy_input stays exactly 0 without inputs, and the
    // ledger keeps closing to roundoff (the dropped amounts are of that size).
    ContactWork work(const NewmarkState& s, bool violated, double zNext, ContactBuffers& b) override {
        ContactWork w;
        if (!violated) return w;
        const std::vector<double>& lever = plate_.contactAbscissae();
        plate_.gatherContact(s.wPrev, b.yPrev);
        double muSum = 0.0;
        for (int i : *b.active) {
            muSum += b.mu[i];
            w.sum[b.mu[i] < 0.0] += b.mu[i];
            w.moment += b.mu[i] * lever[i];
            w.dissipated += std::max(0.0, b.mu[i] * ((b.yPrev[i] + s.zPrev) - (b.y[i] + zNext)));
        }
        const double dt2 = plate_.dt() * plate_.dt();
        w.dissipated /= 2.0 * dt2;
        w.onBase = -muSum * (zNext - s.zPrev) / (2.0 * dt2);
        return w;
    }

    void reset() override { freeFlight_.reset(); }

private:
    const DiscretePlate& plate_;
    Eigen::VectorXd rowLower_, rowUpper_;  // each contact row's obstacles (±∞ off its stops, §25)
    FreeFlightBound freeFlight_;
};

// What the laws that look at every vertex, every step share: the constraint on
// (u⁺ + e u⁻)/(1 + e) (§12; e = 0: on u⁺) and the contact work of the whole impulse τ of the
// step, not clamped (it can return energy). The derived law gives τ per vertex from the QP's
// multiplier (workOf's `impulse`, inlined: no virtual call per vertex).
class VertexImpact : public ImpactLaw {
public:
    // Per-vertex bounds on y⁺ = C w⁺: (1+e)·obstacle − e u⁻ − z⁺.
    bool bounds(const NewmarkState& s, const Eigen::VectorXd& wFree, double zNext, ContactBuffers& b) final {
        plate_.gatherContact(s.wPrev, b.yPrev);
        plate_.gatherContact(wFree, b.yFree);
        if (e_ > 0.0) {
            for (int i = 0; i < b.yFree.size(); ++i) {
                const double uPrev = b.yPrev[i] + s.zPrev;
                b.lower[i] = (1.0 + e_) * rowLower_[i] - e_ * uPrev - zNext;
                b.upper[i] = (1.0 + e_) * rowUpper_[i] - e_ * uPrev - zNext;
            }
        } else {
            b.lower.array() = rowLower_.array() - zNext;
            b.upper.array() = rowUpper_.array() - zNext;
        }
        bool violated = false;
        for (int i = 0; i < b.yFree.size(); ++i)
            violated = violated || b.yFree[i] < b.lower[i] || b.yFree[i] > b.upper[i];
        return violated;
    }

protected:
    VertexImpact(const DiscretePlate& plate, const Obstacles& obstacles, double restitution)
        : plate_(plate), e_(restitution) {
        obstacles.rowBounds(plate.clamped().contactStops, rowLower_, rowUpper_);
    }

    // ½ τᵀ(u⁺ − u⁻)/Δt² with τ_i = impulse(i, μ_i) the whole impulse at vertex i (μ_i = 0 where
    // the QP did not run): at a vertex on the law's constraint u⁺ − u⁻ = (1+e)(obstacle − u⁻) (§12).
    template <class Impulse>
    ContactWork workOf(const NewmarkState& s, bool violated, double zNext, const ContactBuffers& b,
                       Impulse&& impulse) const {
        ContactWork w;
        const std::vector<double>& lever = plate_.contactAbscissae();
        const Eigen::VectorXd& yNext = violated ? b.y : b.yFree;
        double tauSum = 0.0;
        for (int i = 0; i < yNext.size(); ++i) {
            const double tau = impulse(i, violated ? b.mu[i] : 0.0);
            if (tau == 0.0) continue;
            w.sum[tau < 0.0] += tau;
            w.moment += tau * lever[i];
            w.dissipated += tau * ((b.yPrev[i] + s.zPrev) - (yNext[i] + zNext));
            tauSum += tau;
        }
        const double dt2 = plate_.dt() * plate_.dt();
        w.dissipated /= 2.0 * dt2;
        w.onBase = -tauSum * (zNext - s.zPrev) / (2.0 * dt2);
        return w;
    }

    const DiscretePlate& plate_;
    Eigen::VectorXd rowLower_, rowUpper_;  // each contact row's obstacles (±∞ off its stops, §25)
    double e_;
};

// Restitution with a consistent mass (§12, e > 0): the impulse of a step is the QP's multiplier.
class RestitutionImpact final : public VertexImpact {
public:
    RestitutionImpact(const DiscretePlate& plate, const Obstacles& obstacles, double restitution)
        : VertexImpact(plate, obstacles, restitution) {}

    ContactWork work(const NewmarkState& s, bool violated, double zNext, ContactBuffers& b) override {
        return workOf(s, violated, zNext, b, [](int, double mu) { return mu; });
    }
};

// A singular mass (§11), any e ≥ 0 (§12): the contact impulses of the two previous steps carried
// into the right-hand side, kept in the state (contactImpulse, contactImpulsePrev); the impulse of
// a step is the QP's multiplier plus what was carried.
class SingularMassImpact final : public VertexImpact {
public:
    SingularMassImpact(const DiscretePlate& plate, const Obstacles& obstacles, double restitution)
        : VertexImpact(plate, obstacles, restitution) {
        carried_.resize(plate.contactCount());
        next_.resize(plate.contactCount());
    }

    // Cᵀν with ν = ((1−2β)/β) μ_n + μ_{n−1} (T.4): the β-average of the contact forces of the massless
    // equilibria at t_{n−1}, t_n, t_{n+1} (§11); μ_{n+1} comes from this step's QP.
    void addCarried(const NewmarkState& s, Eigen::VectorXd& rhs) override {
        const double beta = plate_.beta();
        carried_.noalias() = ((1.0 - 2.0 * beta) / beta) * s.contactImpulse + s.contactImpulsePrev;
        plate_.scatterContact(carried_, rhs);
    }

    ContactWork work(const NewmarkState& s, bool violated, double zNext, ContactBuffers& b) override {
        return workOf(s, violated, zNext, b, [this](int i, double mu) {
            next_[i] = mu;
            return mu + carried_[i];
        });
    }

    void commit(NewmarkState& s) override {
        s.contactImpulsePrev.swap(s.contactImpulse);
        s.contactImpulse.swap(next_);
    }

    // No impulse before t = 0 unless setInitialContactForce gives one.
    void initialize(NewmarkState& s) override {
        s.contactImpulse = Eigen::VectorXd::Zero(plate_.contactCount());
        s.contactImpulsePrev = s.contactImpulse;
    }

    // The impulse history βΔt²λ0 at t_0 and t_{−1}: the massless part balanced at both.
    void setInitialContactForce(NewmarkState& s, const Eigen::VectorXd& force) override {
        s.contactImpulse = (plate_.beta() * plate_.dt() * plate_.dt()) * force;
        s.contactImpulsePrev = s.contactImpulse;
    }

    // The initial state's massless part is in equilibrium with the load it was made with (§11).
    bool keepsLoadBeforeStart() const override { return true; }

private:
    Eigen::VectorXd carried_, next_;
};

}  // namespace

std::unique_ptr<ImpactLaw> makeImpactLaw(const DiscretePlate& plate, const Obstacles& obstacles, double restitution,
                                         bool carryImpulses) {
    if (carryImpulses) return std::make_unique<SingularMassImpact>(plate, obstacles, restitution);
    if (restitution > 0.0) return std::make_unique<RestitutionImpact>(plate, obstacles, restitution);
    return std::make_unique<InelasticImpact>(plate, obstacles);
}

}  // namespace plate
