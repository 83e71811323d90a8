#include "schemes/StepDoubling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "base/Errors.h"
#include "base/StateArchive.h"

namespace plate {

namespace {

// The kept run takes at least 2^2 sub-steps: at 2 against 1 the pair is too coarse for its
// difference to say what the finer one missed (measured: estimates at half the error at the first
// impact of a contact-rich scene, docs/performance.md).
constexpr int kLowestLevel = 2;
// The observed order of held contact steps is a running mean over the last ~kOrderMemory rises.
constexpr double kOrderMemory = 8.0;
// A pair that sees an event differs by about what the coarse run's event error is, at least the kept
// run's (first order: a level down at least doubles it). R's difference above kBlindPair times the pair's
// says the pair missed it: both runs resolved the event at the same boundary (docs/theory.md §22, events
// resolved; measured: 8 and 16 give the same 24 verdicts, 4 breaks one of them).
constexpr double kBlindPair = 8.0;

}  // namespace

StepDoubling::StepDoubling(const CondensedPlate& plate, const std::array<int, 3>& probes, const Eigen::VectorXd& lower,
                           const Eigen::VectorXd& upper, const ExactFlow& exact, bool damped,
                           const ContactRefinement& refinement, double dt, FlowState& state, Run run, Perturb perturb)
    : plate_(plate),
      lower_(lower),
      upper_(upper),
      exact_(exact),
      dampedModes_(damped),
      tolerance_(refinement.tolerance),
      top_(std::ilogb(refinement.maxSubsteps)),
      dt_(dt),
      flow_(state),
      run_(std::move(run)),
      perturb_(std::move(perturb)),
      fixedLevel_(std::ilogb(refinement.substeps)) {
    const Eigen::Index m = plate.modes();
    std::vector<int> measured;
    for (int i : probes)
        if (i >= 0) measured.push_back(i);
    if (measured.empty())
        for (int i = 0; i < plate.rows(); ++i) measured.push_back(i);
    measuredRows_ = plate.rowModesT(Eigen::all, measured).transpose();
    measuredRows2_ = measuredRows_.cwiseAbs2();
    // Two motions differ at a row by its gap at most, where both obstacles' stops cover it (§22, §25).
    for (int i : measured) gapBound_ = std::max(gapBound_, upper[i] - lower[i]);
    inverseOmega_ = plate.omega2.cwiseSqrt().cwiseInverse();
    for (Eigen::VectorXd* v : {&amplitude_, &errorNextQ_, &errorNextMomentum_, &localQ_, &localMomentum_, &scratchQ_,
                               &eventQ_, &eventMomentum_, &lastEventQ_, &lastEventMomentum_})
        v->resize(m);
    rowBound_.resize(Eigen::Index(measured.size()));
    stepDecay_ = exact.f11.cwiseProduct(exact.f22) - exact.f12.cwiseProduct(exact.f21);
}

void StepDoubling::contactStep(const StepState& start, const Eigen::VectorXd& rowsStart,
                               const Eigen::VectorXd& trialEnd, double zNext, double pNext, StepState& kept) {
    start_ = &start;
    kept_ = &kept;
    onsetFraction_ = onsetFraction(rowsStart, trialEnd);
    flowAtStart_ = flow_;
    try {
        refine(zNext, pNext);
    } catch (...) {  // the estimate as it was at t_n
        flow_ = flowAtStart_;
        throw;
    }
}

// Free flight after the first contact step: E at the reported points at every step (after a release
// their error grows within a few steps, and a sample every 8 steps let the running maximum trail it:
// 0.88 of it at an output, docs/theory.md §22).
void StepDoubling::afterFreeStep(long long step) {
    if (flow_.contactSteps > 0 && !(flow_.lostAt >= 0.0 && boundedByGap())) {
        rotateError(step);
        sampleError(false);
    }
}

// tolerance > 0 (docs/theory.md §22). The contact step from t_n is taken at level j (2^j sub-steps,
// kept) and at level j − 1 from the same start x_n; their difference says what the kept run missed
// (localError). While that local error exceeds the step's share of the tolerance the
// level rises (the kept run becomes the coarse one) up to the cap. The global error E_n carried to
// t_n goes through the step by the step itself: a companion at level j − 1 from x_n + E_n, whose
// difference from the coarse run is E carried through the contact (its growth at an impact
// included). E_{n+1} = that + the kept run's local error. Every run is a sequence of
// discrete-gradient sub-steps: the energy identity holds at any level; the coarse runs and the
// companion leave no trace but their work count.
void StepDoubling::refine(double zNext, double pNext) {
    const CondensedState& s = start_->s;
    const int top = top_;
    // Past the time the estimate passed the tolerance (the scene's horizon for it: no sub-step brings
    // it back) the contact steps take contact_substeps sub-steps, as without a tolerance; the estimate
    // goes on where no gap bounds it (sampleError).
    const bool lost = flow_.lostAt >= 0.0;
    int j = std::clamp(lost ? fixedLevel_ : std::max(flow_.refinementLevel, onsetLevel()), 1, top);
    ++flow_.contactSteps;
    if (lost && boundedByGap()) {
        // The estimate already reads the gap, the bound no later step changes: no pair, no companion.
        run_(*start_, zNext, pNext, j, false, *kept_);
        return;
    }
    rotateError(s.step);
    const double target = lost ? HUGE_VAL : localTarget();
    run_(*start_, zNext, pNext, j - 1, false, coarse_);
    long long discardedSolves = coarse_.s.contactSolves - s.contactSolves;
    double local = 0.0, before = HUGE_VAL, differenceBefore = 0.0;
    bool smoothBefore = false;
    blindPair_ = straddled_ = false;
    // Content: within the share, at the cap, or a rise that did not halve the error (what remains is not
    // the sub-step's).
    const auto settledAt = [&](double error) { return error <= target || j == top || error > 0.5 * before; };
    for (;;) {
        run_(*start_, zNext, pNext, j, false, *kept_);
        local = localError();
        // Two differences of a smooth step at successive levels measure its order (their ratio
        // is 2^p): the held contact's order is learnt from the run's own rises.
        if (smoothBefore && smooth_ && difference_ > 0.0 && differenceBefore > difference_) {
            const double order = std::clamp(std::log2(differenceBefore / difference_), 1.0, 2.0);
            flow_.smoothOrder += (order - flow_.smoothOrder) / kOrderMemory;
        }
        bool settled = settledAt(local);
        // Risen because the pair was blind: the coarse run is the kept run R found wrong (docs/theory.md
        // §22, events resolved), so R runs whether or not this pair is content.
        const bool afterBlind = blindPair_ || straddled_;
        blindPair_ = straddled_ = false;
        if ((settled || afterBlind) && !smooth_) {
            // Rows changed sides: the pair may be blind to an event both runs resolve at the same
            // sub-step boundary (docs/theory.md §22, events resolved). R says; if so its error is the step's.
            // (R's solves are not counted in contact_solves.)
            double resolved = resolveEvents(zNext, pNext, j);
            blindPair_ = resolved > kBlindPair * local;
            straddled_ = afterBlind && resolved >= 0.0 && local > kBlindPair * resolved;
            if (straddled_) resolved = straddledError();
            if (blindPair_) {
                lastEventQ_ = eventQ_;
                lastEventMomentum_ = eventMomentum_;
            }
            if (blindPair_ || straddled_) {
                local = resolved;
                settled = settledAt(local);
            }
        }
        if (settled) break;
        discardedSolves += kept_->s.contactSolves - s.contactSolves;
        std::swap(coarse_, *kept_);  // the kept run is the next pair's coarse one
        before = local;
        differenceBefore = difference_;
        smoothBefore = smooth_;
        ++j;
    }
    discardedSolves += carryThroughStep(zNext, pNext, j - 1);
    kept_->s.contactSolves += discardedSolves;
    if (!smooth_) addEventError();
    carryError(s.step + 1);
    flow_.cappedSteps += !lost && local > target && j == top;
    // One level lower next time when the pair one level down would still be well inside the target
    // (a level down multiplies the local error by about 4 where the sub-steps are second order).
    if (!lost) flow_.refinementLevel = j > 1 && 8.0 * local < target ? j - 1 : j;
}

// The kept run's lowest level: kLowestLevel, and in an onset step one whose coarse run's last sub-step
// starts after the onset (docs/theory.md §22, the onset's level). Runs that meet the obstacle in their
// last sub-step, whatever its length, end within roundoff of one another — the onset's error is the same
// for 1, 2 and 4 sub-steps when it lies in the last quarter of the step (measured: §5.2 with modes = 20)
// — so their difference would say nothing of it.
int StepDoubling::onsetLevel() const {
    if (!(onsetFraction_ > 0.5)) return kLowestLevel;
    // The coarse run's 2^(j−1) sub-steps: its last starts at 1 − 2^(1−j), after the onset when
    // 2^(j−1) > 1/(1 − onset).
    return std::max(kLowestLevel, 2 + static_cast<int>(std::floor(std::log2(1.0 / (1.0 - onsetFraction_)))));
}

// The first row's crossing of an obstacle in an onset step (none held at t_n), as a fraction of the
// step, on the straight line between its heights at t_n and at the free trial's end (the look's):
// where the step's contact begins, to the precision the choice of a level needs. 0 when a row is held.
double StepDoubling::onsetFraction(const Eigen::VectorXd& rowsStart, const Eigen::VectorXd& trialEnd) const {
    if (start_->s.contactPoints > 0) return 0.0;
    double first = 1.0;
    for (Eigen::Index i = 0; i < trialEnd.size(); ++i) {
        const double r0 = rowsStart[i], r1 = trialEnd[i];
        if (r1 < lower_[i] && r0 >= lower_[i]) first = std::min(first, (r0 - lower_[i]) / (r0 - r1));
        if (r1 > upper_[i] && r0 <= upper_[i]) first = std::min(first, (upper_[i] - r0) / (r1 - r0));
    }
    return first < 1.0 ? first : 0.0;
}

// A step the computed motion takes in free flight (kept: exact) while a row is within the carried
// error's reach of an obstacle: E goes through it by its companion against a coarse run from the
// same start t_n (at the coarse level of the last contact step, in every row); the step adds no error
// of its own (afterNearStep). Returns the runs' solves.
long long StepDoubling::nearMiss(const StepState& start, double zNext, double pNext) {
    start_ = &start;
    rotateError(start.s.step);
    const int j = std::clamp(std::max(flow_.refinementLevel, kLowestLevel), 1, top_) - 1;
    long long solves = 0;
    try {
        run_(start, zNext, pNext, j, false, coarse_);
        solves = coarse_.s.contactSolves - start.s.contactSolves;
        solves += carryThroughStep(zNext, pNext, j);
    } catch (const StepError&) {  // the coarse run cannot be taken: E by the free flow (the step is kept)
        carryByFreeFlow();
    }
    localQ_.setZero();
    localMomentum_.setZero();
    return solves;
}

// E from t_n through the step to t_{n+1} into errorNext*: the companion at `level` against coarse_
// (its work returned), or the free flow when E is zero or the companion cannot be taken (past the
// horizon E is as large as the motion and may put rows deep past an obstacle).
long long StepDoubling::carryThroughStep(double zNext, double pNext, int level) {
    if (flow_.errorQ.isZero(0.0) && flow_.errorMomentum.isZero(0.0)) {
        carryByFreeFlow();
        return 0;
    }
    try {
        return companion(zNext, pNext, level);
    } catch (const StepError&) {
        carryByFreeFlow();
        return 0;
    }
}

void StepDoubling::carryByFreeFlow() {
    errorNextQ_ = exact_.f11.cwiseProduct(flow_.errorQ) + exact_.f12.cwiseProduct(flow_.errorMomentum);
    errorNextMomentum_ = exact_.f21.cwiseProduct(flow_.errorQ) + exact_.f22.cwiseProduct(flow_.errorMomentum);
}

// E_{n+1} = E carried through the step + the kept run's own error, at t_{n+1}; sampled at the
// reported points, and its reach over the rows in free flight: ‖G_i‖ max times the modes' error
// amplitudes (constant undamped, decaying damped). Past the horizon (lost) E is as large as the
// motion's own differences: every step would be near, and the steps are no longer chosen for the
// tolerance.
void StepDoubling::carryError(long long toStep) {
    if (dampedModes_) flow_.eventError2.array() *= stepDecay_.array();
    flow_.errorQ = errorNextQ_ + localQ_;
    flow_.errorMomentum = errorNextMomentum_ + localMomentum_;
    flow_.errorStep = toStep;
    sampleError();
    squaredAmplitudes(flow_.errorQ, flow_.errorMomentum, amplitude_);
    errorReach_ = flow_.lostAt >= 0.0 ? 0.0 : plate_.rowModeNormMax * std::sqrt(amplitude_.sum());
}

// The companion of the contact step: from t_n with the global error added to the massive modes
// (the massless part's contact force and energy at t_n solved again for the perturbed rows, so the
// discrete gradient starts from its own ψ), taken at level j; E carried through the step is its end
// less the coarse run's (coarse_, the same level from the unperturbed start). Returns its solves.
long long StepDoubling::companion(double zNext, double pNext, int j) {
    perturb_(*start_, flow_.errorQ, flow_.errorMomentum, perturbed_);
    run_(perturbed_, zNext, pNext, j, false, companion_);
    errorNextQ_ = companion_.s.q - coarse_.s.q;
    errorNextMomentum_ = companion_.s.momentum - coarse_.s.momentum;
    return companion_.s.contactSolves - start_->s.contactSolves;
}

// The kept run's own error, from the coarse run's difference to it: 1/(2^p − 1) of it where no row
// changed sides over the step (p the learnt order), all of it across an onset or a release (first
// order). Into localQ_, localMomentum_; returned measured at the reported points as the amplitude
// of their sum of modal oscillations, √Σ(G_ik a_k)², a_k = √(δq_k² + (δP_k/ω_k)²).
double StepDoubling::localError() {
    const CondensedState &s = kept_->s, &start = start_->s;
    smooth_ = s.rowState == start.rowState && coarse_.s.rowState == start.rowState;
    localQ_ = coarse_.s.q - s.q;
    localMomentum_ = coarse_.s.momentum - s.momentum;
    squaredAmplitudes(localQ_, localMomentum_, amplitude_);
    difference_ = atReportedPoints(amplitude_);
    // Order p: the kept run's error is the difference / (2^p − 1).
    const double weight = smooth_ ? 1.0 / (std::exp2(flow_.smoothOrder) - 1.0) : 1.0;
    localQ_ *= weight;
    localMomentum_ *= weight;
    return weight * difference_;
}

// A step where rows changed sides (an onset, a release, a row joining or leaving held contact): its
// pair sizes the kept run's error in every mode but cannot sign it — each run's error comes from where
// the event falls inside its own sub-step — so E may carry it with the wrong sign, and where E's modes
// then cancel at a point the error's add (docs/theory.md §22, events sized, not signed). Each mode's
// squared amplitude, the pair's or R's whichever is larger, is summed over such steps (their signs
// independent) and bounds the estimate from below (sampleError). Where the pair was blind, E carries
// R's difference too, signed: its growth at later impacts goes with it.
void StepDoubling::addEventError() {
    squaredAmplitudes(localQ_, localMomentum_, amplitude_);
    squaredAmplitudes(eventQ_, eventMomentum_, scratchQ_);
    flow_.eventError2.array() += amplitude_.array().max(scratchQ_.array());
    if (straddled_) {  // the pair's difference is the coarse run's event error: E carries straddledError's
        localQ_ = eventQ_;
        localMomentum_ = eventMomentum_;
    } else if (blindPair_) {
        localQ_ += eventQ_;
        localMomentum_ += eventMomentum_;
    }
}

// The pair after a blind one's rise straddles the stair R found (its difference over kBlindPair times
// R's): its coarse run is the kept run R found wrong, and their difference is that run's event error, not
// this one's. This kept run's error is then its own event error (kept − R) plus R's, R's the Richardson
// share of the two R's difference, R_{j−1} − R_j = pair + (kept_j − R_j) − (kept_{j−1} − R_{j−1}), as in
// held contact (docs/theory.md §22, events resolved). Into event*, returned at the reported points, m.
double StepDoubling::straddledError() {
    const double share = 1.0 / (std::exp2(flow_.smoothOrder) - 1.0);
    lastEventQ_ = eventQ_ + share * (localQ_ + eventQ_ - lastEventQ_);  // (coefficient-wise: no alias)
    lastEventMomentum_ = eventMomentum_ + share * (localMomentum_ + eventMomentum_ - lastEventMomentum_);
    eventQ_.swap(lastEventQ_);  // lastEventQ_ keeps this level's kept − R for a further rise
    eventMomentum_.swap(lastEventMomentum_);
    squaredAmplitudes(eventQ_, eventMomentum_, amplitude_);
    return atReportedPoints(amplitude_);
}

// R (docs/theory.md §22, events resolved): the kept run at level j again from t_n, each of its
// sub-steps in which a row changes sides taken again as two of half its length, kResolveDepth times (at
// most to the cap) — a sub-step boundary within 1/16 of a kept sub-step from every onset and release. The error an event leaves depends on
// how far from it the boundary its sub-step resolves it at lies, not smoothly on the sub-step's length:
// runs of 2 and 4 sub-steps may resolve it at one boundary and make one error, which their difference
// cannot see. kept − R is the kept run's error at its events, signed.
double StepDoubling::resolveEvents(double zNext, double pNext, int j) {
    try {
        run_(*start_, zNext, pNext, j, true, resolved_);
    } catch (const StepError&) {  // R cannot be taken: it says nothing (< 0), the kept step stands
        eventQ_.setZero();
        eventMomentum_.setZero();
        return -1.0;
    }
    eventQ_ = kept_->s.q - resolved_.s.q;
    eventMomentum_ = kept_->s.momentum - resolved_.s.momentum;
    squaredAmplitudes(eventQ_, eventMomentum_, amplitude_);
    return atReportedPoints(amplitude_);
}

// E from errorStep to toStep by the exact free flow of each mode (the error obeys the homogeneous
// equation: the base and the load are the same for the computed and the exact motion).
void StepDoubling::rotateError(long long toStep) {
    Eigen::VectorXd& u = flow_.errorQ;
    Eigen::VectorXd& v = flow_.errorMomentum;
    Eigen::VectorXd& events = flow_.eventError2;  // amplitudes only: constant undamped, decaying damped
    for (; flow_.errorStep < toStep; ++flow_.errorStep) {
        scratchQ_ = exact_.f11.cwiseProduct(u) + exact_.f12.cwiseProduct(v);
        v = exact_.f21.cwiseProduct(u) + exact_.f22.cwiseProduct(v);
        u.swap(scratchQ_);
        if (dampedModes_) events.array() *= stepDecay_.array();
    }
}

// The reported points' error implied by E now, into the running maximum. Two motions between both
// obstacles differ at a constraint row by the gap at most: past the horizon, where E grows with the
// motion's sensitivity, the estimate stops there (and E with it).
void StepDoubling::sampleError(bool events) {
    rowBound_.noalias() = measuredRows_ * flow_.errorQ;
    double now = rowBound_.size() > 0 ? rowBound_.cwiseAbs().maxCoeff() : 0.0;
    // The events' error, unsigned: the amplitude of its modes' oscillations at the point, √Σ G_ik² A_k²
    // — a floor under |G_i δq| where E's events have the wrong sign (docs/theory.md §22). Free flight
    // keeps or damps each amplitude, so only a contact step can raise it.
    if (events) now = std::max(now, atReportedPoints(flow_.eventError2));
    const double gap = gapBound_;
    if (!(now < gap)) {  // also a non-finite E
        const double scale = std::isfinite(now) && now > 0.0 ? gap / now : 0.0;
        flow_.errorQ *= scale;
        flow_.errorMomentum *= scale;
    }
    flow_.errorEstimate = std::max(flow_.errorEstimate, std::isfinite(now) ? std::min(now, gap) : gap);
    if (flow_.lostAt < 0.0 && flow_.errorEstimate > tolerance_) flow_.lostAt = double(flow_.errorStep) * dt_;
    if (flow_.lostAt >= 0.0 && boundedByGap()) {
        // Past the horizon between two obstacles the estimate is their gap from now on: the one bound
        // that holds whatever the motion's sensitivity does (docs/theory.md §22), and E is no longer
        // carried (every later step would otherwise pay a pair and a companion for it).
        flow_.errorEstimate = gap;
        flow_.errorQ.setZero();
        flow_.errorMomentum.setZero();
        flow_.eventError2.setZero();
    }
}

// Past the horizon the contact steps take 2^fixedLevel_ sub-steps, within the levels refine steps on.
ToleranceHorizon StepDoubling::horizon() const { return {flow_.lostAt, 1 << std::clamp(fixedLevel_, 1, top_)}; }

bool StepDoubling::boundedByGap() const { return std::isfinite(gapBound_); }

// The step's share of the tolerance (docs/theory.md §22): what is left of it, over the contact steps
// still to come. Their number is unknown; it lies between the contact steps so far (the run goes on
// as it went) and all steps so far (contact at every step from now on), and the share takes their
// geometric mean.
double StepDoubling::localTarget() const {
    const double left = std::max(tolerance_ - flow_.errorEstimate, 0.5 * tolerance_);
    return left / std::sqrt(double(flow_.contactSteps) * double(start_->s.step + 1));
}

// Each mode's squared error amplitude a_k² = δq_k² + (δP_k/ω_k)² (constant in undamped free flight).
void StepDoubling::squaredAmplitudes(const Eigen::VectorXd& q, const Eigen::VectorXd& momentum,
                                     Eigen::VectorXd& into) const {
    into.array() = q.array().square() + (momentum.array() * inverseOmega_.array()).square();
}

// Modes of independent phases at the reported points: the largest amplitude of their sum, √max_i Σ_k G_ik² a_k².
double StepDoubling::atReportedPoints(const Eigen::VectorXd& squared) {
    rowBound_.noalias() = measuredRows2_ * squared;
    return rowBound_.size() > 0 ? std::sqrt(rowBound_.maxCoeff()) : 0.0;
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

std::vector<double> FlowState::save() const {
    return archive::save(*this, kFlowFormat, std::array<std::size_t, 1>{std::size_t(errorQ.size())}, flowMembers);
}

FlowState FlowState::load(const std::vector<double>& data, std::size_t modes) {
    FlowState loaded = archive::load<FlowState>(data, kFlowFormat, std::array<std::size_t, 1>{modes}, flowMembers);
    if ((loaded.eventError2.array() < 0.0).any())
        throw std::invalid_argument("corrupt state: a negative squared amplitude in the events' error");
    return loaded;
}

}  // namespace plate
