#pragma once
// time_scheme = flow (docs/theory.md §21): a step without contact advances every massive mode by
// its exact flow (the base linear and the load linear over the step, the damping exact); a step
// in which a row is or becomes active is taken as m midpoint sub-steps of Δt/m, each with its
// discrete gradient (CondensedScheme). Free flight has no phase error, the contact phases are
// resolved, and the energy identity (T.17d) holds step by step. With a tolerance (§22) each contact
// step chooses its sub-steps from an error estimate of its own.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "schemes/CondensedScheme.h"
#include "schemes/RowSpace.h"

namespace plate {

// How the flow law divides a contact step (docs/theory.md §21–22).
struct ContactRefinement {
    int substeps = 16;  // tolerance = 0: every contact step in this many sub-steps
    // > 0 (m): each contact step as many sub-steps as its error estimate asks (step doubling),
    // at most maxSubsteps (a power of two); the estimate accumulates in errorEstimate.
    double tolerance = 0.0;
    int maxSubsteps = 128;
    bool rowSpace = true;  // contact sub-steps in the rows that can touch (§24); false: in every row
};

// The flow law's own state (after the condensed schemes' in the flat form): with a tolerance
// (docs/theory.md §22), the global error estimate — the vector E = (δq, δP) of modal displacement
// and momentum errors at step errorStep, carried through free flight by the exact flow and through
// each contact step by a companion of the step from the perturbed start — the largest output error
// it has implied so far, the contact steps taken, those the cap bounded, and the controller's level
// (the next contact step takes 2^level sub-steps).
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
};

class FlowScheme final : public CondensedScheme {
public:
    FlowScheme(std::shared_ptr<const CondensedPlate> plate, Obstacles obstacles, double dt,
               ContactRefinement refinement, double dampingMass = 0.0, double dampingStiffness = 0.0,
               OutputRows rows = {});

    std::string name() const override;
    const FlowState& flowState() const { return flow_; }
    ToleranceHorizon toleranceHorizon() const override;
    // Contact steps' runs taken in the rows that can touch, and those taken again in every row because
    // a row outside them ended past an obstacle (docs/theory.md §24).
    long long rowSpaceSteps() const { return rowSpaceSteps_; }
    long long rowSpaceRetries() const { return rowSpaceRetries_; }

private:
    void advance(double zNext, double pNext) override;  // exact free flight, or a run on contact
    void exactStep(double zNext,
                   double pNext);  // every mode's exact flow over Δt into qNext_, momentumNext_, qIntegral_
    void freeStep(double zNext, double pNext, Look look);  // the exact step recorded
    // A run (docs/theory.md §21, §24): the contact step from `from` (t_n) to (zNext, pNext) as m midpoint
    // sub-steps of op's length — or, resolveFrom ≥ 0, R's sub-steps from that level (resolvedSubsteps) —
    // in the rows that can touch while the step has them, else in every row. Its end into `to`, with the
    // step's record (the port's values over the step); the scheme's state is not touched.
    void run(const StepState& from, double zNext, double pNext, int m, const MidpointOperator& op, StepState& to,
             int resolveFrom = -1);
    // The m sub-steps of op's length in x's space (rows: C's, else every row), base and load linear.
    void midpointSubsteps(bool inRows, const MidpointOperator& op, StepState& x, double zNext, double pNext, int m);
    // That level's sub-steps, those in which rows change sides halved, three levels down at most (R).
    void resolvedSubsteps(bool inRows, StepState& x, double zNext, double pNext, int level);
    StepSpace spaceFor(bool inRows, const MidpointOperator& op);
    const MidpointOperator& level(int j) const { return j == 0 ? full_ : *levels_[std::size_t(j - 1)]; }
    // The contact step's run as the step: the state changes here, once.
    void recordRun(StepState& end);
    void addOutputs(PlateOutputs& o) const override;
    std::vector<double> saveOwn() const override;
    void restoreOwn(const std::vector<double>& own) override;

    // tolerance > 0 (docs/theory.md §22): the kept run at level j and its companion from the
    // perturbed start at level j − 1; the global error carried and sampled. Runs into kept_.
    void refine(double zNext, double pNext);
    // A free step within E's reach of an obstacle: E through it by runs from t_n; their solves.
    long long nearMiss(double zNext, double pNext);
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
    double onsetFraction() const;  // from the rows at t_n (rowsStart_) and at the free trial's end
    int onsetLevel() const;  // the kept run's lowest level in this step
    double localError();  // the kept run's own error, into local*: at the reported points, m
    void squaredAmplitudes(const Eigen::VectorXd& q, const Eigen::VectorXd& momentum, Eigen::VectorXd& into) const;
    double atReportedPoints(const Eigen::VectorXd& squared);  // squared modal amplitudes → m, at the worst point

    ContactRefinement refinement_;
    FlowState flow_;
    std::unique_ptr<RowSpace> touch_;  // the rows a contact step can touch (rowSpace)
    long long rowSpaceSteps_ = 0, rowSpaceRetries_ = 0;
    long long stepRowSpaceRuns_ = 0, stepRowSpaceRetries_ = 0;  // this step's, counted at its record
    // Runs' ends: the kept run (the step's), the coarse run, R, the companion and its start, a sub-step of R.
    StepState kept_, coarse_, resolved_, companion_, perturbed_, substep_;
    Eigen::VectorXd rowsStart_;  // the rows at t_n (selectRows, onsetFraction)
    MidpointOperator sub_;  // sub-steps of Δt/m (tolerance = 0)
    // tolerance > 0: level j takes 2^j sub-steps of Δt/2^j (level 0 is full_).
    std::vector<std::unique_ptr<MidpointOperator>> levels_;
    bool blindPair_ = false;  // this step's pair missed an event R saw (docs/theory.md §22, events resolved)
    bool straddled_ = false;  // the pair after its rise measured its coarse run's event error (straddledError)
    FlowState flowAtStart_;  // the estimate at t_n, for a contact step that throws
    double errorReach_ = 0.0;  // how far the carried error can move a row (0 without a tolerance)
    // Where in an onset step (no row held at its start) the first row reaches an obstacle, as a fraction
    // of the step; 0 otherwise (docs/theory.md §22: the kept run's lowest level).
    double onsetFraction_ = 0.0;
    double gapBound_ = 0.0;  // the largest gap between the obstacles at a reported point (∞: one lacks one)
    bool smooth_ = false;  // the last localError's pair: no row changed sides
    double difference_ = 0.0;  // and its difference at the reported points, m
    int fixedLevel_ = 0;  // past the tolerance's horizon: 2^fixedLevel_ sub-steps (≤ contact_substeps)
    Eigen::MatrixXd measuredRows_;  // G at the reported points
    Eigen::MatrixXd measuredRows2_;  // and its entries squared (amplitudes of independent phases, no temporary)
    Eigen::VectorXd inverseOmega_, amplitude_, rowBound_, errorNextQ_, errorNextMomentum_, localQ_, localMomentum_,
        scratchQ_, eventQ_, eventMomentum_, lastEventQ_, lastEventMomentum_;
    // How each mode's squared amplitude decays over Δt (det Φ: 1 undamped).
    Eigen::VectorXd stepDecay_;
    // The exact flow over Δt of each mode's u = q − q_particular (§21): (u, u̇)⁺ = Φ (u, u̇).
    Eigen::VectorXd flow11_, flow12_, flow21_, flow22_;
    Eigen::VectorXd inverseOmega2_;  // 1/ω²
    bool dampedModes_ = false;  // some c_k ≠ 0
    Eigen::VectorXd slope_, offset_, u0_, ud0_, u1_, ud1_;  // the exact step's buffers
    Eigen::VectorXd qIntegral_;  // ∫ q over the exact step
};

}  // namespace plate
