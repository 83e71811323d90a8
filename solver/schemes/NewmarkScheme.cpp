#include "schemes/NewmarkScheme.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "base/History.h"
#include "plate/ModalPlate.h"
#include "plate/PlateParameters.h"
#include "plate/Spectrum.h"

namespace plate {

NewmarkScheme::NewmarkScheme(std::shared_ptr<const DiscretePlate> plate, Obstacles obstacles, SchemeOptions options,
                             OutputPoints points)
    : Scheme(obstacles, plate->dt()),
      plate_(std::move(plate)),
      options_(options),
      vertexCount_(points.vertexCount),
      corner1_(plate_->probe(points.length, 0.0)),
      corner2_(plate_->probe(points.length, points.width)),
      freeEdgeMid_(plate_->probe(points.length, 0.5 * points.width)) {
    const auto n = plate_->size();
    const int m = plate_->contactCount();
    rhs_.resize(n);
    d_.resize(n);
    wNext_.resize(n);
    kwNext_.resize(n);
    if (plate_->law().dampingMass > 0.0 || plate_->law().dampingStiffness > 0.0) {
        dampingBuffer_.resize(n);
        massVelocity_.resize(n);
        massVelocityNext_.resize(n);
    }
    if (options_.carried) armature_ = std::make_unique<Armature>(*plate_, options_.carrier);
    setCarried(options_.carried);  // the carrier checks its own drive (stepCarried)
    if (obstacles_.any()) {
        const DiscretePlate* p = plate_.get();
        columns_ = std::make_unique<ContactColumns>(
            m, [p](int j, Eigen::VectorXd& z) { p->stepMatrixContactColumn(j, z); },
            [p](const Eigen::VectorXd& z, Eigen::VectorXd& y) { p->gatherContact(z, y); });
        if (armature_) columns_ = armature_->contactColumns();  // the bordered matrix's (T.19)
        qp_ = std::make_unique<BoxQP>(*columns_);
        law_ = makeImpactLaw(*plate_, obstacles_, plate_->law().restitution, options_.singularMass);
        for (Eigen::VectorXd* v : {&contact_.yFree, &contact_.y, &contact_.yPrev, &contact_.lower, &contact_.upper})
            v->resize(m);
        contact_.mu = Eigen::VectorXd::Zero(m);
        contact_.active = &qp_->active();
        trialState_.assign(m, 0);
    }
}

void NewmarkScheme::initialize(const Eigen::VectorXd& w0, double z0, double p0) {
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
    if (law_) {
        law_->initialize(s);  // its part of the state (e.g. the carried impulses, zero)
        law_->reset();
    }
    if (armature_) armature_->reset();
    if (obstacles_.any()) {
        Eigen::VectorXd& y = contact_.y;
        plate_->gatherContact(w0, y);
        Eigen::VectorXd lower, upper;  // each row's obstacles (docs/theory.md §25)
        obstacles_.rowBounds(plate_->clamped().contactStops, lower, upper);
        for (int i = 0; i < y.size(); ++i) {
            const double u = y[i] + z0;
            if (u <= lower[i]) s.contactState[i] = -1;
            if (u >= upper[i]) s.contactState[i] = +1;
            s.contactPoints += s.contactState[i] != 0;
        }
    }
}

void NewmarkScheme::setInitialContactForce(const Eigen::VectorXd& force) {
    if (law_ && state_.step == 0) law_->setInitialContactForce(state_, force);
}

void NewmarkScheme::setLoadAtStart(double p0) {
    // The law may keep the load the initial state was made with (a singular mass: its massless
    // part is in equilibrium with it, docs/theory.md §11).
    if (state_.step == 0 && !(law_ && law_->keepsLoadBeforeStart())) state_.p = state_.pPrev = state_.pPrev2 = p0;
}

NewmarkScheme::SolvedStep NewmarkScheme::finishSolve() {
    plate_->applyStiffness(wNext_, kwNext_);
    const double damped = dampingWork();
    const double sNext = plate_->pressureLoad().dot(wNext_);
    const double tNext = plate_->baseInertia().dot(wNext_);
    if (!std::isfinite(sNext) || !std::isfinite(tNext)) refuseNonFinite();
    return {damped, sNext, tNext};
}

// The step of (3.6) = docs/theory.md (T.1) in w = u − z·1 (§3–4): the free solution, the law's
// contact phase, then the ledger (§6) of what the step did.
void NewmarkScheme::advance(double zNext, double pNext) {
    if (armature_) return stepCarried(zNext, pNext);  // zNext is the drive force (§18)
    const NewmarkState& s = state_;
    const double baseJump = zNext - 2.0 * s.z + s.zPrev;  // Δt² z̈_n
    const double pBeta = beta() * pNext + (1.0 - 2.0 * beta()) * s.p + beta() * s.pPrev;  // f^{nβ}
    assembleRightHandSide(baseJump, pBeta);
    plate_->solveStepMatrix(rhs_, d_);
    wNext_.noalias() = 2.0 * s.w - s.wPrev + d_;
    ContactWork contact;
    int iterations = 0, contactCount = 0;
    double kkt = 0.0;
    if (law_) contact = resolveContact(zNext, iterations, kkt, contactCount);
    const auto [damped, sNext, tNext] = finishSolve();
    const double work = inputWork(zNext, baseJump, pBeta, sNext, tNext, contact);
    commit(zNext, pNext, sNext, tNext, contact, damped, work, iterations, kkt, contactCount);
}

// (3.6) as A d = Δt²(f^{nβ} − K w) − (M·1) Δt² z̈ (+ damping, + what the law carries) for
// d = w⁺ − 2w + w⁻.
void NewmarkScheme::assembleRightHandSide(double baseJump, double pBeta) {
    const NewmarkState& s = state_;
    const double dt = this->dt(), dt2 = dt * dt;
    rhs_.noalias() = (dt2 * pBeta) * plate_->pressureLoad() - dt2 * s.kw;
    rhs_.noalias() -= baseJump * plate_->baseInertia();
    if (dampingBuffer_.size() > 0) {
        // (T.5): centered damping C(w⁺ − w⁻)/(2Δt) with w⁺ − w⁻ = d + 2(w − w⁻): A carries C d Δt/2, the
        // rest is −Δt C(w − w⁻) (§13); K w and K w⁻ are kept, so the stiffness part is free.
        const double a = plate_->law().dampingMass, b = plate_->law().dampingStiffness;  // C = a M + b K
        if (b > 0.0) rhs_.noalias() -= (dt * b) * (s.kw - s.kwPrev);
        if (a > 0.0) {
            if (!massVelocityValid_) {
                dampingBuffer_.noalias() = s.w - s.wPrev;
                plate_->applyMass(dampingBuffer_, massVelocity_);
                massVelocityValid_ = true;
            }
            rhs_.noalias() -= (dt * a) * massVelocity_;
        }
    }
    if (law_) law_->addCarried(s, rhs_);
}

ContactWork NewmarkScheme::resolveContact(double zNext, int& iterations, double& kkt, int& contactCount) {
    const NewmarkState& s = state_;
    const bool violated = law_->bounds(s, wNext_, zNext, contact_);
    if (violated) {
        trialState_ = s.contactState;
        const QPResult r =
            qp_->solve(contact_.yFree, contact_.lower, contact_.upper, trialState_, contact_.mu, contact_.y);
        iterations = r.iterations;
        kkt = r.kktResidual;
        if (!r.converged || !(kkt <= 1e-10)) refuseUnsolved("contact QP", r.iterations, kkt);
        if (armature_)
            carrierShift_ = armature_->correct(*columns_, qp_->active(), contact_.mu, wNext_, contact_.y);
        else
            for (int i : qp_->active()) wNext_.noalias() += contact_.mu[i] * columns_->column(i);
        contactCount = static_cast<int>(qp_->active().size());
    } else {
        std::fill(trialState_.begin(), trialState_.end(), 0);
    }
    return law_->work(s, violated, zNext + carrierShift_, contact_);
}

double NewmarkScheme::dampingWork() {
    if (dampingBuffer_.size() == 0) return 0.0;
    const NewmarkState& s = state_;
    // (w⁺ − w⁻)ᵀ C (w⁺ − w⁻) / (4Δt): the damping term of the step times (w⁺ − w⁻)/2 (§13).
    double damped = 0.0;
    const double a = plate_->law().dampingMass, b = plate_->law().dampingStiffness;  // C = a M + b K
    if (a > 0.0) {
        // M(w⁺ − w⁻) = M(w⁺ − w) + M(w − w⁻): one product per step, the first part kept
        // for the next step's right-hand side.
        dampingBuffer_.noalias() = wNext_ - s.w;
        plate_->applyMass(dampingBuffer_, massVelocityNext_);
    }
    dampingBuffer_.noalias() = wNext_ - s.wPrev;
    if (b > 0.0) damped += b * dampingBuffer_.dot(kwNext_ - s.kwPrev);
    if (a > 0.0) damped += a * dampingBuffer_.dot(massVelocityNext_ + massVelocity_);
    return damped / (4.0 * dt());
}

// Discrete work of the inputs in this step, from the scheme (see energy()): pressure and base
// inertia on w⁺ − w⁻, the contact force on the moving frame, and the change of the cross term
// ż vᵀ(M·1) + ½ ż² 1ᵀM1 that turns the relative energy into the absolute one.
double NewmarkScheme::inputWork(double zNext, double baseJump, double pBeta, double sNext, double tNext,
                                const ContactWork& contact) const {
    const NewmarkState& s = state_;
    const double dt = this->dt(), dt2 = dt * dt;
    const double zDotNext = (zNext - s.z) / dt, zDot = (s.z - s.zPrev) / dt;
    const double mass = plate_->totalMass();
    const double crossNext = zDotNext * (tNext - s.baseCoupling) / dt + 0.5 * zDotNext * zDotNext * mass;
    const double cross = zDot * (s.baseCoupling - s.baseCouplingPrev) / dt + 0.5 * zDot * zDot * mass;
    return 0.5 * pBeta * (sNext - s.pressureWorkPrev) - 0.5 * (baseJump / dt2) * (tNext - s.baseCouplingPrev) +
           contact.onBase + crossNext - cross;
}

void NewmarkScheme::commit(double zNext, double pNext, double sNext, double tNext, const ContactWork& contact,
                           double damped, double work, int iterations, double kkt, int contactCount) {
    NewmarkState& s = state_;
    const double dt = this->dt(), dt2 = dt * dt;
    s.wPrev2.swap(s.wPrev);  // three levels rotate by swaps: no copy
    s.wPrev.swap(s.w);
    s.w.swap(wNext_);
    s.kwPrev.swap(s.kw);
    s.kw.swap(kwNext_);
    // (T.6): energy = E0 + input − dissipated − damped.
    recordStep(s, zNext, pNext, {work, contact.dissipated, damped, iterations, iterations, kkt});
    s.pressureWorkPrev = s.pressureWork;
    s.pressureWork = sNext;
    advanceLevels(s.baseCoupling, s.baseCouplingPrev, s.baseCouplingPrev2, tNext);
    const double force[2] = {contact.sum[0] / dt2, contact.sum[1] / dt2};  // the port (§14)
    bookContact(s, force, dt);
    s.stepContactMoment = contact.moment / dt2;
    if (plate_->law().dampingMass > 0.0) massVelocity_.swap(massVelocityNext_);
    if (law_) law_->commit(s);
    if (qp_) s.contactState.swap(trialState_);
    s.contactPoints = contactCount;
}

double NewmarkScheme::energy() const {
    // (T.2): E = ½ vᵀ(M + (β−¼)Δt²K) v + ½ ūᵀKū with v the absolute velocity (w − w⁻)/Δt + ż·1 and
    // ū = (w + w⁻)/2; K·1 = 0, so only the mass sees the base (docs/theory.md).
    const NewmarkState& s = state_;
    dwScratch_ = s.w - s.wPrev;  // read once per communication step: reuse the buffers
    const Eigen::VectorXd& dw = dwScratch_;
    plate_->applyMass(dw, scratch_);
    const double dt = this->dt(), dt2 = dt * dt;
    const double zDot = (s.z - s.zPrev) / dt;
    const double kinetic = 0.5 * dw.dot(scratch_) / dt2 + 0.5 * (beta() - 0.25) * dw.dot(s.kw - s.kwPrev) +
                           zDot * (s.baseCoupling - s.baseCouplingPrev) / dt + 0.5 * zDot * zDot * plate_->totalMass();
    const double potential = 0.125 * (s.w + s.wPrev).dot(s.kw + s.kwPrev);
    return kinetic + potential;
}

// --- Outputs (docs/theory.md §14) ---

double NewmarkScheme::pointHeight(int k, int level) const {
    const NewmarkState& st = state_;
    const PointProbe* probes[3] = {&corner1_, &corner2_, &freeEdgeMid_};
    return atLevel(level, st.z, st.zPrev, st.zPrev2) + (*probes[k])(atLevel(level, st.w, st.wPrev, st.wPrev2));
}

double NewmarkScheme::outputEnergy() const {
    if (energyStep_ != state_.step) {
        energyCache_ = energy();
        energyStep_ = state_.step;
    }
    return energyCache_;
}

void NewmarkScheme::clampLoad(double& force, double& moment) const {
    // docs/theory.md §14, (T.14a, b): the step from t_n to t_{n+1} summed against the rigid motions 1 and X
    // (K·1 = K·X = 0) gives the clamp's force and moment on the plate at t_n; the plate exerts
    // their opposites on the clamp. Levels: w = w_{n+1}, wPrev = w_n, wPrev2 = w_{n−1}.
    const NewmarkState& st = state_;
    if (st.step == 0) {  // no step yet: the initial static state's reaction (§14)
        force = initialForce_;
        moment = initialMoment_;
        return;
    }
    const ClampedPlate& clamped = plate_->clamped();
    const double dt = plate_->dt(), beta = plate_->beta(), dt2 = dt * dt;
    const Eigen::VectorXd& rotation = plate_->rotationInertia();
    const double zAcc = (st.z - 2.0 * st.zPrev + st.zPrev2) / dt2;
    const double translationAcc = (st.baseCoupling - 2.0 * st.baseCouplingPrev + st.baseCouplingPrev2) / dt2;
    const double rotationAcc = (rotation.dot(st.w) - 2.0 * rotation.dot(st.wPrev) + rotation.dot(st.wPrev2)) / dt2;
    const double pBeta = beta * st.p + (1.0 - 2.0 * beta) * st.pPrev + beta * st.pPrev2;  // f^{nβ}
    const double contact = st.stepContactForce[0] + st.stepContactForce[1];
    force = -(clamped.totalMass * zAcc + translationAcc - pBeta * clamped.loadResultant - contact);
    moment = -(clamped.totalMassMoment * zAcc + rotationAcc - pBeta * clamped.loadMoment - st.stepContactMoment);
}

std::vector<double> NewmarkScheme::vertexDisplacements() const {
    const NewmarkState& st = state_;
    const ClampedPlate& clamped = plate_->clamped();
    std::vector<double> u(static_cast<std::size_t>(vertexCount_), st.z);
    Eigen::VectorXd y;
    plate_->gatherContact(st.w, y);
    for (std::size_t i = 0; i < clamped.contactVertices.size(); ++i)
        u[clamped.contactVertices[i]] += y[static_cast<Eigen::Index>(i)];
    return u;
}

void NewmarkScheme::restoreState(const std::vector<double>& data) {
    const NewmarkState& current = state_;
    setState(deserialize(data, current.w.size(), current.contactState.size(), current.contactImpulse.size()));
}

std::string NewmarkScheme::name() const {
    const auto* modal = dynamic_cast<const ModalPlate*>(plate_.get());
    if (!modal) return "sparse";
    return modal->complete() ? "modal-complete" : "modal-" + std::to_string(modal->size());
}

double NewmarkScheme::firstFrequency() const {
    const auto* modal = dynamic_cast<const ModalPlate*>(plate_.get());
    double omega2;
    if (modal) {
        omega2 = modal->omega2()[0];
    } else {
        Eigen::MatrixXd phi;
        Eigen::VectorXd w2;
        lowestModes(plate_->clamped(), 1, phi, w2);
        omega2 = w2[0];
    }
    return std::sqrt(omega2) / (2.0 * M_PI);
}

double NewmarkScheme::kappa() const {
    if (kappa_ < 0.0) {
        const auto* modal = dynamic_cast<const ModalPlate*>(plate_.get());
        kappa_ = modal && modal->complete() ? modal->omega2().maxCoeff() : largestEigenvalue(plate_->clamped());
    }
    return kappa_;
}

CarrierOutputs NewmarkScheme::carrierOutputs() const {
    CarrierOutputs o;
    const Armature* carrier = armature_.get();
    if (!carrier) return o;
    const CarrierState& c = carrier->state();
    o.energy = carrier->energy(state_);
    o.driveWork = c.driveWork;
    o.damperWork = c.damperWork;
    o.portWork = c.portWork;
    o.waveOut = c.waveOut;
    o.transit = c.transit;
    o.lineLoss = c.lineLoss;
    return o;
}

}  // namespace plate
