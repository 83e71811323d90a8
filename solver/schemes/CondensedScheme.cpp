#include "schemes/CondensedScheme.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "base/Errors.h"
#include "base/History.h"
#include "base/StateArchive.h"
#include "plate/PlateParameters.h"

namespace plate {

namespace {

// The discrete gradient's fixed point (T.17c) is iterated until the step's energy residual
// ψ0 − ψ1 − Λᵀ Δr is below this fraction of the energies in play (measured: 2–5 iterations).
constexpr double kGradientTolerance = 1e-13;
constexpr int kGradientIterations = 200;
// The contact solves' relative KKT residual (BoxQP) must reach this.
constexpr double kKktTolerance = 1e-10;

}  // namespace

std::unique_ptr<ContactColumns> CondensedScheme::denseColumns(const Eigen::MatrixXd& matrix) {
    return std::make_unique<ContactColumns>(matrix);
}

void CondensedScheme::buildOperator(MidpointOperator& op, double h) const {
    const CondensedPlate& c = *plate_;
    op.h = h;
    op.inverseH = (1.0 + 0.5 * h * damping_.array() + 0.25 * h * h * c.omega2.array()).inverse().matrix();
    // W₂ = ½h² G H⁻¹ Gᵀ: how the rows move in one step per unit of Λ (T.17c).
    op.w2 = (0.5 * h * h) * (c.rowModesT.transpose() * op.inverseH.asDiagonal() * c.rowModesT);
    op.midpointMatrix = 0.5 * op.w2 + c.delassus;
    op.midColumns = denseColumns(op.midpointMatrix);
    op.midQP = std::make_unique<BoxQP>(*op.midColumns);
}

void RowBuffers::resize(Eigen::Index rows) {
    for (Eigen::VectorXd* v :
         {&forceNext, &multiplier, &r0, &r1, &drFree, &dr, &base, &e, &y, &w2v, &midForce, &endForce})
        v->setZero(rows);
    for (auto* v : {&rowTrial, &midTrial}) v->assign(std::size_t(rows), 0);
    forceNextZero = true;
    multiplierUsed = false;
}

CondensedScheme::CondensedScheme(std::shared_ptr<const CondensedPlate> plate, Obstacles obstacles,
                                 const LawParameters& law, OutputRows outputRows)
    : Scheme(obstacles, law.dt), plate_(std::move(plate)), rows_(std::move(outputRows)) {
    const CondensedPlate& c = *plate_;
    const Eigen::Index m = c.modes(), rows = c.rows();
    damping_ = (law.dampingMass + law.dampingStiffness * c.omega2.array()).matrix();
    buildOperator(full_, law.dt);
    endMatrix_ = c.delassus;
    endColumns_ = denseColumns(endMatrix_);
    endQP_ = std::make_unique<BoxQP>(*endColumns_);
    obstacles_.rowBounds(c.rowStops, lower_, upper_);  // each row's obstacles (docs/theory.md §25)
    all_.resize(rows);
    everyRow_ = {&full_, &c.rowModesT, &c.rowLoad, &c.rowAbscissae, endQP_.get(), rows, &lower_, &upper_, &all_};
    for (Eigen::VectorXd* v : {&rhs_, &dq_, &qNext_, &momentumNext_, &modalForce_, &modalScratch_}) v->resize(m);
    if (rows > 0) rowLoadMax_ = c.rowLoad.cwiseAbs().maxCoeff();
    now_.freeFlight.setup(m, c.rowModeNormMax, rowLoadMax_);
}

// W₂ v = ½Δt² G H⁻¹ Gᵀ v: through the modes when they are fewer than half the rows (a reduced
// model: 2·rows·m operations instead of rows²).
void CondensedScheme::applyW2(const StepSpace& space, const Eigen::VectorXd& v, Eigen::VectorXd& out) {
    const CondensedPlate& c = *plate_;
    const MidpointOperator& op = *space.op;
    const double h = op.h;
    const Eigen::Index n = space.count;  // the space's rows lead; past them out stays zero (StepSpace)
    if (2 * Eigen::Index(c.modes()) >= n) {
        out.head(n).noalias() = op.w2.topLeftCorner(n, n) * v.head(n);
    } else {
        modalScratch_.noalias() = space.modes->leftCols(n) * v.head(n);
        modalScratch_.array() *= (0.5 * h * h) * op.inverseH.array();
        out.head(n).noalias() = space.modes->leftCols(n).transpose() * modalScratch_;
    }
    out.tail(v.size() - n).setZero();
}

void CondensedScheme::gatherRows(const StepSpace& space, const Eigen::VectorXd& q, double p, double z,
                                 Eigen::VectorXd& r) const {
    const Eigen::Index n = space.count;  // the space's rows lead; past them r stays zero (StepSpace)
    r.resize(plate_->rows());  // (sized once: a row vector has every row's length)
    auto head = r.head(n);
    head.noalias() = space.modes->leftCols(n).transpose() * q;
    head.noalias() += p * space.load->head(n);
    head.array() += z;
    r.tail(r.size() - n).setZero();
}

void CondensedScheme::solveContact(const StepSpace& space, BoxQP& qp, const Eigen::VectorXd& free,
                                   std::vector<signed char>& state, Eigen::VectorXd& force, Eigen::VectorXd& y) {
    const QPResult r = qp.solve(free, *space.lower, *space.upper, state, force, y);
    ++solves_;
    kkt_ = std::max(kkt_, r.kktResidual);
    if (!r.converged || !(r.kktResidual <= kKktTolerance)) refuseUnsolved("contact solve", r.iterations, r.kktResidual);
}

// The static problem of the condensed plate (§17): Ω² q = p0 F_m + Gᵀλ with the rows
// r = G q + p0 c_p + z0 + D λ between the obstacles: one contact solve with G Ω⁻² Gᵀ + D.
void CondensedScheme::initialize(double z0, double p0) {
    const CondensedPlate& c = *plate_;
    CondensedState& s = now_.s;
    s = CondensedState{};
    const Eigen::Index m = c.modes(), rows = c.rows();
    const Eigen::VectorXd qFree = p0 * c.modalLoad.cwiseQuotient(c.omega2);
    s.force = Eigen::VectorXd::Zero(rows);
    s.rowState.assign(rows, 0);
    s.midState.assign(rows, 0);
    Eigen::VectorXd r(rows);
    gatherRows(everyRow_, qFree, p0, z0, r);
    s.q = qFree;
    if (obstacles_.any() && rows > 0) {
        const Eigen::MatrixXd flexibility =
            c.rowModesT.transpose() * c.omega2.cwiseInverse().asDiagonal() * c.rowModesT + c.delassus;
        const auto columns = denseColumns(flexibility);
        BoxQP qp(*columns);
        std::vector<signed char> state(rows, 0);
        Eigen::VectorXd y(rows);
        const QPResult result = qp.solve(r, lower_, upper_, state, s.force, y);
        if (!result.converged || !(result.kktResidual <= kKktTolerance))
            throw ParameterError("the initial static state's contact problem did not converge");
        s.q.noalias() += c.omega2.cwiseInverse().cwiseProduct(c.rowModesT * s.force);
    }
    s.z = s.zPrev = s.zPrev2 = z0;
    s.p = s.pPrev = s.pPrev2 = p0;
    // The massless part's own contact forces at the rows: λ*(r) with r from the new q.
    if (obstacles_.any() && rows > 0) solveAtRest(now_);
    s.qPrev = s.qPrev2 = s.q;
    s.momentum = Eigen::VectorXd::Zero(m);
    s.forcePrev = s.forcePrev2 = s.force;
    s.contactPoints =
        static_cast<int>(std::count_if(s.rowState.begin(), s.rowState.end(), [](signed char x) { return x != 0; }));
    refreshDerived(now_);
}

void CondensedScheme::setLoadAtStart(double p0) {
    CondensedState& s = now_.s;
    if (s.step != 0 || p0 == s.p) return;
    s.p = s.pPrev = s.pPrev2 = p0;
    if (obstacles_.any() && plate_->rows() > 0) {
        solveAtRest(now_);
        s.forcePrev = s.forcePrev2 = s.force;
        s.contactPoints =
            static_cast<int>(std::count_if(s.rowState.begin(), s.rowState.end(), [](signed char x) { return x != 0; }));
    }
    refreshDerived(now_);
}

void CondensedScheme::solveAtRest(StepState& x) {
    Eigen::VectorXd& r = all_.r0;
    gatherRows(everyRow_, x.s.q, x.s.p, x.s.z, r);
    solveContact(everyRow_, *endQP_, r, x.s.rowState, all_.endForce, all_.y);
    x.s.force = all_.endForce;
    x.s.boundary = 0.5 * x.s.force.dot(all_.y - r);
}

// The rows r1 at the trial's end looked at: Contact when a row is held at the start or past an
// obstacle at the end, Free otherwise; the margin kept for keepLook.
CondensedScheme::Look CondensedScheme::lookAtRowsNow(const StepSpace& space, StepState& x, double zNext, double pNext,
                                                     double reserve) {
    Eigen::VectorXd& r1 = space.buffers->r1;
    const Eigen::VectorXd &lower = *space.lower, &upper = *space.upper;
    gatherRows(space, qNext_, pNext, zNext, r1);
    double margin = std::numeric_limits<double>::infinity();
    for (Eigen::Index i = 0; i < r1.size(); ++i)
        margin = std::min(margin, std::min(r1[i] - lower[i], upper[i] - r1[i]));
    lookMargin_ = margin;
    if (x.s.contactPoints > 0 || margin < 0.0) return Look::Contact;
    return margin < reserve ? Look::Near : Look::Free;
}

void CondensedScheme::keepLook(StepState& x, Look look, double zNext, double pNext) {
    if (look == Look::Contact)
        x.freeFlight.reset();
    else if (look != Look::Skipped)
        x.freeFlight.restart(qNext_, zNext, pNext, lookMargin_);
}

void CondensedScheme::midpointStep(const StepSpace& space, StepState& x, double zBefore, double zNext, double pNext) {
    const CondensedPlate& c = *plate_;
    const CondensedState& s = x.s;
    RowBuffers& b = *space.buffers;
    const MidpointOperator& op = *space.op;
    const double dt = op.h, dz = zNext - s.z, dp = pNext - s.p, pMid = 0.5 * (s.p + pNext);
    // The free midpoint step (T.17b with Λ = 0): H Δq = Δt P − b_m Δz + ½Δt²(p̄ F_m − Ω² q).
    rhs_.noalias() = dt * s.momentum - dz * c.modalBaseInertia;
    rhs_.noalias() += (0.5 * dt * dt) * (pMid * c.modalLoad - c.omega2.cwiseProduct(s.q));
    dq_.noalias() = op.inverseH.cwiseProduct(rhs_);
    qNext_.noalias() = s.q + dq_;
    iterations_ = solves_ = 0;
    kkt_ = 0.0;
    const Look look = lookAtRows(space, x, zNext, pNext);
    const bool contact = look == Look::Contact, rowsLooked = look != Look::Skipped;
    // The contact buffers are zero in free flight: cleared only when the last use left them not.
    if (b.multiplierUsed) b.multiplier.setZero();
    b.multiplierUsed = contact;
    if (!b.forceNextZero) b.forceNext.setZero();
    b.forceNextZero = !contact;  // (the contact solve writes it)
    if (contact) {
        if (x.rowsKnown)
            b.r0 = x.rows;
        else
            gatherRows(space, s.q, s.p, s.z, b.r0);
        b.drFree = b.r1 - b.r0;
        discreteGradient(space, x);
        // Δq = Δq_free + ½Δt² H⁻¹ Gᵀ Λ.
        modalForce_.noalias() = space.modes->leftCols(space.count) * space.live(b.multiplier);
        dq_.noalias() += (0.5 * dt * dt) * op.inverseH.cwiseProduct(modalForce_);
        qNext_.noalias() = s.q + dq_;
    } else {
        modalForce_.setZero();
    }
    momentumNext_.noalias() = (2.0 / dt) * (dq_ + dz * c.modalBaseInertia) - s.momentum;
    if (!std::isfinite(momentumNext_.sum()) || !std::isfinite(qNext_.sum())) refuseNonFinite();
    // The step's forces on the massive modes at the midpoint (T.17b) and the work (T.17d).
    const double damped = dq_.dot(damping_.cwiseProduct(dq_)) / dt;
    rhs_.noalias() =
        pMid * c.modalLoad - 0.5 * c.omega2.cwiseProduct(s.q + qNext_) + modalForce_ - damping_.cwiseProduct(dq_) / dt;
    const double contactSum = contact ? space.live(b.multiplier).sum() : 0.0,
                 onLoad = contact ? space.live(b.multiplier).dot(space.live(*space.load)) : 0.0;
    const double onRigid = c.modalBaseInertia.dot(rhs_) - contactSum;  // clamp + load on the plate
    const double work = pMid * c.modalLoad.dot(dq_) - dp * onLoad + dz * onRigid;
    CondensedState& st = x.s;
    st.clampForce = onRigid - pMid * c.loadResultant;
    st.clampMoment = c.modalRotationInertia.dot(rhs_) - pMid * c.loadMoment;
    st.stepContactMoment = 0.0;
    double sums[2] = {0.0, 0.0};
    if (contact) {
        for (Eigen::Index i = 0; i < b.multiplier.size(); ++i) {
            if (b.multiplier[i] == 0.0) continue;
            // Each row's force goes to the obstacle nearer to it at the midpoint (of those holding it).
            const double lo = (*space.lower)[i], hi = (*space.upper)[i];
            const double middle =
                std::isfinite(lo) && std::isfinite(hi) ? 0.5 * (lo + hi) : (std::isfinite(lo) ? HUGE_VAL : -HUGE_VAL);
            sums[0.5 * (b.r0[i] + b.r1[i]) >= middle] += b.multiplier[i];
            st.stepContactMoment += b.multiplier[i] * (*space.x)[static_cast<std::size_t>(i)];
        }
        st.clampMoment -= st.stepContactMoment;
    }
    bookContact(st, sums, dt);
    keepLook(x, look, zNext, pNext);
    commit(space, x, zBefore, zNext, pNext, work, damped, iterations_);
    // The rows at the end start the next contact step: r1 is G q⁺ + … when they were looked at, r0 + Δr
    // after a contact solve.
    x.rowsKnown = rowsLooked;
    if (rowsLooked) x.rows = b.r1;
}

// Λ = λ*(r_mid) + c_g Δr with c_g = (ψ0 − ψ1 − λ*(r_mid)·Δr)/|Δr|² (T.17c), so that Λ·Δr = ψ0 − ψ1.
// With e = c_g Δr held from the last iterate, λ*(r_mid) solves the contact problem with the
// constant matrix ½W₂ + D at r0 + ½Δr_free + ½W₂e; then Δr = Δr_free + W₂(λ + e), ψ1 = ψ(r0 + Δr)
// from one solve with D, and e is updated, until the energy residual vanishes.
void CondensedScheme::discreteGradient(const StepSpace& space, StepState& x) {
    const CondensedState& s = x.s;
    RowBuffers& b = *space.buffers;
    const double psi0 = s.boundary;
    b.e.setZero();
    b.rowTrial = s.rowState;
    b.midTrial = s.midState;
    Eigen::VectorXd& lambda = b.multiplier;
    // The step's energies set the residual's scale: the contact terms, and the plate's kinetic and
    // modal strain energy (a contact onset has ψ0 = ψ1 ≈ 0: its residual is measured against those).
    const double energyScale = 0.5 * s.momentum.squaredNorm() + 0.5 * s.q.dot(plate_->omega2.cwiseProduct(s.q)) +
                               std::numeric_limits<double>::min();
    for (int it = 1;; ++it) {
        b.base.noalias() = b.r0 + 0.5 * b.drFree;
        if (it > 1) {
            applyW2(space, b.e, b.w2v);
            b.base.noalias() += 0.5 * b.w2v;
        }
        solveContact(space, *space.op->midQP, b.base, b.midTrial, b.midForce, b.y);
        lambda = b.midForce + b.e;  // Λ
        applyW2(space, lambda, b.w2v);
        b.dr.noalias() = b.drFree + b.w2v;
        b.r1.noalias() = b.r0 + b.dr;
        solveContact(space, *space.endQP, b.r1, b.rowTrial, b.endForce, b.y);
        b.forceNext = b.endForce;
        const double psi1 = 0.5 * space.live(b.forceNext).dot(space.live(b.y) - space.live(b.r1));  // ½ λ1ᵀ D λ1
        boundaryNext_ = psi1;
        const double residual = psi0 - psi1 - space.live(lambda).dot(space.live(b.dr));
        const double scale = psi0 + psi1 + std::abs(space.live(lambda).dot(space.live(b.dr))) + energyScale;
        iterations_ = it;
        const double norm2 = space.live(b.dr).squaredNorm();
        if (std::abs(residual) <= kGradientTolerance * scale || norm2 == 0.0) return;
        if (it == kGradientIterations) {
            std::ostringstream msg;
            msg << "the discrete gradient of the contact step to t = " << nextTime() << " did not converge in " << it
                << " iterations (energy residual " << residual << " J)";
            throw StepError(msg.str(), nextTime());
        }
        // e ← c_g Δr with c_g from λ*(r_mid) = Λ − e.
        b.e = ((psi0 - psi1 - (space.live(lambda) - space.live(b.e)).dot(space.live(b.dr))) / norm2) * b.dr;
    }
}

void CondensedScheme::commit(const StepSpace& space, StepState& x, double zBefore, double zNext, double pNext,
                             double work, double damped, int iterations) {
    const CondensedPlate& c = *plate_;
    CondensedState& s = x.s;
    RowBuffers& b = *space.buffers;
    const double dt = space.op->h;
    // The mass moving with the clamp (discarded modes) and the massless part's load terms enter
    // the energy (T.17a); their changes are booked as the inputs' work (T.17d).
    const double zDot = (s.z - zBefore) / dt, zDotNext = (zNext - s.z) / dt;
    const bool nextZero = solves_ == 0;  // a free step leaves λ_{n+1} = 0
    const double loadTerms = (nextZero ? 0.0 : pNext * space.live(b.forceNext).dot(space.live(*space.load))) +
                             0.5 * pNext * pNext * c.loadFlexibility -
                             ((x.forceZero[0] ? 0.0 : s.p * space.live(s.force).dot(space.live(*space.load))) +
                              0.5 * s.p * s.p * c.loadFlexibility);
    const double input = work + 0.5 * c.clampMass * (zDotNext * zDotNext - zDot * zDot) + loadTerms;
    // The clamp-carried mass's inertia at t_n (its work pairs with (z⁺ − z⁻)/2, §17).
    const double zAcc = (zNext - 2.0 * s.z + zBefore) / (dt * dt);
    s.clampForce += c.clampMass * zAcc;
    s.clampMoment += c.clampMassMoment * zAcc;
    s.qPrev2.swap(s.qPrev);
    s.qPrev.swap(s.q);
    s.q.swap(qNext_);
    s.momentum.swap(momentumNext_);
    s.forcePrev2.swap(s.forcePrev);
    s.forcePrev.swap(s.force);
    s.force.swap(b.forceNext);
    b.forceNextZero = x.forceZero[2];
    x.forceZero = {nextZero, x.forceZero[0], x.forceZero[1]};
    s.boundary = solves_ > 0 ? boundaryNext_ : 0.0;
    recordStep(s, zNext, pNext, {input, 0.0, damped, solves_, iterations, kkt_});
    if (solves_ > 0) {
        s.rowState.swap(b.rowTrial);
        s.midState.swap(b.midTrial);
        s.contactPoints =
            static_cast<int>(std::count_if(s.rowState.begin(), s.rowState.end(), [](signed char x) { return x != 0; }));
    } else if (s.contactPoints > 0) {
        std::fill(s.rowState.begin(), s.rowState.end(), 0);
        s.contactPoints = 0;
    }
}

// A run's end becomes the state at t_{n+1}: its levels before it are the scheme's t_n and t_{n−1}.
void CondensedScheme::recordRun(StepState& end) {
    CondensedState &s = now_.s, &e = end.s;
    e.qPrev2.swap(s.qPrev);
    e.qPrev.swap(s.q);
    e.forcePrev2.swap(s.forcePrev);
    e.forcePrev.swap(s.force);
    e.zPrev2 = s.zPrev;
    e.zPrev = s.z;
    e.pPrev2 = s.pPrev;
    e.pPrev = s.p;
    e.step = s.step + 1;
    std::swap(s, e);
    now_.rows.swap(end.rows);
    now_.rowsKnown = end.rowsKnown;
    now_.forceZero = {s.force.isZero(0.0), s.forcePrev.isZero(0.0), s.forcePrev2.isZero(0.0)};
    now_.freeFlight.reset();
}

double CondensedScheme::energy() const {
    const CondensedPlate& c = *plate_;
    const CondensedState& s = now_.s;
    const double zDot = (s.z - s.zPrev) / dt_;
    const double kinetic = 0.5 * s.momentum.squaredNorm() + 0.5 * c.clampMass * zDot * zDot;
    // Strain energy: ½ qᵀΩ²q + ½ bᵀ S b of the massless part b = S⁻¹Q0ᵀ(pF + Cᵀλ) (T.17a).
    const double massless = s.boundary + s.p * s.force.dot(c.rowLoad) + 0.5 * s.p * s.p * c.loadFlexibility;
    return kinetic + 0.5 * s.q.dot(c.omega2.cwiseProduct(s.q)) + massless;
}

double CondensedScheme::rowHeight(int i, int level) const {
    const CondensedPlate& c = *plate_;
    const CondensedState& s = now_.s;
    const Eigen::VectorXd& q = atLevel(level, s.q, s.qPrev, s.qPrev2);
    const Eigen::VectorXd& f = atLevel(level, s.force, s.forcePrev, s.forcePrev2);
    const double z = atLevel(level, s.z, s.zPrev, s.zPrev2);
    const double p = atLevel(level, s.p, s.pPrev, s.pPrev2);
    const double heldBack = f.isZero(0.0) ? 0.0 : c.delassus.col(i).dot(f);  // D symmetric: column = row
    return c.rowModesT.col(i).dot(q) + p * c.rowLoad[i] + z + heldBack;
}

// The recovery functionals of w = V q + Q0 S⁻¹ Q0ᵀ (p F + Cᵀλ) (docs/theory.md §23): the modes,
// the massless part's response to the load and to the contact forces (skipped while they are zero).
void CondensedScheme::recover(Eigen::Index first, int level, Eigen::Ref<Eigen::VectorXd> out) const {
    const CondensedPlate& c = *plate_;
    const CondensedState& s = now_.s;
    const Eigen::VectorXd& q = atLevel(level, s.q, s.qPrev, s.qPrev2);
    const Eigen::VectorXd& f = atLevel(level, s.force, s.forcePrev, s.forcePrev2);
    const double p = atLevel(level, s.p, s.pPrev, s.pPrev2);
    const Eigen::Index n = out.size();
    out.noalias() = c.recoveryModes.middleRows(first, n) * q;
    out += p * c.recoveryLoad.segment(first, n);
    if (!f.isZero(0.0)) out.noalias() += c.recoveryRows.middleRows(first, n) * f;
}

void CondensedScheme::initialReaction(double& force, double& moment) const {
    const CondensedPlate& c = *plate_;
    const CondensedState& s = now_.s;
    const Eigen::VectorXd rate = s.p * c.modalLoad - c.omega2.cwiseProduct(s.q) + c.rowModesT * s.force;
    double contact = 0.0, contactMoment = 0.0;
    for (Eigen::Index i = 0; i < s.force.size(); ++i) {
        contact += s.force[i];
        contactMoment += s.force[i] * c.rowAbscissae[static_cast<std::size_t>(i)];
    }
    force = -(c.modalBaseInertia.dot(rate) - contact - s.p * c.loadResultant);
    moment = -(c.modalRotationInertia.dot(rate) - contactMoment - s.p * c.loadMoment);
}

void CondensedScheme::setState(const CondensedState& s) {
    now_.s = s;
    refreshDerived(now_);
}

std::vector<double> CondensedScheme::saveState() const {
    std::vector<double> out = serialize();
    const std::vector<double> own = saveOwn();
    out.insert(out.end(), own.begin(), own.end());
    return out;
}

void CondensedScheme::restoreState(const std::vector<double>& data) {
    const std::size_t length = std::min(data.size(), serializedLength());
    const auto split = data.begin() + std::ptrdiff_t(length);
    const CondensedState s = deserialize(std::vector<double>(data.begin(), split));  // throws: nothing set
    restoreOwn(std::vector<double>(split, data.end()));  // throws: nothing set; else the own part is set
    setState(s);
}

void CondensedScheme::restoreOwn(const std::vector<double>& own) {
    if (!own.empty()) throw std::invalid_argument("state does not belong to this plate (size or format differs)");
}

void CondensedScheme::refreshDerived(StepState& x) {
    const CondensedState& s = x.s;
    x.forceZero = {s.force.isZero(0.0), s.forcePrev.isZero(0.0), s.forcePrev2.isZero(0.0)};
    x.rowsKnown = false;
    x.freeFlight.reset();  // the free-flight bound restarts from a full look
}

// The port at t_{n−½} (§17): what the plate exerts on the clamp is the opposite of the clamp's
// force on it; before the first step, the initial state's reaction.
void CondensedScheme::clampLoad(double& force, double& moment) const {
    if (now_.s.step == 0) return initialReaction(force, moment);
    force = -now_.s.clampForce;
    moment = -now_.s.clampMoment;
}

std::vector<double> CondensedScheme::vertexDisplacements() const {
    const std::vector<int>& vertexRows = rows_.vertices;
    std::vector<double> u(vertexRows.size(), now_.s.z);
    for (std::size_t v = 0; v < vertexRows.size(); ++v)
        if (vertexRows[v] >= 0) u[v] = rowHeight(vertexRows[v]);
    return u;
}

std::string CondensedScheme::name() const {
    const CondensedPlate& c = *plate_;
    return c.modes() == c.massiveCount ? "conserving-complete" : "conserving-" + std::to_string(c.modes());
}

double CondensedScheme::firstFrequency() const { return std::sqrt(plate_->omega2[0]) / (2.0 * M_PI); }

// The flat form for FMU states (base/StateArchive.h): a format tag, the sizes (massive modes,
// constraint rows), then every member in the order of this one description. A new member is one
// line here, with kFormat raised.
namespace {

constexpr double kFormat = 20.0;  // the condensed schemes' state, version 4 (the base's share first, Scheme.h)
constexpr std::size_t kModalVectors = 0, kRows = 1;  // the sizes' order in the archive

const auto condensedMembers = [](auto& s, auto& v) {
    for (auto* x : {&s.q, &s.qPrev, &s.qPrev2, &s.momentum}) v.vector(*x, kModalVectors, "modal coordinate");
    for (auto* x : {&s.force, &s.forcePrev, &s.forcePrev2}) v.vector(*x, kRows, "contact force");
    sharedMembers(s, v, static_cast<double>(v.size(kRows)));
    v.real(s.boundary, "boundary energy");
    v.real(s.clampForce, "clamp force");
    v.real(s.clampMoment, "clamp moment");
    for (auto* x : {&s.rowState, &s.midState}) v.states(*x, kRows);
};

}  // namespace

std::vector<double> CondensedScheme::serialize() const {
    return archive::save(now_.s, kFormat, sizes(), condensedMembers);
}

CondensedState CondensedScheme::deserialize(const std::vector<double>& data) const {
    CondensedState s = archive::load<CondensedState>(data, kFormat, sizes(), condensedMembers);
    if (s.z < obstacles_.clampLower() || s.z > obstacles_.clampUpper())
        throw std::invalid_argument("corrupt state: clamp past an obstacle");
    return s;
}

std::size_t CondensedScheme::serializedLength() const {
    return archive::length<CondensedState>(sizes(), condensedMembers);
}

std::array<std::size_t, 2> CondensedScheme::sizes() const {
    return {static_cast<std::size_t>(plate_->modes()), static_cast<std::size_t>(plate_->rows())};
}

}  // namespace plate
