// The condensed singular plate (docs/theory.md §17) against identities it must satisfy, computed
// independently here from a dense solve with K: the static flexibility splits into its massive
// and massless parts, the modes are mass-normalized and carry the whole mass, the load splits
// alike; and the conserving stepper closes its ledger step by step through impacts.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <memory>

#include "Assembly.h"
#include "CondensedPlate.h"
#include "ConservingStepper.h"
#include "PlateParameters.h"
#include "SingularMass.h"

using namespace plate;

namespace {

struct Condensed {
    PlateParameters p;
    std::shared_ptr<const FiniteElementSpace> space;
    std::shared_ptr<const ClampedPlate> clamped;
    Eigen::SparseMatrix<double> rootFree;
    CondensedPlate c;

    Condensed(ElementType element, int nx, int ny, MassProjection projection, int modes = 0) {
        p.nx = nx;
        p.ny = ny;
        space = makeSpace(element, Mesh(p.length, p.width, nx, ny));
        PlateMatrices m = assemble(*space, p.surfaceDensity(), p.bendingStiffness(), p.poissonRatio);
        SingularMass s = assembleSingularMass(*space, p.surfaceDensity(), projection);
        m.mass = s.mass;
        m.massMoment = s.massMoment;
        clamped = std::make_shared<const ClampedPlate>(clamp(*space, m));
        rootFree = freeRows(s.root, *clamped);
        // free_edge_mid between vertices as an extra row when ny is odd, as PlateSimulation does
        std::vector<ConstraintRow> extra;
        if (ny % 2 == 1) extra.push_back({clamped->probe(*space, p.length, 0.5 * p.width), p.length});
        c = condense(*clamped, rootFree, extra, modes);
    }

    // C K⁻¹ Cᵀ, C K⁻¹ F and Fᵀ K⁻¹ F from a dense factor of K.
    void flexibilities(Eigen::MatrixXd& rows, Eigen::VectorXd& load, double& loadLoad) const {
        const Eigen::MatrixXd k = Eigen::MatrixXd(clamped->stiffness);
        const Eigen::LLT<Eigen::MatrixXd> llt(k);
        const Eigen::Index n = k.rows(), r = c.rows();
        Eigen::MatrixXd ct = Eigen::MatrixXd::Zero(n, r);
        for (std::size_t i = 0; i < clamped->contactDofs.size(); ++i) ct(clamped->contactDofs[i], Eigen::Index(i)) = 1;
        if (r > Eigen::Index(clamped->contactDofs.size())) {
            const PointProbe probe = clamped->probe(*space, p.length, 0.5 * p.width);
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

// Step by step, E_{n+1} − E_n = work − damped to the discrete gradient's tolerance (T.17d), through
// the impacts of §5.2 (released from 8600 Pa, the lower obstacle raised to −0.08 m) with a moving
// base, a varying load and modal damping.
TEST(ConservingStepper, LedgerClosesEveryStepThroughImpacts) {
    const Condensed s(ElementType::Argyris, 14, 5, MassProjection::P0);
    auto plate = std::make_shared<const CondensedPlate>(s.c);
    Obstacles obstacles;
    obstacles.lower = -0.08;
    ConservingStepper stepper(plate, obstacles, 2e-5, 1.0, 1e-5);
    stepper.initialize(0.0, 8600.0);
    stepper.setLoadAtStart(0.0);
    const double e0 = stepper.energy();
    double previous = e0, worst = 0.0;
    int contactSteps = 0;
    for (int n = 1; n <= 10000; ++n) {
        const double t = n * 2e-5;
        const ConservingState before = stepper.state();
        stepper.step(0.01 * std::sin(2 * M_PI * 5 * t), 100.0 * std::sin(2 * M_PI * 3 * t));
        const ConservingState& after = stepper.state();
        const double e = stepper.energy();
        const double balance =
            (e - previous) - (after.energyInput - before.energyInput) + (after.energyDamped - before.energyDamped);
        worst = std::max(worst, std::abs(balance));
        contactSteps += after.contactRows > 0;
        previous = e;
    }
    EXPECT_GT(contactSteps, 50);
    // 1e-13 of the step's energies per step (the gradient's tolerance), E0 ~ 100 J.
    EXPECT_LE(worst, 1e-10 * e0);
}
