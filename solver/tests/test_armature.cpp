// The carried clamp (docs/theory.md §18): the Schur-complement step and the bordered contact
// columns against a dense solve of the bordered matrix (T.18)/(T.19), and the ledger of plate and
// armature through impacts on the sparse engine (the FMU's tests run the modal one).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <memory>

#include "schemes/Armature.h"
#include "fe/Assembly.h"
#include "plate/FullOrderPlate.h"
#include "schemes/NewmarkScheme.h"
#include "plate/PlateParameters.h"

using namespace plate;

namespace {

struct Rig {
    PlateParameters p;
    std::shared_ptr<const FiniteElementSpace> space;
    std::shared_ptr<const ClampedPlate> clamped;
    std::shared_ptr<const FullOrderPlate> plate;
    CarrierOptions carrier;
    Rig() {
        p.mesh.nx = 5;
        p.mesh.ny = 2;
        space = std::shared_ptr<const FiniteElementSpace>(
            makeSpace(ElementType::Argyris, Mesh(p.mesh.length, p.mesh.width, p.mesh.nx, p.mesh.ny)));
        clamped = std::make_shared<const ClampedPlate>(clamp(*space, assemble(*space, p.material)));
        p.law.dt = 1e-4;
        plate = std::make_shared<const FullOrderPlate>(space, clamped, p.law);
        carrier.mass = 20.0;
        carrier.stiffness = 3158.0;
        carrier.damping = 50.0;
        carrier.restPosition = 0.001;
    }
    // The bordered matrix of (T.18), dense.
    Eigen::MatrixXd bordered() const {
        const double dt = plate->dt(), beta = plate->beta();
        const Eigen::Index n = plate->size();
        Eigen::MatrixXd a(n + 1, n + 1);
        a.topLeftCorner(n, n) = Eigen::MatrixXd(clamped->mass) + beta * dt * dt * Eigen::MatrixXd(clamped->stiffness);
        a.topRightCorner(n, 1) = clamped->baseInertia;
        a.bottomLeftCorner(1, n) = clamped->baseInertia.transpose();
        a(n, n) = carrier.mass + clamped->totalMass + beta * dt * dt * carrier.stiffness + 0.5 * dt * carrier.damping;
        return a;
    }
};

}  // namespace

TEST(Armature, SchurStepIsTheBorderedSolve) {
    const Rig rig;
    const Armature armature(*rig.plate, rig.carrier);
    const Eigen::Index n = rig.plate->size();
    NewmarkState s;
    s.z = 0.003;
    s.zPrev = 0.0025;
    const double force = 120.0, pressure = 40.0, dt = rig.plate->dt();
    const Eigen::VectorXd rw = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0).array().sin() * 1e-3;
    Eigen::VectorXd d;
    rig.plate->solveStepMatrix(rw, d);
    const double e = armature.solveFree(s, force, pressure, d);
    Eigen::VectorXd rhs(n + 1);
    rhs.head(n) = rw;
    rhs[n] =
        dt * dt *
            (force + pressure * rig.clamped->loadResultant - rig.carrier.stiffness * (s.z - rig.carrier.restPosition)) -
        dt * rig.carrier.damping * (s.z - s.zPrev);
    const Eigen::VectorXd x = rig.bordered().ldlt().solve(rhs);
    // Two backward-stable solves of the same SPD system: measured 5e-15 relative apart. 1e-12
    // leaves room for other compilers and is far below any wrong term (the base coupling alone
    // changes d by O(1) relative).
    EXPECT_NEAR(e, x[n], 1e-12 * std::abs(x[n]));
    EXPECT_LE((d - x.head(n)).norm(), 1e-12 * x.head(n).norm());
}

TEST(Armature, ContactColumnsAreTheBorderedInverse) {
    const Rig rig;
    const Armature armature(*rig.plate, rig.carrier);
    const Eigen::Index n = rig.plate->size();
    const Eigen::LDLT<Eigen::MatrixXd> factor = rig.bordered().ldlt();
    for (int j : {0, rig.plate->contactCount() / 2, rig.plate->contactCount() - 1}) {
        Eigen::VectorXd c;
        rig.plate->contactDirection(j, c);
        Eigen::VectorXd g(n + 1);
        g.head(n) = c;
        g[n] = 1.0;  // the constraint is on u_j = (C w)_j + z
        const Eigen::VectorXd expected = factor.solve(g);
        Eigen::VectorXd x, y;
        armature.column(j, x);
        EXPECT_LE((x - expected).norm(), 1e-12 * expected.norm()) << j;  // measured <= 1.1e-14
        armature.gather(x, y);  // W̃ e_j: symmetric, positive on the diagonal
        EXPECT_GT(y[j], 0.0);
    }
}

TEST(Armature, LedgerOfPlateAndArmatureClosesThroughImpacts) {
    const Rig rig;
    Obstacles obstacles;
    obstacles.lower = -0.02;
    obstacles.upper = 0.02;
    SchemeOptions options;
    options.carried = true;
    options.carrier = rig.carrier;
    options.carrier.restPosition = 0.0;
    NewmarkScheme stepper(rig.plate, obstacles, options);
    stepper.initialize(Eigen::VectorXd::Zero(rig.plate->size()), 0.0, 0.0);
    const double dt = rig.plate->dt();
    double worst = 0.0, largest = 0.0;
    for (int k = 1; k <= 8000; ++k) {
        const double t = k * dt, ramp = std::pow(std::sin(0.5 * M_PI * std::min(t / 0.25, 1.0)), 2);
        stepper.step(500.0 * ramp * std::sin(2.0 * M_PI * 6.0 * t), 0.0);
        const NewmarkState& s = stepper.state();
        const CarrierState& c = stepper.carrier()->state();
        const double stored = stepper.energy() + stepper.carrier()->energy(s);
        const double balance = c.driveWork - c.damperWork - s.energyDissipated - s.energyDamped;
        worst = std::max(worst, std::abs(stored - balance));
        worst = std::max(worst, std::abs(s.energyInput + c.portWork));  // the power identity of §14
        largest = std::max(largest, std::abs(c.driveWork));
    }
    const NewmarkState& s = stepper.state();
    EXPECT_GT(s.contactOnsets[0] + s.contactOnsets[1], 5);
    // Roundoff of sums of ~10 J terms over 8000 steps (measured ~1e-12 J); an impact loses ~0.1 J.
    EXPECT_LE(worst, 1e-9 * largest);
}
