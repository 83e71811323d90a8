#pragma once
// The schemes of the condensed singular plate (CondensedPlate.h, docs/theory.md §17): what the
// conserving midpoint rule (MidpointScheme) and the exact flow with contact sub-steps (FlowScheme,
// §21) share — the state, the input checks, the midpoint step with the discrete gradient of the
// boundary potential ψ(r) = ½ λ*(r)ᵀ D λ*(r), the ledger, the outputs and the state's flat form.
// Per step, exactly up to the contact solve,
//
//   E_{n+1} − E_n = (work of the base and the load) − (modal damping),       (T.17d)
//
// at any Δt, through impacts. In absolute modal momenta P = q̇ + b_m ż the midpoint step reads (T.17b)
//
//   q⁺ − q = Δt (P + P⁺)/2 − b_m (z⁺ − z),
//   P⁺ − P = Δt (−Ω² q̄ + p̄ F_m + GᵀΛ) − c ⊙ (q⁺ − q),     q̄ = (q + q⁺)/2, p̄ = (p + p⁺)/2,
//
// with Λ = λ*(r_mid) + c_g Δr the discrete gradient (T.17c) at the constraint rows'
// r = G q + p c_p + z·𝟙. In free flight (every row inside the obstacles at both ends) Λ = 0 and the
// step is the diagonal midpoint step; a bound on how far the rows can have moved since they were
// last looked at skips even the look (as the modal plate's free-flight bound does).
// The output points are constraint rows (the corners and a vertex free_edge_mid among the contact
// vertices, a free_edge_mid between vertices as a row of its own), so every reported height is
// within the obstacles.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include "plate/BoxQP.h"
#include "plate/CondensedPlate.h"
#include "plate/Obstacles.h"
#include "plate/PlateParameters.h"
#include "schemes/FreeFlightBound.h"
#include "schemes/Scheme.h"

namespace plate {

// The scheme's whole mutable state: the base's share (SchemeState) and the condensed plate's.
// Saving and restoring it continues bit-identically.
struct CondensedState : SchemeState {
    Eigen::VectorXd q, qPrev, qPrev2;  // massive modal coordinates at t_n, t_{n−1}, t_{n−2}
    Eigen::VectorXd momentum;  // P_n = q̇_n + b_m ż_n
    Eigen::VectorXd force, forcePrev, forcePrev2;  // λ*(r) at t_n, t_{n−1}, t_{n−2} (per row, N)
    double boundary = 0;  // ψ(r_n) = ½ λ_nᵀ D λ_n, the massless part's contact energy at t_n
    std::vector<signed char> rowState, midState;  // warm starts: end point and midpoint solves
    // The clamp's force and moment on the plate over the last step, at t_{n−½} (§14, §17).
    double clampForce = 0, clampMoment = 0;
};

// Which rows the outputs read: corner_1, corner_2 and free_edge_mid, and the row of each mesh
// vertex (−1 for a clamped vertex). Empty: no outputs but the ledger (the unit tests).
struct OutputRows {
    std::array<int, 3> probes{{-1, -1, -1}};
    std::vector<int> vertices;
};

// What the midpoint step (T.17b–c) of length h needs: H⁻¹, W₂ and the midpoint contact problem's
// matrix ½W₂ + D with its solver.
struct MidpointOperator {
    double h = 0.0;
    Eigen::VectorXd inverseH;  // 1 / (1 + ½h c + ¼h²Ω²)
    Eigen::MatrixXd w2, midpointMatrix;  // W₂ = ½h² G H⁻¹ Gᵀ and ½W₂ + D
    std::unique_ptr<ContactColumns> midColumns;
    std::unique_ptr<BoxQP> midQP;
};

// A midpoint step's row-sized buffers in one space, allocated once with every row's length (a space
// of fewer rows uses their leading entries and keeps the rest zero), and which of them are known to
// be zero: free flight touches none of them.
struct RowBuffers {
    Eigen::VectorXd forceNext, multiplier, r0, r1, drFree, dr, base, e, y, w2v, midForce, endForce;
    std::vector<signed char> rowTrial, midTrial;
    bool forceNextZero = true, multiplierUsed = false;
    void resize(Eigen::Index rows);  // every buffer zero
};

// What one midpoint step runs on (docs/theory.md §24): the operator of its length and the constraint
// rows it resolves contact in — every row (the conserving law, every look at the rows) or the rows a
// flow-law contact step can touch (RowSpace) — with their data and buffers. Past `count` the bounds
// are ∓∞ and the data zero, so that a contact step allocates nothing.
struct StepSpace {
    const MidpointOperator* op;
    const Eigen::MatrixXd* modes;  // Gᵀ: its leading `count` columns (massive modes × the space's rows)
    const Eigen::VectorXd* load;  // c_p at those rows (zero past them)
    const std::vector<double>* x;  // their lever arms about the clamp line
    BoxQP* endQP;  // the contact problem with their D
    Eigen::Index count;  // how many rows
    const Eigen::VectorXd *lower, *upper;  // their obstacles (docs/theory.md §25)
    RowBuffers* buffers;
    // A row vector's entries in the space: reductions over them alone add what a vector of the
    // space's own length would, in the same order.
    auto live(const Eigen::VectorXd& v) const { return v.head(count); }
};

// What a midpoint step starts from and leaves: the state (its row vectors in the step's space), which
// of its force levels are zero, its rows when a look left them (the next contact step starts from
// them), and the free-flight bound of its last look. The scheme's own, or a run's scratch.
struct StepState {
    CondensedState s;
    std::array<bool, 3> forceZero{{true, true, true}};  // λ at t, and at the two levels before
    Eigen::VectorXd rows;
    bool rowsKnown = false;
    FreeFlightBound freeFlight;
};

class CondensedScheme : public Scheme {
public:
    // At rest in static equilibrium under the pressure p0 with the clamp at z0 (the plate's own
    // static problem, reduced or not: it starts without vibrating). Throws ParameterError if the
    // contact problem does not converge.
    void initialize(double z0, double p0);
    // The load input at t = 0 (only before the first step): the massless part follows it at
    // once, the massive part keeps the initial state (docs/theory.md §11, §17).
    void setLoadAtStart(double p0) override;

    std::vector<double> vertexDisplacements() const override;
    void recover(Eigen::Index first, int level, Eigen::Ref<Eigen::VectorXd> out) const override;  // §23
    // The flat form: the base's members (serialize), then a subclass's own (saveOwn).
    std::vector<double> saveState() const override;
    void restoreState(const std::vector<double>& state) override;
    std::string name() const override;
    double firstFrequency() const override;
    double kappa() const override { return plate_->omega2.maxCoeff(); }

    // E_n = ½|P|² + ½ m_c ż² + ½ qᵀΩ²q + (strain energy of the massless part), J (T.17a).
    double energy() const;
    // What the plate at t_n, at rest, exerts on the clamp: −R with R from the instantaneous rates
    // Ṗ = −Ω²q + p F_m + Gᵀλ (docs/theory.md §17); the port's outputs before the first step.
    void initialReaction(double& force, double& moment) const;
    // Absolute height of constraint row i at t_n, t_{n−1}, t_{n−2} (level 0, 1, 2).
    double rowHeight(int i, int level = 0) const;

    const CondensedState& state() const { return now_.s; }
    void setState(const CondensedState& s);
    const CondensedPlate& plate() const { return *plate_; }

    std::vector<double> serialize() const;
    // Throws std::invalid_argument when the data does not fit this plate or is corrupt.
    CondensedState deserialize(const std::vector<double>& data) const;
    std::array<std::size_t, 2> sizes() const;  // of the flat form: massive modes, constraint rows
    std::size_t serializedLength() const;  // of serialize()'s flat form

protected:
    const SchemeState& shared() const override { return now_.s; }
    double pointHeight(int k, int level) const override { return rowHeight(rows_.probes[k], level); }
    double outputEnergy() const override { return energy(); }
    void clampLoad(double& force, double& moment) const override;
    // A subclass's own state after the base's in the flat form; restoreOwn checks it whole before
    // it sets anything (throws std::invalid_argument).
    virtual std::vector<double> saveOwn() const { return {}; }
    virtual void restoreOwn(const std::vector<double>& own);

    // The law's Δt and damping (the rest of LawParameters is the choice of this scheme).
    CondensedScheme(std::shared_ptr<const CondensedPlate> plate, Obstacles obstacles, const LawParameters& law,
                    OutputRows rows);

    void buildOperator(MidpointOperator& op, double h) const;
    // One step of space.op->h from x to (zNext, pNext) (T.17b–c); zBefore: the base one such step
    // before x's time (ż and z̈ at its start). x's ledger takes the step's record and its levels move on.
    // Throws StepError with x as it was. The rows at x's time are x.rows where known, else gathered.
    void midpointStep(const StepSpace& space, StepState& x, double zBefore, double zNext, double pNext);
    // The contact check after a trial step to (qNext_, zNext, pNext) from x: Skipped while x's
    // free-flight bound holds (inline: the common case of both schemes), else lookAtRowsNow.
    // `reserve` (FlowScheme with a tolerance): a free row within it of an obstacle is Near.
    enum class Look { Skipped, Free, Near, Contact };
    Look lookAtRows(const StepSpace& space, StepState& x, double zNext, double pNext, double reserve = 0.0) {
        if (!obstacles_.any() || plate_->rows() == 0 ||
            (x.s.contactPoints == 0 && x.freeFlight.holds(qNext_, zNext, pNext, reserve)))
            return Look::Skipped;
        return lookAtRowsNow(space, x, zNext, pNext, reserve);
    }
    Look lookAtRowsNow(const StepSpace& space, StepState& x, double zNext, double pNext, double reserve = 0.0);
    // What the look leaves for x's next step, at the step's end (a throw before leaves x as it was): the
    // free-flight bound from a free look, none after contact.
    void keepLook(StepState& x, Look look, double zNext, double pNext);
    // The space's rows at (q, p, z) into its leading entries of r (the rest zero).
    void gatherRows(const StepSpace& space, const Eigen::VectorXd& q, double p, double z, Eigen::VectorXd& r) const;
    // λ*(r) of x's rows r = G q + p c_p + z with D, into x's force, contact set and boundary energy ψ.
    void solveAtRest(StepState& x);
    // What a step's end leaves in x (the levels moved on, the ledger); `work`, `damped` its record.
    void commit(const StepSpace& space, StepState& x, double zBefore, double zNext, double pNext, double work,
                double damped, int iterations);
    // A run's end (sub-steps from t_n on a scratch state: the flow law's contact step) recorded as the
    // step to t_{n+1}: the state changes here, once.
    void recordRun(StepState& end);
    void refreshDerived(StepState& x);  // what is derived from x.s (which force levels are zero; nothing looked at)

    // What a scheme of the condensed plate reads of the base: the damping, the output rows, every
    // row's obstacles and max |c_p|, the step of Δt, the space of every row; the state at t_n; the
    // trial step's end (q, P at t_{n+1}: a look reads them, commit takes them); the solves' counts.
    const Eigen::VectorXd& damping() const { return damping_; }
    const OutputRows& outputRows() const { return rows_; }
    const Eigen::VectorXd& rowLower() const { return lower_; }
    const Eigen::VectorXd& rowUpper() const { return upper_; }
    double rowLoadMax() const { return rowLoadMax_; }
    const MidpointOperator& fullStep() const { return full_; }
    const StepSpace& everyRow() const { return everyRow_; }
    StepState& now() { return now_; }
    Eigen::VectorXd& qNext() { return qNext_; }
    Eigen::VectorXd& momentumNext() { return momentumNext_; }
    void resetSolves() {
        iterations_ = solves_ = 0;
        kkt_ = 0.0;
    }
    int iterations() const { return iterations_; }  // of the last contact solve

private:
    void applyW2(const StepSpace& space, const Eigen::VectorXd& v, Eigen::VectorXd& out);
    void discreteGradient(const StepSpace& space, StepState& x);  // Λ into the multiplier, from r0, drFree
    void solveContact(const StepSpace& space, BoxQP& qp, const Eigen::VectorXd& free, std::vector<signed char>& state,
                      Eigen::VectorXd& force, Eigen::VectorXd& y);
    static std::unique_ptr<ContactColumns> denseColumns(const Eigen::MatrixXd& matrix);  // its columns, as they are

    std::shared_ptr<const CondensedPlate> plate_;
    Eigen::VectorXd damping_;  // c_k = a + b ω_k² (Rayleigh on the massive modes, §17)
    OutputRows rows_;
    MidpointOperator full_;  // steps of Δt
    Eigen::VectorXd lower_, upper_;  // every row's obstacles (docs/theory.md §25)
    double rowLoadMax_ = 0.0;  // max |c_p|
    StepSpace everyRow_;  // Δt in every row: the conserving law's steps, and every look at the rows
    StepState now_;  // the scheme's state at t_n
    // The step's modal buffers, allocated once, and its contact solves' counts.
    Eigen::VectorXd rhs_, dq_, qNext_, momentumNext_;
    int iterations_ = 0, solves_ = 0;
    double kkt_ = 0.0;
    Eigen::MatrixXd endMatrix_;  // D
    std::unique_ptr<ContactColumns> endColumns_;
    std::unique_ptr<BoxQP> endQP_;
    RowBuffers all_;  // every row's buffers
    Eigen::VectorXd modalForce_, modalScratch_;
    double boundaryNext_ = 0.0, lookMargin_ = 0.0;
};

}  // namespace plate
