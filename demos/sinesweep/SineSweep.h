#pragma once
// A sine sweep for the clamp: z(t) = a s(t) sin φ(t), the controller of the two-FMU system
// model (SineSweep.fmu). Value and first two derivatives in closed form, so that the FMU can
// give exact output derivatives (docs/theory.md, "The sine-sweep controller").
#include <stdexcept>

namespace plate {

enum class SweepLaw { Linear = 1, Logarithmic = 2 };

struct SineSweepParameters {
    double amplitude = 0.09;  // m
    double startFrequency = 10.0;  // Hz
    double endFrequency = 35.0;  // Hz
    double duration = 1.0;  // s: the frequency goes from start to end over [0, duration]
    SweepLaw law = SweepLaw::Linear;
    double rampTime = 0.0;  // s: envelope s = sin²(πt / (2 rampTime)) over [0, rampTime]
};

struct SweepSample {
    double value = 0.0, d1 = 0.0, d2 = 0.0;  // z, dz/dt, d²z/dt²
    double frequency = 0.0;  // instantaneous frequency φ'/2π, Hz
};

class SineSweep {
public:
    // Throws std::invalid_argument naming the parameter, its value and the allowed range.
    explicit SineSweep(const SineSweepParameters& p);
    SweepSample at(double t) const;  // t >= 0; after `duration` the end frequency holds

private:
    SineSweepParameters p_;
};

}  // namespace plate
