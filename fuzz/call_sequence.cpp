// libFuzzer harness (a): the input is decoded into a sequence of up to 16 fmi2* calls with arguments —
// value references in and out of range, awkward values, step sizes, NULL pointers where the
// standard allows them, FMU states from another instance, serialized states with a byte
// changed. Any crash or sanitizer report is a finding. Plates stay small (at most 2 x 2 cells)
// and steps short (at most 20 internal steps), so that an input runs in about a millisecond.
#include <array>
#include <vector>

#include "FuzzSupport.h"

namespace {

struct Session {
    std::array<fmi2Component, 2> instances{};
    std::vector<std::pair<int, fmi2FMUstate>> states;  // (owner, state)
    std::array<double, 2> time{};

    ~Session() {
        for (auto& [owner, state] : states) fmi2FreeFMUstate(instances[owner], &state);
        for (fmi2Component c : instances) fmi2FreeInstance(c);
    }
};

fmi2ValueReference anyVr(FuzzedDataProvider& in) {
    return in.ConsumeBool() ? in.ConsumeIntegralInRange<fmi2ValueReference>(0, 45)
                            : in.ConsumeIntegral<fmi2ValueReference>();
}

void step(FuzzedDataProvider& in, Session& s, int i) {
    fmi2Component c = s.instances[i];
    fmi2Real dt = 1e-4;
    const fmi2ValueReference dtVr = fuzz::kDt;
    fmi2GetReal(c, &dtVr, 1, &dt);
    double h = dt * in.ConsumeIntegralInRange(1, 20);
    switch (in.ConsumeIntegralInRange(0, 3)) {
        case 0: break;
        case 1: h = fuzz::awkwardReal(in); break;
        case 2: h *= 1.0 + 1e-12; break;
        default: h = dt * in.ConsumeFloatingPointInRange<double>(0.0, 3.0); break;
    }
    if (!(std::fabs(h / dt) <= 20.0)) return;  // a legal but long step: not what this harness looks for
    const double t = in.ConsumeBool() ? s.time[i] : fuzz::awkwardReal(in);
    if (fmi2DoStep(c, t, h, fmi2True) == fmi2OK) s.time[i] += h;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    FuzzedDataProvider in(data, size);
    Session s;
    for (int i = 0; i < 2; ++i) {
        s.instances[i] = fuzz::instantiate(i == 0 ? "a" : "b");
        fuzz::smallPlate(s.instances[i], in.ConsumeIntegralInRange(1, 2), in.ConsumeIntegralInRange(1, 2));
    }
    int calls = 0;
    while (in.remaining_bytes() > 0 && ++calls <= 16) {
        const int i = in.ConsumeIntegralInRange(0, 1);
        fmi2Component c = s.instances[i];
        const fmi2ValueReference vr = anyVr(in);
        switch (in.ConsumeIntegralInRange(0, 21)) {
            case 0: fmi2SetupExperiment(c, in.ConsumeBool(), fuzz::awkwardReal(in), 0.0, in.ConsumeBool(), 1.0); break;
            case 1: fmi2EnterInitializationMode(c); break;
            case 2: fmi2ExitInitializationMode(c); break;
            case 3: fmi2Terminate(c); break;
            case 4:
                if (fmi2Reset(c) == fmi2OK) {
                    fuzz::smallPlate(c, 1, 1);
                    s.time[i] = 0.0;
                }
                break;
            case 5: {
                const fmi2Real x = fuzz::awkwardReal(in);
                fmi2SetReal(c, &vr, 1, &x);
                break;
            }
            case 6: {
                // nx, ny and modes stay small: a large mesh is legal, only slow
                const bool size = vr == fuzz::kNx || vr == fuzz::kNy || vr == fuzz::kModes;
                const fmi2Integer x = size ? in.ConsumeIntegralInRange(-1, 2) : in.ConsumeIntegral<fmi2Integer>();
                fmi2SetInteger(c, &vr, 1, &x);
                break;
            }
            case 7: {
                const fmi2Boolean x = in.ConsumeIntegral<fmi2Boolean>();
                fmi2SetBoolean(c, &vr, 1, &x);
                break;
            }
            case 8: {
                fmi2Real r[4];
                fmi2Integer n[4];
                fmi2Boolean b[4];
                const fmi2ValueReference vrs[4] = {vr, anyVr(in), anyVr(in), anyVr(in)};
                const size_t count = in.ConsumeIntegralInRange<size_t>(0, 4);
                fmi2GetReal(c, vrs, count, r);
                fmi2GetInteger(c, vrs, count, n);
                fmi2GetBoolean(c, vrs, count, b);
                fmi2GetReal(c, nullptr, 0, nullptr);  // allowed: nothing to read
                fmi2String text[1];
                fmi2GetString(c, vrs, count > 1 ? 1 : count, text);
                break;
            }
            case 9: step(in, s, i); break;
            case 10: {
                const fmi2Integer order = in.ConsumeIntegralInRange(-1, 3);
                const fmi2Real x = fuzz::awkwardReal(in);
                fmi2SetRealInputDerivatives(c, &vr, 1, &order, &x);
                break;
            }
            case 11: {
                fmi2FMUstate state = nullptr;
                if (fmi2GetFMUstate(c, &state) == fmi2OK) s.states.emplace_back(i, state);
                break;
            }
            case 12:
                if (!s.states.empty()) {  // possibly a state of the other instance
                    const auto& [owner, state] = s.states[in.ConsumeIntegralInRange<size_t>(0, s.states.size() - 1)];
                    (void)owner;
                    if (fmi2SetFMUstate(c, state) == fmi2OK) {
                        fmi2Real t = 0.0;
                        if (fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &t) == fmi2OK) s.time[i] = t;
                    }
                }
                break;
            case 13:
                if (!s.states.empty()) {
                    const size_t k = in.ConsumeIntegralInRange<size_t>(0, s.states.size() - 1);
                    fmi2FreeFMUstate(s.instances[s.states[k].first], &s.states[k].second);
                    s.states.erase(s.states.begin() + static_cast<std::ptrdiff_t>(k));
                }
                break;
            case 14:
                if (!s.states.empty()) {  // serialize, maybe damage one byte, read back
                    fmi2FMUstate state = s.states.back().second;
                    size_t bytes = 0;
                    if (fmi2SerializedFMUstateSize(c, state, &bytes) != fmi2OK) break;
                    std::vector<fmi2Byte> blob(bytes);
                    if (fmi2SerializeFMUstate(c, state, blob.data(), blob.size()) != fmi2OK) break;
                    if (!blob.empty() && in.ConsumeBool())
                        blob[in.ConsumeIntegralInRange<size_t>(0, blob.size() - 1)] ^= in.ConsumeIntegral<fmi2Byte>();
                    const size_t cut =
                        in.ConsumeBool() ? blob.size() : in.ConsumeIntegralInRange<size_t>(0, blob.size());
                    fmi2FMUstate back = nullptr;
                    if (fmi2DeSerializeFMUstate(c, blob.data(), cut, &back) == fmi2OK) s.states.emplace_back(i, back);
                }
                break;
            case 15: {
                fmi2Status st;
                fmi2Real r;
                fmi2Integer n;
                fmi2Boolean b;
                fmi2String text;
                // the four kinds FMI 2.0 defines (another value is not representable in the C++ enum)
                const auto kind = static_cast<fmi2StatusKind>(in.ConsumeIntegralInRange(0, 3));
                fmi2GetStatus(c, kind, in.ConsumeBool() ? &st : nullptr);
                fmi2GetRealStatus(c, kind, in.ConsumeBool() ? &r : nullptr);
                fmi2GetIntegerStatus(c, kind, &n);
                fmi2GetBooleanStatus(c, kind, &b);
                fmi2GetStringStatus(c, kind, &text);
                break;
            }
            case 16: {
                const char* categories[] = {"logAll", "logStatusError", "nonsense", nullptr};
                const size_t n = in.ConsumeIntegralInRange<size_t>(0, 4);
                fmi2SetDebugLogging(c, in.ConsumeBool(), n, in.ConsumeBool() ? categories : nullptr);
                break;
            }
            case 17: {
                const fmi2Integer order = in.ConsumeIntegralInRange(0, 3);
                fmi2Real x;
                fmi2GetRealOutputDerivatives(c, &vr, 1, &order, &x);
                break;
            }
            case 18: fmi2CancelStep(c); break;
            case 19: fmi2SetTime(c, fuzz::awkwardReal(in)); break;
            case 20: fmi2SetReal(c, &vr, 1, nullptr); break;  // NULL values with nvr > 0: an error, not a crash
            default: {
                fmi2FMUstate junk = nullptr;
                fmi2DeSerializeFMUstate(c, reinterpret_cast<const fmi2Byte*>(data), size,
                                        &junk);  // the raw input as a state
                if (junk) fmi2FreeFMUstate(c, &junk);
                break;
            }
        }
    }
    return 0;
}
