#include "PlateInstance.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <vector>

#include "PlateImpactGuid.h"  // generated at build time: PLATEIMPACT_GUID

namespace plateimpact {

namespace {

// Allowed states of each function group (FMI 2.0.4, table in section 4.2.4).
constexpr unsigned kFreeInstanceStates = Instantiated | InitializationMode | StepComplete | StepFailed |
                                         StepCanceled | Terminated | Error;
constexpr unsigned kDebugLoggingStates = kFreeInstanceStates | StepInProgress;
constexpr unsigned kResetStates = kFreeInstanceStates;
constexpr unsigned kFMUstateStates = kFreeInstanceStates;
constexpr unsigned kGetStates = InitializationMode | StepComplete | StepFailed | StepCanceled | Terminated | Error;
constexpr unsigned kSetStates = Instantiated | InitializationMode | StepComplete;
constexpr unsigned kInputDerivativeStates = Instantiated | InitializationMode | StepComplete;
constexpr unsigned kOutputDerivativeStates = StepComplete | StepFailed | StepCanceled | Terminated | Error;
constexpr unsigned kStatusStates = StepComplete | StepInProgress | StepFailed | Terminated;
constexpr unsigned kAnyState = ~0u;

// Tolerances of fmi2DoStep (importers' communication points wobble in the last digits).
constexpr double kTimeTolerance = 1e-9;
constexpr double kStepMultipleTolerance = 1e-9;

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

// The importer may treat the message as a printf format (FMI 2.0, fmi2CallbackLogger).
std::string escapePercent(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (char ch : text) {
        out += ch;
        if (ch == '%') out += '%';
    }
    return out;
}

bool sameParameters(const plate::PlateParameters& a, const plate::PlateParameters& b) {
    return a.length == b.length && a.width == b.width && a.thickness == b.thickness &&
           a.youngsModulus == b.youngsModulus && a.poissonRatio == b.poissonRatio &&
           a.density == b.density && a.nx == b.nx && a.ny == b.ny && a.element == b.element &&
           a.obstacleLower == b.obstacleLower && a.obstacleUpper == b.obstacleUpper &&
           a.obstacleLowerEnabled == b.obstacleLowerEnabled &&
           a.obstacleUpperEnabled == b.obstacleUpperEnabled && a.dt == b.dt && a.beta == b.beta &&
           a.initialLoad == b.initialLoad && a.modes == b.modes;
}

bool isStateOfSnapshot(double code) {
    for (unsigned s : {unsigned(Instantiated), unsigned(InitializationMode), unsigned(StepComplete),
                       unsigned(StepFailed), unsigned(StepCanceled), unsigned(Terminated), unsigned(Error)}) {
        if (code == double(s)) return true;
    }
    return false;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// FMU states (fmi2GetFMUstate & co.)

struct Snapshot {
    static constexpr std::uint64_t kTag = 0x506c617465536e70ULL;  // "PlateSnp": guards the cast
    std::uint64_t tag = kTag;
    State state = Instantiated;
    double startTime = 0.0;
    ModelValues values;
    bool hasSimulation = false;
    double simulationBase0 = 0.0;
    std::vector<double> simulationState;  // PlateSimulation::saveState()
};

namespace {

Snapshot* asSnapshot(fmi2FMUstate state) {
    auto* snapshot = static_cast<Snapshot*>(state);
    return snapshot && snapshot->tag == Snapshot::kTag ? snapshot : nullptr;
}

// Serialized format (native byte order, this FMU's own platform only):
//   bytes  0..7   magic "PLATEIMP"
//   bytes  8..11  uint32 format version
//   bytes 12..15  uint32 length of the GUID
//   bytes 16..63  GUID of the FMU build that wrote it (NUL padded)
//   bytes 64..71  uint64 number n of doubles that follow
//   bytes 72..    n doubles: the instance fields in the order of encodeSnapshot, then the
//                 PlateSimulation state.
constexpr char kMagic[8] = {'P', 'L', 'A', 'T', 'E', 'I', 'M', 'P'};
// Version 2: the inputs carry their mode, whether derivatives were given and their history.
constexpr std::uint32_t kFormatVersion = 2;
constexpr std::size_t kGuidField = 48;
constexpr std::size_t kHeaderBytes = 8 + 4 + 4 + kGuidField + 8;

class DecodeError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class Reader {
public:
    explicit Reader(const std::vector<double>& data) : data_(data) {}
    double real(const char* what) {
        if (next_ >= data_.size()) throw DecodeError(std::string("data end before ") + what);
        return data_[next_++];
    }
    double finite(const char* what) {
        const double x = real(what);
        if (!std::isfinite(x)) throw DecodeError(std::string(what) + " is not finite");
        return x;
    }
    long long integer(const char* what, double lo, double hi) {
        const double x = real(what);
        if (!(x >= lo && x <= hi) || std::floor(x) != x)
            throw DecodeError(std::string(what) + " is not an integer in range");
        return static_cast<long long>(x);
    }
    bool boolean(const char* what) { return integer(what, 0, 1) != 0; }
    std::size_t remaining() const { return data_.size() - next_; }
    std::vector<double> rest() const {
        return std::vector<double>(data_.begin() + static_cast<std::ptrdiff_t>(next_), data_.end());
    }

private:
    const std::vector<double>& data_;
    std::size_t next_ = 0;
};

void encodeInput(std::vector<double>& out, const InputPort& port) {
    out.insert(out.end(), {port.signal.value, port.signal.d1, port.signal.d2, port.derivativesGiven ? 1.0 : 0.0,
                           double(static_cast<int>(port.mode))});
    port.history.serialize(out);
}

void decodeInput(Reader& in, InputPort& port, const char* what) {
    port.signal.value = in.finite(what);
    port.signal.d1 = in.finite(what);
    port.signal.d2 = in.finite(what);
    port.derivativesGiven = in.boolean(what);
    port.mode = static_cast<plate::InputMode>(in.integer(what, 1, 3));
    double history[plate::InputHistory::kSerializedSize];
    for (double& x : history) x = in.real(what);
    try {
        port.history = plate::InputHistory::deserialize(history);
    } catch (const std::invalid_argument& e) {
        throw DecodeError(std::string(what) + ": " + e.what());
    }
}

std::vector<double> encodeSnapshot(const Snapshot& s) {
    const plate::PlateParameters& p = s.values.parameters;
    const plate::PlateOutputs& o = s.values.outputs;
    std::vector<double> out = {
        double(unsigned(s.state)), s.startTime,
        p.length, p.width, p.thickness, p.youngsModulus, p.poissonRatio, p.density,
        double(p.nx), double(p.ny), p.element == plate::ElementType::Fvs ? 2.0 : 1.0,
        p.obstacleLower, p.obstacleUpper, p.obstacleLowerEnabled ? 1.0 : 0.0,
        p.obstacleUpperEnabled ? 1.0 : 0.0, p.dt, p.beta, p.initialLoad, double(p.modes)};
    encodeInput(out, s.values.baseDisplacement);
    encodeInput(out, s.values.load);
    out.insert(out.end(), {o.corner1, o.corner2, o.freeEdgeMid, o.energy, o.energyDissipated,
                           o.energyInput, double(o.contactVertices), o.maxKktResidual,
                           double(o.qpIterations), double(o.qpIterationsTotal), double(o.qpIterationsMax)});
    out.insert(out.end(), {s.hasSimulation ? 1.0 : 0.0, s.simulationBase0,
                           double(s.simulationState.size())});
    out.insert(out.end(), s.simulationState.begin(), s.simulationState.end());
    return out;
}

void decodeSnapshot(const std::vector<double>& data, Snapshot& s) {
    Reader in(data);
    const double code = in.real("state");
    if (!isStateOfSnapshot(code)) throw DecodeError("unknown state-machine state");
    s.state = static_cast<State>(static_cast<unsigned>(code));
    s.startTime = in.finite("start time");
    plate::PlateParameters& p = s.values.parameters;
    constexpr double kIntMin = -2147483648.0, kIntMax = 2147483647.0;
    p.length = in.finite("length");
    p.width = in.finite("width");
    p.thickness = in.finite("thickness");
    p.youngsModulus = in.finite("youngs_modulus");
    p.poissonRatio = in.finite("poisson_ratio");
    p.density = in.finite("density");
    p.nx = int(in.integer("nx", kIntMin, kIntMax));
    p.ny = int(in.integer("ny", kIntMin, kIntMax));
    p.element = in.integer("element", 1, 2) == 2 ? plate::ElementType::Fvs : plate::ElementType::Argyris;
    p.obstacleLower = in.finite("obstacle_lower");
    p.obstacleUpper = in.finite("obstacle_upper");
    p.obstacleLowerEnabled = in.boolean("obstacle_lower_enabled");
    p.obstacleUpperEnabled = in.boolean("obstacle_upper_enabled");
    p.dt = in.finite("dt");
    p.beta = in.finite("beta");
    p.initialLoad = in.finite("initial_load");
    p.modes = int(in.integer("modes", kIntMin, kIntMax));
    decodeInput(in, s.values.baseDisplacement, "base_displacement");
    decodeInput(in, s.values.load, "load");
    plate::PlateOutputs& o = s.values.outputs;
    o.corner1 = in.real("corner_1");
    o.corner2 = in.real("corner_2");
    o.freeEdgeMid = in.real("free_edge_mid");
    o.energy = in.real("energy");
    o.energyDissipated = in.real("energy_dissipated");
    o.energyInput = in.real("energy_input");
    o.contactVertices = int(in.integer("contact_vertices", kIntMin, kIntMax));
    o.maxKktResidual = in.real("qp_kkt_residual_max");
    o.qpIterations = int(in.integer("qp iterations", kIntMin, kIntMax));
    o.qpIterationsTotal = in.integer("qp_iterations_total", -9.0e15, 9.0e15);
    o.qpIterationsMax = int(in.integer("qp_iterations_max", kIntMin, kIntMax));
    s.hasSimulation = in.boolean("simulation flag");
    s.simulationBase0 = in.finite("initial base displacement");
    const long long count = in.integer("simulation state size", 0, 9.0e15);
    if (static_cast<unsigned long long>(count) != in.remaining())
        throw DecodeError("simulation state size does not match the data");
    if (!s.hasSimulation && count != 0) throw DecodeError("simulation state without a simulation");
    const unsigned needsSimulation = StepComplete | StepFailed | StepCanceled | Terminated;
    if ((s.state & needsSimulation) && !s.hasSimulation)
        throw DecodeError("state after initialization without simulation data");
    s.simulationState = in.rest();
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
    }
    return "unknown";
}

const char* logCategoryName(LogCategory category) {
    switch (category) {
        case LogStatusError: return "logStatusError";
        case LogStatusWarning: return "logStatusWarning";
        case LogAll: return "logAll";
        case LogCategoryCount: break;
    }
    return "logAll";
}

const char* buildGuid() { return PLATEIMPACT_GUID; }

void logWithoutInstance(const fmi2CallbackFunctions* functions, fmi2String instanceName,
                        const char* format, ...) {
    if (!functions || !functions->logger) return;
    try {
        va_list args;
        va_start(args, format);
        const std::string message = escapePercent(formatMessage(format, args));
        va_end(args);
        functions->logger(functions->componentEnvironment, instanceName ? instanceName : "",
                          fmi2Error, logCategoryName(LogStatusError), message.c_str());
    } catch (...) {
        // nothing sensible is left to do: the caller returns NULL
    }
}

void PlateInstance::vlog(fmi2Status status, LogCategory category, const char* format, va_list args) {
    if (!callbacks_.logger || !logCategories_[category]) return;
    try {
        const std::string message = escapePercent(formatMessage(format, args));
        callbacks_.logger(callbacks_.componentEnvironment, instanceName_.c_str(), status,
                          logCategoryName(category), message.c_str());
    } catch (...) {
        // out of memory while logging: drop the message, never throw into the importer
    }
}

void PlateInstance::log(fmi2Status status, LogCategory category, const char* format, ...) {
    va_list args;
    va_start(args, format);
    vlog(status, category, format, args);
    va_end(args);
}

fmi2Status PlateInstance::fail(const char* format, ...) {
    va_list args;
    va_start(args, format);
    vlog(fmi2Error, LogStatusError, format, args);
    va_end(args);
    return fmi2Error;
}

template <class Body>
fmi2Status PlateInstance::call(const char* function, unsigned allowedStates, Body&& body) {
    fmi2Status status = fmi2Error;
    if (!(state_ & allowedStates)) {
        log(fmi2Error, LogStatusError, "illegal call sequence: %s is not allowed in state %s", function,
            stateName(state_));
    } else {
        try {
            status = body();
        } catch (const std::exception& e) {
            log(fmi2Error, LogStatusError, "%s: %s", function, e.what());
            status = fmi2Error;
        } catch (...) {
            log(fmi2Error, LogStatusError, "%s: unknown exception", function);
            status = fmi2Error;
        }
    }
    // FMI 2.0: after fmi2Error only fmi2SetFMUstate, fmi2Reset, fmi2FreeInstance (and getters
    // for debugging) are allowed.
    if (status == fmi2Error) state_ = Error;
    if (status == fmi2Fatal) state_ = Fatal;
    return status;
}

// ---------------------------------------------------------------------------------------------
// Life cycle

PlateInstance::PlateInstance(std::string instanceName, const fmi2CallbackFunctions& callbacks, bool loggingOn)
    : instanceName_(std::move(instanceName)), callbacks_(callbacks) {
    // As the Reference FMUs: errors are logged unless switched off with fmi2SetDebugLogging;
    // warnings and the call trace follow loggingOn.
    logCategories_[LogStatusError] = true;
    logCategories_[LogStatusWarning] = loggingOn;
    logCategories_[LogAll] = loggingOn;
    log(fmi2OK, LogAll, "fmi2Instantiate: instance \"%s\" of PlateImpact (GUID %s)", instanceName_.c_str(),
        buildGuid());
}

PlateInstance::~PlateInstance() = default;

void PlateInstance::logFreeInstance() { log(fmi2OK, LogAll, "fmi2FreeInstance"); }

fmi2Status PlateInstance::setDebugLogging(fmi2Boolean loggingOn, size_t nCategories, const fmi2String categories[]) {
    return call("fmi2SetDebugLogging", kDebugLoggingStates, [&]() -> fmi2Status {
        const bool on = loggingOn != fmi2False;
        bool next[LogCategoryCount];
        std::copy(logCategories_, logCategories_ + LogCategoryCount, next);
        if (nCategories == 0) {
            std::fill(next, next + LogCategoryCount, on);
        } else {
            if (!categories) return fail("fmi2SetDebugLogging: argument categories[] must not be NULL");
            for (size_t i = 0; i < nCategories; ++i) {
                const char* name = categories[i];
                if (!name) return fail("fmi2SetDebugLogging: categories[%zu] must not be NULL", i);
                if (std::strcmp(name, "logStatusError") == 0) {
                    next[LogStatusError] = on;
                } else if (std::strcmp(name, "logStatusWarning") == 0) {
                    next[LogStatusWarning] = on;
                } else if (std::strcmp(name, "logAll") == 0) {
                    std::fill(next, next + LogCategoryCount, on);  // "all" switches every category
                } else {
                    return fail("fmi2SetDebugLogging: unknown log category \"%s\"; the categories of this "
                                "FMU are logStatusError, logStatusWarning and logAll", name);
                }
            }
        }
        std::copy(next, next + LogCategoryCount, logCategories_);
        return fmi2OK;
    });
}

fmi2Status PlateInstance::setupExperiment(fmi2Boolean toleranceDefined, fmi2Real tolerance, fmi2Real startTime,
                                          fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
    return call("fmi2SetupExperiment", Instantiated, [&]() -> fmi2Status {
        if (!std::isfinite(startTime))
            return fail("fmi2SetupExperiment: startTime = %g is not a finite number", startTime);
        startTime_ = startTime;
        if (toleranceDefined)
            log(fmi2OK, LogAll, "fmi2SetupExperiment: tolerance %g ignored (fixed time step dt)", tolerance);
        if (stopTimeDefined) log(fmi2OK, LogAll, "fmi2SetupExperiment: stopTime %g", stopTime);
        return fmi2OK;
    });
}

fmi2Status PlateInstance::enterInitializationMode() {
    return call("fmi2EnterInitializationMode", Instantiated, [&]() -> fmi2Status {
        state_ = InitializationMode;
        return fmi2OK;
    });
}

void PlateInstance::ensureSimulation(const char* function) {
    if (simulation_) return;
    // A plate::ParameterError names the parameter, its value and the allowed range; call()
    // logs it (category logStatusError) and returns fmi2Error.
    simulation_ = std::make_unique<plate::PlateSimulation>(values_.parameters,
                                                         values_.baseDisplacement.signal.value);
    simulationBase0_ = values_.baseDisplacement.signal.value;
    refreshOutputs();
    log(fmi2OK, LogAll, "%s: simulation built (nx = %d, ny = %d, dt = %g s, beta = %g, modes = %d)", function,
        values_.parameters.nx, values_.parameters.ny, values_.parameters.dt, values_.parameters.beta,
        values_.parameters.modes);
}

fmi2Status PlateInstance::exitInitializationMode() {
    return call("fmi2ExitInitializationMode", InitializationMode, [&]() -> fmi2Status {
        ensureSimulation("fmi2ExitInitializationMode");
        state_ = StepComplete;
        return fmi2OK;
    });
}

fmi2Status PlateInstance::terminate() {
    return call("fmi2Terminate", StepComplete | StepFailed, [&]() -> fmi2Status {
        state_ = Terminated;
        return fmi2OK;
    });
}

fmi2Status PlateInstance::reset() {
    return call("fmi2Reset", kResetStates, [&]() -> fmi2Status {
        // Same values as after fmi2Instantiate; the next fmi2ExitInitializationMode rebuilds.
        simulation_.reset();
        values_ = ModelValues{};
        startTime_ = 0.0;
        simulationBase0_ = 0.0;
        state_ = Instantiated;
        return fmi2OK;
    });
}

double PlateInstance::currentTime() const { return startTime_ + (simulation_ ? simulation_->time() : 0.0); }

void PlateInstance::refreshOutputs() { values_.outputs = simulation_ ? simulation_->outputs() : plate::PlateOutputs{}; }

// ---------------------------------------------------------------------------------------------
// Variables

const Variable* PlateInstance::variableFor(const char* function, fmi2ValueReference vr, bool integerTypes,
                                           VariableType type) {
    const Variable* variable = findVariable(vr);
    if (!variable) {
        fail("%s: unknown value reference %u", function, vr);
        return nullptr;
    }
    const bool typeOk = variable->type == type || (integerTypes && variable->type == VariableType::Enumeration);
    if (!typeOk) {
        fail("%s: value reference %u (%s) is a %s variable, not %s", function, vr, variable->name,
             typeName(variable->type), typeName(type));
        return nullptr;
    }
    return variable;
}

fmi2Status PlateInstance::checkSettable(const char* function, const Variable& variable) {
    if (variable.causality == Causality::Output)
        return fail("%s: %s (vr %u) is an output and cannot be set", function, variable.name, variable.vr);
    if (variable.causality == Causality::Parameter && !(state_ & (Instantiated | InitializationMode)))
        return fail("illegal call sequence: %s of fixed parameter %s (vr %u) in state %s; fixed parameters "
                    "can only be set before fmi2ExitInitializationMode",
                    function, variable.name, variable.vr, stateName(state_));
    return fmi2OK;
}

void PlateInstance::afterSet(const Variable& variable) {
    // Before initialization ends, the simulation (if an output was already read) was built
    // from the old value: drop it, fmi2ExitInitializationMode builds it again.
    if (variable.shapesInitialState && (state_ & (Instantiated | InitializationMode)) && simulation_) {
        simulation_.reset();
        refreshOutputs();
    }
}

bool PlateInstance::needsOutputs(const fmi2ValueReference vr[], size_t nvr) const {
    for (size_t i = 0; i < nvr; ++i) {
        const Variable* variable = findVariable(vr[i]);
        if (variable && variable->causality == Causality::Output) return true;
    }
    return false;
}

fmi2Status PlateInstance::getReal(const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]) {
    return call("fmi2GetReal", kGetStates, [&]() -> fmi2Status {
        if (nvr == 0) return fmi2OK;
        if (!vr || !value) return fail("fmi2GetReal: arguments vr[] and value[] must not be NULL");
        if (state_ == InitializationMode && needsOutputs(vr, nvr)) ensureSimulation("fmi2GetReal");
        for (size_t i = 0; i < nvr; ++i) {
            const Variable* variable = variableFor("fmi2GetReal", vr[i], false, VariableType::Real);
            if (!variable) return fmi2Error;
            value[i] = variable->getReal(values_);
        }
        return fmi2OK;
    });
}

fmi2Status PlateInstance::getInteger(const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[]) {
    return call("fmi2GetInteger", kGetStates, [&]() -> fmi2Status {
        if (nvr == 0) return fmi2OK;
        if (!vr || !value) return fail("fmi2GetInteger: arguments vr[] and value[] must not be NULL");
        if (state_ == InitializationMode && needsOutputs(vr, nvr)) ensureSimulation("fmi2GetInteger");
        for (size_t i = 0; i < nvr; ++i) {
            const Variable* variable = variableFor("fmi2GetInteger", vr[i], true, VariableType::Integer);
            if (!variable) return fmi2Error;
            value[i] = variable->getInteger(values_);
        }
        return fmi2OK;
    });
}

fmi2Status PlateInstance::getBoolean(const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[]) {
    return call("fmi2GetBoolean", kGetStates, [&]() -> fmi2Status {
        if (nvr == 0) return fmi2OK;
        if (!vr || !value) return fail("fmi2GetBoolean: arguments vr[] and value[] must not be NULL");
        for (size_t i = 0; i < nvr; ++i) {
            const Variable* variable = variableFor("fmi2GetBoolean", vr[i], false, VariableType::Boolean);
            if (!variable) return fmi2Error;
            value[i] = variable->getBoolean(values_) ? fmi2True : fmi2False;
        }
        return fmi2OK;
    });
}

fmi2Status PlateInstance::getString(const fmi2ValueReference vr[], size_t nvr, fmi2String[]) {
    return call("fmi2GetString", kGetStates, [&]() -> fmi2Status {
        if (nvr == 0) return fmi2OK;
        return fail("fmi2GetString: this FMU has no String variables (value reference %u)", vr ? vr[0] : 0u);
    });
}

fmi2Status PlateInstance::setReal(const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]) {
    return call("fmi2SetReal", kSetStates, [&]() -> fmi2Status {
        if (nvr == 0) return fmi2OK;
        if (!vr || !value) return fail("fmi2SetReal: arguments vr[] and value[] must not be NULL");
        for (size_t i = 0; i < nvr; ++i) {
            const Variable* variable = variableFor("fmi2SetReal", vr[i], false, VariableType::Real);
            if (!variable || checkSettable("fmi2SetReal", *variable) != fmi2OK) return fmi2Error;
            if (!std::isfinite(value[i]))
                return fail("fmi2SetReal: %s (vr %u) = %g rejected: NaN and Inf are not allowed", variable->name,
                            variable->vr, value[i]);
            variable->setReal(values_, value[i]);
            afterSet(*variable);
        }
        return fmi2OK;
    });
}

fmi2Status PlateInstance::setInteger(const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[]) {
    return call("fmi2SetInteger", kSetStates, [&]() -> fmi2Status {
        if (nvr == 0) return fmi2OK;
        if (!vr || !value) return fail("fmi2SetInteger: arguments vr[] and value[] must not be NULL");
        for (size_t i = 0; i < nvr; ++i) {
            const Variable* variable = variableFor("fmi2SetInteger", vr[i], true, VariableType::Integer);
            if (!variable || checkSettable("fmi2SetInteger", *variable) != fmi2OK) return fmi2Error;
            variable->setInteger(values_, value[i]);  // throws VariableError for a bad enumeration item
            afterSet(*variable);
        }
        return fmi2OK;
    });
}

fmi2Status PlateInstance::setBoolean(const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[]) {
    return call("fmi2SetBoolean", kSetStates, [&]() -> fmi2Status {
        if (nvr == 0) return fmi2OK;
        if (!vr || !value) return fail("fmi2SetBoolean: arguments vr[] and value[] must not be NULL");
        for (size_t i = 0; i < nvr; ++i) {
            const Variable* variable = variableFor("fmi2SetBoolean", vr[i], false, VariableType::Boolean);
            if (!variable || checkSettable("fmi2SetBoolean", *variable) != fmi2OK) return fmi2Error;
            variable->setBoolean(values_, value[i] != fmi2False);
            afterSet(*variable);
        }
        return fmi2OK;
    });
}

fmi2Status PlateInstance::setString(const fmi2ValueReference vr[], size_t nvr, const fmi2String[]) {
    return call("fmi2SetString", kSetStates, [&]() -> fmi2Status {
        if (nvr == 0) return fmi2OK;
        return fail("fmi2SetString: this FMU has no String variables (value reference %u)", vr ? vr[0] : 0u);
    });
}

// ---------------------------------------------------------------------------------------------
// FMU states

void PlateInstance::capture(Snapshot& snapshot) const {
    snapshot.state = state_;
    snapshot.startTime = startTime_;
    snapshot.values = values_;
    snapshot.hasSimulation = simulation_ != nullptr;
    snapshot.simulationBase0 = simulationBase0_;
    snapshot.simulationState = simulation_ ? simulation_->saveState() : std::vector<double>{};
}

void PlateInstance::restore(const Snapshot& snapshot) {
    if (snapshot.hasSimulation) {
        const bool reuse = simulation_ && simulationBase0_ == snapshot.simulationBase0 &&
                           sameParameters(simulation_->parameters(), snapshot.values.parameters);
        if (reuse) {
            simulation_->restoreState(snapshot.simulationState);
        } else {
            // Another discretization: build one for the snapshot's parameters, then load its state.
            auto simulation = std::make_unique<plate::PlateSimulation>(snapshot.values.parameters,
                                                                       snapshot.simulationBase0);
            simulation->restoreState(snapshot.simulationState);
            simulation_ = std::move(simulation);
        }
    } else {
        simulation_.reset();
    }
    state_ = snapshot.state;
    startTime_ = snapshot.startTime;
    values_ = snapshot.values;
    simulationBase0_ = snapshot.simulationBase0;
    if (simulation_) refreshOutputs();
}

fmi2Status PlateInstance::getFMUstate(fmi2FMUstate* state) {
    return call("fmi2GetFMUstate", kFMUstateStates, [&]() -> fmi2Status {
        if (!state) return fail("fmi2GetFMUstate: argument FMUstate must not be NULL");
        if (*state) {  // reuse a state this FMU handed out before
            Snapshot* previous = asSnapshot(*state);
            if (!previous) return fail("fmi2GetFMUstate: *FMUstate is not an FMU state of PlateImpact");
            capture(*previous);
            return fmi2OK;
        }
        auto snapshot = std::make_unique<Snapshot>();
        capture(*snapshot);
        *state = snapshot.release();  // owned by the importer until fmi2FreeFMUstate
        return fmi2OK;
    });
}

fmi2Status PlateInstance::setFMUstate(fmi2FMUstate state) {
    return call("fmi2SetFMUstate", kFMUstateStates, [&]() -> fmi2Status {
        const Snapshot* snapshot = asSnapshot(state);
        if (!snapshot) return fail("fmi2SetFMUstate: FMUstate is NULL or not an FMU state of PlateImpact");
        restore(*snapshot);
        return fmi2OK;
    });
}

fmi2Status PlateInstance::freeFMUstate(fmi2FMUstate* state) {
    return call("fmi2FreeFMUstate", kFMUstateStates, [&]() -> fmi2Status {
        if (!state) return fail("fmi2FreeFMUstate: argument FMUstate must not be NULL");
        if (!*state) return fmi2OK;
        Snapshot* snapshot = asSnapshot(*state);
        if (!snapshot) return fail("fmi2FreeFMUstate: *FMUstate is not an FMU state of PlateImpact");
        std::unique_ptr<Snapshot> owned(snapshot);  // takes ownership back and frees it
        *state = nullptr;
        return fmi2OK;
    });
}

fmi2Status PlateInstance::serializedFMUstateSize(fmi2FMUstate state, size_t* size) {
    return call("fmi2SerializedFMUstateSize", kFMUstateStates, [&]() -> fmi2Status {
        const Snapshot* snapshot = asSnapshot(state);
        if (!snapshot) return fail("fmi2SerializedFMUstateSize: FMUstate is NULL or not an FMU state of PlateImpact");
        if (!size) return fail("fmi2SerializedFMUstateSize: argument size must not be NULL");
        *size = kHeaderBytes + sizeof(double) * encodeSnapshot(*snapshot).size();
        return fmi2OK;
    });
}

fmi2Status PlateInstance::serializeFMUstate(fmi2FMUstate state, fmi2Byte serialized[], size_t size) {
    return call("fmi2SerializeFMUstate", kFMUstateStates, [&]() -> fmi2Status {
        const Snapshot* snapshot = asSnapshot(state);
        if (!snapshot) return fail("fmi2SerializeFMUstate: FMUstate is NULL or not an FMU state of PlateImpact");
        if (!serialized) return fail("fmi2SerializeFMUstate: argument serializedState must not be NULL");
        const std::vector<double> data = encodeSnapshot(*snapshot);
        const std::size_t expected = kHeaderBytes + sizeof(double) * data.size();
        if (size != expected)
            return fail("fmi2SerializeFMUstate: size = %zu, but the state needs %zu bytes "
                        "(fmi2SerializedFMUstateSize)", size, expected);
        const std::string guid = buildGuid();
        if (guid.size() > kGuidField) return fail("fmi2SerializeFMUstate: GUID too long");
        const std::uint32_t version = kFormatVersion;
        const std::uint32_t guidLength = static_cast<std::uint32_t>(guid.size());
        const std::uint64_t count = data.size();
        std::memset(serialized, 0, kHeaderBytes);
        std::memcpy(serialized, kMagic, 8);
        std::memcpy(serialized + 8, &version, 4);
        std::memcpy(serialized + 12, &guidLength, 4);
        std::memcpy(serialized + 16, guid.data(), guid.size());
        std::memcpy(serialized + 16 + kGuidField, &count, 8);
        if (!data.empty()) std::memcpy(serialized + kHeaderBytes, data.data(), sizeof(double) * data.size());
        return fmi2OK;
    });
}

fmi2Status PlateInstance::deSerializeFMUstate(const fmi2Byte serialized[], size_t size, fmi2FMUstate* state) {
    return call("fmi2DeSerializeFMUstate", kFMUstateStates, [&]() -> fmi2Status {
        if (!state) return fail("fmi2DeSerializeFMUstate: argument FMUstate must not be NULL");
        if (!serialized && size > 0) return fail("fmi2DeSerializeFMUstate: argument serializedState must not be NULL");
        if (size < kHeaderBytes)
            return fail("fmi2DeSerializeFMUstate: corrupt serialized state: %zu bytes, shorter than the "
                        "%zu-byte header", size, kHeaderBytes);
        if (std::memcmp(serialized, kMagic, 8) != 0)
            return fail("fmi2DeSerializeFMUstate: corrupt serialized state: wrong magic (not a PlateImpact FMU state)");
        std::uint32_t version = 0, guidLength = 0;
        std::uint64_t count = 0;
        std::memcpy(&version, serialized + 8, 4);
        std::memcpy(&guidLength, serialized + 12, 4);
        std::memcpy(&count, serialized + 16 + kGuidField, 8);
        if (version != kFormatVersion)
            return fail("fmi2DeSerializeFMUstate: corrupt serialized state: format version %u, expected %u", version,
                        kFormatVersion);
        const std::string guid = buildGuid();
        if (guidLength != guid.size() || std::memcmp(serialized + 16, guid.data(), guid.size()) != 0)
            return fail("fmi2DeSerializeFMUstate: the serialized state was written by a different PlateImpact build "
                        "(GUID mismatch; this FMU has GUID %s)", guid.c_str());
        const std::size_t payload = size - kHeaderBytes;
        if (payload % sizeof(double) != 0 || count != payload / sizeof(double))
            return fail("fmi2DeSerializeFMUstate: corrupt serialized state: wrong size, %zu bytes for the %llu "
                        "values its header announces", size, static_cast<unsigned long long>(count));
        std::vector<double> data(static_cast<std::size_t>(count));
        if (count > 0) std::memcpy(data.data(), serialized + kHeaderBytes, payload);
        auto snapshot = std::make_unique<Snapshot>();
        try {
            decodeSnapshot(data, *snapshot);
        } catch (const DecodeError& e) {
            return fail("fmi2DeSerializeFMUstate: corrupt serialized state: %s", e.what());
        }
        if (*state) {
            Snapshot* previous = asSnapshot(*state);
            if (!previous) return fail("fmi2DeSerializeFMUstate: *FMUstate is not an FMU state of PlateImpact");
            *previous = std::move(*snapshot);
            return fmi2OK;
        }
        *state = snapshot.release();  // owned by the importer until fmi2FreeFMUstate
        return fmi2OK;
    });
}

// ---------------------------------------------------------------------------------------------
// Co-simulation

fmi2Status PlateInstance::setRealInputDerivatives(const fmi2ValueReference vr[], size_t nvr,
                                                  const fmi2Integer order[], const fmi2Real value[]) {
    return call("fmi2SetRealInputDerivatives", kInputDerivativeStates, [&]() -> fmi2Status {
        if (nvr == 0) return fmi2OK;
        if (!vr || !order || !value)
            return fail("fmi2SetRealInputDerivatives: arguments vr[], order[] and value[] must not be NULL");
        for (size_t i = 0; i < nvr; ++i) {
            const Variable* variable = findVariable(vr[i]);
            if (!variable || variable->causality != Causality::Input || variable->type != VariableType::Real)
                return fail("fmi2SetRealInputDerivatives: value reference %u is not a Real input; input derivatives "
                            "exist for base_displacement (vr %u) and load (vr %u)", vr[i], kVrBaseDisplacement, kVrLoad);
            if (order[i] != 1 && order[i] != 2)
                return fail("fmi2SetRealInputDerivatives: derivative order %d of %s is not supported; orders 1 and 2 are",
                            order[i], variable->name);
            if (!std::isfinite(value[i]))
                return fail("fmi2SetRealInputDerivatives: derivative of order %d of %s = %g rejected: NaN and Inf are "
                            "not allowed", order[i], variable->name, value[i]);
            InputPort& port = vr[i] == kVrBaseDisplacement ? values_.baseDisplacement : values_.load;
            (order[i] == 1 ? port.signal.d1 : port.signal.d2) = value[i];
            port.derivativesGiven = true;
        }
        return fmi2OK;
    });
}

fmi2Status PlateInstance::getRealOutputDerivatives(const fmi2ValueReference[], size_t, const fmi2Integer[], fmi2Real[]) {
    return call("fmi2GetRealOutputDerivatives", kOutputDerivativeStates, [&]() -> fmi2Status {
        return fail("fmi2GetRealOutputDerivatives: not supported (maxOutputDerivativeOrder=\"0\")");
    });
}

fmi2Status PlateInstance::doStep(fmi2Real t, fmi2Real h, fmi2Boolean) {
    return call("fmi2DoStep", StepComplete, [&]() -> fmi2Status {
        if (!simulation_) return fail("fmi2DoStep: internal error: no simulation in state stepComplete");
        const double now = currentTime();
        if (!std::isfinite(t) || std::fabs(t - now) > kTimeTolerance * std::max(1.0, std::fabs(t)))
            return fail("fmi2DoStep: currentCommunicationPoint = %.17g differs from the FMU's time %.17g; each step "
                        "must start where the previous one ended (relative tolerance %g)", t, now, kTimeTolerance);
        if (!std::isfinite(h) || !(h > 0))
            return fail("fmi2DoStep: communicationStepSize h = %.17g rejected: it must be > 0", h);
        const double dt = simulation_->parameters().dt;
        const double ratio = h / dt;
        const long long steps = ratio < 9.0e15 ? std::llround(ratio) : 0;
        if (steps < 1 || std::fabs(double(steps) * dt - h) > kStepMultipleTolerance * h)
            return fail("fmi2DoStep: communicationStepSize h = %.17g is not a whole multiple of dt = %.17g "
                        "(h/dt = %.17g); the rule is h = n*dt with an integer n >= 1, relative tolerance %g", h, dt,
                        ratio, kStepMultipleTolerance);
        // The communicated values at this point extend the histories; a master that set no
        // derivatives gets the inputs reconstructed from them (InputPort::stepSignal). The
        // history's times are the FMU's own (whole numbers of dt): a master's roundoff in t
        // does not reach the divided differences.
        values_.baseDisplacement.history.record(now, values_.baseDisplacement.signal.value);
        values_.load.history.record(now, values_.load.signal.value);
        try {
            const double span = double(steps) * dt;  // the step as taken (h up to roundoff)
            simulation_->advance(steps, values_.baseDisplacement.stepSignal(span), values_.load.stepSignal(span));
        } catch (const plate::StepError& e) {
            refreshOutputs();  // the simulation stays at its last good step (for debugging)
            return fail("fmi2DoStep: step from t = %.17g failed at t = %.17g: %s", t, currentTime(), e.what());
        }
        refreshOutputs();
        log(fmi2OK, LogAll, "fmi2DoStep: t = %.17g, h = %.17g, %lld steps of dt = %g", t, h, steps, dt);
        return fmi2OK;
    });
}

fmi2Status PlateInstance::cancelStep() {
    // fmi2DoStep never returns fmi2Pending (canRunAsynchronuously="false"), so there is never a
    // step to cancel: the only allowed state, stepInProgress, does not occur.
    return call("fmi2CancelStep", StepInProgress, [&]() -> fmi2Status {
        return fail("fmi2CancelStep: not supported (canRunAsynchronuously=\"false\")");
    });
}

fmi2Status PlateInstance::statusNotAvailable(const char* function, fmi2StatusKind kind) {
    static constexpr const char* kKinds[] = {"fmi2DoStepStatus", "fmi2PendingStatus", "fmi2LastSuccessfulTime",
                                             "fmi2Terminated"};
    const char* name = (kind >= 0 && kind <= 3) ? kKinds[kind] : "an unknown status kind";
    log(fmi2Discard, LogStatusError, "%s: %s is not available from this function (fmi2DoStep never returns "
        "fmi2Pending or fmi2Discard); returning fmi2Discard", function, name);
    return fmi2Discard;
}

fmi2Status PlateInstance::getStatus(fmi2StatusKind kind, fmi2Status* value) {
    return call("fmi2GetStatus", kStatusStates, [&]() -> fmi2Status {
        if (!value) return fail("fmi2GetStatus: argument value must not be NULL");
        return statusNotAvailable("fmi2GetStatus", kind);
    });
}

fmi2Status PlateInstance::getRealStatus(fmi2StatusKind kind, fmi2Real* value) {
    return call("fmi2GetRealStatus", kStatusStates, [&]() -> fmi2Status {
        if (!value) return fail("fmi2GetRealStatus: argument value must not be NULL");
        if (kind != fmi2LastSuccessfulTime) return statusNotAvailable("fmi2GetRealStatus", kind);
        *value = currentTime();
        return fmi2OK;
    });
}

fmi2Status PlateInstance::getIntegerStatus(fmi2StatusKind kind, fmi2Integer* value) {
    return call("fmi2GetIntegerStatus", kStatusStates, [&]() -> fmi2Status {
        if (!value) return fail("fmi2GetIntegerStatus: argument value must not be NULL");
        return statusNotAvailable("fmi2GetIntegerStatus", kind);
    });
}

fmi2Status PlateInstance::getBooleanStatus(fmi2StatusKind kind, fmi2Boolean* value) {
    return call("fmi2GetBooleanStatus", kStatusStates, [&]() -> fmi2Status {
        if (!value) return fail("fmi2GetBooleanStatus: argument value must not be NULL");
        if (kind != fmi2Terminated) return statusNotAvailable("fmi2GetBooleanStatus", kind);
        *value = fmi2False;  // the plate never asks the master to end the simulation
        return fmi2OK;
    });
}

fmi2Status PlateInstance::getStringStatus(fmi2StatusKind kind, fmi2String* value) {
    return call("fmi2GetStringStatus", kStatusStates, [&]() -> fmi2Status {
        if (!value) return fail("fmi2GetStringStatus: argument value must not be NULL");
        return statusNotAvailable("fmi2GetStringStatus", kind);
    });
}

fmi2Status PlateInstance::getDirectionalDerivative() {
    return call("fmi2GetDirectionalDerivative", kGetStates, [&]() -> fmi2Status {
        return fail("fmi2GetDirectionalDerivative: not supported (providesDirectionalDerivative=\"false\")");
    });
}

fmi2Status PlateInstance::modelExchangeFunction(const char* function) {
    return call(function, kAnyState, [&]() -> fmi2Status {
        return fail("%s: Model Exchange is not supported; this FMU implements FMI 2.0 Co-Simulation only", function);
    });
}

}  // namespace plateimpact
