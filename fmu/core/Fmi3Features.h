#pragma once
// What FMI 3.0 adds to a model (the fmi3/ front end and the FMI 3.0 description ask it; FMI 2.0
// has none of it): structural parameters and arrays, terminals, early return at events, and the
// intermediate update with its inputs. Every member has a default: a model without them (the
// demos) writes nothing here. fmu::Model derives from it (Model.h).
#include <cmath>
#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

#include "core/Types.h"

namespace fmu {

struct Variable;

// FMI 3.0 only (FMI 2.0 has no arrays): a structural parameter giving one extent of an array.
// Either a view of an Integer parameter of the table, not a value of its own:
// extent = parameter + offset; setting it sets the parameter (FMU states carry the parameter).
// Or (parameter = kOwnValue) a value of its own in [min, max], starting at `offset`, that the
// model keeps (Fmi3Features::ownStructuralValue; min = 0 lets the master empty the array, FMI 3.0
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

class Fmi3Features {
public:
    virtual ~Fmi3Features() = default;

    const StructuralParameter* findStructural(ValueReference vr) const;  // nullptr: none
    const ArrayVariable* findArray(ValueReference vr) const;  // nullptr: none

    // Early return: like doStep, but the step may end early, right after the first internal step at
    // which an event of the model happens (time() tells where). Returns whether the step ended at an
    // event. Asked only of a model that hasEvents (mightReturnEarlyFromDoStep).
    virtual bool hasEvents() const { return false; }
    virtual bool doStepUntilEvent(double t, double h);
    // providesIntermediateUpdate: doStep calls intermediateUpdate at its grid points.
    virtual bool providesIntermediateUpdate() const { return false; }
    // The internal step of the default configuration (fixedInternalStepSize); 0: none.
    virtual double fixedInternalStepSize() const { return 0.0; }
    // Arrays: none by default. getArray writes the product of the extents' values (read from the
    // table) into `out` (an output: called only when built()); setArray (a parameter) takes them, n
    // checked by the caller; throws ModelError.
    virtual const std::vector<StructuralParameter>& structuralParameters() const;
    virtual const std::vector<ArrayVariable>& arrayVariables() const;
    virtual void getArray(const ArrayVariable& a, double* out, std::size_t n) const;
    virtual void setArray(const ArrayVariable& a, const double* values, std::size_t n);
    virtual const std::vector<Terminal>& terminals() const;  // none by default
    // The value of a structural parameter with a value of its own (its start until set; the
    // caller has checked the range). A new instance (a reset) starts again from the starts. A
    // model that sizes its own data by one (the probes) overrides both for it.
    virtual double ownStructuralValue(const StructuralParameter& s) const;
    virtual void setOwnStructuralValue(const StructuralParameter& s, double value);
    // Intermediate update with inputs: the inputs a master may set inside its callback, at the grid
    // point the model is about to step to (intermediateUpdate="true" on an input), and such a value
    // (the instance has checked type, range and that the model asked for it). Default: none.
    virtual bool takesIntermediateValue(const Variable&) const { return false; }
    virtual void setIntermediate(const Variable& v, double value);

    // Intermediate update, when the master gave the callback: the model calls it at each
    // internal grid point inside a communication step, standing there (time() and the outputs
    // of that point); it returns the time at which the master wants the step to end (HUGE_VAL:
    // none), which a step that may return early honours at the first grid point not before it.
    std::function<double(double time)> intermediateUpdate;
    // Intermediate update with inputs, when the master gave the callback and required an
    // input that takesIntermediateValue: the model calls it before each internal step with the grid
    // time it steps to; the master sets those inputs there (setIntermediate), the step uses them.
    std::function<void(double time)> intermediateInputs;

private:
    std::vector<std::pair<ValueReference, double>> ownStructuralValues_;  // those set so far
};

}  // namespace fmu
