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

#include "core/Fmi3Features.h"
#include "core/Types.h"

namespace fmu {

enum class VariableType { Real, Integer, Boolean };
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

// A value or call the model rejects; the message names what, the value and what is allowed.
// The generic layer logs it after the name of the front end's function.
class ModelError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A model: its table and behaviour for either FMI version, and what FMI 3.0 adds (Fmi3Features.h:
// arrays, terminals, early return, intermediate update), which the FMI 2.0 front end never asks.
class Model : public Fmi3Features {
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

    // What sets the model's accuracy instead of an importer's experiment tolerance (which it ignores).
    virtual std::string accuracyParameters() const { return "its parameters (a fixed time step)"; }

    // Everything beyond the variables' values that an FMU state must carry (append / read
    // back in the same order; `in` advances). restoreState throws ModelError on bad data.
    virtual void saveState(std::vector<double>& out) const = 0;
    virtual void restoreState(const double*& in, const double* end) = 0;

    // Where the model's trace messages go (the instance's logAll category).
    std::function<void(const std::string&)> trace = [](const std::string&) {};
    // Where the model's information for the user goes (the instance's logInfo category): what
    // an initialization will cost and how far it is.
    std::function<void(const std::string&)> inform = [](const std::string&) {};
    // Where the model's plausibility warnings go (the instance's logStatusWarning category, status
    // Warning): a result that is computed but likely not what the user meant, once each.
    std::function<void(const std::string&)> warn = [](const std::string&) {};

private:
    int fmiVersion_ = 2;
};

// Defined once by each model binding.
std::unique_ptr<Model> createModel();
const char* modelGuid();  // compiled in at build time (fmu/cmake/MakeGuid.cmake)

}  // namespace fmu
