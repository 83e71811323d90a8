#pragma once
// time_scheme = flow with a tolerance (docs/theory.md §22): the controller of the contact steps'
// sub-steps by step doubling and the global error estimate. It talks to the flow law (FlowScheme)
// through runs: the contact step from t_n at a level (2^j sub-steps of Δt/2^j), R's run of it with its
// events resolved, and the companion from t_n + E; the scheme records the kept run as the step.
#include <Eigen/Core>
#include <array>
#include <functional>
#include <vector>

#include "plate/CondensedPlate.h"
#include "schemes/CondensedScheme.h"
#include "schemes/ExactFlow.h"
#include "schemes/PlateOutputs.h"

namespace plate {

// The controller's state, part of the flow law's (after the condensed schemes' in the flat form): the
// global error estimate — the vector E = (δq, δP) of modal displacement and momentum errors at step
// errorStep, carried through free flight by the exact flow and through each contact step by a
// companion of the step from the perturbed start — the largest output error it has implied so far,
// the contact steps taken, those the cap bounded, and the controller's level (the next contact step
// takes 2^level sub-steps).
struct FlowState {
    double errorEstimate = 0;  // the largest estimated error of the reported points so far, m
    long long cappedSteps = 0;
    int refinementLevel = 1;
    long long contactSteps = 0;
    long long errorStep = 0;
    double lostAt = -1;  // when the estimate passed the tolerance, s (< 0: not yet)
    // The sub-steps' order in held contact, observed (docs/theory.md §22); log2 3 until a rise says.
    double smoothOrder = 1.584962500721156;
    Eigen::VectorXd errorQ, errorMomentum;  // E at errorStep (sized to the massive modes)
    // The steps where rows changed sides leave an error whose size their pair gives but not its sign
    // (docs/theory.md §22, events sized, not signed): each mode's squared amplitude, summed over them,
    // at errorStep; it bounds the estimate from below as their oscillations' root-sum-square.
    Eigen::VectorXd eventError2;

    std::vector<double> save() const;  // the flat form (base/StateArchive.h)
    // Throws std::invalid_argument when the data does not fit `modes` or is corrupt.
    static FlowState load(const std::vector<double>& data, std::size_t modes);
};

class StepDoubling {
public:
    // The contact step from `from` to (zNext, pNext) at level j (resolve: R's sub-steps from it) into `to`.
    using Run =
        std::function<void(const StepState& from, double zNext, double pNext, int level, bool resolve, StepState& to)>;
    // The companion's start: `from` with (dq, dP) added to its modes, its contact at rest solved again.
    using Perturb =
        std::function<void(const StepState& from, const Eigen::VectorXd& dq, const Eigen::VectorXd& dP, StepState& to)>;
    // `probes`: the reported points' rows, where the error is measured (every row without them, as in
    // the unit tests); `exact`: the free flow over Δt; `refinement`: the tolerance, the levels up to
    // log2 max_contact_substeps, and contact_substeps past the horizon; `state`: the scheme's FlowState.
    StepDoubling(const CondensedPlate& plate, const std::array<int, 3>& probes, const Eigen::VectorXd& lower,
                 const Eigen::VectorXd& upper, const ExactFlow& exact, bool damped, const ContactRefinement& refinement,
                 double dt, FlowState& state, Run run, Perturb perturb);

    // The contact step from `start` (its rows at t_n, the free trial's at its end): the kept run into
    // `kept`, its work counting the other runs'. A throw leaves the estimate as it was.
    void contactStep(const StepState& start, const Eigen::VectorXd& rowsStart, const Eigen::VectorXd& trialEnd,
                     double zNext, double pNext, StepState& kept);
    // A free step within E's reach of an obstacle, from `start`: E through it by runs (in every row);
    // their solves. afterNearStep(n + 1) once the step is taken.
    long long nearMiss(const StepState& start, double zNext, double pNext);
    void afterNearStep(long long step) { carryError(step); }
    void afterFreeStep(long long step);  // E sampled at every step after the first contact step
    double reach() const { return errorReach_; }  // how far the carried error can move a row
    ToleranceHorizon horizon() const;

private:
    void refine(double zNext, double pNext);
    long long carryThroughStep(double zNext, double pNext, int level);  // E through the step
    void carryByFreeFlow();  // E through the step by the free flow, into errorNext*
    void carryError(long long toStep);  // E_{n+1} = carried + local at toStep; sampled; its reach
    long long companion(double zNext, double pNext, int level);  // from t_n + E: E carried, into errorNext*
    void rotateError(long long toStep);  // E by the exact free flow from errorStep to toStep
    // The reported points' error implied by E and (events) the events', into the running maximum.
    void sampleError(bool events = true);
    void addEventError();  // a step where rows changed sides: its local error's amplitudes, unsigned
    // A step where rows changed sides: the kept run at `level` again with its events resolved (R), from
    // t_n; kept − R into event*, returned at the reported points, m (−1 and event* zero where R cannot
    // be taken).
    double resolveEvents(double zNext, double pNext, int level);
    // The rise after a blind pair, whose new pair straddles R's stair: the kept run's error from both
    // levels' R, into event*, at the reported points, m.
    double straddledError();
    bool boundedByGap()
        const;  // every reported point under both obstacles: two motions differ there by gapBound_ at most
    double localTarget() const;  // what this contact step may add at the reported points, m
    double onsetFraction(const Eigen::VectorXd& rowsStart, const Eigen::VectorXd& trialEnd) const;
    int onsetLevel() const;  // the kept run's lowest level in this step
    double localError();  // the kept run's own error, into local*: at the reported points, m
    void squaredAmplitudes(const Eigen::VectorXd& q, const Eigen::VectorXd& momentum, Eigen::VectorXd& into) const;
    double atReportedPoints(const Eigen::VectorXd& squared);  // squared modal amplitudes → m, at the worst point

    const CondensedPlate& plate_;
    const Eigen::VectorXd &lower_, &upper_;
    const ExactFlow& exact_;
    const bool dampedModes_;  // some c_k ≠ 0
    const double tolerance_;
    const int top_;
    const double dt_;
    FlowState& flow_;
    Run run_;
    Perturb perturb_;
    const StepState* start_ = nullptr;  // this step's start and kept run (contactStep, nearMiss)
    StepState* kept_ = nullptr;
    StepState coarse_, resolved_, companion_, perturbed_;  // the other runs' ends, the companion's start
    FlowState flowAtStart_;  // the estimate at t_n, for a contact step that throws
    bool blindPair_ = false;  // this step's pair missed an event R saw (docs/theory.md §22, events resolved)
    bool straddled_ = false;  // the pair after its rise measured its coarse run's event error (straddledError)
    double errorReach_ = 0.0;
    // Where in an onset step (no row held at its start) the first row reaches an obstacle, as a fraction
    // of the step; 0 otherwise (docs/theory.md §22: the kept run's lowest level).
    double onsetFraction_ = 0.0;
    double gapBound_ = 0.0;  // the largest gap between the obstacles at a reported point (∞: one lacks one)
    bool smooth_ = false;  // the last localError's pair: no row changed sides
    double difference_ = 0.0;  // and its difference at the reported points, m
    const int fixedLevel_;  // past the tolerance's horizon: 2^fixedLevel_ sub-steps (≤ contact_substeps)
    Eigen::MatrixXd measuredRows_;  // G at the reported points
    Eigen::MatrixXd measuredRows2_;  // and its entries squared (amplitudes of independent phases, no temporary)
    Eigen::VectorXd inverseOmega_, amplitude_, rowBound_, errorNextQ_, errorNextMomentum_, localQ_, localMomentum_,
        scratchQ_, eventQ_, eventMomentum_, lastEventQ_, lastEventMomentum_;
    Eigen::VectorXd stepDecay_;  // how each mode's squared amplitude decays over Δt (det Φ: 1 undamped)
};

}  // namespace plate
