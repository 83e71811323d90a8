// The FMI 3.0 C API (Co-Simulation), model-independent: a thin front end over the same
// version-neutral core as fmi2/fmi2Functions.cpp (core/Instance.h), converting FMI 3.0 types
// and statuses. Every fmi3* function runs its body through Instance::call with the states that
// allow it (Fmi3Interface.h), which logs an illegal call sequence, prefixes messages with the
// function's name and keeps exceptions inside. Beyond FMI 2.0: the independent variable
// "time", array outputs sized by UInt64 structural parameters (views
// of Integer parameters of the table, Model.h), configuration mode, and early return with
// event mode at the model's events (Model::doStepUntilEvent) when the master grants them at
// fmi3InstantiateCoSimulation. Only the fmi3* symbols leave the shared object (fmi3/exports.map).
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "fmi3/Fmi3Interface.h"
#include "core/Instance.h"
#include "fmi3Functions.h"

using fmu::ArrayVariable;
using fmu::Instance;
using fmu::Status;
using fmu::StructuralParameter;
using fmu::VariableType;
using fmu::fmi3::kTimeValueReference;

static_assert(std::is_same_v<fmi3ValueReference, fmu::ValueReference> && std::is_same_v<fmi3Byte, fmu::Byte> &&
                  std::is_same_v<fmi3Int32, int>,
              "value references, bytes and derivative orders pass unconverted");

namespace {

// Tolerance of "the step ended before t + h" (the model's grid times against the master's sum).
constexpr double kEarlyTolerance = 1e-9;

// The functions the core's messages name. The size message has always named FMI 2.0's
// function, in FMI 3.0 too; kept so that the messages stay as they were.
constexpr fmu::ApiNames kNames = {"fmi3ExitInitializationMode", "fmi3SerializedFMUStateSize", 3};

// Status and fmi3Status list the same outcomes in the same order.
fmi3Status toFmi3(Status status) {
    static constexpr fmi3Status kStatus[] = {fmi3OK, fmi3Warning, fmi3Discard, fmi3Error, fmi3Fatal};
    return kStatus[static_cast<int>(status)];
}

// The core's logger over the master's fmi3LogMessageCallback (none without one).
fmu::Logger loggerOf(fmi3InstanceEnvironment environment, fmi3LogMessageCallback logMessage) {
    if (!logMessage) return nullptr;
    return [environment, logMessage](Status status, const char* category, const char* message) {
        logMessage(environment, toFmi3(status), category, message);
    };
}

// One FMI 3.0 instance: the master's callbacks and grants, and the core's Instance.
struct Fmi3Instance {
    fmi3InstanceEnvironment environment = nullptr;
    bool eventModeUsed = false;
    bool earlyReturnAllowed = false;
    fmi3IntermediateUpdateCallback intermediateUpdate = nullptr;
    std::unique_ptr<Instance> instance;
};

// Runs `body(self, instance)` as `function` when `c` is an instance and the state allows it.
template <class Body>
fmi3Status run(fmi3Instance c, const char* function, unsigned allowed, Body&& body) {
    auto* self = static_cast<Fmi3Instance*>(c);
    if (!self) return fmi3Error;  // a NULL instance has no logger to tell
    Instance& instance = *self->instance;
    return toFmi3(instance.call(function, allowed, [&]() -> Status { return body(*self, instance); }));
}

// The FMI 3.0 types of the get/set functions, as far as they concern this layer.
enum class Kind { Float64, Int32, Int64, UInt64, Boolean, Other };

// The FMI 3.0 type of the variable behind vr, for messages ("Float64 variable length").
std::string describe(const fmu::Model& model, fmi3ValueReference vr) {
    if (vr == kTimeValueReference) return "the Float64 variable time";
    if (const StructuralParameter* s = model.findStructural(vr)) return std::string("the UInt64 variable ") + s->name;
    if (const ArrayVariable* a = model.findArray(vr))
        return std::string("the Float64 ") +
               (a->causality == fmu::Causality::Parameter ? "parameter array " : "array ") + a->name;
    if (const fmu::Variable* v = model.find(vr))
        return std::string("the ") + fmu::fmi3::typeName(v->type) + " variable " + v->name;
    return "no variable (unknown value reference)";
}

// The table's type a Kind reads and writes (Int64 and the rest: none of the table's).
bool tableTypeOf(Kind kind, const fmu::Variable& v, VariableType* type) {
    switch (kind) {
        case Kind::Float64: *type = VariableType::Real; return v.type == VariableType::Real;
        case Kind::Int32: *type = VariableType::Integer; return v.type == VariableType::Integer;
        case Kind::Boolean: *type = VariableType::Boolean; return v.type == VariableType::Boolean;
        default: return false;
    }
}

// One scalar of an fmi3Get<kind> call into *x.
Status getScalar(Instance& i, Kind kind, fmi3ValueReference vr, double* x) {
    const fmu::Model& model = i.model();
    if (vr == kTimeValueReference && kind == Kind::Float64) {
        *x = i.currentTime();
        return Status::OK;
    }
    if (const StructuralParameter* s = model.findStructural(vr)) {
        if (kind != Kind::UInt64) return i.fail("value reference %u is %s", vr, describe(model, vr).c_str());
        *x = double(i.structuralValue(*s));
        return Status::OK;
    }
    const fmu::Variable* v = model.find(vr);
    VariableType type;
    if (!v || !tableTypeOf(kind, *v, &type)) return i.fail("value reference %u is %s", vr, describe(model, vr).c_str());
    return i.getValues(type, &vr, 1, x);
}

// Outputs exist from initialization mode on (parameters and inputs can be read before).
bool beforeInitialization(const Instance& i, fmi3ValueReference vr) {
    if (!(i.state() & (fmu::Instantiated | fmu::ConfigurationMode))) return false;
    const fmu::Variable* v = i.model().find(vr);
    const ArrayVariable* a = i.model().findArray(vr);
    return (a && a->causality == fmu::Causality::Output) || vr == kTimeValueReference ||
           (v && v->causality == fmu::Causality::Output);
}

template <class T>
Status getValues(Instance& i, Kind kind, const fmi3ValueReference vrs[], size_t nvr, T values[], size_t nValues) {
    if (nvr == 0) return Status::OK;
    if (!vrs || !values) return i.fail("arguments valueReferences[] and values[] must not be NULL");
    std::size_t next = 0;
    for (size_t k = 0; k < nvr; ++k) {
        if (beforeInitialization(i, vrs[k]))
            return i.fail("value reference %u is %s, an output: available from initialization mode on", vrs[k],
                          describe(i.model(), vrs[k]).c_str());
        const ArrayVariable* array = i.model().findArray(vrs[k]);
        if (array && kind != Kind::Float64)
            return i.fail("value reference %u is %s", vrs[k], describe(i.model(), vrs[k]).c_str());
        const std::size_t n = array ? i.arrayLength(*array) : 1;
        if (nValues - next < n || next > nValues)
            return i.fail(
                "nValues = %zu is too small: %s (value reference %u) needs %zu values, from position %zu "
                "of values[]",
                nValues, describe(i.model(), vrs[k]).c_str(), vrs[k], n, next);
        if (array) {
            if constexpr (std::is_same_v<T, double>) {  // an emptied array (an extent 0) has nothing to ask
                if (n > 0 && i.getArray(*array, values + next, n) != Status::OK) return Status::Error;
            }
        } else {
            double x = 0.0;
            if (getScalar(i, kind, vrs[k], &x) != Status::OK) return Status::Error;
            values[next] = static_cast<T>(x);
        }
        next += n;
    }
    if (next != nValues) {
        std::string arrays;  // which of them are arrays, and their sizes
        for (size_t k = 0; k < nvr; ++k)
            if (const ArrayVariable* array = i.model().findArray(vrs[k]))
                arrays += std::string(arrays.empty() ? "" : ", ") + array->name + " needs " +
                          std::to_string(i.arrayLength(*array)) + " values";
        return i.fail("nValues = %zu, but the %zu value references have %zu values%s%s%s", nValues, nvr, next,
                      arrays.empty() ? "" : " (", arrays.c_str(), arrays.empty() ? "" : ")");
    }
    return Status::OK;
}

Status setScalar(Instance& i, Kind kind, fmi3ValueReference vr, double x) {
    const fmu::Model& model = i.model();
    if (const StructuralParameter* s = model.findStructural(vr); s && kind == Kind::UInt64)
        return i.setStructural(*s, x);
    if (vr == kTimeValueReference)
        return i.fail("value reference %u is %s, which cannot be set", vr, describe(model, vr).c_str());
    const fmu::Variable* v = model.find(vr);
    VariableType type;
    if (!v || !tableTypeOf(kind, *v, &type)) return i.fail("value reference %u is %s", vr, describe(model, vr).c_str());
    return i.setValues(type, &vr, 1, &x);
}

// The values of every value reference, an array's as many as its extents give now (a parameter
// array: Float64; an output array is refused by name).
template <class T>
Status setValues(Instance& i, Kind kind, const fmi3ValueReference vrs[], size_t nvr, const T values[], size_t nValues) {
    if (nvr == 0) return Status::OK;
    if (!vrs || !values) return i.fail("arguments valueReferences[] and values[] must not be NULL");
    std::size_t next = 0;
    for (size_t k = 0; k < nvr; ++k) {
        const ArrayVariable* array = i.model().findArray(vrs[k]);
        if (array && (kind != Kind::Float64 || array->causality != fmu::Causality::Parameter))
            return i.fail("value reference %u is %s, which cannot be set%s", vrs[k],
                          describe(i.model(), vrs[k]).c_str(), kind != Kind::Float64 ? " with this type" : "");
        const std::size_t n = array ? i.arrayLength(*array) : 1;
        if (next > nValues || nValues - next < n)
            return i.fail(
                "nValues = %zu is too small: %s (value reference %u) takes %zu values, from position %zu of values[]",
                nValues, describe(i.model(), vrs[k]).c_str(), vrs[k], n, next);
        if (array) {
            if constexpr (std::is_same_v<T, double>) {
                if (i.setArray(*array, values + next, n) != Status::OK) return Status::Error;
            }
        } else {
            const double x = kind == Kind::Boolean ? double(values[next] != 0) : double(values[next]);
            if (setScalar(i, kind, vrs[k], x) != Status::OK) return Status::Error;
        }
        next += n;
    }
    if (next != nValues)
        return i.fail("nValues = %zu, but the %zu value references take %zu values", nValues, nvr, next);
    return Status::OK;
}

// fmi3Get/Set of a type this FMU has no variables of.
Status noVariables(Instance& i, const char* type, const fmi3ValueReference vrs[], size_t nvr) {
    if (nvr == 0) return Status::OK;
    const fmi3ValueReference vr = vrs ? vrs[0] : 0u;
    return i.fail("this FMU has no %s variables (value reference %u is %s)", type, vr, describe(i.model(), vr).c_str());
}

fmi3Status unsupported(fmi3Instance c, const char* function, const char* why) {
    return run(c, function, fmu::kAnyState, [&](Fmi3Instance&, Instance& i) { return i.fail("%s", why); });
}

constexpr const char* kModelExchange =
    "Model Exchange is not supported; this FMU implements FMI 3.0 Co-Simulation only";
constexpr const char* kScheduled = "Scheduled Execution is not supported; this FMU implements Co-Simulation only";
constexpr const char* kNoClocks = "this FMU has no clocks";

// An instantiation of an interface type this FMU does not implement: logs why, returns NULL.
fmi3Instance refuse(fmi3InstanceEnvironment environment, fmi3LogMessageCallback logMessage, const char* function,
                    fmi3String instanceName, const char* why) {
    fmu::logWithoutInstance(loggerOf(environment, logMessage), "%s (%s): %s", function,
                            instanceName ? instanceName : "", why);
    return nullptr;
}

}  // namespace

#define PLATEIMPACT_FMI3_GET(Name, T, kind)                                                                      \
    fmi3Status fmi3Get##Name(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, T values[], size_t n) { \
        return run(c, "fmi3Get" #Name, fmu::fmi3::kGetStates,                                                    \
                   [&](Fmi3Instance&, Instance& i) { return getValues(i, kind, vrs, nvr, values, n); });         \
    }
#define PLATEIMPACT_FMI3_SET(Name, T, kind)                                                                            \
    fmi3Status fmi3Set##Name(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, const T values[], size_t n) { \
        return run(c, "fmi3Set" #Name, fmu::fmi3::kSetStates,                                                          \
                   [&](Fmi3Instance&, Instance& i) { return setValues(i, kind, vrs, nvr, values, n); });               \
    }
#define PLATEIMPACT_FMI3_NONE(Name, T, Const)                                                                 \
    fmi3Status fmi3Get##Name(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, T[], size_t) {       \
        return run(c, "fmi3Get" #Name, fmu::fmi3::kGetStates,                                                 \
                   [&](Fmi3Instance&, Instance& i) { return noVariables(i, #Name, vrs, nvr); });              \
    }                                                                                                         \
    fmi3Status fmi3Set##Name(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, Const T[], size_t) { \
        return run(c, "fmi3Set" #Name, fmu::fmi3::kSetStates,                                                 \
                   [&](Fmi3Instance&, Instance& i) { return noVariables(i, #Name, vrs, nvr); });              \
    }

extern "C" {

// ---------------------------------------------------------------------------------------------
// Common functions

const char* fmi3GetVersion(void) { return fmi3Version; }

fmi3Status fmi3SetDebugLogging(fmi3Instance c, fmi3Boolean loggingOn, size_t nCategories,
                               const fmi3String categories[]) {
    return run(c, "fmi3SetDebugLogging", fmu::fmi3::kDebugLoggingStates,
               [&](Fmi3Instance&, Instance& i) { return i.setDebugLogging(loggingOn, nCategories, categories); });
}

fmi3Instance fmi3InstantiateCoSimulation(fmi3String instanceName, fmi3String instantiationToken, fmi3String,
                                         fmi3Boolean, fmi3Boolean loggingOn, fmi3Boolean eventModeUsed,
                                         fmi3Boolean earlyReturnAllowed,
                                         const fmi3ValueReference requiredIntermediateVariables[],
                                         size_t nRequiredIntermediateVariables,
                                         fmi3InstanceEnvironment instanceEnvironment, fmi3LogMessageCallback logMessage,
                                         fmi3IntermediateUpdateCallback intermediateUpdate) {
    try {
        auto self = std::make_unique<Fmi3Instance>();
        self->environment = instanceEnvironment;
        self->eventModeUsed = eventModeUsed;
        self->earlyReturnAllowed = earlyReturnAllowed;
        const fmu::Logger logger = loggerOf(instanceEnvironment, logMessage);
        const char* f = "fmi3InstantiateCoSimulation";
        if (!instanceName || instanceName[0] == '\0') {
            fmu::logWithoutInstance(logger, "%s: missing instance name", f);
            return nullptr;
        }
        if (!instantiationToken || std::strcmp(instantiationToken, fmu::modelGuid()) != 0) {
            fmu::logWithoutInstance(logger,
                                    "%s: wrong instantiationToken \"%s\"; this binary has \"%s\" "
                                    "(modelDescription.xml and binary come from different builds)",
                                    f, instantiationToken ? instantiationToken : "(null)", fmu::modelGuid());
            return nullptr;
        }
        self->intermediateUpdate = intermediateUpdate;
        self->instance = std::make_unique<Instance>(logger, loggingOn, kNames);
        self->instance->log(Status::OK, fmu::LogAll, "%s: instance \"%s\" of %s (instantiationToken %s)", f,
                            instanceName, self->instance->model().info().modelName, fmu::modelGuid());
        // Intermediate update (providesIntermediateUpdate): the outputs, the arrays and time may be
        // read inside the callback after each internal step; the inputs that take intermediate values
        // (intermediateUpdate="true": base_displacement, load), when required, are asked for before
        // each internal step (intermediateVariableSetRequested = true) and used at that grid point.
        const fmu::Model& model = self->instance->model();
        bool inputsRequired = false;
        for (size_t k = 0; k < nRequiredIntermediateVariables; ++k) {
            const fmi3ValueReference vr = requiredIntermediateVariables ? requiredIntermediateVariables[k] : 0;
            const fmu::Variable* v = model.find(vr);
            const bool readable =
                vr == kTimeValueReference || (v && v->causality == fmu::Causality::Output) || model.findArray(vr);
            const bool input = v && v->causality == fmu::Causality::Input && model.takesIntermediateValue(*v);
            inputsRequired = inputsRequired || input;
            if (!requiredIntermediateVariables || !(readable || input)) {
                std::string inputs;
                for (const fmu::Variable& w : model.variables())
                    if (model.takesIntermediateValue(w)) inputs += std::string(inputs.empty() ? "" : ", ") + w.name;
                fmu::logWithoutInstance(
                    logger,
                    "%s: required intermediate variable %s (vr %u) has no intermediateUpdate=\"true\" "
                    "(the intermediate update variables are the outputs, the arrays, time and "
                    "the inputs %s)",
                    f, v ? v->name : "(unknown)", vr, inputs.c_str());
                return nullptr;
            }
        }
        if (intermediateUpdate && inputsRequired) {
            Fmi3Instance* raw = self.get();
            self->instance->setIntermediateInputs([raw](double time) {
                fmi3Boolean requested = fmi3False;
                fmi3Float64 at = time;
                raw->intermediateUpdate(raw->environment, time, /*intermediateVariableSetRequested=*/fmi3True,
                                        /*intermediateVariableGetAllowed=*/fmi3False,
                                        /*intermediateStepFinished=*/fmi3False, /*canReturnEarly=*/fmi3False,
                                        &requested, &at);
            });
        }
        if (intermediateUpdate) {
            Fmi3Instance* raw = self.get();
            self->instance->setIntermediateUpdate([raw](double time) {
                fmi3Boolean requested = fmi3False;
                fmi3Float64 at = time;
                raw->intermediateUpdate(raw->environment, time, /*intermediateVariableSetRequested=*/fmi3False,
                                        /*intermediateVariableGetAllowed=*/fmi3True,
                                        /*intermediateStepFinished=*/fmi3True, raw->earlyReturnAllowed, &requested,
                                        &at);
                return requested && raw->earlyReturnAllowed ? at : HUGE_VAL;
            });
        }
        return self.release();
    } catch (...) {
        if (logMessage)
            logMessage(instanceEnvironment, fmi3Error, "logStatusError", "fmi3InstantiateCoSimulation: out of memory");
        return nullptr;
    }
}

fmi3Instance fmi3InstantiateModelExchange(fmi3String instanceName, fmi3String, fmi3String, fmi3Boolean, fmi3Boolean,
                                          fmi3InstanceEnvironment instanceEnvironment,
                                          fmi3LogMessageCallback logMessage) {
    return refuse(instanceEnvironment, logMessage, "fmi3InstantiateModelExchange", instanceName, kModelExchange);
}

fmi3Instance fmi3InstantiateScheduledExecution(fmi3String instanceName, fmi3String, fmi3String, fmi3Boolean,
                                               fmi3Boolean, fmi3InstanceEnvironment instanceEnvironment,
                                               fmi3LogMessageCallback logMessage, fmi3ClockUpdateCallback,
                                               fmi3LockPreemptionCallback, fmi3UnlockPreemptionCallback) {
    return refuse(instanceEnvironment, logMessage, "fmi3InstantiateScheduledExecution", instanceName, kScheduled);
}

void fmi3FreeInstance(fmi3Instance c) {
    std::unique_ptr<Fmi3Instance> owned(static_cast<Fmi3Instance*>(c));
    if (owned) owned->instance->log(Status::OK, fmu::LogAll, "fmi3FreeInstance");
}

fmi3Status fmi3EnterInitializationMode(fmi3Instance c, fmi3Boolean toleranceDefined, fmi3Float64 tolerance,
                                       fmi3Float64 startTime, fmi3Boolean stopTimeDefined, fmi3Float64 stopTime) {
    return run(c, "fmi3EnterInitializationMode", fmu::Instantiated, [&](Fmi3Instance&, Instance& i) {
        const Status status = i.setupExperiment(startTime, toleranceDefined, tolerance, stopTimeDefined, stopTime);
        return status == Status::OK ? i.enterInitializationMode() : status;
    });
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance c) {
    return run(c, "fmi3ExitInitializationMode", fmu::InitializationMode, [](Fmi3Instance& self, Instance& i) {
        const Status status = i.exitInitializationMode();
        if (status == Status::OK && self.eventModeUsed) i.enterState(fmu::EventMode);
        return status;
    });
}

fmi3Status fmi3EnterEventMode(fmi3Instance c) {
    return run(c, "fmi3EnterEventMode", fmu::fmi3::StepMode, [](Fmi3Instance& self, Instance& i) {
        if (!self.eventModeUsed) return i.fail("event mode was not requested at instantiation (eventModeUsed = false)");
        i.enterState(fmu::EventMode);
        return Status::OK;
    });
}

fmi3Status fmi3Terminate(fmi3Instance c) {
    return run(c, "fmi3Terminate", fmu::fmi3::kTerminateStates,
               [](Fmi3Instance&, Instance& i) { return i.terminate(); });
}

fmi3Status fmi3Reset(fmi3Instance c) {
    return run(c, "fmi3Reset", fmu::fmi3::kResetStates, [](Fmi3Instance&, Instance& i) { return i.reset(); });
}

// ---------------------------------------------------------------------------------------------
// Variables

PLATEIMPACT_FMI3_GET(Float64, fmi3Float64, Kind::Float64)
PLATEIMPACT_FMI3_GET(Int32, fmi3Int32, Kind::Int32)
PLATEIMPACT_FMI3_GET(Int64, fmi3Int64, Kind::Int64)
PLATEIMPACT_FMI3_GET(UInt64, fmi3UInt64, Kind::UInt64)
PLATEIMPACT_FMI3_GET(Boolean, fmi3Boolean, Kind::Boolean)
PLATEIMPACT_FMI3_SET(Float64, fmi3Float64, Kind::Float64)
PLATEIMPACT_FMI3_SET(Int32, fmi3Int32, Kind::Int32)
PLATEIMPACT_FMI3_SET(Int64, fmi3Int64, Kind::Int64)
PLATEIMPACT_FMI3_SET(UInt64, fmi3UInt64, Kind::UInt64)
PLATEIMPACT_FMI3_SET(Boolean, fmi3Boolean, Kind::Boolean)
PLATEIMPACT_FMI3_NONE(Float32, fmi3Float32, const)
PLATEIMPACT_FMI3_NONE(Int8, fmi3Int8, const)
PLATEIMPACT_FMI3_NONE(UInt8, fmi3UInt8, const)
PLATEIMPACT_FMI3_NONE(Int16, fmi3Int16, const)
PLATEIMPACT_FMI3_NONE(UInt16, fmi3UInt16, const)
PLATEIMPACT_FMI3_NONE(UInt32, fmi3UInt32, const)
PLATEIMPACT_FMI3_NONE(String, fmi3String, const)

fmi3Status fmi3GetBinary(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, size_t[], fmi3Binary[], size_t) {
    return run(c, "fmi3GetBinary", fmu::fmi3::kGetStates,
               [&](Fmi3Instance&, Instance& i) { return noVariables(i, "Binary", vrs, nvr); });
}

fmi3Status fmi3SetBinary(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, const size_t[], const fmi3Binary[],
                         size_t) {
    return run(c, "fmi3SetBinary", fmu::fmi3::kSetStates,
               [&](Fmi3Instance&, Instance& i) { return noVariables(i, "Binary", vrs, nvr); });
}

fmi3Status fmi3GetClock(fmi3Instance c, const fmi3ValueReference[], size_t, fmi3Clock[]) {
    return unsupported(c, "fmi3GetClock", kNoClocks);
}
fmi3Status fmi3SetClock(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3Clock[]) {
    return unsupported(c, "fmi3SetClock", kNoClocks);
}

fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance c, fmi3ValueReference, size_t*) {
    return unsupported(c, "fmi3GetNumberOfVariableDependencies",
                       "not supported (providesPerElementDependencies=\"false\"); see <ModelStructure>");
}
fmi3Status fmi3GetVariableDependencies(fmi3Instance c, fmi3ValueReference, size_t[], fmi3ValueReference[], size_t[],
                                       fmi3DependencyKind[], size_t) {
    return unsupported(c, "fmi3GetVariableDependencies",
                       "not supported (providesPerElementDependencies=\"false\"); see <ModelStructure>");
}

// ---------------------------------------------------------------------------------------------
// FMU states

fmi3Status fmi3GetFMUState(fmi3Instance c, fmi3FMUState* state) {
    return run(c, "fmi3GetFMUState", fmu::fmi3::kFMUStateStates,
               [&](Fmi3Instance&, Instance& i) { return i.getState(state); });
}
fmi3Status fmi3SetFMUState(fmi3Instance c, fmi3FMUState state) {
    return run(c, "fmi3SetFMUState", fmu::fmi3::kFMUStateStates,
               [&](Fmi3Instance&, Instance& i) { return i.setState(state); });
}
fmi3Status fmi3FreeFMUState(fmi3Instance c, fmi3FMUState* state) {
    return run(c, "fmi3FreeFMUState", fmu::fmi3::kFMUStateStates,
               [&](Fmi3Instance&, Instance& i) { return i.freeState(state); });
}
fmi3Status fmi3SerializedFMUStateSize(fmi3Instance c, fmi3FMUState state, size_t* size) {
    return run(c, "fmi3SerializedFMUStateSize", fmu::fmi3::kFMUStateStates,
               [&](Fmi3Instance&, Instance& i) { return i.serializedStateSize(state, size); });
}
fmi3Status fmi3SerializeFMUState(fmi3Instance c, fmi3FMUState state, fmi3Byte serialized[], size_t size) {
    return run(c, "fmi3SerializeFMUState", fmu::fmi3::kFMUStateStates,
               [&](Fmi3Instance&, Instance& i) { return i.serializeState(state, serialized, size); });
}
fmi3Status fmi3DeserializeFMUState(fmi3Instance c, const fmi3Byte serialized[], size_t size, fmi3FMUState* state) {
    return run(c, "fmi3DeserializeFMUState", fmu::fmi3::kFMUStateStates,
               [&](Fmi3Instance&, Instance& i) { return i.deserializeState(serialized, size, state); });
}

fmi3Status fmi3GetDirectionalDerivative(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3ValueReference[],
                                        size_t, const fmi3Float64[], size_t, fmi3Float64[], size_t) {
    return unsupported(c, "fmi3GetDirectionalDerivative", "not supported (providesDirectionalDerivatives=\"false\")");
}
fmi3Status fmi3GetAdjointDerivative(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3ValueReference[],
                                    size_t, const fmi3Float64[], size_t, fmi3Float64[], size_t) {
    return unsupported(c, "fmi3GetAdjointDerivative", "not supported (providesAdjointDerivatives=\"false\")");
}

// ---------------------------------------------------------------------------------------------
// Configuration mode (the structural parameters are fixed: set before initialization)

fmi3Status fmi3EnterConfigurationMode(fmi3Instance c) {
    return run(c, "fmi3EnterConfigurationMode", fmu::Instantiated, [](Fmi3Instance&, Instance& i) {
        if (i.model().structuralParameters().empty())
            return i.fail("this FMU has no structural parameters to configure");
        i.enterState(fmu::ConfigurationMode);
        return Status::OK;
    });
}

fmi3Status fmi3ExitConfigurationMode(fmi3Instance c) {
    return run(c, "fmi3ExitConfigurationMode", fmu::ConfigurationMode, [](Fmi3Instance&, Instance& i) {
        i.enterState(fmu::Instantiated);
        return Status::OK;
    });
}

// ---------------------------------------------------------------------------------------------
// Clocks: none

fmi3Status fmi3GetIntervalDecimal(fmi3Instance c, const fmi3ValueReference[], size_t, fmi3Float64[],
                                  fmi3IntervalQualifier[]) {
    return unsupported(c, "fmi3GetIntervalDecimal", kNoClocks);
}
fmi3Status fmi3GetIntervalFraction(fmi3Instance c, const fmi3ValueReference[], size_t, fmi3UInt64[], fmi3UInt64[],
                                   fmi3IntervalQualifier[]) {
    return unsupported(c, "fmi3GetIntervalFraction", kNoClocks);
}
fmi3Status fmi3GetShiftDecimal(fmi3Instance c, const fmi3ValueReference[], size_t, fmi3Float64[]) {
    return unsupported(c, "fmi3GetShiftDecimal", kNoClocks);
}
fmi3Status fmi3GetShiftFraction(fmi3Instance c, const fmi3ValueReference[], size_t, fmi3UInt64[], fmi3UInt64[]) {
    return unsupported(c, "fmi3GetShiftFraction", kNoClocks);
}
fmi3Status fmi3SetIntervalDecimal(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3Float64[]) {
    return unsupported(c, "fmi3SetIntervalDecimal", kNoClocks);
}
fmi3Status fmi3SetIntervalFraction(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3UInt64[],
                                   const fmi3UInt64[]) {
    return unsupported(c, "fmi3SetIntervalFraction", kNoClocks);
}
fmi3Status fmi3SetShiftDecimal(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3Float64[]) {
    return unsupported(c, "fmi3SetShiftDecimal", kNoClocks);
}
fmi3Status fmi3SetShiftFraction(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3UInt64[],
                                const fmi3UInt64[]) {
    return unsupported(c, "fmi3SetShiftFraction", kNoClocks);
}
fmi3Status fmi3ActivateModelPartition(fmi3Instance c, fmi3ValueReference, fmi3Float64) {
    return unsupported(c, "fmi3ActivateModelPartition", kScheduled);
}

// ---------------------------------------------------------------------------------------------
// Event mode: the model's events (contact onset and release) change no discrete state the
// master could iterate on; the event is the point in time and the outputs there.

fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance c) {
    return unsupported(c, "fmi3EvaluateDiscreteStates", "not supported (providesEvaluateDiscreteStates=\"false\")");
}

fmi3Status fmi3UpdateDiscreteStates(fmi3Instance c, fmi3Boolean* discreteStatesNeedUpdate,
                                    fmi3Boolean* terminateSimulation, fmi3Boolean* nominalsChanged,
                                    fmi3Boolean* valuesChanged, fmi3Boolean* nextEventTimeDefined,
                                    fmi3Float64* nextEventTime) {
    return run(c, "fmi3UpdateDiscreteStates", fmu::EventMode, [&](Fmi3Instance&, Instance& i) {
        if (!discreteStatesNeedUpdate || !terminateSimulation || !nominalsChanged || !valuesChanged ||
            !nextEventTimeDefined || !nextEventTime)
            return i.fail("the output arguments must not be NULL");
        *discreteStatesNeedUpdate = *terminateSimulation = *nominalsChanged = *valuesChanged = fmi3False;
        *nextEventTimeDefined = fmi3False;
        *nextEventTime = 0.0;
        return Status::OK;
    });
}

fmi3Status fmi3EnterStepMode(fmi3Instance c) {
    return run(c, "fmi3EnterStepMode", fmu::EventMode, [](Fmi3Instance&, Instance& i) {
        i.enterState(fmu::fmi3::StepMode);
        return Status::OK;
    });
}

// ---------------------------------------------------------------------------------------------
// Model Exchange: not implemented

fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance c) {
    return unsupported(c, "fmi3EnterContinuousTimeMode", kModelExchange);
}
fmi3Status fmi3CompletedIntegratorStep(fmi3Instance c, fmi3Boolean, fmi3Boolean*, fmi3Boolean*) {
    return unsupported(c, "fmi3CompletedIntegratorStep", kModelExchange);
}
fmi3Status fmi3SetTime(fmi3Instance c, fmi3Float64) { return unsupported(c, "fmi3SetTime", kModelExchange); }
fmi3Status fmi3SetContinuousStates(fmi3Instance c, const fmi3Float64[], size_t) {
    return unsupported(c, "fmi3SetContinuousStates", kModelExchange);
}
fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance c, fmi3Float64[], size_t) {
    return unsupported(c, "fmi3GetContinuousStateDerivatives", kModelExchange);
}
fmi3Status fmi3GetEventIndicators(fmi3Instance c, fmi3Float64[], size_t) {
    return unsupported(c, "fmi3GetEventIndicators", kModelExchange);
}
fmi3Status fmi3GetContinuousStates(fmi3Instance c, fmi3Float64[], size_t) {
    return unsupported(c, "fmi3GetContinuousStates", kModelExchange);
}
fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance c, fmi3Float64[], size_t) {
    return unsupported(c, "fmi3GetNominalsOfContinuousStates", kModelExchange);
}
fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance c, size_t*) {
    return unsupported(c, "fmi3GetNumberOfEventIndicators", kModelExchange);
}
fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance c, size_t*) {
    return unsupported(c, "fmi3GetNumberOfContinuousStates", kModelExchange);
}

// ---------------------------------------------------------------------------------------------
// Co-Simulation

fmi3Status fmi3GetOutputDerivatives(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr,
                                    const fmi3Int32 orders[], fmi3Float64 values[], size_t nValues) {
    return run(c, "fmi3GetOutputDerivatives", fmu::fmi3::StepMode | fmu::Terminated, [&](Fmi3Instance&, Instance& i) {
        if (nValues != nvr) return i.fail("nValues = %zu, but %zu value references of scalars", nValues, nvr);
        return i.getOutputDerivatives(vrs, nvr, orders, values);
    });
}

// With early return granted, the step ends right after the internal step at which the model's
// event happens (PlateImpact: the contact set becomes non-empty or empty), at that grid time.
fmi3Status fmi3DoStep(fmi3Instance c, fmi3Float64 t, fmi3Float64 h, fmi3Boolean, fmi3Boolean* eventHandlingNeeded,
                      fmi3Boolean* terminateSimulation, fmi3Boolean* earlyReturn, fmi3Float64* lastSuccessfulTime) {
    return run(c, "fmi3DoStep", fmu::fmi3::StepMode, [&](Fmi3Instance& self, Instance& i) {
        if (!eventHandlingNeeded || !terminateSimulation || !earlyReturn || !lastSuccessfulTime)
            return i.fail("the output arguments must not be NULL");
        *eventHandlingNeeded = *terminateSimulation = *earlyReturn = fmi3False;
        bool atEvent = false;
        const Status status = i.doStep(t, h, self.earlyReturnAllowed, &atEvent);
        *lastSuccessfulTime = i.currentTime();
        if (status != Status::OK) return status;
        // Early: at an event of the model, or where the master's intermediate update asked.
        const bool early = (t + h) - *lastSuccessfulTime > kEarlyTolerance * std::fabs(h);
        *earlyReturn = early;
        *eventHandlingNeeded = atEvent && self.eventModeUsed;
        if (early)
            i.log(Status::OK, fmu::LogAll, "fmi3DoStep: early return at t = %.17g (%s; the step asked for %.17g)",
                  *lastSuccessfulTime, atEvent ? "an event" : "asked by the intermediate update", t + h);
        return Status::OK;
    });
}

}  // extern "C"
