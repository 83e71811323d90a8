// The discretization cache (solver/plate/DiscretizationCache.h): an instance that shares a cached
// plate gives the results of one that built its own, bit for bit; 32 instances in 8 threads give
// those of serial runs; a key that differs is not shared; the budget bounds what is kept.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "PlateSimulation.h"
#include "plate/DiscretizationCache.h"

namespace plate {
namespace {

// The budget for one scope (PLATEIMPACT_CACHE_MB is read at every lookup).
class CacheBudget {
public:
    explicit CacheBudget(const char* mb) { setenv("PLATEIMPACT_CACHE_MB", mb, 1); }
    ~CacheBudget() { unsetenv("PLATEIMPACT_CACHE_MB"); }
};

// One of each cached kind: the default plate (complete modal basis), a reduced basis with β < ¼
// (κ_h), the sparse factor (not cached: its own per instance), the conserving and flow laws on
// the condensed plate (with a probe, so that the recovery rows are part of the key).
PlateParameters scene(int kind, double gap) {
    PlateParameters p;
    p.obstacles.lower = -gap;
    p.obstacles.upper = gap;
    switch (kind % 5) {
        case 0: break;
        case 1: p.mesh.nx = 8, p.mesh.ny = 3, p.law.modes = 12, p.law.beta = 0.2, p.law.dt = 5e-6; break;
        case 2: p.mesh.nx = 6, p.mesh.ny = 2, p.law.engine = LawParameters::Engine::SparseFactor; break;
        case 3:
            p.mesh.nx = 8, p.mesh.ny = 3, p.law.mass = MassModel::SingularP0, p.law.timeScheme = TimeScheme::Conserving;
            break;
        default:
            p.mesh.nx = 8, p.mesh.ny = 3, p.law.mass = MassModel::SingularP1dg, p.law.timeScheme = TimeScheme::Flow;
            p.outputs.probeX = {1.0}, p.outputs.probeY = {0.3}, p.outputs.stressOutputs = true;
            break;
    }
    return p;
}

// A run into contact: the base 0.015 sin(2π f t) m between obstacles at ±gap, every output and
// the final state as one vector of doubles.
std::vector<double> run(const PlateParameters& p, double frequency, int steps = 600) {
    PlateSimulation s(p, 0.0);
    std::vector<double> out;
    const double w = 2.0 * M_PI * frequency;
    for (int k = 0; k < steps / 100; ++k) {
        const double t = s.time();
        InputSignal base{0.015 * std::sin(w * t), 0.015 * w * std::cos(w * t), -0.015 * w * w * std::sin(w * t)};
        s.advance(100, base, InputSignal{});
        const PlateOutputs o = s.outputs(true, FieldOutputs::Plate);
        const double probe = p.outputs.probeCount() > 0 ? s.probes().displacement[0] : 0.0;
        out.insert(out.end(), {o.corner1, o.corner2, o.freeEdgeMid, o.energy, o.clampForce, o.rootStress, probe,
                               o.maxStress, o.contactVertices});
    }
    const std::vector<double> state = s.saveState();
    out.insert(out.end(), state.begin(), state.end());
    return out;
}

bool bitIdentical(const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

TEST(DiscretizationCache, SharedPlateGivesTheBuiltOnesResultsBitForBit) {
    for (int kind = 0; kind < 5; ++kind) {
        const PlateParameters p = scene(kind, 0.02);
        std::vector<double> alone;
        {
            CacheBudget off("0");
            alone = run(p, 25.0);
        }
        clearDiscretizationCache();
        const std::vector<double> first = run(p, 25.0);  // builds and keeps
        const CacheStatistics before = discretizationCacheStatistics();
        const std::vector<double> second = run(p, 25.0);  // shares
        const CacheStatistics after = discretizationCacheStatistics();
        EXPECT_EQ(after.builds, before.builds) << "kind " << kind << ": the second instance built something";
        EXPECT_GE(after.hits - before.hits, 2) << "kind " << kind;  // the space and the clamped plate, at least
        EXPECT_TRUE(bitIdentical(alone, first)) << "kind " << kind;
        EXPECT_TRUE(bitIdentical(alone, second)) << "kind " << kind;
    }
}

TEST(DiscretizationCache, ThirtyTwoInstancesInEightThreadsGiveSerialResults) {
    constexpr int kInstances = 32, kThreads = 8;
    auto scenePoint = [](int i) { return std::make_pair(scene(i, 0.02 + 0.002 * (i % 3)), 15.0 + i); };
    std::vector<std::vector<double>> serial(kInstances), threaded(kInstances);
    for (int i = 0; i < kInstances; ++i) serial[i] = run(scenePoint(i).first, scenePoint(i).second);
    clearDiscretizationCache();  // the threads race to build every entry
    const CacheStatistics before = discretizationCacheStatistics();
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t)
        threads.emplace_back([&, t] {
            for (int i = t; i < kInstances; i += kThreads) threaded[i] = run(scenePoint(i).first, scenePoint(i).second);
        });
    for (auto& thread : threads) thread.join();
    const CacheStatistics after = discretizationCacheStatistics();
    for (int i = 0; i < kInstances; ++i) EXPECT_TRUE(bitIdentical(serial[i], threaded[i])) << "instance " << i;
    // Each distinct key built once, however many threads asked for it (the gaps change no key): 3
    // spaces (14 x 5, 8 x 3, 6 x 2), 5 clamped plates, 2 modal bases and the complete one the
    // reduced one takes its modes from, κ_h, 2 condensed plates.
    EXPECT_EQ(after.builds - before.builds, 14);
}

// A sweep over `modes` (Newmark's bases of one plate): one dense eigen solution, the complete basis,
// whose leading columns each reduced basis takes — the results those of instances that solved for
// their own, bit for bit.
TEST(DiscretizationCache, BasesOfOnePlateShareOneEigenSolution) {
    PlateParameters p = scene(1, 0.02);
    const int counts[3] = {12, 30, 0};  // 0: the complete basis
    std::vector<std::vector<double>> alone;
    for (int modes : counts) {
        CacheBudget off("0");
        p.law.modes = modes;
        alone.push_back(run(p, 25.0));
    }
    clearDiscretizationCache();
    long long builds[3], hits[3];
    for (int k = 0; k < 3; ++k) {
        p.law.modes = counts[k];
        const CacheStatistics before = discretizationCacheStatistics();
        EXPECT_TRUE(bitIdentical(alone[std::size_t(k)], run(p, 25.0))) << "modes " << counts[k];
        builds[k] = discretizationCacheStatistics().builds - before.builds;
        hits[k] = discretizationCacheStatistics().hits - before.hits;
    }
    EXPECT_EQ(hits[2], 4);  // the space, the clamped plate, the complete basis, κ_h
    // The first: the space, the clamped plate, the complete basis, its own, κ_h; the second: its own
    // basis only; the complete one: nothing.
    EXPECT_EQ(builds[0], 5);
    EXPECT_EQ(builds[1], 1);
    EXPECT_EQ(builds[2], 0);
}

TEST(DiscretizationCache, ADifferentPlateIsNotShared) {
    clearDiscretizationCache();
    PlateParameters p = scene(1, 0.02);
    (void)run(p, 20.0, 100);
    const CacheStatistics before = discretizationCacheStatistics();
    p.material.thickness *= 0.9;  // the same space, other matrices: everything but the space is built again
    const std::vector<double> thicker = run(p, 20.0, 100);
    const CacheStatistics after = discretizationCacheStatistics();
    EXPECT_EQ(after.hits - before.hits, 1);
    EXPECT_EQ(after.builds - before.builds, 4);  // the clamped plate, the complete basis, the reduced one, κ_h
    CacheBudget off("0");
    EXPECT_TRUE(bitIdentical(thicker, run(p, 20.0, 100)));
}

// Every parameter a key holds, changed one at a time after the unchanged plate was cached: the
// instance gives what one built alone gives (a parameter missing from its key would hand it the
// cached plate of the old value). A mutation check of the keys: drop one from
// DiscretizationCache.cpp and its line fails.
TEST(DiscretizationCache, EveryKeyParameterChangesTheResult) {
    using Change = void (*)(PlateParameters&);
    const std::vector<std::pair<const char*, Change>> changes = {
        {"element", [](PlateParameters& p) { p.mesh.element = ElementType::Fvs; }},
        {"length", [](PlateParameters& p) { p.mesh.length *= 1.1; }},
        {"width", [](PlateParameters& p) { p.mesh.width *= 1.1; }},
        {"nx", [](PlateParameters& p) { p.mesh.nx += 1; }},
        {"ny", [](PlateParameters& p) { p.mesh.ny += 1; }},
        {"thickness", [](PlateParameters& p) { p.material.thickness *= 0.9; }},
        {"youngsModulus", [](PlateParameters& p) { p.material.youngsModulus *= 0.9; }},
        {"poissonRatio", [](PlateParameters& p) { p.material.poissonRatio = 0.25; }},
        {"density", [](PlateParameters& p) { p.material.density *= 1.1; }},
        {"dt", [](PlateParameters& p) { p.law.dt *= 0.5; }},
        {"beta", [](PlateParameters& p) { p.law.beta = 0.3; }},
        {"modes", [](PlateParameters& p) { p.law.modes += 2; }},
        {"dampingMass", [](PlateParameters& p) { p.law.dampingMass = 3.0; }},
        {"dampingStiffness", [](PlateParameters& p) { p.law.dampingStiffness = 1e-5; }},
    };
    for (int kind : {1, 3, 4}) {  // Newmark's reduced modal basis, the conserving and flow laws
        for (const auto& [name, change] : changes) {
            PlateParameters p = scene(kind, 0.02);
            if (kind == 4 && std::string(name) == "element") continue;  // P1dg's mass is Argyris's only
            if (kind != 1 && std::string(name) == "beta") continue;  // the condensed laws refuse beta
            clearDiscretizationCache();
            (void)run(p, 20.0, 100);  // the unchanged plate, cached
            change(p);
            const std::vector<double> changed = run(p, 20.0, 200);
            CacheBudget off("0");
            EXPECT_TRUE(bitIdentical(changed, run(p, 20.0, 200))) << "kind " << kind << ", " << name;
        }
    }
    // The condensed plate's recovery rows: a probe moved.
    PlateParameters p = scene(4, 0.02);
    clearDiscretizationCache();
    (void)run(p, 20.0, 100);
    p.outputs.probeX[0] = 0.7;
    const std::vector<double> moved = run(p, 20.0, 200);
    CacheBudget off("0");
    EXPECT_TRUE(bitIdentical(moved, run(p, 20.0, 200))) << "probe_1_x";
}

TEST(DiscretizationCache, TheBudgetBoundsWhatIsKept) {
    clearDiscretizationCache();
    CacheBudget small("1");  // 1 MB: the default plate's modal basis (4.3 MB) is not kept
    (void)run(scene(0, 0.02), 20.0, 100);
    const CacheStatistics kept = discretizationCacheStatistics();
    EXPECT_LE(kept.bytes, std::size_t(1) << 20);
    EXPECT_GE(kept.evictions, 1);
    const CacheStatistics before = discretizationCacheStatistics();
    (void)run(scene(0, 0.02), 20.0, 100);
    EXPECT_GE(discretizationCacheStatistics().builds - before.builds, 1);  // the basis built again
}

}  // namespace
}  // namespace plate
