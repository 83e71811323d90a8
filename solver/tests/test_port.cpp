// The clamp's force and moment (docs/theory.md §14) against an independent computation: the
// residual of the clamped rows of the full-space step, summed against the rigid motions 1 and X.
// The port formula (T.14) uses only the free rows' quantities and K·1 = K·X = 0; this test
// assembles the clamped rows themselves, so it checks that identity — the discrete momentum and
// moment balance of the scheme — through impacts, to roundoff.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <cmath>
#include <memory>

#include "fe/Assembly.h"
#include "plate/FullOrderPlate.h"
#include "schemes/NewmarkScheme.h"
#include "plate/PlateParameters.h"

using namespace plate;

namespace {

Eigen::VectorXd fullField(const ClampedPlate& c, const Eigen::VectorXd& constant, const Eigen::VectorXd& w, double z) {
    Eigen::VectorXd u = z * constant;
    for (std::size_t k = 0; k < c.freeDofs.size(); ++k) u[c.freeDofs[k]] += w[static_cast<Eigen::Index>(k)];
    return u;
}

}  // namespace

TEST(Port, ClampForceAndMomentAreTheClampedRowsResidual) {
    PlateParameters p;
    p.mesh.nx = 7;
    p.mesh.ny = 3;
    const auto space = std::shared_ptr<const FiniteElementSpace>(
        makeSpace(ElementType::Argyris, Mesh(p.mesh.length, p.mesh.width, p.mesh.nx, p.mesh.ny)));
    const PlateMatrices full = assemble(*space, p.material);
    const auto clamped = std::make_shared<const ClampedPlate>(clamp(*space, full));
    // X, the dof vector of the function x: its Galerkin projection is exact (x is in the space).
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> massFactor(full.mass);
    const Eigen::VectorXd rotation = massFactor.solve(full.massMoment);
    // K·X = 0 up to the roundoff of the mass solve (cond(M) eps ‖K‖ ‖X‖).
    ASSERT_LE((full.stiffness * rotation).norm(), 1e-9 * full.stiffness.norm() * rotation.norm());
    std::vector<bool> isClamped(full.constant.size(), true);
    for (auto d : clamped->freeDofs) isClamped[d] = false;

    const double dt = 1e-4, beta = 0.5;
    Obstacles obstacles;
    obstacles.lower = -0.02;
    obstacles.upper = 0.02;
    LawParameters law;
    law.dt = dt;
    law.beta = beta;
    auto plate = std::make_shared<const FullOrderPlate>(space, clamped, law);
    NewmarkScheme stepper(plate, obstacles);
    stepper.initialize(Eigen::VectorXd::Zero(plate->size()), 0.0, 0.0);
    Eigen::VectorXd uPrev = fullField(*clamped, full.constant, stepper.state().w, 0.0), u = uPrev;
    double worstForce = 0.0, worstMoment = 0.0, largestForce = 0.0;
    long long impacts = 0;
    for (int n = 0; n < 3000; ++n) {
        const double zNext = 0.015 * std::sin(2.0 * M_PI * 30.0 * (n + 1) * dt);
        stepper.step(zNext, 0.0);
        const NewmarkState& s = stepper.state();
        const Eigen::VectorXd uNext = fullField(*clamped, full.constant, s.w, s.z);
        // The clamped rows of M Δ²u/Δt² + K(βu⁺ + (1−2β)u + βu⁻) (no load): the clamp's reaction.
        const Eigen::VectorXd residual = full.mass * (uNext - 2.0 * u + uPrev) / (dt * dt) +
                                         full.stiffness * (beta * uNext + (1.0 - 2.0 * beta) * u + beta * uPrev);
        double force = 0.0, moment = 0.0;
        for (Eigen::Index i = 0; i < residual.size(); ++i)
            if (isClamped[i]) {
                force += residual[i] * full.constant[i];
                moment += residual[i] * rotation[i];
            }
        // (T.14a, b) from the state: what portOutputs computes.
        const double zAcc = (s.z - 2.0 * s.zPrev + s.zPrev2) / (dt * dt);
        const double t14a = clamped->totalMass * zAcc +
                            (s.baseCoupling - 2.0 * s.baseCouplingPrev + s.baseCouplingPrev2) / (dt * dt) -
                            (s.stepContactForce[0] + s.stepContactForce[1]);
        const Eigen::VectorXd& r = clamped->rotationInertia;
        const double t14b = clamped->totalMassMoment * zAcc +
                            (r.dot(s.w) - 2.0 * r.dot(s.wPrev) + r.dot(s.wPrev2)) / (dt * dt) - s.stepContactMoment;
        worstForce = std::max(worstForce, std::abs(force - t14a));
        worstMoment = std::max(worstMoment, std::abs(moment - t14b));
        largestForce = std::max(largestForce, std::abs(force));
        uPrev = u;
        u = uNext;
        impacts = s.contactOnsets[0] + s.contactOnsets[1];
    }
    std::printf("[ port ] clamp force up to %.4g N; worst |residual - (T.14a)| %.3g N, moment %.3g N.m; %lld onsets\n",
                largestForce, worstForce, worstMoment, impacts);
    ASSERT_GT(impacts, 2);
    // Roundoff: a second difference of momenta (~1 kg·m/s) over dt² = 1e-8 s²: ~1e-8 relative
    // to the force; 1e-7 leaves a margin.
    EXPECT_LE(worstForce, 1e-7 * largestForce);
    EXPECT_LE(worstMoment, 1e-7 * largestForce * p.mesh.length);
}
