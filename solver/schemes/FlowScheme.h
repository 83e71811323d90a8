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
#include "schemes/ExactFlow.h"
#include "schemes/RowSpace.h"
#include "schemes/StepDoubling.h"

namespace plate {

class FlowScheme final : public CondensedScheme {
public:
    FlowScheme(std::shared_ptr<const CondensedPlate> plate, Obstacles obstacles, const LawParameters& law,
               ContactRefinement refinement, OutputRows rows = {});

    std::string name() const override;
    const FlowState& flowState() const { return flow_; }
    ToleranceHorizon toleranceHorizon() const override;
    // Contact steps' runs taken in the rows that can touch, and those taken again in every row because
    // a row outside them ended past an obstacle (docs/theory.md §24).
    long long rowSpaceSteps() const { return rowSpaceSteps_; }
    long long rowSpaceRetries() const { return rowSpaceRetries_; }

private:
    void advance(double zNext, double pNext) override;  // exact free flight, or a run on contact
    // Every mode's exact flow over Δt into qNext(), momentumNext() and qIntegral_.
    void exactStep(double zNext, double pNext);
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
    const MidpointOperator& level(int j) const { return j == 0 ? fullStep() : *levels_[std::size_t(j - 1)]; }
    void addOutputs(PlateOutputs& o) const override;
    std::vector<double> saveOwn() const override { return flow_.save(); }
    void restoreOwn(const std::vector<double>& own) override;

    ContactRefinement refinement_;
    FlowState flow_;  // the error estimate's (StepDoubling), archived with the scheme's state
    ExactFlow exact_;  // the free flow over Δt
    std::unique_ptr<RowSpace> touch_;  // the rows a contact step can touch (rowSpace)
    std::unique_ptr<StepDoubling> doubling_;  // tolerance > 0
    long long rowSpaceSteps_ = 0, rowSpaceRetries_ = 0;
    long long stepRowSpaceRuns_ = 0, stepRowSpaceRetries_ = 0;  // this step's, counted at its record
    StepState kept_, substep_;  // the step's run (the kept run with a tolerance), a sub-step of R
    Eigen::VectorXd rowsStart_;  // the rows at t_n (the row space, the onset)
    MidpointOperator sub_;  // sub-steps of Δt/m (tolerance = 0)
    // tolerance > 0: level j takes 2^j sub-steps of Δt/2^j (level 0 is fullStep()).
    std::vector<std::unique_ptr<MidpointOperator>> levels_;
    Eigen::VectorXd inverseOmega2_;  // 1/ω²
    bool dampedModes_ = false;  // some c_k ≠ 0
    Eigen::VectorXd slope_, offset_, u0_, ud0_, u1_, ud1_;  // the exact step's buffers
    Eigen::VectorXd qIntegral_;  // ∫ q over the exact step
    Eigen::VectorXd dq_, rhs_;  // its record's: Δq and the mean forces on the modes
};

}  // namespace plate
