// The condensed singular plate (docs/theory.md §17) against identities it must satisfy, computed
// independently here from a dense solve with K: the static flexibility splits into its massive
// and massless parts, the modes are mass-normalized and carry the whole mass, the load splits
// alike; and the conserving stepper closes its ledger step by step through impacts.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "base/Errors.h"
#include "fe/Assembly.h"
#include "plate/CondensedPlate.h"
#include "plate/CondensedSparse.h"
#include "schemes/FlowScheme.h"
#include "schemes/MidpointScheme.h"
#include "plate/PlateParameters.h"
#include "fe/SingularMass.h"

using namespace plate;

namespace {

// time_scheme = conserving (substeps = 0) or flow (substeps = m > 0), as makeScheme makes them.
std::unique_ptr<CondensedScheme> condensedScheme(std::shared_ptr<const CondensedPlate> plate, Obstacles obstacles,
                                                 double dt, double a, double b, int substeps) {
    if (substeps > 0)
        return std::make_unique<FlowScheme>(std::move(plate), obstacles, dt, ContactRefinement{substeps}, a, b);
    return std::make_unique<MidpointScheme>(std::move(plate), obstacles, dt, a, b);
}

struct Condensed {
    PlateParameters p;
    std::shared_ptr<const FiniteElementSpace> space;
    std::shared_ptr<const ClampedPlate> clamped;
    Eigen::SparseMatrix<double> rootFree;
    CondensedPlate c;

    Condensed(ElementType element, int nx, int ny, MassProjection projection, int modes = 0,
              Condensation method = Condensation::Auto, Eigen::Index recoveredRows = 0) {
        p.mesh.nx = nx;
        p.mesh.ny = ny;
        space = makeSpace(element, Mesh(p.mesh.length, p.mesh.width, nx, ny));
        PlateMatrices m = assemble(*space, p.material);
        SingularMass s = assembleSingularMass(*space, p.material.surfaceDensity(), projection);
        m.mass = s.mass;
        m.massMoment = s.massMoment;
        clamped = std::make_shared<const ClampedPlate>(clamp(*space, m));
        rootFree = freeRows(s.root, *clamped);
        // free_edge_mid between vertices as an extra row when ny is odd, as PlateSimulation does
        std::vector<ConstraintRow> extra;
        if (ny % 2 == 1) extra.push_back({clamped->probe(*space, p.mesh.length, 0.5 * p.mesh.width), p.mesh.length});
        // the last `recoveredRows` constraint rows (< 0: all) read again as recovery functionals (L = those rows of C)
        const SparseRows rows = constraintRows(*clamped, extra);
        c = condense(*clamped, rootFree, extra, modes, rows.bottomRows(recoveredRows < 0 ? rows.rows() : recoveredRows),
                     method);
    }

    // C K⁻¹ Cᵀ, C K⁻¹ F and Fᵀ K⁻¹ F from a dense factor of K.
    void flexibilities(Eigen::MatrixXd& rows, Eigen::VectorXd& load, double& loadLoad) const {
        const Eigen::MatrixXd k = Eigen::MatrixXd(clamped->stiffness);
        const Eigen::LLT<Eigen::MatrixXd> llt(k);
        const Eigen::Index n = k.rows(), r = c.rows();
        Eigen::MatrixXd ct = Eigen::MatrixXd::Zero(n, r);
        for (std::size_t i = 0; i < clamped->contactDofs.size(); ++i) ct(clamped->contactDofs[i], Eigen::Index(i)) = 1;
        if (r > Eigen::Index(clamped->contactDofs.size())) {
            const PointProbe probe = clamped->probe(*space, p.mesh.length, 0.5 * p.mesh.width);
            for (std::size_t k2 = 0; k2 < probe.dofs.size(); ++k2) ct(probe.dofs[k2], r - 1) += probe.coefficients[k2];
        }
        const Eigen::MatrixXd x = llt.solve(ct);
        rows = ct.transpose() * x;
        const Eigen::VectorXd xf = llt.solve(clamped->pressureLoad);
        load = ct.transpose() * xf;
        loadLoad = clamped->pressureLoad.dot(xf);
    }
};

void expectIdentities(const Condensed& s) {
    const CondensedPlate& c = s.c;
    Eigen::MatrixXd rows;
    Eigen::VectorXd load;
    double loadLoad;
    s.flexibilities(rows, load, loadLoad);
    // Static flexibility = massive part G Ω⁻² Gᵀ + massless part D (every mode kept).
    const Eigen::MatrixXd split =
        c.rowModesT.transpose() * c.omega2.cwiseInverse().asDiagonal() * c.rowModesT + c.delassus;
    EXPECT_LE((split - rows).cwiseAbs().maxCoeff(), 1e-9 * rows.cwiseAbs().maxCoeff());
    EXPECT_LE((c.rowModesT.transpose() * c.omega2.cwiseInverse().asDiagonal() * c.modalLoad + c.rowLoad - load)
                  .cwiseAbs()
                  .maxCoeff(),
              1e-9 * load.cwiseAbs().maxCoeff());
    EXPECT_NEAR(c.modalLoad.dot(c.omega2.cwiseInverse().asDiagonal() * c.modalLoad) + c.loadFlexibility, loadLoad,
                1e-9 * loadLoad);
    // The modes carry the whole mass: |b_m|² = 1ᵀ M_s 1 (orthonormal complete basis, §17).
    EXPECT_NEAR(c.modalBaseInertia.squaredNorm(), c.totalMass, 1e-9 * c.totalMass);
    EXPECT_EQ(c.clampMass, 0.0);
    // D is positive definite (Renard's condition) and the massless load response is that of D's space.
    EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(c.delassus).info(), Eigen::Success);
    EXPECT_EQ(c.massiveCount, c.modes());
}

}  // namespace

TEST(CondensedPlate, ArgyrisP0SplitsTheFlexibility) {
    expectIdentities(Condensed(ElementType::Argyris, 14, 5, MassProjection::P0));
}

TEST(CondensedPlate, FvsP0SplitsTheFlexibility) {
    expectIdentities(Condensed(ElementType::Fvs, 10, 3, MassProjection::P0));
}

TEST(CondensedPlate, ArgyrisP1dgSplitsTheFlexibility) {
    expectIdentities(Condensed(ElementType::Argyris, 6, 2, MassProjection::P1dg));
}

TEST(CondensedPlate, ReducedModelKeepsTheMasslessPartAndTheLowestModes) {
    const Condensed full(ElementType::Argyris, 14, 5, MassProjection::P0);
    const Condensed reduced(ElementType::Argyris, 14, 5, MassProjection::P0, 20);
    ASSERT_EQ(reduced.c.modes(), 20);
    EXPECT_EQ(reduced.c.delassus, full.c.delassus);  // the massless space is whole
    EXPECT_EQ(reduced.c.omega2, full.c.omega2.head(20));
    // The discarded modes' mass moves with the clamp: m_c = m − |b_m|² > 0, and they sum to m.
    EXPECT_GT(reduced.c.clampMass, 0.0);
    EXPECT_NEAR(reduced.c.clampMass + reduced.c.modalBaseInertia.squaredNorm(), full.c.totalMass,
                1e-9 * full.c.totalMass);
}

// The sparse condensation (Lanczos for the kept modes, the massless part on the sparse factors)
// against the dense eigen solution of the whole massive space, on the default plate (140 massive
// coordinates, 100 of them kept) and on a 28x10 plate (560). The eigenvalues to 1e-10 relative
// (Lanczos' residuals of 1e-12 square into far less); the modes themselves up to the sign, and
// rotations within a cluster of near-equal frequencies, through what the schemes read of them: the
// rows' massive flexibility G Ω⁻² Gᵀ and the modal load's energy. The massless part, the same
// operator by another route (one L D Lᵀ factor of the saddle point [K R; Rᵀ 0], against the dense
// difference C K⁻¹ Cᵀ − C K⁻¹ R T⁻¹ Rᵀ K⁻¹ Cᵀ, which cancels three of four digits: C K⁻¹ Cᵀ is ~1700
// times D), within 5e-9 of D's largest entry (measured 1.3e-11 and 1.9e-10).
//
// The recovery functionals: every row again (more than a quarter of the rows: they ride on the rows'
// own full solves, so L Q0 S⁻¹ Q0ᵀ Cᵀ is D's rows to roundoff of one symmetrization), or the last
// three (D's triangle alone, the functionals on solves of their own: D's rows by the other
// solves, to the sparse solution's own accuracy).
void expectSparseMatchesDense(int nx, int ny, int modes, bool everyRowRecovered) {
    const Eigen::Index recovered = everyRowRecovered ? -1 : 3;
    const Condensed dense(ElementType::Argyris, nx, ny, MassProjection::P0, modes, Condensation::Dense, recovered);
    const Condensed sparse(ElementType::Argyris, nx, ny, MassProjection::P0, modes, Condensation::Sparse, recovered);
    const CondensedPlate &d = dense.c, &s = sparse.c;
    ASSERT_EQ(s.recoveryRows.rows(), everyRowRecovered ? d.rows() : 3);
    ASSERT_EQ(s.modes(), modes);
    ASSERT_EQ(s.rows(), d.rows());
    EXPECT_LE(((s.omega2 - d.omega2).array() / d.omega2.array()).abs().maxCoeff(), 1e-10);
    const auto massiveRows = [](const CondensedPlate& c) {
        return Eigen::MatrixXd(c.rowModesT.transpose() * c.omega2.cwiseInverse().asDiagonal() * c.rowModesT);
    };
    const Eigen::MatrixXd gd = massiveRows(d);
    EXPECT_LE((massiveRows(s) - gd).cwiseAbs().maxCoeff(), 1e-9 * gd.cwiseAbs().maxCoeff());
    const double loadEnergy = d.modalLoad.dot(d.omega2.cwiseInverse().asDiagonal() * d.modalLoad);
    EXPECT_NEAR(s.modalLoad.dot(s.omega2.cwiseInverse().asDiagonal() * s.modalLoad), loadEnergy, 1e-10 * loadEnergy);
    EXPECT_NEAR(s.clampMass, d.clampMass, 1e-10 * d.totalMass);
    EXPECT_NEAR(s.clampMassMoment, d.clampMassMoment, 1e-10 * std::abs(d.totalMassMoment));
    EXPECT_LE((s.delassus - d.delassus).cwiseAbs().maxCoeff(), 5e-9 * d.delassus.cwiseAbs().maxCoeff());
    const Eigen::Index l = s.recoveryRows.rows();
    EXPECT_LE((s.recoveryRows - d.recoveryRows).cwiseAbs().maxCoeff(), 5e-9 * d.delassus.cwiseAbs().maxCoeff());
    EXPECT_LE((s.recoveryRows - s.delassus.bottomRows(l)).cwiseAbs().maxCoeff(),
              (everyRowRecovered ? 1e-12 : 5e-9) * d.delassus.cwiseAbs().maxCoeff());
    EXPECT_EQ(s.delassus, s.delassus.transpose());
    // The uniform pressure's massless part is zero with P0 (F = p B·1 lies in the range of R): both
    // give roundoff of the whole flexibility's response C K⁻¹ F, Fᵀ K⁻¹ F.
    Eigen::MatrixXd rows;
    Eigen::VectorXd load;
    double loadLoad;
    dense.flexibilities(rows, load, loadLoad);
    EXPECT_LE((s.rowLoad - d.rowLoad).cwiseAbs().maxCoeff(), 1e-12 * load.cwiseAbs().maxCoeff());
    EXPECT_LE(std::abs(s.loadFlexibility - d.loadFlexibility), 1e-12 * loadLoad);
}

TEST(CondensedPlate, SparseModesMatchTheDenseSolutionOnTheDefaultPlate) {
    expectSparseMatchesDense(14, 5, 100, true);
    expectSparseMatchesDense(14, 5, 100, false);
}

TEST(CondensedPlate, SparseModesMatchTheDenseSolutionOn28x10) {
    expectSparseMatchesDense(28, 10, 100, true);
    expectSparseMatchesDense(28, 10, 100, false);
}

// Auto keeps the dense solution where it served before the sparse one (the golden scenes, bit for
// bit), and takes the sparse one for a few modes of a large massive space.
TEST(CondensedPlate, DenseSolutionServesSmallSpacesAndCompleteBases) {
    EXPECT_TRUE(denseCondensationServes(140, 0));  // the default plate
    EXPECT_TRUE(denseCondensationServes(1120, 40));  // 28x20 and coarser
    EXPECT_TRUE(denseCondensationServes(2240, 0));  // every mode of 56x20
    EXPECT_TRUE(denseCondensationServes(2240, 600));  // most of them
    EXPECT_FALSE(denseCondensationServes(2240, 100));
    const Condensed viaAuto(ElementType::Argyris, 14, 5, MassProjection::P0, 20);
    const Condensed viaDense(ElementType::Argyris, 14, 5, MassProjection::P0, 20, Condensation::Dense);
    EXPECT_EQ(viaAuto.c.omega2, viaDense.c.omega2);
    EXPECT_EQ(viaAuto.c.delassus, viaDense.c.delassus);
    EXPECT_THROW(Condensed(ElementType::Argyris, 6, 2, MassProjection::P0, 0, Condensation::Sparse),
                 std::invalid_argument);
}

// Step by step, E_{n+1} − E_n = work − damped to the discrete gradient's tolerance (T.17d), through
// the impacts of §5.2 (released from 8600 Pa, the lower obstacle raised to −0.08 m) with a moving
// base, a varying load and modal damping.
// Released from 8600 Pa with base and load moving and Rayleigh damping: the largest per-step
// residual of the ledger (T.17d), the contact steps, E0 and the lowest row height seen.
struct LedgerRun {
    double worst = 0.0, e0 = 0.0, lowest = HUGE_VAL;
    int contactSteps = 0;
};

LedgerRun runLedger(const std::shared_ptr<const CondensedPlate>& plate, const Obstacles& obstacles, double dt,
                    int steps, int substeps, double tolerance = 0.0) {
    const auto scheme = tolerance > 0.0 ? std::make_unique<FlowScheme>(plate, obstacles, dt,
                                                                       ContactRefinement{16, tolerance}, 1.0, 1e-5)
                                        : condensedScheme(plate, obstacles, dt, 1.0, 1e-5, substeps);
    CondensedScheme& stepper = *scheme;
    stepper.initialize(0.0, 8600.0);
    stepper.setLoadAtStart(0.0);
    LedgerRun run;
    run.e0 = stepper.energy();
    double previous = run.e0;
    for (int n = 1; n <= steps; ++n) {
        const double t = n * dt;
        const CondensedState before = stepper.state();
        stepper.step(0.01 * std::sin(2 * M_PI * 5 * t), 100.0 * std::sin(2 * M_PI * 3 * t));
        const CondensedState& after = stepper.state();
        const double e = stepper.energy();
        const double balance =
            (e - previous) - (after.energyInput - before.energyInput) + (after.energyDamped - before.energyDamped);
        run.worst = std::max(run.worst, std::abs(balance));
        run.contactSteps += after.contactPoints > 0;
        previous = e;
        for (int i = 0; i < plate->rows(); ++i) run.lowest = std::min(run.lowest, stepper.rowHeight(i));
    }
    return run;
}

TEST(CondensedScheme, LedgerClosesEveryStepThroughImpacts) {
    const Condensed s(ElementType::Argyris, 14, 5, MassProjection::P0);
    auto plate = std::make_shared<const CondensedPlate>(s.c);
    Obstacles obstacles;
    obstacles.lower = -0.08;
    const LedgerRun run = runLedger(plate, obstacles, 2e-5, 10000, 0);
    const int contactSteps = run.contactSteps;
    const double worst = run.worst, e0 = run.e0;
    EXPECT_GT(contactSteps, 50);
    // 1e-13 of the step's energies per step (the gradient's tolerance), E0 ~ 100 J.
    EXPECT_LE(worst, 1e-10 * e0);
}

// time_scheme = flow (docs/theory.md §21): a step without contact is each mode's exact flow.
namespace {

// Height of row i from the modal coordinates (no contact force: free flight).
double rowOf(const CondensedPlate& c, const Eigen::VectorXd& q, double p, double z, int i) {
    return c.rowModesT.col(i).dot(q) + p * c.rowLoad[i] + z;
}

}  // namespace

// Released from the static shape under 8600 Pa (no obstacles, no input): q_k(t) = q_k(0) cos ω_k t.
// The corner's height over 2000 steps within 1e-12 m of that sum (amplitude ~0.2 m).
TEST(FlowStepper, FreeFlightIsTheClosedFormModalSolution) {
    const Condensed s(ElementType::Argyris, 8, 3, MassProjection::P0);
    auto plate = std::make_shared<const CondensedPlate>(s.c);
    const double dt = 2e-5;
    const auto scheme = condensedScheme(plate, Obstacles{}, dt, 0.0, 0.0, 8);
    CondensedScheme& stepper = *scheme;
    stepper.initialize(0.0, 8600.0);
    stepper.setLoadAtStart(0.0);
    const Eigen::VectorXd q0 = stepper.state().q;
    int corner = 0;  // the row that moves most: a free corner
    for (int i = 1; i < plate->rows(); ++i)
        if (std::abs(rowOf(*plate, q0, 0.0, 0.0, i)) > std::abs(rowOf(*plate, q0, 0.0, 0.0, corner))) corner = i;
    double worst = 0.0, amplitude = 0.0;
    for (int n = 1; n <= 2000; ++n) {
        stepper.step(0.0, 0.0);
        const double t = n * dt;
        Eigen::VectorXd exact(q0.size());
        for (Eigen::Index k = 0; k < q0.size(); ++k) exact[k] = q0[k] * std::cos(std::sqrt(plate->omega2[k]) * t);
        const double got = rowOf(*plate, stepper.state().q, 0.0, 0.0, corner);
        const double want = rowOf(*plate, exact, 0.0, 0.0, corner);
        worst = std::max(worst, std::abs(got - want));
        amplitude = std::max(amplitude, std::abs(want));
    }
    EXPECT_GT(amplitude, 0.05);
    EXPECT_LE(worst, 1e-12);
}

// Forced: the base at constant velocity v and the load a ramp from rest in the static shape under
// p0: q = A + B t + (u̇0/ω) sin ωt with B = F ṗ/ω², A = F p0/ω², u̇0 = −b v − B (the clamp's velocity
// kick at t = 0 seen from the moving clamp). Rayleigh mass damping a: the same with the damped
// oscillator's free part.
TEST(FlowStepper, ForcedAndDampedStepsAreTheClosedFormModalSolution) {
    const Condensed s(ElementType::Argyris, 8, 3, MassProjection::P0);
    auto plate = std::make_shared<const CondensedPlate>(s.c);
    const CondensedPlate& c = *plate;
    const double dt = 2e-5, v = 0.05, p0 = 1000.0, pDot = -20000.0;
    for (const double a : {0.0, 5.0}) {
        const auto scheme = condensedScheme(plate, Obstacles{}, dt, a, 0.0, 8);
        CondensedScheme& stepper = *scheme;
        stepper.initialize(0.0, p0);
        double worst = 0.0, amplitude = 0.0;
        for (int n = 1; n <= 1500; ++n) {
            const double t = n * dt;
            stepper.step(v * t, p0 + pDot * t);
            Eigen::VectorXd exact(c.modes());
            for (Eigen::Index k = 0; k < c.modes(); ++k) {
                const double w2 = c.omega2[k], f = c.modalLoad[k];
                const double slope = f * pDot / w2, offset = (f * p0 - a * slope) / w2;
                const double u0 = f * p0 / w2 - offset, ud0 = -c.modalBaseInertia[k] * v - slope;
                const double wd = std::sqrt(w2 - 0.25 * a * a), decay = std::exp(-0.5 * a * t);
                const double u = decay * (u0 * std::cos(wd * t) + (ud0 + 0.5 * a * u0) / wd * std::sin(wd * t));
                exact[k] = offset + slope * t + u;
            }
            const double got = rowOf(c, stepper.state().q, p0 + pDot * t, v * t, c.rows() - 1);
            const double want = rowOf(c, exact, p0 + pDot * t, v * t, c.rows() - 1);
            worst = std::max(worst, std::abs(got - want));
            amplitude = std::max(amplitude, std::abs(want - v * t));
        }
        EXPECT_GT(amplitude, 1e-4) << "a = " << a;
        EXPECT_LE(worst, 1e-12) << "a = " << a;
    }
}

// A contact step that throws leaves the scheme as it was (Scheme.h), in the rows that can touch and in
// every row, with and without a tolerance: the lowest frequency made non-finite after the start fails
// the step's first sub-step (its result is not finite; the exact free flight reads the frequencies
// through coefficients of its own); the state saved before equals the state after, bit for bit, and
// with ω₁ repaired the step is the one a twin that never failed takes. The refusal names the step it
// could not take: t_{n+1}.
TEST(FlowStepper, AContactStepThatThrowsLeavesTheStateAsItWas) {
    const Condensed s(ElementType::Argyris, 8, 3, MassProjection::P0);
    Obstacles obstacles;
    obstacles.lower = -0.08;
    for (const bool rowSpace : {true, false}) {
        for (const double tolerance : {0.0, 1e-5}) {
            ContactRefinement refinement{16, tolerance};
            refinement.rowSpace = rowSpace;
            auto plate = std::make_shared<CondensedPlate>(s.c);
            FlowScheme scheme(plate, obstacles, 2e-5, refinement), twin(plate, obstacles, 2e-5, refinement);
            for (FlowScheme* f : {&scheme, &twin}) {
                f->initialize(0.0, 8600.0);
                f->setLoadAtStart(0.0);
            }
            while (scheme.state().contactPoints == 0) {
                scheme.step(0.0, 0.0);
                twin.step(0.0, 0.0);
            }
            const std::vector<double> before = scheme.saveState();
            const double omega2 = plate->omega2[0];
            plate->omega2[0] = std::numeric_limits<double>::quiet_NaN();
            const double next = double(scheme.stepCount() + 1) * 2e-5;
            double refusedAt = -1.0;
            try {
                scheme.step(0.0, 0.0);
            } catch (const StepError& e) {
                refusedAt = e.time();
            }
            EXPECT_EQ(refusedAt, next) << "rowSpace " << rowSpace << ", tolerance " << tolerance;
            plate->omega2[0] = omega2;
            EXPECT_EQ(scheme.saveState(), before) << "rowSpace " << rowSpace << ", tolerance " << tolerance;
            scheme.step(0.0, 0.0);
            twin.step(0.0, 0.0);
            EXPECT_EQ(scheme.saveState(), twin.saveState()) << "rowSpace " << rowSpace << ", tolerance " << tolerance;
        }
    }
}

// The energy identity (T.17d) step by step through impacts with sub-steps, at three dt, with
// forcing and Rayleigh damping (the flow's exact damping and the sub-steps' midpoint damping).
TEST(FlowStepper, LedgerClosesEveryStepThroughImpactsAtThreeDt) {
    const Condensed s(ElementType::Argyris, 14, 5, MassProjection::P0);
    auto plate = std::make_shared<const CondensedPlate>(s.c);
    Obstacles obstacles;
    obstacles.lower = -0.08;
    for (const double dt : {4e-5, 2e-5, 1e-5}) {
        const LedgerRun run = runLedger(plate, obstacles, dt, static_cast<int>(0.2 / dt), 8);
        EXPECT_GT(run.contactSteps, 20) << "dt = " << dt;
        EXPECT_LE(run.worst, 1e-10 * run.e0) << "dt = " << dt;
        EXPECT_GE(run.lowest, obstacles.lower - 1e-14) << "dt = " << dt;
    }
}

// After impact the error is made in the contact steps (docs/theory.md §21): with the free flight
// exact, corner_1 over 0.15 s (two impacts on the lower obstacle) converges in the contact
// sub-step Δt/m at second order — each halving of Δt/m divides the error by about 4 (at least 3
// asserted), measured against m = 64.
TEST(FlowStepper, CornerAfterImpactConvergesAtSecondOrderInTheSubstep) {
    const Condensed s(ElementType::Argyris, 8, 3, MassProjection::P0);
    auto plate = std::make_shared<const CondensedPlate>(s.c);
    Obstacles obstacles;
    obstacles.lower = -0.08;
    const double dt = 2e-5;
    const auto run = [&](int m) {
        const auto scheme = condensedScheme(plate, obstacles, dt, 0.0, 0.0, m);
        CondensedScheme& stepper = *scheme;
        stepper.initialize(0.0, 8600.0);
        stepper.setLoadAtStart(0.0);
        std::vector<double> corner;
        int contacts = 0;
        for (int n = 1; n <= 7500; ++n) {
            stepper.step(0.0, 0.0);
            contacts += stepper.state().contactPoints > 0;
            if (n % 5 == 0) corner.push_back(stepper.rowHeight(0));
        }
        EXPECT_GT(contacts, 0);
        return corner;
    };
    const std::vector<double> reference = run(64);
    const auto error = [&](int m) {
        const std::vector<double> c = run(m);
        double worst = 0.0;
        for (std::size_t i = 0; i < c.size(); ++i) worst = std::max(worst, std::abs(c[i] - reference[i]));
        return worst;
    };
    const double e4 = error(4), e8 = error(8), e16 = error(16);
    EXPECT_GT(e4 / e8, 3.0) << e4 << " " << e8;
    EXPECT_GT(e8 / e16, 3.0) << e8 << " " << e16;
    EXPECT_LT(e16, 1e-4);
}

// docs/theory.md §22: with a tolerance every run of a contact step (the coarse, the discarded and
// the kept one) is a sequence of discrete-gradient sub-steps from the same start, so the kept
// step closes the ledger (T.17d) as a fixed count does, with forcing and damping.
TEST(FlowTolerance, LedgerClosesEveryStepThroughImpacts) {
    const Condensed s(ElementType::Argyris, 14, 5, MassProjection::P0);
    auto plate = std::make_shared<const CondensedPlate>(s.c);
    Obstacles obstacles;
    obstacles.lower = -0.08;
    const LedgerRun run = runLedger(plate, obstacles, 2e-5, 10000, 0, 1e-5);
    EXPECT_GT(run.contactSteps, 20);
    EXPECT_LE(run.worst, 1e-10 * run.e0);
    EXPECT_GE(run.lowest, obstacles.lower - 1e-14);
}

namespace {

// corner_1 every 5 steps over 0.15 s of §5.2's release (two impacts on the lower obstacle) on the
// 8×3 plate, and the scheme's state at the end.
struct CornerRun {
    std::vector<double> corner;
    CondensedState end;
    FlowState flow;
};
CornerRun releaseRun(const std::shared_ptr<const CondensedPlate>& plate, double dt, ContactRefinement refinement,
                     double upper = std::numeric_limits<double>::infinity()) {
    Obstacles obstacles;
    obstacles.lower = -0.08;
    obstacles.upper = upper;
    OutputRows corner;  // the estimate measured where the run is compared: row 0
    corner.probes = {0, 0, 0};
    FlowScheme scheme(plate, obstacles, dt, refinement, 0.0, 0.0, corner);
    scheme.initialize(0.0, 8600.0);
    scheme.setLoadAtStart(0.0);
    CornerRun run;
    const int steps = static_cast<int>(std::lround(0.15 / dt)), every = static_cast<int>(std::lround(1e-4 / dt));
    for (int n = 1; n <= steps; ++n) {
        scheme.step(0.0, 0.0);
        if (n % every == 0) run.corner.push_back(scheme.rowHeight(0));
    }
    run.end = scheme.state();
    run.flow = scheme.flowState();
    return run;
}

double worstDifference(const std::vector<double>& a, const std::vector<double>& b) {
    double worst = 0.0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
    return worst;
}

}  // namespace

// The tolerance met and the estimate honest (docs/theory.md §22): against a converged reference
// (a quarter of the step, 64 sub-steps per contact step: its own error is checked to be below a
// tenth of the smallest tolerance against half that step), corner_1's error stays inside the
// tolerance at 1e-4 and 1e-5 m, and the global estimate is not below the error nor above three
// times it (the estimate may over-state what a user gets, never under-state it).
TEST(FlowTolerance, ErrorWithinToleranceAndEstimateBoundsIt) {
    const Condensed s(ElementType::Argyris, 8, 3, MassProjection::P0);
    auto plate = std::make_shared<const CondensedPlate>(s.c);
    const double dt = 2e-5;
    const CornerRun reference = releaseRun(plate, dt / 4, ContactRefinement{64});
    const CornerRun check = releaseRun(plate, dt / 2, ContactRefinement{64});
    ASSERT_LT(worstDifference(reference.corner, check.corner), 1e-6);
    for (const double tolerance : {1e-4, 1e-5}) {
        const CornerRun run = releaseRun(plate, dt, ContactRefinement{16, tolerance});
        const double error = worstDifference(run.corner, reference.corner);
        EXPECT_LE(error, tolerance) << "tolerance " << tolerance;
        EXPECT_GE(run.flow.errorEstimate, error) << "tolerance " << tolerance << ", error " << error;
        EXPECT_LE(run.flow.errorEstimate, error * 3.0) << "tolerance " << tolerance << ", error " << error;
        EXPECT_EQ(run.flow.cappedSteps, 0);
    }
}

// The cap (§22): at most 2 sub-steps per contact step against a tolerance they cannot meet. The first
// contact step is counted as capped, its own error enters the estimate, which passes the tolerance:
// the tolerance is lost from that time on (lostAt, said by the FMU), and no later step goes past the
// cap either.
TEST(FlowTolerance, CapBoundsTheWorkAndCountsTheSteps) {
    const Condensed s(ElementType::Argyris, 8, 3, MassProjection::P0);
    auto plate = std::make_shared<const CondensedPlate>(s.c);
    const CornerRun capped = releaseRun(plate, 2e-5, ContactRefinement{16, 1e-12, 2});
    EXPECT_GE(capped.flow.cappedSteps, 1);
    EXPECT_EQ(capped.flow.refinementLevel, 1);
    EXPECT_GT(capped.flow.errorEstimate, 1e-12);
    EXPECT_GT(capped.flow.lostAt, 0.05);  // at the first impact, near 0.07 s
    EXPECT_LT(capped.flow.lostAt, 0.1);
    EXPECT_GT(capped.flow.contactSteps, 10);
}

// Past the horizon between two obstacles (§22) the estimate is their gap, the one bound that still
// holds, and the contact steps take contact_substeps sub-steps without a pair or a companion: the
// same contact solves as the run without a tolerance from the loss on, far fewer than a run that
// kept estimating. Before the loss both runs are the same run.
TEST(FlowTolerance, PastTheHorizonBetweenTwoObstaclesTheEstimateIsTheGap) {
    const Condensed s(ElementType::Argyris, 8, 3, MassProjection::P0);
    auto plate = std::make_shared<const CondensedPlate>(s.c);
    const double upper = 0.08, gap = upper - (-0.08);
    const CornerRun lost = releaseRun(plate, 2e-5, ContactRefinement{16, 1e-12, 2}, upper);
    EXPECT_GE(lost.flow.lostAt, 0.0);  // 1e-12 m: lost at the first contact step
    EXPECT_EQ(lost.flow.errorEstimate, gap);
    EXPECT_TRUE(lost.flow.errorQ.isZero(0.0) && lost.flow.errorMomentum.isZero(0.0));
    // The one-obstacle run of the same scene goes on estimating: no bound to stop at.
    const CornerRun open = releaseRun(plate, 2e-5, ContactRefinement{16, 1e-12, 2});
    EXPECT_LT(open.flow.errorEstimate, gap);
}

// What the FMU says past the horizon (PlateAdvice): when the estimate passed the tolerance, and the
// sub-steps a contact step takes from then on — contact_substeps = 12 down to a power of two, 8.
TEST(FlowTolerance, TheHorizonSaysWhenAndHowManySubsteps) {
    const Condensed s(ElementType::Argyris, 8, 3, MassProjection::P0);
    auto plate = std::make_shared<const CondensedPlate>(s.c);
    Obstacles obstacles;
    obstacles.lower = -0.08;
    FlowScheme scheme(plate, obstacles, 2e-5, ContactRefinement{12, 1e-12});
    scheme.initialize(0.0, 8600.0);
    scheme.setLoadAtStart(0.0);
    EXPECT_EQ(scheme.toleranceHorizon().substeps, 8);
    EXPECT_LT(scheme.toleranceHorizon().lostAt, 0.0);
    while (scheme.flowState().lostAt < 0.0) {
        scheme.step(0.0, 0.0);
        ASSERT_LT(scheme.stepCount(), 20000);
    }
    EXPECT_EQ(scheme.toleranceHorizon().lostAt, scheme.flowState().lostAt);
    EXPECT_EQ(scheme.toleranceHorizon().lostAt, double(scheme.stepCount()) * 2e-5);  // lost at this step
    EXPECT_EQ(FlowScheme(plate, obstacles, 2e-5, ContactRefinement{12}).toleranceHorizon().substeps, 0);
}

namespace {

// The release from 8600 Pa onto the lower obstacle with a tolerance of 1e-5 m: `a` runs it, a fresh
// scheme `b` of the same plate takes a's saved states.
struct ToleranceRelease {
    Condensed s{ElementType::Argyris, 8, 3, MassProjection::P0};
    std::shared_ptr<const CondensedPlate> plate = std::make_shared<const CondensedPlate>(s.c);
    Obstacles obstacles = [] {
        Obstacles o;
        o.lower = -0.08;
        return o;
    }();
    ContactRefinement refinement{16, 1e-5};
    FlowScheme a{plate, obstacles, 2e-5, refinement}, b{plate, obstacles, 2e-5, refinement};
    ToleranceRelease() {
        a.initialize(0.0, 8600.0);
        a.setLoadAtStart(0.0);
        b.initialize(0.0, 8600.0);
    }
};

}  // namespace

// A state saved in free flight after an impact, with a tolerance (E carried, no row held), restored
// into a fresh scheme, continues bit for bit through the next impacts: what the scheme keeps beside
// its state (the rows looked at, the free-flight bound) changes no result.
TEST(FlowTolerance, RestoredInFreeFlightAfterAnImpactContinuesBitForBit) {
    ToleranceRelease run;
    FlowScheme &a = run.a, &b = run.b;
    int free = 0;
    while (a.flowState().contactSteps == 0 || free < 5) {  // five free steps after the first contact
        a.step(0.0, 0.0);
        free = a.flowState().contactSteps > 0 && a.state().contactPoints == 0 ? free + 1 : 0;
        ASSERT_LT(a.stepCount(), 20000);
    }
    EXPECT_GT(a.flowState().errorEstimate, 0.0);
    b.restoreState(a.saveState());
    const long long contactSteps = a.flowState().contactSteps;
    for (int k = 0; k < 3000; ++k) {
        a.step(0.0, 0.0);
        b.step(0.0, 0.0);
    }
    EXPECT_GT(a.flowState().contactSteps, contactSteps + 10);  // through later impacts
    EXPECT_EQ(a.saveState(), b.saveState());
}

// The controller's state is part of the scheme's state: a run saved and restored into a fresh
// scheme mid-contact continues bit for bit.
TEST(FlowTolerance, SavedStateContinuesBitForBit) {
    ToleranceRelease run;
    FlowScheme &a = run.a, &b = run.b;
    int n = 0;
    while (a.state().contactPoints == 0 || a.flowState().contactSteps < 5) {  // E carried, mid-contact
        a.step(0.0, 0.0);
        ASSERT_LT(++n, 20000);
    }
    // The events' error (an onset among the steps so far) is part of it too, the state's last values;
    // a negative squared amplitude there is a damaged state, refused.
    EXPECT_GT(a.flowState().eventError2.maxCoeff(), 0.0);
    std::vector<double> damaged = a.saveState();
    damaged.back() = -1e-12;
    FlowScheme c(run.plate, run.obstacles, 2e-5, run.refinement);
    try {
        c.restoreState(damaged);
        ADD_FAILURE() << "a negative squared amplitude was accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "corrupt state: a negative squared amplitude in the events' error");
    }
    b.restoreState(a.saveState());
    for (int k = 0; k < 2000; ++k) {
        a.step(0.0, 0.0);
        b.step(0.0, 0.0);
    }
    EXPECT_EQ(a.saveState(), b.saveState());
}
