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

// The ranges keep every product the scheme forms (K ~ E t³/h⁴, Δt²K, energies) far inside
// the doubles' range, so that accepted parameters never give Inf or NaN; they are wide enough
// for any plate a structural code would model (fuzz/parameters.cpp found the need: dt = 1e-323
// was accepted and the energy came out NaN).
void requireRange(const char* name, double value, double lo, double hi) {
    if (!(value >= lo && value <= hi)) {
        std::ostringstream allowed;
        allowed << lo << " <= " << name << " <= " << hi;
        reject(name, value, allowed.str().c_str());
    }
}

}  // namespace

void validate(const PlateParameters& p) {
    requireRange("length", p.length, 1e-4, 1e4);
    requireRange("width", p.width, 1e-4, 1e4);
    requireRange("thickness", p.thickness, 1e-6, 1e2);
    requireRange("youngs_modulus", p.youngsModulus, 1.0, 1e14);
    if (!(p.poissonRatio > 0.0 && p.poissonRatio < 0.5))
        reject("poisson_ratio", p.poissonRatio, "0 < poisson_ratio < 0.5");
    requireRange("density", p.density, 1e-2, 1e6);
    if (p.nx < 1 || p.nx > 400) reject("nx", p.nx, "1 <= nx <= 400");
    if (p.ny < 1 || p.ny > 400) reject("ny", p.ny, "1 <= ny <= 400");
    if (p.obstacleLowerEnabled && !(p.obstacleLower >= -kMaxDisplacement && p.obstacleLower < 0.0))
        reject("obstacle_lower", p.obstacleLower,
               "-1e4 <= obstacle_lower < 0 when obstacle_lower_enabled (the plate starts at w = 0)");
    if (p.obstacleUpperEnabled && !(p.obstacleUpper > 0.0 && p.obstacleUpper <= kMaxDisplacement))
        reject("obstacle_upper", p.obstacleUpper,
               "0 < obstacle_upper <= 1e4 when obstacle_upper_enabled (the plate starts at w = 0)");
    requireRange("dt", p.dt, 1e-12, 1.0);
    if (!(p.beta >= 0.0 && p.beta <= 0.5)) reject("beta", p.beta, "0 <= beta <= 0.5");
    requireRange("initial_load", p.initialLoad, -kMaxLoad, kMaxLoad);
    if (p.modes < 0) reject("modes", p.modes, "modes >= 0 (0 = full space)");
    if (p.mass != MassModel::Consistent && p.mass != MassModel::SingularP0 && p.mass != MassModel::SingularP1dg)
        reject("mass", static_cast<int>(p.mass), "1 (consistent), 2 (singular_p0) or 3 (singular_p1dg)");
    if (p.singularMass() && p.modes != 0)
        reject("modes", p.modes, "modes = 0 with a singular mass (the modal reduction needs the consistent mass)");
    if (p.singularMass() && p.beta < 0.25)
        reject("beta", p.beta,
               "0.25 <= beta <= 0.5 with a singular mass (massless dofs have no explicit stability bound)");
    if (!(p.restitution >= 0.0 && p.restitution <= 1.0)) reject("restitution", p.restitution, "0 <= restitution <= 1");
    // 1e6 1/s and 1 s: damping ratios up to ~1e6 at 1 Hz and at 1e6 Hz, far past critical.
    requireRange("damping_mass", p.dampingMass, 0.0, 1e6);
    requireRange("damping_stiffness", p.dampingStiffness, 0.0, 1.0);
}

}  // namespace plate
