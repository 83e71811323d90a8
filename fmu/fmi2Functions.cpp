// The FMI 2.0 C API of the PlateImpact co-simulation FMU: each fmi2* function forwards to
// one PlateInstance method (which checks the state machine, logs, and never throws). Only the
// fmi2* symbols leave the shared object: the header declares them FMI2_Export (default
// visibility) inside extern "C", everything else is hidden (-fvisibility=hidden and the
// linker version script fmu/exports.map).
#include <cstring>
#include <memory>

#include "PlateInstance.h"
#include "fmi2Functions.h"

using plateimpact::PlateInstance;

namespace {

PlateInstance* instance(fmi2Component c) { return static_cast<PlateInstance*>(c); }

template <class F>
fmi2Status forward(fmi2Component c, F&& f) {
    PlateInstance* i = instance(c);
    return i ? f(*i) : fmi2Error;  // a NULL instance has no logger to tell
}

}  // namespace

extern "C" {

// ---------------------------------------------------------------------------------------------
// Common functions

const char* fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }

const char* fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[]) {
    return forward(c, [&](PlateInstance& i) { return i.setDebugLogging(loggingOn, nCategories, categories); });
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions* functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn) {
    (void)fmuResourceLocation;  // the FMU has no resources
    (void)visible;
    if (!functions) return nullptr;
    if (!instanceName || instanceName[0] == '\0') {
        plateimpact::logWithoutInstance(functions, instanceName, "fmi2Instantiate: missing instance name");
        return nullptr;
    }
    if (fmuType != fmi2CoSimulation) {
        plateimpact::logWithoutInstance(functions, instanceName,
                                        "fmi2Instantiate: fmuType must be fmi2CoSimulation; this FMU does not "
                                        "implement Model Exchange");
        return nullptr;
    }
    if (!fmuGUID || std::strcmp(fmuGUID, plateimpact::buildGuid()) != 0) {
        plateimpact::logWithoutInstance(functions, instanceName,
                                        "fmi2Instantiate: wrong GUID \"%s\"; this binary has GUID \"%s\" "
                                        "(modelDescription.xml and binary come from different builds)",
                                        fmuGUID ? fmuGUID : "(null)", plateimpact::buildGuid());
        return nullptr;
    }
    try {
        auto created = std::make_unique<PlateInstance>(instanceName, *functions, loggingOn != fmi2False);
        return created.release();  // owned by the importer until fmi2FreeInstance
    } catch (...) {
        plateimpact::logWithoutInstance(functions, instanceName, "fmi2Instantiate: out of memory");
        return nullptr;
    }
}

void fmi2FreeInstance(fmi2Component c) {
    std::unique_ptr<PlateInstance> owned(instance(c));
    if (owned) owned->logFreeInstance();
}

// ---------------------------------------------------------------------------------------------
// Initialization, termination, reset

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
    return forward(c, [&](PlateInstance& i) {
        return i.setupExperiment(toleranceDefined, tolerance, startTime, stopTimeDefined, stopTime);
    });
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
    return forward(c, [&](PlateInstance& i) { return i.enterInitializationMode(); });
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
    return forward(c, [&](PlateInstance& i) { return i.exitInitializationMode(); });
}

fmi2Status fmi2Terminate(fmi2Component c) {
    return forward(c, [&](PlateInstance& i) { return i.terminate(); });
}

fmi2Status fmi2Reset(fmi2Component c) {
    return forward(c, [&](PlateInstance& i) { return i.reset(); });
}

// ---------------------------------------------------------------------------------------------
// Variables

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]) {
    return forward(c, [&](PlateInstance& i) { return i.getReal(vr, nvr, value); });
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[]) {
    return forward(c, [&](PlateInstance& i) { return i.getInteger(vr, nvr, value); });
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[]) {
    return forward(c, [&](PlateInstance& i) { return i.getBoolean(vr, nvr, value); });
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String value[]) {
    return forward(c, [&](PlateInstance& i) { return i.getString(vr, nvr, value); });
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]) {
    return forward(c, [&](PlateInstance& i) { return i.setReal(vr, nvr, value); });
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[]) {
    return forward(c, [&](PlateInstance& i) { return i.setInteger(vr, nvr, value); });
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[]) {
    return forward(c, [&](PlateInstance& i) { return i.setBoolean(vr, nvr, value); });
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String value[]) {
    return forward(c, [&](PlateInstance& i) { return i.setString(vr, nvr, value); });
}

// ---------------------------------------------------------------------------------------------
// FMU states

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate* FMUstate) {
    return forward(c, [&](PlateInstance& i) { return i.getFMUstate(FMUstate); });
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate) {
    return forward(c, [&](PlateInstance& i) { return i.setFMUstate(FMUstate); });
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate* FMUstate) {
    return forward(c, [&](PlateInstance& i) { return i.freeFMUstate(FMUstate); });
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate FMUstate, size_t* size) {
    return forward(c, [&](PlateInstance& i) { return i.serializedFMUstateSize(FMUstate, size); });
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate FMUstate, fmi2Byte serializedState[], size_t size) {
    return forward(c, [&](PlateInstance& i) { return i.serializeFMUstate(FMUstate, serializedState, size); });
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[], size_t size,
                                   fmi2FMUstate* FMUstate) {
    return forward(c, [&](PlateInstance& i) { return i.deSerializeFMUstate(serializedState, size, FMUstate); });
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference[], size_t,
                                        const fmi2ValueReference[], size_t, const fmi2Real[], fmi2Real[]) {
    return forward(c, [&](PlateInstance& i) { return i.getDirectionalDerivative(); });
}

// ---------------------------------------------------------------------------------------------
// Model Exchange: not implemented by this FMU (every call returns fmi2Error with a log line)

fmi2Status fmi2EnterEventMode(fmi2Component c) {
    return forward(c, [&](PlateInstance& i) { return i.modelExchangeFunction("fmi2EnterEventMode"); });
}

fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo*) {
    return forward(c, [&](PlateInstance& i) { return i.modelExchangeFunction("fmi2NewDiscreteStates"); });
}

fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c) {
    return forward(c, [&](PlateInstance& i) { return i.modelExchangeFunction("fmi2EnterContinuousTimeMode"); });
}

fmi2Status fmi2CompletedIntegratorStep(fmi2Component c, fmi2Boolean, fmi2Boolean*, fmi2Boolean*) {
    return forward(c, [&](PlateInstance& i) { return i.modelExchangeFunction("fmi2CompletedIntegratorStep"); });
}

fmi2Status fmi2SetTime(fmi2Component c, fmi2Real) {
    return forward(c, [&](PlateInstance& i) { return i.modelExchangeFunction("fmi2SetTime"); });
}

fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real[], size_t) {
    return forward(c, [&](PlateInstance& i) { return i.modelExchangeFunction("fmi2SetContinuousStates"); });
}

fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real[], size_t) {
    return forward(c, [&](PlateInstance& i) { return i.modelExchangeFunction("fmi2GetDerivatives"); });
}

fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real[], size_t) {
    return forward(c, [&](PlateInstance& i) { return i.modelExchangeFunction("fmi2GetEventIndicators"); });
}

fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real[], size_t) {
    return forward(c, [&](PlateInstance& i) { return i.modelExchangeFunction("fmi2GetContinuousStates"); });
}

fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real[], size_t) {
    return forward(c, [&](PlateInstance& i) { return i.modelExchangeFunction("fmi2GetNominalsOfContinuousStates"); });
}

// ---------------------------------------------------------------------------------------------
// Co-Simulation

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[]) {
    return forward(c, [&](PlateInstance& i) { return i.setRealInputDerivatives(vr, nvr, order, value); });
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[]) {
    return forward(c, [&](PlateInstance& i) { return i.getRealOutputDerivatives(vr, nvr, order, value); });
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint) {
    return forward(c, [&](PlateInstance& i) {
        return i.doStep(currentCommunicationPoint, communicationStepSize, noSetFMUStatePriorToCurrentPoint);
    });
}

fmi2Status fmi2CancelStep(fmi2Component c) {
    return forward(c, [&](PlateInstance& i) { return i.cancelStep(); });
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status* value) {
    return forward(c, [&](PlateInstance& i) { return i.getStatus(s, value); });
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real* value) {
    return forward(c, [&](PlateInstance& i) { return i.getRealStatus(s, value); });
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer* value) {
    return forward(c, [&](PlateInstance& i) { return i.getIntegerStatus(s, value); });
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean* value) {
    return forward(c, [&](PlateInstance& i) { return i.getBooleanStatus(s, value); });
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String* value) {
    return forward(c, [&](PlateInstance& i) { return i.getStringStatus(s, value); });
}

}  // extern "C"
