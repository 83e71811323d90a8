// Stops (docs/theory.md §25): an obstacle that covers a rectangle of the plate holds the contact
// points inside it and nothing else. The scene of issue 52: a lower stop under the tip (x ≥ 1.0 m
// of the 1.2 m plate) at −0.05 m, the upper obstacle off, the default drive 0.09 sin(2π·10 t) m.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "PlateSimulation.h"
#include "base/Errors.h"
#include "fe/Mesh.h"

namespace {

using plate::PlateParameters;

constexpr double kStop = -0.05, kTipFrom = 1.0;
// Roundoff of z + w at a vertex held on the stop (docs/stability.md measures ≤ 1e-15 m for the
// whole-plate obstacles); 1e-12 m leaves three orders for the longer run and the condensed rows.
constexpr double kPenetration = 1e-12;

plate::InputSignal stopSceneBase(double t) {
    const double a = 0.09, w = 2.0 * M_PI * 10.0;
    return {a * std::sin(w * t), a * w * std::cos(w * t), -a * w * w * std::sin(w * t)};
}

enum class Law { Newmark, Conserving, Flow };

PlateParameters tipStop(Law law, plate::ElementType element) {
    PlateParameters p;
    p.mesh.element = element;
    if (element == plate::ElementType::Fvs) p.mesh.nx = 20, p.mesh.ny = 7;  // the paper's FVS mesh
    p.obstacles.lower = kStop;
    p.obstacles.upperEnabled = false;
    p.obstacles.lowerStop.xMin = kTipFrom;
    if (law != Law::Newmark) p.law.mass = plate::MassModel::SingularP0;
    if (law == Law::Conserving) p.law.timeScheme = plate::TimeScheme::Conserving;
    if (law == Law::Flow) p.law.timeScheme = plate::TimeScheme::Flow;
    p.outputs.probeX = {0.6};
    p.outputs.probeY = {0.2};
    return p;
}

struct LawCase {
    Law law;
    plate::ElementType element;
    const char* name;
};

class TipStop : public ::testing::TestWithParam<LawCase> {};

// Every contact point under the stop stays at or above it (to roundoff) at every communication
// step, while the probe at (0.6, 0.2), off the stop, passes below its height: the stop holds only
// where it is. The run must hit the stop (onsets) for the first claim to say anything.
TEST_P(TipStop, HoldsTheVerticesUnderItAndNoOthers) {
    const LawCase c = GetParam();
    const PlateParameters p = tipStop(c.law, c.element);
    plate::PlateSimulation sim(p, stopSceneBase(0.0).value);
    const plate::Mesh mesh(p.mesh.length, p.mesh.width, p.mesh.nx, p.mesh.ny);
    std::vector<int> under;
    for (int v = 0; v < mesh.vertexCount(); ++v)
        if (mesh.point(v).x() >= kTipFrom - 1e-12) under.push_back(v);
    ASSERT_GT(under.size(), 0u);
    double lowestUnder = INFINITY, lowestProbe = INFINITY;
    for (int k = 0; k < 10000; ++k) {  // 1 s in communication steps of 1e-4 s
        sim.advance(10, stopSceneBase(sim.time()), plate::InputSignal{});
        const std::vector<double> u = sim.vertexDisplacements();
        for (int v : under) lowestUnder = std::min(lowestUnder, u[std::size_t(v)]);
        lowestProbe = std::min(lowestProbe, sim.probes().displacement[0]);
    }
    const plate::PlateOutputs o = sim.outputs(true);
    EXPECT_GT(o.contactOnsets[0], 0) << c.name << ": the stop was never hit";
    EXPECT_GE(lowestUnder, kStop - kPenetration) << c.name;
    // The middle of the plate is under no stop: it passes below the stop's height.
    EXPECT_LT(lowestProbe, kStop) << c.name;
    EXPECT_EQ(o.contactOnsets[1], 0) << c.name << ": the upper obstacle is off";
}

INSTANTIATE_TEST_SUITE_P(Laws, TipStop,
                         ::testing::Values(LawCase{Law::Newmark, plate::ElementType::Argyris, "newmark argyris"},
                                           LawCase{Law::Newmark, plate::ElementType::Fvs, "newmark fvs"},
                                           LawCase{Law::Conserving, plate::ElementType::Argyris, "conserving argyris"},
                                           LawCase{Law::Flow, plate::ElementType::Argyris, "flow argyris"},
                                           LawCase{Law::Flow, plate::ElementType::Fvs, "flow fvs"}),
                         [](const ::testing::TestParamInfo<LawCase>& info) {
                             std::string name = info.param.name;
                             std::replace(name.begin(), name.end(), ' ', '_');
                             return name;
                         });

// The energy identity (T.17d) of the conserving and flow laws holds step by step with the stop:
// E_{n+1} − E_n = (work put in) − (damped) − (dissipated) to 1e-10 of the energy scale per step
// (the discrete gradient is iterated to 1e-13 of the step's energies, docs/theory.md §17).
TEST(TipStopEnergy, ClosesEveryStepForTheConservingLaws) {
    for (Law law : {Law::Conserving, Law::Flow}) {
        PlateParameters p = tipStop(law, plate::ElementType::Argyris);
        p.law.modes = law == Law::Conserving ? 40 : 0;  // a reduced model too (modes)
        plate::PlateSimulation sim(p, 0.0);
        double previous = 0.0, scale = std::abs(sim.outputs().energy), worst = 0.0;
        const double e0 = sim.outputs().energy;
        long long contactSteps = 0;
        for (int n = 0; n < 20000; ++n) {  // 0.2 s, one internal step at a time
            sim.advance(1, stopSceneBase(sim.time()), plate::InputSignal{});
            const plate::PlateOutputs o = sim.outputs();
            scale = std::max({scale, std::abs(o.energy), std::abs(o.energyInput)});
            const double residual = o.energy - e0 - o.energyInput + o.energyDamped + o.energyDissipated;
            worst = std::max(worst, std::abs(residual - previous));
            previous = residual;
            contactSteps += o.contactVertices > 0;
        }
        EXPECT_GT(contactSteps, 10) << "the stop must be hit";
        EXPECT_LE(worst, 1e-10 * scale) << (law == Law::Flow ? "flow" : "conserving") << " (scale " << scale << " J)";
    }
}

// A rectangle that covers the plate is the whole plate: the outputs are the default's bit for bit
// (the default rectangle reaches past any plate, this one is the plate exactly).
TEST(WholePlateStop, IsTheDefaultBitForBit) {
    for (Law law : {Law::Newmark, Law::Conserving, Law::Flow}) {
        PlateParameters a = tipStop(law, plate::ElementType::Argyris);
        a.obstacles.lower = -0.1;
        a.obstacles.upperEnabled = true;
        a.obstacles.lowerStop = {};
        PlateParameters b = a;
        b.obstacles.lowerStop = {0.0, b.mesh.length, 0.0, b.mesh.width};
        b.obstacles.upperStop = {0.0, b.mesh.length, 0.0, b.mesh.width};
        plate::PlateSimulation simA(a, 0.0), simB(b, 0.0);
        for (int k = 0; k < 700; ++k) {  // 0.07 s: the first impacts from ≈ 0.05 s on
            simA.advance(10, stopSceneBase(simA.time()), plate::InputSignal{});
            simB.advance(10, stopSceneBase(simB.time()), plate::InputSignal{});
        }
        EXPECT_EQ(simA.saveState(), simB.saveState());
        EXPECT_EQ(simA.vertexDisplacements(), simB.vertexDisplacements());
        EXPECT_GT(simA.outputs().contactOnsets[0] + simA.outputs().contactOnsets[1], 0);
    }
}

// FMU states: a saved state restored continues bit for bit with a stop (the rows are the stop's).
TEST(TipStopState, RestoresBitForBit) {
    for (Law law : {Law::Newmark, Law::Flow}) {
        const PlateParameters p = tipStop(law, plate::ElementType::Argyris);
        plate::PlateSimulation a(p, 0.0), b(p, 0.0);
        for (int k = 0; k < 600; ++k) a.advance(10, stopSceneBase(a.time()), plate::InputSignal{});
        b.restoreState(a.saveState());
        for (int k = 0; k < 600; ++k) {
            a.advance(10, stopSceneBase(a.time()), plate::InputSignal{});
            b.advance(10, stopSceneBase(b.time()), plate::InputSignal{});
        }
        EXPECT_EQ(a.saveState(), b.saveState());
    }
}

std::string refusal(const PlateParameters& p) {
    try {
        plate::validate(p);
    } catch (const plate::ParameterError& e) {
        return e.what();
    }
    return "";
}

// Bad stops are refused at initialization with the allowed range (issue 52, item 5).
TEST(StopValidation, RefusesInvertedOutsideAndEmptyRectangles) {
    PlateParameters p;
    p.obstacles.lowerStop.xMin = 1.1, p.obstacles.lowerStop.xMax = 1.0;
    EXPECT_NE(refusal(p).find("x_min <= x_max"), std::string::npos) << refusal(p);
    p.obstacles.lowerStop = {};
    p.obstacles.upperStop.yMin = 0.5;  // the plate is 0.4 m wide
    EXPECT_NE(refusal(p).find("meets the plate"), std::string::npos) << refusal(p);
    p.obstacles.upperStop = {};
    // Between the vertex columns x = 0.9429 and 1.0286 (14 cells): no contact point; the nearest (0.0171 m off) is named.
    p.obstacles.lowerStop.xMin = 0.96, p.obstacles.lowerStop.xMax = 1.0;
    const std::string empty = refusal(p);
    EXPECT_NE(empty.find("nearest"), std::string::npos) << empty;
    EXPECT_NE(empty.find("(0.942857142857143, 0)"), std::string::npos) << empty;
    // Only at the clamped edge: its vertices move with the clamp, none is a contact point.
    p.obstacles.lowerStop.xMin = 0.0, p.obstacles.lowerStop.xMax = 0.0;
    EXPECT_NE(refusal(p).find("nearest"), std::string::npos) << refusal(p);
    // An absent obstacle's stop is not looked at.
    p.obstacles.lowerEnabled = false;
    EXPECT_EQ(refusal(p), "");
}

}  // namespace
