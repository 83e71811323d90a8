#pragma once
// What the FMI 3.0 front end (fmi3Functions.cpp) and the FMI 3.0 model description writer
// (modelDescription/WriteModelDescription.cpp, its FMI 3.0 emitter) agree on beyond the model's
// table: the value reference of the independent variable, the FMI 3.0 type names of the table's
// types, and the states of the FMI 3.0 co-simulation state machine as the core's bits.
#include "core/FmiState.h"
#include "core/Model.h"

namespace fmu {
namespace fmi3 {

// FMI 3.0 declares the independent variable: "time", Float64, this value reference (above the
// models' own value references, which stay those of FMI 2.0). The front end reads it from the
// core's Instance::currentTime; the core knows no value reference for it.
constexpr ValueReference kTimeValueReference = 1000;

// As modelDescription.xml of FMI 3.0 spells the table's types (Real -> Float64, Integer -> Int32).
inline const char* typeName(VariableType type) {
    switch (type) {
        case VariableType::Real: return "Float64";
        case VariableType::Integer: return "Int32";
        case VariableType::Boolean: return "Boolean";
    }
    return "?";
}

// FMI 3.0 co-simulation states (FMI 3.0, section 4.2) as the core's states: Step Mode is the
// core's StepComplete; Event Mode, Configuration Mode and the rest keep their names.
constexpr State StepMode = StepComplete;
constexpr unsigned kGetStates = Instantiated | InitializationMode | ConfigurationMode | EventMode | StepMode |
                                IntermediateUpdateMode | Terminated | Error;
// IntermediateUpdateMode: the inputs that take intermediate values, when the FMU requested them
// (Instance::setValues checks).
constexpr unsigned kSetStates =
    Instantiated | ConfigurationMode | InitializationMode | EventMode | StepMode | IntermediateUpdateMode;
constexpr unsigned kFMUStateStates = Instantiated | InitializationMode | EventMode | StepMode | Terminated | Error;
constexpr unsigned kTerminateStates = EventMode | StepMode;
constexpr unsigned kResetStates = Instantiated | InitializationMode | StepComplete | StepFailed | StepCanceled |
                                  Terminated | Error | EventMode | ConfigurationMode;
constexpr unsigned kDebugLoggingStates = ~0u;

}  // namespace fmi3
}  // namespace fmu
