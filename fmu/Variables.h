#pragma once
// The one table of model variables of the PlateImpact FMU: value reference, name, type,
// causality and accessors. fmi2Get*/fmi2Set* go through this table only; it must agree with
// modelDescription/modelDescription.xml.in (python_tests/test_fmi_conformance.py checks that).
#include <cstddef>
#include <stdexcept>

#include "PlateSimulation.h"
#include "fmi2Functions.h"

namespace plateimpact {

// One Real input as the master passes it (docs/theory.md, "Inputs between communication
// points"): the value, the derivatives if the master set them since the value, and the values
// at the last communication points for masters that give none.
struct InputPort {
    plate::InputSignal signal;      // value (fmi2SetReal) + derivatives (fmi2SetRealInputDerivatives)
    bool derivativesGiven = false;  // the master set derivatives since the value: they win
    plate::InputMode mode;          // otherwise the step follows history.extrapolate(mode)
    plate::InputHistory history;

    explicit InputPort(plate::InputMode defaultMode) : mode(defaultMode) {}
    // The signal over the step of length h that starts now.
    plate::InputSignal stepSignal(double h) {
        if (!derivativesGiven) return history.continueStep(mode, h);
        history.reached(signal.at(h));
        return signal;
    }
};

// Everything an importer can set or read, as plain values.
struct ModelValues {
    plate::PlateParameters parameters;  // defaults = the start values in modelDescription.xml
    // Default modes, chosen by measurement (docs/input-accuracy.md): a clamp displacement is
    // smooth (quadratic extrapolation); a load may step, and extrapolating a step overshoots.
    InputPort baseDisplacement{plate::InputMode::Quadratic};
    InputPort load{plate::InputMode::Hold};
    plate::PlateOutputs outputs;          // copy of PlateSimulation::outputs() after each change
};

enum class VariableType { Real, Integer, Boolean, Enumeration };
enum class Causality { Parameter, Input, Output };

// A value an accessor rejects (e.g. an enumeration value without an item). The message names
// the variable, the value and what is allowed.
class VariableError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct Variable {
    fmi2ValueReference vr;
    const char* name;
    VariableType type;
    Causality causality;
    // true if a new value changes the initial state of the simulation (parameters and the
    // base displacement, which places the clamp at t = 0)
    bool shapesInitialState;
    // Accessors: the pair matching `type` is set (Enumeration uses the Integer pair); the
    // setters are null for outputs.
    double (*getReal)(const ModelValues&);
    void (*setReal)(ModelValues&, double);
    int (*getInteger)(const ModelValues&);
    void (*setInteger)(ModelValues&, int);
    bool (*getBoolean)(const ModelValues&);
    void (*setBoolean)(ModelValues&, bool);
};

// nullptr if no variable has this value reference.
const Variable* findVariable(fmi2ValueReference vr);

const char* typeName(VariableType type);
const char* causalityName(Causality causality);

// Value references of the inputs (also used by fmi2SetRealInputDerivatives).
constexpr fmi2ValueReference kVrBaseDisplacement = 20;
constexpr fmi2ValueReference kVrLoad = 21;

}  // namespace plateimpact
