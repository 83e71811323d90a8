#include "NewmarkContactStepper.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "PlateParameters.h"

namespace plate {

NewmarkContactStepper::NewmarkContactStepper(std::shared_ptr<const DiscretePlate> plate, double dt, double beta,
                                             Obstacles obstacles, SchemeOptions options)
    : plate_(std::move(plate)), dt_(dt), beta_(beta), obstacles_(obstacles), options_(options) {
    const auto n = plate_->size();
    const int m = plate_->contactCount();
    rhs_.resize(n);
    d_.resize(n);
    wNext_.resize(n);
    kwNext_.resize(n);
    if (!obstacles_.any()) options_.singularMass = false;  // no contact, no impulses to carry
    generalLaw_ = options_.restitution > 0.0 || options_.singularMass;
    if (options_.dampingMass > 0.0 || options_.dampingStiffness > 0.0) {
        dampingBuffer_.resize(n);
        massVelocity_.resize(n);
        massVelocityNext_.resize(n);
    }
    if (options_.singularMass) {
        impulseHistory_.resize(m);
        impulseNext_.resize(m);
    }
    if (obstacles_.any()) {
        const DiscretePlate* p = plate_.get();
        columns_ = std::make_unique<ContactColumns>(
            m, [p](int j, Eigen::VectorXd& z) { p->stepMatrixContactColumn(j, z); },
            [p](const Eigen::VectorXd& z, Eigen::VectorXd& y) { p->gatherContact(z, y); });
        qp_ = std::make_unique<BoxQP>(*columns_);
        yFree_.resize(m);
        y_.resize(m);
        yPrev_.resize(m);
        mu_ = Eigen::VectorXd::Zero(m);
        lowerBound_.resize(m);
        upperBound_.resize(m);
        trialState_.assign(m, 0);
        rowNormBound_ = plate_->contactRowNormBound();
        if (rowNormBound_ > 0.0) wCheck_.resize(n);
    }
}

void NewmarkContactStepper::initialize(const Eigen::VectorXd& w0, double z0, double p0) {
    NewmarkState& s = state_;
    s = NewmarkState{};
    massVelocityValid_ = false;
    s.w = w0;
    s.wPrev = w0;
    s.wPrev2 = w0;
    plate_->applyStiffness(w0, s.kw);
    s.kwPrev = s.kw;
    s.z = s.zPrev = s.zPrev2 = z0;
    s.p = s.pPrev = s.pPrev2 = p0;
    s.pressureWork = s.pressureWorkPrev = plate_->pressureLoad().dot(w0);
    s.baseCoupling = s.baseCouplingPrev = s.baseCouplingPrev2 = plate_->baseInertia().dot(w0);
    s.contactState.assign(obstacles_.any() ? plate_->contactCount() : 0, 0);
    if (options_.singularMass) {
        s.contactImpulse = Eigen::VectorXd::Zero(plate_->contactCount());
        s.contactImpulsePrev = s.contactImpulse;
    }
    checkMargin_ = -1.0;
    if (obstacles_.any()) {
        plate_->gatherContact(w0, y_);
        for (int i = 0; i < y_.size(); ++i) {
            const double u = y_[i] + z0;
            if (u <= obstacles_.lower) s.contactState[i] = -1;
            if (u >= obstacles_.upper) s.contactState[i] = +1;
            s.contactVertices += s.contactState[i] != 0;
        }
    }
}

void NewmarkContactStepper::setInitialContactForce(const Eigen::VectorXd& force) {
    if (!options_.singularMass || state_.step != 0) return;
    state_.contactImpulse = (beta_ * dt_ * dt_) * force;
    state_.contactImpulsePrev = state_.contactImpulse;
}

void NewmarkContactStepper::setLoadAtStart(double p0) {
    // With a singular mass the load before t = 0 stays the one the initial state's massless part
    // is in equilibrium with (docs/theory.md §11).
    if (state_.step == 0 && !options_.singularMass) state_.p = state_.pPrev = state_.pPrev2 = p0;
}

void NewmarkContactStepper::step(double zNext, double pNext) {
    NewmarkState& s = state_;
    if (!std::isfinite(zNext) || !std::isfinite(pNext)) {
        std::ostringstream msg;
        msg << "non-finite input at t = " << (s.step + 1) * dt_ << ": base_displacement = " << zNext
            << ", load = " << pNext;
        throw StepError(msg.str());
    }
    if (!(std::fabs(zNext) <= kMaxDisplacement && std::fabs(pNext) <= kMaxLoad)) {
        std::ostringstream msg;
        msg << "input out of range at t = " << (s.step + 1) * dt_ << ": base_displacement = " << zNext
            << ", load = " << pNext << " (allowed: |base_displacement| <= " << kMaxDisplacement
            << " m, |load| <= " << kMaxLoad << " Pa)";
        throw StepError(msg.str());
    }
    if (zNext < obstacles_.lower || zNext > obstacles_.upper) {
        std::ostringstream msg;
        msg.precision(15);  // round-trips what users type (0.7, not 0.69999999999999996)
        msg << "base_displacement = " << zNext << " at t = " << (s.step + 1) * dt_ << " puts the clamped edge past "
            << (zNext < obstacles_.lower ? "obstacle_lower = " : "obstacle_upper = ")
            << (zNext < obstacles_.lower ? obstacles_.lower : obstacles_.upper)
            << " (allowed: obstacle_lower <= base_displacement <= obstacle_upper)";
        throw StepError(msg.str());
    }
    const double dt2 = dt_ * dt_;
    const double baseJump = zNext - 2.0 * s.z + s.zPrev;  // Δt² z̈_n
    const double pBeta = beta_ * pNext + (1.0 - 2.0 * beta_) * s.p + beta_ * s.pPrev;  // f^{nβ}
    // (3.6) as A d = Δt²(f^{nβ} − K w) − (M·1) Δt² z̈  for d = w⁺ − 2w + w⁻.
    rhs_.noalias() = (dt2 * pBeta) * plate_->pressureLoad() - dt2 * s.kw;
    rhs_.noalias() -= baseJump * plate_->baseInertia();
    if (dampingBuffer_.size() > 0) {
        // Centered damping C(w⁺ − w⁻)/(2Δt) with w⁺ − w⁻ = d + 2(w − w⁻): A carries C d Δt/2, the
        // rest is −Δt C(w − w⁻) (§13); K w and K w⁻ are kept, so the stiffness part is free.
        if (options_.dampingStiffness > 0.0) rhs_.noalias() -= (dt_ * options_.dampingStiffness) * (s.kw - s.kwPrev);
        if (options_.dampingMass > 0.0) {
            if (!massVelocityValid_) {
                dampingBuffer_.noalias() = s.w - s.wPrev;
                plate_->applyMass(dampingBuffer_, massVelocity_);
                massVelocityValid_ = true;
            }
            rhs_.noalias() -= (dt_ * options_.dampingMass) * massVelocity_;
        }
    }
    if (options_.singularMass) {
        // Cᵀν with ν = ((1−2β)/β) μ_n + μ_{n−1}: the β-average of the contact forces of the massless
        // equilibria at t_{n−1}, t_n, t_{n+1} (§11); μ_{n+1} comes from this step's QP.
        impulseHistory_.noalias() = ((1.0 - 2.0 * beta_) / beta_) * s.contactImpulse + s.contactImpulsePrev;
        plate_->scatterContact(impulseHistory_, rhs_);
    }
    plate_->solveStepMatrix(rhs_, d_);
    wNext_.noalias() = 2.0 * s.w - s.wPrev + d_;

    double dissipated = 0.0, contactWorkOnBase = 0.0;
    // The port (§14): the step's contact impulses τ per obstacle (lower τ > 0, upper τ < 0) and
    // their moment about the clamp line, summed over the vertices the contact work visits.
    double contactSum[2] = {0.0, 0.0}, contactMoment = 0.0;
    const std::vector<double>& lever = plate_->contactAbscissae();
    int contactCount = 0;
    int iterations = 0;
    double kkt = 0.0;
    if (qp_) {
        const double lo = obstacles_.lower - zNext, hi = obstacles_.upper - zNext;
        bool violated = false;
        if (generalLaw_) {
            // The constraint on (u⁺ + e u⁻)/(1 + e) (§12): per-vertex bounds on y⁺ = C w⁺,
            // (1+e)·obstacle − e u⁻ − z⁺. Every vertex is looked at, every step.
            const double e = options_.restitution;
            plate_->gatherContact(s.wPrev, yPrev_);
            plate_->gatherContact(wNext_, yFree_);
            for (int i = 0; i < yFree_.size(); ++i) {
                const double uPrev = yPrev_[i] + s.zPrev;
                lowerBound_[i] = e > 0.0 ? (1.0 + e) * obstacles_.lower - e * uPrev - zNext : lo;
                upperBound_[i] = e > 0.0 ? (1.0 + e) * obstacles_.upper - e * uPrev - zNext : hi;
                violated |= (yFree_[i] < lowerBound_[i]) | (yFree_[i] > upperBound_[i]);
            }
        } else if (checkMargin_ <= 0.0 ||  // 1e-12 m: roundoff of the values the bound is compared with
                   rowNormBound_ * (wNext_ - wCheck_).norm() + std::abs(zNext - zCheck_) + 1e-12 >= checkMargin_) {
            plate_->gatherContact(wNext_, yFree_);
            double margin = std::numeric_limits<double>::infinity();
            for (int i = 0; i < yFree_.size(); ++i) {
                violated |= (yFree_[i] < lo) | (yFree_[i] > hi);
                margin = std::min(margin, std::min(yFree_[i] - lo, hi - yFree_[i]));
            }
            checkMargin_ = -1.0;
            if (!violated && rowNormBound_ > 0.0) {
                wCheck_ = wNext_;  // same size: no allocation
                zCheck_ = zNext;
                checkMargin_ = margin;
            }
        }
        if (violated) {
            if (!generalLaw_) {
                lowerBound_.setConstant(lo);
                upperBound_.setConstant(hi);
            }
            trialState_ = s.contactState;
            const QPResult r = qp_->solve(yFree_, lowerBound_, upperBound_, trialState_, mu_, y_);
            iterations = r.iterations;
            kkt = r.kktResidual;
            if (!r.converged || !(kkt <= 1e-10)) {
                std::ostringstream msg;
                msg << "contact QP did not converge at t = " << (s.step + 1) * dt_ << " (" << r.iterations
                    << " iterations, relative KKT residual " << kkt << ")";
                throw StepError(msg.str());
            }
            for (int i : qp_->active()) wNext_.noalias() += mu_[i] * columns_->column(i);
            contactCount = static_cast<int>(qp_->active().size());
        } else {
            std::fill(trialState_.begin(), trialState_.end(), 0);
        }
        if (!generalLaw_ && violated) {
            // Loss ½ λᵀ(u⁻ − u⁺) on the active vertices (docs/theory.md), absolute heights. Each
            // term is ≥ 0 in exact arithmetic (u⁺ on the obstacle, u⁻ not past it). A vertex
            // that stays on the obstacle has u⁻ there only up to the roundoff of
            // w + Σ μ_j A⁻¹Cᵀe_j (~1e-17 m), which can make its term ~1e-13 J negative: that
            // is no physical work at all, so it is dropped — energy_dissipated never
            // decreases, energy_input stays exactly 0 without inputs, and the ledger keeps
            // closing to roundoff (the dropped amounts are of that size).
            plate_->gatherContact(s.wPrev, yPrev_);
            double muSum = 0.0;
            for (int i : qp_->active()) {
                muSum += mu_[i];
                contactSum[mu_[i] < 0.0] += mu_[i];
                contactMoment += mu_[i] * lever[i];
                dissipated += std::max(0.0, mu_[i] * ((yPrev_[i] + s.zPrev) - (y_[i] + zNext)));
            }
            dissipated /= 2.0 * dt2;
            contactWorkOnBase = -muSum * (zNext - s.zPrev) / (2.0 * dt2);
        } else if (generalLaw_) {
            // The contact work of the step, ½ τᵀ(u⁺ − u⁻)/Δt² with τ = μ (+ ν with a singular mass)
            // the whole impulse: at a vertex on the law's constraint u⁺ − u⁻ = (1+e)(obstacle − u⁻)
            // (§12). Not clamped: with e > 0 or a singular mass it can return energy (§12, §11).
            const Eigen::VectorXd& yNext = violated ? y_ : yFree_;
            double tauSum = 0.0;
            for (int i = 0; i < yNext.size(); ++i) {
                double tau = violated ? mu_[i] : 0.0;
                if (options_.singularMass) {
                    impulseNext_[i] = tau;
                    tau += impulseHistory_[i];
                }
                if (tau == 0.0) continue;
                contactSum[tau < 0.0] += tau;
                contactMoment += tau * lever[i];
                dissipated += tau * ((yPrev_[i] + s.zPrev) - (yNext[i] + zNext));
                tauSum += tau;
            }
            dissipated /= 2.0 * dt2;
            contactWorkOnBase = -tauSum * (zNext - s.zPrev) / (2.0 * dt2);
        }
    }
    plate_->applyStiffness(wNext_, kwNext_);
    double damped = 0.0;
    if (dampingBuffer_.size() > 0) {
        // (w⁺ − w⁻)ᵀ C (w⁺ − w⁻) / (4Δt): the damping term of the step times (w⁺ − w⁻)/2 (§13).
        if (options_.dampingMass > 0.0) {
            // M(w⁺ − w⁻) = M(w⁺ − w) + M(w − w⁻): one product per step, the first part kept
            // for the next step's right-hand side.
            dampingBuffer_.noalias() = wNext_ - s.w;
            plate_->applyMass(dampingBuffer_, massVelocityNext_);
        }
        dampingBuffer_.noalias() = wNext_ - s.wPrev;
        if (options_.dampingStiffness > 0.0)
            damped += options_.dampingStiffness * dampingBuffer_.dot(kwNext_ - s.kwPrev);
        if (options_.dampingMass > 0.0)
            damped += options_.dampingMass * dampingBuffer_.dot(massVelocityNext_ + massVelocity_);
        damped /= 4.0 * dt_;
    }
    const double sNext = plate_->pressureLoad().dot(wNext_);
    const double tNext = plate_->baseInertia().dot(wNext_);
    if (!std::isfinite(sNext) || !std::isfinite(tNext)) {
        std::ostringstream msg;
        msg << "the step to t = " << (s.step + 1) * dt_ << " produced a non-finite displacement";
        throw StepError(msg.str());
    }

    // Discrete work of the inputs in this step, from the scheme (see energy()): pressure and
    // base inertia on w⁺ − w⁻, the contact force on the moving frame, and the change of the
    // cross term ż vᵀ(M·1) + ½ ż² 1ᵀM1 that turns the relative energy into the absolute one.
    const double zDotNext = (zNext - s.z) / dt_, zDot = (s.z - s.zPrev) / dt_;
    const double mass = plate_->totalMass();
    const double crossNext = zDotNext * (tNext - s.baseCoupling) / dt_ + 0.5 * zDotNext * zDotNext * mass;
    const double cross = zDot * (s.baseCoupling - s.baseCouplingPrev) / dt_ + 0.5 * zDot * zDot * mass;
    const double work = 0.5 * pBeta * (sNext - s.pressureWorkPrev) -
                        0.5 * (baseJump / dt2) * (tNext - s.baseCouplingPrev) + contactWorkOnBase + crossNext - cross;

    // Commit.
    s.wPrev2.swap(s.wPrev);  // three levels rotate by swaps: no copy
    s.wPrev.swap(s.w);
    s.w.swap(wNext_);
    s.kwPrev.swap(s.kw);
    s.kw.swap(kwNext_);
    s.zPrev2 = s.zPrev;
    s.zPrev = s.z;
    s.z = zNext;
    s.pPrev2 = s.pPrev;
    s.pPrev = s.p;
    s.p = pNext;
    s.pressureWorkPrev = s.pressureWork;
    s.pressureWork = sNext;
    s.baseCouplingPrev2 = s.baseCouplingPrev;
    s.baseCouplingPrev = s.baseCoupling;
    s.baseCoupling = tNext;
    for (int k = 0; k < 2; ++k) {
        const double force = contactSum[k] / dt2;
        s.impactCount[k] += force != 0.0 && s.stepContactForce[k] == 0.0;  // a contact onset
        s.stepContactForce[k] = force;
        s.contactImpulseSum[k] += force * dt_;
    }
    s.stepContactMoment = contactMoment / dt2;
    ++s.step;
    s.energyInput += work;
    s.energyDissipated += dissipated;
    s.energyDamped += damped;
    if (options_.dampingMass > 0.0) massVelocity_.swap(massVelocityNext_);
    if (options_.singularMass) {
        s.contactImpulsePrev.swap(s.contactImpulse);
        s.contactImpulse.swap(impulseNext_);
    }
    if (qp_) s.contactState.swap(trialState_);
    s.contactVertices = contactCount;
    s.qpIterationsLast = iterations;
    s.qpIterationsTotal += iterations;
    s.qpIterationsMax = std::max(s.qpIterationsMax, iterations);
    s.maxKktResidual = std::max(s.maxKktResidual, kkt);
}

double NewmarkContactStepper::energy() const {
    // E = ½ vᵀ(M + (β−¼)Δt²K) v + ½ ūᵀKū with v the absolute velocity (w − w⁻)/Δt + ż·1 and
    // ū = (w + w⁻)/2; K·1 = 0, so only the mass sees the base (docs/theory.md).
    const NewmarkState& s = state_;
    dwScratch_ = s.w - s.wPrev;  // read once per communication step: reuse the buffers
    const Eigen::VectorXd& dw = dwScratch_;
    plate_->applyMass(dw, scratch_);
    const double dt2 = dt_ * dt_;
    const double zDot = (s.z - s.zPrev) / dt_;
    const double kinetic = 0.5 * dw.dot(scratch_) / dt2 + 0.5 * (beta_ - 0.25) * dw.dot(s.kw - s.kwPrev) +
                           zDot * (s.baseCoupling - s.baseCouplingPrev) / dt_ + 0.5 * zDot * zDot * plate_->totalMass();
    const double potential = 0.125 * (s.w + s.wPrev).dot(s.kw + s.kwPrev);
    return kinetic + potential;
}

}  // namespace plate
