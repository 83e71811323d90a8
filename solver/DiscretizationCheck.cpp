#include "DiscretizationCheck.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "PlateSimulation.h"
#include "plate/Stops.h"

namespace plate {

namespace {

// The companion and the plate have parted once their difference is this share of the motion's size
// (the larger of the nearer obstacle's distance and the largest |w| so far): an impact then comes at
// another time on either mesh, and the meshes no longer differ by a correction but by another
// trajectory (past this mesh's predictability horizon, theory §26), where no Richardson factor holds.
// Measured on the scenes of tools/plate_front.py (at p̂ = 1.5): the estimate fell below a third of the
// error only past a difference of 17% (FVS on the default drive at 0.1 s); at 10% the bound comes first.
constexpr double kParted = 0.1;

}  // namespace

PlateParameters DiscretizationCheck::companionParameters(const PlateParameters& plate) {
    PlateParameters c = plate;
    c.mesh.nx = (plate.mesh.nx + 1) / 2;
    c.mesh.ny = (plate.mesh.ny + 1) / 2;
    c.outputs = {};  // no check of its own, no probes, no stresses
    // Twice the step and a quarter of the contact sub-steps (no tolerance): the companion's time
    // error stays far below its mesh's (the flow law's 1e-6–1e-5 m against 1e-3 m, theory §22 and
    // §26; 4 sub-steps instead of 16 moved 28×10 on 40 modes by less than its distance from the
    // plate, docs/performance.md), and on a modal basis, whose free step costs the same on either
    // mesh, and in contact steps, whose sub-steps cost more than their rows, it costs a fraction of
    // the plate's steps (on the complete basis the check 0.9–1.3× the plate's CPU; on a modal basis,
    // whose companion is a complete coarse plate, 1.1–1.9× on 40 modes and up to 3.5× on two:
    // docs/plate_front.json). A dt at the edge of its range keeps the plate's.
    c.refinement.tolerance = 0.0;
    // Every mode of the coarser mesh (the complete basis), whatever the plate's `modes`: on a truncated
    // modal basis the truncation is part of the error, and only a companion that keeps the modes the
    // plate drops sees it wherever the drive puts its energy (theory §26, "A truncated modal basis").
    // A companion on the same `modes` makes the same truncation (7 × 3 and 14 × 5 on one mode 3e-4 m
    // apart, both 3e-2 m from the plate); one on half of them misses every mode above the plate's own:
    // 14 × 5 on 4 modes driven at the fourth bending mode (205 Hz) was 1.2e-3 m from the plate where the
    // companion on 2 modes read 4e-4 m, and at 360 Hz 4.6e-3 m against 4.2e-4 m (tools/unseen_scenes.py).
    c.law.modes = 0;
    c.refinement.substeps =
        (plate.refinement.substeps + 3) / 4;  // 16 → 4: on §5.2 28×10 on 40 modes is as near the plate
    c.law.dt = 2.0 * plate.law.dt;
    try {
        validate(c);
    } catch (const ParameterError&) {
        c.law.dt = plate.law.dt;
    }
    return c;
}

DiscretizationCheck::DiscretizationCheck(const PlateSimulation& simulation, double baseDisplacement0,
                                         double loadAtStart)
    : consistentMass_(!simulation.parameters().law.singularMass()) {
    const PlateParameters& plate = simulation.parameters();
    // The scene's own size for "parted": the nearer obstacle's distance from the plate's start (an
    // impact earlier or later moves the points by about that); without obstacles the motion is linear
    // and the meshes never part.
    const Obstacles o = obstaclesOf(plate.obstacles);
    if (plate.obstacles.lowerEnabled) partingScale_ = -o.lower;
    if (plate.obstacles.upperEnabled) partingScale_ = partingScale_ > 0.0 ? std::min(partingScale_, o.upper) : o.upper;
    // The converged plate stays between the obstacles at every point; the discrete one only at its
    // contact vertices (a reported point between vertices may pass them): the bound's range (T.26c).
    if (plate.obstacles.lowerEnabled) floor_ = o.lower;
    if (plate.obstacles.upperEnabled) ceiling_ = o.upper;
    const PlateParameters c = companionParameters(plate);
    try {
        companion_ = std::make_unique<PlateSimulation>(c, baseDisplacement0, loadAtStart);
    } catch (const ParameterError& e) {
        throw ParameterError(std::string("discretization_check: the companion on ") + std::to_string(c.mesh.nx) +
                             " x " + std::to_string(c.mesh.ny) + " cells cannot be built (" + e.what() +
                             "); set discretization_check = false, or choose a mesh whose coarsening by two keeps "
                             "the scene (its stops on mesh lines)");
    }
    // The refinement between the two meshes: 2 in each direction when nx and ny are even; with an
    // odd count the geometric mean of the cell areas' ratio (14×5 against 7×3: r = 1.83).
    const double r = std::sqrt(double(plate.mesh.nx) * plate.mesh.ny / (double(c.mesh.nx) * c.mesh.ny));
    factor_ = 1.0 / (std::pow(r, kAssumedOrder) - 1.0);
    const PlateOutputs start = companion_->outputs();
    lowest_ = highest_ = {start.corner1, start.corner2, start.freeEdgeMid};
    // Already at t = 0 the two meshes differ: a static start (initial_load, a pressed plate) is each
    // mesh's own static shape (on §5.2 14 × 5 starts 4e-5 m below 56 × 20).
    compare(simulation);
}

DiscretizationCheck::~DiscretizationCheck() = default;

void DiscretizationCheck::follow(const PlateSimulation& plate, const InputSignal& base, const InputSignal& load) {
    PlateSimulation& c = *companion_;
    // To the plate's communication time on the companion's own grid (§15), the same signals from
    // the same start; an early return at no step at all (FMI 3.0) leaves nothing to take.
    const double h = plate.time() - c.time();
    if (h > 1e-9 * c.parameters().law.dt) c.communicate(c.plan(h), base, load);
    compare(plate);
}

void DiscretizationCheck::compare(const PlateSimulation& plate) {
    const PlateOutputs a = plate.outputs(), b = companion_->outputs();
    const double difference = std::max(
        {std::fabs(a.corner1 - b.corner1), std::fabs(a.corner2 - b.corner2), std::fabs(a.freeEdgeMid - b.freeEdgeMid)});
    const std::array<double, 3> pa{a.corner1, a.corner2, a.freeEdgeMid}, pb{b.corner1, b.corner2, b.freeEdgeMid};
    for (std::size_t k = 0; k < 3; ++k) {
        lowest_[k] = std::min({lowest_[k], pa[k], pb[k]});
        highest_[k] = std::max({highest_[k], pa[k], pb[k]});
    }
    largestDifference_ = std::max(largestDifference_, difference);
    scale_ = std::max({scale_, std::fabs(a.corner1), std::fabs(a.corner2), std::fabs(a.freeEdgeMid)});
    if (cannotSince_ >= 0.0) return;
    if (consistentMass_ && a.contactVertices > 0)
        cannot_ = Cannot::ImpactLaw;
    else if (partingScale_ > 0.0 && largestDifference_ > kParted * std::max(scale_, partingScale_))
        cannot_ = Cannot::Parted;
    else
        return;
    cannotSince_ = plate.time();
}

double DiscretizationCheck::error() const {
    const double richardson = factor_ * largestDifference_;
    if (cannotSince_ < 0.0) return richardson;
    // Past the horizon (theory §26, "When it cannot") the plate and the converged plate are two
    // trajectories through the same space: their distance is bounded by the range each point swept
    // (on either mesh) joined with the obstacles' (the converged plate's range where both are on),
    // not by a correction of the mesh.
    double swept = 0.0;
    for (std::size_t k = 0; k < 3; ++k)
        swept = std::max(swept, std::max(highest_[k], ceiling_) - std::min(lowest_[k], floor_));
    return std::max(richardson, swept);
}

std::string DiscretizationCheck::takeWarning() {
    if (cannotSince_ < 0.0 || warned_) return "";
    warned_ = true;
    char text[600];
    if (cannot_ == Cannot::ImpactLaw)
        std::snprintf(text, sizeof text,
                      "discretization_error is a bound from t = %.17g s on, no longer an estimate: at the first "
                      "impact with mass = consistent (the paper's law), whose motion after impacts tends to another "
                      "limit than the converged plate's (docs/theory.md section 26), which a companion on the same "
                      "law cannot see; it now reads the range the reported points swept (between two obstacles at "
                      "least their gap); mass = singular_p0 with time_scheme = flow keeps the estimate",
                      cannotSince_);
    else
        std::snprintf(text, sizeof text,
                      "discretization_error is a bound from t = %.17g s on, no longer an estimate: the companion "
                      "and the plate have parted (their difference passed %.0f%% of the motion's size), past this "
                      "mesh's predictability horizon, where no Richardson factor holds; it now reads the range the "
                      "reported points swept (between two obstacles at least their gap); a finer mesh reaches "
                      "further (python -m plateimpact.sizing)",
                      cannotSince_, 100.0 * kParted);
    return text;
}

std::vector<double> DiscretizationCheck::saveState() const {
    std::vector<double> out = companion_->saveState();
    out.insert(out.end(),
               {largestDifference_, scale_, cannotSince_, double(static_cast<int>(cannot_)), warned_ ? 1.0 : 0.0});
    out.insert(out.end(), lowest_.begin(), lowest_.end());
    out.insert(out.end(), highest_.begin(), highest_.end());
    out.push_back(double(out.size() + 1));  // the part's length, last
    return out;
}

void DiscretizationCheck::restoreState(const std::vector<double>& state) {
    // The companion's state, then the largest difference, the motion's size, the time the estimate
    // stopped holding (−1: it holds), why (0, 1, 2: Cannot), whether that was said, the points'
    // lowest and highest values, the part's length.
    constexpr std::size_t kOwn = 12;
    if (state.size() < kOwn || state.back() != double(state.size()))
        throw std::invalid_argument("corrupt state: the discretization check's part (its length)");
    const double* own = state.data() + state.size() - kOwn;
    const bool holds = own[2] == -1.0 && own[3] == 0.0;
    const bool stopped = own[2] >= 0.0 && std::isfinite(own[2]) && (own[3] == 1.0 || own[3] == 2.0);
    if (!(own[0] >= 0.0) || !std::isfinite(own[0]) || !(own[1] >= 0.0) || !std::isfinite(own[1]) ||
        !(holds || stopped) || (own[4] != 0.0 && own[4] != 1.0))
        throw std::invalid_argument("corrupt state: the discretization check's part");
    for (std::size_t k = 0; k < 3; ++k) {
        if (!std::isfinite(own[5 + k]) || !std::isfinite(own[8 + k]) || own[5 + k] > own[8 + k])
            throw std::invalid_argument("corrupt state: the discretization check's part (the points' range)");
    }
    companion_->restoreState(std::vector<double>(state.begin(), state.end() - kOwn));  // throws: nothing set
    largestDifference_ = own[0];
    scale_ = own[1];
    cannotSince_ = own[2];
    cannot_ = static_cast<Cannot>(static_cast<int>(own[3]));
    warned_ = own[4] == 1.0;
    std::copy(own + 5, own + 8, lowest_.begin());
    std::copy(own + 8, own + 11, highest_.begin());
}

}  // namespace plate
