#pragma once
// What the plate reports at a communication point, whatever engine computed it.
#include <Eigen/Core>
#include <iterator>

#include "base/FieldTable.h"

namespace plate {

// What the plate reports at a communication point. Counts are whole numbers stored as doubles
// (exact below 2^53), so that the struct is one list of doubles (kOutputFields below) for
// blending and states.
struct PlateOutputs {
    double corner1 = 0, corner2 = 0, freeEdgeMid = 0;  // w at (L,0), (L,W), (L,W/2), m
    double energy = 0;  // discrete energy E^{n-1/2} (docs/theory.md), J
    double energyDissipated = 0;  // cumulative contact loss, J
    double energyInput = 0;  // cumulative work of base motion and load, J
    double energyDamped = 0;  // cumulative work of the Rayleigh damping, J
    double maxKktResidual = 0;  // largest relative KKT residual of all QPs so far
    double contactVertices = 0;  // count: vertices on an obstacle after the last step
    double contactSolves = 0, contactIterationsMax = 0;  // counts (qp_iterations_total, qp_iterations_max)
    // The port (docs/theory.md §14), computed only when asked for (outputs(true)).
    double clampForce = 0, clampMoment = 0;  // what the plate exerts on the clamp, N, N·m
    double clampDisplacement = 0, clampVelocity = 0, clampAcceleration = 0;  // z, ż, z̈
    double contactForce[2] = {0, 0}, contactImpulse[2] = {0, 0};  // lower, upper: N, N·s
    double impacts[2] = {0, 0};  // counts: impact episodes per obstacle (docs/theory.md §14)
    double contactOnsets[2] = {0, 0};  // counts: (sub-)steps whose contact force starts from zero, per obstacle
    double velocity[3] = {0, 0, 0}, acceleration[3] = {0, 0, 0};  // corner1, corner2, freeEdgeMid
    // time_scheme = flow with a tolerance (docs/theory.md §22): the accumulated estimate of the
    // displacement error (m) and the contact steps whose sub-steps the cap bounded (count).
    double errorEstimate = 0, cappedSteps = 0;
    // discretization_check (docs/theory.md §26): the estimated error of the reported points against
    // the converged plate that the mesh and the modal basis make, the largest so far (m).
    double discretizationError = 0;
    // Stress (docs/theory.md §23). The root's peak is tracked every step (PlateSimulation); the rest
    // is computed only when asked for (PlateSimulation::outputs(…, field)). The probes, as many as
    // the parameters place, are ProbeOutputs below.
    double rootStress = 0, rootStressPeak = 0;  // largest von Mises stress on x = 0 now, since t = 0, Pa
    double maxStress = 0, maxStressX = 0, maxStressY = 0;  // largest over the plate's vertices, Pa, and where, m
};

// The probes' absolute motion (docs/theory.md §23), one entry per probe (PlateParameters::probeX):
// w, its velocity (as corner_1_velocity) and acceleration (as corner_1_acceleration). Computed
// when asked for (PlateSimulation::probes()), interpolated between grid points as the quantities
// of PlateOutputs are.
struct ProbeOutputs {
    Eigen::VectorXd displacement, velocity, acceleration;
    void resize(Eigen::Index n) {
        displacement.setZero(n);
        velocity.setZero(n);
        acceleration.setZero(n);
    }
};

// Which of the stress outputs (docs/theory.md §23) to compute: none, the root's (a few rows), or
// the plate's too (its largest stress and where: rows
// at every vertex).
enum class FieldOutputs { None, Points, Plate };

// A point's velocity at the newest level (second-order backward difference) and its acceleration
// at the level before (central difference) from its heights at the three levels: the port's points
// and the probes alike.
inline double backwardVelocity(double now, double prev, double prev2, double dt) {
    return (3.0 * now - 4.0 * prev + prev2) / (2.0 * dt);
}
inline double centralAcceleration(double now, double prev, double prev2, double dt2) {
    return (now - 2.0 * prev + prev2) / dt2;
}

// The port's kinematics (docs/theory.md §14, §17), written once: `height(k, level)` is the height
// of output point k (0 corner_1, 1 corner_2, 2 free_edge_mid, 3 the clamp) at the newest level 0
// and the two before it; the velocity is the second-order backward difference at level 0, the
// acceleration the central difference at level 1.
template <class Height>
void setPortKinematics(PlateOutputs& o, double dt, Height&& height) {
    const double dt2 = dt * dt;
    double* velocity[4] = {&o.velocity[0], &o.velocity[1], &o.velocity[2], &o.clampVelocity};
    double* acceleration[4] = {&o.acceleration[0], &o.acceleration[1], &o.acceleration[2], &o.clampAcceleration};
    for (int k = 0; k < 4; ++k) {
        const double now = height(k, 0), prev = height(k, 1), prev2 = height(k, 2);
        *velocity[k] = backwardVelocity(now, prev, prev2, dt);
        *acceleration[k] = centralAcceleration(now, prev, prev2, dt2);
    }
    o.clampDisplacement = height(3, 0);
}

// How an output passes between grid points (PlateSimulation::outputs).
enum class Between {
    Interpolated,  // a quantity: linear interpolation between the grid points around t
    Held,  // a count: its value at the grid point before t
};

// A row of the outputs' table: the field, its name for messages and how it is blended.
struct OutputField {
    const char* name;
    Between between;
    double& (*field)(PlateOutputs&);
    double value(const PlateOutputs& o) const { return field(const_cast<PlateOutputs&>(o)); }  // reads only
};

// Every output once (checked below), in the order of the FMU states (PlateSimulation::saveState).
// A new output is its field above and its row here: blending and states walk this table, and
// nothing else lists the outputs but the FMU's table of variables (fmu/binding/PlateVariables.cpp).
// clang-format off
inline constexpr OutputField kOutputFields[] = {
    {"corner1",           Between::Interpolated, fieldOf<&PlateOutputs::corner1>},
    {"corner2",           Between::Interpolated, fieldOf<&PlateOutputs::corner2>},
    {"freeEdgeMid",       Between::Interpolated, fieldOf<&PlateOutputs::freeEdgeMid>},
    {"energy",            Between::Interpolated, fieldOf<&PlateOutputs::energy>},
    {"energyDissipated",  Between::Interpolated, fieldOf<&PlateOutputs::energyDissipated>},
    {"energyInput",       Between::Interpolated, fieldOf<&PlateOutputs::energyInput>},
    {"energyDamped",      Between::Interpolated, fieldOf<&PlateOutputs::energyDamped>},
    {"maxKktResidual",    Between::Interpolated, fieldOf<&PlateOutputs::maxKktResidual>},
    {"clampForce",        Between::Interpolated, fieldOf<&PlateOutputs::clampForce>},
    {"clampMoment",       Between::Interpolated, fieldOf<&PlateOutputs::clampMoment>},
    {"clampDisplacement", Between::Interpolated, fieldOf<&PlateOutputs::clampDisplacement>},
    {"clampVelocity",     Between::Interpolated, fieldOf<&PlateOutputs::clampVelocity>},
    {"clampAcceleration", Between::Interpolated, fieldOf<&PlateOutputs::clampAcceleration>},
    {"contactForce[0]",   Between::Interpolated, fieldOf<&PlateOutputs::contactForce, 0>},
    {"contactForce[1]",   Between::Interpolated, fieldOf<&PlateOutputs::contactForce, 1>},
    {"contactImpulse[0]", Between::Interpolated, fieldOf<&PlateOutputs::contactImpulse, 0>},
    {"contactImpulse[1]", Between::Interpolated, fieldOf<&PlateOutputs::contactImpulse, 1>},
    {"velocity[0]",       Between::Interpolated, fieldOf<&PlateOutputs::velocity, 0>},
    {"velocity[1]",       Between::Interpolated, fieldOf<&PlateOutputs::velocity, 1>},
    {"velocity[2]",       Between::Interpolated, fieldOf<&PlateOutputs::velocity, 2>},
    {"acceleration[0]",   Between::Interpolated, fieldOf<&PlateOutputs::acceleration, 0>},
    {"acceleration[1]",   Between::Interpolated, fieldOf<&PlateOutputs::acceleration, 1>},
    {"acceleration[2]",   Between::Interpolated, fieldOf<&PlateOutputs::acceleration, 2>},
    {"rootStress",        Between::Interpolated, fieldOf<&PlateOutputs::rootStress>},
    {"rootStressPeak",    Between::Interpolated, fieldOf<&PlateOutputs::rootStressPeak>},
    {"maxStress",         Between::Interpolated, fieldOf<&PlateOutputs::maxStress>},
    {"contactVertices",   Between::Held,         fieldOf<&PlateOutputs::contactVertices>},
    {"contactSolves",     Between::Held,         fieldOf<&PlateOutputs::contactSolves>},
    {"contactIterationsMax",Between::Held,         fieldOf<&PlateOutputs::contactIterationsMax>},
    {"impacts[0]",        Between::Held,         fieldOf<&PlateOutputs::impacts, 0>},
    {"impacts[1]",        Between::Held,         fieldOf<&PlateOutputs::impacts, 1>},
    {"contactOnsets[0]",  Between::Held,         fieldOf<&PlateOutputs::contactOnsets, 0>},
    {"contactOnsets[1]",  Between::Held,         fieldOf<&PlateOutputs::contactOnsets, 1>},
    {"errorEstimate",     Between::Held,         fieldOf<&PlateOutputs::errorEstimate>},
    {"cappedSteps",       Between::Held,         fieldOf<&PlateOutputs::cappedSteps>},
    {"discretizationError",Between::Held,        fieldOf<&PlateOutputs::discretizationError>},
    {"maxStressX",        Between::Held,         fieldOf<&PlateOutputs::maxStressX>},  // a place, not a quantity
    {"maxStressY",        Between::Held,         fieldOf<&PlateOutputs::maxStressY>},
};
// clang-format on
constexpr std::size_t kOutputCount = std::size(kOutputFields);
static_assert(coversEachFieldOnce<PlateOutputs>(kOutputFields),
              "kOutputFields must list every double of PlateOutputs exactly once");

// The clamp's carrier at a communication point (docs/theory.md §18–19): zero without one. Only
// on the grid (a carried clamp refuses steps between grid points).
struct CarrierOutputs {
    double energy = 0;  // ½ M_a v² + the suspension's Φ, J
    double driveWork = 0, damperWork = 0, portWork = 0;  // cumulative, J (portWork: the plate's work on it)
    double waveOut = 0, transit = 0, lineLoss = 0;  // a line end: ā (N), h ā²/(4Z) and the line's loss (J)
};

// With a tolerance (the flow law, docs/theory.md §22): when the estimate passed it, in the scheme's time
// (< 0: not yet), and the sub-steps a contact step takes from then on (the FMU's advice says both).
struct ToleranceHorizon {
    double lostAt = -1.0;
    int substeps = 0;
};

}  // namespace plate
