#include "PlateSimulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "Assembly.h"
#include "BoxQP.h"
#include "SparseCholesky.h"
#include "FullOrderPlate.h"
#include "ModalPlate.h"
#include "NewmarkContactStepper.h"
#include "SingularMass.h"
#include "Spectrum.h"
#include "StaticEquilibrium.h"

namespace plate {

namespace {

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
    const auto n = plate.mass.rows();
    const auto m = static_cast<Eigen::Index>(plate.contactDofs.size());
    return n <= 1000 && m * n <= 8 * plate.stiffness.nonZeros();
}

}  // namespace

struct PlateSimulation::Impl {
    PlateParameters parameters;
    std::shared_ptr<const FiniteElementSpace> space;
    std::shared_ptr<const ClampedPlate> clamped;
    std::shared_ptr<const DiscretePlate> discrete;
    mutable std::unique_ptr<SparseCholesky> floorFactor;  // sparse A, for the floor measurement
    std::unique_ptr<NewmarkContactStepper> stepper;
    PointProbe corner1, corner2, freeEdgeMid;
    mutable double kappa = -1.0;
    mutable long long energyStep = -1;
    mutable double energyCache = 0.0;
    double unprojectedEnergy = 0.0;
};

PlateSimulation::PlateSimulation(const PlateParameters& p, double baseDisplacement0, double loadAtStart)
    : impl_(std::make_unique<Impl>()) {
    validate(p);
    const Obstacles obstacles = obstaclesOf(p);
    if (!std::isfinite(baseDisplacement0) || baseDisplacement0 < obstacles.lower ||
        baseDisplacement0 > obstacles.upper) {
        std::ostringstream msg;
        msg.precision(15);  // round-trips what users type (0.7, not 0.69999999999999996)
        msg << "invalid initial state: base_displacement = " << baseDisplacement0
            << " puts the clamped edge outside the obstacles (allowed: obstacle_lower = " << obstacles.lower
            << " <= base_displacement <= obstacle_upper = " << obstacles.upper << ")";
        throw ParameterError(msg.str());
    }
    Impl& s = *impl_;
    s.parameters = p;
    const Mesh mesh(p.length, p.width, p.nx, p.ny);
    s.space = makeSpace(p.element, mesh);
    PlateMatrices matrices = assemble(*s.space, p.surfaceDensity(), p.bendingStiffness(), p.poissonRatio);
    Eigen::SparseMatrix<double> coupling;  // B of the singular mass, all dofs
    if (p.singularMass()) {
        SingularMass singular = assembleSingularMass(
            *s.space, p.surfaceDensity(), p.mass == MassModel::SingularP0 ? MassProjection::P0 : MassProjection::P1dg);
        matrices.mass = std::move(singular.mass);
        coupling = std::move(singular.coupling);
    }
    s.clamped = std::make_shared<const ClampedPlate>(clamp(*s.space, matrices));
    Eigen::SparseMatrix<double> couplingFree;
    if (p.singularMass()) {
        couplingFree = freeRows(coupling, *s.clamped);
        requireMasslessContact(couplingFree, *s.clamped,
                               p.mass == MassModel::SingularP0 ? "singular_p0" : "singular_p1dg");
    }
    if (p.beta < 0.25) {
        // Stability of γ = ½, β < ¼ (docs/theory.md): Δt < 2 / √((1 − 4β) κ_h).
        const double bound = 2.0 / std::sqrt((1.0 - 4.0 * p.beta) * kappa());
        if (!(p.dt < bound)) {
            std::ostringstream msg;
            msg.precision(6);
            msg << "invalid parameter dt = " << p.dt << " for beta = " << p.beta
                << " (allowed: dt < 2/sqrt((1-4 beta) kappa_h) = " << bound << " s, kappa_h = " << kappa()
                << " s^-2; or beta >= 0.25)";
            throw ParameterError(msg.str());
        }
    }
    using Engine = PlateParameters::Engine;
    // A singular mass has no M-orthonormal modal basis: it runs on the sparse factor.
    const bool modal = !p.singularMass() && (p.modes > 0 || p.engine == Engine::CompleteModal ||
                                             (p.engine == Engine::Auto && completeModalPays(*s.clamped)));
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
    options.singularMass = p.singularMass() && p.singularEquilibrium;
    s.stepper = std::make_unique<NewmarkContactStepper>(s.discrete, p.dt, p.beta, obstacles, options);
    Eigen::VectorXd w0;
    const auto* modalPlate = dynamic_cast<const ModalPlate*>(s.discrete.get());
    if (modalPlate && modalPlate->complete()) {
        // Exact mode in modal coordinates: solve the static problem with the sparse factor of
        // K (roundoff ~eps·cond(K) rather than the dense eigen solution's eps·λ_max/λ_1) and
        // change coordinates, α0 = ΦᵀM w0, exact for the complete basis.
        const FullOrderPlate full(s.space, s.clamped, p.dt, p.beta);
        w0 = modalPlate->fromFullSpace(staticEquilibrium(full, obstacles, baseDisplacement0, p.initialLoad));
    } else if (!p.singularMass()) {
        w0 = staticEquilibrium(*s.discrete, obstacles, baseDisplacement0, p.initialLoad);
    }
    if (!p.singularMass()) {
        s.stepper->initialize(w0, baseDisplacement0, 0.0);
        s.unprojectedEnergy = s.stepper->energy();
    } else {
        // §11: only the part of w0 the singular mass sees is initial data; the massless part
        // is in equilibrium with the load at t = 0 (unless the static state already is).
        Eigen::VectorXd force;
        w0 = staticEquilibrium(*s.discrete, obstacles, baseDisplacement0, p.initialLoad, &force);
        s.stepper->initialize(w0, baseDisplacement0, loadAtStart);
        s.unprojectedEnergy = s.stepper->energy();
        if (loadAtStart != p.initialLoad) {
            w0 = masslessEquilibrium(*s.clamped, couplingFree, obstacles, baseDisplacement0, loadAtStart, w0, force);
            s.stepper->initialize(w0, baseDisplacement0, loadAtStart);
        }
        s.stepper->setInitialContactForce(force);
    }
    s.corner1 = s.discrete->probe(p.length, 0.0);
    s.corner2 = s.discrete->probe(p.length, p.width);
    s.freeEdgeMid = s.discrete->probe(p.length, 0.5 * p.width);
}

PlateSimulation::~PlateSimulation() = default;

const PlateParameters& PlateSimulation::parameters() const { return impl_->parameters; }
double PlateSimulation::time() const { return impl_->stepper->state().step * impl_->parameters.dt; }
long long PlateSimulation::stepCount() const { return impl_->stepper->state().step; }
double PlateSimulation::baseDisplacement() const { return impl_->stepper->state().z; }

void PlateSimulation::advance(long long steps, const InputSignal& base, const InputSignal& load) {
    const double dt = impl_->parameters.dt;
    if (!std::isfinite(load.value)) throw StepError("non-finite load input at the step start");
    impl_->stepper->setLoadAtStart(load.value);
    for (long long k = 1; k <= steps; ++k) {
        const double s = k * dt;
        impl_->stepper->step(base.at(s), load.at(s));
    }
}

PlateOutputs PlateSimulation::outputs() const {
    const Impl& s = *impl_;
    const NewmarkState& st = s.stepper->state();
    PlateOutputs o;
    o.corner1 = st.z + s.corner1(st.w);
    o.corner2 = st.z + s.corner2(st.w);
    o.freeEdgeMid = st.z + s.freeEdgeMid(st.w);
    if (s.energyStep != st.step) {
        s.energyCache = s.stepper->energy();
        s.energyStep = st.step;
    }
    o.energy = s.energyCache;
    o.energyDissipated = st.energyDissipated;
    o.energyInput = st.energyInput;
    o.energyDamped = st.energyDamped;
    o.contactVertices = st.contactVertices;
    o.maxKktResidual = st.maxKktResidual;
    o.qpIterations = st.qpIterationsLast;
    o.qpIterationsTotal = st.qpIterationsTotal;
    o.qpIterationsMax = st.qpIterationsMax;
    return o;
}

double PlateSimulation::displacement(double x, double y) const {
    const NewmarkState& st = impl_->stepper->state();
    return st.z + impl_->discrete->probe(x, y)(st.w);
}

std::vector<double> PlateSimulation::vertexDisplacements() const {
    const Impl& s = *impl_;
    const NewmarkState& st = s.stepper->state();
    std::vector<double> u(s.space->mesh().vertexCount(), st.z);
    Eigen::VectorXd y;
    s.discrete->gatherContact(st.w, y);
    for (std::size_t i = 0; i < s.clamped->contactVertices.size(); ++i)
        u[s.clamped->contactVertices[i]] += y[static_cast<Eigen::Index>(i)];
    return u;
}

std::string PlateSimulation::engine() const {
    const auto* modal = dynamic_cast<const ModalPlate*>(impl_->discrete.get());
    if (!modal) return "sparse";
    return modal->complete() ? "modal-complete" : "modal-" + std::to_string(modal->size());
}

Eigen::Index PlateSimulation::dofCount() const { return impl_->clamped->mass.rows(); }

double PlateSimulation::firstFrequency() const {
    const auto* modal = dynamic_cast<const ModalPlate*>(impl_->discrete.get());
    double omega2;
    if (modal) {
        omega2 = modal->omega2()[0];
    } else {
        Eigen::MatrixXd phi;
        Eigen::VectorXd w2;
        lowestModes(*impl_->clamped, 1, phi, w2);
        omega2 = w2[0];
    }
    return std::sqrt(omega2) / (2.0 * M_PI);
}

double PlateSimulation::kappa() const {
    if (impl_->kappa < 0.0) {
        const auto* modal = dynamic_cast<const ModalPlate*>(impl_->discrete.get());
        impl_->kappa = modal && modal->complete() ? modal->omega2().maxCoeff() : largestEigenvalue(*impl_->clamped);
    }
    return impl_->kappa;
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

double PlateSimulation::unprojectedInitialEnergy() const { return impl_->unprojectedEnergy; }

std::vector<double> PlateSimulation::saveState() const { return serialize(impl_->stepper->state()); }

void PlateSimulation::restoreState(const std::vector<double>& in) {
    const NewmarkState& current = impl_->stepper->state();
    impl_->stepper->setState(
        deserialize(in, current.w.size(), current.contactState.size(), current.contactImpulse.size()));
    impl_->energyStep = -1;
}

}  // namespace plate
