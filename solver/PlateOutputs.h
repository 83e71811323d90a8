#pragma once
// What the plate reports at a communication point, whatever engine computed it.
#include <array>

namespace plate {

// What the plate reports at a communication point. Counts are whole numbers stored as doubles
// (exact below 2^53), so that the struct is one list of doubles (forEach) for blending and states.
struct PlateOutputs {
    double corner1 = 0, corner2 = 0, freeEdgeMid = 0;  // w at (L,0), (L,W), (L,W/2), m
    double energy = 0;  // discrete energy E^{n-1/2} (docs/theory.md), J
    double energyDissipated = 0;  // cumulative contact loss, J
    double energyInput = 0;  // cumulative work of base motion and load, J
    double energyDamped = 0;  // cumulative work of the Rayleigh damping, J
    double maxKktResidual = 0;  // largest relative KKT residual of all QPs so far
    double contactVertices = 0;  // count: vertices on an obstacle after the last step
    double qpIterationsTotal = 0, qpIterationsMax = 0;  // counts
    // The port (docs/theory.md §14), computed only when asked for (outputs(true)).
    double clampForce = 0, clampMoment = 0;  // what the plate exerts on the clamp, N, N·m
    double clampDisplacement = 0, clampVelocity = 0, clampAcceleration = 0;  // z, ż, z̈
    double contactForce[2] = {0, 0}, contactImpulse[2] = {0, 0};  // lower, upper: N, N·s
    double impacts[2] = {0, 0};  // counts: contact onsets per obstacle
    double velocity[3] = {0, 0, 0}, acceleration[3] = {0, 0, 0};  // corner1, corner2, freeEdgeMid

    // Every field in a fixed order: the first kRealCount are quantities, the rest counts.
    static constexpr int kFieldCount = 28, kRealCount = 23;
    std::array<double*, kFieldCount> fields() {
        return {&corner1,           &corner2,           &freeEdgeMid,       &energy,          &energyDissipated,
                &energyInput,       &energyDamped,      &maxKktResidual,    &clampForce,      &clampMoment,
                &clampDisplacement, &clampVelocity,     &clampAcceleration, &contactForce[0], &contactForce[1],
                &contactImpulse[0], &contactImpulse[1], &velocity[0],       &velocity[1],     &velocity[2],
                &acceleration[0],   &acceleration[1],   &acceleration[2],   &contactVertices, &qpIterationsTotal,
                &qpIterationsMax,   &impacts[0],        &impacts[1]};
    }
};

}  // namespace plate
