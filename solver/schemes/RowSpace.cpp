#include "schemes/RowSpace.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace plate {

RowSpace::RowSpace(const CondensedPlate& plate, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                   const FreeFlightBound& freeFlight)
    : plate_(plate), lowerAll_(lower), upperAll_(upper) {
    const Eigen::Index m = plate.modes(), rows = plate.rows();
    index_.reserve(std::size_t(rows));
    gathered_.reserve(std::size_t(rows));
    modes_.resize(m, rows);
    delassus_.resize(rows, rows);
    load_.resize(rows);
    x_.resize(std::size_t(rows));
    endColumns_ = std::make_unique<ContactColumns>(delassus_);
    endQP_ = std::make_unique<BoxQP>(*endColumns_);
    op_.inverseH.resize(m);
    op_.w2.resize(rows, rows);
    op_.midpointMatrix.resize(rows, rows);
    op_.midColumns = std::make_unique<ContactColumns>(op_.midpointMatrix);
    op_.midQP = std::make_unique<BoxQP>(*op_.midColumns);
    lower_.setZero(rows);
    upper_.setZero(rows);
    buffers_.resize(rows);
    inside_.rows.setZero(rows);
    inside_.freeFlight = freeFlight;
}

void RowSpace::select(const CondensedState& s, const Eigen::VectorXd& rowsStart, const Eigen::VectorXd& qNext,
                      const Eigen::VectorXd& rowsEnd, double zNext, double pNext, double rowLoadMax) {
    const CondensedPlate& c = plate_;
    index_.clear();
    const double reach =
        2.0 * (c.rowModeNormMax * (qNext - s.q).norm() + std::abs(zNext - s.z) + std::abs(pNext - s.p) * rowLoadMax);
    const auto gap = [this](int i, double r) { return std::min(r - lowerAll_[i], upperAll_[i] - r); };  // §25
    const int rows = c.rows();
    for (int i = 0; i < rows; ++i) {
        const auto k = static_cast<std::size_t>(i);
        if (s.rowState[k] != 0 || s.midState[k] != 0 || gap(i, rowsStart[i]) < reach || gap(i, rowsEnd[i]) < reach)
            index_.push_back(i);
    }
    if (int(index_.size()) == rows) {
        index_.clear();
        return;
    }
    // C's data, gathered when C changed (in held contact it often does not): its leading columns and block.
    const Eigen::Index n = Eigen::Index(index_.size());
    if (index_ == gathered_) return;
    gathered_.assign(index_.begin(), index_.end());  // within the reserved capacity
    modes_.leftCols(n) = c.rowModesT(Eigen::all, indices());
    delassus_.topLeftCorner(n, n) = c.delassus(indices(), indices());
    load_.head(n) = c.rowLoad(indices());
    load_.tail(c.rows() - n).setZero();
    std::fill(x_.begin() + n, x_.end(), 0.0);
    for (Eigen::Index k = 0; k < n; ++k) x_[std::size_t(k)] = c.rowAbscissae[std::size_t(index_[std::size_t(k)])];
    // C's bounds; past C they are ∓∞: those entries never bind (StepSpace).
    constexpr double infinity = std::numeric_limits<double>::infinity();
    lower_.setConstant(-infinity);
    upper_.setConstant(infinity);
    lower_.head(n) = lowerAll_(indices());
    upper_.head(n) = upperAll_(indices());
    endColumns_->useLeading(int(n));
    endQP_->forgetFactor();
    from_ = nullptr;
}

// W₂ and the midpoint contact problem ½W₂ + D of op's sub-step length, in C (their leading block).
StepSpace RowSpace::space(const MidpointOperator& op) {
    const Eigen::Index n = Eigen::Index(index_.size());
    if (from_ != &op) {
        from_ = &op;
        op_.h = op.h;
        op_.inverseH = op.inverseH;
        op_.w2.topLeftCorner(n, n) = op.w2(indices(), indices());
        op_.midpointMatrix.topLeftCorner(n, n) = 0.5 * op_.w2.topLeftCorner(n, n) + delassus_.topLeftCorner(n, n);
        op_.midColumns->useLeading(int(n));
        op_.midQP->forgetFactor();
    }
    return {&op_, &modes_, &load_, &x_, endQP_.get(), n, &lower_, &upper_, &buffers_};
}

StepState& RowSpace::enter(const StepState& from) {
    StepState& in = inside_;
    RowBuffers& b = buffers_;
    const Eigen::Index n = Eigen::Index(index_.size()), rest = plate_.rows() - n;
    in.s = from.s;  // (the same sizes: no allocation)
    in.forceZero = from.forceZero;
    in.rowsKnown = from.rowsKnown;
    in.freeFlight.reset();
    // Past C every row vector is zero (StepSpace), whatever an earlier C left there.
    for (Eigen::VectorXd* v : {&b.r0, &b.r1, &b.drFree, &b.dr, &b.base, &b.e, &b.y, &b.w2v, &in.rows})
        v->tail(rest).setZero();
    for (Eigen::VectorXd* v : {&b.forceNext, &b.multiplier, &b.midForce, &b.endForce}) v->setZero();
    for (auto* v : {&b.rowTrial, &b.midTrial}) std::fill(v->begin() + n, v->end(), 0);
    b.forceNextZero = true;
    b.multiplierUsed = false;
    for (Eigen::VectorXd* v : {&in.s.force, &in.s.forcePrev, &in.s.forcePrev2}) v->tail(rest).setZero();
    for (auto* v : {&in.s.rowState, &in.s.midState}) std::fill(v->begin() + n, v->end(), 0);
    in.s.force.head(n) = from.s.force(indices());
    in.s.forcePrev.head(n) = from.s.forcePrev(indices());
    in.s.forcePrev2.head(n) = from.s.forcePrev2(indices());
    if (from.rowsKnown) in.rows.head(n) = from.rows(indices());
    for (std::size_t k = 0; k < index_.size(); ++k) {
        in.s.rowState[k] = from.s.rowState[std::size_t(index_[k])];
        in.s.midState[k] = from.s.midState[std::size_t(index_[k])];
    }
    return in;
}

void RowSpace::leave(StepState& end, StepState& to) const {
    to.s = end.s;
    to.s.force.setZero();
    std::fill(to.s.rowState.begin(), to.s.rowState.end(), 0);
    std::fill(to.s.midState.begin(), to.s.midState.end(), 0);
    to.s.force(indices()) = end.s.force.head(Eigen::Index(index_.size()));
    for (std::size_t k = 0; k < index_.size(); ++k) {
        const auto i = index_[k];
        to.s.rowState[std::size_t(i)] = end.s.rowState[k];
        to.s.midState[std::size_t(i)] = end.s.midState[k];
    }
    to.rowsKnown = false;
}

bool RowSpace::stayFree(const Eigen::VectorXd& rows, const Eigen::VectorXd& force) const {
    const CondensedPlate& c = plate_;
    std::size_t k = 0;
    for (int i = 0; i < c.rows(); ++i) {
        if (k < index_.size() && index_[k] == i) {
            ++k;
            continue;
        }
        double y = rows[i];
        for (int a : index_)
            if (force[a] != 0.0) y += c.delassus(i, a) * force[a];
        if (y < lowerAll_[i] || y > upperAll_[i]) return false;
    }
    return true;
}

}  // namespace plate
