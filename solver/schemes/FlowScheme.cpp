#include "schemes/FlowScheme.h"

#include <algorithm>
#include <cmath>

namespace plate {

namespace {

// R halves an event's sub-step kResolveDepth times: its boundary then lies within 1/16 of a kept
// sub-step from the event; where the kept run's event error is large, its own boundary lies a quarter or
// more from it, and an error growing with that distance squared is sixteen times smaller in R (measured:
// the same 24 verdicts as halving to the cap).
constexpr int kResolveDepth = 3;

}  // namespace

FlowScheme::FlowScheme(std::shared_ptr<const CondensedPlate> plate, Obstacles obstacles, const LawParameters& law,
                       ContactRefinement refinement, OutputRows outputRows)
    : CondensedScheme(std::move(plate), obstacles, law, std::move(outputRows)), refinement_(refinement) {
    const CondensedPlate& c = CondensedScheme::plate();
    const Eigen::Index m = c.modes(), rows = c.rows();
    const double dt = law.dt;
    flow_.errorQ = flow_.errorMomentum = flow_.eventError2 = Eigen::VectorXd::Zero(m);
    exact_ = ExactFlow(c.omega2, damping(), dt);
    inverseOmega2_ = c.omega2.cwiseInverse();
    dampedModes_ = (damping().array() != 0.0).any();
    for (Eigen::VectorXd* v : {&slope_, &offset_, &u0_, &ud0_, &u1_, &ud1_, &qIntegral_, &dq_, &rhs_}) v->resize(m);
    if (refinement_.tolerance > 0.0) {
        // Levels 1 … log2(maxSubsteps): 2^j sub-steps of Δt/2^j (level 0 is the step itself, fullStep()).
        for (int j = 1; (1 << j) <= refinement_.maxSubsteps; ++j) {
            levels_.push_back(std::make_unique<MidpointOperator>());
            buildOperator(*levels_.back(), dt / double(1 << j));
        }
        const auto run = [this](const StepState& from, double zNext, double pNext, int j, bool resolve, StepState& to) {
            this->run(from, zNext, pNext, 1 << j, level(j), to, resolve ? j : -1);
        };
        const auto perturb = [this](const StepState& from, const Eigen::VectorXd& dq, const Eigen::VectorXd& dP,
                                    StepState& to) {
            to = from;
            to.s.q += dq;
            to.s.momentum += dP;
            solveAtRest(to);  // the massless part's contact at t_n for the perturbed rows: its own ψ
            to.s.contactSolves += 1;
            refreshDerived(to);
        };
        doubling_ = std::make_unique<StepDoubling>(c, CondensedScheme::outputRows().probes, rowLower(), rowUpper(),
                                                   exact_, dampedModes_, refinement_, dt, flow_, run, perturb);
    } else {
        buildOperator(sub_, dt / refinement_.substeps);
    }
    if (refinement_.rowSpace && rows > 0)
        touch_ = std::make_unique<RowSpace>(c, rowLower(), rowUpper(), now().freeFlight);
}

// time_scheme = flow (docs/theory.md §21). Over a step the base moves linearly (ż = v = Δz/Δt, the
// input the midpoint step assumes too) and the load linearly; in relative coordinates each mode
// then obeys q̈ + c q̇ + ω² q = F (p + ṗ s) with q̇ = P − b v, whose solution is a particular
// polynomial q_p = A + B s (ω²B = Fṗ, ω²A + cB = F p) plus the free flow of u = q − q_p. A row past an
// obstacle at the end: the step is a run of m discrete-gradient sub-steps instead (with a tolerance,
// the run its estimate chose), recorded once; a throw in it leaves the scheme as it was.
void FlowScheme::advance(double zNext, double pNext) {
    const CondensedState& s = now().s;
    exactStep(zNext, pNext);
    resetSolves();
    // The contact check of the midpoint step (its free-flight bound included). With a tolerance, a
    // row the carried error could take past an obstacle is looked at too (Near): the exact motion
    // may touch where the computed one does not (§22).
    const Look look = lookAtRows(everyRow(), now(), zNext, pNext, doubling_ ? doubling_->reach() : 0.0);
    if (look != Look::Contact) return freeStep(zNext, pNext, look);
    // The rows at t_n, once for what reads them: the row space and the onset (§22); the free trial's
    // end is the look's (everyRow()'s r1).
    const Eigen::VectorXd& trialEnd = everyRow().buffers->r1;
    if (touch_ || doubling_) {
        if (now().rowsKnown)
            rowsStart_ = now().rows;
        else
            gatherRows(everyRow(), s.q, s.p, s.z, rowsStart_);
    }
    if (touch_) touch_->select(s, rowsStart_, qNext(), trialEnd, zNext, pNext, rowLoadMax());
    stepRowSpaceRuns_ = stepRowSpaceRetries_ = 0;
    try {
        if (doubling_)
            doubling_->contactStep(now(), rowsStart_, trialEnd, zNext, pNext, kept_);
        else
            run(now(), zNext, pNext, refinement_.substeps, sub_, kept_);
    } catch (...) {
        if (touch_) touch_->forget();  // C's data gathered again by the next contact step
        throw;
    }
    recordRun(kept_);
    rowSpaceSteps_ += stepRowSpaceRuns_;
    rowSpaceRetries_ += stepRowSpaceRetries_;
}

// (F.1) for every mode at once: q_p = offset + slope·s, u = q − q_p flows by Φ; into qNext(),
// momentumNext() and ∫q (qIntegral_).
void FlowScheme::exactStep(double zNext, double pNext) {
    const CondensedPlate& c = plate();
    const CondensedState& s = now().s;
    const double h = dt_, v = (zNext - s.z) / h, pDot = (pNext - s.p) / h;
    const auto F = c.modalLoad.array();
    const auto b = c.modalBaseInertia.array();
    const auto invW2 = inverseOmega2_.array();
    const auto c_k = damping().array();
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
        offset = (s.p * F - c_k * slope) * invW2;
    }
    u0 = s.q.array() - offset;
    ud0 = s.momentum.array() - v * b - slope;
    u1 = exact_.f11.array() * u0 + exact_.f12.array() * ud0;
    ud1 = exact_.f21.array() * u0 + exact_.f22.array() * ud0;
    qNext().array() = u1 + offset + h * slope;
    momentumNext().array() = ud1 + slope + v * b;
    qIntegral_.array() = -((ud1 - ud0) + c_k * (u1 - u0)) * invW2 + h * (offset + (0.5 * h) * slope);
}

// The exact step recorded. The integral ∫u = −(Δu̇ + c Δu)/ω² (the equation integrated) gives the
// work exactly:
//   load  Σ F ([p q] − ṗ ∫q),   base  Δz · bᵀ(F p̄ − Ω² ∫q/Δt − c Δq/Δt),
//   damped  Σ (−Δe + F([p q] − ṗ ∫q)),  e = ½ q̇² + ½ ω² q²  (per damped mode),
// so that the ledger (T.17d) closes as in a midpoint step. Near an obstacle (with a tolerance) E goes
// through the step by runs from t_n first, their solves in the step's record.
void FlowScheme::freeStep(double zNext, double pNext, Look look) {
    const CondensedPlate& c = plate();
    CondensedState& s = now().s;
    if (!std::isfinite(momentumNext().sum()) || !std::isfinite(qNext().sum())) refuseNonFinite();
    const bool near = look == Look::Near;
    if (near) {
        if (touch_) touch_->clear();  // its runs in every row
        s.contactSolves += doubling_->nearMiss(now(), zNext, pNext);
        exactStep(zNext, pNext);  // the step and its look again: the runs used their buffers
        lookAtRowsNow(everyRow(), now(), zNext, pNext, doubling_->reach());
        resetSolves();
    }
    now().rowsKnown = look != Look::Skipped;
    if (now().rowsKnown) now().rows = everyRow().buffers->r1;
    keepLook(now(), look, zNext, pNext);
    RowBuffers& buffers = *everyRow().buffers;
    if (buffers.multiplierUsed) buffers.multiplier.setZero();
    buffers.multiplierUsed = false;
    if (!buffers.forceNextZero) buffers.forceNext.setZero();
    buffers.forceNextZero = true;
    const double h = dt_, dz = zNext - s.z, v = dz / h, pDot = (pNext - s.p) / h, pMid = 0.5 * (s.p + pNext);
    const auto c_k = damping().array();
    dq_.noalias() = qNext() - s.q;
    // The step's mean forces on the massive modes: F p̄ − Ω² ∫q/Δt − c Δq/Δt.
    const double perStep = 1.0 / h;
    rhs_.array() = pMid * c.modalLoad.array() - perStep * (c.omega2.array() * qIntegral_.array() + c_k * dq_.array());
    const double loadWork =
        pNext * c.modalLoad.dot(qNext()) - s.p * c.modalLoad.dot(s.q) - pDot * c.modalLoad.dot(qIntegral_);
    const double onRigid = c.modalBaseInertia.dot(rhs_);  // clamp + load on the plate (no contact)
    double dampedWork = 0.0;
    if (dampedModes_) {
        for (Eigen::Index k = 0; k < c.omega2.size(); ++k) {
            if (damping()[k] == 0.0) continue;
            const double b = c.modalBaseInertia[k], f = c.modalLoad[k], w2 = c.omega2[k];
            const double qd0 = s.momentum[k] - b * v, qd1 = momentumNext()[k] - b * v;
            const double de = 0.5 * (qd1 * qd1 - qd0 * qd0) + 0.5 * w2 * (qNext()[k] * qNext()[k] - s.q[k] * s.q[k]);
            dampedWork += -de + f * (pNext * qNext()[k] - s.p * s.q[k] - pDot * qIntegral_[k]);
        }
    }
    s.clampForce = onRigid - pMid * c.loadResultant;
    s.clampMoment = c.modalRotationInertia.dot(rhs_) - pMid * c.loadMoment;
    s.stepContactMoment = 0.0;
    s.stepContactForce[0] = s.stepContactForce[1] = 0.0;  // (no onset: bookContact needs no call)
    commit(everyRow(), now(), s.zPrev, zNext, pNext, loadWork + dz * onRigid, dampedWork, 0);
    if (near)
        doubling_->afterNearStep(s.step);
    else if (doubling_)
        doubling_->afterFreeStep(s.step);
}

void FlowScheme::run(const StepState& from, double zNext, double pNext, int m, const MidpointOperator& op,
                     StepState& to, int resolveFrom) {
    const auto substeps = [&](bool inRows, StepState& x) {
        if (resolveFrom >= 0)
            resolvedSubsteps(inRows, x, zNext, pNext, resolveFrom);
        else
            midpointSubsteps(inRows, op, x, zNext, pNext, m);
    };
    if (touch_ && !touch_->empty()) {
        StepState& in = touch_->enter(from);
        substeps(true, in);
        touch_->leave(in, to);
        ++stepRowSpaceRuns_;
        gatherRows(everyRow(), to.s.q, to.s.p, to.s.z, to.rows);  // the rows at the end start the next step
        to.rowsKnown = true;
        if (touch_->stayFree(to.rows, to.s.force)) return;
        ++stepRowSpaceRetries_;  // a row outside C touched: the run again in every row, and the step's later runs
        touch_->clear();
    }
    to = from;
    to.freeFlight.reset();
    substeps(false, to);
}

StepSpace FlowScheme::spaceFor(bool inRows, const MidpointOperator& op) {
    if (inRows) return touch_->space(op);
    StepSpace space = everyRow();
    space.op = &op;
    return space;
}

// The m sub-steps from x's t_n to zNext, pNext at t_{n+1}, the base and the load linear in between (as
// the exact step assumes). Each keeps its energy identity; the port's values over the step are their
// means, and the step's iterations the most of one sub-step.
void FlowScheme::midpointSubsteps(bool inRows, const MidpointOperator& op, StepState& x, double zNext, double pNext,
                                  int m) {
    const StepSpace space = spaceFor(inRows, op);
    CondensedState& s = x.s;
    const double z0 = s.z, p0 = s.p;
    double zBefore = z0 - (z0 - s.zPrev) / m;  // one sub-step before t_n on the last step's line: ż as it had it
    double force = 0.0, moment = 0.0, contact[2] = {0.0, 0.0}, contactMoment = 0.0;
    int iterationsMax = 0;
    for (int j = 1; j <= m; ++j) {
        const double z = j == m ? zNext : z0 + (zNext - z0) * (double(j) / m);
        const double p = j == m ? pNext : p0 + (pNext - p0) * (double(j) / m);
        midpointStep(space, x, zBefore, z, p);
        zBefore = s.zPrev;
        force += s.clampForce;
        moment += s.clampMoment;
        contact[0] += s.stepContactForce[0];
        contact[1] += s.stepContactForce[1];
        contactMoment += s.stepContactMoment;
        iterationsMax = std::max(iterationsMax, iterations());
    }
    s.clampForce = force / m;
    s.clampMoment = moment / m;
    s.stepContactForce[0] = contact[0] / m;
    s.stepContactForce[1] = contact[1] / m;
    s.stepContactMoment = contactMoment / m;
    s.contactIterationsLast = iterationsMax;
}

std::string FlowScheme::name() const {
    const CondensedPlate& c = plate();
    return c.modes() == c.massiveCount ? "flow-complete" : "flow-" + std::to_string(c.modes());
}

void FlowScheme::addOutputs(PlateOutputs& o) const {
    o.errorEstimate = flow_.errorEstimate;
    o.cappedSteps = double(flow_.cappedSteps);
}

void FlowScheme::restoreOwn(const std::vector<double>& own) {
    flow_ = FlowState::load(own, std::size_t(plate().modes()));
}

ToleranceHorizon FlowScheme::toleranceHorizon() const { return doubling_ ? doubling_->horizon() : ToleranceHorizon{}; }

// R's sub-steps: from t_n at `level`; one in which a row changes sides is taken again as two halves
// (kResolveDepth levels down at most), and the run returns to the coarser length where the halves
// realign. The base and the load linear in between, as in midpointSubsteps; only R's end is read.
// Each sub-step is taken from x into substep_, kept (swapped) or taken again as halves.
void FlowScheme::resolvedSubsteps(bool inRows, StepState& x, double zNext, double pNext, int from) {
    const int top = static_cast<int>(levels_.size());
    const int deepest = std::min(top, from + kResolveDepth);
    const long long finest = 1LL << top;  // positions in units of Δt / 2^top
    const double z0 = x.s.z, p0 = x.s.p;
    long long at = 0;
    int l = from;
    while (at < finest) {
        const long long length = finest >> l, to = at + length;
        const StepSpace space = spaceFor(inRows, level(l));
        const double fraction = double(to) / double(finest);
        const double z = to == finest ? zNext : z0 + (zNext - z0) * fraction;
        const double p = to == finest ? pNext : p0 + (pNext - p0) * fraction;
        const double zBefore = x.s.z - (zNext - z0) * (double(length) / double(finest));  // ż = Δz/Δt over the step
        substep_ = x;
        midpointStep(space, substep_, zBefore, z, p);
        if (l < deepest && substep_.s.rowState != x.s.rowState) {
            // Taken again from x as it was, the next look a full one.
            x.forceZero = {x.s.force.isZero(0.0), x.s.forcePrev.isZero(0.0), x.s.forcePrev2.isZero(0.0)};
            x.freeFlight.reset();
            ++l;
            continue;
        }
        std::swap(x, substep_);
        at = to;
        while (l > from && at % (finest >> (l - 1)) == 0) --l;
    }
}

}  // namespace plate
