#pragma once
// The modes of base_drive as one table (docs/theory.md §16–19): per item its name, the input that
// drives the clamp, whether the clamp is carried inside the step, the clamp's path over a step from
// that input, and the drive input's own value inside that path (where a step that ended early
// leaves the input's history). PlateModel reads the row of the drive it runs; nothing else switches
// on base_drive.
#include "binding/PlateVariables.h"

namespace plateimpact {

// The clamp's state at the communication time that a velocity or an acceleration drive integrates from.
struct ClampMotion {
    double position = 0.0, velocity = 0.0;
};

struct DriveMode {
    BaseDrive drive;
    const char* item;  // base_drive's item: "displacement"
    const char* input;  // the input that drives the clamp: "base_displacement"
    InputPort PlateValues::*port;
    bool carried;  // force, tlm: the clamp is carried inside the step (§18–19); else a motion input (§16)
    // The clamp's path over a step of length span from the communication time now; a reconstructed
    // displacement stays in [lower, upper] (the obstacles).
    plate::InputSignal (*path)(PlateValues& values, const ClampMotion& clamp, double now, double span, double lower,
                               double upper);
    // The drive input's own signal inside the clamp's path `base`, at `span` into the step.
    double (*inputAt)(const plate::InputSignal& base, double span);
};

const DriveMode& driveMode(BaseDrive drive);
// Every mode, in base_drive's order (1 displacement ... 5 tlm).
const DriveMode* driveModes();
constexpr int kDriveModeCount = 5;

}  // namespace plateimpact
