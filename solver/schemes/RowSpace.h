#pragma once
// The rows a contact step of the flow law can touch (docs/theory.md §24): chosen at the step's start,
// their data gathered (kept while they stay the same), the midpoint operator of a sub-step length in
// them, and buffers and a scratch state of their own: a run in them starts from a state gathered into
// them and ends scattered back into every row. Sized to every row once; a step fills the leading |C|
// entries, columns and blocks and allocates nothing.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "schemes/CondensedScheme.h"

namespace plate {

class RowSpace {
public:
    RowSpace(const CondensedPlate& plate, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
             const FreeFlightBound& freeFlight);

    // C for the step from `start` (its rows at t_n: rowsStart) whose free trial ends at (qNext, rowsEnd,
    // zNext, pNext): the rows held at its start, and those an obstacle is within reach of at its start or
    // at the trial's end. Reach: twice what any row can move with the plate, the base and the load over
    // the step in free flight (FreeFlightBound's sum); the contact forces' own effect on the other rows
    // is checked at the run's end (stayFree). Empty when every row can touch.
    void select(const CondensedState& start, const Eigen::VectorXd& rowsStart, const Eigen::VectorXd& qNext,
                const Eigen::VectorXd& rowsEnd, double zNext, double pNext, double rowLoadMax);
    bool empty() const { return index_.empty(); }
    void clear() { index_.clear(); }  // the rest of the step in every row
    void forget() { gathered_.clear(); }  // C's data gathered again by the next step that selects it
    // C's space for sub-steps of op's length (its W₂ and ½W₂ + D built when the length changed).
    StepSpace space(const MidpointOperator& op);
    // `from` (every row) gathered into C: the state a run in C starts from.
    StepState& enter(const StepState& from);
    // The run's end in C scattered into `to` (every row): its state, λ and the contact sets zero outside
    // C; the levels before its time are not its own (the scheme records them), its rows not known.
    void leave(StepState& end, StepState& to) const;
    // Every row outside C inside the obstacles at the run's end (rows: every row's r there), held back
    // by C's forces through D (y = r + D λ).
    bool stayFree(const Eigen::VectorXd& rows, const Eigen::VectorXd& force) const;

private:
    // C as Eigen's index (a view of index_: an indexed view holds its index by value, and a copy allocates).
    Eigen::Map<const Eigen::ArrayXi> indices() const { return {index_.data(), Eigen::Index(index_.size())}; }

    const CondensedPlate& plate_;
    const Eigen::VectorXd &lowerAll_, &upperAll_;
    std::vector<int> index_, gathered_;  // C: the rows that can touch, ascending; the C the data hold
    Eigen::MatrixXd modes_, delassus_;  // G_Cᵀ, D_CC
    Eigen::VectorXd load_, lower_, upper_;
    std::vector<double> x_;
    std::unique_ptr<ContactColumns> endColumns_;
    std::unique_ptr<BoxQP> endQP_;
    MidpointOperator op_;  // in C, for the sub-step length of `from_`
    const MidpointOperator* from_ = nullptr;
    RowBuffers buffers_;
    StepState inside_;  // a run's state in C
};

}  // namespace plate
