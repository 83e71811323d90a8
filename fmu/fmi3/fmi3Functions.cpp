// The FMI 3.0 C API (Co-Simulation), model-independent: a thin front end over the same
// version-neutral core as fmi2/fmi2Functions.cpp (core/Instance.h), converting FMI 3.0 types
// and statuses. Every fmi3* function runs its body through Instance::call with the states that
// allow it (Fmi3Interface.h), which logs an illegal call sequence, prefixes messages with the
// function's name and keeps exceptions inside. Beyond FMI 2.0: the independent variable
// "time", arrays sized by UInt64 structural parameters (Model.h; their get and set: Fmi3Values.cpp),
// configuration mode, intermediate update, and early return with event mode at the model's events
// (Model::doStepUntilEvent) when the master grants them at fmi3InstantiateCoSimulation. Only the
// fmi3* symbols leave the shared object (fmi3/exports.map).
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "fmi3/Fmi3Instance.h"
#include "fmi3/Fmi3Interface.h"
#include "fmi3/Fmi3Values.h"
#include "core/Instance.h"
#include "fmi3/Fmi3Own.h"

using fmu::Instance;
using fmu::Status;
using fmu::fmi3::Fmi3Instance;
using fmu::fmi3::Kind;
using fmu::fmi3::kTimeValueReference;
using fmu::fmi3::loggerOf;
using fmu::fmi3::run;

static_assert(std::is_same_v<fmi3ValueReference, fmu::ValueReference> && std::is_same_v<fmi3Byte, fmu::Byte> &&
                  std::is_same_v<fmi3Int32, int>,
              "value references, bytes and derivative orders pass unconverted");

namespace {

// Tolerance of "the step ended before t + h" (the model's grid times against the master's sum).
constexpr double kEarlyTolerance = 1e-9;

// The functions the core's messages name. The size message has always named FMI 2.0's
// function, in FMI 3.0 too; kept so that the messages stay as they were.
constexpr fmu::ApiNames kNames = {"fmi3ExitInitializationMode", "fmi3SerializedFMUStateSize", 3};

// Intermediate update (providesIntermediateUpdate): the outputs, the output arrays and time may be
// read inside the callback after each internal step; the inputs that take intermediate values
// (intermediateUpdate="true": base_displacement, load), when required, are asked for before each
// internal step (intermediateVariableSetRequested = true) and used at that grid point. Logs the
// first required variable that is neither, and returns false; *inputsRequired: an input is among them.
bool requiredVariablesAllowed(const fmu::Model& model, const fmu::Logger& logger, const fmi3ValueReference vrs[],
                              size_t n, bool* inputsRequired) {
    for (size_t k = 0; k < n; ++k) {
        const fmi3ValueReference vr = vrs ? vrs[k] : 0;
        const fmu::Variable* v = model.find(vr);
        const fmu::ArrayVariable* a = model.findArray(vr);
        const bool readable = vr == kTimeValueReference || (v && v->causality == fmu::Causality::Output) ||
                              (a && a->causality == fmu::Causality::Output);
        const bool input = v && v->causality == fmu::Causality::Input && model.takesIntermediateValue(*v);
        *inputsRequired = *inputsRequired || input;
        if (vrs && (readable || input)) continue;
        std::string inputs;
        for (const fmu::Variable& w : model.variables())
            if (model.takesIntermediateValue(w)) inputs += std::string(inputs.empty() ? "" : ", ") + w.name;
        fmu::logWithoutInstance(logger,
                                "%s: required intermediate variable %s (vr %u) has no intermediateUpdate=\"true\" "
                                "(the intermediate update variables are the outputs, the arrays, time and "
                                "the inputs %s)",
                                "fmi3InstantiateCoSimulation", v ? v->name : "(unknown)", vr, inputs.c_str());
        return false;
    }
    return true;
}

// The master's callback as the core's two hooks: before each internal step when an input is
// required (the master sets it), after each one (the master reads, may ask for an early return).
void connectIntermediateUpdate(Fmi3Instance* raw, bool inputsRequired) {
    // One call of the master's callback at `time`, before the step (set) or after it: when to end.
    const auto call = [raw](double time, bool set) {
        fmi3Boolean requested = fmi3False;
        fmi3Float64 at = time;
        const fmi3Boolean canReturnEarly = set ? fmi3False : raw->earlyReturnAllowed;
        raw->intermediateUpdate(raw->environment, time, /*intermediateVariableSetRequested=*/set,
                                /*intermediateVariableGetAllowed=*/!set, /*intermediateStepFinished=*/!set,
                                canReturnEarly, &requested, &at);
        return requested && canReturnEarly ? at : HUGE_VAL;
    };
    if (inputsRequired) raw->instance->setIntermediateInputs([call](double time) { call(time, true); });
    raw->instance->setIntermediateUpdate([call](double time) { return call(time, false); });
}

}  // namespace

#define PLATEIMPACT_FMI3_GET(Name, T, kind)                                                                         \
    fmi3Status fmi3Get##Name(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, T values[], size_t n) {    \
        return run(c, "fmi3Get" #Name, fmu::fmi3::kGetStates,                                                       \
                   [&](Fmi3Instance&, Instance& i) { return fmu::fmi3::getValues(i, kind, vrs, nvr, values, n); }); \
    }
#define PLATEIMPACT_FMI3_SET(Name, T, kind)                                                                            \
    fmi3Status fmi3Set##Name(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, const T values[], size_t n) { \
        return run(c, "fmi3Set" #Name, fmu::fmi3::kSetStates,                                                          \
                   [&](Fmi3Instance&, Instance& i) { return fmu::fmi3::setValues(i, kind, vrs, nvr, values, n); });    \
    }
#define PLATEIMPACT_FMI3_NONE(Name, T, Const)                                                                 \
    fmi3Status fmi3Get##Name(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, T[], size_t) {       \
        return run(c, "fmi3Get" #Name, fmu::fmi3::kGetStates,                                                 \
                   [&](Fmi3Instance&, Instance& i) { return fmu::fmi3::noVariables(i, #Name, vrs, nvr); });   \
    }                                                                                                         \
    fmi3Status fmi3Set##Name(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, Const T[], size_t) { \
        return run(c, "fmi3Set" #Name, fmu::fmi3::kSetStates,                                                 \
                   [&](Fmi3Instance&, Instance& i) { return fmu::fmi3::noVariables(i, #Name, vrs, nvr); });   \
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
        bool inputsRequired = false;
        if (!requiredVariablesAllowed(self->instance->model(), logger, requiredIntermediateVariables,
                                      nRequiredIntermediateVariables, &inputsRequired))
            return nullptr;
        if (intermediateUpdate) connectIntermediateUpdate(self.get(), inputsRequired);
        return self.release();
    } catch (...) {
        if (logMessage)
            logMessage(instanceEnvironment, fmi3Error, "logStatusError", "fmi3InstantiateCoSimulation: out of memory");
        return nullptr;
    }
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
               [&](Fmi3Instance&, Instance& i) { return fmu::fmi3::noVariables(i, "Binary", vrs, nvr); });
}

fmi3Status fmi3SetBinary(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, const size_t[], const fmi3Binary[],
                         size_t) {
    return run(c, "fmi3SetBinary", fmu::fmi3::kSetStates,
               [&](Fmi3Instance&, Instance& i) { return fmu::fmi3::noVariables(i, "Binary", vrs, nvr); });
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

// ---------------------------------------------------------------------------------------------
// Configuration mode: the structural parameters (some settable only here: probe_count)

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
// Event mode: the model's events (contact onset and release) change no discrete state the
// master could iterate on; the event is the point in time and the outputs there.

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
