#include "PlateParameters.h"

#include <cmath>
#include <sstream>

namespace plate {

namespace {

template <class T>
[[noreturn]] void reject(const char* name, T value, const char* allowed) {
    std::ostringstream msg;
    msg.precision(15);  // round-trips what users type (0.7, not 0.69999999999999996)
    msg << "invalid parameter " << name << " = " << value << " (allowed: " << allowed << ")";
    throw ParameterError(msg.str());
}

void requirePositive(const char* name, double value) {
    if (!(std::isfinite(value) && value > 0.0)) reject(name, value, "finite and > 0");
}

}  // namespace

void validate(const PlateParameters& p) {
    requirePositive("length", p.length);
    requirePositive("width", p.width);
    requirePositive("thickness", p.thickness);
    requirePositive("youngs_modulus", p.youngsModulus);
    if (!(p.poissonRatio > 0.0 && p.poissonRatio < 0.5))
        reject("poisson_ratio", p.poissonRatio, "0 < poisson_ratio < 0.5");
    requirePositive("density", p.density);
    if (p.nx < 1 || p.nx > 400) reject("nx", p.nx, "1 <= nx <= 400");
    if (p.ny < 1 || p.ny > 400) reject("ny", p.ny, "1 <= ny <= 400");
    if (p.obstacleLowerEnabled && !(std::isfinite(p.obstacleLower) && p.obstacleLower < 0.0))
        reject("obstacle_lower", p.obstacleLower,
               "finite and < 0 when obstacle_lower_enabled (the plate starts at w = 0)");
    if (p.obstacleUpperEnabled && !(std::isfinite(p.obstacleUpper) && p.obstacleUpper > 0.0))
        reject("obstacle_upper", p.obstacleUpper,
               "finite and > 0 when obstacle_upper_enabled (the plate starts at w = 0)");
    if (!(std::isfinite(p.dt) && p.dt > 0.0)) reject("dt", p.dt, "finite and > 0");
    if (!(p.beta >= 0.0 && p.beta <= 0.5)) reject("beta", p.beta, "0 <= beta <= 0.5");
    if (!std::isfinite(p.initialLoad)) reject("initial_load", p.initialLoad, "finite");
    if (p.modes < 0) reject("modes", p.modes, "modes >= 0 (0 = full space)");
}

}  // namespace plate
