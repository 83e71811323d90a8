#pragma once
// The plate's values as the importer sets and reads them, and the one table of its variables
// (PlateVariables.cpp): name, value reference, type, causality, unit, description and the
// accessors. modelDescription.xml, FMU states and the README's table all come from it.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/Model.h"
#include "PlateSimulation.h"

namespace plateimpact {

// One Real input as the master passes it (docs/theory.md §8): the value, the derivatives if
// the master set them since the value, and the values at the last communication points for
// masters that give none. Only what the master set is a sample, at the time it set it: a step
// it did not set the input for continues the reconstruction (after an early return, FMI 3.0
// event mode), where recording the unchanged value again would bend the signal at that time.
struct InputPort {
    plate::InputSignal signal;  // the value set + its derivatives (input derivatives)
    bool derivativesGiven = false;  // the master set derivatives since the value: they win
    bool fresh = true;  // set since the last step began (the start value counts as set at t = 0)
    double signalTime = 0.0;  // the model time `signal` starts at (its value's communication point)
    plate::InputMode mode;  // otherwise the step follows history.continueStep(mode, now, h)
    plate::InputHistory history;
    double reach = 0.0;  // how far into the step its signal is read (PlateSimulation's grid points)

    explicit InputPort(plate::InputMode defaultMode) : mode(defaultMode) {}
    // A new value: its derivatives are zero and not given until the master sets them again.
    void setValue(double x) {
        signal = plate::InputSignal{x, 0.0, 0.0};
        derivativesGiven = false;
        fresh = true;
    }
    // At the start of a step from model time `now`: a value set since the last step is a sample
    // at `now`; without one the step continues the reconstruction, however long ago the last
    // sample was (a master that sets an input only when it changes wants `hold`: docs/theory.md §8).
    void beginStep(double now) {
        if (fresh) {
            history.record(now, signal.value);
            signalTime = now;
        }
        fresh = false;
    }
    // The signal over the step of length h that starts at `now`; a reconstruction stays inside
    // [lower, upper] (the obstacles, for the clamp). Given derivatives are a polynomial from
    // their communication point on: a later start continues it.
    plate::InputSignal stepSignal(double now, double h, double lower = -HUGE_VAL, double upper = HUGE_VAL) {
        if (!derivativesGiven) return history.continueStep(mode, now, h, lower, upper, reach);
        const plate::InputSignal s = signal.shifted(now - signalTime);
        history.reached(s.at(h));
        return s;
    }
};

// Which input moves the clamp (docs/theory.md §16): the others are ignored.
// Force and Tlm: the clamp is carried inside the step (docs/theory.md §18–19).
enum class BaseDrive { Displacement = 1, Velocity = 2, Acceleration = 3, Force = 4, Tlm = 5 };

// The probes as the importer places them (docs/theory.md §23): the FMI 2.0 FMU's scalar slots
// probe_1 ... probe_4 (a place is kept while probe_count leaves it off) and the FMI 3.0 FMU's arrays
// of probe_count entries, both over these vectors; the first `count` places are the solver's probes.
constexpr std::size_t kScalarProbes = 4;  // FMI 2.0: probe_1 ... probe_4
constexpr std::size_t kMaxProbes = 1024;  // FMI 3.0: probe_count's max
struct ProbePlaces {
    std::size_t count = 0;
    std::size_t max = kScalarProbes;  // the interface's largest count (FMI 3.0: kMaxProbes)
    std::vector<double> x = std::vector<double>(kScalarProbes, 0.0), y = std::vector<double>(kScalarProbes, 0.0);
    bool placed = false;  // the importer set a count or a place (what is not asked for is not warned about)
    // A new count: the places before it kept, new ones at the clamp's corner (0, 0).
    void setCount(std::size_t n) {
        count = n;
        x.resize(std::max(n, kScalarProbes), 0.0);
        y.resize(std::max(n, kScalarProbes), 0.0);
    }
    // As FMU states and configurations carry them: the count, then the x and the y of every place
    // (as many as the FMI 2.0 slots, or the count if more). Read back: the count (false: not a
    // count in range), then the 2 x.size() places it gives room for (false: one not finite).
    void appendTo(std::vector<double>& out) const {
        out.push_back(double(count));
        out.insert(out.end(), x.begin(), x.end());
        out.insert(out.end(), y.begin(), y.end());
    }
    bool setCountFrom(double n) {
        if (!(n >= 0.0 && n <= double(max)) || std::floor(n) != n) return false;
        setCount(std::size_t(n));
        return true;
    }
    bool readPlaces(const double* places) {
        for (std::size_t k = 0; k < x.size(); ++k) {
            x[k] = places[k];
            y[k] = places[x.size() + k];
            if (!std::isfinite(x[k]) || !std::isfinite(y[k])) return false;
        }
        return true;
    }
};

// Everything an importer can set or read, as plain values.
struct PlateValues {
    plate::PlateParameters parameters;  // defaults = the start values of modelDescription.xml (probes: below)
    ProbePlaces probes;
    // The solver's parameters: `parameters` with the first probes.count places.
    plate::PlateParameters solverParameters() const {
        plate::PlateParameters p = parameters;
        p.outputs.probeX.assign(probes.x.begin(), probes.x.begin() + std::ptrdiff_t(probes.count));
        p.outputs.probeY.assign(probes.y.begin(), probes.y.begin() + std::ptrdiff_t(probes.count));
        return p;
    }
    // Default modes, chosen by measurement (docs/input-accuracy.md): a clamp motion is smooth
    // (quadratic extrapolation); a load may step, and extrapolating a step overshoots.
    InputPort baseDisplacement{plate::InputMode::Quadratic};
    InputPort baseVelocity{plate::InputMode::Quadratic};
    InputPort baseAcceleration{plate::InputMode::Quadratic};
    InputPort load{plate::InputMode::Hold};
    InputPort driveForce{plate::InputMode::Quadratic};  // base_drive = force (§18)
    InputPort tlmWaveIn{plate::InputMode::Hold};  // base_drive = tlm: always held (§19)
    BaseDrive baseDrive = BaseDrive::Displacement;
    // The outputs after each change; the port's fields (port()), the probes and the root's stress
    // (field()), the plate's largest stress (plateField(): rows at every vertex) and the probes' motion
    // only once one of them is read: they cost probe and rotation products nobody else needs
    // (docs/theory.md §23). Without a simulation each reads as none was computed.
    plate::PlateOutputs outputs;
    const plate::PlateSimulation* simulation = nullptr;
    template <class T>
    struct OnFirstRead {
        mutable T value;
        mutable bool valid = false;
        template <class Compute>
        const T& get(const plate::PlateSimulation* s, Compute compute) const {
            if (!valid) value = s ? compute(*s) : T{};
            valid = true;
            return value;
        }
    };
    OnFirstRead<plate::PlateOutputs> portOutputs, fieldOutputs, plateFieldOutputs;
    OnFirstRead<plate::ProbeOutputs> probeOutputs;
    void forgetReads() {
        portOutputs.valid = fieldOutputs.valid = plateFieldOutputs.valid = probeOutputs.valid = false;
    }
    const plate::PlateOutputs& port() const {
        return portOutputs.get(simulation, [](const auto& s) { return s.outputs(true); });
    }
    const plate::PlateOutputs& field() const {
        return fieldOutputs.get(simulation,
                                [](const auto& s) { return s.outputs(false, plate::FieldOutputs::Points); });
    }
    const plate::PlateOutputs& plateField() const {
        return plateFieldOutputs.get(simulation,
                                     [](const auto& s) { return s.outputs(false, plate::FieldOutputs::Plate); });
    }
    // Probe k's displacement, velocity or acceleration (0: not computed).
    double probe(Eigen::VectorXd plate::ProbeOutputs::*quantity, std::size_t k) const {
        const Eigen::VectorXd& v = probeOutputs.get(simulation, [](const auto& s) { return s.probes(); }).*quantity;
        return Eigen::Index(k) < v.size() ? v[Eigen::Index(k)] : 0.0;
    }
    InputPort* inputPort(fmu::ValueReference vr);  // nullptr: not an input
};

// The value references: part of the interface, never renumbered (a gap leaves room to group).
enum PlateVr : fmu::ValueReference {
    kVrLength = 0,
    kVrWidth = 1,
    kVrThickness = 2,
    kVrYoungsModulus = 3,
    kVrPoissonRatio = 4,
    kVrDensity = 5,
    kVrNx = 6,
    kVrNy = 7,
    kVrElement = 8,
    kVrObstacleLower = 9,
    kVrObstacleUpper = 10,
    kVrObstacleLowerEnabled = 11,
    kVrObstacleUpperEnabled = 12,
    // Each obstacle's stop (docs/theory.md §25): x_min, x_max, y_min, y_max.
    kVrObstacleLowerXMin = 90,
    kVrObstacleLowerXMax = 91,
    kVrObstacleLowerYMin = 92,
    kVrObstacleLowerYMax = 93,
    kVrObstacleUpperXMin = 94,
    kVrObstacleUpperXMax = 95,
    kVrObstacleUpperYMin = 96,
    kVrObstacleUpperYMax = 97,
    kVrDt = 13,
    kVrBeta = 14,
    kVrInitialLoad = 15,
    kVrModes = 16,
    kVrBaseInputMode = 17,
    kVrLoadInputMode = 18,
    kVrBaseDisplacement = 20,
    kVrLoad = 21,
    kVrCorner1 = 30,
    kVrCorner2 = 31,
    kVrFreeEdgeMid = 32,
    kVrEnergy = 33,
    kVrEnergyDissipated = 34,
    kVrEnergyInput = 35,
    kVrContactVertices = 36,
    kVrQpKktResidualMax = 37,
    kVrQpIterationsTotal = 38,
    kVrQpIterationsMax = 39,
    kVrEnergyDamped = 40,
    kVrMass = 50,
    kVrRestitution = 51,
    kVrDampingMass = 52,
    kVrDampingStiffness = 53,
    kVrBaseDrive = 54,
    kVrBaseVelocity = 22,
    kVrBaseAcceleration = 23,
    kVrClampForce = 70,
    kVrClampMoment = 71,
    kVrClampDisplacement = 72,
    kVrClampVelocity = 73,
    kVrClampAcceleration = 74,
    kVrContactForceLower = 75,
    kVrContactForceUpper = 76,
    kVrContactImpulseLower = 77,
    kVrContactImpulseUpper = 78,
    kVrImpactsLower = 79,
    kVrImpactsUpper = 80,
    kVrCorner1Velocity = 81,
    kVrCorner2Velocity = 82,
    kVrFreeEdgeMidVelocity = 83,
    kVrCorner1Acceleration = 84,
    kVrCorner2Acceleration = 85,
    kVrFreeEdgeMidAcceleration = 86,
    kVrContactOnsetsLower = 87,
    kVrContactOnsetsUpper = 88,
    kVrMemoryLimit = 60,
    kVrTimeScheme = 65,
    kVrContactSubsteps = 66,
    kVrTolerance = 67,
    kVrMaxContactSubsteps = 68,
    kVrErrorEstimate = 41,
    kVrCappedSteps = 42,
    // The discretization error at run time (docs/theory.md §26).
    kVrDiscretizationCheck = 240,
    kVrDiscretizationError = 241,
    // The carried clamp (docs/theory.md §18–19).
    kVrArmatureMass = 100,
    kVrArmatureStiffness = 101,
    kVrArmatureDamping = 102,
    kVrTlmImpedance = 103,
    kVrDriveForce = 104,
    kVrTlmWaveIn = 105,
    kVrArmatureEnergy = 106,
    kVrArmatureDriveWork = 107,
    kVrArmatureDamped = 108,
    kVrArmaturePortWork = 109,
    kVrTlmWaveOut = 110,
    kVrTlmTransit = 111,
    kVrTlmLineLoss = 112,
    // Stress and probes (docs/theory.md §23).
    kVrRootStress = 200,
    kVrRootStressPeak = 201,
    kVrMaxStress = 202,
    kVrMaxStressX = 203,
    kVrMaxStressY = 204,
    kVrProbe1X = 210,  // probe k: x at 210 + 2(k − 1), y at 211 + 2(k − 1)
    kVrProbe1Y = 211,
    kVrProbe2X = 212,
    kVrProbe2Y = 213,
    kVrProbe3X = 214,
    kVrProbe3Y = 215,
    kVrProbe4X = 216,
    kVrProbe4Y = 217,
    kVrStressOutputs = 205,
    kVrProbeCount = 218,
    kVrProbe1 = 220,  // probe k: w at 220 + 3(k − 1), its velocity and acceleration after it
    kVrProbe1Velocity = 221,
    kVrProbe1Acceleration = 222,
    kVrProbe2 = 223,
    kVrProbe2Velocity = 224,
    kVrProbe2Acceleration = 225,
    kVrProbe3 = 226,
    kVrProbe3Velocity = 227,
    kVrProbe3Acceleration = 228,
    kVrProbe4 = 229,
    kVrProbe4Velocity = 230,
    kVrProbe4Acceleration = 231,
};

// Bounds of the clamp's velocity and acceleration inputs: far beyond any shaker (1 km/s,
// 10^6 g), inside what keeps the integrated clamp position's arithmetic finite.
constexpr double kMaxBaseVelocity = 1e3;  // m/s
constexpr double kMaxBaseAcceleration = 1e7;  // m/s^2

const std::vector<fmu::Variable>& plateVariables();
// FMI 3.0 terminals over the table's variables (terminalsAndIcons.xml): the clamp as a vertical
// translational flange, driven by motion (clamp) or by force (armature), and the transmission
// line's end (line). The kinds are documented in the model's page (PlateInfo.cpp).
const std::vector<fmu::Terminal>& plateTerminals();
// The fixed part of modelDescription.xml and the documentation page (PlateInfo.cpp).
const fmu::ModelInfo& plateInfo();
double getValue(const PlateValues& values, const fmu::Variable& v);
void setValue(PlateValues& values, const fmu::Variable& v, double x);

}  // namespace plateimpact
