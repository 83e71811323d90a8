#pragma once
// The co-simulation state machine's states, shared by the instance (Instance.h) and the FMU
// states that record them (StateFormat.h).
namespace fmu {

// States of the co-simulation state machine (FMI 2.0.4 section 4.2.4, FMI 3.0 section 4.2), as bits so
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
    ConfigurationMode = 1u << 12,  // FMI 3.0 only (entering configuration mode)
    // FMI 3.0 only: inside a step, while the master's intermediate update callback runs
    // (outputs may be read, nothing set).
    IntermediateUpdateMode = 1u << 13,
};
const char* stateName(State state);

}  // namespace fmu
