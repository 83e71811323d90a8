#pragma once
// One instance of the PlateImpact co-simulation FMU: its values, the PlateSimulation built
// from them, the FMI 2.0 state machine and the logger. fmi2Functions.cpp maps each fmi2*
// call onto one method; every method returns the fmi2Status for the importer and never
// throws. No numerics here: all physics is in plate::PlateSimulation.
#include <cstdarg>
#include <memory>
#include <string>

#include "PlateSimulation.h"
#include "Variables.h"
#include "fmi2Functions.h"

namespace plateimpact {

// States of the FMI 2.0 co-simulation state machine (FMI 2.0.4, section 4.2.4), as bits so
// that the allowed states of a function are one mask. EventMode and ContinuousTimeMode
// belong to Model Exchange and are never entered.
enum State : unsigned {
    StartAndEnd = 1u << 0,
    Instantiated = 1u << 1,
    InitializationMode = 1u << 2,
    EventMode = 1u << 3,
    ContinuousTimeMode = 1u << 4,
    StepComplete = 1u << 5,
    StepInProgress = 1u << 6,
    StepFailed = 1u << 7,
    StepCanceled = 1u << 8,
    Terminated = 1u << 9,
    Error = 1u << 10,
    Fatal = 1u << 11,
};
const char* stateName(State state);

// Log categories declared in modelDescription.xml (LogCategories).
enum LogCategory { LogStatusError = 0, LogStatusWarning = 1, LogAll = 2, LogCategoryCount = 3 };
const char* logCategoryName(LogCategory category);

// The GUID compiled into this binary (generated at build time; see fmu/cmake/MakeGuid.cmake).
const char* buildGuid();

// Logging without an instance (fmi2Instantiate failures).
void logWithoutInstance(const fmi2CallbackFunctions* functions, fmi2String instanceName,
                        const char* format, ...) __attribute__((format(printf, 3, 4)));

struct Snapshot;

class PlateInstance {
public:
    PlateInstance(std::string instanceName, const fmi2CallbackFunctions& callbacks, bool loggingOn);
    ~PlateInstance();
    PlateInstance(const PlateInstance&) = delete;
    PlateInstance& operator=(const PlateInstance&) = delete;

    fmi2Status setDebugLogging(fmi2Boolean loggingOn, size_t nCategories, const fmi2String categories[]);

    fmi2Status setupExperiment(fmi2Boolean toleranceDefined, fmi2Real tolerance, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime);
    fmi2Status enterInitializationMode();
    fmi2Status exitInitializationMode();
    fmi2Status terminate();
    fmi2Status reset();
    void logFreeInstance();

    fmi2Status getReal(const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]);
    fmi2Status getInteger(const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[]);
    fmi2Status getBoolean(const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[]);
    fmi2Status getString(const fmi2ValueReference vr[], size_t nvr, fmi2String value[]);
    fmi2Status setReal(const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]);
    fmi2Status setInteger(const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[]);
    fmi2Status setBoolean(const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[]);
    fmi2Status setString(const fmi2ValueReference vr[], size_t nvr, const fmi2String value[]);

    fmi2Status getFMUstate(fmi2FMUstate* state);
    fmi2Status setFMUstate(fmi2FMUstate state);
    fmi2Status freeFMUstate(fmi2FMUstate* state);
    fmi2Status serializedFMUstateSize(fmi2FMUstate state, size_t* size);
    fmi2Status serializeFMUstate(fmi2FMUstate state, fmi2Byte serialized[], size_t size);
    fmi2Status deSerializeFMUstate(const fmi2Byte serialized[], size_t size, fmi2FMUstate* state);

    fmi2Status setRealInputDerivatives(const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[]);
    fmi2Status getRealOutputDerivatives(const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[]);
    fmi2Status doStep(fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint);
    fmi2Status cancelStep();

    fmi2Status getStatus(fmi2StatusKind kind, fmi2Status* value);
    fmi2Status getRealStatus(fmi2StatusKind kind, fmi2Real* value);
    fmi2Status getIntegerStatus(fmi2StatusKind kind, fmi2Integer* value);
    fmi2Status getBooleanStatus(fmi2StatusKind kind, fmi2Boolean* value);
    fmi2Status getStringStatus(fmi2StatusKind kind, fmi2String* value);

    // fmi2GetDirectionalDerivative: not provided (providesDirectionalDerivative="false").
    fmi2Status getDirectionalDerivative();
    // Model-exchange functions: this FMU implements co-simulation only.
    fmi2Status modelExchangeFunction(const char* function);

private:
    // Runs `body` if the state allows `function` (else logs "illegal call sequence: ..."),
    // turns exceptions into a logged fmi2Error and enters the error state on fmi2Error.
    template <class Body>
    fmi2Status call(const char* function, unsigned allowedStates, Body&& body);
    fmi2Status fail(const char* format, ...) __attribute__((format(printf, 2, 3)));
    void log(fmi2Status status, LogCategory category, const char* format, ...)
        __attribute__((format(printf, 4, 5)));
    void vlog(fmi2Status status, LogCategory category, const char* format, va_list args);

    double currentTime() const;
    const Variable* variableFor(const char* function, fmi2ValueReference vr, bool integerTypes,
                                VariableType type);
    fmi2Status checkSettable(const char* function, const Variable& variable);
    void afterSet(const Variable& variable);
    void ensureSimulation(const char* function);
    bool needsOutputs(const fmi2ValueReference vr[], size_t nvr) const;
    void refreshOutputs();
    void capture(Snapshot& snapshot) const;
    void restore(const Snapshot& snapshot);
    fmi2Status statusNotAvailable(const char* function, fmi2StatusKind kind);

    std::string instanceName_;
    fmi2CallbackFunctions callbacks_;
    bool logCategories_[LogCategoryCount];

    State state_ = Instantiated;
    double startTime_ = 0.0;
    ModelValues values_;
    // Built from values_ at fmi2ExitInitializationMode (or earlier, when an output is read
    // in initialization mode); dropped whenever a value that shapes the initial state changes.
    std::unique_ptr<plate::PlateSimulation> simulation_;
    double simulationBase0_ = 0.0;  // base displacement the simulation was built with
};

}  // namespace plateimpact
