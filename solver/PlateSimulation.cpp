#include "PlateSimulation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "schemes/ImpactEpisodes.h"
#include "MakeScheme.h"
#include "base/StateArchive.h"
#include "base/PortableMath.h"
#include "fe/Assembly.h"
#include "fe/SingularMass.h"
#include "plate/DiscretizationCache.h"
#include "plate/Stops.h"
#include "schemes/Armature.h"
#include "schemes/FieldRecovery.h"
#include "schemes/Scheme.h"

namespace plate {

namespace {

// What every scheme starts from (one entry of the discretization cache, DiscretizationCache.h):
// the space, the clamped M and K, and the singular mass's B and R on the free rows (empty with the
// consistent mass).
struct ClampedDiscretization {
    std::shared_ptr<const FiniteElementSpace> space;
    std::shared_ptr<const ClampedPlate> clamped;
    Eigen::SparseMatrix<double> couplingFree, rootFree;
    std::size_t bytes() const {
        const ClampedPlate& c = *clamped;
        return heapBytes(c.mass) + heapBytes(c.stiffness) + heapBytes(couplingFree) + heapBytes(rootFree) +
               heapBytes(c.pressureLoad) + heapBytes(c.baseInertia) + heapBytes(c.rotationInertia) +
               sizeof(Eigen::Index) * (c.freeDofs.size() + 2 * c.contactDofs.size()) + c.contactStops.size();
    }
};

ClampedDiscretization clampedDiscretization(const PlateParameters& p, std::shared_ptr<const FiniteElementSpace> space) {
    ClampedDiscretization d;
    d.space = std::move(space);
    PlateMatrices matrices = assemble(*d.space, p.material);
    Eigen::SparseMatrix<double> coupling, root;  // B and R of the singular mass, all dofs
    if (p.law.singularMass()) {
        SingularMass singular =
            assembleSingularMass(*d.space, p.material.surfaceDensity(),
                                 p.law.mass == MassModel::SingularP0 ? MassProjection::P0 : MassProjection::P1dg);
        matrices.mass = std::move(singular.mass);
        matrices.massMoment = std::move(singular.massMoment);
        coupling = std::move(singular.coupling);
        root = std::move(singular.root);
    }
    const StopMap stops(p.obstacles, p.mesh);  // only the vertices under a stop are contact rows (docs/theory.md §25)
    d.clamped = std::make_shared<const ClampedPlate>(
        clamp(*d.space, matrices, [&stops](const Eigen::Vector2d& x) { return stops.at(x); }));
    if (p.law.singularMass()) {
        d.couplingFree = freeRows(coupling, *d.clamped);
        requireMasslessContact(d.couplingFree, *d.clamped,
                               p.law.mass == MassModel::SingularP0 ? "singular_p0" : "singular_p1dg");
        d.rootFree = freeRows(root, *d.clamped);
    }
    return d;
}

std::size_t spaceBytes(const FiniteElementSpace& space) {
    std::size_t bytes = 0;
    for (int e = 0; e < space.elementCount(); ++e) bytes += 256 + sizeof(Eigen::Index) * space.elementDofs(e).size();
    return bytes;
}

std::string describe(const CacheUse& cache) {
    std::ostringstream line;
    line << "discretization: " << cache.shared << " of " << cache.shared + cache.built
         << " parts shared from the process's cache, " << cache.built
         << " built (PLATEIMPACT_CACHE_MB sets its budget, 0 turns it off)";
    return line.str();
}

}  // namespace

struct PlateSimulation::Impl {
    PlateParameters parameters;
    std::shared_ptr<const FiniteElementSpace> space;
    std::shared_ptr<const ClampedPlate> clamped;
    std::unique_ptr<Scheme> scheme;
    // Stress and probes (docs/theory.md §23): the functionals, and the peak since t = 0 of the root's
    // largest |w_xx|, tracked every step (part of the state).
    std::unique_ptr<FieldRecovery> recovery;
    double rootPeak = 0.0;
    ImpactEpisodes episodes;  // per obstacle (docs/theory.md §14), counted every step (part of the state)
    // Only with stress_outputs: off, the peak stays 0 and the step costs nothing more.
    void trackRoot() {
        if (parameters.outputs.stressOutputs) rootPeak = std::max(rootPeak, recovery->rootCurvature(*scheme));
    }
    // Between grid points (docs/theory.md §15): the communication time, and the outputs at the
    // grid point before it (the one after it is the scheme's state).
    double commTime = 0.0;
    bool onGrid = true;
    PlateOutputs before;
    ProbeOutputs probesBefore;
    // Where t_c lies between t_{n−1} and t_n, as a fraction of Δt (the interpolation's weight).
    double theta() const {
        return (commTime - double(scheme->stepCount() - 1) * parameters.law.dt) / parameters.law.dt;
    }
    ResourceEstimate resources;  // made before the assembly
    InputSampler sampler;  // setInputSampler
};

PlateSimulation::PlateSimulation(const PlateParameters& p, double baseDisplacement0, double loadAtStart,
                                 const ProgressLog& log)
    : impl_(std::make_unique<Impl>()) {
    portable::fixDenseBlocking();  // the same bits on every CPU (docs/theory.md §20)
    validate(p);
    const Obstacles obstacles = obstaclesOf(p.obstacles);
    requireStartBetween(obstacles, baseDisplacement0);
    Impl& s = *impl_;
    s.parameters = p;
    requireMeshWithinBudget(p);  // far beyond memory_limit: refused before the space is built
    CacheUse cache;
    const auto space = cached<FiniteElementSpace>(
        spaceKey(p), [&] { return std::shared_ptr<const FiniteElementSpace>(makeSpace(p.mesh)); }, spaceBytes, cache);
    s.resources = planResources(p, *space, log);  // refuses beyond memory_limit
    InitProgress progress(log, s.resources.initSeconds);
    progress.phase("assembly of M and K", s.resources.assemblySeconds);
    const auto plate = cached<ClampedDiscretization>(
        clampedPlateKey(p),
        [&] { return std::make_shared<const ClampedDiscretization>(clampedDiscretization(p, space)); },
        [](const ClampedDiscretization& d) { return d.bytes(); }, cache);
    s.space = plate->space;
    s.clamped = plate->clamped;
    s.recovery = std::make_unique<FieldRecovery>(*s.space, *s.clamped, p);
    s.probesBefore.resize(s.recovery->probeCount());
    s.scheme = makeScheme(SchemeSetup{p, s.space, s.clamped, *s.recovery, s.resources, plate->couplingFree,
                                      plate->rootFree, obstacles, baseDisplacement0, loadAtStart, cache},
                          progress);
    if (log) log(describe(cache));
    s.trackRoot();  // the initial state's (t = 0 belongs to the peak)
    s.episodes = ImpactEpisodes(p.firstFrequencyEstimate(), p.law.dt);
    progress.done(s.resources.peakMB);
}

PlateSimulation::~PlateSimulation() = default;

const PlateParameters& PlateSimulation::parameters() const { return impl_->parameters; }
double PlateSimulation::time() const { return impl_->commTime; }
long long PlateSimulation::stepCount() const { return impl_->scheme->stepCount(); }

void PlateSimulation::advance(long long steps, const InputSignal& base, const InputSignal& load) {
    if (!impl_->onGrid) throw StepError("advance() needs a communication time on the grid; use communicate()");
    StepPlan plan;
    plan.steps = steps;
    plan.end = double(impl_->scheme->stepCount() + steps) * impl_->parameters.law.dt;
    communicate(plan, base, load);
}

StepPlan PlateSimulation::plan(double h) const {
    const Impl& s = *impl_;
    return planStep(h, s.parameters.law.dt, s.scheme->stepCount(), s.commTime, s.onGrid);
}

// The one loop of a communication step (docs/theory.md §15): the plan's internal steps with
// the inputs at s = offset + k Δt; `stopAfter(last)` is asked after each step that ends on a
// grid point (every one but the last of a step that ends between grid points), with the
// simulation standing there (time() and outputs() of that grid point); true ends the
// communication step on that grid point. Returns whether it ended early that way.
template <class StopAfter>
bool PlateSimulation::stepThrough(const StepPlan& plan, const InputSignal& base, const InputSignal& load,
                                  StopAfter&& stopAfter) {
    Impl& s = *impl_;
    const double dt = s.parameters.law.dt;
    if (!std::isfinite(load.value)) throw StepError("non-finite load input at the step start");
    s.scheme->setLoadAtStart(load.value);
    Armature* carrier = s.scheme->carrier();
    if (carrier) carrier->beginCommunication();
    for (long long k = 1; k <= plan.steps; ++k) {
        // The last step of one that ends between grid points: keep the grid point before it.
        if (k == plan.steps && !plan.endsOnGrid) {
            s.before = gridOutputs(true, FieldOutputs::Plate);
            s.recovery->fillProbes(*s.scheme, dt, s.probesBefore);  // sized at construction: no allocation
        }
        const double t = plan.offset + k * dt;
        double z = base.at(t), p = load.at(t);
        if (s.sampler) s.sampler(t, z, p);
        s.scheme->step(z, p);
        s.trackRoot();
        s.episodes.count(*s.scheme);
        if (k == plan.steps && !plan.endsOnGrid) break;
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

void PlateSimulation::setInputSampler(InputSampler sampler) { impl_->sampler = std::move(sampler); }

void PlateSimulation::communicate(const StepPlan& plan, const InputSignal& base, const InputSignal& load,
                                  const GridPointObserver& observer) {
    stepThrough(plan, base, load, [&observer](bool last) {
        if (!last && observer) observer();
        return false;
    });
}

bool PlateSimulation::communicateUntilContactChange(const StepPlan& plan, const InputSignal& base,
                                                    const InputSignal& load, const GridPointObserver& observer) {
    Impl& s = *impl_;
    const double dt = s.parameters.law.dt;
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
    return stepThrough(plan, base, load, [&](bool last) {
        if (inContact() != contactBefore) return true;
        return !last && observer && observer();
    });
}

PlateOutputs PlateSimulation::outputs(bool port, FieldOutputs field) const {
    PlateOutputs o = gridOutputs(port, field);
    if (impl_->onGrid) return o;
    // t_c in (t_{n−1}, t_n): linear interpolation, each ledger term alike so the ledger closes.
    const double theta = impl_->theta();
    const PlateOutputs& before = impl_->before;
    for (const OutputField& f : kOutputFields) {
        const double from = f.value(before);
        double& to = f.field(o);
        to = f.between == Between::Interpolated ? from + theta * (to - from) : from;
    }
    return o;
}

ProbeOutputs PlateSimulation::probes() const {
    const Impl& s = *impl_;
    ProbeOutputs o;
    s.recovery->fillProbes(*s.scheme, s.parameters.law.dt, o);
    if (s.onGrid) return o;
    // Between grid points as outputs(): the linear interpolation of the two neighbours.
    const double theta = s.theta();
    const ProbeOutputs& before = s.probesBefore;
    o.displacement = before.displacement + theta * (o.displacement - before.displacement);
    o.velocity = before.velocity + theta * (o.velocity - before.velocity);
    o.acceleration = before.acceleration + theta * (o.acceleration - before.acceleration);
    return o;
}

PlateOutputs PlateSimulation::gridOutputs(bool port, FieldOutputs field) const {
    const Impl& s = *impl_;
    PlateOutputs o = s.scheme->outputs(port);
    o.rootStressPeak = s.recovery->rootStress(s.rootPeak);  // 0 unless stress_outputs (never tracked)
    o.impacts[0] = double(s.episodes.episodes[0]);
    o.impacts[1] = double(s.episodes.episodes[1]);
    if (field != FieldOutputs::None) s.recovery->fill(*s.scheme, o, field == FieldOutputs::Plate);
    return o;
}

std::vector<double> PlateSimulation::vertexStress() const { return impl_->recovery->vertexStress(*impl_->scheme); }

std::vector<double> PlateSimulation::vertexDisplacements() const {
    std::vector<double> heights = impl_->scheme->vertexDisplacements();
    impl_->recovery->addFreeVertices(*impl_->scheme, heights);  // the vertices off every stop (§25)
    return heights;
}

const ResourceEstimate& PlateSimulation::resources() const { return impl_->resources; }
CarrierOutputs PlateSimulation::carrierOutputs() const { return impl_->scheme->carrierOutputs(); }
ToleranceHorizon PlateSimulation::toleranceHorizon() const { return impl_->scheme->toleranceHorizon(); }

std::string PlateSimulation::engine() const { return impl_->scheme->name(); }
Eigen::Index PlateSimulation::dofCount() const { return impl_->clamped->mass.rows(); }
double PlateSimulation::firstFrequency() const { return impl_->scheme->firstFrequency(); }
double PlateSimulation::kappa() const { return impl_->scheme->kappa(); }

namespace {

// The grid's part of the flat form, after the scheme's (base/StateArchive.h): the communication
// time, whether it is on the grid, the root's peak |w_xx| since t = 0 (§23) and the outputs and the
// probes at the grid point before the communication time (§15), measured in the probes' count.
// Format 2: the probes became any number (format 1 had four fixed among the outputs), and the
// impact episodes (§14) were added. Format 3: discretization_error joined the outputs; 4: the check's part carries the points' range (§26).
struct GridState {
    double commTime = 0.0;
    int onGrid = 1;
    double rootPeak = 0.0;
    PlateOutputs before;
    ProbeOutputs probesBefore;
    long long freeSteps[2] = {0, 0};  // ImpactEpisodes::freeSteps + 1 (a count: 0 is never touched)
    long long episodes[2] = {0, 0};
};
constexpr double kGridFormat = 4.0;  // 3: discretizationError among the outputs; 4: the check's range (§26)
const auto gridMembers = [](auto& g, auto& v) {
    v.real(g.commTime, "communication time");
    v.count(g.onGrid, "on the grid", 1.0);
    v.real(g.rootPeak, "the root's peak");
    for (const OutputField& f : kOutputFields) v.real(f.field(const_cast<PlateOutputs&>(g.before)), f.name);
    v.vector(g.probesBefore.displacement, 0, "the probes' displacement");
    v.vector(g.probesBefore.velocity, 0, "the probes' velocity");
    v.vector(g.probesBefore.acceleration, 0, "the probes' acceleration");
    // The impact episodes (§14): steps since each obstacle was last touched, and the counts.
    for (int k = 0; k < 2; ++k) {
        v.count(g.freeSteps[k], "steps free of an obstacle");
        v.count(g.episodes[k], "impact episodes");
    }
};

}  // namespace

// The scheme's state, then the grid's (GridState), then the carrier's fields (§18); CheckedPlate
// adds the discretization check's part (§26; a carried clamp refuses the check: never both).
std::vector<double> PlateSimulation::saveState() const {
    const Impl& s = *impl_;
    std::vector<double> out = s.scheme->saveState();
    const std::array<std::size_t, 1> sizes{std::size_t(s.recovery->probeCount())};
    GridState state{s.commTime, s.onGrid ? 1 : 0, s.rootPeak, s.before, s.probesBefore, {}, {}};
    for (int k = 0; k < 2; ++k) {
        state.freeSteps[k] = s.episodes.freeSteps[k] + 1;
        state.episodes[k] = s.episodes.episodes[k];
    }
    const std::vector<double> grid = archive::save(state, kGridFormat, sizes, gridMembers);
    out.insert(out.end(), grid.begin(), grid.end());
    if (const Armature* carrier = s.scheme->carrier()) {  // last (§18)
        for (const auto& f : kCarrierFields) out.push_back(f.value(carrier->state()));
    }
    return out;
}

void PlateSimulation::restoreState(const std::vector<double>& all) {
    Impl& s = *impl_;
    std::vector<double> in = all;
    CarrierState carried;
    Armature* carrier = s.scheme->carrier();
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
    const std::array<std::size_t, 1> sizes{std::size_t(s.recovery->probeCount())};
    const std::size_t gridLength = archive::length<GridState>(sizes, gridMembers);
    if (in.size() < gridLength) throw std::invalid_argument("state does not belong to this plate (too short)");
    const auto split = in.end() - std::ptrdiff_t(gridLength);
    const GridState grid = archive::load<GridState>(std::vector<double>(split, in.end()), kGridFormat, sizes,
                                                    gridMembers);  // throws: nothing set
    if (!(grid.rootPeak >= 0.0)) throw std::invalid_argument("corrupt state: the root's peak is negative");
    Scheme& scheme = *s.scheme;
    const std::vector<double> current = scheme.saveState();
    scheme.restoreState(std::vector<double>(in.begin(), split));  // throws, the state unchanged
    // On the grid the time is the grid point's; between, within one step before it.
    const double dt = s.parameters.law.dt, gridTime = double(scheme.stepCount()) * dt;
    const bool onGrid = grid.onGrid == 1;
    if (!(onGrid ? grid.commTime == gridTime : (grid.commTime < gridTime && grid.commTime > gridTime - dt))) {
        scheme.restoreState(current);
        throw std::invalid_argument("corrupt state: communication time does not fit the grid");
    }
    if (carrier) carrier->setState(carried);
    s.commTime = grid.commTime;
    s.onGrid = onGrid;
    s.before = grid.before;
    s.probesBefore = grid.probesBefore;
    for (int k = 0; k < 2; ++k) {
        s.episodes.freeSteps[k] = grid.freeSteps[k] - 1;
        s.episodes.episodes[k] = grid.episodes[k];
        s.episodes.onsetsSeen[k] = scheme.contactOnsets(k);  // counted up to the state's step
    }
    s.rootPeak = grid.rootPeak;
}

}  // namespace plate
