#include "core/Instance.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <vector>

#include "core/StateFormat.h"

namespace fmu {

namespace {

// Tolerance of a step's communication point (importers' times wobble in the last digits).
constexpr double kTimeTolerance = 1e-9;

std::string formatMessage(const char* format, va_list args) {
    va_list copy;
    va_copy(copy, args);
    const int length = std::vsnprintf(nullptr, 0, format, copy);
    va_end(copy);
    if (length < 0) return format;
    std::string text(static_cast<std::size_t>(length) + 1, '\0');
    std::vsnprintf(&text[0], text.size(), format, args);
    text.resize(static_cast<std::size_t>(length));
    return text;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Names and logging

const char* stateName(State state) {
    switch (state) {
        case StartAndEnd: return "startAndEnd";
        case Instantiated: return "instantiated";
        case InitializationMode: return "initializationMode";
        case EventMode: return "eventMode";
        case ContinuousTimeMode: return "continuousTimeMode";
        case StepComplete: return "stepComplete";
        case StepInProgress: return "stepInProgress";
        case StepFailed: return "stepFailed";
        case StepCanceled: return "stepCanceled";
        case Terminated: return "terminated";
        case Error: return "error";
        case Fatal: return "fatal";
        case ConfigurationMode: return "configurationMode";
        case IntermediateUpdateMode: return "intermediateUpdateMode";
    }
    return "unknown";
}

const char* logCategoryName(LogCategory category) {
    switch (category) {
        case LogStatusError: return "logStatusError";
        case LogStatusWarning: return "logStatusWarning";
        case LogAll: return "logAll";
        case LogInfo: return "logInfo";
        case LogCategoryCount: break;
    }
    return "logAll";
}

void logWithoutInstance(const Logger& logger, const char* format, ...) {
    if (!logger) return;
    try {
        va_list args;
        va_start(args, format);
        const std::string message = formatMessage(format, args);
        va_end(args);
        logger(Status::Error, logCategoryName(LogStatusError), message.c_str());
    } catch (...) {
        // nothing sensible is left to do: the caller returns NULL
    }
}

void Instance::vlog(Status status, LogCategory category, const char* format, va_list args) {
    if (!logger_ || !logCategories_[category]) return;
    try {
        const std::string message = formatMessage(format, args);
        logger_(status, logCategoryName(category), message.c_str());
    } catch (...) {
        // out of memory while logging: drop the message, never throw into the importer
    }
}

void Instance::log(Status status, LogCategory category, const char* format, ...) {
    va_list args;
    va_start(args, format);
    vlog(status, category, format, args);
    va_end(args);
}

Status Instance::fail(const char* format, ...) {
    va_list args;
    va_start(args, format);
    std::string message;
    try {
        message = std::string(function_) + ": " + formatMessage(format, args);
    } catch (...) {}
    va_end(args);
    log(Status::Error, LogStatusError, "%s", message.c_str());
    return Status::Error;
}

// ---------------------------------------------------------------------------------------------
// Life cycle

Instance::Instance(Logger logger, bool loggingOn, ApiNames names)
    : logger_(std::move(logger)), names_(names), model_(createModel()) {
    model_->useVersion(names_.fmiVersion);
    // As the Reference FMUs: errors are logged unless switched off with setDebugLogging;
    // so are warnings (a computed result that is likely not what was meant); the call trace follows loggingOn.
    logCategories_[LogStatusError] = true;
    logCategories_[LogStatusWarning] = true;  // the model's plausibility warnings: results the user must see
    logCategories_[LogAll] = loggingOn;
    logCategories_[LogInfo] = loggingOn;
    attachTrace();
}

Instance::~Instance() = default;

void Instance::attachTrace() {
    const auto sink = [this](Status status, LogCategory category) {
        return [this, status, category](const std::string& message) {
            log(status, category, "%s: %s", function_, message.c_str());
        };
    };
    model_->trace = sink(Status::OK, LogAll);
    model_->inform = sink(Status::OK, LogInfo);
    model_->warn = sink(Status::Warning, LogStatusWarning);
    // The master's callbacks may call back into this instance (to get outputs, to set the inputs that
    // take intermediate values): they do so in IntermediateUpdateMode, and the running function's name
    // is restored for the messages after.
    const auto insideCallback = [this](const auto& call) {
        const State running = state_;
        const char* function = function_;
        state_ = IntermediateUpdateMode;
        const double result = call();
        const bool failed = state_ & (Error | Fatal);
        function_ = function;
        if (failed) throw std::runtime_error("a call of the master inside its intermediate update callback failed");
        state_ = running;
        return result;
    };
    model_->intermediateInputs = nullptr;
    if (intermediateInputs_)
        model_->intermediateInputs = [this, insideCallback](double time) {
            insideCallback([&] {
                inputsRequested_ = true;
                intermediateInputs_(startTime_ + time);
                inputsRequested_ = false;
                return 0.0;
            });
        };
    model_->intermediateUpdate = nullptr;
    if (intermediateUpdate_)
        model_->intermediateUpdate = [this, insideCallback](double time) {
            return insideCallback([&] { return intermediateUpdate_(startTime_ + time); }) - startTime_;
        };
}

void Instance::setIntermediateUpdate(std::function<double(double)> callback) {
    intermediateUpdate_ = std::move(callback);
    attachTrace();
}

void Instance::setIntermediateInputs(std::function<void(double)> callback) {
    intermediateInputs_ = std::move(callback);
    attachTrace();
}

const char* Instance::howToGoOn() const {
    const bool fmi3 = names_.fmiVersion == 3;
    if (state_ == Error)
        return fmi3 ? " (an earlier call failed, see its message: go on with fmi3Reset, fmi3SetFMUState to a "
                      "state saved before, or fmi3FreeInstance)"
                    : " (an earlier call failed, see its message: go on with fmi2Reset, fmi2SetFMUstate to a "
                      "state saved before, or fmi2FreeInstance)";
    if (state_ == Fatal)
        return fmi3 ? " (the instance is lost: fmi3FreeInstance)" : " (the instance is lost: fmi2FreeInstance)";
    return "";
}

Status Instance::setDebugLogging(bool on, std::size_t nCategories, const char* const categories[]) {
    bool next[LogCategoryCount];
    std::copy(logCategories_, logCategories_ + LogCategoryCount, next);
    if (nCategories == 0) {
        std::fill(next, next + LogCategoryCount, on);
    } else {
        if (!categories) return fail("argument categories[] must not be NULL");
        for (std::size_t i = 0; i < nCategories; ++i) {
            const char* name = categories[i];
            if (!name) return fail("categories[%zu] must not be NULL", i);
            if (std::strcmp(name, "logStatusError") == 0) {
                next[LogStatusError] = on;
            } else if (std::strcmp(name, "logStatusWarning") == 0) {
                next[LogStatusWarning] = on;
            } else if (std::strcmp(name, "logInfo") == 0) {
                next[LogInfo] = on;
            } else if (std::strcmp(name, "logAll") == 0) {
                std::fill(next, next + LogCategoryCount, on);  // "all" switches every category
            } else {
                return fail(
                    "unknown log category \"%s\"; the categories of this FMU are logStatusError, "
                    "logStatusWarning, logInfo and logAll",
                    name);
            }
        }
    }
    std::copy(next, next + LogCategoryCount, logCategories_);
    return Status::OK;
}

Status Instance::setupExperiment(double startTime, bool toleranceDefined, double tolerance, bool stopTimeDefined,
                                 double stopTime) {
    if (!std::isfinite(startTime)) return fail("startTime = %g is not a finite number", startTime);
    startTime_ = startTime;
    // function_: the front end's function that takes these arguments.
    // An importer's experiment tolerance (fmpy's relative_tolerance) changes nothing here: a Warning (an OK
    // message is hidden by most importers) that names the parameters that do set the accuracy.
    if (toleranceDefined)
        log(Status::Warning, LogStatusWarning,
            "%s: the experiment's tolerance = %g (relative_tolerance in fmpy) is ignored: the results do not "
            "change with it; the accuracy is set by %s",
            function_, tolerance, model_->accuracyParameters().c_str());
    if (stopTimeDefined) log(Status::OK, LogAll, "%s: stopTime %g", function_, stopTime);
    return Status::OK;
}

Status Instance::enterInitializationMode() {
    state_ = InitializationMode;
    return Status::OK;
}

Status Instance::exitInitializationMode() {
    if (!model_->built()) model_->build();  // throws ModelError naming a bad parameter
    state_ = StepComplete;
    return Status::OK;
}

Status Instance::terminate() {
    if (model_->built()) model_->terminate();
    state_ = Terminated;
    return Status::OK;
}

Status Instance::reset() {
    // The same as after instantiation: a fresh model with its default values.
    model_ = createModel();
    model_->useVersion(names_.fmiVersion);
    attachTrace();
    startTime_ = 0.0;
    state_ = Instantiated;
    return Status::OK;
}

double Instance::currentTime() const { return startTime_ + model_->time(); }

// ---------------------------------------------------------------------------------------------
// Variables

const Variable* Instance::variableFor(ValueReference vr, VariableType type) {
    const Variable* variable = model_->find(vr);
    if (!variable) {
        fail("unknown value reference %u", vr);
        return nullptr;
    }
    if (variable->type != type) {
        fail("value reference %u (%s) is a %s variable, not %s", vr, variable->name, typeName(variable->type),
             typeName(type));
        return nullptr;
    }
    return variable;
}

bool Instance::settable(const Variable& variable) {
    if (variable.causality == Causality::Output) {
        fail("%s (vr %u) is an output and cannot be set", variable.name, variable.vr);
        return false;
    }
    if (variable.causality == Causality::Parameter &&
        !(state_ & (Instantiated | ConfigurationMode | InitializationMode))) {
        log(Status::Error, LogStatusError,
            "illegal call sequence: %s of fixed parameter %s (vr %u) in state %s; fixed parameters can only be set "
            "before %s",
            function_, variable.name, variable.vr, stateName(state_), names_.exitInitializationMode);
        return false;
    }
    return true;
}

Status Instance::getValues(VariableType type, const ValueReference vr[], std::size_t nvr, double value[]) {
    if (nvr == 0) return Status::OK;
    if (!vr || !value) return fail("arguments vr[] and value[] must not be NULL");
    for (std::size_t i = 0; i < nvr; ++i) {
        const Variable* variable = variableFor(vr[i], type);
        if (!variable) return Status::Error;
        if (state_ == IntermediateUpdateMode && variable->causality != Causality::Output)
            return fail(
                "%s (vr %u) is not an intermediate update variable (allowed inside the intermediate update "
                "callback: the outputs)",
                variable->name, variable->vr);
        // An output read in initialization mode: build what the parameters describe now.
        if (variable->causality == Causality::Output && state_ == InitializationMode && !model_->built())
            model_->build();
        value[i] = model_->get(*variable);
    }
    return Status::OK;
}

Status Instance::setValues(VariableType type, const ValueReference vr[], std::size_t nvr, const double value[]) {
    if (nvr == 0) return Status::OK;
    if (!vr || !value) return fail("arguments vr[] and value[] must not be NULL");
    const bool intermediate = state_ == IntermediateUpdateMode;
    for (std::size_t i = 0; i < nvr; ++i) {
        const Variable* variable = variableFor(vr[i], type);
        if (!variable || !settable(*variable)) return Status::Error;
        if (intermediate && !(inputsRequested_ && model_->takesIntermediateValue(*variable))) {
            std::string inputs;
            for (const Variable& v : model_->variables())
                if (model_->takesIntermediateValue(v)) inputs += (inputs.empty() ? "" : ", ") + std::string(v.name);
            return fail(
                "%s (vr %u) cannot be set inside the intermediate update callback%s (settable there: %s, and only "
                "when the FMU asks, intermediateVariableSetRequested = true)",
                variable->name, variable->vr, inputsRequested_ ? "" : " now: the FMU did not request inputs",
                inputs.empty() ? "nothing" : inputs.c_str());
        }
        if (!std::isfinite(value[i]))
            return fail("%s (vr %u) = %g rejected: NaN and Inf are not allowed", variable->name, variable->vr,
                        value[i]);
        if (variable->causality == Causality::Input && variable->hasRange() &&
            !(value[i] >= variable->min && value[i] <= variable->max))
            return fail("%s = %.17g out of range (allowed: %.17g <= %s <= %.17g)", variable->name, value[i],
                        variable->min, variable->name, variable->max);
        if (variable->enumeration &&
            !(std::floor(value[i]) == value[i] && variable->enumeration->contains(int(value[i]))))
            return fail("%s = %.17g is none of its items (%s)", variable->name, value[i],
                        variable->enumeration->itemList().c_str());
        if (intermediate) {  // the value at the grid point the model is about to step to
            model_->setIntermediate(*variable, value[i]);
            continue;
        }
        model_->set(*variable, value[i]);
        // Before initialization ends, what was built (an output was read) came from the old value.
        if (variable->shapesInitialState && (state_ & (Instantiated | ConfigurationMode | InitializationMode)) &&
            model_->built())
            model_->drop();
    }
    return Status::OK;
}

// ---------------------------------------------------------------------------------------------
// Co-simulation

Status Instance::setInputDerivatives(const ValueReference vr[], std::size_t nvr, const int order[],
                                     const double value[]) {
    if (nvr == 0) return Status::OK;
    if (!vr || !order || !value) return fail("arguments vr[], order[] and value[] must not be NULL");
    for (std::size_t i = 0; i < nvr; ++i) {
        const Variable* variable = model_->find(vr[i]);
        if (!variable || variable->causality != Causality::Input || !variable->hasDerivatives) {
            std::string inputs;
            for (const Variable& v : model_->variables())
                if (v.causality == Causality::Input && v.hasDerivatives)
                    inputs += (inputs.empty() ? "" : ", ") + std::string(v.name) + " (vr " + std::to_string(v.vr) + ")";
            return fail("value reference %u is not a Real input; input derivatives exist for %s", vr[i],
                        inputs.empty() ? "no variable" : inputs.c_str());
        }
        if (order[i] != 1 && order[i] != 2)
            return fail("derivative order %d of %s is not supported; orders 1 and 2 are", order[i], variable->name);
        if (!std::isfinite(value[i]))
            return fail("derivative of order %d of %s = %g rejected: NaN and Inf are not allowed", order[i],
                        variable->name, value[i]);
        model_->setInputDerivative(*variable, order[i], value[i]);
    }
    return Status::OK;
}

Status Instance::getOutputDerivatives(const ValueReference vr[], std::size_t nvr, const int order[], double value[]) {
    const int maxOrder = model_->info().maxOutputDerivativeOrder;
    if (maxOrder == 0) return fail("not supported (maxOutputDerivativeOrder=\"0\")");
    if (nvr == 0) return Status::OK;
    if (!vr || !order || !value) return fail("arguments vr[], order[] and value[] must not be NULL");
    for (std::size_t i = 0; i < nvr; ++i) {
        const Variable* variable = model_->find(vr[i]);
        if (!variable || variable->causality != Causality::Output || !variable->hasDerivatives)
            return fail("value reference %u is not a Real output with derivatives", vr[i]);
        if (order[i] < 1 || order[i] > maxOrder)
            return fail("derivative order %d of %s is not supported (1 to %d)", order[i], variable->name, maxOrder);
        value[i] = model_->getOutputDerivative(*variable, order[i]);
    }
    return Status::OK;
}

Status Instance::doStep(double t, double h, bool stopAtEvent, bool* endedAtEvent) {
    if (endedAtEvent) *endedAtEvent = false;
    const double now = currentTime();
    if (!std::isfinite(t) || std::fabs(t - now) > kTimeTolerance * std::max(1.0, std::fabs(t)))
        return fail(
            "currentCommunicationPoint = %.17g differs from the FMU's time %.17g; each step must start where "
            "the previous one ended (relative tolerance %g)",
            t, now, kTimeTolerance);
    if (!std::isfinite(h) || !(h > 0)) return fail("communicationStepSize h = %.17g rejected: it must be > 0", h);
    if (stopAtEvent && model_->hasEvents()) {
        const bool atEvent = model_->doStepUntilEvent(t, h);
        if (endedAtEvent) *endedAtEvent = atEvent;
    } else {
        model_->doStep(t, h);
    }
    return Status::OK;
}

}  // namespace fmu
