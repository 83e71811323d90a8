#pragma once
// One time scheme of the plate behind PlateSimulation (docs/architecture.md): Newmark with its
// impact laws (NewmarkScheme), the conserving midpoint rule (MidpointScheme, docs/theory.md §17)
// or the exact modal flow with contact resolved in the contact rows (FlowScheme, §21). As scipy's
// OdeSolver keeps `step()` in its base and each method writes `_step_impl`, the base owns what
// every scheme shares — the inputs' levels, the step count, the ledger, the port's contact sums and
// impact counts, the input checks and the refusals, the outputs written once — and a scheme writes
// its advance (`advance`) and the heights of its output points (`pointHeight`). PlateSimulation owns
// the communication grid, the inputs and the interpolation between grid points. Schemes are made
// in one place: makeScheme (solver/MakeScheme.cpp).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "base/History.h"
#include "plate/Obstacles.h"
#include "plate/PlateParameters.h"
#include "schemes/PlateOutputs.h"

namespace plate {

class Armature;

// The value at the output level (0: t_n) or one of the two before it (1: t_{n−1}, 2: t_{n−2}).
template <class T>
const T& atLevel(int level, const T& now, const T& prev, const T& prev2) {
    return level == 0 ? now : level == 1 ? prev : prev2;
}

// What every scheme's state holds alike. NewmarkState and CondensedState derive from it; each
// archives these members in its own (unchanged) order.
struct SchemeState {
    double z = 0, zPrev = 0, zPrev2 = 0;  // base at t_n, t_{n−1}, t_{n−2}
    double p = 0, pPrev = 0, pPrev2 = 0;  // pressure at t_n, t_{n−1}, t_{n−2}
    long long step = 0;
    double energyInput = 0;  // cumulative work of base motion and load, J
    double energyDissipated = 0;  // cumulative loss at impacts, J (the condensed schemes lose none)
    double energyDamped = 0;  // cumulative work of the Rayleigh damping (docs/theory.md §13), J
    double maxKktResidual = 0;  // largest relative KKT residual of the contact solves so far
    // The contact solves so far (Newmark: iterations of its QP; the condensed schemes: solves of
    // theirs), the most iterations of one step (Newmark: QP, condensed: discrete gradient) and the last.
    long long contactSolves = 0;
    int contactIterationsMax = 0, contactIterationsLast = 0;
    int contactPoints = 0;  // vertices (Newmark) or rows (condensed) held by an obstacle at t_n
    // The port (docs/theory.md §14) over the last step, per obstacle (0 lower, 1 upper): the contact
    // force, its moment about the clamp line (both obstacles), the cumulative impulse and the contact
    // onsets so far: (sub-)steps whose force starts from zero, every chatter of a vertex among them
    // (the impact episodes are PlateSimulation's, docs/theory.md §14).
    double stepContactForce[2] = {0, 0}, stepContactMoment = 0;
    double contactImpulseSum[2] = {0, 0};
    long long contactOnsets[2] = {0, 0};
};

// The base's share of every scheme's flat form (base/StateArchive.h), first after the scheme's
// vectors: one description for all schemes. `maxContacts`: the bound of contactPoints.
template <class State, class Archive>
void sharedMembers(State& s, Archive& v, double maxContacts) {
    for (auto* x : {&s.z, &s.zPrev, &s.zPrev2}) v.real(*x, "z");
    for (auto* x : {&s.p, &s.pPrev, &s.pPrev2}) v.real(*x, "p");
    v.count(s.step, "step");
    v.real(s.energyInput, "energy input");
    v.real(s.energyDissipated, "energy dissipated");
    v.real(s.energyDamped, "energy damped");
    v.real(s.maxKktResidual, "KKT residual");
    v.count(s.contactSolves, "contact solves");
    for (auto* k : {&s.contactIterationsMax, &s.contactIterationsLast}) v.count(*k, "contact iterations");
    v.count(s.contactPoints, "contact points", maxContacts);
    for (auto* x : {&s.stepContactForce[0], &s.stepContactForce[1]}) v.real(*x, "contact force");
    v.real(s.stepContactMoment, "contact moment");
    for (auto* x : {&s.contactImpulseSum[0], &s.contactImpulseSum[1]}) v.real(*x, "contact impulse");
    for (auto* k : {&s.contactOnsets[0], &s.contactOnsets[1]}) v.count(*k, "contact onsets");
}

class Scheme {
public:
    virtual ~Scheme() = default;

    // The load input at t = 0, known only when the master starts stepping (before the first step).
    virtual void setLoadAtStart(double p0) = 0;
    // One internal step to t_{n+1} with the base at zNext (a carried clamp: the carrier's drive) and
    // the pressure pNext there: the inputs checked, then the scheme's advance. Transactional: a step
    // that cannot be taken throws StepError (its time: t_{n+1}) and leaves the scheme as it was, what
    // it keeps beside its state included (a scheme's own work is on scratch until it records the step).
    void step(double zNext, double pNext) {
        if (!carried_) checkInputs(zNext, pNext);
        advance(zNext, pNext);
    }

    long long stepCount() const { return shared().step; }
    double clampHeight(int level) const {  // z at the output level (0) or one of the two before it
        const SchemeState& s = shared();
        return atLevel(level, s.z, s.zPrev, s.zPrev2);
    }
    int contactVertices() const { return shared().contactPoints; }  // points held by an obstacle at t_n
    // Per obstacle (0 lower, 1 upper): the contact force of the last (sub-)step and the contact onsets
    // so far (§14); what the impact episodes are counted from (PlateSimulation, §14).
    double contactForce(int k) const { return shared().stepContactForce[k]; }
    long long contactOnsets(int k) const { return shared().contactOnsets[k]; }
    // The outputs at t_n, written once for every scheme; `port` adds the port's fields (§14).
    PlateOutputs outputs(bool port) const;
    // Absolute height of every mesh vertex at t_n.
    virtual std::vector<double> vertexDisplacements() const = 0;
    // The recovery functionals [first, first + out.size()) — the probes and stress samples
    // PlateSimulation gave the scheme at construction (docs/theory.md §23) — of the displacement
    // relative to the clamp at the output level (0) or one of the two before it (1, 2).
    virtual void recover(Eigen::Index first, int level, Eigen::Ref<Eigen::VectorXd> out) const = 0;

    virtual std::vector<double> saveState() const = 0;
    virtual void restoreState(const std::vector<double>& state) = 0;  // throws std::invalid_argument

    virtual std::string name() const = 0;  // "sparse", "modal-complete", "modal-<m>", "conserving-…", "flow-…"
    virtual double firstFrequency() const = 0;  // Hz, lowest mode of the plate as stepped
    virtual double kappa() const = 0;  // largest ω² of the plate as stepped, s⁻²
    double dt() const { return dt_; }

    // The clamp's carrier (docs/theory.md §18–19), where the scheme carries the clamp: none by default.
    virtual Armature* carrier() { return nullptr; }
    const Armature* carrier() const { return const_cast<Scheme*>(this)->carrier(); }
    virtual CarrierOutputs carrierOutputs() const { return {}; }  // zero without a carrier
    virtual ToleranceHorizon toleranceHorizon() const { return {}; }  // none without a tolerance

protected:
    Scheme(Obstacles obstacles, double dt) : obstacles_(obstacles), dt_(dt) {}

    // The scheme's step to t_{n+1}, inputs checked (the carried clamp checks its own drive).
    virtual void advance(double zNext, double pNext) = 0;
    virtual const SchemeState& shared() const = 0;
    // The absolute height of output point k (0 corner_1, 1 corner_2, 2 free_edge_mid) at the output
    // level (0) or one of the two before it.
    virtual double pointHeight(int k, int level) const = 0;
    virtual double outputEnergy() const = 0;  // the discrete energy at t_n, J
    // What the plate exerts on the clamp over the last step (before the first: the initial static
    // state's reaction), N and N·m (§14).
    virtual void clampLoad(double& force, double& moment) const = 0;
    virtual void addOutputs(PlateOutputs&) const {}  // a scheme's own outputs (the flow law's estimate)

    // What a (sub-)step leaves in the base's share of the state, written here once for every scheme:
    // the inputs' levels and the step count move on, the ledger's sums (T.6, T.17d) take the step's
    // work, loss and damping, and the contact solves' statistics take the step's.
    struct StepRecord {
        double input = 0, dissipated = 0, damped = 0;  // J
        long long solves = 0;
        int iterations = 0;
        double kkt = 0;
    };
    static void recordStep(SchemeState& s, double zNext, double pNext, const StepRecord& r) {
        advanceLevels(s.z, s.zPrev, s.zPrev2, zNext);
        advanceLevels(s.p, s.pPrev, s.pPrev2, pNext);
        ++s.step;
        s.energyInput += r.input;
        s.energyDissipated += r.dissipated;
        s.energyDamped += r.damped;
        s.contactSolves += r.solves;
        s.contactIterationsLast = r.iterations;
        s.contactIterationsMax = std::max(s.contactIterationsMax, r.iterations);
        s.maxKktResidual = std::max(s.maxKktResidual, r.kkt);
    }
    // The step's contact force per obstacle (N) over a (sub-)step of length h into the port's sums:
    // an onset where an obstacle's force was zero the step before (docs/theory.md §14).
    static void bookContact(SchemeState& s, const double (&force)[2], double h) {
        for (int k = 0; k < 2; ++k) {
            s.contactOnsets[k] += force[k] != 0.0 && s.stepContactForce[k] == 0.0;
            s.stepContactForce[k] = force[k];
            s.contactImpulseSum[k] += force[k] * h;
        }
    }
    // The inputs of a step: finite, in range, the clamp between the obstacles whose stops reach it (inline: every step
    // asks; refuseInputs builds the message only for a refusal).
    void checkInputs(double zNext, double pNext) const {
        const bool finite = std::isfinite(zNext) && std::isfinite(pNext);
        const bool inRange = std::fabs(zNext) <= kMaxDisplacement && std::fabs(pNext) <= kMaxLoad;
        const bool between = zNext >= obstacles_.clampLower() && zNext <= obstacles_.clampUpper();  // §25
        if (!(finite && inRange && between)) refuseInputs(zNext, pNext, finite, inRange);
    }
    double nextTime() const { return double(shared().step + 1) * dt_; }  // t_{n+1}, for messages
    [[noreturn]] void refuseInputs(double zNext, double pNext, bool finite, bool inRange) const;
    [[noreturn]] void refuseNonFinite() const;  // the step produced a non-finite displacement
    [[noreturn]] void refuseUnsolved(const char* what, int iterations, double kkt) const;  // a contact solve failed
    void setCarried(bool carried) { carried_ = carried; }

    Obstacles obstacles_;
    double dt_;

private:
    bool carried_ = false;
};

}  // namespace plate
