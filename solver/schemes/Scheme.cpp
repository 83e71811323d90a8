#include "schemes/Scheme.h"

#include <sstream>

#include "base/Errors.h"

namespace plate {

// The outputs of every scheme (docs/theory.md §14): the points' heights, the energy and the ledger
// at t_n; the port's force and moment over the last step, the points' velocities at t_n
// (second-order backward) and accelerations at t_{n−1}, and the contact sums.
PlateOutputs Scheme::outputs(bool port) const {
    const SchemeState& s = shared();
    PlateOutputs o;
    o.corner1 = pointHeight(0, 0);
    o.corner2 = pointHeight(1, 0);
    o.freeEdgeMid = pointHeight(2, 0);
    o.energy = outputEnergy();
    o.energyDissipated = s.energyDissipated;
    o.energyInput = s.energyInput;
    o.energyDamped = s.energyDamped;
    o.maxKktResidual = s.maxKktResidual;
    o.contactVertices = s.contactPoints;
    o.contactSolves = double(s.contactSolves);
    o.contactIterationsMax = s.contactIterationsMax;
    o.contactOnsets[0] = double(s.contactOnsets[0]);
    o.contactOnsets[1] = double(s.contactOnsets[1]);
    addOutputs(o);
    if (!port) return o;
    clampLoad(o.clampForce, o.clampMoment);
    setPortKinematics(o, dt_, [&](int k, int level) { return k < 3 ? pointHeight(k, level) : clampHeight(level); });
    for (int k = 0; k < 2; ++k) {
        o.contactForce[k] = s.stepContactForce[k];
        o.contactImpulse[k] = s.contactImpulseSum[k];
    }
    return o;
}

void Scheme::refuseInputs(double zNext, double pNext, bool finite, bool inRange) const {
    const double t = nextTime();
    std::ostringstream msg;
    msg.precision(15);  // round-trips what users type (0.7, not 0.69999999999999996)
    if (!finite) {
        msg << "non-finite input at t = " << t << ": base_displacement = " << zNext << ", load = " << pNext;
    } else if (!inRange) {
        msg << "input out of range at t = " << t << ": base_displacement = " << zNext << ", load = " << pNext
            << " (allowed: |base_displacement| <= " << kMaxDisplacement << " m, |load| <= " << kMaxLoad << " Pa)";
    } else {
        msg << "base_displacement = " << zNext << " at t = " << t << " puts the clamped edge past "
            << (zNext < obstacles_.clampLower() ? "obstacle_lower = " : "obstacle_upper = ")
            << (zNext < obstacles_.clampLower() ? obstacles_.clampLower() : obstacles_.clampUpper())
            << " (allowed: obstacle_lower <= base_displacement <= obstacle_upper)";
    }
    throw StepError(msg.str(), nextTime());
}

void Scheme::refuseNonFinite() const {
    std::ostringstream msg;
    msg << "the step to t = " << nextTime() << " produced a non-finite displacement";
    throw StepError(msg.str(), nextTime());
}

void Scheme::refuseUnsolved(const char* what, int iterations, double kkt) const {
    std::ostringstream msg;
    msg << what << " did not converge at t = " << nextTime() << " (" << iterations
        << " iterations, relative KKT residual " << kkt << ")";
    throw StepError(msg.str(), nextTime());
}

}  // namespace plate
