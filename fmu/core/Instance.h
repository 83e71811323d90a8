#pragma once
// One instance of a co-simulation FMU, model-independent and of no FMI version: the state
// machine (the front end gives each function's allowed-state mask), logging, the checks every
// get/set makes against the model's table of variables, FMU states, and the dispatch that runs
// a function's body, prefixes its messages with the function's name and keeps exceptions
// inside. Everything the model does is behind fmu::Model (Model.h); the front ends
// (the folders fmi2/ and fmi3/) convert types and statuses (core/Types.h).
#include <cstdarg>
#include <functional>
#include <memory>
#include <string>

#include "core/FmiState.h"
#include "core/Model.h"
#include "core/Types.h"

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

// Logging without an instance (failed instantiations): an error in logStatusError.
void logWithoutInstance(const Logger& logger, const char* format, ...) PLATEIMPACT_PRINTF_FORMAT(2, 3);

// What the core knows of its front end: how its own messages name two functions of the front
// end's interface, and the FMI version the model serves (Model::useVersion).
struct ApiNames {
    const char* exitInitializationMode;  // fixed parameters can be set only before it
    const char* serializedStateSize;  // gives the size a serialized state needs
    int fmiVersion;
};

struct Snapshot;

class Instance {
public:
    // `names`: the functions of the front end's interface that the core's messages name.
    Instance(Logger logger, bool loggingOn, ApiNames names);
    ~Instance();
    Instance(const Instance&) = delete;
    Instance& operator=(const Instance&) = delete;

    // Runs `body` as the front end's function `function` if the state allows it (else logs
    // "illegal call sequence: ..."); exceptions become a logged Status::Error; an error enters
    // the error state. The front ends call every function through it.
    template <class Body>
    Status call(const char* function, unsigned allowedStates, Body&& body);

    Status setDebugLogging(bool loggingOn, std::size_t nCategories, const char* const categories[]);
    Status setupExperiment(double startTime, bool toleranceDefined, double tolerance, bool stopTimeDefined,
                           double stopTime);
    Status enterInitializationMode();
    Status exitInitializationMode();
    Status terminate();
    Status reset();

    // Get/set of any type: values travel as doubles (exact for Integer and Boolean).
    Status getValues(VariableType type, const ValueReference vr[], std::size_t nvr, double value[]);
    Status setValues(VariableType type, const ValueReference vr[], std::size_t nvr, const double value[]);

    Status getState(StateHandle* state);
    Status setState(StateHandle state);
    Status freeState(StateHandle* state);
    Status serializedStateSize(StateHandle state, std::size_t* size);
    Status serializeState(StateHandle state, Byte serialized[], std::size_t size);
    Status deserializeState(const Byte serialized[], std::size_t size, StateHandle* state);

    // Derivatives of Real inputs (set) and outputs (get), orders from 1.
    Status setInputDerivatives(const ValueReference vr[], std::size_t nvr, const int order[], const double value[]);
    Status getOutputDerivatives(const ValueReference vr[], std::size_t nvr, const int order[], double value[]);
    // One communication step from `t` (the current time, checked) of length `h`. With
    // stopAtEvent the step may end early at an event of the model (Model::doStepUntilEvent);
    // *endedAtEvent tells whether it ended at one.
    Status doStep(double t, double h, bool stopAtEvent = false, bool* endedAtEvent = nullptr);
    // Intermediate update (FMI 3.0): `callback(time)` runs the master's callback at an internal
    // grid point (the instance in IntermediateUpdateMode meanwhile) and returns the early return
    // time it asked for (HUGE_VAL: none). Kept across reset().
    void setIntermediateUpdate(std::function<double(double)> callback);
    // Intermediate update with inputs (FMI 3.0): `callback(time)` runs the master's callback before
    // the internal step to `time`, asking it to set the inputs that take intermediate values
    // (Model::takesIntermediateValue); only those, and only then, may be set. Kept across reset().
    void setIntermediateInputs(std::function<void(double)> callback);
    // Arrays (FMI 3.0): the values of an array of the model (n of them); setting a parameter array
    // (n its length now, checked by the caller) before initialization ends.
    Status getArray(const ArrayVariable& array, double value[], std::size_t n);
    Status setArray(const ArrayVariable& array, const double value[], std::size_t n);
    // Number of values of an array output: the product of its extents' values now.
    std::size_t arrayLength(const ArrayVariable& array) const;
    // Structural parameters (FMI 3.0): the value now (0 for a negative one), and setting it: its
    // own value, or its Integer parameter becomes value - offset.
    std::size_t structuralValue(const StructuralParameter& s) const;
    Status setStructural(const StructuralParameter& s, double value);
    // Transitions without work of their own (configuration, event and step mode).
    void enterState(State next) { state_ = next; }
    const Model& model() const { return *model_; }
    Model& model() { return *model_; }
    // The time of the independent variable: the start time plus the model's time.
    double currentTime() const;
    const char* function() const { return function_; }  // the function running (message prefix)

    // Logs "<function>: <message>" as an error and returns Status::Error.
    Status fail(const char* format, ...) PLATEIMPACT_PRINTF_FORMAT(2, 3);
    void log(Status status, LogCategory category, const char* format, ...) PLATEIMPACT_PRINTF_FORMAT(4, 5);

    State state() const { return state_; }

private:
    void vlog(Status status, LogCategory category, const char* format, va_list args);
    const Variable* variableFor(ValueReference vr, VariableType type);
    bool settable(const Variable& variable);  // logs why not
    void capture(Snapshot& snapshot) const;
    void restore(const Snapshot& snapshot);
    void attachTrace();
    // After an error, what the importer may still call (the message of a refused call says it).
    const char* howToGoOn() const;

    Logger logger_;
    bool logCategories_[LogCategoryCount];
    ApiNames names_;
    const char* function_ = "";  // the front end's function running (message prefix)
    State state_ = Instantiated;
    double startTime_ = 0.0;
    std::unique_ptr<Model> model_;
    std::function<double(double)> intermediateUpdate_;
    std::function<void(double)> intermediateInputs_;
    bool inputsRequested_ = false;  // inside intermediateInputs_: the inputs may be set
};

template <class Body>
Status Instance::call(const char* function, unsigned allowedStates, Body&& body) {
    function_ = function;
    Status status = Status::Error;
    if (!(state_ & allowedStates)) {
        log(Status::Error, LogStatusError, "illegal call sequence: %s is not allowed in state %s%s", function,
            stateName(state_), howToGoOn());
    } else {
        try {
            status = body();
        } catch (const std::exception& e) {
            fail("%s", e.what());
        } catch (...) {
            fail("unknown exception");
        }
    }
    // After an error only setting an FMU state, reset and freeing the instance (and getters
    // for debugging) are allowed.
    if (status == Status::Error) state_ = Error;
    if (status == Status::Fatal) state_ = Fatal;
    return status;
}

// Every state: functions that only log why they are not supported.
constexpr unsigned kAnyState = ~0u;

}  // namespace fmu
