#include "PlateSimulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "Assembly.h"
#include "BoxQP.h"
#include "CholmodFactor.h"
#include "FullOrderPlate.h"
#include "ModalPlate.h"
#include "NewmarkContactStepper.h"

namespace plate {

namespace {

// Largest eigenvalue of M⁻¹K by power iteration with the Rayleigh quotient. The top of the FE
// spectrum is clustered, so the quotient is within a fraction of a percent after a few hundred
// iterations even where the eigenvector converges slowly.
double largestEigenvalue(const ClampedPlate& plate) {
    const CholmodFactor massFactor(plate.mass);
    Eigen::VectorXd x = Eigen::VectorXd::Ones(plate.mass.rows());
    for (Eigen::Index i = 0; i < x.size(); ++i) x[i] += 0.37 * std::sin(1.0 + 7.0 * i);
    Eigen::VectorXd kx, y, mx;
    double lambda = 0.0;
    for (int it = 0; it < 2000; ++it) {
        kx = plate.stiffness * x;
        massFactor.solve(kx, y);
        mx = plate.mass * y;
        const double next = y.dot(plate.stiffness * y) / y.dot(mx);
        x = y / std::sqrt(y.dot(mx));
        if (it > 50 && std::abs(next - lambda) <= 1e-7 * next) {
            lambda = next;
            break;
        }
        lambda = next;
    }
    return lambda;
}

Obstacles obstaclesOf(const PlateParameters& p) {
    Obstacles o;
    if (p.obstacleLowerEnabled) o.lower = p.obstacleLower;
    if (p.obstacleUpperEnabled) o.upper = p.obstacleUpper;
    return o;
}

// Static equilibrium K w = p0 F between the obstacles (the initial state of §5.2), with the
// clamp at z0: the same contact-space QP as a time step, with S = K, in the plate's own
// coordinates.
Eigen::VectorXd staticEquilibrium(const DiscretePlate& plate, const Obstacles& obstacles,
                                  double z0, double p0) {
    const DiscretePlate::Solver solveK = plate.stiffnessSolver();
    Eigen::VectorXd w;
    solveK(Eigen::VectorXd(p0 * plate.pressureLoad()), w);
    if (!obstacles.any()) return w;
    const int m = plate.contactCount();
    ContactColumns columns(
        m,
        [&](int j, Eigen::VectorXd& z) {
            Eigen::VectorXd c;
            plate.contactDirection(j, c);
            solveK(c, z);
        },
        [&plate](const Eigen::VectorXd& z, Eigen::VectorXd& y) { plate.gatherContact(z, y); });
    Eigen::VectorXd yFree, y, mu = Eigen::VectorXd::Zero(m);
    plate.gatherContact(w, yFree);
    const Eigen::VectorXd lower = Eigen::VectorXd::Constant(m, obstacles.lower - z0);
    const Eigen::VectorXd upper = Eigen::VectorXd::Constant(m, obstacles.upper - z0);
    std::vector<signed char> state(m, 0);
    BoxQP qp(columns);
    const QPResult r = qp.solve(yFree, lower, upper, state, mu, y);
    if (!r.converged || !(r.kktResidual <= 1e-10)) {
        std::ostringstream msg;
        msg << "invalid parameter initial_load = " << p0
            << ": the static contact problem for the initial state did not converge (relative KKT "
            << r.kktResidual << ")";
        throw ParameterError(msg.str());
    }
    for (int i : qp.active()) w.noalias() += mu[i] * columns.column(i);
    return w;
}

// Exact mode (modes = 0) runs the complete modal basis where it is cheaper per step than the
// sparse factor of A (both are the same scheme (3.6) in other coordinates). A modal step costs
// about one pass over the dense contact operator CΦ (contact vertices x dofs); a sparse step
// a solve and a product K w, several indexed passes over about nnz(K) entries each, at ~5
// instructions per entry against ~1 per entry of the vectorized dense pass (callgrind).
// Measured with plate_bench: Argyris 14x5 (CΦ 62k, nnz(K) 30k) modal 10 µs against sparse
// 45 µs per step; FVS 14x5 modal 5 µs against sparse 12 µs; FVS 20x7 (CΦ 77k, nnz(K) 12k)
// modal 19 µs against sparse 28 µs; FVS 28x10 (CΦ 259k) even at 60 µs. The O(n³) eigen solution at start stays near a second up to ~1000
// dofs.
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
    mutable std::unique_ptr<CholmodFactor> floorFactor;  // sparse A, for the floor measurement
    std::unique_ptr<NewmarkContactStepper> stepper;
    PointProbe corner1, corner2, freeEdgeMid;
    mutable double kappa = -1.0;
    mutable long long energyStep = -1;
    mutable double energyCache = 0.0;
};

PlateSimulation::PlateSimulation(const PlateParameters& p, double baseDisplacement0)
    : impl_(std::make_unique<Impl>()) {
    validate(p);
    const Obstacles obstacles = obstaclesOf(p);
    if (!std::isfinite(baseDisplacement0) || baseDisplacement0 < obstacles.lower ||
        baseDisplacement0 > obstacles.upper) {
        std::ostringstream msg;
        msg.precision(15);  // round-trips what users type (0.7, not 0.69999999999999996)
        msg << "invalid initial state: base_displacement = " << baseDisplacement0
            << " puts the clamped edge outside the obstacles (allowed: obstacle_lower = "
            << obstacles.lower << " <= base_displacement <= obstacle_upper = " << obstacles.upper
            << ")";
        throw ParameterError(msg.str());
    }
    Impl& s = *impl_;
    s.parameters = p;
    const Mesh mesh(p.length, p.width, p.nx, p.ny);
    s.space = makeSpace(p.element, mesh);
    const PlateMatrices matrices =
        assemble(*s.space, p.surfaceDensity(), p.bendingStiffness(), p.poissonRatio);
    s.clamped = std::make_shared<const ClampedPlate>(clamp(*s.space, matrices));
    if (p.beta < 0.25) {
        // Stability of γ = ½, β < ¼ (NOTES.md): Δt < 2 / √((1 − 4β) κ_h).
        const double bound = 2.0 / std::sqrt((1.0 - 4.0 * p.beta) * kappa());
        if (!(p.dt < bound)) {
            std::ostringstream msg;
            msg.precision(6);
            msg << "invalid parameter dt = " << p.dt << " for beta = " << p.beta
                << " (allowed: dt < 2/sqrt((1-4 beta) kappa_h) = " << bound
                << " s, kappa_h = " << kappa() << " s^-2; or beta >= 0.25)";
            throw ParameterError(msg.str());
        }
    }
    using Engine = PlateParameters::Engine;
    const bool modal = p.modes > 0 || p.engine == Engine::CompleteModal ||
                       (p.engine == Engine::Auto && completeModalPays(*s.clamped));
    if (modal)
        s.discrete = std::make_shared<const ModalPlate>(s.space, s.clamped, p.dt, p.beta, p.modes);
    else
        s.discrete = std::make_shared<const FullOrderPlate>(s.space, s.clamped, p.dt, p.beta);
    s.stepper = std::make_unique<NewmarkContactStepper>(s.discrete, p.dt, p.beta, obstacles);
    Eigen::VectorXd w0;
    const auto* modalPlate = dynamic_cast<const ModalPlate*>(s.discrete.get());
    if (modalPlate && modalPlate->complete()) {
        // Exact mode in modal coordinates: solve the static problem with the sparse factor of
        // K (roundoff ~eps·cond(K) rather than the dense eigen solution's eps·λ_max/λ_1) and
        // change coordinates, α0 = ΦᵀM w0, exact for the complete basis.
        const FullOrderPlate full(s.space, s.clamped, p.dt, p.beta);
        w0 = modalPlate->fromFullSpace(
            staticEquilibrium(full, obstacles, baseDisplacement0, p.initialLoad));
    } else {
        w0 = staticEquilibrium(*s.discrete, obstacles, baseDisplacement0, p.initialLoad);
    }
    s.stepper->initialize(w0, baseDisplacement0, 0.0);
    s.corner1 = s.discrete->probe(p.length, 0.0);
    s.corner2 = s.discrete->probe(p.length, p.width);
    s.freeEdgeMid = s.discrete->probe(p.length, 0.5 * p.width);
}

PlateSimulation::~PlateSimulation() = default;

const PlateParameters& PlateSimulation::parameters() const { return impl_->parameters; }
double PlateSimulation::time() const { return impl_->stepper->state().step * impl_->parameters.dt; }
long long PlateSimulation::stepCount() const { return impl_->stepper->state().step; }

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
        impl_->kappa = modal && modal->complete() ? modal->omega2().maxCoeff()
                                                  : largestEigenvalue(*impl_->clamped);
    }
    return impl_->kappa;
}

double PlateSimulation::measureFloorSolveSeconds(int repeats) const {
    // The floor is one solve with the sparse factor of A = M + βΔt²K (NOTES.md), whatever
    // coordinates the stepper runs in.
    const Impl& s = *impl_;
    if (!s.floorFactor)
        s.floorFactor = std::make_unique<CholmodFactor>(Eigen::SparseMatrix<double>(
            s.clamped->mass + (s.parameters.beta * s.parameters.dt * s.parameters.dt) *
                                  s.clamped->stiffness));
    const CholmodFactor& factor = *s.floorFactor;
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

std::vector<double> PlateSimulation::saveState() const {
    const NewmarkState& s = impl_->stepper->state();
    const auto n = s.w.size();
    std::vector<double> out;
    out.reserve(4 * n + s.contactState.size() + 32);
    out.push_back(1.0);  // format version
    out.push_back(static_cast<double>(n));
    out.push_back(static_cast<double>(s.contactState.size()));
    for (const Eigen::VectorXd* v : {&s.w, &s.wPrev, &s.kw, &s.kwPrev})
        out.insert(out.end(), v->data(), v->data() + n);
    for (double x : {s.z, s.zPrev, s.p, s.pPrev, s.s, s.sPrev, s.t, s.tPrev,
                     static_cast<double>(s.step), s.energyInput, s.energyDissipated,
                     s.maxKktResidual, static_cast<double>(s.qpIterationsTotal),
                     static_cast<double>(s.qpIterationsMax),
                     static_cast<double>(s.qpIterationsLast),
                     static_cast<double>(s.contactVertices)})
        out.push_back(x);
    for (signed char c : s.contactState) out.push_back(c);
    return out;
}

void PlateSimulation::restoreState(const std::vector<double>& in) {
    const NewmarkState& current = impl_->stepper->state();
    const auto n = current.w.size();
    const auto m = current.contactState.size();
    if (in.size() != 3 + 4 * static_cast<std::size_t>(n) + 16 + m || in[0] != 1.0 ||
        in[1] != static_cast<double>(n) || in[2] != static_cast<double>(m))
        throw std::invalid_argument("state does not belong to this plate (size or format differs)");
    NewmarkState s;
    std::size_t k = 3;
    for (Eigen::VectorXd* v : {&s.w, &s.wPrev, &s.kw, &s.kwPrev}) {
        *v = Eigen::Map<const Eigen::VectorXd>(in.data() + k, n);
        k += n;
    }
    s.z = in[k++]; s.zPrev = in[k++]; s.p = in[k++]; s.pPrev = in[k++];
    s.s = in[k++]; s.sPrev = in[k++]; s.t = in[k++]; s.tPrev = in[k++];
    s.step = static_cast<long long>(in[k++]);
    s.energyInput = in[k++]; s.energyDissipated = in[k++]; s.maxKktResidual = in[k++];
    s.qpIterationsTotal = static_cast<long long>(in[k++]);
    s.qpIterationsMax = static_cast<int>(in[k++]);
    s.qpIterationsLast = static_cast<int>(in[k++]);
    s.contactVertices = static_cast<int>(in[k++]);
    s.contactState.resize(m);
    for (std::size_t i = 0; i < m; ++i) {
        const double c = in[k++];
        if (c != -1.0 && c != 0.0 && c != 1.0) throw std::invalid_argument("corrupt contact state");
        s.contactState[i] = static_cast<signed char>(c);
    }
    for (const Eigen::VectorXd* v : {&s.w, &s.wPrev, &s.kw, &s.kwPrev})
        if (!v->allFinite()) throw std::invalid_argument("corrupt state: non-finite displacement");
    impl_->stepper->setState(s);
    impl_->energyStep = -1;
}

}  // namespace plate
