#include "PlateVariables.h"

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
using plate::MassModel;
using plate::TimeScheme;

const fmu::EnumerationType kElementType{
    "ElementType",
    "C1 plate element",
    {{"argyris", 1, "Argyris triangle (P5, 21 dofs); each cell split into two triangles"},
     {"fvs", 2, "Reduced Fraeijs de Veubeke-Sander quadrilateral (12 dofs); one per cell"}}};

const fmu::EnumerationType kInputMode{
    "InputMode",
    "How an input is continued inside a communication step from its communicated values",
    {{"hold", 1, "Held constant over the step"},
     {"linear", 2, "Extrapolated along the line through the last two communicated values"},
     {"quadratic", 3, "Extrapolated along the parabola through the last three communicated values"}}};

const fmu::EnumerationType kMassModel{
    "MassModel",
    "Mass matrix of the plate",
    {{"consistent", 1, "Consistent mass of the finite element space (the paper's scheme)"},
     {"singular_p0", 2,
      "Singular mass projected on element-wise constants: no inertia at the contact vertices, energy-consistent "
      "impacts as dt -> 0"},
     {"singular_p1dg", 3, "Singular mass projected on element-wise linear functions (Argyris only)"}}};

const fmu::EnumerationType kTimeScheme{
    "TimeScheme",
    "Time scheme",
    {{"newmark", 1, "The paper's three-level Newmark scheme with the impact law set by mass and restitution"},
     {"conserving", 2,
      "Condensed singular plate (needs mass = singular_p0 or singular_p1dg): massive modes stepped by the midpoint "
      "rule, the massless boundary static, impacts through a discrete gradient; conserves energy through impacts "
      "at any dt"}}};

const fmu::EnumerationType kBaseDrive{
    "BaseDrive",
    "Which input moves the clamped edge",
    {{"displacement", 1, "base_displacement (the clamp position)"},
     {"velocity", 2, "base_velocity, integrated exactly over each communication step from the position at its start"},
     {"acceleration", 3, "base_acceleration, integrated twice exactly over each communication step"},
     {"force", 4,
      "drive_force on an armature that carries the clamp inside the FMU (armature_mass, _stiffness, _damping)"},
     {"tlm", 5,
      "tlm_wave_in: the clamp is the end of a transmission line of impedance tlm_impedance to a partner FMU"}}};

// A row: the variable as modelDescription.xml declares it, and how its value is read and set.
struct Row {
    fmu::Variable variable;
    double (*get)(const PlateValues&);
    void (*set)(PlateValues&, double);  // nullptr for outputs
};

fmu::Variable parameter(fmi2ValueReference vr, const char* name, VariableType type, const char* unit,
                        const char* description) {
    return {vr, name, type, Causality::Parameter, description, unit, nullptr, true, false};
}
// A parameter with its range (solver/PlateParameters.h, the one place it is written).
fmu::Variable parameter(fmi2ValueReference vr, const char* name, VariableType type, const char* unit,
                        const char* description, const plate::Range& range) {
    fmu::Variable v = parameter(vr, name, type, unit, description);
    v.min = range.min;
    v.max = range.max;
    return v;
}
fmu::Variable input(fmi2ValueReference vr, const char* name, const char* unit, bool shapesInitialState, double bound,
                    const char* description) {
    fmu::Variable v{vr,  name, VariableType::Real, Causality::Input, description, unit, nullptr, shapesInitialState,
                    true};
    v.min = -bound;
    v.max = bound;
    return v;
}
fmu::Variable output(fmi2ValueReference vr, const char* name, VariableType type, const char* unit,
                     const char* description) {
    return {vr, name, type, Causality::Output, description, unit, nullptr, false, false};
}

// The switches' accessors (Integer values of the items above).
double getElement(const PlateValues& v) { return v.parameters.element == ElementType::Fvs ? 2.0 : 1.0; }
void setElement(PlateValues& v, double x) { v.parameters.element = x == 2.0 ? ElementType::Fvs : ElementType::Argyris; }
double getBaseInputMode(const PlateValues& v) { return double(static_cast<int>(v.baseDisplacement.mode)); }
void setBaseInputMode(PlateValues& v, double x) {
    // One mode for every input of the clamp's motion.
    for (InputPort* port : {&v.baseDisplacement, &v.baseVelocity, &v.baseAcceleration, &v.driveForce})
        port->mode = static_cast<InputMode>(int(x));
}
double getLoadInputMode(const PlateValues& v) { return double(static_cast<int>(v.load.mode)); }
void setLoadInputMode(PlateValues& v, double x) { v.load.mode = static_cast<InputMode>(int(x)); }
double getMass(const PlateValues& v) { return double(static_cast<int>(v.parameters.mass)); }
void setMass(PlateValues& v, double x) { v.parameters.mass = static_cast<MassModel>(int(x)); }
double getTimeScheme(const PlateValues& v) { return double(static_cast<int>(v.parameters.timeScheme)); }
void setTimeScheme(PlateValues& v, double x) { v.parameters.timeScheme = static_cast<TimeScheme>(int(x)); }
double getBaseDrive(const PlateValues& v) { return double(static_cast<int>(v.baseDrive)); }
void setBaseDrive(PlateValues& v, double x) {
    v.baseDrive = static_cast<BaseDrive>(int(x));
    using Carrier = plate::PlateParameters::Carrier;  // §18–19
    v.parameters.carrier = x == 4.0 ? Carrier::Armature : x == 5.0 ? Carrier::Line : Carrier::None;
}

double saturate(double n) { return n > INT_MAX ? double(INT_MAX) : n; }  // counts are >= 0

#define PARAMETER_FIELD(field)                                       \
    [](const PlateValues& v) { return double(v.parameters.field); }, \
        [](PlateValues& v, double x) { v.parameters.field = decltype(v.parameters.field)(x); }
#define OUTPUT_FIELD(field) [](const PlateValues& v) { return double(v.outputs.field); }, nullptr
#define PORT_FIELD(field) [](const PlateValues& v) { return v.port().field; }, nullptr
#define CARRIER_FIELD(field) \
    [](const PlateValues& v) { return v.simulation ? v.simulation->carrierOutputs().field : 0.0; }, nullptr

// The table: one row per variable, in the order of modelDescription.xml. A new variable is one
// row here (and its value reference in PlateVariables.h); nothing else lists the variables.
const Row kRows[] = {
    {parameter(kVrLength, "length", VariableType::Real, "m", "Plate length along x (clamped edge at x = 0)",
               plate::ranges::kLength),
     PARAMETER_FIELD(length)},
    {parameter(kVrWidth, "width", VariableType::Real, "m", "Plate width along y", plate::ranges::kWidth),
     PARAMETER_FIELD(width)},
    {parameter(kVrThickness, "thickness", VariableType::Real, "m", "Plate thickness", plate::ranges::kThickness),
     PARAMETER_FIELD(thickness)},
    {parameter(kVrYoungsModulus, "youngs_modulus", VariableType::Real, "Pa", "Young's modulus E",
               plate::ranges::kYoungsModulus),
     PARAMETER_FIELD(youngsModulus)},
    {parameter(kVrPoissonRatio, "poisson_ratio", VariableType::Real, "1", "Poisson's ratio, in (0, 0.5)",
               plate::ranges::kPoissonRatio),
     PARAMETER_FIELD(poissonRatio)},
    {parameter(kVrDensity, "density", VariableType::Real, "kg/m3", "Mass density of the plate material",
               plate::ranges::kDensity),
     PARAMETER_FIELD(density)},
    {parameter(kVrNx, "nx", VariableType::Integer, nullptr, "Number of mesh cells along x (at least 1)",
               plate::ranges::kCells),
     PARAMETER_FIELD(nx)},
    {parameter(kVrNy, "ny", VariableType::Integer, nullptr, "Number of mesh cells along y (at least 1)",
               plate::ranges::kCells),
     PARAMETER_FIELD(ny)},
    {fmu::integerSwitch(kVrElement, "element", "Finite element", kElementType), getElement, setElement},
    {parameter(kVrObstacleLower, "obstacle_lower", VariableType::Real, "m",
               "Height of the lower obstacle (negative; used when obstacle_lower_enabled)",
               plate::ranges::kObstacleLower),
     PARAMETER_FIELD(obstacleLower)},
    {parameter(kVrObstacleUpper, "obstacle_upper", VariableType::Real, "m",
               "Height of the upper obstacle (positive; used when obstacle_upper_enabled)",
               plate::ranges::kObstacleUpper),
     PARAMETER_FIELD(obstacleUpper)},
    {parameter(kVrObstacleLowerEnabled, "obstacle_lower_enabled", VariableType::Boolean, nullptr,
               "Whether the lower obstacle is present"),
     PARAMETER_FIELD(obstacleLowerEnabled)},
    {parameter(kVrObstacleUpperEnabled, "obstacle_upper_enabled", VariableType::Boolean, nullptr,
               "Whether the upper obstacle is present"),
     PARAMETER_FIELD(obstacleUpperEnabled)},
    {parameter(kVrDt, "dt", VariableType::Real, "s",
               "Internal time step of the scheme's fixed grid; a communication step of any length is taken on it, the "
               "outputs interpolated between grid points",
               plate::ranges::kDt),
     PARAMETER_FIELD(dt)},
    {parameter(kVrBeta, "beta", VariableType::Real, "1",
               "Newmark parameter beta in [0, 0.5] (gamma = 1/2); unconditionally stable for beta >= 1/4",
               plate::ranges::kBeta),
     PARAMETER_FIELD(beta)},
    {parameter(kVrInitialLoad, "initial_load", VariableType::Real, "Pa",
               "Uniform pressure (positive upward) whose static equilibrium is the initial shape; the plate "
               "starts at rest",
               plate::ranges::kInitialLoad),
     PARAMETER_FIELD(initialLoad)},
    {parameter(kVrModes, "modes", VariableType::Integer, nullptr,
               "0: full finite element space (exact scheme); m > 0: reduced model on m modes", plate::ranges::kModes),
     PARAMETER_FIELD(modes)},
    {fmu::integerSwitch(kVrBaseInputMode, "base_input_mode",
                        "How base_displacement (and base_velocity, base_acceleration) moves inside a "
                        "communication step{fmi2: when the master gives no input derivatives}: held, or extrapolated "
                        "from the communicated values{fmi2: (derivatives set by the master always win)}",
                        kInputMode),
     getBaseInputMode, setBaseInputMode},
    {fmu::integerSwitch(kVrLoadInputMode, "load_input_mode",
                        "How load moves inside a communication step{fmi2: when the master gives no input "
                        "derivatives}: held (a load may step; extrapolating a step overshoots) or extrapolated",
                        kInputMode),
     getLoadInputMode, setLoadInputMode},
    {fmu::integerSwitch(kVrMass, "mass",
                        "Mass matrix: consistent (the paper's scheme; impacts lose energy at every mesh vertex), "
                        "singular_p0 (energy-consistent impacts, results converge after impact) or singular_p1dg",
                        kMassModel),
     getMass, setMass},
    {fmu::integerSwitch(kVrTimeScheme, "time_scheme",
                        "Time scheme: newmark (the paper's scheme, default) or conserving (needs a singular mass: the "
                        "energy balance closes exactly through impacts at any dt and every reported displacement stays "
                        "within the obstacles; modes = m keeps the m lowest massive modes, damping acts on them; beta "
                        "and restitution do not apply)",
                        kTimeScheme),
     getTimeScheme, setTimeScheme},
    {parameter(kVrRestitution, "restitution", VariableType::Real, "1",
               "Restitution coefficient e in [0, 1] of the impact law on (u+ + e u-)/(1 + e); 0 is the paper's "
               "scheme",
               plate::ranges::kRestitution),
     PARAMETER_FIELD(restitution)},
    {parameter(kVrDampingMass, "damping_mass", VariableType::Real, "1/s",
               "Rayleigh damping, mass-proportional coefficient a (C = a M + b K; damping ratio a/(2 omega) + "
               "b omega/2), >= 0",
               plate::ranges::kDampingMass),
     PARAMETER_FIELD(dampingMass)},
    {parameter(kVrDampingStiffness, "damping_stiffness", VariableType::Real, "s",
               "Rayleigh damping, stiffness-proportional coefficient b (C = a M + b K), >= 0",
               plate::ranges::kDampingStiffness),
     PARAMETER_FIELD(dampingStiffness)},
    {parameter(kVrMemoryLimit, "memory_limit", VariableType::Real, "MB",
               "Memory budget of the instance: one whose estimated peak exceeds it is refused at "
               "fmiXExitInitializationMode before allocating (the estimate is logged, category logInfo); 0 = no "
               "limit",
               plate::ranges::kMemoryLimit),
     PARAMETER_FIELD(memoryLimit)},
    {input(kVrBaseDisplacement, "base_displacement", "m", true, plate::kMaxDisplacement,
           "Vertical displacement z of the clamped edge (base motion); its value at initialization places "
           "the clamp at t = 0"),
     [](const PlateValues& v) { return v.baseDisplacement.signal.value; },
     [](PlateValues& v, double x) { v.baseDisplacement.setValue(x); }},
    {input(kVrLoad, "load", "Pa", false, plate::kMaxLoad,
           "Uniform pressure on the plate, positive upward, acting from t = 0 on"),
     [](const PlateValues& v) { return v.load.signal.value; }, [](PlateValues& v, double x) { v.load.setValue(x); }},
    {fmu::integerSwitch(kVrBaseDrive, "base_drive",
                        "Which input moves the clamped edge: displacement (base_displacement), velocity "
                        "(base_velocity, integrated from the initial base_displacement) or acceleration "
                        "(base_acceleration, integrated twice, the clamp at rest at t = 0)",
                        kBaseDrive),
     getBaseDrive, setBaseDrive},
    {input(kVrBaseVelocity, "base_velocity", "m/s", false, kMaxBaseVelocity,
           "Vertical velocity of the clamped edge (used when base_drive = velocity)"),
     [](const PlateValues& v) { return v.baseVelocity.signal.value; },
     [](PlateValues& v, double x) { v.baseVelocity.setValue(x); }},
    {input(kVrBaseAcceleration, "base_acceleration", "m/s2", false, kMaxBaseAcceleration,
           "Vertical acceleration of the clamped edge (used when base_drive = acceleration)"),
     [](const PlateValues& v) { return v.baseAcceleration.signal.value; },
     [](PlateValues& v, double x) { v.baseAcceleration.setValue(x); }},
    {output(kVrCorner1, "corner_1", VariableType::Real, "m", "Absolute displacement w at the free corner (length, 0)"),
     OUTPUT_FIELD(corner1)},
    {output(kVrCorner2, "corner_2", VariableType::Real, "m",
            "Absolute displacement w at the free corner (length, width)"),
     OUTPUT_FIELD(corner2)},
    {output(kVrFreeEdgeMid, "free_edge_mid", VariableType::Real, "m",
            "Absolute displacement w at the middle of the free edge (length, width/2)"),
     OUTPUT_FIELD(freeEdgeMid)},
    {output(kVrEnergy, "energy", VariableType::Real, "J", "Discrete energy of the scheme (kinetic + bending)"),
     OUTPUT_FIELD(energy)},
    {output(kVrEnergyDissipated, "energy_dissipated", VariableType::Real, "J",
            "Energy lost in impacts since t = 0 (cumulative; non-negative with the paper's scheme, a net "
            "amount with restitution > 0 or a singular mass)"),
     OUTPUT_FIELD(energyDissipated)},
    {output(kVrEnergyInput, "energy_input", VariableType::Real, "J",
            "Work done by base motion and load since t = 0 (cumulative)"),
     OUTPUT_FIELD(energyInput)},
    {output(kVrEnergyDamped, "energy_damped", VariableType::Real, "J",
            "Energy dissipated by the Rayleigh damping since t = 0 (cumulative)"),
     OUTPUT_FIELD(energyDamped)},
    {output(kVrContactVertices, "contact_vertices", VariableType::Integer, nullptr,
            "Number of mesh vertices on an obstacle after the last step"),
     OUTPUT_FIELD(contactVertices)},
    {output(kVrQpKktResidualMax, "qp_kkt_residual_max", VariableType::Real, "1",
            "Largest relative KKT residual of the per-step contact QPs so far"),
     OUTPUT_FIELD(maxKktResidual)},
    {output(kVrQpIterationsTotal, "qp_iterations_total", VariableType::Integer, nullptr,
            "Active-set iterations of all per-step QPs so far (saturates at 2147483647)"),
     [](const PlateValues& v) { return saturate(v.outputs.qpIterationsTotal); }, nullptr},
    {output(kVrQpIterationsMax, "qp_iterations_max", VariableType::Integer, nullptr,
            "Largest number of active-set iterations of one per-step QP so far"),
     OUTPUT_FIELD(qpIterationsMax)},
    {output(kVrClampForce, "clamp_force", VariableType::Real, "N",
            "Vertical force the plate exerts on the clamp (positive upward): what a shaker carrying the clamp "
            "feels; the scheme's value at the last internal step's centre t - dt (t - dt/2 with time_scheme = "
            "conserving). Fed back with held values to a partner that moves the clamp (base_velocity) the loop is "
            "unstable: it carries the plate's rigid inertia one step late (an added mass), and impacts make it "
            "worse; base_drive = tlm couples stably, base_drive = force puts the armature inside"),
     PORT_FIELD(clampForce)},
    {output(kVrClampMoment, "clamp_moment", VariableType::Real, "N.m",
            "Moment about the clamp line x = 0 of the forces the plate exerts on the clamp (positive when "
            "they lift the plate side), at t - dt"),
     PORT_FIELD(clampMoment)},
    {output(kVrClampDisplacement, "clamp_displacement", VariableType::Real, "m",
            "Position z of the clamped edge as the scheme took it (the integrated input for base_drive = "
            "velocity or acceleration)"),
     PORT_FIELD(clampDisplacement)},
    {output(kVrClampVelocity, "clamp_velocity", VariableType::Real, "m/s",
            "Velocity of the clamped edge (second-order backward difference of the scheme's positions)"),
     PORT_FIELD(clampVelocity)},
    {output(kVrClampAcceleration, "clamp_acceleration", VariableType::Real, "m/s2",
            "Acceleration of the clamped edge at t - dt (the scheme's central difference): the control "
            "accelerometer"),
     PORT_FIELD(clampAcceleration)},
    {output(kVrContactForceLower, "contact_force_lower", VariableType::Real, "N",
            "Force of the lower obstacle on the plate over the last internal step (>= 0, upward)"),
     PORT_FIELD(contactForce[0])},
    {output(kVrContactForceUpper, "contact_force_upper", VariableType::Real, "N",
            "Force of the upper obstacle on the plate over the last internal step (<= 0, downward)"),
     PORT_FIELD(contactForce[1])},
    {output(kVrContactImpulseLower, "contact_impulse_lower", VariableType::Real, "N.s",
            "Impulse of the lower obstacle on the plate since t = 0 (cumulative)"),
     PORT_FIELD(contactImpulse[0])},
    {output(kVrContactImpulseUpper, "contact_impulse_upper", VariableType::Real, "N.s",
            "Impulse of the upper obstacle on the plate since t = 0 (cumulative, <= 0)"),
     PORT_FIELD(contactImpulse[1])},
    {output(kVrImpactsLower, "impacts_lower", VariableType::Integer, nullptr,
            "Contact onsets on the lower obstacle since t = 0 (steps whose contact force starts from zero)"),
     PORT_FIELD(impacts[0])},
    {output(kVrImpactsUpper, "impacts_upper", VariableType::Integer, nullptr,
            "Contact onsets on the upper obstacle since t = 0"),
     PORT_FIELD(impacts[1])},
    {output(kVrCorner1Velocity, "corner_1_velocity", VariableType::Real, "m/s",
            "Absolute velocity at corner_1 (second-order backward difference)"),
     PORT_FIELD(velocity[0])},
    {output(kVrCorner2Velocity, "corner_2_velocity", VariableType::Real, "m/s", "Absolute velocity at corner_2"),
     PORT_FIELD(velocity[1])},
    {output(kVrFreeEdgeMidVelocity, "free_edge_mid_velocity", VariableType::Real, "m/s",
            "Absolute velocity at free_edge_mid"),
     PORT_FIELD(velocity[2])},
    {output(kVrCorner1Acceleration, "corner_1_acceleration", VariableType::Real, "m/s2",
            "Absolute acceleration at corner_1 at t - dt (the scheme's central difference)"),
     PORT_FIELD(acceleration[0])},
    {output(kVrCorner2Acceleration, "corner_2_acceleration", VariableType::Real, "m/s2",
            "Absolute acceleration at corner_2 at t - dt"),
     PORT_FIELD(acceleration[1])},
    {output(kVrFreeEdgeMidAcceleration, "free_edge_mid_acceleration", VariableType::Real, "m/s2",
            "Absolute acceleration at free_edge_mid at t - dt"),
     PORT_FIELD(acceleration[2])},
    // The carried clamp (docs/theory.md §18–19): its motion is clamp_displacement, _velocity, _acceleration.
    {parameter(kVrArmatureMass, "armature_mass", VariableType::Real, "kg",
               "Mass of the armature carrying the clamp (base_drive = force; > 0)", plate::ranges::kArmatureMass),
     PARAMETER_FIELD(armatureMass)},
    {parameter(kVrArmatureStiffness, "armature_stiffness", VariableType::Real, "N/m",
               "Suspension stiffness of the armature (base_drive = force), relaxed at the initial clamp position",
               plate::ranges::kArmatureStiffness),
     PARAMETER_FIELD(armatureStiffness)},
    {parameter(kVrArmatureDamping, "armature_damping", VariableType::Real, "N.s/m",
               "Suspension damping of the armature (base_drive = force)", plate::ranges::kArmatureDamping),
     PARAMETER_FIELD(armatureDamping)},
    {parameter(kVrTlmImpedance, "tlm_impedance", VariableType::Real, "N.s/m",
               "Characteristic impedance Z of the transmission line to the partner (base_drive = tlm; > 0)",
               plate::ranges::kTlmImpedance),
     PARAMETER_FIELD(tlmImpedance)},
    {input(kVrDriveForce, "drive_force", "N", false, plate::kMaxCarrierForce,
           "Drive force on the armature, positive upward (base_drive = force)"),
     [](const PlateValues& v) { return v.driveForce.signal.value; },
     [](PlateValues& v, double x) { v.driveForce.setValue(x); }},
    {input(kVrTlmWaveIn, "tlm_wave_in", "N", false, plate::kMaxCarrierForce,
           "Wave arriving from the partner (base_drive = tlm): connect the partner's tlm_wave_out; held over "
           "the step"),
     [](const PlateValues& v) { return v.tlmWaveIn.signal.value; },
     [](PlateValues& v, double x) { v.tlmWaveIn.setValue(x); }},
    {output(kVrArmatureEnergy, "armature_energy", VariableType::Real, "J",
            "Discrete energy of the armature (kinetic + suspension spring); 0 for a line end"),
     CARRIER_FIELD(energy)},
    {output(kVrArmatureDriveWork, "armature_drive_work", VariableType::Real, "J",
            "Work of drive_force (or of tlm_wave_in) on the carrier since t = 0"),
     CARRIER_FIELD(driveWork)},
    {output(kVrArmatureDamped, "armature_damped", VariableType::Real, "J",
            "Energy dissipated in the carrier's damper (the suspension, or the line's impedance) since t = 0"),
     CARRIER_FIELD(damperWork)},
    {output(kVrArmaturePortWork, "armature_port_work", VariableType::Real, "J",
            "Work of the plate on the carrier since t = 0 (= -energy_input with load 0)"),
     CARRIER_FIELD(portWork)},
    {output(kVrTlmWaveOut, "tlm_wave_out", VariableType::Real, "N",
            "Mean wave launched into the line over the last communication step (base_drive = tlm): connect to "
            "the partner's tlm_wave_in"),
     CARRIER_FIELD(waveOut)},
    {output(kVrTlmTransit, "tlm_transit", VariableType::Real, "J",
            "Energy of the wave this end launched in the last step, stored in the line until the partner "
            "receives it"),
     CARRIER_FIELD(transit)},
    {output(kVrTlmLineLoss, "tlm_line_loss", VariableType::Real, "J",
            "Energy this end launched that the mean wave does not carry, since t = 0 (>= 0: the line is passive)"),
     CARRIER_FIELD(lineLoss)},
};

#undef PARAMETER_FIELD
#undef OUTPUT_FIELD
#undef PORT_FIELD
#undef CARRIER_FIELD

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

InputPort* PlateValues::inputPort(fmi2ValueReference vr) {
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
