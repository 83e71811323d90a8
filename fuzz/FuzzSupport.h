#pragma once
// What the three libFuzzer harnesses share: callbacks for fmi2Instantiate, the awkward values
// they feed (range edges, NaN, infinities, denormals, huge), and a small plate that builds in
// well under a millisecond (so that the fuzzer runs thousands of inputs a second).
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "core/Model.h"
#include "binding/PlateVariables.h"
#include "fmi2Functions.h"

namespace fuzz {

inline void logger(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, ...) {}

inline const fmi2CallbackFunctions* callbacks() {
    static const fmi2CallbackFunctions functions = {logger, nullptr, nullptr, nullptr, nullptr};
    return &functions;
}

inline fmi2Component instantiate(const char* name = "fuzz") {
    return fmi2Instantiate(name, fmi2CoSimulation, fmu::modelGuid(), "", callbacks(), fmi2False, fmi2False);
}

// A double from the awkward set or, for the rest, any bit pattern.
inline double awkwardReal(FuzzedDataProvider& in) {
    static const double kValues[] = {0.0,
                                     -0.0,
                                     1.0,
                                     -1.0,
                                     0.5,
                                     0.25,
                                     1e-5,
                                     1e-300,
                                     std::numeric_limits<double>::denorm_min(),
                                     -std::numeric_limits<double>::denorm_min(),
                                     std::numeric_limits<double>::min(),
                                     std::numeric_limits<double>::max(),
                                     -std::numeric_limits<double>::max(),
                                     std::numeric_limits<double>::infinity(),
                                     -std::numeric_limits<double>::infinity(),
                                     std::numeric_limits<double>::quiet_NaN(),
                                     1e300,
                                     0.1,
                                     -0.1,
                                     0.09};
    if (in.ConsumeBool()) return in.PickValueInArray(kValues);
    const std::uint64_t bits = in.ConsumeIntegral<std::uint64_t>();
    double x;
    static_assert(sizeof x == sizeof bits, "64-bit doubles");
    __builtin_memcpy(&x, &bits, sizeof x);
    return x;
}

// Value references of PlateImpact the harnesses treat specially (mesh sizes stay small).
constexpr fmi2ValueReference kNx = plateimpact::kVrNx, kNy = plateimpact::kVrNy, kDt = plateimpact::kVrDt,
                             kModes = plateimpact::kVrModes;

// Parameters that make a plate that builds fast (1-3 x 1-2 cells, dt = 1e-4 s).
inline void smallPlate(fmi2Component c, int nx, int ny) {
    const fmi2ValueReference vr[] = {kNx, kNy};
    const fmi2Integer value[] = {nx, ny};
    fmi2SetInteger(c, vr, 2, value);
    const fmi2ValueReference dtVr = kDt;
    const fmi2Real dt = 1e-4;
    fmi2SetReal(c, &dtVr, 1, &dt);
}

}  // namespace fuzz
