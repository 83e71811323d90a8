// The exported FMI 2.0 functions of this library (the only symbols that leave it: fmi2/exports.map):
// each calls this copy's implementation (fmi2Functions.cpp, compiled as plateimpactOwn_fmi2X)
// or, when another copy of the same build is the process's primary, the primary's, so that one
// copy's code and one discretization cache serve the whole process (core/PrimaryCopy.h).
// The list is that of fmi2FunctionTypes.h (one X per fmi2XTYPE); a signature that differs from
// the header's declaration does not compile, a missing one fails test_primary_copy.py.
#include "core/PrimaryCopy.h"
#include "fmi2Functions.h"

// X(return type, name, (parameters), (arguments))
#define FMI2_FUNCTIONS(X)                                                                                              \
    X(const char*, fmi2GetTypesPlatform, (), ())                                                                       \
    X(const char*, fmi2GetVersion, (), ())                                                                             \
    X(fmi2Status, fmi2SetDebugLogging,                                                                                 \
      (fmi2Component c, fmi2Boolean loggingOn, size_t nCategories, const fmi2String categories[]),                     \
      (c, loggingOn, nCategories, categories))                                                                         \
    X(fmi2Component, fmi2Instantiate,                                                                                  \
      (fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID, fmi2String fmuResourceLocation,                  \
       const fmi2CallbackFunctions* functions, fmi2Boolean visible, fmi2Boolean loggingOn),                            \
      (instanceName, fmuType, fmuGUID, fmuResourceLocation, functions, visible, loggingOn))                            \
    X(void, fmi2FreeInstance, (fmi2Component c), (c))                                                                  \
    X(fmi2Status, fmi2SetupExperiment,                                                                                 \
      (fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance, fmi2Real startTime,                          \
       fmi2Boolean stopTimeDefined, fmi2Real stopTime),                                                                \
      (c, toleranceDefined, tolerance, startTime, stopTimeDefined, stopTime))                                          \
    X(fmi2Status, fmi2EnterInitializationMode, (fmi2Component c), (c))                                                 \
    X(fmi2Status, fmi2ExitInitializationMode, (fmi2Component c), (c))                                                  \
    X(fmi2Status, fmi2Terminate, (fmi2Component c), (c))                                                               \
    X(fmi2Status, fmi2Reset, (fmi2Component c), (c))                                                                   \
    X(fmi2Status, fmi2GetReal, (fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]),         \
      (c, vr, nvr, value))                                                                                             \
    X(fmi2Status, fmi2GetInteger, (fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[]),   \
      (c, vr, nvr, value))                                                                                             \
    X(fmi2Status, fmi2GetBoolean, (fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[]),   \
      (c, vr, nvr, value))                                                                                             \
    X(fmi2Status, fmi2GetString, (fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String value[]),     \
      (c, vr, nvr, value))                                                                                             \
    X(fmi2Status, fmi2SetReal, (fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]),   \
      (c, vr, nvr, value))                                                                                             \
    X(fmi2Status, fmi2SetInteger,                                                                                      \
      (fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[]), (c, vr, nvr, value))    \
    X(fmi2Status, fmi2SetBoolean,                                                                                      \
      (fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[]), (c, vr, nvr, value))    \
    X(fmi2Status, fmi2SetString,                                                                                       \
      (fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String value[]), (c, vr, nvr, value))     \
    X(fmi2Status, fmi2GetFMUstate, (fmi2Component c, fmi2FMUstate * FMUstate), (c, FMUstate))                          \
    X(fmi2Status, fmi2SetFMUstate, (fmi2Component c, fmi2FMUstate FMUstate), (c, FMUstate))                            \
    X(fmi2Status, fmi2FreeFMUstate, (fmi2Component c, fmi2FMUstate * FMUstate), (c, FMUstate))                         \
    X(fmi2Status, fmi2SerializedFMUstateSize, (fmi2Component c, fmi2FMUstate FMUstate, size_t * size),                 \
      (c, FMUstate, size))                                                                                             \
    X(fmi2Status, fmi2SerializeFMUstate, (fmi2Component c, fmi2FMUstate FMUstate, fmi2Byte a2[], size_t size),         \
      (c, FMUstate, a2, size))                                                                                         \
    X(fmi2Status, fmi2DeSerializeFMUstate,                                                                             \
      (fmi2Component c, const fmi2Byte serializedState[], size_t size, fmi2FMUstate* FMUstate),                        \
      (c, serializedState, size, FMUstate))                                                                            \
    X(fmi2Status, fmi2GetDirectionalDerivative,                                                                        \
      (fmi2Component c, const fmi2ValueReference vUnknown_ref[], size_t nUnknown,                                      \
       const fmi2ValueReference vKnown_ref[], size_t nKnown, const fmi2Real dvKnown[], fmi2Real dvUnknown[]),          \
      (c, vUnknown_ref, nUnknown, vKnown_ref, nKnown, dvKnown, dvUnknown))                                             \
    X(fmi2Status, fmi2EnterEventMode, (fmi2Component c), (c))                                                          \
    X(fmi2Status, fmi2NewDiscreteStates, (fmi2Component c, fmi2EventInfo * fmi2eventInfo), (c, fmi2eventInfo))         \
    X(fmi2Status, fmi2EnterContinuousTimeMode, (fmi2Component c), (c))                                                 \
    X(fmi2Status, fmi2CompletedIntegratorStep,                                                                         \
      (fmi2Component c, fmi2Boolean noSetFMUStatePriorToCurrentPoint, fmi2Boolean * enterEventMode,                    \
       fmi2Boolean * terminateSimulation),                                                                             \
      (c, noSetFMUStatePriorToCurrentPoint, enterEventMode, terminateSimulation))                                      \
    X(fmi2Status, fmi2SetTime, (fmi2Component c, fmi2Real time), (c, time))                                            \
    X(fmi2Status, fmi2SetContinuousStates, (fmi2Component c, const fmi2Real x[], size_t nx), (c, x, nx))               \
    X(fmi2Status, fmi2GetDerivatives, (fmi2Component c, fmi2Real derivatives[], size_t nx), (c, derivatives, nx))      \
    X(fmi2Status, fmi2GetEventIndicators, (fmi2Component c, fmi2Real eventIndicators[], size_t ni),                    \
      (c, eventIndicators, ni))                                                                                        \
    X(fmi2Status, fmi2GetContinuousStates, (fmi2Component c, fmi2Real x[], size_t nx), (c, x, nx))                     \
    X(fmi2Status, fmi2GetNominalsOfContinuousStates, (fmi2Component c, fmi2Real x_nominal[], size_t nx),               \
      (c, x_nominal, nx))                                                                                              \
    X(fmi2Status, fmi2SetRealInputDerivatives,                                                                         \
      (fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer order[], const fmi2Real value[]), \
      (c, vr, nvr, order, value))                                                                                      \
    X(fmi2Status, fmi2GetRealOutputDerivatives,                                                                        \
      (fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer order[], fmi2Real value[]),       \
      (c, vr, nvr, order, value))                                                                                      \
    X(fmi2Status, fmi2DoStep,                                                                                          \
      (fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,                            \
       fmi2Boolean noSetFMUStatePriorToCurrentPoint),                                                                  \
      (c, currentCommunicationPoint, communicationStepSize, noSetFMUStatePriorToCurrentPoint))                         \
    X(fmi2Status, fmi2CancelStep, (fmi2Component c), (c))                                                              \
    X(fmi2Status, fmi2GetStatus, (fmi2Component c, const fmi2StatusKind s, fmi2Status* value), (c, s, value))          \
    X(fmi2Status, fmi2GetRealStatus, (fmi2Component c, const fmi2StatusKind s, fmi2Real* value), (c, s, value))        \
    X(fmi2Status, fmi2GetIntegerStatus, (fmi2Component c, const fmi2StatusKind s, fmi2Integer* value), (c, s, value))  \
    X(fmi2Status, fmi2GetBooleanStatus, (fmi2Component c, const fmi2StatusKind s, fmi2Boolean* value), (c, s, value))  \
    X(fmi2Status, fmi2GetStringStatus, (fmi2Component c, const fmi2StatusKind s, fmi2String* value), (c, s, value))

FMU_FORWARDED_EXPORTS(FMI2_FUNCTIONS, "FMI2")
