// discretization_check (solver/DiscretizationCheck.h, docs/theory.md §26): the plate's results are
// the same bits with the check on; the estimate is Richardson's factor times the largest difference
// from the companion, which is the coarsened plate (2 Δt) run alone, until the check says it cannot
// hold, and from then on the bound (the range the points swept on either mesh, the obstacles' gap);
// a state restored into a fresh
// simulation continues bit for bit, the estimate included; meshes of one cell and carried clamps
// are refused with the allowed range.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "CheckedPlate.h"
#include "DiscretizationCheck.h"
#include "base/Errors.h"

namespace plate {
namespace {

PlateParameters contactScene(bool check) {
    PlateParameters p;
    p.mesh.nx = 8, p.mesh.ny = 3;  // the companion: 4 × 2
    p.obstacles.lower = -0.01, p.obstacles.upper = 0.01;
    p.law.mass = MassModel::SingularP0, p.law.timeScheme = TimeScheme::Flow;
    p.outputs.discretizationCheck = check;
    return p;
}

InputSignal sine(double t) {
    const double a = 0.008, w = 2.0 * M_PI * 25.0;
    return {a * std::sin(w * t), a * w * std::cos(w * t), -a * w * w * std::sin(w * t)};
}

struct Record {
    std::vector<double> points;  // corner_1, corner_2, free_edge_mid after every communication step
    std::vector<double> estimates;  // discretization_error after every communication step
    std::vector<bool> said;  // whether the check had said it cannot hold, after every step
    double estimate = 0.0;
};

// 30 communication steps of 1e-4 s, then `more` of 2.5e-5 s (between grid points when dt does not divide them).
Record run(CheckedPlate& s, int steps, int first = 0) {
    Record r;
    for (int k = first; k < first + steps; ++k) {
        const double h = k % 3 == 2 ? 2.5e-4 : 1e-4;
        s.communicate(s.plan(h), sine(s.time()), InputSignal{});
        const PlateOutputs o = s.outputs();
        r.points.insert(r.points.end(), {o.corner1, o.corner2, o.freeEdgeMid});
        r.estimate = o.discretizationError;
        r.estimates.push_back(o.discretizationError);
        r.said.push_back((r.said.empty() ? false : bool(r.said.back())) || !s.takeDiscretizationWarning().empty());
    }
    return r;
}

TEST(DiscretizationCheck, ThePlateIsTheSameBitsAndTheEstimateIsRichardsonsFactorThenTheBound) {
    CheckedPlate plain(contactScene(false), 0.0), checked(contactScene(true), 0.0);
    CheckedPlate companion(DiscretizationCheck::companionParameters(contactScene(true)), 0.0);  // no check of its own
    EXPECT_EQ(companion.parameters().mesh.nx, 4);
    EXPECT_EQ(companion.parameters().mesh.ny, 2);
    EXPECT_EQ(companion.parameters().law.dt, 2.0 * contactScene(true).law.dt);
    const Record a = run(plain, 120), b = run(checked, 120), c = run(companion, 120);
    EXPECT_EQ(a.points, b.points);  // bit for bit
    EXPECT_EQ(a.estimate, 0.0);
    // r = 2 in each direction with nx, ny = 8, 3 → 4, 2: sqrt(24/8) = sqrt(3); p̂ of theory (T.26b)
    const double factor = 1.0 / (std::pow(std::sqrt(3.0), DiscretizationCheck::kAssumedOrder) - 1.0);
    // The points' range starts at the companion's start (the check's constructor).
    const PlateOutputs s0 = PlateSimulation(companion.parameters(), 0.0).outputs();
    std::vector<double> lowest{s0.corner1, s0.corner2, s0.freeEdgeMid}, highest = lowest;
    double largest = 0.0;
    std::size_t before = 0, after = 0;
    for (std::size_t k = 0; k < b.estimates.size(); ++k) {
        double swept = 0.0;
        for (std::size_t i = 3 * k; i < 3 * k + 3; ++i) {
            largest = std::max(largest, std::fabs(b.points[i] - c.points[i]));
            lowest[i % 3] = std::min({lowest[i % 3], b.points[i], c.points[i]});
            highest[i % 3] = std::max({highest[i % 3], b.points[i], c.points[i]});
            swept = std::max(swept, highest[i % 3] - lowest[i % 3]);
        }
        // The companion inside the check steps to the plate's time (h from the two times), the one
        // alone by the step sizes themselves: the same up to the times' last bits.
        const double expected = b.said[k] ? std::max({factor * largest, swept, 0.02}) : factor * largest;
        EXPECT_NEAR(b.estimates[k], expected, 1e-9 * std::max(expected, 1e-12)) << "step " << k;
        ++(b.said[k] ? after : before);
    }
    ASSERT_GT(largest, 1e-5);  // the scene reaches the obstacles: the meshes differ visibly
    EXPECT_GT(before, 0u);  // both regimes were met: the scene parts within 120 steps
    EXPECT_GT(after, 0u);
}

TEST(DiscretizationCheck, TheCompanionOfAModalPlateIsOnTheCompleteBasis) {
    // A truncated plate's error is mostly the modes it drops; a companion on fewer modes drops them too
    // (on 4 modes at the fourth bending mode: 0.16 of the error, issue 73): it keeps every mode of its
    // mesh, whatever the plate's `modes` (theory §26, "A truncated modal basis").
    for (const int modes : {1, 2, 4, 40}) {
        PlateParameters p = contactScene(true);
        p.law.modes = modes;
        const PlateParameters c = DiscretizationCheck::companionParameters(p);
        EXPECT_EQ(c.law.modes, 0) << modes;
        EXPECT_EQ(c.mesh.nx, 4);
        EXPECT_EQ(c.mesh.ny, 2);
    }
}

TEST(DiscretizationCheck, AStateRestoredIntoAFreshSimulationContinuesBitForBit) {
    CheckedPlate first(contactScene(true), 0.0);
    run(first, 40);
    const std::vector<double> state = first.saveState();
    const Record goOn = run(first, 40, 40);
    CheckedPlate fresh(contactScene(true), 0.0);
    fresh.restoreState(state);
    const Record restored = run(fresh, 40, 40);
    EXPECT_EQ(goOn.points, restored.points);
    EXPECT_EQ(goOn.estimate, restored.estimate);
    // A state of a run without the check is not this plate's.
    CheckedPlate unchecked(contactScene(false), 0.0);
    EXPECT_THROW(fresh.restoreState(unchecked.saveState()), std::invalid_argument);
}

TEST(DiscretizationCheck, RefusesMeshesOfOneCellAndCarriedClamps) {
    PlateParameters p = contactScene(true);
    p.mesh.ny = 1;
    try {
        CheckedPlate s(p, 0.0);
        FAIL() << "a mesh of one cell across was accepted";
    } catch (const ParameterError& e) {
        EXPECT_NE(std::string(e.what()).find("nx >= 2 and ny >= 2"), std::string::npos) << e.what();
    }
    p = PlateParameters{};
    p.outputs.discretizationCheck = true;
    p.carrier = PlateParameters::Carrier::Armature;
    EXPECT_THROW(CheckedPlate(p, 0.0), ParameterError);
}

}  // namespace
}  // namespace plate
