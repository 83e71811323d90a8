#include "Variables.h"

#include <array>
#include <climits>
#include <string>

namespace plateimpact {
namespace {

using plate::ElementType;

// Table rows, one helper per kind of variable, so that the table below reads like the
// interface description.
using RealGet = double (*)(const ModelValues&);
using RealSet = void (*)(ModelValues&, double);
using IntGet = int (*)(const ModelValues&);
using IntSet = void (*)(ModelValues&, int);
using BoolGet = bool (*)(const ModelValues&);
using BoolSet = void (*)(ModelValues&, bool);

constexpr Variable realParameter(fmi2ValueReference vr, const char* name, RealGet get, RealSet set) {
    return {vr, name, VariableType::Real, Causality::Parameter, true,
            get, set, nullptr, nullptr, nullptr, nullptr};
}
constexpr Variable integerParameter(fmi2ValueReference vr, const char* name, IntGet get, IntSet set) {
    return {vr, name, VariableType::Integer, Causality::Parameter, true,
            nullptr, nullptr, get, set, nullptr, nullptr};
}
constexpr Variable enumerationParameter(fmi2ValueReference vr, const char* name, IntGet get, IntSet set) {
    return {vr, name, VariableType::Enumeration, Causality::Parameter, true,
            nullptr, nullptr, get, set, nullptr, nullptr};
}
constexpr Variable booleanParameter(fmi2ValueReference vr, const char* name, BoolGet get, BoolSet set) {
    return {vr, name, VariableType::Boolean, Causality::Parameter, true,
            nullptr, nullptr, nullptr, nullptr, get, set};
}
constexpr Variable realInput(fmi2ValueReference vr, const char* name, bool shapesInitialState,
                             RealGet get, RealSet set) {
    return {vr, name, VariableType::Real, Causality::Input, shapesInitialState,
            get, set, nullptr, nullptr, nullptr, nullptr};
}
constexpr Variable realOutput(fmi2ValueReference vr, const char* name, RealGet get) {
    return {vr, name, VariableType::Real, Causality::Output, false,
            get, nullptr, nullptr, nullptr, nullptr, nullptr};
}
constexpr Variable integerOutput(fmi2ValueReference vr, const char* name, IntGet get) {
    return {vr, name, VariableType::Integer, Causality::Output, false,
            nullptr, nullptr, get, nullptr, nullptr, nullptr};
}

// Enumeration ElementType in modelDescription.xml: argyris = 1, fvs = 2.
int elementItem(ElementType e) { return e == ElementType::Fvs ? 2 : 1; }
void setElementItem(ModelValues& v, int item) {
    if (item == 1) {
        v.parameters.element = ElementType::Argyris;
    } else if (item == 2) {
        v.parameters.element = ElementType::Fvs;
    } else {
        throw VariableError("element = " + std::to_string(item) +
                            " is not an item of the enumeration ElementType (argyris = 1, fvs = 2)");
    }
}

// Enumeration InputMode: hold = 1, linear = 2, quadratic = 3 (the values of plate::InputMode).
int inputModeItem(plate::InputMode m) { return static_cast<int>(m); }
plate::InputMode inputModeOf(const char* name, int item) {
    if (item < 1 || item > 3)
        throw VariableError(std::string(name) + " = " + std::to_string(item) +
                            " is not an item of the enumeration InputMode (hold = 1, linear = 2, quadratic = 3)");
    return static_cast<plate::InputMode>(item);
}

// A new value makes the input a plain value again: its derivatives are zero and not given,
// so the step reconstructs the input from the communicated values unless the master sets
// derivatives again.
void setInputValue(InputPort& port, double x) {
    port.signal = plate::InputSignal{x, 0.0, 0.0};
    port.derivativesGiven = false;
}

int saturateToInt(long long n) { return n > INT_MAX ? INT_MAX : n < INT_MIN ? INT_MIN : int(n); }

// Inputs: setting a value resets its derivatives (fmi2SetRealInputDerivatives). FMI 2.0 lets
// input derivatives apply to the communication step that follows them; a master that wants
// them for the next step as well sets them again after setting the new value. A master that
// sets values only gets the reconstruction chosen by base_input_mode / load_input_mode.
const std::array<Variable, 31> kVariables = {{
    realParameter(0, "length",
        [](const ModelValues& v) { return v.parameters.length; },
        [](ModelValues& v, double x) { v.parameters.length = x; }),
    realParameter(1, "width",
        [](const ModelValues& v) { return v.parameters.width; },
        [](ModelValues& v, double x) { v.parameters.width = x; }),
    realParameter(2, "thickness",
        [](const ModelValues& v) { return v.parameters.thickness; },
        [](ModelValues& v, double x) { v.parameters.thickness = x; }),
    realParameter(3, "youngs_modulus",
        [](const ModelValues& v) { return v.parameters.youngsModulus; },
        [](ModelValues& v, double x) { v.parameters.youngsModulus = x; }),
    realParameter(4, "poisson_ratio",
        [](const ModelValues& v) { return v.parameters.poissonRatio; },
        [](ModelValues& v, double x) { v.parameters.poissonRatio = x; }),
    realParameter(5, "density",
        [](const ModelValues& v) { return v.parameters.density; },
        [](ModelValues& v, double x) { v.parameters.density = x; }),
    integerParameter(6, "nx",
        [](const ModelValues& v) { return v.parameters.nx; },
        [](ModelValues& v, int x) { v.parameters.nx = x; }),
    integerParameter(7, "ny",
        [](const ModelValues& v) { return v.parameters.ny; },
        [](ModelValues& v, int x) { v.parameters.ny = x; }),
    enumerationParameter(8, "element",
        [](const ModelValues& v) { return elementItem(v.parameters.element); },
        setElementItem),
    realParameter(9, "obstacle_lower",
        [](const ModelValues& v) { return v.parameters.obstacleLower; },
        [](ModelValues& v, double x) { v.parameters.obstacleLower = x; }),
    realParameter(10, "obstacle_upper",
        [](const ModelValues& v) { return v.parameters.obstacleUpper; },
        [](ModelValues& v, double x) { v.parameters.obstacleUpper = x; }),
    booleanParameter(11, "obstacle_lower_enabled",
        [](const ModelValues& v) { return v.parameters.obstacleLowerEnabled; },
        [](ModelValues& v, bool x) { v.parameters.obstacleLowerEnabled = x; }),
    booleanParameter(12, "obstacle_upper_enabled",
        [](const ModelValues& v) { return v.parameters.obstacleUpperEnabled; },
        [](ModelValues& v, bool x) { v.parameters.obstacleUpperEnabled = x; }),
    realParameter(13, "dt",
        [](const ModelValues& v) { return v.parameters.dt; },
        [](ModelValues& v, double x) { v.parameters.dt = x; }),
    realParameter(14, "beta",
        [](const ModelValues& v) { return v.parameters.beta; },
        [](ModelValues& v, double x) { v.parameters.beta = x; }),
    realParameter(15, "initial_load",
        [](const ModelValues& v) { return v.parameters.initialLoad; },
        [](ModelValues& v, double x) { v.parameters.initialLoad = x; }),
    integerParameter(16, "modes",
        [](const ModelValues& v) { return v.parameters.modes; },
        [](ModelValues& v, int x) { v.parameters.modes = x; }),
    enumerationParameter(17, "base_input_mode",
        [](const ModelValues& v) { return inputModeItem(v.baseDisplacement.mode); },
        [](ModelValues& v, int x) { v.baseDisplacement.mode = inputModeOf("base_input_mode", x); }),
    enumerationParameter(18, "load_input_mode",
        [](const ModelValues& v) { return inputModeItem(v.load.mode); },
        [](ModelValues& v, int x) { v.load.mode = inputModeOf("load_input_mode", x); }),

    realInput(kVrBaseDisplacement, "base_displacement", true,
        [](const ModelValues& v) { return v.baseDisplacement.signal.value; },
        [](ModelValues& v, double x) { setInputValue(v.baseDisplacement, x); }),
    realInput(kVrLoad, "load", false,
        [](const ModelValues& v) { return v.load.signal.value; },
        [](ModelValues& v, double x) { setInputValue(v.load, x); }),

    realOutput(30, "corner_1", [](const ModelValues& v) { return v.outputs.corner1; }),
    realOutput(31, "corner_2", [](const ModelValues& v) { return v.outputs.corner2; }),
    realOutput(32, "free_edge_mid", [](const ModelValues& v) { return v.outputs.freeEdgeMid; }),
    realOutput(33, "energy", [](const ModelValues& v) { return v.outputs.energy; }),
    realOutput(34, "energy_dissipated", [](const ModelValues& v) { return v.outputs.energyDissipated; }),
    realOutput(35, "energy_input", [](const ModelValues& v) { return v.outputs.energyInput; }),
    integerOutput(36, "contact_vertices", [](const ModelValues& v) { return v.outputs.contactVertices; }),
    realOutput(37, "qp_kkt_residual_max", [](const ModelValues& v) { return v.outputs.maxKktResidual; }),
    integerOutput(38, "qp_iterations_total",
        [](const ModelValues& v) { return saturateToInt(v.outputs.qpIterationsTotal); }),
    integerOutput(39, "qp_iterations_max", [](const ModelValues& v) { return v.outputs.qpIterationsMax; }),
}};

}  // namespace

const Variable* findVariable(fmi2ValueReference vr) {
    for (const Variable& v : kVariables) {
        if (v.vr == vr) return &v;
    }
    return nullptr;
}

const char* typeName(VariableType type) {
    switch (type) {
        case VariableType::Real: return "Real";
        case VariableType::Integer: return "Integer";
        case VariableType::Boolean: return "Boolean";
        case VariableType::Enumeration: return "Enumeration";
    }
    return "?";
}

const char* causalityName(Causality causality) {
    switch (causality) {
        case Causality::Parameter: return "parameter";
        case Causality::Input: return "input";
        case Causality::Output: return "output";
    }
    return "?";
}

}  // namespace plateimpact
