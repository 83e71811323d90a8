#include "binding/PlateVariables.h"

#include "binding/PlateSwitches.h"

#include <array>
#include <climits>
#include <cmath>
#include <cstdio>

namespace plateimpact {

namespace {

using fmu::Causality;
using fmu::VariableType;
using plate::ElementType;
using plate::InputMode;

using Get = double (*)(const PlateValues&);
using Set = void (*)(PlateValues&, double);

// A row: the variable as modelDescription.xml declares it, and how its value is read and set.
struct Row {
    fmu::Variable variable;
    Get get;
    Set set;  // nullptr for outputs
};

// The variable; a parameter's new value invalidates what was built from the old one.
fmu::Variable declared(fmu::ValueReference vr, const char* name, VariableType type, Causality causality,
                       const char* unit, const char* description, double min = NAN, double max = NAN) {
    fmu::Variable v{vr, name, type, causality, description, unit, nullptr, causality == Causality::Parameter, false};
    v.min = min;
    v.max = max;
    return v;
}

// The rows' makers, one per kind of variable, each with the description last so that a row of
// the table below keeps its data on its first line. Ranges are solver/plate/PlateParameters.h's (the one
// place they are written); an Integer or a Boolean here has no unit.
Row parameter(fmu::ValueReference vr, const char* name, const char* unit, const plate::Range& range, Get get, Set set,
              const char* description) {
    return {declared(vr, name, VariableType::Real, Causality::Parameter, unit, description, range.min, range.max), get,
            set};
}
Row integerParameter(fmu::ValueReference vr, const char* name, const plate::Range& range, Get get, Set set,
                     const char* description) {
    return {declared(vr, name, VariableType::Integer, Causality::Parameter, nullptr, description, range.min, range.max),
            get, set};
}
Row booleanParameter(fmu::ValueReference vr, const char* name, Get get, Set set, const char* description) {
    return {declared(vr, name, VariableType::Boolean, Causality::Parameter, nullptr, description), get, set};
}
// A parameter that switches between named items (fmu::integerSwitch).
Row choice(fmu::ValueReference vr, const char* name, const fmu::EnumerationType& items, Get get, Set set,
           const char* description) {
    return {fmu::integerSwitch(vr, name, description, items), get, set};
}
// A Real input in [-bound, bound] with derivatives; shapesInitialState: its value at
// initialization places the initial state.
Row input(fmu::ValueReference vr, const char* name, const char* unit, bool shapesInitialState, double bound, Get get,
          Set set, const char* description) {
    fmu::Variable v = declared(vr, name, VariableType::Real, Causality::Input, unit, description, -bound, bound);
    v.shapesInitialState = shapesInitialState;
    v.hasDerivatives = true;
    return {v, get, set};
}
Row output(fmu::ValueReference vr, const char* name, const char* unit, Get get, const char* description) {
    return {declared(vr, name, VariableType::Real, Causality::Output, unit, description), get, nullptr};
}
Row integerOutput(fmu::ValueReference vr, const char* name, Get get, const char* description) {
    return {declared(vr, name, VariableType::Integer, Causality::Output, nullptr, description), get, nullptr};
}
// A row of the FMI 2.0 interface only: its scalar probes (FMI 3.0 has them as arrays, PlateArrays.cpp).
Row fmi2Only(Row row) {
    row.variable.version = 2;
    return row;
}
constexpr plate::Range kScalarProbeCount{0.0, double(kScalarProbes)};

// The switches' accessors (Integer values of the items above).
double getElement(const PlateValues& v) { return v.parameters.mesh.element == ElementType::Fvs ? 2.0 : 1.0; }
void setElement(PlateValues& v, double x) {
    v.parameters.mesh.element = x == 2.0 ? ElementType::Fvs : ElementType::Argyris;
}
double getBaseInputMode(const PlateValues& v) { return double(static_cast<int>(v.baseDisplacement.mode)); }
void setBaseInputMode(PlateValues& v, double x) {
    // One mode for every input of the clamp's motion.
    for (InputPort* port : {&v.baseDisplacement, &v.baseVelocity, &v.baseAcceleration, &v.driveForce})
        port->mode = static_cast<InputMode>(int(x));
}
double getLoadInputMode(const PlateValues& v) { return double(static_cast<int>(v.load.mode)); }
void setLoadInputMode(PlateValues& v, double x) { v.load.mode = static_cast<InputMode>(int(x)); }
double getBaseDrive(const PlateValues& v) { return double(static_cast<int>(v.baseDrive)); }
void setBaseDrive(PlateValues& v, double x) {
    v.baseDrive = static_cast<BaseDrive>(int(x));
    using Carrier = plate::PlateParameters::Carrier;  // §18–19
    v.parameters.carrier = x == 4.0 ? Carrier::Armature : x == 5.0 ? Carrier::Line : Carrier::None;
}

// probe_count (the FMI 2.0 Integer; FMI 3.0's structural parameter sets the same count).
double getProbeCount(const PlateValues& v) { return double(v.probes.count); }
void setProbeCount(PlateValues& v, double x) {
    if (!(x >= 0.0 && x <= double(v.probes.max)))
        throw fmu::ModelError("invalid parameter probe_count = " + std::to_string(x) +
                              " (allowed: 0 <= probe_count <= " + std::to_string(v.probes.max) + ")");
    v.probes.setCount(std::size_t(x));
    v.probes.placed = true;
}

double saturate(double n) { return n > INT_MAX ? double(INT_MAX) : n; }  // counts are >= 0
double getQpIterationsTotal(const PlateValues& v) { return saturate(v.outputs.contactSolves); }

// The accessors of the rows that read (and set) a field: of the parameters, of an input port, of
// the cheap outputs, of the port's outputs (computed on the first read), of the carrier's.
#define PARAMETER(field)                                             \
    [](const PlateValues& v) { return double(v.parameters.field); }, \
        [](PlateValues& v, double x) { v.parameters.field = decltype(v.parameters.field)(x); }
#define INPUT(member) \
    [](const PlateValues& v) { return v.member.signal.value; }, [](PlateValues& v, double x) { v.member.setValue(x); }
#define OUTPUT(field) [](const PlateValues& v) { return double(v.outputs.field); }
// An edge of an obstacle's stop (docs/theory.md §25): obstacle_<side>_<edge>, m.
#define STOP_EDGE(vr, side, edge, member, more)                                                 \
    parameter(vr, "obstacle_" side "_" edge, "m", kStopCoordinate, PARAMETER(obstacles.member), \
              "Edge " edge " of the " side                                                      \
              " obstacle's stop: the mesh vertices inside its rectangle (clipped to "           \
              "the plate) are its contact points" more)
#define PORT(field) [](const PlateValues& v) { return v.port().field; }
#define FIELD(member) [](const PlateValues& v) { return v.field().member; }
#define PLATE_FIELD(member) [](const PlateValues& v) { return v.plateField().member; }
#define PROBE(axis, k)                                     \
    [](const PlateValues& v) { return v.probes.axis[k]; }, \
        [](PlateValues& v, double x) { v.probes.axis[k] = x, v.probes.placed = true; }
#define PROBE_MOTION(quantity, k) [](const PlateValues& v) { return v.probe(&plate::ProbeOutputs::quantity, k); }
#define CARRIER(field) [](const PlateValues& v) { return v.simulation ? v.simulation->carrierOutputs().field : 0.0; }

using namespace plate::ranges;  // the parameters' ranges: kLength, kCells, ...

// The table: one row per variable, in the order of modelDescription.xml. A new variable is one
// row here (and its value reference in PlateVariables.h); nothing else lists the variables.
// Each row: its maker's data on one line (value reference, name, then as the maker says), the
// description after it.
// clang-format off
const Row kRows[] = {
    parameter(kVrLength,            "length",             "m",     kLength,            PARAMETER(mesh.length),
        "Plate length along x (clamped edge at x = 0)"),
    parameter(kVrWidth,             "width",              "m",     kWidth,             PARAMETER(mesh.width),
        "Plate width along y"),
    parameter(kVrThickness,         "thickness",          "m",     kThickness,         PARAMETER(material.thickness),
        "Plate thickness"),
    parameter(kVrYoungsModulus,     "youngs_modulus",     "Pa",    kYoungsModulus,     PARAMETER(material.youngsModulus),
        "Young's modulus E"),
    parameter(kVrPoissonRatio,      "poisson_ratio",      "1",     kPoissonRatio,      PARAMETER(material.poissonRatio),
        "Poisson's ratio, in (0, 0.5)"),
    parameter(kVrDensity,           "density",            "kg/m3", kDensity,           PARAMETER(material.density),
        "Mass density of the plate material"),
    integerParameter(kVrNx,    "nx",    kCells, PARAMETER(mesh.nx),
        "Number of mesh cells along x (at least 1)"),
    integerParameter(kVrNy,    "ny",    kCells, PARAMETER(mesh.ny),
        "Number of mesh cells along y (at least 1)"),
    choice(kVrElement,       "element",         elementType(), getElement,       setElement,
        "Finite element"),
    parameter(kVrObstacleLower,     "obstacle_lower",     "m",     kObstacleLower,     PARAMETER(obstacles.lower),
        "Height of the lower obstacle (negative; used when obstacle_lower_enabled)"),
    parameter(kVrObstacleUpper,     "obstacle_upper",     "m",     kObstacleUpper,     PARAMETER(obstacles.upper),
        "Height of the upper obstacle (positive; used when obstacle_upper_enabled)"),
    booleanParameter(kVrObstacleLowerEnabled, "obstacle_lower_enabled", PARAMETER(obstacles.lowerEnabled),
        "Whether the lower obstacle is present"),
    booleanParameter(kVrObstacleUpperEnabled, "obstacle_upper_enabled", PARAMETER(obstacles.upperEnabled),
        "Whether the upper obstacle is present"),
    STOP_EDGE(kVrObstacleLowerXMin, "lower", "x_min", lowerStop.xMin, ""),
    STOP_EDGE(kVrObstacleLowerXMax, "lower", "x_max", lowerStop.xMax, " (default 1e4: to the plate's edge)"),
    STOP_EDGE(kVrObstacleLowerYMin, "lower", "y_min", lowerStop.yMin, ""),
    STOP_EDGE(kVrObstacleLowerYMax, "lower", "y_max", lowerStop.yMax, " (default 1e4: to the plate's edge)"),
    STOP_EDGE(kVrObstacleUpperXMin, "upper", "x_min", upperStop.xMin, ""),
    STOP_EDGE(kVrObstacleUpperXMax, "upper", "x_max", upperStop.xMax, " (default 1e4: to the plate's edge)"),
    STOP_EDGE(kVrObstacleUpperYMin, "upper", "y_min", upperStop.yMin, ""),
    STOP_EDGE(kVrObstacleUpperYMax, "upper", "y_max", upperStop.yMax, " (default 1e4: to the plate's edge)"),
    parameter(kVrDt,                "dt",                 "s",     kDt,                PARAMETER(law.dt),
        "Internal time step of the scheme's fixed grid; a communication step of any length is taken on it, the "
        "outputs interpolated between grid points"),
    parameter(kVrBeta,              "beta",               "1",     kBeta,              PARAMETER(law.beta),
        "Newmark parameter beta in [0, 0.5] (gamma = 1/2); unconditionally stable for beta >= 1/4"),
    parameter(kVrInitialLoad,       "initial_load",       "Pa",    kInitialLoad,       PARAMETER(initialLoad),
        "Uniform pressure (positive upward) whose static equilibrium is the initial shape; the plate starts at rest"),
    integerParameter(kVrModes, "modes", kModes, PARAMETER(law.modes),
        "0: full finite element space (exact scheme); m > 0: reduced model on m modes"),
    choice(kVrBaseInputMode, "base_input_mode", inputMode(),   getBaseInputMode, setBaseInputMode,
        "How base_displacement (and base_velocity, base_acceleration) moves inside a communication step{fmi2: when "
        "the master gives no input derivatives}: held, or extrapolated from the communicated values{fmi2: "
        "(derivatives set by the master always win)}"),
    choice(kVrLoadInputMode, "load_input_mode", inputMode(),   getLoadInputMode, setLoadInputMode,
        "How load moves inside a communication step{fmi2: when the master gives no input derivatives}: held (a load "
        "may step; extrapolating a step overshoots) or extrapolated"),
    choice(kVrMass,          "mass",            massModel(),   PARAMETER(law.mass),
        "Mass matrix: consistent (the paper's scheme; impacts lose energy at every mesh vertex), singular_p0 "
        "(energy-consistent impacts, results converge after impact) or singular_p1dg"),
    choice(kVrTimeScheme,    "time_scheme",     timeScheme(),  PARAMETER(law.timeScheme),
        "Time scheme: newmark (the paper's scheme, default), conserving (needs a singular mass: the energy balance "
        "closes exactly through impacts at any dt and every reported displacement stays within the obstacles; modes "
        "= m keeps the m lowest massive modes, damping acts on them; beta and restitution do not apply) or flow (the "
        "conserving scheme with exact free flight and sub-stepped contact steps: accurate after impact)"),
    integerParameter(kVrContactSubsteps, "contact_substeps", kContactSubsteps, PARAMETER(refinement.substeps),
        "time_scheme = flow: midpoint sub-steps of each internal step in which a constraint row is or becomes "
        "active when tolerance = 0 (1..64; the free steps take the exact modal flow whatever this is)"),
    parameter(kVrTolerance,         "tolerance",          "m",     kTolerance,         PARAMETER(refinement.tolerance),
        "time_scheme = flow: > 0 bounds the time error of the reported points (corner_1, corner_2, free_edge_mid): "
        "their distance from the exact motion of this mesh (its distance from the converged plate: "
        "discretization_error); each contact step takes the sub-steps the global error estimate asks for, and "
        "a warning says when the estimate passes the tolerance (the scene's horizon for it; contact steps then "
        "take contact_substeps sub-steps); 0 = contact_substeps sub-steps"),
    integerParameter(kVrMaxContactSubsteps, "max_contact_substeps", kMaxContactSubsteps,
        PARAMETER(refinement.maxSubsteps),
        "time_scheme = flow with tolerance > 0: the most sub-steps one contact step may take (a power of two, "
        "2..1024): the cap on one internal step's work; capped_steps counts the steps it bounded"),
    parameter(kVrRestitution,       "restitution",        "1",     kRestitution,       PARAMETER(law.restitution),
        "Restitution coefficient e in [0, 1] of the impact law on (u+ + e u-)/(1 + e); 0 is the paper's scheme"),
    parameter(kVrDampingMass,       "damping_mass",       "1/s",   kDampingMass,       PARAMETER(law.dampingMass),
        "Rayleigh damping, mass-proportional coefficient a (C = a M + b K; damping ratio a/(2 omega) + b omega/2), "
        ">= 0"),
    parameter(kVrDampingStiffness,  "damping_stiffness",  "s",     kDampingStiffness,  PARAMETER(law.dampingStiffness),
        "Rayleigh damping, stiffness-proportional coefficient b (C = a M + b K), >= 0"),
    parameter(kVrMemoryLimit,       "memory_limit",       "MB",    kMemoryLimit,       PARAMETER(memoryLimit),
        "Memory budget of the instance: one whose estimated peak exceeds it is refused at fmiXExitInitializationMode "
        "before allocating (the estimate is logged, category logInfo); 0 = no limit"),
    input(kVrBaseDisplacement, "base_displacement", "m",    true,  plate::kMaxDisplacement, INPUT(baseDisplacement),
        "Vertical displacement z of the clamped edge (base motion); its value at initialization places the clamp at "
        "t = 0"),
    input(kVrLoad,             "load",              "Pa",   false, plate::kMaxLoad,         INPUT(load),
        "Uniform pressure on the plate, positive upward, acting from t = 0 on"),
    choice(kVrBaseDrive,     "base_drive",      baseDrive(),   getBaseDrive,     setBaseDrive,
        "Which input moves the clamped edge: displacement (base_displacement), velocity (base_velocity, integrated "
        "from the initial base_displacement), acceleration (base_acceleration, integrated twice, the clamp at rest "
        "at t = 0), force (drive_force on an armature inside the FMU that carries the clamp) or tlm (a transmission "
        "line to a partner: tlm_wave_in, tlm_wave_out)"),
    input(kVrBaseVelocity,     "base_velocity",     "m/s",  false, kMaxBaseVelocity,        INPUT(baseVelocity),
        "Vertical velocity of the clamped edge (used when base_drive = velocity)"),
    input(kVrBaseAcceleration, "base_acceleration", "m/s2", false, kMaxBaseAcceleration,    INPUT(baseAcceleration),
        "Vertical acceleration of the clamped edge (used when base_drive = acceleration)"),
    output(kVrCorner1,                 "corner_1",                   "m",    OUTPUT(corner1),
        "Absolute displacement w at the free corner (length, 0)"),
    output(kVrCorner2,                 "corner_2",                   "m",    OUTPUT(corner2),
        "Absolute displacement w at the free corner (length, width)"),
    output(kVrFreeEdgeMid,             "free_edge_mid",              "m",    OUTPUT(freeEdgeMid),
        "Absolute displacement w at the middle of the free edge (length, width/2)"),
    output(kVrEnergy,                  "energy",                     "J",    OUTPUT(energy),
        "Discrete energy of the scheme (kinetic + bending)"),
    output(kVrEnergyDissipated,        "energy_dissipated",          "J",    OUTPUT(energyDissipated),
        "Energy lost in impacts since t = 0 (cumulative; non-negative with the paper's scheme, a net amount with "
        "restitution > 0 or a singular mass)"),
    output(kVrEnergyInput,             "energy_input",               "J",    OUTPUT(energyInput),
        "Work done by base motion and load since t = 0 (cumulative)"),
    output(kVrEnergyDamped,            "energy_damped",              "J",    OUTPUT(energyDamped),
        "Energy dissipated by the Rayleigh damping since t = 0 (cumulative)"),
    integerOutput(kVrContactVertices,   "contact_vertices",    OUTPUT(contactVertices),
        "Number of mesh vertices on an obstacle after the last step"),
    output(kVrQpKktResidualMax,        "qp_kkt_residual_max",        "1",    OUTPUT(maxKktResidual),
        "Largest relative KKT residual of the per-step contact QPs so far"),
    integerOutput(kVrQpIterationsTotal, "qp_iterations_total", getQpIterationsTotal,
        "Contact solves so far: active-set iterations of the per-step QPs (time_scheme = newmark), solves of the "
        "contact problems (conserving, flow); saturates at 2147483647"),
    integerOutput(kVrQpIterationsMax,   "qp_iterations_max",   OUTPUT(contactIterationsMax),
        "Largest number of iterations of one step's contact solve so far: active-set iterations (newmark), "
        "discrete-gradient iterations (conserving, flow)"),
    output(kVrErrorEstimate,           "error_estimate",             "m",    OUTPUT(errorEstimate),
        "time_scheme = flow with tolerance > 0: the largest time error of the reported points since t = 0 (their "
        "distance from the exact motion of this mesh, not from the converged plate: discretization_error), "
        "estimated from the global error carried through free flight and impacts (the theory, section 22); at "
        "most the gap between the obstacles; 0 otherwise"),
    integerOutput(kVrCappedSteps,       "capped_steps",        OUTPUT(cappedSteps),
        "time_scheme = flow with tolerance > 0: contact steps whose own error stayed above their share of the "
        "tolerance at max_contact_substeps sub-steps (the cap bounded their work; error_estimate includes them)"),
    booleanParameter(kVrDiscretizationCheck, "discretization_check", PARAMETER(outputs.discretizationCheck),
        "Estimate the error the mesh and the modal basis make (discretization_error) while the run goes: a companion "
        "plate on the mesh coarsened by two (ceil(nx/2) x ceil(ny/2) cells, on every mode of that mesh) is fed the same "
        "inputs; the outputs stay "
        "the same bits; needs nx, ny >= 2 and base_drive displacement, velocity or acceleration (the theory, "
        "section 26)"),
    output(kVrDiscretizationError,     "discretization_error",       "m",    OUTPUT(discretizationError),
        "discretization_check = true: the largest error of the reported points (corner_1, corner_2, free_edge_mid) "
        "since t = 0 against the converged plate that comes from the mesh and the modal basis, estimated from the "
        "companion's difference by Richardson's factor; from the Warning that says so on (the paper's law after "
        "its first impact, or the meshes parted) a bound: the range the points swept joined with the obstacles' "
        "heights, between two obstacles at least their gap (the theory, section 26; error_estimate is the time error of this mesh, not this); 0 "
        "otherwise"),
    output(kVrClampForce,              "clamp_force",                "N",    PORT(clampForce),
        "Vertical force the plate exerts on the clamp (positive upward): what a shaker carrying the clamp feels; the "
        "scheme's value at the last internal step's centre t - dt (t - dt/2 with time_scheme = conserving). Fed back "
        "with held values to a partner that moves the clamp (base_velocity) the loop is unstable: it carries the "
        "plate's rigid inertia one step late (an added mass), and impacts make it worse; base_drive = tlm couples "
        "stably, base_drive = force puts the armature inside"),
    output(kVrClampMoment,             "clamp_moment",               "N.m",  PORT(clampMoment),
        "Moment about the clamp line x = 0 of the forces the plate exerts on the clamp (positive when they lift the "
        "plate side), at t - dt"),
    output(kVrClampDisplacement,       "clamp_displacement",         "m",    PORT(clampDisplacement),
        "Position z of the clamped edge as the scheme took it (the integrated input for base_drive = velocity or "
        "acceleration)"),
    output(kVrClampVelocity,           "clamp_velocity",             "m/s",  PORT(clampVelocity),
        "Velocity of the clamped edge (second-order backward difference of the scheme's positions)"),
    output(kVrClampAcceleration,       "clamp_acceleration",         "m/s2", PORT(clampAcceleration),
        "Acceleration of the clamped edge at t - dt (the scheme's central difference): the control accelerometer"),
    output(kVrContactForceLower,       "contact_force_lower",        "N",    PORT(contactForce[0]),
        "Force of the lower obstacle on the plate over the last internal step (>= 0, upward)"),
    output(kVrContactForceUpper,       "contact_force_upper",        "N",    PORT(contactForce[1]),
        "Force of the upper obstacle on the plate over the last internal step (<= 0, downward)"),
    output(kVrContactImpulseLower,     "contact_impulse_lower",      "N.s",  PORT(contactImpulse[0]),
        "Impulse of the lower obstacle on the plate since t = 0 (cumulative)"),
    output(kVrContactImpulseUpper,     "contact_impulse_upper",      "N.s",  PORT(contactImpulse[1]),
        "Impulse of the upper obstacle on the plate since t = 0 (cumulative, <= 0)"),
    integerOutput(kVrImpactsLower,      "impacts_lower",       OUTPUT(impacts[0]),
        "Impacts on the lower obstacle since t = 0: contacts after the whole plate was free of it for at least a "
        "quarter of its first natural period (impact episodes, as counted on a corner's plot; the chatter of single "
        "vertices inside one is contact_onsets_lower)"),
    integerOutput(kVrImpactsUpper,      "impacts_upper",       OUTPUT(impacts[1]),
        "Impacts on the upper obstacle since t = 0 (impact episodes, as impacts_lower)"),
    integerOutput(kVrContactOnsetsLower, "contact_onsets_lower", OUTPUT(contactOnsets[0]),
        "Internal steps whose lower contact force starts from zero, since t = 0: every vertex's chatter inside "
        "an impact counts (depends on dt)"),
    integerOutput(kVrContactOnsetsUpper, "contact_onsets_upper", OUTPUT(contactOnsets[1]),
        "Internal steps whose upper contact force starts from zero, since t = 0 (as contact_onsets_lower)"),
    output(kVrCorner1Velocity,         "corner_1_velocity",          "m/s",  PORT(velocity[0]),
        "Absolute velocity at corner_1 (second-order backward difference)"),
    output(kVrCorner2Velocity,         "corner_2_velocity",          "m/s",  PORT(velocity[1]),
        "Absolute velocity at corner_2"),
    output(kVrFreeEdgeMidVelocity,     "free_edge_mid_velocity",     "m/s",  PORT(velocity[2]),
        "Absolute velocity at free_edge_mid"),
    output(kVrCorner1Acceleration,     "corner_1_acceleration",      "m/s2", PORT(acceleration[0]),
        "Absolute acceleration at corner_1 at t - dt (the scheme's central difference)"),
    output(kVrCorner2Acceleration,     "corner_2_acceleration",      "m/s2", PORT(acceleration[1]),
        "Absolute acceleration at corner_2 at t - dt"),
    output(kVrFreeEdgeMidAcceleration, "free_edge_mid_acceleration", "m/s2", PORT(acceleration[2]),
        "Absolute acceleration at free_edge_mid at t - dt"),
    // The carried clamp (docs/theory.md §18–19): its motion is clamp_displacement, _velocity, _acceleration.
    parameter(kVrArmatureMass,      "armature_mass",      "kg",    kArmatureMass,      PARAMETER(armatureMass),
        "Mass of the armature carrying the clamp (base_drive = force; > 0)"),
    parameter(kVrArmatureStiffness, "armature_stiffness", "N/m",   kArmatureStiffness, PARAMETER(armatureStiffness),
        "Suspension stiffness of the armature (base_drive = force), relaxed at the initial clamp position"),
    parameter(kVrArmatureDamping,   "armature_damping",   "N.s/m", kArmatureDamping,   PARAMETER(armatureDamping),
        "Suspension damping of the armature (base_drive = force)"),
    parameter(kVrTlmImpedance,      "tlm_impedance",      "N.s/m", kTlmImpedance,      PARAMETER(tlmImpedance),
        "Characteristic impedance Z of the transmission line to the partner (base_drive = tlm; > 0)"),
    input(kVrDriveForce,       "drive_force",       "N",    false, plate::kMaxCarrierForce, INPUT(driveForce),
        "Drive force on the armature, positive upward (base_drive = force)"),
    input(kVrTlmWaveIn,        "tlm_wave_in",       "N",    false, plate::kMaxCarrierForce, INPUT(tlmWaveIn),
        "Wave arriving from the partner (base_drive = tlm): connect the partner's tlm_wave_out; held over the step"),
    output(kVrArmatureEnergy,          "armature_energy",            "J",    CARRIER(energy),
        "Discrete energy of the armature (kinetic + suspension spring); 0 for a line end"),
    output(kVrArmatureDriveWork,       "armature_drive_work",        "J",    CARRIER(driveWork),
        "Work of drive_force (or of tlm_wave_in) on the carrier since t = 0"),
    output(kVrArmatureDamped,          "armature_damped",            "J",    CARRIER(damperWork),
        "Energy dissipated in the carrier's damper (the suspension, or the line's impedance) since t = 0"),
    output(kVrArmaturePortWork,        "armature_port_work",         "J",    CARRIER(portWork),
        "Work of the plate on the carrier since t = 0 (= -energy_input with load 0)"),
    output(kVrTlmWaveOut,              "tlm_wave_out",               "N",    CARRIER(waveOut),
        "Mean wave launched into the line over the last communication step (base_drive = tlm): connect to the "
        "partner's tlm_wave_in"),
    output(kVrTlmTransit,              "tlm_transit",                "J",    CARRIER(transit),
        "Energy of the wave this end launched in the last step, stored in the line until the partner receives it"),
    output(kVrTlmLineLoss,             "tlm_line_loss",              "J",    CARRIER(lineLoss),
        "Energy this end launched that the mean wave does not carry, since t = 0 (>= 0: the line is passive)"),
    // Stress and probes (docs/theory.md §23).
    booleanParameter(kVrStressOutputs, "stress_outputs", PARAMETER(outputs.stressOutputs),
        "Compute the stress outputs (root_stress, root_stress_peak, max_stress and its place, vertex_stress): the "
        "root's peak is then tracked at every internal step; off (default) they read 0 and cost nothing"),
    fmi2Only(integerParameter(kVrProbeCount, "probe_count", kScalarProbeCount, getProbeCount, setProbeCount,
        "How many probes (probe_1 ... probe_4, at probe_k_x, probe_k_y) are computed; the others read 0")),
    output(kVrRootStress,              "root_stress",                "Pa",   FIELD(rootStress),
        "Largest von Mises surface bending stress along the clamped edge x = 0 now (plane stress from the "
        "curvatures: 6D/t^2 |w_xx| sqrt(1 - nu + nu^2) there), over each clamped element edge's ends (and middle: "
        "argyris); 0 unless stress_outputs = true"),
    output(kVrRootStressPeak,          "root_stress_peak",           "Pa",   OUTPUT(rootStressPeak),
        "Largest root_stress since t = 0, tracked at every internal step (read or not) when stress_outputs = true; "
        "0 otherwise"),
    output(kVrMaxStress,               "max_stress",                 "Pa",   PLATE_FIELD(maxStress),
        "Largest von Mises surface bending stress over the plate now: at its mesh vertices (as vertex_stress) and "
        "root_stress's points; 0 unless stress_outputs = true"),
    output(kVrMaxStressX,              "max_stress_x",               "m",    PLATE_FIELD(maxStressX),
        "x of the point where max_stress is (held between grid points)"),
    output(kVrMaxStressY,              "max_stress_y",               "m",    PLATE_FIELD(maxStressY),
        "y of the point where max_stress is (held between grid points)"),
    fmi2Only(parameter(kVrProbe1X, "probe_1_x", "m", kProbeCoordinate, PROBE(x, 0),
        "x of probe 1 (0 <= probe_1_x <= length; outputs probe_1, _velocity, _acceleration)")),
    fmi2Only(parameter(kVrProbe1Y, "probe_1_y", "m", kProbeCoordinate, PROBE(y, 0),
        "y of probe 1 (0 <= probe_1_y <= width)")),
    fmi2Only(parameter(kVrProbe2X, "probe_2_x", "m", kProbeCoordinate, PROBE(x, 1), "x of probe 2 (0 ... length)")),
    fmi2Only(parameter(kVrProbe2Y, "probe_2_y", "m", kProbeCoordinate, PROBE(y, 1), "y of probe 2 (0 ... width)")),
    fmi2Only(parameter(kVrProbe3X, "probe_3_x", "m", kProbeCoordinate, PROBE(x, 2), "x of probe 3 (0 ... length)")),
    fmi2Only(parameter(kVrProbe3Y, "probe_3_y", "m", kProbeCoordinate, PROBE(y, 2), "y of probe 3 (0 ... width)")),
    fmi2Only(parameter(kVrProbe4X, "probe_4_x", "m", kProbeCoordinate, PROBE(x, 3), "x of probe 4 (0 ... length)")),
    fmi2Only(parameter(kVrProbe4Y, "probe_4_y", "m", kProbeCoordinate, PROBE(y, 3), "y of probe 4 (0 ... width)")),
    fmi2Only(output(kVrProbe1,                  "probe_1",                    "m",    PROBE_MOTION(displacement, 0),
        "Absolute displacement w at probe 1 (probe_1_x, probe_1_y), from the element's shape functions; 0 unless "
        "probe_count >= 1")),
    fmi2Only(output(kVrProbe1Velocity,          "probe_1_velocity",           "m/s",  PROBE_MOTION(velocity, 0),
        "Absolute velocity at probe 1 (second-order backward difference, as corner_1_velocity)")),
    fmi2Only(output(kVrProbe1Acceleration,      "probe_1_acceleration",       "m/s2", PROBE_MOTION(acceleration, 0),
        "Absolute acceleration at probe 1 at t - dt (the scheme's central difference, as corner_1_acceleration)")),
    fmi2Only(output(kVrProbe2,                  "probe_2",                    "m",    PROBE_MOTION(displacement, 1),
        "Absolute displacement w at probe 2")),
    fmi2Only(output(kVrProbe2Velocity,          "probe_2_velocity",           "m/s",  PROBE_MOTION(velocity, 1),
        "Absolute velocity at probe 2")),
    fmi2Only(output(kVrProbe2Acceleration,      "probe_2_acceleration",       "m/s2", PROBE_MOTION(acceleration, 1),
        "Absolute acceleration at probe 2 at t - dt")),
    fmi2Only(output(kVrProbe3,                  "probe_3",                    "m",    PROBE_MOTION(displacement, 2),
        "Absolute displacement w at probe 3")),
    fmi2Only(output(kVrProbe3Velocity,          "probe_3_velocity",           "m/s",  PROBE_MOTION(velocity, 2),
        "Absolute velocity at probe 3")),
    fmi2Only(output(kVrProbe3Acceleration,      "probe_3_acceleration",       "m/s2", PROBE_MOTION(acceleration, 2),
        "Absolute acceleration at probe 3 at t - dt")),
    fmi2Only(output(kVrProbe4,                  "probe_4",                    "m",    PROBE_MOTION(displacement, 3),
        "Absolute displacement w at probe 4")),
    fmi2Only(output(kVrProbe4Velocity,          "probe_4_velocity",           "m/s",  PROBE_MOTION(velocity, 3),
        "Absolute velocity at probe 4")),
    fmi2Only(output(kVrProbe4Acceleration,      "probe_4_acceleration",       "m/s2", PROBE_MOTION(acceleration, 3),
        "Absolute acceleration at probe 4 at t - dt")),
};
// clang-format on

#undef PARAMETER
#undef INPUT
#undef OUTPUT
#undef PORT
#undef CARRIER
#undef FIELD
#undef PLATE_FIELD
#undef PROBE
#undef PROBE_MOTION

const Row& rowOf(const fmu::Variable& v) {
    // `v` is an element of plateVariables(), which lists the rows' variables in the same order.
    return kRows[static_cast<std::size_t>(&v - plateVariables().data())];
}

}  // namespace

const std::vector<fmu::Variable>& plateVariables() {
    static const std::vector<fmu::Variable> variables = [] {
        std::vector<fmu::Variable> out;
        for (const Row& row : kRows) out.push_back(row.variable);
        return out;
    }();
    return variables;
}

InputPort* PlateValues::inputPort(fmu::ValueReference vr) {
    switch (vr) {
        case kVrBaseDisplacement: return &baseDisplacement;
        case kVrBaseVelocity: return &baseVelocity;
        case kVrBaseAcceleration: return &baseAcceleration;
        case kVrLoad: return &load;
        case kVrDriveForce: return &driveForce;
        case kVrTlmWaveIn: return &tlmWaveIn;
        default: return nullptr;
    }
}

double getValue(const PlateValues& values, const fmu::Variable& v) { return rowOf(v).get(values); }

void setValue(PlateValues& values, const fmu::Variable& v, double x) { rowOf(v).set(values, x); }

}  // namespace plateimpact
