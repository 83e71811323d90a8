#include "DiscretizationCheck.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "PlateSimulation.h"
#include "plate/Stops.h"

namespace plate {

namespace {

// The order in h the estimate assumes (docs/theory.md §26): measured on the mesh ladders of
// tools/plate_front.py, between 0.7 and 2.2 (≈ 1 after a kink of the drive, ≈ 2 from a smooth
// start). Richardson's factor 1/(r^p − 1) at p = 1.5 is within 1.7× of both ends' at the
// default mesh's r = 1.83; the promise [1/3, 3] of theory §26 is measured, not derived from this.
constexpr double kAssumedOrder = 1.5;
// The companion and the plate have parted once their difference is this share of the motion's size
// (the larger of the nearer obstacle's distance and the largest |w| so far): an impact then comes at
// another time on either mesh, and the meshes no longer differ by a correction but by another
// trajectory (past this mesh's predictability horizon, theory §26), where no Richardson factor holds.
// Measured on the scenes of tools/plate_front.py: the estimate fell below a third of the error only
// past a difference of 17% (FVS on the default drive at 0.1 s); at 10% the warning comes first.
constexpr double kParted = 0.1;

}  // namespace

PlateParameters DiscretizationCheck::companionParameters(const PlateParameters& plate) {
    PlateParameters c = plate;
    c.nx = (plate.nx + 1) / 2;
    c.ny = (plate.ny + 1) / 2;
    c.discretizationCheck = false;
    c.probeX.clear();
    c.probeY.clear();
    c.stressOutputs = false;
    // Twice the step and a quarter of the contact sub-steps (no tolerance): the companion's time
    // error stays far below its mesh's (the flow law's 1e-6–1e-5 m against 1e-3 m, theory §22 and
    // §26; 4 sub-steps instead of 16 moved 28×10 on 40 modes by less than its distance from the
    // plate, docs/performance.md), and on a modal basis, whose free step costs the same on either
    // mesh, and in contact steps, whose sub-steps cost more than their rows, it costs a fraction of
    // the plate's steps (the check ≤ 1.5× the plate's CPU). A dt at the edge of its range keeps the
    // plate's.
    c.tolerance = 0.0;
    c.contactSubsteps = (plate.contactSubsteps + 3) / 4;  // 16 → 4: on §5.2 28×10 on 40 modes is as near the plate
    c.dt = 2.0 * plate.dt;
    try {
        validate(c);
    } catch (const ParameterError&) {
        c.dt = plate.dt;
    }
    return c;
}

DiscretizationCheck::DiscretizationCheck(const PlateParameters& plate, double baseDisplacement0, double loadAtStart)
    : consistentMass_(!plate.singularMass()) {
    // The scene's own size for "parted": the nearer obstacle's distance from the plate's start (an
    // impact earlier or later moves the points by about that); without obstacles the motion is linear
    // and the meshes never part.
    const Obstacles o = obstaclesOf(plate);
    if (plate.obstacleLowerEnabled) partingScale_ = -o.lower;
    if (plate.obstacleUpperEnabled) partingScale_ = partingScale_ > 0.0 ? std::min(partingScale_, o.upper) : o.upper;
    const PlateParameters c = companionParameters(plate);
    try {
        companion_ = std::make_unique<PlateSimulation>(c, baseDisplacement0, loadAtStart);
    } catch (const ParameterError& e) {
        throw ParameterError(std::string("discretization_check: the companion on ") + std::to_string(c.nx) + " x " +
                             std::to_string(c.ny) + " cells cannot be built (" + e.what() +
                             "); set discretization_check = false, or choose a mesh whose coarsening by two keeps "
                             "the scene (its stops on mesh lines)");
    }
    // The refinement between the two meshes: 2 in each direction when nx and ny are even; with an
    // odd count the geometric mean of the cell areas' ratio (14×5 against 7×3: r = 1.83).
    const double r = std::sqrt(double(plate.nx) * plate.ny / (double(c.nx) * c.ny));
    factor_ = 1.0 / (std::pow(r, kAssumedOrder) - 1.0);
}

DiscretizationCheck::~DiscretizationCheck() = default;

void DiscretizationCheck::follow(const PlateSimulation& plate, const InputSignal& base, const InputSignal& load) {
    PlateSimulation& c = *companion_;
    // To the plate's communication time on the companion's own grid (§15), the same signals from
    // the same start; an early return at no step at all (FMI 3.0) leaves nothing to take.
    const double h = plate.time() - c.time();
    if (h > 1e-9 * c.parameters().dt) c.communicate(c.plan(h), base, load);
    const PlateOutputs a = plate.outputs(), b = c.outputs();
    const double difference = std::max(
        {std::fabs(a.corner1 - b.corner1), std::fabs(a.corner2 - b.corner2), std::fabs(a.freeEdgeMid - b.freeEdgeMid)});
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

std::string DiscretizationCheck::takeWarning() {
    if (cannotSince_ < 0.0 || warned_) return "";
    warned_ = true;
    char text[600];
    if (cannot_ == Cannot::ImpactLaw)
        std::snprintf(text, sizeof text,
                      "discretization_error may under-state the error against the plate from t = %.17g s on: the "
                      "first impact with mass = consistent (the paper's law); after impacts this law's plate differs "
                      "from the converged plate by more than its meshes differ from each other (docs/performance.md, "
                      "\"The error against the plate\"), which the companion, on the same law, cannot see; mass = "
                      "singular_p0 with time_scheme = flow keeps the estimate",
                      cannotSince_);
    else
        std::snprintf(text, sizeof text,
                      "discretization_error may under-state the error against the plate from t = %.17g s on: the "
                      "companion and the plate have parted (their difference passed %.0f%% of the motion's size): "
                      "past this mesh's predictability horizon no Richardson factor holds; a finer mesh reaches "
                      "further (python -m plateimpact.sizing)",
                      cannotSince_, 100.0 * kParted);
    return text;
}

std::vector<double> DiscretizationCheck::saveState() const {
    std::vector<double> out = companion_->saveState();
    out.insert(out.end(),
               {largestDifference_, scale_, cannotSince_, double(static_cast<int>(cannot_)), warned_ ? 1.0 : 0.0});
    out.push_back(double(out.size() + 1));  // the part's length, last
    return out;
}

void DiscretizationCheck::restoreState(const std::vector<double>& state) {
    // The companion's state, then the largest difference, the motion's size, the time the estimate
    // stopped holding (−1: it holds), why (0, 1, 2: Cannot), whether that was said, the part's length.
    constexpr std::size_t kOwn = 6;
    if (state.size() < kOwn || state.back() != double(state.size()))
        throw std::invalid_argument("corrupt state: the discretization check's part (its length)");
    const double* own = state.data() + state.size() - kOwn;
    const bool holds = own[2] == -1.0 && own[3] == 0.0;
    const bool stopped = own[2] >= 0.0 && std::isfinite(own[2]) && (own[3] == 1.0 || own[3] == 2.0);
    if (!(own[0] >= 0.0) || !std::isfinite(own[0]) || !(own[1] >= 0.0) || !std::isfinite(own[1]) ||
        !(holds || stopped) || (own[4] != 0.0 && own[4] != 1.0))
        throw std::invalid_argument("corrupt state: the discretization check's part");
    companion_->restoreState(std::vector<double>(state.begin(), state.end() - kOwn));  // throws: nothing set
    largestDifference_ = own[0];
    scale_ = own[1];
    cannotSince_ = own[2];
    cannot_ = static_cast<Cannot>(static_cast<int>(own[3]));
    warned_ = own[4] == 1.0;
}

}  // namespace plate
