#pragma once
// One instance of a co-simulation FMU, model-independent: the FMI 2.0 state machine (one
// allowed-state mask per function), logging, the checks every fmi2Get*/fmi2Set* makes against
// the model's table of variables, FMU states, and the dispatch that runs a function's body,
// prefixes its messages with the function's name and keeps exceptions inside. Everything the
// model does is behind fmu::Model (Model.h).
#include <cstdarg>
#include <functional>
#include <memory>
#include <string>

#include "core/FmiState.h"
#include "core/Model.h"
#include "fmi2Functions.h"

// printf-style checking of the log formats; mingw-w64 formats with its own C99 stdio.
#if defined(__MINGW32__)
#define PLATEIMPACT_PRINTF_FORMAT(f, a) __attribute__((format(gnu_printf, f, a)))
#else
#define PLATEIMPACT_PRINTF_FORMAT(f, a) __attribute__((format(printf, f, a)))
#endif

namespace fmu {

// Log categories every FMU of this layer declares.
enum LogCategory { LogStatusError = 0, LogStatusWarning = 1, LogAll = 2, LogInfo = 3, LogCategoryCount = 4 };
const char* logCategoryName(LogCategory category);

// Logging without an instance (fmi2Instantiate failures).
void logWithoutInstance(const fmi2CallbackFunctions* functions, fmi2String instanceName, const char* format, ...)
    PLATEIMPACT_PRINTF_FORMAT(3, 4);

struct Snapshot;

class Instance {
public:
    // `api` is the prefix of the front end's function names ("fmi2" or "fmi3"): the messages the
    // layer writes on its own name the functions of the interface the importer called.
    Instance(std::string instanceName, const fmi2CallbackFunctions& callbacks, bool loggingOn,
             const char* api = "fmi2");
    ~Instance();
    Instance(const Instance&) = delete;
    Instance& operator=(const Instance&) = delete;

    // Runs `body` as the fmi2 function `function` if the state allows it (else logs "illegal
    // call sequence: ..."); exceptions become a logged fmi2Error; fmi2Error enters the error
    // state. fmi2Functions.cpp calls every function through it.
    template <class Body>
    fmi2Status call(const char* function, unsigned allowedStates, Body&& body);

    fmi2Status setDebugLogging(fmi2Boolean loggingOn, size_t nCategories, const fmi2String categories[]);
    fmi2Status setupExperiment(fmi2Real startTime, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime);
    fmi2Status enterInitializationMode();
    fmi2Status exitInitializationMode();
    fmi2Status terminate();
    fmi2Status reset();
    void logFreeInstance();

    // fmi2Get*/fmi2Set* of any type: values travel as doubles (exact for Integer and Boolean).
    fmi2Status getValues(VariableType type, const fmi2ValueReference vr[], size_t nvr, double value[]);
    fmi2Status setValues(VariableType type, const fmi2ValueReference vr[], size_t nvr, const double value[]);

    fmi2Status getFMUstate(fmi2FMUstate* state);
    fmi2Status setFMUstate(fmi2FMUstate state);
    fmi2Status freeFMUstate(fmi2FMUstate* state);
    fmi2Status serializedFMUstateSize(fmi2FMUstate state, size_t* size);
    fmi2Status serializeFMUstate(fmi2FMUstate state, fmi2Byte serialized[], size_t size);
    fmi2Status deSerializeFMUstate(const fmi2Byte serialized[], size_t size, fmi2FMUstate* state);

    fmi2Status setRealInputDerivatives(const fmi2ValueReference vr[], size_t nvr, const fmi2Integer order[],
                                       const fmi2Real value[]);
    fmi2Status getRealOutputDerivatives(const fmi2ValueReference vr[], size_t nvr, const fmi2Integer order[],
                                        fmi2Real value[]);
    fmi2Status doStep(fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize);
    // FMI 3.0 (fmi3Functions.cpp): with stopAtEvent the step may end early at an event of the
    // model (Model::doStepUntilEvent); *endedAtEvent tells whether it ended at one.
    fmi2Status doStep(fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize, bool stopAtEvent,
                      bool* endedAtEvent);
    // FMI 3.0 intermediate update: `callback(time)` runs the master's callback at an internal
    // grid point (the instance in IntermediateUpdateMode meanwhile) and returns the early return
    // time it asked for (HUGE_VAL: none). Kept across fmi3Reset.
    void setIntermediateUpdate(std::function<double(double)> callback);
    // FMI 3.0 arrays: the values of an array output of the model (n of them).
    fmi2Status getArray(const ArrayOutput& array, double value[], size_t n);
    // FMI 3.0 transitions without work of their own (configuration, event and step mode).
    void enterState(State next) { state_ = next; }
    const Model& model() const { return *model_; }
    Model& model() { return *model_; }
    fmi2Status statusNotAvailable(fmi2StatusKind kind);
    double currentTime() const;

    // Logs "<function>: <message>" as an fmi2Error and returns fmi2Error.
    fmi2Status fail(const char* format, ...) PLATEIMPACT_PRINTF_FORMAT(2, 3);
    void log(fmi2Status status, LogCategory category, const char* format, ...) PLATEIMPACT_PRINTF_FORMAT(4, 5);

    State state() const { return state_; }

private:
    void vlog(fmi2Status status, LogCategory category, const char* format, va_list args);
    const Variable* variableFor(fmi2ValueReference vr, VariableType type);
    bool settable(const Variable& variable);  // logs why not
    void capture(Snapshot& snapshot) const;
    void restore(const Snapshot& snapshot);
    void attachTrace();

    std::string instanceName_;
    fmi2CallbackFunctions callbacks_;
    bool logCategories_[LogCategoryCount];
    const char* api_;  // "fmi2" or "fmi3"
    const char* function_ = "";  // the fmi2/fmi3 function running (message prefix)
    State state_ = Instantiated;
    double startTime_ = 0.0;
    std::unique_ptr<Model> model_;
    std::function<double(double)> intermediateUpdate_;
};

template <class Body>
fmi2Status Instance::call(const char* function, unsigned allowedStates, Body&& body) {
    function_ = function;
    fmi2Status status = fmi2Error;
    if (!(state_ & allowedStates)) {
        log(fmi2Error, LogStatusError, "illegal call sequence: %s is not allowed in state %s", function,
            stateName(state_));
    } else {
        try {
            status = body();
        } catch (const std::exception& e) {
            fail("%s", e.what());
        } catch (...) {
            fail("unknown exception");
        }
    }
    // FMI 2.0: after fmi2Error only fmi2SetFMUstate, fmi2Reset, fmi2FreeInstance (and getters
    // for debugging) are allowed.
    if (status == fmi2Error) state_ = Error;
    if (status == fmi2Fatal) state_ = Fatal;
    return status;
}

// Allowed states of each function group (FMI 2.0.4, table in section 4.2.4).
constexpr unsigned kFreeInstanceStates =
    Instantiated | InitializationMode | StepComplete | StepFailed | StepCanceled | Terminated | Error;
constexpr unsigned kDebugLoggingStates = kFreeInstanceStates | StepInProgress;
constexpr unsigned kResetStates = kFreeInstanceStates;
constexpr unsigned kFMUstateStates = kFreeInstanceStates;
constexpr unsigned kGetStates = InitializationMode | StepComplete | StepFailed | StepCanceled | Terminated | Error;
constexpr unsigned kSetStates = Instantiated | InitializationMode | StepComplete;
constexpr unsigned kInputDerivativeStates = Instantiated | InitializationMode | StepComplete;
constexpr unsigned kOutputDerivativeStates = StepComplete | StepFailed | StepCanceled | Terminated | Error;
constexpr unsigned kStatusStates = StepComplete | StepInProgress | StepFailed | Terminated;
constexpr unsigned kAnyState = ~0u;

}  // namespace fmu
