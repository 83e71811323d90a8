// The FMI 2.0 C API, model-independent: every fmi2* function runs its body through
// Instance::call with the states that allow it (one mask per function, FMI 2.0.4 section
// 4.2.4), which logs an illegal call sequence, prefixes messages with the function's name and
// keeps exceptions from crossing into the importer. Only the fmi2* symbols leave the shared
// object: the header declares them FMI2_Export inside extern "C", everything else is hidden
// (-fvisibility=hidden and the linker version script fmu/exports.map).
#include <cstring>
#include <memory>
#include <vector>

#include "core/Instance.h"
#include "fmi2Functions.h"

using fmu::Instance;
using fmu::VariableType;

namespace {

// Runs `body(instance)` as `function` when `c` is an instance and the state allows it.
template <class Body>
fmi2Status run(fmi2Component c, const char* function, unsigned allowed, Body&& body) {
    Instance* instance = static_cast<Instance*>(c);
    if (!instance) return fmi2Error;  // a NULL instance has no logger to tell
    return instance->call(function, allowed, [&]() { return body(*instance); });
}

// fmi2Get/SetInteger and fmi2Get/SetBoolean through the layer's double values.
template <class T>
fmi2Status getAs(Instance& i, VariableType type, const fmi2ValueReference vr[], size_t nvr, T value[]) {
    std::vector<double> values(nvr);
    const fmi2Status status = i.getValues(type, vr, nvr, value ? values.data() : nullptr);
    if (status == fmi2OK && value)
        for (size_t k = 0; k < nvr; ++k) value[k] = static_cast<T>(values[k]);
    return status;
}

template <class T>
fmi2Status setAs(Instance& i, VariableType type, const fmi2ValueReference vr[], size_t nvr, const T value[]) {
    std::vector<double> values(value ? nvr : 0);
    for (size_t k = 0; k < values.size(); ++k) values[k] = type == VariableType::Boolean ? (value[k] != 0) : value[k];
    return i.setValues(type, vr, nvr, value ? values.data() : nullptr);
}

fmi2Status modelExchange(fmi2Component c, const char* function) {
    return run(c, function, fmu::kAnyState, [&](Instance& i) {
        return i.fail("Model Exchange is not supported; this FMU implements FMI 2.0 Co-Simulation only");
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
    return run(c, "fmi2SetDebugLogging", fmu::kDebugLoggingStates,
               [&](Instance& i) { return i.setDebugLogging(loggingOn, nCategories, categories); });
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions* functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn) {
    (void)fmuResourceLocation;  // the FMU has no resources
    (void)visible;
    if (!functions) return nullptr;
    if (!instanceName || instanceName[0] == '\0') {
        fmu::logWithoutInstance(functions, instanceName, "fmi2Instantiate: missing instance name");
        return nullptr;
    }
    if (fmuType != fmi2CoSimulation) {
        fmu::logWithoutInstance(functions, instanceName,
                                "fmi2Instantiate: fmuType must be fmi2CoSimulation; this FMU does not implement "
                                "Model Exchange");
        return nullptr;
    }
    if (!fmuGUID || std::strcmp(fmuGUID, fmu::modelGuid()) != 0) {
        fmu::logWithoutInstance(functions, instanceName,
                                "fmi2Instantiate: wrong GUID \"%s\"; this binary has GUID \"%s\" "
                                "(modelDescription.xml and binary come from different builds)",
                                fmuGUID ? fmuGUID : "(null)", fmu::modelGuid());
        return nullptr;
    }
    try {
        return std::make_unique<Instance>(instanceName, *functions, loggingOn != fmi2False).release();
    } catch (...) {
        fmu::logWithoutInstance(functions, instanceName, "fmi2Instantiate: out of memory");
        return nullptr;
    }
}

void fmi2FreeInstance(fmi2Component c) {
    std::unique_ptr<Instance> owned(static_cast<Instance*>(c));
    if (owned) owned->logFreeInstance();
}

// ---------------------------------------------------------------------------------------------
// Initialization, termination, reset

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
    return run(c, "fmi2SetupExperiment", fmu::Instantiated, [&](Instance& i) {
        return i.setupExperiment(startTime, toleranceDefined, tolerance, stopTimeDefined, stopTime);
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
    return run(c, "fmi2Reset", fmu::kResetStates, [](Instance& i) { return i.reset(); });
}

// ---------------------------------------------------------------------------------------------
// Variables

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]) {
    return run(c, "fmi2GetReal", fmu::kGetStates,
               [&](Instance& i) { return i.getValues(VariableType::Real, vr, nvr, value); });
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[]) {
    return run(c, "fmi2GetInteger", fmu::kGetStates,
               [&](Instance& i) { return getAs(i, VariableType::Integer, vr, nvr, value); });
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[]) {
    return run(c, "fmi2GetBoolean", fmu::kGetStates,
               [&](Instance& i) { return getAs(i, VariableType::Boolean, vr, nvr, value); });
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String[]) {
    return run(c, "fmi2GetString", fmu::kGetStates, [&](Instance& i) {
        return nvr == 0 ? fmi2OK : i.fail("this FMU has no String variables (value reference %u)", vr ? vr[0] : 0u);
    });
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]) {
    return run(c, "fmi2SetReal", fmu::kSetStates,
               [&](Instance& i) { return i.setValues(VariableType::Real, vr, nvr, value); });
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[]) {
    return run(c, "fmi2SetInteger", fmu::kSetStates,
               [&](Instance& i) { return setAs(i, VariableType::Integer, vr, nvr, value); });
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[]) {
    return run(c, "fmi2SetBoolean", fmu::kSetStates,
               [&](Instance& i) { return setAs(i, VariableType::Boolean, vr, nvr, value); });
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String[]) {
    return run(c, "fmi2SetString", fmu::kSetStates, [&](Instance& i) {
        return nvr == 0 ? fmi2OK : i.fail("this FMU has no String variables (value reference %u)", vr ? vr[0] : 0u);
    });
}

// ---------------------------------------------------------------------------------------------
// FMU states

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate* FMUstate) {
    return run(c, "fmi2GetFMUstate", fmu::kFMUstateStates, [&](Instance& i) { return i.getFMUstate(FMUstate); });
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate) {
    return run(c, "fmi2SetFMUstate", fmu::kFMUstateStates, [&](Instance& i) { return i.setFMUstate(FMUstate); });
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate* FMUstate) {
    return run(c, "fmi2FreeFMUstate", fmu::kFMUstateStates, [&](Instance& i) { return i.freeFMUstate(FMUstate); });
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate FMUstate, size_t* size) {
    return run(c, "fmi2SerializedFMUstateSize", fmu::kFMUstateStates,
               [&](Instance& i) { return i.serializedFMUstateSize(FMUstate, size); });
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate FMUstate, fmi2Byte serializedState[], size_t size) {
    return run(c, "fmi2SerializeFMUstate", fmu::kFMUstateStates,
               [&](Instance& i) { return i.serializeFMUstate(FMUstate, serializedState, size); });
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[], size_t size,
                                   fmi2FMUstate* FMUstate) {
    return run(c, "fmi2DeSerializeFMUstate", fmu::kFMUstateStates,
               [&](Instance& i) { return i.deSerializeFMUstate(serializedState, size, FMUstate); });
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference[], size_t, const fmi2ValueReference[],
                                        size_t, const fmi2Real[], fmi2Real[]) {
    return run(c, "fmi2GetDirectionalDerivative", fmu::kGetStates,
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
    return run(c, "fmi2SetRealInputDerivatives", fmu::kInputDerivativeStates,
               [&](Instance& i) { return i.setRealInputDerivatives(vr, nvr, order, value); });
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[]) {
    return run(c, "fmi2GetRealOutputDerivatives", fmu::kOutputDerivativeStates,
               [&](Instance& i) { return i.getRealOutputDerivatives(vr, nvr, order, value); });
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
    return run(c, "fmi2GetStatus", fmu::kStatusStates, [&](Instance& i) {
        return value ? i.statusNotAvailable(s) : i.fail("argument value must not be NULL");
    });
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real* value) {
    return run(c, "fmi2GetRealStatus", fmu::kStatusStates, [&](Instance& i) {
        if (!value) return i.fail("argument value must not be NULL");
        if (s != fmi2LastSuccessfulTime) return i.statusNotAvailable(s);
        *value = i.currentTime();
        return fmi2OK;
    });
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer* value) {
    return run(c, "fmi2GetIntegerStatus", fmu::kStatusStates, [&](Instance& i) {
        return value ? i.statusNotAvailable(s) : i.fail("argument value must not be NULL");
    });
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean* value) {
    return run(c, "fmi2GetBooleanStatus", fmu::kStatusStates, [&](Instance& i) {
        if (!value) return i.fail("argument value must not be NULL");
        if (s != fmi2Terminated) return i.statusNotAvailable(s);
        *value = fmi2False;  // the model never asks the master to end the simulation
        return fmi2OK;
    });
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String* value) {
    return run(c, "fmi2GetStringStatus", fmu::kStatusStates, [&](Instance& i) {
        return value ? i.statusNotAvailable(s) : i.fail("argument value must not be NULL");
    });
}

}  // extern "C"
