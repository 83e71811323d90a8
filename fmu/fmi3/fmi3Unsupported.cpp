// The FMI 3.0 functions this FMU does not implement — Model Exchange, Scheduled Execution, clocks,
// directional and adjoint derivatives, per-element dependencies, discrete-state evaluation: each
// logs why and returns fmi3Error (an instantiation: NULL), as the Reference FMUs do.
#include "fmi3/Fmi3Instance.h"
#include "fmi3/Fmi3Own.h"

using fmu::fmi3::kModelExchange;
using fmu::fmi3::kNoClocks;
using fmu::fmi3::kScheduled;
using fmu::fmi3::refuse;
using fmu::fmi3::unsupported;

extern "C" {

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

fmi3Status fmi3GetDirectionalDerivative(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3ValueReference[],
                                        size_t, const fmi3Float64[], size_t, fmi3Float64[], size_t) {
    return unsupported(c, "fmi3GetDirectionalDerivative", "not supported (providesDirectionalDerivatives=\"false\")");
}

fmi3Status fmi3GetAdjointDerivative(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3ValueReference[],
                                    size_t, const fmi3Float64[], size_t, fmi3Float64[], size_t) {
    return unsupported(c, "fmi3GetAdjointDerivative", "not supported (providesAdjointDerivatives=\"false\")");
}

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

fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance c) {
    return unsupported(c, "fmi3EvaluateDiscreteStates", "not supported (providesEvaluateDiscreteStates=\"false\")");
}

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

}  // extern "C"
