// SineSweep.fmu: the FMI 2.0 co-simulation API over plate::SineSweep (solver/SineSweep.h), the
// controller of the two-FMU system model (examples/system_model.py). It has no inputs; its
// output base_displacement comes with exact first and second derivatives through
// fmi2GetRealOutputDerivatives (maxOutputDerivativeOrder = 2), for masters that pass them on.
// One allowed-state mask per function, as in the FMI 2.0 state machine (section 4.2.4).
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

#include "SineSweep.h"
#include "SineSweepGuid.h"  // generated at build time: PLATEIMPACT_GUID
#include "fmi2Functions.h"

namespace {

enum State : unsigned {
    Instantiated = 1u << 0,
    InitializationMode = 1u << 1,
    StepComplete = 1u << 2,
    Terminated = 1u << 3,
    Error = 1u << 4,
};
constexpr unsigned kAny = Instantiated | InitializationMode | StepComplete | Terminated | Error;
constexpr unsigned kSetParameters = Instantiated | InitializationMode;
constexpr unsigned kGet = InitializationMode | StepComplete | Terminated | Error;

// Value references (modelDescription/SineSweep.xml.in).
enum : fmi2ValueReference {
    kAmplitude = 0, kStartFrequency = 1, kEndFrequency = 2, kDuration = 3, kLaw = 4, kRampTime = 5,
    kBaseDisplacement = 10, kFrequency = 11,
};

struct Sweep {
    std::string name;
    fmi2CallbackFunctions callbacks;
    bool logAll = false;
    State state = Instantiated;
    double startTime = 0.0, time = 0.0;
    plate::SineSweepParameters parameters;

    void log(fmi2Status status, const char* category, const char* format, ...) __attribute__((format(printf, 4, 5))) {
        if (!callbacks.logger || (status == fmi2OK && !logAll)) return;
        char message[512];
        va_list args;
        va_start(args, format);
        std::vsnprintf(message, sizeof message, format, args);
        va_end(args);
        for (char* p = message; *p; ++p) if (*p == '%') *p = ' ';  // the logger may printf it
        callbacks.logger(callbacks.componentEnvironment, name.c_str(), status, category, message);
    }
    plate::SweepSample sample() const { return plate::SineSweep(parameters).at(time - startTime); }
};

Sweep* sweepOf(fmi2Component c) { return static_cast<Sweep*>(c); }

// Runs body if the state allows `function`; exceptions become a logged fmi2Error; fmi2Error
// puts the instance into the error state (only reset, free and getters are allowed there).
template <class Body>
fmi2Status call(fmi2Component c, const char* function, unsigned allowed, Body&& body) {
    Sweep* s = sweepOf(c);
    if (!s) return fmi2Error;
    fmi2Status status = fmi2Error;
    if (!(s->state & allowed)) {
        s->log(fmi2Error, "logStatusError", "%s: illegal call sequence (state %u)", function, unsigned(s->state));
    } else {
        try {
            status = body(*s);
        } catch (const std::exception& e) {
            s->log(fmi2Error, "logStatusError", "%s: %s", function, e.what());
            status = fmi2Error;
        }
    }
    if (status == fmi2Error) s->state = Error;
    return status;
}

fmi2Status unsupported(fmi2Component c, const char* function) {
    return call(c, function, kAny, [&](Sweep& s) {
        s.log(fmi2Error, "logStatusError", "%s: not supported by SineSweep (co-simulation, no FMU states)", function);
        return fmi2Error;
    });
}

double* realParameter(Sweep& s, fmi2ValueReference vr) {
    switch (vr) {
        case kAmplitude: return &s.parameters.amplitude;
        case kStartFrequency: return &s.parameters.startFrequency;
        case kEndFrequency: return &s.parameters.endFrequency;
        case kDuration: return &s.parameters.duration;
        case kRampTime: return &s.parameters.rampTime;
        default: return nullptr;
    }
}

}  // namespace

extern "C" {

const char* fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char* fmi2GetVersion(void) { return fmi2Version; }

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String guid, fmi2String,
                              const fmi2CallbackFunctions* functions, fmi2Boolean, fmi2Boolean loggingOn) {
    if (!functions || !instanceName || fmuType != fmi2CoSimulation || !guid ||
        std::strcmp(guid, PLATEIMPACT_GUID) != 0) {
        if (functions && functions->logger)
            functions->logger(functions->componentEnvironment, instanceName ? instanceName : "", fmi2Error,
                              "logStatusError", "fmi2Instantiate: needs an instance name, fmi2CoSimulation and this "
                              "build's GUID");
        return nullptr;
    }
    try {
        auto s = std::make_unique<Sweep>();
        s->name = instanceName;
        s->callbacks = *functions;
        s->logAll = loggingOn != fmi2False;
        return s.release();
    } catch (...) {
        return nullptr;
    }
}

void fmi2FreeInstance(fmi2Component c) { std::unique_ptr<Sweep> owned(sweepOf(c)); }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t, const fmi2String[]) {
    return call(c, "fmi2SetDebugLogging", kAny, [&](Sweep& s) {
        s.logAll = loggingOn != fmi2False;
        return fmi2OK;
    });
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean, fmi2Real, fmi2Real startTime, fmi2Boolean, fmi2Real) {
    return call(c, "fmi2SetupExperiment", Instantiated, [&](Sweep& s) {
        if (!std::isfinite(startTime)) throw std::invalid_argument("startTime is not finite");
        s.startTime = s.time = startTime;
        return fmi2OK;
    });
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
    return call(c, "fmi2EnterInitializationMode", Instantiated, [](Sweep& s) {
        s.state = InitializationMode;
        return fmi2OK;
    });
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
    return call(c, "fmi2ExitInitializationMode", InitializationMode, [](Sweep& s) {
        plate::SineSweep check(s.parameters);  // throws with the parameter and its range
        (void)check;
        s.state = StepComplete;
        return fmi2OK;
    });
}

fmi2Status fmi2Terminate(fmi2Component c) {
    return call(c, "fmi2Terminate", StepComplete, [](Sweep& s) {
        s.state = Terminated;
        return fmi2OK;
    });
}

fmi2Status fmi2Reset(fmi2Component c) {
    return call(c, "fmi2Reset", kAny, [](Sweep& s) {
        s.parameters = plate::SineSweepParameters{};
        s.startTime = s.time = 0.0;
        s.state = Instantiated;
        return fmi2OK;
    });
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]) {
    return call(c, "fmi2GetReal", kGet, [&](Sweep& s) {
        if (nvr > 0 && (!vr || !value)) throw std::invalid_argument("vr[] and value[] must not be NULL");
        for (size_t i = 0; i < nvr; ++i) {
            if (double* p = realParameter(s, vr[i])) {
                value[i] = *p;
            } else if (vr[i] == kBaseDisplacement || vr[i] == kFrequency) {
                const plate::SweepSample x = s.sample();
                value[i] = vr[i] == kBaseDisplacement ? x.value : x.frequency;
            } else {
                throw std::invalid_argument("unknown Real value reference " + std::to_string(vr[i]));
            }
        }
        return fmi2OK;
    });
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]) {
    return call(c, "fmi2SetReal", kSetParameters, [&](Sweep& s) {
        if (nvr > 0 && (!vr || !value)) throw std::invalid_argument("vr[] and value[] must not be NULL");
        for (size_t i = 0; i < nvr; ++i) {
            double* p = realParameter(s, vr[i]);
            if (!p) throw std::invalid_argument("value reference " + std::to_string(vr[i]) + " is not a Real parameter");
            if (!std::isfinite(value[i])) throw std::invalid_argument("NaN and Inf are not allowed");
            *p = value[i];
        }
        return fmi2OK;
    });
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[]) {
    return call(c, "fmi2GetInteger", kGet, [&](Sweep& s) {
        for (size_t i = 0; i < nvr; ++i) {
            if (!vr || !value || vr[i] != kLaw) throw std::invalid_argument("the only Integer/Enumeration is law (vr 4)");
            value[i] = static_cast<int>(s.parameters.law);
        }
        return fmi2OK;
    });
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[]) {
    return call(c, "fmi2SetInteger", kSetParameters, [&](Sweep& s) {
        for (size_t i = 0; i < nvr; ++i) {
            if (!vr || !value || vr[i] != kLaw) throw std::invalid_argument("the only Integer/Enumeration is law (vr 4)");
            if (value[i] != 1 && value[i] != 2)
                throw std::invalid_argument("law = " + std::to_string(value[i]) +
                                            " is not an item of SweepLaw (linear = 1, logarithmic = 2)");
            s.parameters.law = static_cast<plate::SweepLaw>(value[i]);
        }
        return fmi2OK;
    });
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference[], size_t nvr, fmi2Boolean[]) {
    return nvr == 0 ? fmi2OK : unsupported(c, "fmi2GetBoolean");
}
fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference[], size_t nvr, const fmi2Boolean[]) {
    return nvr == 0 ? fmi2OK : unsupported(c, "fmi2SetBoolean");
}
fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference[], size_t nvr, fmi2String[]) {
    return nvr == 0 ? fmi2OK : unsupported(c, "fmi2GetString");
}
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference[], size_t nvr, const fmi2String[]) {
    return nvr == 0 ? fmi2OK : unsupported(c, "fmi2SetString");
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[]) {
    return call(c, "fmi2GetRealOutputDerivatives", StepComplete | Terminated | Error, [&](Sweep& s) {
        const plate::SweepSample x = s.sample();
        for (size_t i = 0; i < nvr; ++i) {
            if (!vr || !order || !value || vr[i] != kBaseDisplacement)
                throw std::invalid_argument("output derivatives exist for base_displacement (vr 10) only");
            if (order[i] != 1 && order[i] != 2)
                throw std::invalid_argument("derivative order " + std::to_string(order[i]) + " (allowed: 1, 2)");
            value[i] = order[i] == 1 ? x.d1 : x.d2;
        }
        return fmi2OK;
    });
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real h, fmi2Boolean) {
    return call(c, "fmi2DoStep", StepComplete, [&](Sweep& s) {
        if (!std::isfinite(t) || !std::isfinite(h) || !(h > 0))
            throw std::invalid_argument("currentCommunicationPoint and communicationStepSize > 0 must be finite");
        if (std::fabs(t - s.time) > 1e-9 * std::max(1.0, std::fabs(t)))
            throw std::invalid_argument("currentCommunicationPoint differs from the FMU's time");
        s.time = t + h;
        return fmi2OK;
    });
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind kind, fmi2Real* value) {
    return call(c, "fmi2GetRealStatus", StepComplete | Terminated, [&](Sweep& s) {
        if (kind != fmi2LastSuccessfulTime || !value) throw std::invalid_argument("only fmi2LastSuccessfulTime");
        *value = s.time;
        return fmi2OK;
    });
}

// Not provided (see modelDescription/SineSweep.xml.in): each logs and returns fmi2Error.
fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t, const fmi2Integer[],
                                       const fmi2Real[]) { return unsupported(c, "fmi2SetRealInputDerivatives"); }
fmi2Status fmi2CancelStep(fmi2Component c) { return unsupported(c, "fmi2CancelStep"); }
fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind, fmi2Status*) { return unsupported(c, "fmi2GetStatus"); }
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind, fmi2Integer*) {
    return unsupported(c, "fmi2GetIntegerStatus");
}
fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind, fmi2Boolean*) {
    return unsupported(c, "fmi2GetBooleanStatus");
}
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind, fmi2String*) {
    return unsupported(c, "fmi2GetStringStatus");
}
fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate*) { return unsupported(c, "fmi2GetFMUstate"); }
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate) { return unsupported(c, "fmi2SetFMUstate"); }
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate*) { return unsupported(c, "fmi2FreeFMUstate"); }
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate, size_t*) {
    return unsupported(c, "fmi2SerializedFMUstateSize");
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate, fmi2Byte[], size_t) {
    return unsupported(c, "fmi2SerializeFMUstate");
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte[], size_t, fmi2FMUstate*) {
    return unsupported(c, "fmi2DeSerializeFMUstate");
}
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference[], size_t, const fmi2ValueReference[],
                                        size_t, const fmi2Real[], fmi2Real[]) {
    return unsupported(c, "fmi2GetDirectionalDerivative");
}

}  // extern "C"
