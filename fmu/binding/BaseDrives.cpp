#include "binding/BaseDrives.h"

namespace plateimpact {

namespace {

using plate::InputSignal;

// The displacement input as it comes (reconstructed between the obstacles).
InputSignal displacementPath(PlateValues& v, const ClampMotion&, double now, double span, double lower, double upper) {
    return v.baseDisplacement.stepSignal(now, span, lower, upper);
}
// The exact integral of the velocity input from the clamp's position (§16).
InputSignal velocityPath(PlateValues& v, const ClampMotion& clamp, double now, double span, double, double) {
    return v.baseVelocity.stepSignal(now, span, -kMaxBaseVelocity, kMaxBaseVelocity).integral(clamp.position);
}
// The acceleration input integrated twice from the clamp's velocity and position (§16).
InputSignal accelerationPath(PlateValues& v, const ClampMotion& clamp, double now, double span, double, double) {
    return v.baseAcceleration.stepSignal(now, span, -kMaxBaseAcceleration, kMaxBaseAcceleration)
        .integral(clamp.velocity)
        .integral(clamp.position);
}
// The drive force on the armature (§18).
InputSignal forcePath(PlateValues& v, const ClampMotion&, double now, double span, double, double) {
    return v.driveForce.stepSignal(now, span, -plate::kMaxCarrierForce, plate::kMaxCarrierForce);
}
// The wave, held: what the partner launched is what arrives (§19).
InputSignal wavePath(PlateValues& v, const ClampMotion&, double, double, double, double) {
    v.tlmWaveIn.history.reached(v.tlmWaveIn.signal.value);
    return InputSignal{v.tlmWaveIn.signal.value, 0.0, 0.0};
}

double displacementAt(const InputSignal& base, double span) { return base.at(span); }
double velocityAt(const InputSignal& base, double span) {
    return InputSignal{base.d1, base.d2, base.d3, base.d4}.at(span);
}
double accelerationAt(const InputSignal& base, double span) { return InputSignal{base.d2, base.d3, base.d4}.at(span); }

// base_drive's items in order; a carried clamp never ends a step early, so its inputAt is not read.
const DriveMode kDriveModes[kDriveModeCount] = {
    {BaseDrive::Displacement, "displacement", "base_displacement", &PlateValues::baseDisplacement, false,
     displacementPath, displacementAt},
    {BaseDrive::Velocity, "velocity", "base_velocity", &PlateValues::baseVelocity, false, velocityPath, velocityAt},
    {BaseDrive::Acceleration, "acceleration", "base_acceleration", &PlateValues::baseAcceleration, false,
     accelerationPath, accelerationAt},
    {BaseDrive::Force, "force", "drive_force", &PlateValues::driveForce, true, forcePath, displacementAt},
    {BaseDrive::Tlm, "tlm", "tlm_wave_in", &PlateValues::tlmWaveIn, true, wavePath, displacementAt},
};

}  // namespace

const DriveMode& driveMode(BaseDrive drive) { return kDriveModes[static_cast<int>(drive) - 1]; }

const DriveMode* driveModes() { return kDriveModes; }

}  // namespace plateimpact
