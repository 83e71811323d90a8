#pragma once
// Physical and numerical parameters of one PlateImpact run, with their validation.
#include <vector>

#include "base/Errors.h"
#include "fe/Assembly.h"
#include "fe/FiniteElementSpace.h"

namespace plate {

// The plate's mass matrix (docs/theory.md §11): the consistent one of (3.4), or a singular
// (redistributed) mass B C⁻¹ Bᵀ projected on piecewise constants (P0) or on discontinuous
// piecewise linears (P1dg), with no inertia left on the contact vertex values.
enum class MassModel { Consistent = 1, SingularP0 = 2, SingularP1dg = 3 };

// The time scheme (docs/theory.md §17): the paper's three-level Newmark scheme (3.3)/(3.6) with
// its impact laws, or the conserving engine — the singular plate as massive modes and a static
// massless boundary, stepped by the midpoint rule with a discrete gradient of the boundary
// potential: the energy balance closes exactly through impacts, at any Δt. Flow (§21): the same
// condensed plate with every massive mode advanced by its exact flow between contacts and each
// contact step taken as `refinement.substeps` discrete-gradient midpoint sub-steps.
enum class TimeScheme { Newmark = 1, Conserving = 2, Flow = 3 };

// The two obstacles (obstaclesOf, StopMap): their heights, whether each is present, and where each is
// (docs/theory.md §25): a stop over the rectangle [xMin, xMax] × [yMin, yMax] of the plate, clipped to
// it. The stops' defaults reach past any plate the ranges allow: the whole plate.
struct ObstacleParameters {
    struct StopRect {
        double xMin = 0.0, xMax = 1e4, yMin = 0.0, yMax = 1e4;  // m
    };
    double lower = -0.1, upper = 0.1;  // m
    bool lowerEnabled = true, upperEnabled = true;
    StopRect lowerStop, upperStop;
    bool present(int k) const { return k == 0 ? lowerEnabled : upperEnabled; }  // k = 0: lower, 1: upper
    const StopRect& stop(int k) const { return k == 0 ? lowerStop : upperStop; }
};

// The law (makeScheme): the time scheme and its step, the mass, the modes, the impact law, the damping.
struct LawParameters {
    TimeScheme timeScheme = TimeScheme::Newmark;
    MassModel mass = MassModel::Consistent;
    int modes = 0;  // 0 = full space (exact)
    double dt = 1e-5;  // s
    double beta = 0.5;
    // Impact law (docs/theory.md §12): the contact constraint holds on (u⁺ + e u⁻)/(1 + e);
    // e = 0 is the paper's scheme.
    double restitution = 0.0;
    // Rayleigh damping C = dampingMass·M + dampingStiffness·K on the motion relative to the
    // clamp (docs/theory.md §13).
    double dampingMass = 0.0;  // 1/s
    double dampingStiffness = 0.0;  // s
    // How exact mode runs (not an FMU parameter: the result is the same scheme either way;
    // benchmarks and tests pin it to compare the two).
    enum class Engine { Auto, SparseFactor, CompleteModal } engine = Engine::Auto;
    bool condensed() const { return timeScheme == TimeScheme::Conserving || timeScheme == TimeScheme::Flow; }
    bool singularMass() const { return mass != MassModel::Consistent; }
};

// How the flow law divides a contact step (docs/theory.md §21–22; FlowScheme).
struct ContactRefinement {
    // tolerance = 0: every contact step in `substeps` sub-steps (contact_substeps, the midpoint sub-steps
    // of a step in which a constraint row is or becomes active). tolerance > 0 (m, on displacements;
    // §22): each contact step as many sub-steps as its own error estimate asks (step doubling), at most
    // maxSubsteps (a power of two); the estimate accumulates in error_estimate.
    int substeps = 16;
    double tolerance = 0.0;
    int maxSubsteps = 128;
    // Not an FMU parameter: false takes every contact sub-step in every row instead of the rows that can
    // touch (docs/theory.md §24) — the baseline plate_bench rowspace=0 measures against.
    bool rowSpace = true;
};

// What the plate reports beyond the points and the ledger (FieldRecovery, CheckedPlate).
struct OutputParameters {
    // The probes (docs/theory.md §23): any number of points (probeX[k], probeY[k]) of the plate, m,
    // each within [0, length] × [0, width] (validate); the two vectors have one entry per probe.
    // None by default: a master that records every output (fmpy's default) pays nothing for them.
    std::vector<double> probeX, probeY;
    // The stress outputs (§23), off by default for the same reason (the root's peak is then tracked
    // every step). Off, they read 0.
    bool stressOutputs = false;
    // The run-time estimate of the discretization error (docs/theory.md §26): a companion plate on
    // the mesh coarsened by two, fed the same inputs. Off by default: it costs the companion's steps.
    bool discretizationCheck = false;
    std::size_t probeCount() const { return probeX.size(); }
};

// The parameters of one PlateImpact run, in the parts each builder takes: makeSpace the mesh,
// assemble the material, obstaclesOf and StopMap the obstacles, makeScheme the law, FlowScheme the
// refinement, FieldRecovery and CheckedPlate the outputs.
struct PlateParameters {
    MeshParameters mesh;
    MaterialParameters material;
    ObstacleParameters obstacles;
    LawParameters law;
    ContactRefinement refinement;  // time_scheme = flow (§21–22)
    OutputParameters outputs;
    // What carries the clamp (docs/theory.md §18–19; not an FMU parameter: base_drive chooses):
    // the master's motion input (None), an armature driven by a force inside the step, or the end
    // of a transmission line to a partner FMU. The carrier's values are checked only when used.
    enum class Carrier { None, Armature, Line } carrier = Carrier::None;
    double armatureMass = 20.0;  // kg
    double armatureStiffness = 3158.0;  // N/m (2 Hz with 20 kg)
    double armatureDamping = 50.0;  // N·s/m
    double tlmImpedance = 2.0e4;  // N·s/m, the line's characteristic impedance
    double initialLoad = 0.0;  // Pa
    // Budget of one instance's memory (ResourceEstimate.h): an instance whose estimated peak
    // exceeds it is refused before anything large is allocated. 0 = no limit.
    double memoryLimit = 2048.0;  // MB
    // The plate's first natural frequency as the clamped-free strip has it, 1.8751²/(2π L²)·√(D/ρh)
    // (Hz): a yardstick for dt that costs nothing (the default plate: 6.10 Hz against 5.95 Hz of
    // its first mode; docs/theory.md §4). The plate's own: PlateSimulation::firstFrequency.
    double firstFrequencyEstimate() const;
};

// Bounds of the inputs and of what the parameters place (obstacles): far beyond any plate,
// inside what the arithmetic of the scheme keeps finite.
constexpr double kMaxDisplacement = 1e4;  // m, |base_displacement|, |obstacle heights|
constexpr double kMaxLoad = 1e12;  // Pa, |load|, |initial_load|
constexpr double kMaxCarrierForce = 1e12;  // N, |drive_force|, |tlm_wave_in|

// The allowed range of one parameter: the one place it is written. validate() checks it, the
// FMU's table of variables declares it (modelDescription.xml min/max, documentation, README).
// An open end is excluded (min < value); the model description can only state the closure.
struct Range {
    double min, max;
    bool minOpen = false, maxOpen = false;
    bool contains(double x) const { return (minOpen ? x > min : x >= min) && (maxOpen ? x < max : x <= max); }
};

// The ranges keep every product the scheme forms (K ~ E t³/h⁴, Δt²K, energies) far inside the
// doubles' range, so that accepted parameters never give Inf or NaN, and are wide enough for any
// plate a structural code would model (fuzz/parameters.cpp found the need: dt = 1e-323 was
// accepted and the energy came out NaN). Damping: ratios up to ~1e6 at 1 Hz and at 1e6 Hz.
namespace ranges {
constexpr Range kLength{1e-4, 1e4}, kWidth{1e-4, 1e4}, kThickness{1e-6, 1e2};
constexpr Range kYoungsModulus{1.0, 1e14}, kPoissonRatio{0.0, 0.5, true, true}, kDensity{1e-2, 1e6};
constexpr Range kCells{1, 400};  // nx, ny
constexpr Range kObstacleLower{-kMaxDisplacement, 0.0, false, true}, kObstacleUpper{0.0, kMaxDisplacement, true};
constexpr Range kDt{1e-12, 1.0}, kBeta{0.0, 0.5}, kInitialLoad{-kMaxLoad, kMaxLoad};
constexpr Range kModes{0, 2147483647.0}, kRestitution{0.0, 1.0};
constexpr Range kContactSubsteps{1, 64};
constexpr Range kTolerance{0.0, 1.0}, kMaxContactSubsteps{2, 1024};
constexpr Range kDampingMass{0.0, 1e6}, kDampingStiffness{0.0, 1.0};
constexpr Range kMemoryLimit{0.0, 1e9};  // MB; 0 = no limit
// The carrier (§18–19): a mass > 0 (a massless armature is a line end or no carrier at all).
constexpr Range kArmatureMass{0.0, 1e9, true}, kArmatureStiffness{0.0, 1e12}, kArmatureDamping{0.0, 1e12};
constexpr Range kTlmImpedance{0.0, 1e12, true};
// A probe's coordinate: what the table can declare; validate() checks it against length and width.
constexpr Range kProbeCoordinate{0.0, 1e4};
// A stop's edge (docs/theory.md §25): validate() checks the rectangle against the plate and its mesh.
constexpr Range kStopCoordinate{0.0, 1e4};
}  // namespace ranges

// Checks everything that can be checked without assembling (throws ParameterError).
// The β < 1/4 stability bound needs κ_h and is checked by makeScheme (solver/MakeScheme.cpp).
void validate(const PlateParameters& p);

}  // namespace plate
