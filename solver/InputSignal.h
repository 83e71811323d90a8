#pragma once
// An input of the plate over one communication step, and its causal reconstruction when the
// master gives only values (docs/theory.md, "Inputs between communication points").
#include <array>
#include <vector>

namespace plate {

// An input over one communication step: value and time derivatives at its start; inside the
// step it follows value + d1 s + d2 s^2 / 2 (FMI input-derivative interpolation).
struct InputSignal {
    double value = 0.0, d1 = 0.0, d2 = 0.0;
    double at(double s) const { return value + s * (d1 + 0.5 * s * d2); }
};

// How an input held by the master over a communication step is continued inside it.
//  Hold       value constant over the step (a staircase).
//  Linear     slope of the line through the last two communicated points.
//  Quadratic  value, slope and curvature of the parabola through the last three points.
// With fewer points recorded (the first steps, after a reset) the order drops to what they
// support. Derivatives the master sets itself always take precedence (the FMU layer decides).
enum class InputMode { Hold = 1, Linear = 2, Quadratic = 3 };

// The last three communicated points (t, value) of one input, newest first, and the
// polynomial extrapolation through them (Newton's divided differences, any spacing).
class InputHistory {
public:
    static constexpr int kCapacity = 3;

    // Records the value communicated at communication point t. A point at the time of the
    // newest one replaces it (the master set the input again before stepping).
    void record(double t, double value);
    void clear() { count_ = 0; }
    int count() const { return count_; }

    // The signal from the newest point on: polynomial of degree min(order(mode), count-1).
    InputSignal extrapolate(InputMode mode) const;

    // Fixed-size flat form for FMU states: count, then (t, value) for kCapacity points.
    static constexpr int kSerializedSize = 1 + 2 * kCapacity;
    void serialize(std::vector<double>& out) const;
    // Throws std::invalid_argument for a count out of range or non-finite recorded points.
    static InputHistory deserialize(const double* data);

private:
    int count_ = 0;
    std::array<double, kCapacity> t_{}, value_{};
};

}  // namespace plate
