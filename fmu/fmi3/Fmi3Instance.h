#pragma once
// What the FMI 3.0 front end's files share (fmi3Functions.cpp, fmi3Unsupported.cpp): one FMI 3.0
// instance (the master's callbacks and grants over the core's Instance), the conversion of
// statuses and of the logger, and `run`, through which every fmi3* function calls its body.
#include <memory>

#include "core/Instance.h"
#include "fmi3FunctionTypes.h"

namespace fmu {
namespace fmi3 {

// Status and fmi3Status list the same outcomes in the same order.
inline fmi3Status toFmi3(fmu::Status status) {
    static constexpr fmi3Status kStatus[] = {fmi3OK, fmi3Warning, fmi3Discard, fmi3Error, fmi3Fatal};
    return kStatus[static_cast<int>(status)];
}

// The core's logger over the master's fmi3LogMessageCallback (none without one).
inline fmu::Logger loggerOf(fmi3InstanceEnvironment environment, fmi3LogMessageCallback logMessage) {
    if (!logMessage) return nullptr;
    return [environment, logMessage](fmu::Status status, const char* category, const char* message) {
        logMessage(environment, toFmi3(status), category, message);
    };
}

// One FMI 3.0 instance: the master's callbacks and grants, and the core's Instance.
struct Fmi3Instance {
    fmi3InstanceEnvironment environment = nullptr;
    bool eventModeUsed = false;
    bool earlyReturnAllowed = false;
    fmi3IntermediateUpdateCallback intermediateUpdate = nullptr;
    std::unique_ptr<Instance> instance;
};

// Runs `body(self, instance)` as `function` when `c` is an instance and the state allows it.
template <class Body>
fmi3Status run(fmi3Instance c, const char* function, unsigned allowed, Body&& body) {
    auto* self = static_cast<Fmi3Instance*>(c);
    if (!self) return fmi3Error;  // a NULL instance has no logger to tell
    Instance& instance = *self->instance;
    return toFmi3(instance.call(function, allowed, [&]() -> Status { return body(*self, instance); }));
}

// A function this FMU does not implement: logs why, in any state.
inline fmi3Status unsupported(fmi3Instance c, const char* function, const char* why) {
    return run(c, function, fmu::kAnyState, [&](Fmi3Instance&, Instance& i) { return i.fail("%s", why); });
}

constexpr const char* kModelExchange =
    "Model Exchange is not supported; this FMU implements FMI 3.0 Co-Simulation only";
constexpr const char* kScheduled = "Scheduled Execution is not supported; this FMU implements Co-Simulation only";
constexpr const char* kNoClocks = "this FMU has no clocks";

// An instantiation of an interface type this FMU does not implement: logs why, returns NULL.
inline fmi3Instance refuse(fmi3InstanceEnvironment environment, fmi3LogMessageCallback logMessage, const char* function,
                           fmi3String instanceName, const char* why) {
    fmu::logWithoutInstance(loggerOf(environment, logMessage), "%s (%s): %s", function,
                            instanceName ? instanceName : "", why);
    return nullptr;
}

}  // namespace fmi3
}  // namespace fmu
