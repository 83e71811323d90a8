#pragma once
// discretization_check (docs/theory.md §26): the run-time estimate of the error the mesh and the
// modal basis make at the reported points. A companion plate on the mesh coarsened by two
// (ceil(nx/2) × ceil(ny/2) cells on every mode of that mesh, 2 Δt, every other parameter the
// same) is fed the same inputs and follows the plate to each communication point; the largest
// difference of the reported points so far, scaled by Richardson's factor for the refinement
// between the two meshes, is the estimate;
// past the mesh's horizon (the paper's law after its first impact, the meshes parted) a bound.
// The plate itself never sees the companion: its results are the same bits with the check or
// without it.
#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "InputSignal.h"
#include "plate/PlateParameters.h"

namespace plate {

class PlateSimulation;

class DiscretizationCheck {
public:
    // The order in h the estimate assumes (p̂ of docs/theory.md (T.26b)): the lowest a converging
    // ladder showed (0.52, the default drive over 0.1 s; 0.65–2.3 elsewhere), so that Richardson's
    // factor 1/(r^p̂ − 1) over-states wherever the mesh converges faster, never under-states where
    // it converges at all (2.41 at r = 2, 2.83 at the default mesh's r = 1.83).
    static constexpr double kAssumedOrder = 0.5;
    // The companion's parameters: the mesh coarsened by two in each direction (validate() has
    // refused meshes of one cell and carried clamps) on its complete basis whatever the plate's
    // `modes`, twice the step, no tolerance, no probes, no stress, no check of its own.
    static PlateParameters companionParameters(const PlateParameters& plate);
    // Builds the companion of `plate` at its start (ParameterError when it cannot be: a stop its mesh
    // cannot resolve) and compares the two there.
    DiscretizationCheck(const PlateSimulation& plate, double baseDisplacement0, double loadAtStart);
    ~DiscretizationCheck();

    // After the plate's communication step (the plate now at `plate.time()`): the companion steps
    // to the same time with the same signals, then the reported points are compared.
    void follow(const PlateSimulation& plate, const InputSignal& base, const InputSignal& load);
    // The estimate so far (m): Richardson's factor times the largest difference while it holds;
    // from when it cannot (theory §26), at least the range the reported points have swept on
    // either mesh joined with the obstacles' heights: a bound, not a correction.
    double error() const;
    // From when the estimate is the bound (theory §26, "When it cannot"), said once: the
    // message the first time it is asked after that time, then empty.
    std::string takeWarning();

    // The companion's state and the largest difference, for FMU states (CheckedPlate's last part).
    std::vector<double> saveState() const;
    void restoreState(const std::vector<double>& state);  // throws std::invalid_argument

private:
    // The reported points of the plate against the companion's at the same time: the largest
    // difference, the ranges, and whether the estimate still holds.
    void compare(const PlateSimulation& plate);

    std::unique_ptr<PlateSimulation> companion_;
    double factor_;  // Richardson's 1/(r^p − 1) for the refinement r between the meshes (theory §26)
    double largestDifference_ = 0.0;
    double scale_ = 0.0;  // the largest |w| of the reported points so far: the motion's size
    double partingScale_ = 0.0;  // the nearer obstacle's distance; 0 without obstacles (never parted)
    // The enabled obstacles (±∞ where off): the converged plate's points stay between them.
    double floor_ = std::numeric_limits<double>::infinity(), ceiling_ = -std::numeric_limits<double>::infinity();
    // Each reported point's lowest and highest value so far on either mesh: the range it swept.
    std::array<double, 3> lowest_{}, highest_{};
    bool consistentMass_;  // the paper's impact law, whose limit after impact the check cannot see
    double cannotSince_ = -1.0;  // the time the estimate stopped holding; −1 while it holds
    enum class Cannot { Holds = 0, ImpactLaw = 1, Parted = 2 } cannot_ = Cannot::Holds;
    bool warned_ = false;
};

}  // namespace plate
