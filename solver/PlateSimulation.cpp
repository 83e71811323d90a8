#include "PlateSimulation.h"

#include <algorithm>
#include <chrono>
#include <cfloat>
#include <cmath>
#include <limits>
#include <sstream>

#include "schemes/FieldRecovery.h"
#include "fe/Assembly.h"
#include "plate/BoxQP.h"
#include "plate/SparseCholesky.h"
#include "plate/FullOrderPlate.h"
#include "plate/ModalPlate.h"
#include "schemes/FlowScheme.h"
#include "schemes/MidpointScheme.h"
#include "schemes/NewmarkScheme.h"
#include "base/PortableMath.h"
#include "fe/SingularMass.h"
#include "plate/Spectrum.h"
#include "plate/StaticEquilibrium.h"

namespace plate {

namespace {

// A communication step that is a whole multiple of Δt up to this relative tolerance runs on the
// grid (importers' step sizes wobble in the last digits).
constexpr double kStepMultipleTolerance = 1e-9;
// A communication time within this fraction of Δt of a grid point is that grid point (§15); it
// is also the shortest step: anything shorter cannot be told from no step at all.
constexpr double kGridSnap = 1e-9;

Obstacles obstaclesOf(const PlateParameters& p) {
    Obstacles o;
    if (p.obstacleLowerEnabled) o.lower = p.obstacleLower;
    if (p.obstacleUpperEnabled) o.upper = p.obstacleUpper;
    return o;
}

// Exact mode (modes = 0) runs the complete modal basis where it is cheaper per step than the
// sparse factor of A (both are the same scheme (3.6) in other coordinates): a modal step is
// about one pass over the dense CΦ (contact vertices × dofs), a sparse step several indexed
// passes over about nnz(K) entries at ~5 times the cost per entry. The threshold and the
// measurements behind it: docs/theory.md §7.
bool completeModalPays(const ClampedPlate& plate) {
    return plate::completeModalPays(plate.mass.rows(), static_cast<long long>(plate.contactDofs.size()),
                                    plate.stiffness.nonZeros());
}

// The clamp's carrier (docs/theory.md §18–19): an armature, or a line end (massless, the line's
// impedance as its damper); the suspension is relaxed where the clamp starts.
CarrierOptions carrierOptions(const PlateParameters& p, double baseDisplacement0) {
    CarrierOptions c;
    c.line = p.carrier == PlateParameters::Carrier::Line;
    c.mass = c.line ? 0.0 : p.armatureMass;
    c.stiffness = c.line ? 0.0 : p.armatureStiffness;
    c.damping = c.line ? p.tlmImpedance : p.armatureDamping;
    c.restPosition = baseDisplacement0;
    return c;
}

}  // namespace

struct PlateSimulation::Impl {
    PlateParameters parameters;
    std::shared_ptr<const FiniteElementSpace> space;
    std::shared_ptr<const ClampedPlate> clamped;
    std::shared_ptr<const DiscretePlate> discrete;
    mutable std::unique_ptr<SparseCholesky> floorFactor;  // sparse A, for the floor measurement
    std::unique_ptr<Scheme> scheme;
    // Stress and probes (docs/theory.md §23): the functionals, and the peak since t = 0 of the root's
    // largest |w_xx|, tracked every step (part of the state).
    std::unique_ptr<FieldRecovery> recovery;
    double rootPeak = 0.0;
    // Only with stress_outputs: off, the peak stays 0 and the step costs nothing more.
    void trackRoot() {
        if (parameters.stressOutputs) rootPeak = std::max(rootPeak, recovery->rootCurvature(*scheme));
    }
    // Between grid points (docs/theory.md §15): the communication time, and the outputs at the
    // grid point before it (the one after it is the scheme's state).
    double commTime = 0.0;
    bool onGrid = true;
    PlateOutputs before;
    ResourceEstimate resources;  // made before the assembly
    InputSampler sampler;  // setInputSampler
};

PlateSimulation::PlateSimulation(const PlateParameters& p, double baseDisplacement0, double loadAtStart,
                                 const ProgressLog& log)
    : impl_(std::make_unique<Impl>()) {
    portable::fixDenseBlocking();  // the same bits on every CPU (docs/theory.md §20)
    validate(p);
    const Obstacles obstacles = obstaclesOf(p);
    requireBaseBetween(obstacles, baseDisplacement0);
    Impl& s = *impl_;
    s.parameters = p;
    requireMeshWithinBudget(p);  // far beyond memory_limit: refused before the space is built
    const Mesh mesh(p.length, p.width, p.nx, p.ny);
    s.space = makeSpace(p.element, mesh);
    s.resources = planResources(p, *s.space, log);  // refuses beyond memory_limit
    InitProgress progress(log, s.resources.initSeconds);
    progress.phase("assembly of M and K", s.resources.assemblySeconds);
    PlateMatrices matrices = assemble(*s.space, p.surfaceDensity(), p.bendingStiffness(), p.poissonRatio);
    Eigen::SparseMatrix<double> coupling, root;  // B and R of the singular mass, all dofs
    if (p.singularMass()) {
        SingularMass singular = assembleSingularMass(
            *s.space, p.surfaceDensity(), p.mass == MassModel::SingularP0 ? MassProjection::P0 : MassProjection::P1dg);
        matrices.mass = std::move(singular.mass);
        matrices.massMoment = std::move(singular.massMoment);
        coupling = std::move(singular.coupling);
        root = std::move(singular.root);
    }
    s.clamped = std::make_shared<const ClampedPlate>(clamp(*s.space, matrices));
    s.recovery = std::make_unique<FieldRecovery>(*s.space, *s.clamped, p);
    matrices = PlateMatrices{};  // the unclamped matrices are not needed past the clamp
    Eigen::SparseMatrix<double> couplingFree;
    if (p.singularMass()) {
        couplingFree = freeRows(coupling, *s.clamped);
        requireMasslessContact(couplingFree, *s.clamped,
                               p.mass == MassModel::SingularP0 ? "singular_p0" : "singular_p1dg");
    }
    const Eigen::SparseMatrix<double> rootFree =
        p.condensed() ? freeRows(root, *s.clamped) : Eigen::SparseMatrix<double>();
    s.scheme = makeScheme(obstacles, baseDisplacement0, loadAtStart, couplingFree, rootFree, progress);
    s.trackRoot();  // the initial state's (t = 0 belongs to the peak)
    progress.done(s.resources.peakMB);
}

// The one place a scheme is made: time_scheme chooses (docs/architecture.md).
std::unique_ptr<Scheme> PlateSimulation::makeScheme(const Obstacles& obstacles, double baseDisplacement0,
                                                    double loadAtStart, const Eigen::SparseMatrix<double>& couplingFree,
                                                    const Eigen::SparseMatrix<double>& rootFree,
                                                    InitProgress& progress) {
    const PlateParameters& p = impl_->parameters;
    if (p.timeScheme == TimeScheme::Newmark)
        return makeNewmark(obstacles, baseDisplacement0, loadAtStart, couplingFree, progress);
    progress.phase("condensed singular plate (massive modes, massless Delassus operator)",
                   impl_->resources.spectrumSeconds + impl_->resources.factorSeconds);
    OutputRows rows;
    auto condensed = condensedPlate(rootFree, rows);
    std::unique_ptr<CondensedScheme> scheme;
    if (p.timeScheme == TimeScheme::Flow)
        scheme = std::make_unique<FlowScheme>(condensed, obstacles, p.dt,
                                              ContactRefinement{p.contactSubsteps, p.tolerance, p.maxContactSubsteps},
                                              p.dampingMass, p.dampingStiffness, std::move(rows));
    else
        scheme = std::make_unique<MidpointScheme>(condensed, obstacles, p.dt, p.dampingMass, p.dampingStiffness,
                                                  std::move(rows));
    scheme->initialize(baseDisplacement0, p.initialLoad);
    scheme->setLoadAtStart(loadAtStart);
    return scheme;
}

// time_scheme = newmark: the plate in modal coordinates or on the sparse factor of A (docs/theory.md §7),
// the scheme with its impact law, and the static initial state.
std::unique_ptr<Scheme> PlateSimulation::makeNewmark(const Obstacles& obstacles, double baseDisplacement0,
                                                     double loadAtStart,
                                                     const Eigen::SparseMatrix<double>& couplingFree,
                                                     InitProgress& progress) {
    Impl& s = *impl_;
    const PlateParameters& p = s.parameters;
    if (p.beta < 0.25) {
        progress.phase("kappa_h by power iteration with the factor of M", s.resources.spectrumSeconds);
        requireStableStep();
    }
    using Engine = PlateParameters::Engine;
    // A singular mass has no M-orthonormal modal basis: it runs on the sparse factor.
    const bool modal = !p.singularMass() && (p.modes > 0 || p.engine == Engine::CompleteModal ||
                                             (p.engine == Engine::Auto && completeModalPays(*s.clamped)));
    progress.phase(modal ? "modal basis (generalized eigenproblem)" : "factorization of A = M + beta dt^2 K",
                   modal ? s.resources.spectrumSeconds : 0.5 * s.resources.factorSeconds);
    if (modal)
        s.discrete = std::make_shared<const ModalPlate>(s.space, s.clamped, p.dt, p.beta, p.modes, p.dampingMass,
                                                        p.dampingStiffness);
    else
        s.discrete =
            std::make_shared<const FullOrderPlate>(s.space, s.clamped, p.dt, p.beta, p.dampingMass, p.dampingStiffness);
    SchemeOptions options;
    options.restitution = p.restitution;
    options.dampingMass = p.dampingMass;
    options.dampingStiffness = p.dampingStiffness;
    options.singularMass = p.singularMass();  // carry the impulses (§11; the tests of the plain
        // step build their NewmarkScheme directly)
    options.carried = p.carrier != PlateParameters::Carrier::None;  // §18–19
    if (options.carried) options.carrier = carrierOptions(p, baseDisplacement0);
    auto scheme = std::make_unique<NewmarkScheme>(s.discrete, obstacles, options,
                                                  OutputPoints{p.length, p.width, s.space->mesh().vertexCount()});
    scheme->setRecovery(s.discrete->rows(s.recovery->functionals()));
    progress.phase("static initial state (factor of K)", s.resources.staticSeconds + 0.5 * s.resources.factorSeconds);
    initializeState(*scheme, obstacles, baseDisplacement0, loadAtStart, couplingFree);
    return scheme;
}

// time_scheme = conserving (docs/theory.md §17): the output points become constraint rows — a
// corner, or a free_edge_mid on a vertex, is its contact vertex's row; a free_edge_mid between
// vertices (ny odd) a row of its own.
std::shared_ptr<const CondensedPlate> PlateSimulation::condensedPlate(const Eigen::SparseMatrix<double>& rootFree,
                                                                      OutputRows& rows) const {
    const Impl& s = *impl_;
    const PlateParameters& p = s.parameters;
    const Mesh& mesh = s.space->mesh();
    std::vector<int> vertexRows(static_cast<std::size_t>(mesh.vertexCount()), -1);
    for (std::size_t i = 0; i < s.clamped->contactVertices.size(); ++i)
        vertexRows[static_cast<std::size_t>(s.clamped->contactVertices[i])] = static_cast<int>(i);
    std::vector<ConstraintRow> extra;
    std::array<int, 3> probeRows{vertexRows[mesh.vertex(p.nx, 0)], vertexRows[mesh.vertex(p.nx, p.ny)], -1};
    if (p.ny % 2 == 0) {
        probeRows[2] = vertexRows[mesh.vertex(p.nx, p.ny / 2)];
    } else {
        extra.push_back({s.clamped->probe(*s.space, p.length, 0.5 * p.width), p.length});
        probeRows[2] = static_cast<int>(s.clamped->contactVertices.size());
    }
    rows.probes = probeRows;
    rows.vertices = std::move(vertexRows);
    return std::make_shared<const CondensedPlate>(
        condense(*s.clamped, rootFree, extra, p.modes, s.recovery->functionals()));
}

void PlateSimulation::requireBaseBetween(const Obstacles& obstacles, double baseDisplacement0) {
    if (!std::isfinite(baseDisplacement0) || baseDisplacement0 < obstacles.lower ||
        baseDisplacement0 > obstacles.upper) {
        std::ostringstream msg;
        msg.precision(15);  // round-trips what users type (0.7, not 0.69999999999999996)
        msg << "invalid initial state: base_displacement = " << baseDisplacement0
            << " puts the clamped edge outside the obstacles (allowed: obstacle_lower = " << obstacles.lower
            << " <= base_displacement <= obstacle_upper = " << obstacles.upper << ")";
        throw ParameterError(msg.str());
    }
}

// Stability of γ = ½, β < ¼ (docs/theory.md §4): Δt < 2 / √((1 − 4β) κ_h).
void PlateSimulation::requireStableStep() const {
    const PlateParameters& p = impl_->parameters;
    const double kappaH = kappa();  // a power iteration: once
    const double bound = 2.0 / std::sqrt((1.0 - 4.0 * p.beta) * kappaH);
    if (!(p.dt < bound)) {
        std::ostringstream msg;
        msg.precision(6);
        msg << "invalid parameter dt = " << p.dt << " for beta = " << p.beta
            << " (allowed: dt < 2/sqrt((1-4 beta) kappa_h) = " << bound << " s, kappa_h = " << kappaH
            << " s^-2; or beta >= 0.25)";
        throw ParameterError(msg.str());
    }
}

// The initial state (docs/theory.md §3, §11): the static equilibrium under initial_load between
// the obstacles, at rest; with a singular mass its massless part in equilibrium with the load at
// t = 0 and the contact forces that hold it.
void PlateSimulation::initializeState(NewmarkScheme& scheme, const Obstacles& obstacles, double baseDisplacement0,
                                      double loadAtStart, const Eigen::SparseMatrix<double>& couplingFree) {
    Impl& s = *impl_;
    const PlateParameters& p = s.parameters;
    Eigen::VectorXd w0, force;
    const auto* modalPlate = dynamic_cast<const ModalPlate*>(s.discrete.get());
    if (modalPlate && modalPlate->complete()) {
        // Exact mode in modal coordinates: solve the static problem with the sparse factor of
        // K (roundoff ~eps·cond(K) rather than the dense eigen solution's eps·λ_max/λ_1) and
        // change coordinates, α0 = ΦᵀM w0, exact for the complete basis.
        const FullOrderPlate full(s.space, s.clamped, p.dt, p.beta);
        w0 = modalPlate->fromFullSpace(staticEquilibrium(full, obstacles, baseDisplacement0, p.initialLoad, &force));
    } else if (!p.singularMass()) {
        w0 = staticEquilibrium(*s.discrete, obstacles, baseDisplacement0, p.initialLoad, &force);
    }
    if (!p.singularMass()) {
        setInitialReaction(scheme, force);
        scheme.initialize(w0, baseDisplacement0, 0.0);
    } else {
        // §11: only the part of w0 the singular mass sees is initial data; the massless part
        // is in equilibrium with the load at t = 0 (unless the static state already is).
        w0 = staticEquilibrium(*s.discrete, obstacles, baseDisplacement0, p.initialLoad, &force);
        setInitialReaction(scheme, force);
        scheme.initialize(w0, baseDisplacement0, loadAtStart);
        if (loadAtStart != p.initialLoad) {
            w0 = masslessEquilibrium(*s.clamped, couplingFree, obstacles, baseDisplacement0, loadAtStart, w0, force);
            scheme.initialize(w0, baseDisplacement0, loadAtStart);
        }
        scheme.setInitialContactForce(force);
    }
}

// The port at t = 0 (docs/theory.md §14): the plate at rest in the static state of initial_load
// exerts on the clamp what the load and the obstacles put on it, p0·|Ω| + Σλ and p0·∫x + Σλ_i x_i.
void PlateSimulation::setInitialReaction(NewmarkScheme& scheme, const Eigen::VectorXd& contactForce) {
    Impl& s = *impl_;
    const ClampedPlate& plate = *s.clamped;
    double force = s.parameters.initialLoad * plate.loadResultant, moment = s.parameters.initialLoad * plate.loadMoment;
    for (Eigen::Index i = 0; i < contactForce.size(); ++i) {
        force += contactForce[i];
        moment += contactForce[i] * plate.contactAbscissae[static_cast<std::size_t>(i)];
    }
    scheme.setInitialReaction(force, moment);
}

PlateSimulation::~PlateSimulation() = default;

const PlateParameters& PlateSimulation::parameters() const { return impl_->parameters; }
double PlateSimulation::time() const { return impl_->commTime; }
long long PlateSimulation::stepCount() const { return impl_->scheme->stepCount(); }
double PlateSimulation::baseDisplacement() const { return impl_->scheme->baseDisplacement(); }

void PlateSimulation::advance(long long steps, const InputSignal& base, const InputSignal& load) {
    if (!impl_->onGrid) throw StepError("advance() needs a communication time on the grid; use communicate()");
    StepPlan plan;
    plan.steps = steps;
    plan.end = double(impl_->scheme->stepCount() + steps) * impl_->parameters.dt;
    communicate(plan, base, load);
}

StepPlan PlateSimulation::plan(double h) const {
    const Impl& s = *impl_;
    const double dt = s.parameters.dt;
    const long long n = s.scheme->stepCount();
    StepPlan p;
    // On the grid, a whole multiple of Δt (importers' steps wobble in the last digits): the grid
    // steps, the inputs' time s = k Δt exactly as the scheme has always taken them.
    const double ratio = h / dt;
    const long long whole = ratio < 9.0e15 ? std::llround(ratio) : 0;
    if (s.onGrid && whole >= 1 && std::fabs(double(whole) * dt - h) <= kStepMultipleTolerance * h) {
        p.steps = whole;
        p.end = double(n + whole) * dt;
        p.span = double(whole) * dt;
        return p;
    }
    // Any other step: the grid leads the communication time by less than Δt (§15).
    const double snap = std::max(kGridSnap * dt, 4.0 * DBL_EPSILON * (s.commTime + h));
    if (!(h >= snap) || !std::isfinite(h)) {
        std::ostringstream msg;
        msg.precision(17);
        msg << "communicationStepSize h = " << h << " is shorter than the smallest step the grid of dt = " << dt
            << " resolves (allowed: h >= " << snap << " s = 1e-9 dt)";
        throw StepError(msg.str());
    }
    const double end = s.commTime + h;
    const double grid = end / dt;
    long long target = std::llround(grid);
    p.endsOnGrid = std::fabs(double(target) * dt - end) <= snap;
    if (!p.endsOnGrid) target = static_cast<long long>(std::ceil(grid));
    p.steps = std::max(0LL, target - n);
    p.offset = double(n) * dt - s.commTime;
    p.end = p.endsOnGrid ? double(target) * dt : end;
    p.span = p.end - s.commTime;
    return p;
}

// The one loop of a communication step (docs/theory.md §15): the plan's internal steps with
// the inputs at s = offset + k Δt; `stopAfter(k, last)` is asked after each step that ends on a
// grid point (every one but the last of a step that ends between grid points), with the
// simulation standing there (time() and outputs() of that grid point); true ends the
// communication step on that grid point. Returns whether it ended early that way.
template <class StopAfter>
bool PlateSimulation::stepThrough(const StepPlan& plan, const InputSignal& base, const InputSignal& load,
                                  StopAfter&& stopAfter) {
    Impl& s = *impl_;
    const double dt = s.parameters.dt;
    if (!std::isfinite(load.value)) throw StepError("non-finite load input at the step start");
    s.scheme->setLoadAtStart(load.value);
    Armature* carrier = s.scheme->carrier();
    if (carrier) carrier->beginCommunication();
    for (long long k = 1; k <= plan.steps; ++k) {
        // The last step of one that ends between grid points: keep the grid point before it.
        if (k == plan.steps && !plan.endsOnGrid) s.before = gridOutputs(true, FieldOutputs::Plate);
        const double t = plan.offset + k * dt;
        double z = base.at(t), p = load.at(t);
        if (s.sampler) s.sampler(t, z, p);
        s.scheme->step(z, p);
        s.trackRoot();
        if (k == plan.steps && !plan.endsOnGrid) break;
        if (!stopAfter.wanted) continue;
        const double commTime = s.commTime;
        const bool onGrid = s.onGrid;
        s.commTime = double(s.scheme->stepCount()) * dt;
        s.onGrid = true;
        if (stopAfter(k == plan.steps)) return true;  // (a carried clamp never stops early: §18)
        s.commTime = commTime;
        s.onGrid = onGrid;
    }
    if (carrier) carrier->endCommunication(plan.steps);
    s.commTime = plan.end;
    s.onGrid = plan.endsOnGrid;
    return false;
}

namespace {

// stepThrough's stop conditions: none; the contact set changed; and/or an observer's wish.
struct NeverStop {
    static constexpr bool wanted = false;
    bool operator()(bool) const { return false; }
};

template <class Condition>
struct StopWhen {
    static constexpr bool wanted = true;
    Condition condition;
    bool operator()(bool last) { return condition(last); }
};
template <class Condition>
StopWhen<Condition> stopWhen(Condition c) {
    return {std::move(c)};
}

}  // namespace

void PlateSimulation::setInputSampler(InputSampler sampler) { impl_->sampler = std::move(sampler); }

void PlateSimulation::communicate(const StepPlan& plan, const InputSignal& base, const InputSignal& load,
                                  const GridPointObserver& observer) {
    if (!observer) {
        stepThrough(plan, base, load, NeverStop{});
        return;
    }
    stepThrough(plan, base, load, stopWhen([&observer](bool last) {
                    if (!last) observer();
                    return false;
                }));
}

bool PlateSimulation::communicateUntilContactChange(const StepPlan& plan, const InputSignal& base,
                                                    const InputSignal& load, const GridPointObserver& observer) {
    Impl& s = *impl_;
    const double dt = s.parameters.dt;
    if (!std::isfinite(load.value)) throw StepError("non-finite load input at the step start");
    const auto inContact = [&s] { return s.scheme->contactVertices() > 0; };
    // The last step ended between grid points and the grid point ahead changed the contact set:
    // the event is that grid point, if this step reaches it.
    if (!s.onGrid && (s.before.contactVertices > 0) != inContact() && double(s.scheme->stepCount()) * dt <= plan.end) {
        s.commTime = double(s.scheme->stepCount()) * dt;
        s.onGrid = true;
        return true;
    }
    const bool contactBefore = inContact();
    return stepThrough(plan, base, load, stopWhen([&](bool last) {
                           if (inContact() != contactBefore) return true;
                           return !last && observer && observer();
                       }));
}

PlateOutputs PlateSimulation::outputs(bool port, FieldOutputs field) const {
    PlateOutputs o = gridOutputs(port, field);
    if (impl_->onGrid) return o;
    // t_c in (t_{n−1}, t_n): linear interpolation, each ledger term alike so the ledger closes.
    const double dt = impl_->parameters.dt;
    const double theta = (impl_->commTime - double(impl_->scheme->stepCount() - 1) * dt) / dt;
    const PlateOutputs& before = impl_->before;
    for (const OutputField& f : kOutputFields) {
        const double from = f.value(before);
        double& to = f.field(o);
        to = f.between == Between::Interpolated ? from + theta * (to - from) : from;
    }
    return o;
}

PlateOutputs PlateSimulation::gridOutputs(bool port, FieldOutputs field) const {
    const Impl& s = *impl_;
    PlateOutputs o = s.scheme->outputs(port);
    o.rootStressPeak = s.recovery->rootStress(s.rootPeak);  // 0 unless stress_outputs (never tracked)
    if (field != FieldOutputs::None) s.recovery->fill(*s.scheme, s.parameters.dt, o, field == FieldOutputs::Plate);
    return o;
}

std::vector<double> PlateSimulation::vertexStress() const { return impl_->recovery->vertexStress(*impl_->scheme); }

std::vector<double> PlateSimulation::vertexDisplacements() const { return impl_->scheme->vertexDisplacements(); }

const ResourceEstimate& PlateSimulation::resources() const { return impl_->resources; }

CarrierOutputs PlateSimulation::carrierOutputs() const { return impl_->scheme->carrierOutputs(); }

std::string PlateSimulation::engine() const { return impl_->scheme->name(); }

Eigen::Index PlateSimulation::dofCount() const { return impl_->clamped->mass.rows(); }

double PlateSimulation::firstFrequency() const { return impl_->scheme->firstFrequency(); }

double PlateSimulation::kappa() const {
    // Before the engine exists (the β < ¼ check of the constructor) from the clamped plate itself.
    if (!impl_->scheme) return largestEigenvalue(*impl_->clamped);
    return impl_->scheme->kappa();
}

double PlateSimulation::measureFloorSolveSeconds(int repeats) const {
    // The floor is one solve with the sparse factor of A = M + βΔt²K (docs/theory.md), whatever
    // coordinates the stepper runs in.
    const Impl& s = *impl_;
    if (!s.floorFactor)
        s.floorFactor = std::make_unique<SparseCholesky>(Eigen::SparseMatrix<double>(
            s.clamped->mass + (s.parameters.beta * s.parameters.dt * s.parameters.dt) * s.clamped->stiffness));
    const SparseCholesky& factor = *s.floorFactor;
    Eigen::VectorXd b = s.clamped->pressureLoad, x(b.size());
    std::vector<double> batches;
    const int perBatch = std::max(1, repeats / 20);
    for (int batch = 0; batch < 21; ++batch) {
        const auto t0 = std::chrono::steady_clock::now();
        for (int r = 0; r < perBatch; ++r) {
            factor.solve(b, x);
            b[0] += 1e-300 * x[0];  // keep the solves dependent so none is optimized away
        }
        const auto t1 = std::chrono::steady_clock::now();
        if (batch > 0) batches.push_back(std::chrono::duration<double>(t1 - t0).count() / perBatch);
    }
    std::nth_element(batches.begin(), batches.begin() + batches.size() / 2, batches.end());
    return batches[batches.size() / 2];
}

// The scheme's state, then the communication time, whether it is on the grid and the outputs
// at the grid point before it (§15).
std::vector<double> PlateSimulation::saveState() const {
    std::vector<double> out = impl_->scheme->saveState();
    out.push_back(impl_->commTime);
    out.push_back(impl_->onGrid ? 1.0 : 0.0);
    out.push_back(impl_->rootPeak);  // the root's peak |w_xx| since t = 0 (§23)
    for (const OutputField& f : kOutputFields) out.push_back(f.value(impl_->before));
    if (const Armature* carrier = impl_->scheme->carrier()) {  // last (§18)
        for (const auto& f : kCarrierFields) out.push_back(f.value(carrier->state()));
    }
    return out;
}

void PlateSimulation::restoreState(const std::vector<double>& all) {
    std::vector<double> in = all;
    CarrierState carried;
    Armature* carrier = impl_->scheme->carrier();
    if (carrier) {  // the carrier's state last (§18)
        if (in.size() < kCarrierStateSize)
            throw std::invalid_argument("state does not belong to this plate (too short)");
        const double* x = in.data() + in.size() - kCarrierStateSize;
        for (const auto& f : kCarrierFields) {
            if (!std::isfinite(*x))
                throw std::invalid_argument(std::string("corrupt state: non-finite carrier value ") + f.name);
            f.field(carried) = *x++;
        }
        in.resize(in.size() - kCarrierStateSize);
    }
    constexpr std::size_t kTail = 3 + kOutputCount;
    if (in.size() < kTail) throw std::invalid_argument("state does not belong to this plate (too short)");
    const std::size_t head = in.size() - kTail;
    const std::vector<double> engineState(in.begin(), in.begin() + std::ptrdiff_t(head));
    const double* tail = in.data() + head;
    const double dt = impl_->parameters.dt;
    const bool onGrid = tail[1] == 1.0;
    Scheme& engine = *impl_->scheme;
    const std::vector<double> current = engine.saveState();
    engine.restoreState(engineState);  // checks the engine's part (throws, the state unchanged)
    const double gridTime = double(engine.stepCount()) * dt;
    PlateOutputs before;
    const char* corrupt = nullptr;  // the first non-finite output
    for (std::size_t i = 0; i < kOutputCount; ++i) {
        const OutputField& f = kOutputFields[i];
        if (!corrupt && !std::isfinite(tail[3 + i])) corrupt = f.name;
        f.field(before) = tail[3 + i];
    }
    // On the grid the time is the grid point's; between, within one step before it.
    const bool timeFits = (tail[1] == 0.0 || onGrid) && std::isfinite(tail[0]) &&
                          (onGrid ? tail[0] == gridTime : (tail[0] < gridTime && tail[0] > gridTime - dt));
    if (!corrupt && !(tail[2] >= 0.0 && std::isfinite(tail[2]))) corrupt = "the root's peak";
    if (corrupt || !timeFits) {
        engine.restoreState(current);
        throw std::invalid_argument(corrupt ? std::string("corrupt state: non-finite output ") + corrupt
                                            : "corrupt state: communication time does not fit the grid");
    }
    if (carrier) carrier->setState(carried);
    impl_->commTime = tail[0];
    impl_->onGrid = onGrid;
    impl_->before = before;
    impl_->rootPeak = tail[2];
}

}  // namespace plate
