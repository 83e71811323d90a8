// time_scheme = flow with its contact steps in the rows that can touch (docs/theory.md §24),
// against the same law in every row, where the row space can fail: several rows entering and
// leaving inside one step, a release and an onset in one step, both obstacles in one step, damping
// on, a load ramp, both elements, a small and a large step. In each case the ledger closes every
// step (T.17d), no row ends a step past an obstacle, and corner_1 agrees with the every-row run to
// roundoff amplified over a short horizon (the two runs differ in the order of their sums only).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "fe/Assembly.h"
#include "fe/SingularMass.h"
#include "plate/CondensedPlate.h"
#include "plate/PlateParameters.h"
#include "schemes/FlowScheme.h"

using namespace plate;

namespace {

std::shared_ptr<const CondensedPlate> condensedPlate(ElementType element, int nx, int ny) {
    PlateParameters p;
    const auto space = makeSpace(element, Mesh(p.mesh.length, p.mesh.width, nx, ny));
    PlateMatrices m = assemble(*space, p.material);
    const SingularMass s = assembleSingularMass(*space, p.material.surfaceDensity(), MassProjection::P0);
    m.mass = s.mass;
    m.massMoment = s.massMoment;
    const ClampedPlate clamped = clamp(*space, m);
    return std::make_shared<const CondensedPlate>(condense(clamped, freeRows(s.root, clamped), {}, 0));
}

struct Case {
    const char* name;
    ElementType element;
    int nx, ny;
    double dt, gap, damping, loadRamp;  // obstacles at ±gap (gap < 0: the lower one only, at gap)
    int steps;
    double frequency = 20.0;  // of the base, Hz
    bool both = false;  // a step with rows on both obstacles is expected
    bool events = true;  // several rows entering or leaving in one step, and a release with an onset
};

// What happened in a run: the worst ledger residual per step against the largest energy, the
// lowest margin to an obstacle at a step's end, corner_1 at every step, and the events counted.
struct FlowRun {
    double worstLedger = 0.0, energyMax = 0.0, worstPenetration = 0.0;
    std::vector<double> corner;
    int multiOnset = 0, multiRelease = 0, releaseAndOnset = 0, bothObstacles = 0;
    long long rowSpaceSteps = 0, retries = 0;
};

FlowRun run(const std::shared_ptr<const CondensedPlate>& plate, const Case& k, bool rowSpace, int substeps = 16) {
    Obstacles obstacles;
    obstacles.lower = k.gap > 0 ? -k.gap : k.gap;
    if (k.gap > 0) obstacles.upper = k.gap;
    LawParameters law;
    law.dt = k.dt;
    law.dampingMass = k.damping;
    law.dampingStiffness = 1e-6 * k.damping;
    FlowScheme scheme(plate, obstacles, law, ContactRefinement{substeps, 0.0, 128, rowSpace});
    scheme.initialize(0.0, 8600.0);  // held on the lower obstacle by the initial load, then released
    scheme.setLoadAtStart(0.0);
    FlowRun r;
    double previous = scheme.energy();
    for (int n = 1; n <= k.steps; ++n) {
        const double t = n * k.dt;
        const CondensedState before = scheme.state();
        // The base at 20 Hz, half the gap; the load ramps (Pa/s).
        scheme.step(0.5 * std::abs(k.gap) * std::sin(2 * M_PI * k.frequency * t), k.loadRamp * t);
        const CondensedState& after = scheme.state();
        const double e = scheme.energy();
        r.energyMax = std::max(r.energyMax, std::abs(e));
        r.worstLedger = std::max(r.worstLedger, std::abs((e - previous) - (after.energyInput - before.energyInput) +
                                                         (after.energyDamped - before.energyDamped)));
        previous = e;
        int onsets = 0, releases = 0;
        bool lower = false, upper = false;
        for (std::size_t i = 0; i < after.rowState.size(); ++i) {
            onsets += before.rowState[i] == 0 && after.rowState[i] != 0;
            releases += before.rowState[i] != 0 && after.rowState[i] == 0;
            lower = lower || after.rowState[i] < 0;
            upper = upper || after.rowState[i] > 0;
        }
        r.multiOnset += onsets >= 2;
        r.multiRelease += releases >= 2;
        r.releaseAndOnset += onsets > 0 && releases > 0;
        r.bothObstacles += lower && upper;
        for (int i = 0; i < plate->rows(); ++i) {
            const double h = scheme.rowHeight(i);
            r.worstPenetration = std::max({r.worstPenetration, obstacles.lower - h, h - obstacles.upper});
        }
        r.corner.push_back(scheme.rowHeight(plate->rows() - 1));
    }
    r.rowSpaceSteps = scheme.rowSpaceSteps();
    r.retries = scheme.rowSpaceRetries();
    return r;
}

class RowSpace : public ::testing::TestWithParam<Case> {};

TEST_P(RowSpace, AgreesWithEveryRowAndClosesTheLedger) {
    const Case k = GetParam();
    const auto plate = condensedPlate(k.element, k.nx, k.ny);
    const FlowRun rows = run(plate, k, true), every = run(plate, k, false), finer = run(plate, k, false, 32);
    EXPECT_GT(rows.rowSpaceSteps, 10) << "the row space was not exercised";
    EXPECT_EQ(every.rowSpaceSteps, 0);
    for (const FlowRun* r : {&rows, &every}) {
        // 1e-13 of the step's energies per step (the discrete gradient's tolerance): 1e-10 of the largest.
        EXPECT_LE(r->worstLedger, 1e-10 * r->energyMax);
        EXPECT_LE(r->worstPenetration, 1e-12);  // on the obstacle up to the roundoff of y = r + D λ
    }
    // Contact events where the row space can fail happened in this run.
    if (k.events) {
        EXPECT_GT(rows.multiOnset, 0);
        EXPECT_GT(rows.multiRelease, 0);
        EXPECT_GT(rows.releaseAndOnset, 0);
    }
    if (k.both) EXPECT_GT(rows.bothObstacles, 0);
    // The two runs take the same sub-steps with other sums: their corners part by roundoff that the
    // impacts amplify (measured: a tenth of the law's own error, or less). It must stay below the
    // law's own error, which the every-row run at twice the sub-steps measures: a third of it, so
    // that the row space adds at most a third to the error a user gets.
    double parting = 0.0, error = 0.0;
    for (std::size_t n = 0; n < rows.corner.size(); ++n) {
        parting = std::max(parting, std::abs(rows.corner[n] - every.corner[n]));
        error = std::max(error, std::abs(finer.corner[n] - every.corner[n]));
    }
    EXPECT_LE(parting, error / 3.0) << "law's own error " << error;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, RowSpace,
    ::testing::Values(Case{"ArgyrisRelease", ElementType::Argyris, 8, 3, 2e-5, 0.02, 0.0, 0.0, 5000},
                      Case{"ArgyrisDampedLoadRamp", ElementType::Argyris, 8, 3, 2e-5, 0.02, 2.0, 2e4, 5000},
                      Case{"FvsRelease", ElementType::Fvs, 8, 3, 2e-5, 0.02, 0.0, 0.0, 5000},
                      Case{"ArgyrisBothObstacles", ElementType::Argyris, 8, 3, 2e-5, 0.002, 0.0, 0.0, 1500, 100.0,
                           true},
                      Case{"FvsBothObstacles", ElementType::Fvs, 8, 3, 2e-5, 0.002, 0.0, 0.0, 1500, 100.0, true},
                      Case{"SmallStep", ElementType::Argyris, 8, 3, 2e-6, 0.02, 0.0, 0.0, 25000, 20.0, false, false},
                      Case{"LargeStep", ElementType::Argyris, 8, 3, 2e-4, 0.02, 1.0, 1e4, 500}),
    [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

}  // namespace
