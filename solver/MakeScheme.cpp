#include "MakeScheme.h"

#include <array>
#include <cmath>
#include <sstream>

#include "base/Errors.h"
#include "fe/FiniteElementSpace.h"
#include "fe/SingularMass.h"
#include "plate/CondensedPlate.h"
#include "plate/FullOrderPlate.h"
#include "plate/ModalPlate.h"
#include "plate/Spectrum.h"
#include "plate/Stops.h"
#include "plate/StaticEquilibrium.h"
#include "schemes/FieldRecovery.h"
#include "schemes/FlowScheme.h"
#include "schemes/MidpointScheme.h"
#include "schemes/NewmarkScheme.h"

namespace plate {

namespace {

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

// Stability of γ = ½, β < ¼ (docs/theory.md §4): Δt < 2 / √((1 − 4β) κ_h).
void requireStableStep(const SchemeSetup& setup) {
    const PlateParameters& p = setup.parameters;
    const double kappaH = *cached<double>(  // a power iteration: once per plate and process
        kappaKey(p), [&] { return std::make_shared<const double>(largestEigenvalue(*setup.clamped)); },
        [](double) { return sizeof(double); }, setup.cache);
    const double bound = 2.0 / std::sqrt((1.0 - 4.0 * p.law.beta) * kappaH);
    if (!(p.law.dt < bound)) {
        std::ostringstream msg;
        msg.precision(6);
        msg << "invalid parameter dt = " << p.law.dt << " for beta = " << p.law.beta
            << " (allowed: dt < 2/sqrt((1-4 beta) kappa_h) = " << bound << " s, kappa_h = " << kappaH
            << " s^-2; or beta >= 0.25)";
        throw ParameterError(msg.str());
    }
}

// The port at t = 0 (docs/theory.md §14): the plate at rest in the static state of initial_load
// exerts on the clamp what the load and the obstacles put on it, p0·|Ω| + Σλ and p0·∫x + Σλ_i x_i.
void setInitialReaction(const SchemeSetup& s, NewmarkScheme& scheme, const Eigen::VectorXd& contactForce) {
    const ClampedPlate& plate = *s.clamped;
    double force = s.parameters.initialLoad * plate.loadResultant, moment = s.parameters.initialLoad * plate.loadMoment;
    for (Eigen::Index i = 0; i < contactForce.size(); ++i) {
        force += contactForce[i];
        moment += contactForce[i] * plate.contactAbscissae[static_cast<std::size_t>(i)];
    }
    scheme.setInitialReaction(force, moment);
}

// The initial state (docs/theory.md §3, §11): the static equilibrium under initial_load between
// the obstacles, at rest; with a singular mass its massless part in equilibrium with the load at
// t = 0 and the contact forces that hold it.
void initializeState(const SchemeSetup& s, const std::shared_ptr<const DiscretePlate>& discrete,
                     NewmarkScheme& scheme) {
    const PlateParameters& p = s.parameters;
    const Obstacles& obstacles = s.obstacles;
    const double baseDisplacement0 = s.baseDisplacement0, loadAtStart = s.loadAtStart;
    Eigen::VectorXd w0, force;
    const auto* modalPlate = dynamic_cast<const ModalPlate*>(discrete.get());
    if (modalPlate && modalPlate->complete()) {
        // Exact mode in modal coordinates: solve the static problem with the sparse factor of
        // K (roundoff ~eps·cond(K) rather than the dense eigen solution's eps·λ_max/λ_1) and
        // change coordinates, α0 = ΦᵀM w0, exact for the complete basis.
        const FullOrderPlate full(s.space, s.clamped, p.law);
        w0 = modalPlate->fromFullSpace(staticEquilibrium(full, obstacles, baseDisplacement0, p.initialLoad, &force));
    } else if (!p.law.singularMass()) {
        w0 = staticEquilibrium(*discrete, obstacles, baseDisplacement0, p.initialLoad, &force);
    }
    if (!p.law.singularMass()) {
        setInitialReaction(s, scheme, force);
        scheme.initialize(w0, baseDisplacement0, 0.0);
    } else {
        // §11: only the part of w0 the singular mass sees is initial data; the massless part
        // is in equilibrium with the load at t = 0 (unless the static state already is).
        w0 = staticEquilibrium(*discrete, obstacles, baseDisplacement0, p.initialLoad, &force);
        setInitialReaction(s, scheme, force);
        scheme.initialize(w0, baseDisplacement0, loadAtStart);
        if (loadAtStart != p.initialLoad) {
            w0 = masslessEquilibrium(*s.clamped, s.couplingFree, obstacles, baseDisplacement0, loadAtStart, w0, force);
            scheme.initialize(w0, baseDisplacement0, loadAtStart);
        }
        scheme.setInitialContactForce(force);
    }
}

// What the discretization cache charges (DiscretizationCache.h).
std::size_t modalBytes(const ModalBasis& m) {
    return heapBytes(m.phi) + heapBytes(m.omega2) + heapBytes(m.contactModesT) + heapBytes(m.pressureLoad) +
           heapBytes(m.baseInertia) + heapBytes(m.rotationInertia);
}

std::size_t condensedBytes(const CondensedPlate& c) {
    return heapBytes(c.omega2) + heapBytes(c.rowModesT) + heapBytes(c.delassus) + heapBytes(c.rowLoad) +
           heapBytes(c.modalLoad) + heapBytes(c.modalBaseInertia) + heapBytes(c.modalRotationInertia) +
           heapBytes(c.recoveryModes) + heapBytes(c.recoveryRows) + heapBytes(c.recoveryLoad);
}

// time_scheme = conserving and flow (docs/theory.md §17): the output points become constraint rows
// — a corner, or a free_edge_mid on a vertex, is its contact vertex's row; a free_edge_mid between
// vertices (ny odd), or a corner no stop covers (§25), a row of its own, held by the obstacles whose
// stops cover it.
std::shared_ptr<const CondensedPlate> condensedPlate(const SchemeSetup& s, OutputRows& rows) {
    const PlateParameters& p = s.parameters;
    const Mesh& mesh = s.space->mesh();
    const StopMap stops(p.obstacles, p.mesh);
    std::vector<int> vertexRows(static_cast<std::size_t>(mesh.vertexCount()), -1);
    for (std::size_t i = 0; i < s.clamped->contactVertices.size(); ++i)
        vertexRows[static_cast<std::size_t>(s.clamped->contactVertices[i])] = static_cast<int>(i);
    std::vector<ConstraintRow> extra;
    const auto rowOf = [&](const Eigen::Vector2d& x) {
        extra.push_back({s.clamped->probe(*s.space, x.x(), x.y()), x.x(), stops.at(x)});
        return static_cast<int>(s.clamped->contactVertices.size() + extra.size() - 1);
    };
    const auto vertexRow = [&](int v) {  // (rows.vertices stays the contact vertices': FieldRecovery has the rest)
        const int row = vertexRows[static_cast<std::size_t>(v)];
        return row >= 0 ? row : rowOf(mesh.point(v));
    };
    std::array<int, 3> probeRows{vertexRow(mesh.vertex(p.mesh.nx, 0)), vertexRow(mesh.vertex(p.mesh.nx, p.mesh.ny)),
                                 -1};
    probeRows[2] = p.mesh.ny % 2 == 0 ? vertexRow(mesh.vertex(p.mesh.nx, p.mesh.ny / 2))
                                      : rowOf({p.mesh.length, 0.5 * p.mesh.width});
    rows.probes = probeRows;
    rows.vertices = std::move(vertexRows);
    return cached<CondensedPlate>(
        condensedPlateKey(p),
        [&] {
            return std::make_shared<const CondensedPlate>(
                condense(*s.clamped, s.rootFree, extra, p.law.modes, s.recovery.functionals()));
        },
        condensedBytes, s.cache);
}

// time_scheme = newmark: the plate in modal coordinates or on the sparse factor of A, as the
// resource estimate decided (docs/theory.md §7), the scheme with its impact law, and the static
// initial state.
std::unique_ptr<Scheme> makeNewmark(const SchemeSetup& s, InitProgress& progress) {
    const PlateParameters& p = s.parameters;
    if (p.law.beta < 0.25) {
        progress.phase("kappa_h by power iteration with the factor of M", s.resources.spectrumSeconds);
        requireStableStep(s);
    }
    const bool modal =
        s.resources.engine == EngineKind::CompleteModal || s.resources.engine == EngineKind::ReducedModal;
    progress.phase(modal ? "modal basis (generalized eigenproblem)" : "factorization of A = M + beta dt^2 K",
                   modal ? s.resources.spectrumSeconds : 0.5 * s.resources.factorSeconds);
    std::shared_ptr<const DiscretePlate> discrete;
    if (modal) {  // shared between instances: plain data. The sparse factor is not (its solve's workspace).
        const bool complete = s.resources.engine == EngineKind::CompleteModal;
        // A reduced basis the dense solution serves is the leading modes of the plate's complete basis,
        // itself shared (the key of a complete-engine instance's; the cache builds without its lock
        // held): a sweep over `modes`, complete basis included, solves the eigenproblem once.
        const auto basis = [&] {
            if (complete || !denseSolutionServes(s.clamped->mass.rows(), p.law.modes))
                return std::make_shared<const ModalBasis>(*s.clamped, p.law.modes);
            PlateParameters whole = p;
            whole.law.modes = 0;
            const auto all = cached<ModalBasis>(
                modalBasisKey(whole, true), [&] { return std::make_shared<const ModalBasis>(*s.clamped, 0); },
                modalBytes, s.cache);
            return std::make_shared<const ModalBasis>(*s.clamped, p.law.modes, all.get());
        };
        discrete = std::make_shared<const ModalPlate>(
            s.space, s.clamped, cached<ModalBasis>(modalBasisKey(p, complete), basis, modalBytes, s.cache), p.law);
    } else {
        discrete = std::make_shared<const FullOrderPlate>(s.space, s.clamped, p.law);
    }
    SchemeOptions options;
    options.singularMass = p.law.singularMass();  // carry the impulses (§11; the tests of the plain
        // step build their NewmarkScheme directly)
    options.carried = p.carrier != PlateParameters::Carrier::None;  // §18–19
    if (options.carried) options.carrier = carrierOptions(p, s.baseDisplacement0);
    auto scheme = std::make_unique<NewmarkScheme>(
        discrete, s.obstacles, options, OutputPoints{p.mesh.length, p.mesh.width, s.space->mesh().vertexCount()});
    scheme->setRecovery(discrete->rows(s.recovery.functionals()));
    progress.phase("static initial state (factor of K)", s.resources.staticSeconds + 0.5 * s.resources.factorSeconds);
    initializeState(s, discrete, *scheme);
    return scheme;
}

}  // namespace

std::unique_ptr<Scheme> makeScheme(const SchemeSetup& setup, InitProgress& progress) {
    const PlateParameters& p = setup.parameters;
    if (p.law.timeScheme == TimeScheme::Newmark) return makeNewmark(setup, progress);
    progress.phase("condensed singular plate (massive modes, massless Delassus operator)",
                   setup.resources.spectrumSeconds + setup.resources.factorSeconds);
    OutputRows rows;
    auto condensed = condensedPlate(setup, rows);
    std::unique_ptr<CondensedScheme> scheme;
    if (p.law.timeScheme == TimeScheme::Flow)
        scheme = std::make_unique<FlowScheme>(condensed, setup.obstacles, p.law, p.refinement, std::move(rows));
    else
        scheme = std::make_unique<MidpointScheme>(condensed, setup.obstacles, p.law, std::move(rows));
    scheme->initialize(setup.baseDisplacement0, p.initialLoad);
    scheme->setLoadAtStart(setup.loadAtStart);
    return scheme;
}

}  // namespace plate
