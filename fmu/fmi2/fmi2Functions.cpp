// The FMI 2.0 C API, model-independent: a thin front end over the version-neutral core
// (core/Instance.h) that converts FMI 2.0 types and statuses and calls the core. Every fmi2*
// function runs its body through Instance::call with the states that allow it (one mask per
// function, FMI 2.0.4 section 4.2.4), which logs an illegal call sequence, prefixes messages
// with the function's name and keeps exceptions from crossing into the importer. Only the fmi2*
// symbols leave the shared object: the header declares them FMI2_Export inside extern "C",
// everything else is hidden (-fvisibility=hidden and the linker version script fmi2/exports.map).
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "core/Instance.h"
#include "fmi2/Fmi2Own.h"

using fmu::Instance;
using fmu::Status;
using fmu::VariableType;

static_assert(std::is_same_v<fmi2ValueReference, fmu::ValueReference>, "value references pass unconverted");

namespace {

// Allowed states of each function group (FMI 2.0.4, table in section 4.2.4).
constexpr unsigned kFreeInstanceStates = fmu::Instantiated | fmu::InitializationMode | fmu::StepComplete |
                                         fmu::StepFailed | fmu::StepCanceled | fmu::Terminated | fmu::Error;
constexpr unsigned kDebugLoggingStates = kFreeInstanceStates | fmu::StepInProgress;
constexpr unsigned kResetStates = kFreeInstanceStates;
constexpr unsigned kFMUstateStates = kFreeInstanceStates;
constexpr unsigned kGetStates = kFreeInstanceStates & ~fmu::Instantiated;
constexpr unsigned kSetStates = fmu::Instantiated | fmu::InitializationMode | fmu::StepComplete;
constexpr unsigned kInputDerivativeStates = kSetStates;
constexpr unsigned kOutputDerivativeStates = kGetStates & ~fmu::InitializationMode;
constexpr unsigned kStatusStates = fmu::StepComplete | fmu::StepInProgress | fmu::StepFailed | fmu::Terminated;

// The functions the core's messages name.
constexpr fmu::ApiNames kNames = {"fmi2ExitInitializationMode", "fmi2SerializedFMUstateSize", 2};

// Status and fmi2Status list the same outcomes in the same order.
fmi2Status toFmi2(Status status) {
    static constexpr fmi2Status kStatus[] = {fmi2OK, fmi2Warning, fmi2Discard, fmi2Error, fmi2Fatal};
    return kStatus[static_cast<int>(status)];
}

// The importer may treat the message as a printf format (FMI 2.0, fmi2CallbackLogger).
std::string escapePercent(const char* text) {
    std::string out;
    for (const char* p = text; *p; ++p) {
        out += *p;
        if (*p == '%') out += '%';
    }
    return out;
}

// The core's logger over the importer's fmi2CallbackLogger (none without one).
fmu::Logger loggerOf(const fmi2CallbackFunctions& functions, fmi2String instanceName) {
    if (!functions.logger) return nullptr;
    return [functions, name = std::string(instanceName ? instanceName : "")](Status status, const char* category,
                                                                             const char* message) {
        functions.logger(functions.componentEnvironment, name.c_str(), toFmi2(status), category,
                         escapePercent(message).c_str());
    };
}

// Runs `body(instance)` as `function` when `c` is an instance and the state allows it.
template <class Body>
fmi2Status run(fmi2Component c, const char* function, unsigned allowed, Body&& body) {
    Instance* instance = static_cast<Instance*>(c);
    if (!instance) return fmi2Error;  // a NULL instance has no logger to tell
    return toFmi2(instance->call(function, allowed, [&]() { return body(*instance); }));
}

// fmi2Get/Set<Real, Integer, Boolean> through the layer's double values (a Real's as they are).
template <class T>
Status getAs(Instance& i, VariableType type, const fmi2ValueReference vr[], size_t nvr, T value[]) {
    if constexpr (std::is_same_v<T, double>) return i.getValues(type, vr, nvr, value);
    std::vector<double> values(nvr);
    const Status status = i.getValues(type, vr, nvr, value ? values.data() : nullptr);
    if (status == Status::OK && value)
        for (size_t k = 0; k < nvr; ++k) value[k] = static_cast<T>(values[k]);
    return status;
}

template <class T>
Status setAs(Instance& i, VariableType type, const fmi2ValueReference vr[], size_t nvr, const T value[]) {
    if constexpr (std::is_same_v<T, double>) return i.setValues(type, vr, nvr, value);
    std::vector<double> values(value ? nvr : 0);
    for (size_t k = 0; k < values.size(); ++k) values[k] = type == VariableType::Boolean ? (value[k] != 0) : value[k];
    return i.setValues(type, vr, nvr, value ? values.data() : nullptr);
}

fmi2Status modelExchange(fmi2Component c, const char* function) {
    return run(c, function, fmu::kAnyState, [&](Instance& i) {
        return i.fail("Model Exchange is not supported; this FMU implements FMI 2.0 Co-Simulation only");
    });
}

// fmi2Get*Status of a kind this FMU does not give: fmi2Discard with a log line.
Status statusNotAvailable(Instance& i, fmi2StatusKind kind) {
    static constexpr const char* kKinds[] = {"fmi2DoStepStatus", "fmi2PendingStatus", "fmi2LastSuccessfulTime",
                                             "fmi2Terminated"};
    const char* name = (kind >= 0 && kind <= 3) ? kKinds[kind] : "an unknown status kind";
    i.log(Status::Discard, fmu::LogStatusError,
          "%s: %s is not available from this function (fmi2DoStep never returns "
          "fmi2Pending or fmi2Discard); returning fmi2Discard",
          i.function(), name);
    return Status::Discard;
}

constexpr std::nullopt_t kNoKind = std::nullopt;  // a status function that gives no kind

// fmi2Get<Type>Status: the kind `given` is give(instance); every other kind is not available.
template <class T, class Give>
fmi2Status getStatus(fmi2Component c, const char* function, fmi2StatusKind s, T* value,
                     std::optional<fmi2StatusKind> given, Give give) {
    return run(c, function, kStatusStates, [&](Instance& i) {
        if (!value) return i.fail("argument value must not be NULL");
        if (s != given) return statusNotAvailable(i, s);
        *value = give(i);
        return Status::OK;
    });
}

}  // namespace

extern "C" {

// ---------------------------------------------------------------------------------------------
// Common functions

const char* fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }

const char* fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[]) {
    return run(c, "fmi2SetDebugLogging", kDebugLoggingStates,
               [&](Instance& i) { return i.setDebugLogging(loggingOn != fmi2False, nCategories, categories); });
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions* functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn) {
    (void)fmuResourceLocation;  // the FMU has no resources
    (void)visible;
    if (!functions) return nullptr;
    fmu::Logger logger;
    try {
        logger = loggerOf(*functions, instanceName);
        if (!instanceName || instanceName[0] == '\0') {
            fmu::logWithoutInstance(logger, "fmi2Instantiate: missing instance name");
            return nullptr;
        }
        if (fmuType != fmi2CoSimulation) {
            fmu::logWithoutInstance(logger,
                                    "fmi2Instantiate: fmuType must be fmi2CoSimulation; this FMU does not implement "
                                    "Model Exchange");
            return nullptr;
        }
        if (!fmuGUID || std::strcmp(fmuGUID, fmu::modelGuid()) != 0) {
            fmu::logWithoutInstance(logger,
                                    "fmi2Instantiate: wrong GUID \"%s\"; this binary has GUID \"%s\" "
                                    "(modelDescription.xml and binary come from different builds)",
                                    fmuGUID ? fmuGUID : "(null)", fmu::modelGuid());
            return nullptr;
        }
        auto instance = std::make_unique<Instance>(logger, loggingOn != fmi2False, kNames);
        instance->log(Status::OK, fmu::LogAll, "fmi2Instantiate: instance \"%s\" of %s (GUID %s)", instanceName,
                      instance->model().info().modelName, fmu::modelGuid());
        return instance.release();
    } catch (...) {
        fmu::logWithoutInstance(logger, "fmi2Instantiate: out of memory");
        return nullptr;
    }
}

void fmi2FreeInstance(fmi2Component c) {
    std::unique_ptr<Instance> owned(static_cast<Instance*>(c));
    if (owned) owned->log(Status::OK, fmu::LogAll, "fmi2FreeInstance");
}

// ---------------------------------------------------------------------------------------------
// Initialization, termination, reset

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
    return run(c, "fmi2SetupExperiment", fmu::Instantiated, [&](Instance& i) {
        return i.setupExperiment(startTime, toleranceDefined != fmi2False, tolerance, stopTimeDefined != fmi2False,
                                 stopTime);
    });
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
    return run(c, "fmi2EnterInitializationMode", fmu::Instantiated,
               [](Instance& i) { return i.enterInitializationMode(); });
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
    return run(c, "fmi2ExitInitializationMode", fmu::InitializationMode,
               [](Instance& i) { return i.exitInitializationMode(); });
}

fmi2Status fmi2Terminate(fmi2Component c) {
    return run(c, "fmi2Terminate", fmu::StepComplete | fmu::StepFailed, [](Instance& i) { return i.terminate(); });
}

fmi2Status fmi2Reset(fmi2Component c) {
    return run(c, "fmi2Reset", kResetStates, [](Instance& i) { return i.reset(); });
}

// ---------------------------------------------------------------------------------------------
// Variables

#define PLATEIMPACT_FMI2_VALUES(Name, T)                                                                    \
    fmi2Status fmi2Get##Name(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, T value[]) {       \
        return run(c, "fmi2Get" #Name, kGetStates,                                                          \
                   [&](Instance& i) { return getAs(i, VariableType::Name, vr, nvr, value); });              \
    }                                                                                                       \
    fmi2Status fmi2Set##Name(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const T value[]) { \
        return run(c, "fmi2Set" #Name, kSetStates,                                                          \
                   [&](Instance& i) { return setAs(i, VariableType::Name, vr, nvr, value); });              \
    }
PLATEIMPACT_FMI2_VALUES(Real, fmi2Real)
PLATEIMPACT_FMI2_VALUES(Integer, fmi2Integer)
PLATEIMPACT_FMI2_VALUES(Boolean, fmi2Boolean)
#undef PLATEIMPACT_FMI2_VALUES

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String[]) {
    return run(c, "fmi2GetString", kGetStates, [&](Instance& i) {
        return nvr == 0 ? Status::OK : i.fail("this FMU has no String variables (value reference %u)", vr ? vr[0] : 0u);
    });
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String[]) {
    return run(c, "fmi2SetString", kSetStates, [&](Instance& i) {
        return nvr == 0 ? Status::OK : i.fail("this FMU has no String variables (value reference %u)", vr ? vr[0] : 0u);
    });
}

// ---------------------------------------------------------------------------------------------
// FMU states

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate* FMUstate) {
    return run(c, "fmi2GetFMUstate", kFMUstateStates, [&](Instance& i) { return i.getState(FMUstate); });
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate) {
    return run(c, "fmi2SetFMUstate", kFMUstateStates, [&](Instance& i) { return i.setState(FMUstate); });
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate* FMUstate) {
    return run(c, "fmi2FreeFMUstate", kFMUstateStates, [&](Instance& i) { return i.freeState(FMUstate); });
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate FMUstate, size_t* size) {
    return run(c, "fmi2SerializedFMUstateSize", kFMUstateStates,
               [&](Instance& i) { return i.serializedStateSize(FMUstate, size); });
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate FMUstate, fmi2Byte serializedState[], size_t size) {
    return run(c, "fmi2SerializeFMUstate", kFMUstateStates, [&](Instance& i) {
        return i.serializeState(FMUstate, reinterpret_cast<fmu::Byte*>(serializedState), size);
    });
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[], size_t size,
                                   fmi2FMUstate* FMUstate) {
    return run(c, "fmi2DeSerializeFMUstate", kFMUstateStates, [&](Instance& i) {
        return i.deserializeState(reinterpret_cast<const fmu::Byte*>(serializedState), size, FMUstate);
    });
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference[], size_t, const fmi2ValueReference[],
                                        size_t, const fmi2Real[], fmi2Real[]) {
    return run(c, "fmi2GetDirectionalDerivative", kGetStates,
               [](Instance& i) { return i.fail("not supported (providesDirectionalDerivative=\"false\")"); });
}

// ---------------------------------------------------------------------------------------------
// Model Exchange: not implemented (every call returns fmi2Error with a log line)

fmi2Status fmi2EnterEventMode(fmi2Component c) { return modelExchange(c, "fmi2EnterEventMode"); }
fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo*) { return modelExchange(c, "fmi2NewDiscreteStates"); }
fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c) { return modelExchange(c, "fmi2EnterContinuousTimeMode"); }
fmi2Status fmi2CompletedIntegratorStep(fmi2Component c, fmi2Boolean, fmi2Boolean*, fmi2Boolean*) {
    return modelExchange(c, "fmi2CompletedIntegratorStep");
}
fmi2Status fmi2SetTime(fmi2Component c, fmi2Real) { return modelExchange(c, "fmi2SetTime"); }
fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real[], size_t) {
    return modelExchange(c, "fmi2SetContinuousStates");
}
fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real[], size_t) { return modelExchange(c, "fmi2GetDerivatives"); }
fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real[], size_t) {
    return modelExchange(c, "fmi2GetEventIndicators");
}
fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real[], size_t) {
    return modelExchange(c, "fmi2GetContinuousStates");
}
fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real[], size_t) {
    return modelExchange(c, "fmi2GetNominalsOfContinuousStates");
}

// ---------------------------------------------------------------------------------------------
// Co-Simulation

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[]) {
    return run(c, "fmi2SetRealInputDerivatives", kInputDerivativeStates,
               [&](Instance& i) { return i.setInputDerivatives(vr, nvr, order, value); });
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[]) {
    return run(c, "fmi2GetRealOutputDerivatives", kOutputDerivativeStates,
               [&](Instance& i) { return i.getOutputDerivatives(vr, nvr, order, value); });
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean) {
    return run(c, "fmi2DoStep", fmu::StepComplete,
               [&](Instance& i) { return i.doStep(currentCommunicationPoint, communicationStepSize); });
}

// fmi2DoStep never returns fmi2Pending (canRunAsynchronuously="false"), so there is never a
// step to cancel: the only allowed state, stepInProgress, does not occur.
fmi2Status fmi2CancelStep(fmi2Component c) {
    return run(c, "fmi2CancelStep", fmu::StepInProgress,
               [](Instance& i) { return i.fail("not supported (canRunAsynchronuously=\"false\")"); });
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status* value) {
    return getStatus(c, "fmi2GetStatus", s, value, kNoKind, [](Instance&) { return fmi2OK; });
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real* value) {
    return getStatus(c, "fmi2GetRealStatus", s, value, fmi2LastSuccessfulTime,
                     [](Instance& i) { return i.currentTime(); });
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer* value) {
    return getStatus(c, "fmi2GetIntegerStatus", s, value, kNoKind, [](Instance&) { return 0; });
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean* value) {
    // The model never asks the master to end the simulation.
    return getStatus(c, "fmi2GetBooleanStatus", s, value, fmi2Terminated, [](Instance&) { return fmi2False; });
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String* value) {
    return getStatus(c, "fmi2GetStringStatus", s, value, kNoKind, [](Instance&) { return ""; });
}

}  // extern "C"
