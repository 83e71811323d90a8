#pragma once
// The contract between the model-independent co-simulation core (Instance.cpp, StateFormat.cpp;
// of no FMI version, the front ends fmi2/ and fmi3/ over it) and one model binding
// (binding/PlateModel.cpp, or demos/sinesweep/SweepModel.cpp): the model's table of variables and its behaviour. The same table
// writes modelDescription.xml (modelDescription/WriteModelDescription.cpp), serializes FMU
// states and decides whether two configurations are equal. A binding knows nothing of the FMI
// state machine; the generic layer knows nothing of plates.
#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/Types.h"

namespace fmu {

enum class VariableType { Real, Integer, Boolean };
enum class Causality { Parameter, Input, Output };
const char* typeName(VariableType type);  // as modelDescription.xml spells it: "Real", ...

struct EnumerationItem {
    const char* name;
    int value;
    const char* description;
};

// The named values of an Integer switch (element, base_drive, ...): the one place its items are
// written down. A switch is an Integer, not an FMI Enumeration, because several masters
// (libcosim, ecos, mosaik-fmi) silently ignore Enumeration variables; the description writer
// declares min/max from the items and lists them in the variable's description, and the
// generic layer refuses a value that is not an item.
struct EnumerationType {
    const char* name;
    const char* description;
    std::vector<EnumerationItem> items;
    bool contains(int value) const;
    std::string itemList() const;  // "1 = argyris, 2 = fvs"
    int lowest() const;
    int highest() const;
};

// One row of a model's table of variables.
struct Variable {
    ValueReference vr;
    const char* name;
    VariableType type;
    Causality causality;
    const char* description;
    const char* unit = nullptr;  // Real only; nullptr: none
    const EnumerationType* enumeration = nullptr;  // Integer switches only: their named items
    // A new value before initialization ends invalidates what was built from the old one
    // (parameters; an input that places the initial state).
    bool shapesInitialState = false;
    // Real inputs: take input derivatives; Real outputs: give output derivatives (FMI 2.0's
    // SetRealInputDerivatives and GetRealOutputDerivatives).
    bool hasDerivatives = false;
    // The allowed range (Real, Integer), NaN where there is none: modelDescription.xml's min and
    // max, the documentation's table; the generic layer refuses an input outside it when set
    // (a parameter's range, open ends included, is the binding's check at initialization).
    double min = NAN, max = NAN;
    bool hasRange() const { return !std::isnan(min) || !std::isnan(max); }
    // The FMI version whose interface has it: 0 both; 2 or 3 that one only (the FMI 2.0 FMU's scalar
    // probes, which FMI 3.0 has as arrays). Model::find does not see a row of the other version.
    int version = 0;
};

// A parameter that switches between named items (element, base_drive, ...): an Integer whose
// min/max are its items' range; the description writer lists the items after `description`.
Variable integerSwitch(ValueReference vr, const char* name, const char* description, const EnumerationType& items);

// Capabilities and fixed parts of modelDescription.xml.
struct ModelInfo {
    const char* modelName;
    const char* modelIdentifier;
    const char* description;
    bool canInterpolateInputs;
    int maxOutputDerivativeOrder;
    bool canGetAndSetFMUstate;  // and canSerializeFMUstate
    double defaultStopTime, defaultStepSize;
    // HTML for documentation/index.html beside the table of variables (what the model is, its
    // default scene, its limits); nullptr: the table only.
    const char* documentationHtml = nullptr;
    // The first 8 bytes of a serialized FMU state (no terminating NUL needed): names the model.
    const char* stateMagic = "FMUSTATE";
};

// FMI 3.0 only (FMI 2.0 has no arrays): a structural parameter giving one extent of an array.
// Either a view of an Integer parameter of the table, not a value of its own:
// extent = parameter + offset; setting it sets the parameter (FMU states carry the parameter).
// Or (parameter = kOwnValue) a value of its own in [min, max], starting at `offset`, that the
// model keeps (Model::ownStructuralValue; min = 0 lets the master empty the array, FMI 3.0
// §2.4.7.3). `configurationOnly`: settable in Configuration Mode only (FMI 3.0's rule for a fixed
// structural parameter); otherwise also in the instantiated state, the leniency the first ones
// (vertex_output, vertices_x, vertices_y) kept for the masters that set them there.
constexpr ValueReference kOwnValue = 0xFFFFFFFFu;
struct StructuralParameter {
    ValueReference vr;
    const char* name;
    const char* description;
    ValueReference parameter;  // the table's Integer parameter it is a view of, or kOwnValue
    int offset;  // a view: extent = parameter + offset; an own value: its start
    int min = 0, max = 0;  // an own value's range (a view's is its parameter's check)
    bool configurationOnly = false;
    bool ownValue() const { return parameter == kOwnValue; }
};

// FMI 3.0 only: an array variable (row-major, the first extent varies slowest): an output, or a
// parameter (a fixed Float64 array set before initialization ends, its range checked by the model).
struct ArrayVariable {
    ValueReference vr;
    const char* name;
    const char* description;
    const char* unit;  // nullptr: none
    std::vector<ValueReference> extents;  // value references of StructuralParameters
    Causality causality = Causality::Output;
    double min = NAN, max = NAN;  // a parameter's declared range
};

// FMI 3.0 terminals (terminalsAndIcons/terminalsAndIcons.xml, FMI 3.0 section 2.4.9): a named
// group of the table's variables that a system tool connects as one. The description writer
// checks that every member names a variable of the table.
struct TerminalMember {
    const char* variableName;  // a variable of the table
    const char* memberName;  // matched against the partner's (plug, bus)
    const char* variableKind;  // signal, inflow, outflow or a reverse-DNS kind
};
struct Terminal {
    const char* name;
    const char* matchingRule;  // plug, bus, sequence, none or a reverse-DNS rule
    const char* terminalKind;  // reverse-DNS; what it means is the model's documentation
    const char* description;
    std::vector<TerminalMember> members;
};

// A value or call the model rejects; the message names what, the value and what is allowed.
// The generic layer logs it after the name of the front end's function.
class ModelError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class Model {
public:
    virtual ~Model() = default;

    virtual const ModelInfo& info() const = 0;
    virtual const std::vector<Variable>& variables() const = 0;
    // The row of `vr` in the interface of fmiVersion() (nullptr: none there).
    const Variable* find(ValueReference vr) const;
    // The FMI version of the front end the model serves (the instance sets it before anything
    // else, the description writer too): which rows find() sees, and the defaults that differ.
    int fmiVersion() const { return fmiVersion_; }
    virtual void useVersion(int version) { fmiVersion_ = version; }
    const StructuralParameter* findStructural(ValueReference vr) const;  // nullptr: none
    const ArrayVariable* findArray(ValueReference vr) const;  // nullptr: none

    // Values, as doubles for every type (Integer and Boolean exactly). The generic
    // layer has checked type, causality and finiteness; `set` may still throw ModelError.
    virtual double get(const Variable& v) const = 0;
    virtual void set(const Variable& v, double value) = 0;
    virtual void setInputDerivative(const Variable& v, int order, double value);
    virtual double getOutputDerivative(const Variable& v, int order) const;

    // Builds what the parameters describe (when initialization mode is left, or earlier when an
    // output is read in initialization mode); drops it again (a shaping value changed).
    virtual void build() = 0;
    virtual bool built() const = 0;
    virtual void drop() = 0;
    // Time since the start of the experiment.
    virtual double time() const = 0;
    // The end of the run (terminate): what the model has to say about the run as a whole.
    virtual void terminate() {}
    // One communication step [t, t + h] (t checked by the caller); throws ModelError.
    virtual void doStep(double t, double h) = 0;

    // FMI 3.0 early return (the fmi3/ front end): like doStep, but the step may end early,
    // right after the first internal step at which an event of the model happens (time()
    // tells where). Returns whether the step ended at an event. Default: no events.
    virtual bool doStepUntilEvent(double t, double h) {
        doStep(t, h);
        return false;
    }
    virtual bool hasEvents() const { return false; }  // mightReturnEarlyFromDoStep
    // FMI 3.0 providesIntermediateUpdate: doStep calls intermediateUpdate at its grid points.
    virtual bool providesIntermediateUpdate() const { return false; }
    // What sets the model's accuracy instead of an importer's experiment tolerance (which it ignores).
    virtual std::string accuracyParameters() const { return "its parameters (a fixed time step)"; }
    // The internal step of the default configuration (fixedInternalStepSize); 0: none.
    virtual double fixedInternalStepSize() const { return 0.0; }
    // FMI 3.0 arrays: none by default. getArray writes the product of the extents' values
    // (read from the table) into `out` (an output: called only when built()); setArray (a
    // parameter) takes them, n checked by the caller; throws ModelError.
    virtual const std::vector<StructuralParameter>& structuralParameters() const;
    virtual const std::vector<ArrayVariable>& arrayVariables() const;
    virtual void getArray(const ArrayVariable& a, double* out, std::size_t n) const;
    virtual void setArray(const ArrayVariable& a, const double* values, std::size_t n);
    // FMI 3.0 terminals: none by default.
    virtual const std::vector<Terminal>& terminals() const;
    // The value of a structural parameter with a value of its own (its start until set; the
    // caller has checked the range). A new instance (a reset) starts again from the starts. A
    // model that sizes its own data by one (the probes) overrides both for it.
    virtual double ownStructuralValue(const StructuralParameter& s) const;
    virtual void setOwnStructuralValue(const StructuralParameter& s, double value);

    // Everything beyond the variables' values that an FMU state must carry (append / read
    // back in the same order; `in` advances). restoreState throws ModelError on bad data.
    virtual void saveState(std::vector<double>& out) const = 0;
    virtual void restoreState(const double*& in, const double* end) = 0;

    // FMI 3.0 intermediate update with inputs: the inputs a master may set inside its callback, at
    // the grid point the model is about to step to (FMI 3.0 intermediateUpdate="true" on an input),
    // and such a value (the instance has checked type, range and that the model asked for it).
    // Default: none.
    virtual bool takesIntermediateValue(const Variable&) const { return false; }
    virtual void setIntermediate(const Variable& v, double value);

    // Where the model's trace messages go (the instance's logAll category).
    std::function<void(const std::string&)> trace = [](const std::string&) {};
    // Where the model's information for the user goes (the instance's logInfo category): what
    // an initialization will cost and how far it is.
    std::function<void(const std::string&)> inform = [](const std::string&) {};
    // Where the model's plausibility warnings go (the instance's logStatusWarning category, status
    // Warning): a result that is computed but likely not what the user meant, once each.
    std::function<void(const std::string&)> warn = [](const std::string&) {};
    // FMI 3.0 intermediate update, when the master gave the callback: the model calls it at each
    // internal grid point inside a communication step, standing there (time() and the outputs
    // of that point); it returns the time at which the master wants the step to end (HUGE_VAL:
    // none), which a step that may return early honours at the first grid point not before it.
    std::function<double(double time)> intermediateUpdate;
    // FMI 3.0 intermediate update with inputs, when the master gave the callback and required an
    // input that takesIntermediateValue: the model calls it before each internal step with the grid
    // time it steps to; the master sets those inputs there (setIntermediate), the step uses them.
    std::function<void(double time)> intermediateInputs;

private:
    std::vector<std::pair<ValueReference, double>> ownStructuralValues_;  // those set so far
    int fmiVersion_ = 2;
};

// Defined once by each model binding.
std::unique_ptr<Model> createModel();
const char* modelGuid();  // compiled in at build time (fmu/cmake/MakeGuid.cmake)

}  // namespace fmu
