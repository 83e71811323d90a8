// The stepper as a whole: the two exact engines (sparse factor of A, complete modal basis) run
// the same scheme; the time step does not allocate.
#include <gtest/gtest.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "PlateSimulation.h"

namespace {
std::atomic<bool> counting{false};
std::atomic<long> allocations{0};
}  // namespace
// Out of line, so that a debugger can stop where an allocation is counted: `break plate_counted_allocation`.
extern "C" __attribute__((noinline)) void plate_counted_allocation() {
    allocations.fetch_add(1, std::memory_order_relaxed);
}
namespace {
void count() {
    if (counting.load(std::memory_order_relaxed)) plate_counted_allocation();
}
}  // namespace

// Count every heap allocation while `counting` is on: malloc itself, so that Eigen's (std::malloc),
// operator new's (it calls malloc) and CHOLMOD's are all seen. glibc's own entry points do the work.
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void* malloc(std::size_t size) {
    count();
    return __libc_malloc(size);
}
void* calloc(std::size_t n, std::size_t size) {
    count();
    return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t size) {
    count();
    return __libc_realloc(p, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) {
    count();
    return __libc_memalign(alignment, size);
}
int posix_memalign(void** p, std::size_t alignment, std::size_t size) {
    count();
    *p = __libc_memalign(alignment, size);
    return *p || size == 0 ? 0 : ENOMEM;
}
}

namespace {

plate::InputSignal sine(double amplitude, double frequency, double t) {
    const double w = 2.0 * M_PI * frequency;
    return {amplitude * std::sin(w * t), amplitude * w * std::cos(w * t), -amplitude * w * w * std::sin(w * t)};
}

void run(plate::PlateSimulation& sim, long long steps, long long perComm = 10) {
    for (long long k = 0; k < steps; k += perComm)
        sim.advance(perComm, sine(0.09, 10.0, sim.time()), plate::InputSignal{});
}

}  // namespace

TEST(Stepper, SparseAndModalEnginesRunTheSameScheme) {
    plate::PlateParameters p;
    p.law.engine = plate::LawParameters::Engine::SparseFactor;
    plate::PlateSimulation sparse(p, 0.0);
    p.law.engine = plate::LawParameters::Engine::CompleteModal;
    plate::PlateSimulation modal(p, 0.0);
    ASSERT_EQ(sparse.engine(), "sparse");
    ASSERT_EQ(modal.engine(), "modal-complete");
    // Before the first impact (t < 0.049 s on this scene) the two are one linear recurrence in
    // two bases. The dense eigen solution is exact to eps·λ_max in each eigenvalue, i.e.
    // 1e-16 · 1.4e12 / 1.4e3 ≈ 1e-7 relative on λ_1; the phase drift by 0.045 s is then at most
    // 1e-7 · ω_1 t ≈ 2e-8 rad: ≤ 3e-9 m at this 0.1 m amplitude (observed ~1e-10 m).
    for (int block = 0; block < 45; ++block) {
        run(sparse, 100);
        run(modal, 100);
        ASSERT_EQ(sparse.outputs().contactVertices, 0);
        const double a = sparse.outputs().corner1, b = modal.outputs().corner1;
        EXPECT_NEAR(a, b, 3e-9) << "t = " << sparse.time();
        EXPECT_NEAR(sparse.outputs().energy, modal.outputs().energy, 1e-7 * std::abs(sparse.outputs().energy));
    }
}

// The steps from `sim`'s state over `steps` steps, taken twice: once to compute what a first use computes
// (the paper's law computes a vertex's contact columns when it first touches, once: BoxQP.h), then
// again from the same state, counted.
long allocationsOfSteps(plate::PlateSimulation& sim, long long steps) {
    const std::vector<double> start = sim.saveState();
    run(sim, steps);
    sim.restoreState(start);
    allocations = 0;
    counting = true;
    run(sim, steps);
    counting = false;
    return allocations.load();
}

TEST(Stepper, TimeStepDoesNotAllocate) {
    // Both engines with the paper's scheme, then the laws of docs/theory.md §11–13 (restitution
    // and damping on the modal engine, the singular mass on the sparse one, all three at once).
    using Engine = plate::LawParameters::Engine;
    struct Case {
        Engine engine;
        plate::MassModel mass;
        double e, a, b;
    };
    for (const Case c : {Case{Engine::SparseFactor, plate::MassModel::Consistent, 0, 0, 0},
                         Case{Engine::CompleteModal, plate::MassModel::Consistent, 0, 0, 0},
                         Case{Engine::CompleteModal, plate::MassModel::Consistent, 0.5, 2.0, 1e-5},
                         Case{Engine::SparseFactor, plate::MassModel::SingularP0, 0.5, 2.0, 1e-5}}) {
        plate::PlateParameters p;
        p.law.engine = c.engine;
        p.law.mass = c.mass;
        p.law.restitution = c.e;
        p.law.dampingMass = c.a;
        p.law.dampingStiffness = c.b;
        plate::PlateSimulation sim(p, 0.0);
        run(sim, 6000);  // the first impact near 0.05 s
        const long long before = static_cast<long long>(sim.outputs().contactSolves);
        const double onsetsBefore[2] = {sim.outputs().contactOnsets[0], sim.outputs().contactOnsets[1]};
        ASSERT_GT(before, 0) << sim.engine();
        // 7,500 steps (0.06–0.135 s): the lower obstacle's contacts (~0.075–0.10 s) and the upper's
        // (~0.12–0.13 s), free flight before, between and after; 10,000 steps (to 0.16 s) added
        // 2,500 free steps, the path of the first 1,500.
        EXPECT_EQ(allocationsOfSteps(sim, 7500), 0) << sim.engine();
        EXPECT_GT(static_cast<long long>(sim.outputs().contactSolves), before) << sim.engine();
        for (int k = 0; k < 2; ++k)  // both obstacles touched in the counted steps
            EXPECT_GT(sim.outputs().contactOnsets[k], onsetsBefore[k]) << sim.engine() << ", obstacle " << k;
    }
}

// The condensed laws (docs/theory.md §17, §21–22, §24): 10⁴ steps of the default scene after its
// first impact, through a dozen more impacts (taken twice: the second time counted). The flow
// law's contact steps run in the rows that can touch with buffers of every row's size (§24), with a
// tolerance too (its step doubling and companion runs).
TEST(Stepper, CondensedLawsStepWithoutAllocating) {
    struct Case {
        const char* name;
        plate::TimeScheme scheme;
        double tolerance;
        int modes;
    };
    for (const Case c :
         {Case{"conserving", plate::TimeScheme::Conserving, 0.0, 0}, Case{"flow", plate::TimeScheme::Flow, 0.0, 0},
          Case{"flow m=20", plate::TimeScheme::Flow, 0.0, 20},
          Case{"flow tolerance", plate::TimeScheme::Flow, 1e-5, 0}}) {
        plate::PlateParameters p;
        p.law.mass = plate::MassModel::SingularP0;
        p.law.timeScheme = c.scheme;
        p.refinement.tolerance = c.tolerance;
        p.law.modes = c.modes;
        plate::PlateSimulation sim(p, 0.0);
        run(sim, 6000);  // the first impact near 0.05 s
        const long long before = static_cast<long long>(sim.outputs().contactSolves);
        ASSERT_GT(before, 0) << c.name;
        EXPECT_EQ(allocationsOfSteps(sim, 10000), 0) << c.name;
        EXPECT_GT(static_cast<long long>(sim.outputs().contactSolves), before) << c.name;
    }
}
