// What the resource estimate tells the user before the time is spent (ResourceEstimate.h,
// costNotices): a setup of more than ten seconds, a run of more than a minute of CPU per simulated
// second, each with what would make it cheaper; nothing for the default scene. From the mesh alone
// (stage 0, predictFromMesh): nothing is assembled.
#include <gtest/gtest.h>

#include <string>
#include <tuple>
#include <vector>

#include "plate/PlateParameters.h"
#include "plate/ResourceEstimate.h"

using namespace plate;

namespace {

std::vector<std::string> notices(const PlateParameters& p) {
    return costNotices(p, estimateResources(p, predictFromMesh(p)));
}

PlateParameters flow(int nx, int ny, int modes) {
    PlateParameters p;
    p.mesh.nx = nx;
    p.mesh.ny = ny;
    p.law.modes = modes;
    p.law.mass = MassModel::SingularP0;
    p.law.timeScheme = TimeScheme::Flow;
    return p;
}

}  // namespace

TEST(ResourceNotices, TheDefaultSceneHasNone) { EXPECT_TRUE(notices(PlateParameters{}).empty()); }

// The paper's and the examples' scenes say nothing either (the FMU logs these at status Warning,
// which masters show): examples/paper_scenes.py's meshes at its finest dt, the paper's law on the
// default mesh, examples/error_against_the_plate.py's accurate plate and the 56x20 goal.
TEST(ResourceNotices, ThePaperAndExampleScenesHaveNone) {
    std::vector<PlateParameters> scenes;
    for (const auto& [element, nx, ny] :
         {std::tuple{ElementType::Argyris, 14, 5}, {ElementType::Argyris, 16, 5}, {ElementType::Fvs, 20, 7}}) {
        PlateParameters p;
        p.mesh.element = element;
        p.mesh.nx = nx;
        p.mesh.ny = ny;
        p.law.dt = 2.5e-6;
        scenes.push_back(p);
    }
    PlateParameters paperLaw;
    paperLaw.law.mass = MassModel::SingularP0;
    paperLaw.law.timeScheme = TimeScheme::Conserving;
    scenes.push_back(paperLaw);
    scenes.push_back(flow(28, 10, 40));
    scenes.push_back(flow(56, 20, 100));
    for (const PlateParameters& p : scenes) {
        const std::vector<std::string> said = notices(p);
        EXPECT_TRUE(said.empty()) << p.mesh.nx << "x" << p.mesh.ny << ": " << (said.empty() ? "" : said[0]);
    }
}

// 112x40 on 100 modes: ~30 s of setup by the estimate (measured 34-39 s of CPU, docs/performance.md).
TEST(ResourceNotices, ALongSetupSaysSoWithWhatShortensIt) {
    const PlateParameters p = flow(112, 40, 100);
    const ResourceEstimate e = estimateResources(p, predictFromMesh(p));
    ASSERT_GT(e.initSeconds, kLongSetupSeconds);
    const std::vector<std::string> lines = costNotices(p, e);
    ASSERT_FALSE(lines.empty());
    EXPECT_NE(lines[0].find("this initialization will take about"), std::string::npos) << lines[0];
    EXPECT_NE(lines[0].find("modes"), std::string::npos) << lines[0];
    EXPECT_NE(lines[0].find("nx = 112, ny = 40"), std::string::npos) << lines[0];
}

// The cost per simulated second is the step's over dt: a hundred times smaller a step on 56x20
// (1.3e-5 s per step at dt = 1e-7: ~130 s per simulated second) crosses the minute; dt = 1e-5 does not.
TEST(ResourceNotices, ACostlyRunSaysSoOnceWithWhatMakesItCheaper) {
    PlateParameters p = flow(56, 20, 100);
    for (const std::string& line : notices(p)) EXPECT_EQ(line.find("each simulated second"), std::string::npos);
    p.law.dt = 1e-7;
    const ResourceEstimate e = estimateResources(p, predictFromMesh(p));
    ASSERT_GT(e.stepSeconds / p.law.dt, kCostlyRunSeconds);
    int costly = 0;
    for (const std::string& line : costNotices(p, e)) {
        if (line.find("each simulated second will cost") == std::string::npos) continue;
        ++costly;
        EXPECT_NE(line.find("fewer modes"), std::string::npos) << line;
        EXPECT_NE(line.find("obstacle_lower_x_min"), std::string::npos) << line;
        EXPECT_NE(line.find("coarser mesh"), std::string::npos) << line;
    }
    EXPECT_EQ(costly, 1);
}

// The sparse condensation's memory (CondensedSparse.cpp; measured 1484 MB at 112x40 on 100 modes,
// 1966 MB with stress_outputs, plate_bench) is what refuses: 112x40 fits the default 2048 MB budget
// either way, not 1200 MB, and the refusal names the estimate and memory_limit. Its setup is over
// ten seconds, 56x20's not.
TEST(ResourceNotices, TheSparseCondensationIsRefusedBeyondTheBudget) {
    PlateParameters p = flow(112, 40, 100);
    const ResourceEstimate e = estimateResources(p, predictFromMesh(p));
    EXPECT_NO_THROW(requireWithinBudget(p, e));
    PlateParameters stress = p;
    stress.outputs.stressOutputs = true;
    EXPECT_NO_THROW(requireWithinBudget(stress, estimateResources(stress, predictFromMesh(stress))));
    p.memoryLimit = 1200.0;
    try {
        requireWithinBudget(p, e);
        FAIL() << "not refused at memory_limit = 1200 MB with " << e.peakMB << " MB estimated";
    } catch (const ResourceError& refused) {
        EXPECT_NE(std::string(refused.what()).find("memory_limit"), std::string::npos) << refused.what();
    }
    const PlateParameters small = flow(56, 20, 100);
    EXPECT_LT(estimateResources(small, predictFromMesh(small)).initSeconds, kLongSetupSeconds);
}
