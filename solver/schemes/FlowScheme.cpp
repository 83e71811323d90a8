#include "schemes/FlowScheme.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "base/Errors.h"
#include "base/PortableMath.h"
#include "base/StateArchive.h"

namespace plate {

namespace {

// The exact flow over h of ü + c u̇ + ω² u = 0 (docs/theory.md §21): (u, u̇)(h) = Φ (u, u̇)(0).
// Undamped, a rotation by ωh (the portable sine and cosine: the same bits on every CPU). Damped,
// exp(A h) of A = [[0, ω], [−ω, −c]] in the balanced variables (u, u̇/ω), by scaling and squaring
// (‖A h‖/2^j ≤ ½, Taylor to degree 20: below 2^-60, then j squarings) — IEEE operations only.
void modalFlow(double omega2, double c, double h, double& f11, double& f12, double& f21, double& f22) {
    const double omega = std::sqrt(omega2);
    if (c == 0.0) {
        double sn, cs;
        portable::sinCos(omega * h, sn, cs);
        f11 = cs, f12 = sn / omega, f21 = -omega * sn, f22 = cs;
        return;
    }
    int exponent = 0;
    std::frexp((omega + c) * h, &exponent);
    const int squarings = std::max(0, exponent + 1);
    const double scale = std::ldexp(h, -squarings);
    const double x12 = omega * scale, x21 = -omega * scale, x22 = -c * scale;  // X = A h / 2^j
    // Taylor: E = Σ X^k / k!, the power kept as T = X^k / k!.
    double e11 = 1.0, e12 = 0.0, e21 = 0.0, e22 = 1.0, t11 = 1.0, t12 = 0.0, t21 = 0.0, t22 = 1.0;
    for (int k = 1; k <= 20; ++k) {
        const double n11 = (t12 * x21) / k, n12 = (t11 * x12 + t12 * x22) / k;
        const double n21 = (t22 * x21) / k, n22 = (t21 * x12 + t22 * x22) / k;
        t11 = n11, t12 = n12, t21 = n21, t22 = n22;
        e11 += t11, e12 += t12, e21 += t21, e22 += t22;
    }
    for (int j = 0; j < squarings; ++j) {
        const double a = e11 * e11 + e12 * e21, b = e11 * e12 + e12 * e22;
        const double d = e21 * e11 + e22 * e21, g = e21 * e12 + e22 * e22;
        e11 = a, e12 = b, e21 = d, e22 = g;
    }
    f11 = e11, f12 = e12 / omega, f21 = e21 * omega, f22 = e22;
}

}  // namespace

FlowScheme::FlowScheme(std::shared_ptr<const CondensedPlate> plate, Obstacles obstacles, double dt,
                       ContactRefinement refinement, double dampingMass, double dampingStiffness, OutputRows outputRows)
    : CondensedScheme(std::move(plate), obstacles, dt, dampingMass, dampingStiffness, std::move(outputRows)),
      refinement_(refinement) {
    const CondensedPlate& c = *plate_;
    const Eigen::Index m = c.modes(), rows = c.rows();
    flow_.errorQ = flow_.errorMomentum = flow_.eventError2 = Eigen::VectorXd::Zero(m);
    if (refinement_.tolerance > 0.0) {
        // Levels 1 … log2(maxSubsteps): 2^j sub-steps of Δt/2^j (level 0 is the step itself, full_).
        for (int j = 1; (1 << j) <= refinement_.maxSubsteps; ++j) {
            levels_.push_back(std::make_unique<MidpointOperator>());
            buildOperator(*levels_.back(), dt / double(1 << j));
        }
        // The error is measured where the user reads it: the reported points (every row when the
        // scheme reports none, as in the unit tests).
        std::vector<int> measured;
        for (int i : rows_.probes)
            if (i >= 0) measured.push_back(i);
        if (measured.empty())
            for (int i = 0; i < rows; ++i) measured.push_back(i);
        measuredRows_ = c.rowModesT(Eigen::all, measured).transpose();
        measuredRows2_ = measuredRows_.cwiseAbs2();
        // Two motions differ at a row by its gap at most, where both obstacles' stops cover it (§22, §25).
        for (int i : measured) gapBound_ = std::max(gapBound_, upper_[i] - lower_[i]);

        inverseOmega_ = c.omega2.cwiseSqrt().cwiseInverse();
        for (Eigen::VectorXd* v : {&amplitude_, &errorNextQ_, &errorNextMomentum_, &localQ_, &localMomentum_,
                                   &scratchQ_, &eventQ_, &eventMomentum_, &lastEventQ_, &lastEventMomentum_})
            v->resize(m);
        rowBound_.resize(Eigen::Index(measured.size()));
        while ((2 << fixedLevel_) <= refinement_.substeps) ++fixedLevel_;  // 2^level ≤ contact_substeps
    } else {
        buildOperator(sub_, dt / refinement_.substeps);
    }
    inverseOmega2_ = c.omega2.cwiseInverse();
    dampedModes_ = (damping_.array() != 0.0).any();
    for (Eigen::VectorXd* v : {&slope_, &offset_, &u0_, &ud0_, &u1_, &ud1_, &qIntegral_}) v->resize(m);
    for (Eigen::VectorXd* v : {&flow11_, &flow12_, &flow21_, &flow22_}) v->resize(m);
    for (Eigen::Index k = 0; k < m; ++k)
        modalFlow(c.omega2[k], damping_[k], dt, flow11_[k], flow12_[k], flow21_[k], flow22_[k]);
    if (refinement_.tolerance > 0.0) stepDecay_ = flow11_.cwiseProduct(flow22_) - flow12_.cwiseProduct(flow21_);
    if (refinement_.rowSpace && rows > 0) sizeRowSpace();
}

void FlowScheme::sizeRowSpace() {
    const CondensedPlate& c = *plate_;
    const Eigen::Index m = c.modes(), rows = c.rows();
    TouchRows& t = touch_;
    t.index.reserve(std::size_t(rows));
    t.gathered.reserve(std::size_t(rows));
    t.modes.resize(m, rows);
    t.delassus.resize(rows, rows);
    t.load.resize(rows);
    t.x.resize(std::size_t(rows));
    t.endColumns = denseColumns(t.delassus);
    t.endQP = std::make_unique<BoxQP>(*t.endColumns);
    MidpointOperator& r = t.op;
    r.inverseH.resize(m);
    r.w2.resize(rows, rows);
    r.midpointMatrix.resize(rows, rows);
    r.midColumns = denseColumns(r.midpointMatrix);
    r.midQP = std::make_unique<BoxQP>(*r.midColumns);
    for (Eigen::VectorXd* v :
         {&t.forceNext, &t.multiplier, &t.r0, &t.r1, &t.drFree, &t.dr, &t.base, &t.e, &t.y, &t.w2v, &t.lower, &t.upper,
          &t.midForce, &t.endForce, &t.rowsCached, &t.force, &t.forcePrev, &t.forcePrev2})
        v->setZero(rows);
    for (auto* v : {&t.rowState, &t.midState, &t.rowTrial, &t.midTrial}) v->assign(std::size_t(rows), 0);
}

// time_scheme = flow (docs/theory.md §21). Over a step the base moves linearly (ż = v = Δz/Δt, the
// input the midpoint step assumes too) and the load linearly; in relative coordinates each mode
// then obeys q̈ + c q̇ + ω² q = F (p + ṗ s) with q̇ = P − b v, whose solution is a particular
// polynomial q_p = A + B s (ω²B = Fṗ, ω²A + cB = F p) plus the free flow of u = q − q_p. The
// integral ∫u = −(Δu̇ + c Δu)/ω² (the equation integrated) gives the work exactly:
//   load  Σ F ([p q] − ṗ ∫q),   base  Δz · bᵀ(F p̄ − Ω² ∫q/Δt − c Δq/Δt),
//   damped  Σ (−Δe + F([p q] − ṗ ∫q)),  e = ½ q̇² + ½ ω² q²  (per damped mode),
// so that the ledger (T.17d) closes as in a midpoint step. A row past an obstacle at the end: the
// step is taken again as m discrete-gradient sub-steps instead.
void FlowScheme::advance(double zNext, double pNext) {
    const CondensedPlate& c = *plate_;
    const CondensedState& s = state_;
    const double h = dt_, dz = zNext - s.z, v = dz / h, pDot = (pNext - s.p) / h, pMid = 0.5 * (s.p + pNext);
    // (F.1) for every mode at once: q_p = offset + slope·s, u = q − q_p flows by Φ.
    const auto F = c.modalLoad.array();
    const auto b = c.modalBaseInertia.array();
    const auto invW2 = inverseOmega2_.array();
    const auto damping = damping_.array();
    auto slope = slope_.array();
    auto offset = offset_.array();
    auto u0 = u0_.array();
    auto ud0 = ud0_.array();
    auto u1 = u1_.array();
    auto ud1 = ud1_.array();
    if (pDot == 0.0) {
        slope.setZero();
        offset = (s.p * F) * invW2;
    } else {
        slope = (pDot * F) * invW2;
        offset = (s.p * F - damping * slope) * invW2;
    }
    u0 = s.q.array() - offset;
    ud0 = s.momentum.array() - v * b - slope;
    u1 = flow11_.array() * u0 + flow12_.array() * ud0;
    ud1 = flow21_.array() * u0 + flow22_.array() * ud0;
    qNext_.array() = u1 + offset + h * slope;
    momentumNext_.array() = ud1 + slope + v * b;
    qIntegral_.array() = -((ud1 - ud0) + damping * (u1 - u0)) * invW2 + h * (offset + (0.5 * h) * slope);
    const bool damped = dampedModes_;
    iterations_ = solves_ = 0;
    kkt_ = 0.0;
    // The contact check of the midpoint step (its free-flight bound included). With a tolerance, a
    // row the carried error could take past an obstacle is looked at too (Near): the exact motion
    // may touch where the computed one does not (§22).
    const Look look = lookAtRows(everyRow_, zNext, pNext, errorReach_);
    if (look == Look::Contact) {
        // One snapshot restores the step: whatever throws in it (a contact solve, a sub-step's non-finite
        // result) leaves the scheme as it was (Scheme.h); the tolerance's runs start from it too.
        // The rows at t_n, once for what reads them: the row space (selectRows) and the onset (§22).
        if (refinement_.rowSpace || refinement_.tolerance > 0.0) {
            if (rowsCachedValid_)
                rowsStart_ = rowsCached_;
            else
                gatherRows(everyRow_, s.q, s.p, s.z, rowsStart_);
        }
        onsetFraction_ = refinement_.tolerance > 0.0 ? onsetFraction() : 0.0;
        save(start_);
        flowAtStart_ = flow_;
        try {
            selectRows(zNext, pNext);
            if (refinement_.tolerance > 0.0)
                refine(zNext, pNext);
            else
                substeps(zNext, pNext, refinement_.substeps, sub_);
        } catch (...) {
            if (inRows_) leaveRows();
            restore(start_);
            flow_ = flowAtStart_;
            touch_.gathered.clear();  // C's data gathered again by the next contact step
            throw;
        }
        return;
    }
    const bool near = look == Look::Near;
    if (near) {
        rotateError(s.step);
        save(start_);
    }
    rowsCachedValid_ = look == Look::Free || near;
    if (rowsCachedValid_) rowsCached_ = r1_;
    if (!std::isfinite(momentumNext_.sum()) || !std::isfinite(qNext_.sum())) refuseNonFinite();
    if (multiplierUsed_) multiplier_.setZero();
    multiplierUsed_ = false;
    if (!forceNextZero_) forceNext_.setZero();
    dq_.noalias() = qNext_ - s.q;
    // The step's mean forces on the massive modes: F p̄ − Ω² ∫q/Δt − c Δq/Δt.
    const double perStep = 1.0 / h;
    rhs_.array() = pMid * F - perStep * (c.omega2.array() * qIntegral_.array() + damping * dq_.array());
    const double loadWork =
        pNext * c.modalLoad.dot(qNext_) - s.p * c.modalLoad.dot(s.q) - pDot * c.modalLoad.dot(qIntegral_);
    const double onRigid = c.modalBaseInertia.dot(rhs_);  // clamp + load on the plate (no contact)
    double dampedWork = 0.0;
    if (damped) {
        for (Eigen::Index k = 0; k < c.omega2.size(); ++k) {
            if (damping_[k] == 0.0) continue;
            const double b = c.modalBaseInertia[k], f = c.modalLoad[k], w2 = c.omega2[k];
            const double qd0 = s.momentum[k] - b * v, qd1 = momentumNext_[k] - b * v;
            const double de = 0.5 * (qd1 * qd1 - qd0 * qd0) + 0.5 * w2 * (qNext_[k] * qNext_[k] - s.q[k] * s.q[k]);
            dampedWork += -de + f * (pNext * qNext_[k] - s.p * s.q[k] - pDot * qIntegral_[k]);
        }
    }
    CondensedState& st = state_;
    st.clampForce = onRigid - pMid * c.loadResultant;
    st.clampMoment = c.modalRotationInertia.dot(rhs_) - pMid * c.loadMoment;
    st.stepContactMoment = 0.0;
    st.stepContactForce[0] = st.stepContactForce[1] = 0.0;  // (no onset: bookContact needs no call)
    commit(everyRow_, zNext, pNext, loadWork + dz * onRigid, dampedWork, 0);
    if (near) return nearMiss(zNext, pNext);
    // E at the reported points at every step: after a release their error grows within a few steps, and a
    // sample every 8 steps let the running maximum trail it (0.88 of it at an output, docs/theory.md §22).
    if (flow_.contactSteps > 0 && !(flow_.lostAt >= 0.0 && boundedByGap())) {
        rotateError(st.step);
        sampleError(false);
    }
}

void FlowScheme::rowsAtStart(const StepSpace& space) {
    if (rowsCachedValid_)
        r0_ = rowsCached_;
    else
        gatherRows(space, state_.q, state_.p, state_.z, r0_);
}

void FlowScheme::rowsAtEnd(bool rowsLooked) {
    rowsCachedValid_ = rowsLooked;
    if (rowsCachedValid_) rowsCached_ = r1_;
}

void FlowScheme::save(Snapshot& to) const {
    to.state = state_;
    to.midForce = midForce_;
    to.endForce = endForce_;
    to.rowsCached = rowsCached_;
    to.rowsCachedValid = rowsCachedValid_;
}

void FlowScheme::restore(const Snapshot& from) {
    state_ = from.state;
    refreshDerived();
    midForce_ = from.midForce;
    endForce_ = from.endForce;
    rowsCached_ = from.rowsCached;
    rowsCachedValid_ = from.rowsCachedValid;
    freeFlight_.reset();
}

// The step from t_n as m midpoint sub-steps of Δt/m, the base and the load linear in between (as
// the exact step assumes), in the rows that can touch (docs/theory.md §24): a sub-step costs what
// those rows cost, not what every row does. Each sub-step keeps its energy identity; the levels
// t_n, t_{n−1} and the port's values over the step are those of one step of Δt afterwards (from the
// run's snapshot of its start). Should a row outside them end the step past an obstacle, the step is
// taken again in every row from that snapshot.
void FlowScheme::substeps(double zNext, double pNext, int m, const MidpointOperator& op, int resolveFrom) {
    const bool inRows = !allRows_ && !touch_.index.empty();
    save(runStart_);
    try {
        if (inRows) {
            buildRowOperator(op);
            enterRows();
        } else {
            substep_ = everyRow_;
            substep_.op = &op;
        }
        if (resolveFrom >= 0)
            resolvedSubsteps(zNext, pNext, resolveFrom);
        else
            midpointSubsteps(zNext, pNext, m);
    } catch (...) {  // the caller restores its start (advance, refine's companion)
        if (inRows_) leaveRows();
        throw;
    }
    if (inRows_) leaveRows();
    CondensedState& s = state_;
    const CondensedState& s0 = runStart_.state;
    s.qPrev2 = s0.qPrev;
    s.qPrev = s0.q;
    s.forcePrev2 = s0.forcePrev;
    s.forcePrev = s0.force;
    s.zPrev2 = s0.zPrev;
    s.zPrev = s0.z;
    s.pPrev2 = s0.pPrev;
    s.pPrev = s0.p;
    s.step = s0.step + 1;
    forceZero_ = {s.force.isZero(0.0), s.forcePrev.isZero(0.0), s.forcePrev2.isZero(0.0)};
    forceNextZero_ = false;
    multiplierUsed_ = true;
    freeFlight_.reset();
    if (!inRows) return;
    ++rowSpaceSteps_;
    if (rowsOutsideStayFree()) return;
    ++rowSpaceRetries_;  // a row outside C touched: the step again, in every row
    restore(runStart_);
    allRows_ = true;
    substeps(zNext, pNext, m, op, resolveFrom);
}

// The m sub-steps of substep_ from the state's t_n to zNext, pNext at t_{n+1}; the time levels after
// them are substeps'.
void FlowScheme::midpointSubsteps(double zNext, double pNext, int m) {
    CondensedState& s = state_;
    const double z0 = s.z, zBefore = s.zPrev, p0 = s.p;
    const long long step0 = s.step;
    // ż at t_n as one step of Δt had it (the clamp-carried mass's terms in commit).
    s.zPrev = z0 - (z0 - zBefore) / m;
    double force = 0.0, moment = 0.0, contact[2] = {0.0, 0.0}, contactMoment = 0.0;
    int iterationsMax = 0;
    for (int j = 1; j <= m; ++j) {
        const double z = j == m ? zNext : z0 + (zNext - z0) * (double(j) / m);
        const double p = j == m ? pNext : p0 + (pNext - p0) * (double(j) / m);
        midpointStep(substep_, z, p);
        s.step = step0;  // one internal step, not m: the messages' t_{n+1} (nextTime) stays right
        force += s.clampForce;
        moment += s.clampMoment;
        contact[0] += s.stepContactForce[0];
        contact[1] += s.stepContactForce[1];
        contactMoment += s.stepContactMoment;
        iterationsMax = std::max(iterationsMax, iterations_);
    }
    s.clampForce = force / m;
    s.clampMoment = moment / m;
    s.stepContactForce[0] = contact[0] / m;
    s.stepContactForce[1] = contact[1] / m;
    s.stepContactMoment = contactMoment / m;
    s.contactIterationsLast = iterationsMax;
}

// The rows that can touch during the contact step from t_n (docs/theory.md §24): those held at its
// start, and those an obstacle is within reach of at its start or at the end of the free trial
// (qNext_, r1_). Reach: twice what any row can move with the plate, the base and the load over the
// step in free flight (FreeFlightBound's sum); the contact forces' own effect on the other rows is
// checked at the step's end (rowsOutsideStayFree).
bool FlowScheme::selectRows(double zNext, double pNext) {
    const CondensedPlate& c = *plate_;
    const CondensedState& s = state_;
    allRows_ = false;
    touch_.index.clear();
    if (!refinement_.rowSpace) return false;  // (rowsStart_: the rows at t_n, from advance)
    const double reach =
        2.0 * (c.rowModeNormMax * (qNext_ - s.q).norm() + std::abs(zNext - s.z) + std::abs(pNext - s.p) * rowLoadMax_);
    const auto gap = [this](int i, double r) { return std::min(r - lower_[i], upper_[i] - r); };  // §25
    const int rows = c.rows();
    for (int i = 0; i < rows; ++i) {
        const auto k = static_cast<std::size_t>(i);
        if (s.rowState[k] != 0 || s.midState[k] != 0 || gap(i, rowsStart_[i]) < reach || gap(i, r1_[i]) < reach)
            touch_.index.push_back(i);
    }
    if (int(touch_.index.size()) == rows) {
        touch_.index.clear();
        return false;
    }
    // C's data, gathered when C changed (in held contact it often does not): its leading columns and block.
    TouchRows& t = touch_;
    const Eigen::Index n = Eigen::Index(t.index.size());
    if (t.index != t.gathered) {
        t.gathered.assign(t.index.begin(), t.index.end());  // within the reserved capacity
        for (Eigen::Index k = 0; k < n; ++k) {
            const int i = t.index[std::size_t(k)];
            t.modes.col(k) = c.rowModesT.col(i);
            t.load[k] = c.rowLoad[i];
            t.x[std::size_t(k)] = c.rowAbscissae[std::size_t(i)];
            for (Eigen::Index a = 0; a < n; ++a) t.delassus(a, k) = c.delassus(t.index[std::size_t(a)], i);
        }
        t.load.tail(c.rows() - n).setZero();
        std::fill(t.x.begin() + n, t.x.end(), 0.0);
        // C's bounds; past C they are ∓∞: those entries never bind (StepSpace).
        constexpr double infinity = std::numeric_limits<double>::infinity();
        t.lower.setConstant(-infinity);
        t.upper.setConstant(infinity);
        for (Eigen::Index k = 0; k < n; ++k) {
            t.lower[k] = lower_[t.index[std::size_t(k)]];
            t.upper[k] = upper_[t.index[std::size_t(k)]];
        }
        t.endColumns->useLeading(int(n));
        t.endQP->forgetFactor();
        t.from = nullptr;
    }
    return true;
}

// W₂ and the midpoint contact problem ½W₂ + D of op's sub-step length, in C (their leading block).
void FlowScheme::buildRowOperator(const MidpointOperator& op) {
    TouchRows& t = touch_;
    MidpointOperator& r = t.op;
    if (t.from == &op) return;
    t.from = &op;
    r.h = op.h;
    r.inverseH = op.inverseH;
    const Eigen::Index n = Eigen::Index(t.index.size());
    for (Eigen::Index b = 0; b < n; ++b) {
        const int j = t.index[std::size_t(b)];
        for (Eigen::Index a = 0; a < n; ++a) {
            r.w2(a, b) = op.w2(t.index[std::size_t(a)], j);
            r.midpointMatrix(a, b) = 0.5 * r.w2(a, b) + t.delassus(a, b);
        }
    }
    r.midColumns->useLeading(int(n));
    r.midQP->forgetFactor();
}

// The state's row vectors and the step's row buffers exchanged with C's (the swaps move no data).
void FlowScheme::swapRowBuffers() {
    CondensedState& s = state_;
    TouchRows& t = touch_;
    for (auto [a, b] : {std::pair{&forceNext_, &t.forceNext},
                        {&multiplier_, &t.multiplier},
                        {&r0_, &t.r0},
                        {&r1_, &t.r1},
                        {&drFree_, &t.drFree},
                        {&dr_, &t.dr},
                        {&base_, &t.base},
                        {&e_, &t.e},
                        {&y_, &t.y},
                        {&w2v_, &t.w2v},
                        {&lower_, &t.lower},
                        {&upper_, &t.upper},
                        {&midForce_, &t.midForce},
                        {&endForce_, &t.endForce},
                        {&rowsCached_, &t.rowsCached},
                        {&s.force, &t.force},
                        {&s.forcePrev, &t.forcePrev},
                        {&s.forcePrev2, &t.forcePrev2}})
        a->swap(*b);
    for (auto [a, b] : {std::pair{&s.rowState, &t.rowState},
                        {&s.midState, &t.midState},
                        {&rowTrial_, &t.rowTrial},
                        {&midTrial_, &t.midTrial}})
        a->swap(*b);
}

// C's values of the state gathered and exchanged with the scheme's own: the step runs in C.
void FlowScheme::enterRows() {
    CondensedState& s = state_;
    TouchRows& t = touch_;
    const Eigen::Index n = Eigen::Index(t.index.size()), rest = plate_->rows() - n;
    // Past C every row buffer is zero (StepSpace), whatever an earlier C left there.
    for (Eigen::VectorXd* v : {&t.forceNext, &t.multiplier, &t.r0, &t.r1, &t.drFree, &t.dr, &t.base, &t.e, &t.y, &t.w2v,
                               &t.midForce, &t.endForce, &t.rowsCached, &t.force, &t.forcePrev, &t.forcePrev2})
        v->tail(rest).setZero();
    for (auto* v : {&t.rowState, &t.midState, &t.rowTrial, &t.midTrial}) std::fill(v->begin() + n, v->end(), 0);
    for (std::size_t k = 0; k < t.index.size(); ++k) {
        const auto i = t.index[k];
        const auto j = Eigen::Index(k);
        t.force[j] = s.force[i];
        t.forcePrev[j] = s.forcePrev[i];
        t.forcePrev2[j] = s.forcePrev2[i];
        t.rowState[k] = s.rowState[std::size_t(i)];
        t.midState[k] = s.midState[std::size_t(i)];
        if (rowsCachedValid_) t.rowsCached[j] = rowsCached_[i];
    }
    for (Eigen::VectorXd* v : {&t.forceNext, &t.multiplier, &t.midForce, &t.endForce}) v->setZero();
    forceNextZero_ = true;
    multiplierUsed_ = false;
    swapRowBuffers();
    substep_ = {&t.op, &t.modes, &t.load, &t.x, t.endQP.get(), n};
    inRows_ = true;
}

// Back in every row: C's results scattered (λ and the contact sets are zero outside C).
void FlowScheme::leaveRows() {
    CondensedState& s = state_;
    TouchRows& t = touch_;
    swapRowBuffers();
    inRows_ = false;
    s.force.setZero();
    std::fill(s.rowState.begin(), s.rowState.end(), 0);
    std::fill(s.midState.begin(), s.midState.end(), 0);
    for (std::size_t k = 0; k < t.index.size(); ++k) {
        const auto i = t.index[k];
        s.force[i] = t.force[Eigen::Index(k)];
        s.rowState[std::size_t(i)] = t.rowState[k];
        s.midState[std::size_t(i)] = t.midState[k];
    }
    forceNextZero_ = false;
    rowsCachedValid_ = false;
}

// Every row outside C inside the obstacles at the step's end, held back by C's forces through D
// (y = r + D λ); the rows at the end start the next step.
bool FlowScheme::rowsOutsideStayFree() {
    const CondensedPlate& c = *plate_;
    const CondensedState& s = state_;
    gatherRows(everyRow_, s.q, s.p, s.z, rowsCached_);
    rowsCachedValid_ = true;
    std::size_t k = 0;
    for (int i = 0; i < c.rows(); ++i) {
        if (k < touch_.index.size() && touch_.index[k] == i) {
            ++k;
            continue;
        }
        double y = rowsCached_[i];
        for (std::size_t a = 0; a < touch_.index.size(); ++a)
            if (s.force[touch_.index[a]] != 0.0) y += c.delassus(i, touch_.index[a]) * s.force[touch_.index[a]];
        if (y < lower_[i] || y > upper_[i]) return false;
    }
    return true;
}

std::string FlowScheme::name() const {
    const CondensedPlate& c = *plate_;
    return c.modes() == c.massiveCount ? "flow-complete" : "flow-" + std::to_string(c.modes());
}

void FlowScheme::addOutputs(PlateOutputs& o) const {
    o.errorEstimate = flow_.errorEstimate;
    o.cappedSteps = double(flow_.cappedSteps);
}

namespace {

// The flow law's own part of the flat form, version 3 (2: the error vector; 3: the events' error).
constexpr double kFlowFormat = 3.0;
const auto flowMembers = [](auto& s, auto& v) {
    v.real(s.errorEstimate, "error estimate");
    v.count(s.cappedSteps, "capped steps");
    v.count(s.refinementLevel, "refinement level", 30.0);
    v.count(s.contactSteps, "contact steps");
    v.count(s.errorStep, "error step");
    v.real(s.lostAt, "time the tolerance was lost");
    v.real(s.smoothOrder, "order of held contact steps");
    for (auto* x : {&s.errorQ, &s.errorMomentum}) v.vector(*x, 0, "error vector");
    v.vector(s.eventError2, 0, "events' error");
};

}  // namespace

std::vector<double> FlowScheme::saveOwn() const {
    return archive::save(flow_, kFlowFormat, std::array<std::size_t, 1>{std::size_t(plate_->modes())}, flowMembers);
}

void FlowScheme::restoreOwn(const std::vector<double>& own) {
    FlowState loaded = archive::load<FlowState>(own, kFlowFormat,
                                                std::array<std::size_t, 1>{std::size_t(plate_->modes())}, flowMembers);
    if ((loaded.eventError2.array() < 0.0).any())
        throw std::invalid_argument("corrupt state: a negative squared amplitude in the events' error");
    flow_ = std::move(loaded);
}

}  // namespace plate
