// The exported FMI 3.0 functions of this library (the only symbols that leave it: fmi3/exports.map):
// each calls this copy's implementation (fmi3Functions.cpp, fmi3Unsupported.cpp, compiled as plateimpactOwn_fmi3X)
// or, when another copy of the same build is the process's primary, the primary's, so that one
// copy's code and one discretization cache serve the whole process (core/PrimaryCopy.h).
// The list is that of fmi3FunctionTypes.h (one X per fmi3XTYPE); a signature that differs from
// the header's declaration does not compile, a missing one fails test_primary_copy.py.
#include "core/PrimaryCopy.h"
#include "fmi3Functions.h"

// The typed accessors, one shape each (fmi3GetBinary and fmi3SetBinary, with their sizes, stand alone).
#define FMI3_GET(X, Name, T)                                                                                   \
    X(fmi3Status, fmi3Get##Name,                                                                               \
      (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, T values[], \
       size_t nValues),                                                                                        \
      (instance, valueReferences, nValueReferences, values, nValues))
#define FMI3_SET(X, Name, T)                                                                                         \
    X(fmi3Status, fmi3Set##Name,                                                                                     \
      (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences, const T values[], \
       size_t nValues),                                                                                              \
      (instance, valueReferences, nValueReferences, values, nValues))

// X(return type, name, (parameters), (arguments))
#define FMI3_FUNCTIONS(X)                                                                                              \
    X(const char*, fmi3GetVersion, (), ())                                                                             \
    X(fmi3Status, fmi3SetDebugLogging,                                                                                 \
      (fmi3Instance instance, fmi3Boolean loggingOn, size_t nCategories, const fmi3String categories[]),               \
      (instance, loggingOn, nCategories, categories))                                                                  \
    X(fmi3Instance, fmi3InstantiateModelExchange,                                                                      \
      (fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath, fmi3Boolean visible,           \
       fmi3Boolean loggingOn, fmi3InstanceEnvironment instanceEnvironment, fmi3LogMessageCallback logMessage),         \
      (instanceName, instantiationToken, resourcePath, visible, loggingOn, instanceEnvironment, logMessage))           \
    X(fmi3Instance, fmi3InstantiateCoSimulation,                                                                       \
      (fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath, fmi3Boolean visible,           \
       fmi3Boolean loggingOn, fmi3Boolean eventModeUsed, fmi3Boolean earlyReturnAllowed,                               \
       const fmi3ValueReference requiredIntermediateVariables[], size_t nRequiredIntermediateVariables,                \
       fmi3InstanceEnvironment instanceEnvironment, fmi3LogMessageCallback logMessage,                                 \
       fmi3IntermediateUpdateCallback intermediateUpdate),                                                             \
      (instanceName, instantiationToken, resourcePath, visible, loggingOn, eventModeUsed, earlyReturnAllowed,          \
       requiredIntermediateVariables, nRequiredIntermediateVariables, instanceEnvironment, logMessage,                 \
       intermediateUpdate))                                                                                            \
    X(fmi3Instance, fmi3InstantiateScheduledExecution,                                                                 \
      (fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath, fmi3Boolean visible,           \
       fmi3Boolean loggingOn, fmi3InstanceEnvironment instanceEnvironment, fmi3LogMessageCallback logMessage,          \
       fmi3ClockUpdateCallback clockUpdate, fmi3LockPreemptionCallback lockPreemption,                                 \
       fmi3UnlockPreemptionCallback unlockPreemption),                                                                 \
      (instanceName, instantiationToken, resourcePath, visible, loggingOn, instanceEnvironment, logMessage,            \
       clockUpdate, lockPreemption, unlockPreemption))                                                                 \
    X(void, fmi3FreeInstance, (fmi3Instance instance), (instance))                                                     \
    X(fmi3Status, fmi3EnterInitializationMode,                                                                         \
      (fmi3Instance instance, fmi3Boolean toleranceDefined, fmi3Float64 tolerance, fmi3Float64 startTime,              \
       fmi3Boolean stopTimeDefined, fmi3Float64 stopTime),                                                             \
      (instance, toleranceDefined, tolerance, startTime, stopTimeDefined, stopTime))                                   \
    X(fmi3Status, fmi3ExitInitializationMode, (fmi3Instance instance), (instance))                                     \
    X(fmi3Status, fmi3EnterEventMode, (fmi3Instance instance), (instance))                                             \
    X(fmi3Status, fmi3Terminate, (fmi3Instance instance), (instance))                                                  \
    X(fmi3Status, fmi3Reset, (fmi3Instance instance), (instance))                                                      \
    FMI3_GET(X, Float32, fmi3Float32)                                                                                  \
    FMI3_GET(X, Float64, fmi3Float64)                                                                                  \
    FMI3_GET(X, Int8, fmi3Int8)                                                                                        \
    FMI3_GET(X, UInt8, fmi3UInt8)                                                                                      \
    FMI3_GET(X, Int16, fmi3Int16)                                                                                      \
    FMI3_GET(X, UInt16, fmi3UInt16)                                                                                    \
    FMI3_GET(X, Int32, fmi3Int32)                                                                                      \
    FMI3_GET(X, UInt32, fmi3UInt32)                                                                                    \
    FMI3_GET(X, Int64, fmi3Int64)                                                                                      \
    FMI3_GET(X, UInt64, fmi3UInt64)                                                                                    \
    FMI3_GET(X, Boolean, fmi3Boolean)                                                                                  \
    FMI3_GET(X, String, fmi3String)                                                                                    \
    X(fmi3Status, fmi3GetBinary,                                                                                       \
      (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,                     \
       size_t valueSizes[], fmi3Binary values[], size_t nValues),                                                      \
      (instance, valueReferences, nValueReferences, valueSizes, values, nValues))                                      \
    X(fmi3Status, fmi3GetClock,                                                                                        \
      (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,                     \
       fmi3Clock values[]),                                                                                            \
      (instance, valueReferences, nValueReferences, values))                                                           \
    FMI3_SET(X, Float32, fmi3Float32)                                                                                  \
    FMI3_SET(X, Float64, fmi3Float64)                                                                                  \
    FMI3_SET(X, Int8, fmi3Int8)                                                                                        \
    FMI3_SET(X, UInt8, fmi3UInt8)                                                                                      \
    FMI3_SET(X, Int16, fmi3Int16)                                                                                      \
    FMI3_SET(X, UInt16, fmi3UInt16)                                                                                    \
    FMI3_SET(X, Int32, fmi3Int32)                                                                                      \
    FMI3_SET(X, UInt32, fmi3UInt32)                                                                                    \
    FMI3_SET(X, Int64, fmi3Int64)                                                                                      \
    FMI3_SET(X, UInt64, fmi3UInt64)                                                                                    \
    FMI3_SET(X, Boolean, fmi3Boolean)                                                                                  \
    FMI3_SET(X, String, fmi3String)                                                                                    \
    X(fmi3Status, fmi3SetBinary,                                                                                       \
      (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,                     \
       const size_t valueSizes[], const fmi3Binary values[], size_t nValues),                                          \
      (instance, valueReferences, nValueReferences, valueSizes, values, nValues))                                      \
    X(fmi3Status, fmi3SetClock,                                                                                        \
      (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,                     \
       const fmi3Clock values[]),                                                                                      \
      (instance, valueReferences, nValueReferences, values))                                                           \
    X(fmi3Status, fmi3GetNumberOfVariableDependencies,                                                                 \
      (fmi3Instance instance, fmi3ValueReference valueReference, size_t * nDependencies),                              \
      (instance, valueReference, nDependencies))                                                                       \
    X(fmi3Status, fmi3GetVariableDependencies,                                                                         \
      (fmi3Instance instance, fmi3ValueReference dependent, size_t elementIndicesOfDependent[],                        \
       fmi3ValueReference independents[], size_t elementIndicesOfIndependents[], fmi3DependencyKind dependencyKinds[], \
       size_t nDependencies),                                                                                          \
      (instance, dependent, elementIndicesOfDependent, independents, elementIndicesOfIndependents, dependencyKinds,    \
       nDependencies))                                                                                                 \
    X(fmi3Status, fmi3GetFMUState, (fmi3Instance instance, fmi3FMUState * FMUState), (instance, FMUState))             \
    X(fmi3Status, fmi3SetFMUState, (fmi3Instance instance, fmi3FMUState FMUState), (instance, FMUState))               \
    X(fmi3Status, fmi3FreeFMUState, (fmi3Instance instance, fmi3FMUState * FMUState), (instance, FMUState))            \
    X(fmi3Status, fmi3SerializedFMUStateSize, (fmi3Instance instance, fmi3FMUState FMUState, size_t * size),           \
      (instance, FMUState, size))                                                                                      \
    X(fmi3Status, fmi3SerializeFMUState,                                                                               \
      (fmi3Instance instance, fmi3FMUState FMUState, fmi3Byte serializedState[], size_t size),                         \
      (instance, FMUState, serializedState, size))                                                                     \
    X(fmi3Status, fmi3DeserializeFMUState,                                                                             \
      (fmi3Instance instance, const fmi3Byte serializedState[], size_t size, fmi3FMUState* FMUState),                  \
      (instance, serializedState, size, FMUState))                                                                     \
    X(fmi3Status, fmi3GetDirectionalDerivative,                                                                        \
      (fmi3Instance instance, const fmi3ValueReference unknowns[], size_t nUnknowns,                                   \
       const fmi3ValueReference knowns[], size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,                      \
       fmi3Float64 sensitivity[], size_t nSensitivity),                                                                \
      (instance, unknowns, nUnknowns, knowns, nKnowns, seed, nSeed, sensitivity, nSensitivity))                        \
    X(fmi3Status, fmi3GetAdjointDerivative,                                                                            \
      (fmi3Instance instance, const fmi3ValueReference unknowns[], size_t nUnknowns,                                   \
       const fmi3ValueReference knowns[], size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,                      \
       fmi3Float64 sensitivity[], size_t nSensitivity),                                                                \
      (instance, unknowns, nUnknowns, knowns, nKnowns, seed, nSeed, sensitivity, nSensitivity))                        \
    X(fmi3Status, fmi3EnterConfigurationMode, (fmi3Instance instance), (instance))                                     \
    X(fmi3Status, fmi3ExitConfigurationMode, (fmi3Instance instance), (instance))                                      \
    X(fmi3Status, fmi3GetIntervalDecimal,                                                                              \
      (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,                     \
       fmi3Float64 intervals[], fmi3IntervalQualifier qualifiers[]),                                                   \
      (instance, valueReferences, nValueReferences, intervals, qualifiers))                                            \
    X(fmi3Status, fmi3GetIntervalFraction,                                                                             \
      (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,                     \
       fmi3UInt64 counters[], fmi3UInt64 resolutions[], fmi3IntervalQualifier qualifiers[]),                           \
      (instance, valueReferences, nValueReferences, counters, resolutions, qualifiers))                                \
    X(fmi3Status, fmi3GetShiftDecimal,                                                                                 \
      (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,                     \
       fmi3Float64 shifts[]),                                                                                          \
      (instance, valueReferences, nValueReferences, shifts))                                                           \
    X(fmi3Status, fmi3GetShiftFraction,                                                                                \
      (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,                     \
       fmi3UInt64 counters[], fmi3UInt64 resolutions[]),                                                               \
      (instance, valueReferences, nValueReferences, counters, resolutions))                                            \
    X(fmi3Status, fmi3SetIntervalDecimal,                                                                              \
      (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,                     \
       const fmi3Float64 intervals[]),                                                                                 \
      (instance, valueReferences, nValueReferences, intervals))                                                        \
    X(fmi3Status, fmi3SetIntervalFraction,                                                                             \
      (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,                     \
       const fmi3UInt64 counters[], const fmi3UInt64 resolutions[]),                                                   \
      (instance, valueReferences, nValueReferences, counters, resolutions))                                            \
    X(fmi3Status, fmi3SetShiftDecimal,                                                                                 \
      (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,                     \
       const fmi3Float64 shifts[]),                                                                                    \
      (instance, valueReferences, nValueReferences, shifts))                                                           \
    X(fmi3Status, fmi3SetShiftFraction,                                                                                \
      (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,                     \
       const fmi3UInt64 counters[], const fmi3UInt64 resolutions[]),                                                   \
      (instance, valueReferences, nValueReferences, counters, resolutions))                                            \
    X(fmi3Status, fmi3EvaluateDiscreteStates, (fmi3Instance instance), (instance))                                     \
    X(fmi3Status, fmi3UpdateDiscreteStates,                                                                            \
      (fmi3Instance instance, fmi3Boolean * discreteStatesNeedUpdate, fmi3Boolean * terminateSimulation,               \
       fmi3Boolean * nominalsOfContinuousStatesChanged, fmi3Boolean * valuesOfContinuousStatesChanged,                 \
       fmi3Boolean * nextEventTimeDefined, fmi3Float64 * nextEventTime),                                               \
      (instance, discreteStatesNeedUpdate, terminateSimulation, nominalsOfContinuousStatesChanged,                     \
       valuesOfContinuousStatesChanged, nextEventTimeDefined, nextEventTime))                                          \
    X(fmi3Status, fmi3EnterContinuousTimeMode, (fmi3Instance instance), (instance))                                    \
    X(fmi3Status, fmi3CompletedIntegratorStep,                                                                         \
      (fmi3Instance instance, fmi3Boolean noSetFMUStatePriorToCurrentPoint, fmi3Boolean * enterEventMode,              \
       fmi3Boolean * terminateSimulation),                                                                             \
      (instance, noSetFMUStatePriorToCurrentPoint, enterEventMode, terminateSimulation))                               \
    X(fmi3Status, fmi3SetTime, (fmi3Instance instance, fmi3Float64 time), (instance, time))                            \
    X(fmi3Status, fmi3SetContinuousStates,                                                                             \
      (fmi3Instance instance, const fmi3Float64 continuousStates[], size_t nContinuousStates),                         \
      (instance, continuousStates, nContinuousStates))                                                                 \
    X(fmi3Status, fmi3GetContinuousStateDerivatives,                                                                   \
      (fmi3Instance instance, fmi3Float64 derivatives[], size_t nContinuousStates),                                    \
      (instance, derivatives, nContinuousStates))                                                                      \
    X(fmi3Status, fmi3GetEventIndicators,                                                                              \
      (fmi3Instance instance, fmi3Float64 eventIndicators[], size_t nEventIndicators),                                 \
      (instance, eventIndicators, nEventIndicators))                                                                   \
    X(fmi3Status, fmi3GetContinuousStates,                                                                             \
      (fmi3Instance instance, fmi3Float64 continuousStates[], size_t nContinuousStates),                               \
      (instance, continuousStates, nContinuousStates))                                                                 \
    X(fmi3Status, fmi3GetNominalsOfContinuousStates,                                                                   \
      (fmi3Instance instance, fmi3Float64 nominals[], size_t nContinuousStates),                                       \
      (instance, nominals, nContinuousStates))                                                                         \
    X(fmi3Status, fmi3GetNumberOfEventIndicators, (fmi3Instance instance, size_t * nEventIndicators),                  \
      (instance, nEventIndicators))                                                                                    \
    X(fmi3Status, fmi3GetNumberOfContinuousStates, (fmi3Instance instance, size_t * nContinuousStates),                \
      (instance, nContinuousStates))                                                                                   \
    X(fmi3Status, fmi3EnterStepMode, (fmi3Instance instance), (instance))                                              \
    X(fmi3Status, fmi3GetOutputDerivatives,                                                                            \
      (fmi3Instance instance, const fmi3ValueReference valueReferences[], size_t nValueReferences,                     \
       const fmi3Int32 orders[], fmi3Float64 values[], size_t nValues),                                                \
      (instance, valueReferences, nValueReferences, orders, values, nValues))                                          \
    X(fmi3Status, fmi3DoStep,                                                                                          \
      (fmi3Instance instance, fmi3Float64 currentCommunicationPoint, fmi3Float64 communicationStepSize,                \
       fmi3Boolean noSetFMUStatePriorToCurrentPoint, fmi3Boolean * eventHandlingNeeded,                                \
       fmi3Boolean * terminateSimulation, fmi3Boolean * earlyReturn, fmi3Float64 * lastSuccessfulTime),                \
      (instance, currentCommunicationPoint, communicationStepSize, noSetFMUStatePriorToCurrentPoint,                   \
       eventHandlingNeeded, terminateSimulation, earlyReturn, lastSuccessfulTime))                                     \
    X(fmi3Status, fmi3ActivateModelPartition,                                                                          \
      (fmi3Instance instance, fmi3ValueReference clockReference, fmi3Float64 activationTime),                          \
      (instance, clockReference, activationTime))

FMU_FORWARDED_EXPORTS(FMI3_FUNCTIONS, "FMI3")
