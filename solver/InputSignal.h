#pragma once
// An input of the plate over one communication step, and its causal reconstruction when the
// master gives only values (docs/theory.md, "Inputs between communication points").
#include <array>
#include <cmath>
#include <vector>

namespace plate {

// An input over one communication step: value and time derivatives at its start; inside the
// step it follows value + d1 s + d2 s^2 / 2 (FMI input-derivative interpolation), plus
// d3 s^3 / 6 + d4 s^4 / 24 for a clamp position integrated from a velocity or an acceleration
// input (docs/theory.md §16).
struct InputSignal {
    double value = 0.0, d1 = 0.0, d2 = 0.0, d3 = 0.0, d4 = 0.0;
    double at(double s) const {
        const double quadratic = value + s * (d1 + 0.5 * s * d2);
        if (d3 == 0.0 && d4 == 0.0) return quadratic;
        return quadratic + s * s * s * (d3 / 6.0 + s * d4 / 24.0);
    }
    // The integral from 0 to s, starting at `start`: the signal of the integrated quantity.
    InputSignal integral(double start) const { return {start, value, d1, d2, d3}; }
    // The same polynomial seen from s0 on (its Taylor coefficients at s0): a step that starts
    // s0 after the signal's own start continues it (an early return, a step without a fresh
    // set). s0 = 0 gives the signal itself, bit for bit.
    InputSignal shifted(double s0) const {
        if (s0 == 0.0) return *this;
        return {at(s0), d1 + s0 * (d2 + s0 * (0.5 * d3 + s0 * d4 / 6.0)), d2 + s0 * (d3 + 0.5 * s0 * d4), d3 + s0 * d4,
                d4};
    }
};

// How an input held by the master over a communication step is continued inside it.
//  Hold       value constant over the step (a staircase).
//  Linear     slope of the line through the last two communicated points.
//  Quadratic  value, slope and curvature of the parabola through the last three points.
// With fewer points recorded (the first steps, after a reset) the order drops to what they
// support. Derivatives the master sets itself always take precedence (the FMU layer decides).
enum class InputMode { Hold = 1, Linear = 2, Quadratic = 3 };

// The last three communicated points (t, value) of one input, newest first, the polynomial
// extrapolation through them (Newton's divided differences, any spacing), and where the
// reconstructed input stood at the end of the last step.
class InputHistory {
public:
    static constexpr int kCapacity = 3;

    // Records the value communicated at communication point t. A point at the time of the
    // newest one replaces it (the master set the input again before stepping).
    void record(double t, double value);
    int count() const { return count_; }
    // The polynomial of degree min(order(mode), count-1) through the newest points, from the
    // newest point on.
    InputSignal extrapolate(InputMode mode) const;

    // The signal for the step of length h that starts at `now`, at or after the newest point
    // (docs/theory.md, "Inputs between communication points": the samples the master set, at
    // the times it set them; a step that starts after the newest point continues the same
    // polynomial). Hold: the newest value. Linear, Quadratic:
    // the extrapolation, made continuous — the step starts where the input ended the last
    // step and the miss (newest value − that end) is spread over the step as a slope miss/h,
    // so the input never jumps (a jump Δz of the clamp is a velocity kick Δz/Δt on one
    // internal step). Where that signal would leave [lower, upper] inside the step (an
    // extrapolated clamp past an obstacle the master's values never passed), the order drops
    // (quadratic → linear → hold) until it stays. Remembers where this step ends.
    // `reach` (≥ h when given): how far into the step the signal is read — beyond h when the grid
    // point ahead of a short step lies past its end; the miss is spread over max(h, reach).
    InputSignal continueStep(InputMode mode, double now, double h, double lower = -HUGE_VAL, double upper = HUGE_VAL,
                             double reach = 0.0);
    // Where the input ended the last step taken through continueStep (no step yet: none).
    bool hasReached() const { return hasReached_; }
    double reachedValue() const { return reached_; }  // where, when hasReached()
    // Records where the input ended a step that the master's derivatives drove.
    void reached(double value) {
        reached_ = value;
        hasReached_ = true;
    }

    // Fixed-size flat form for FMU states: count, (t, value) for kCapacity points, the
    // reached flag and value.
    static constexpr int kSerializedSize = 1 + 2 * kCapacity + 2;
    void serialize(std::vector<double>& out) const;
    // Throws std::invalid_argument for a count out of range or non-finite recorded points.
    static InputHistory deserialize(const double* data);

private:
    int count_ = 0;
    std::array<double, kCapacity> t_{}, value_{};
    bool hasReached_ = false;  // where the input ended the last step through continueStep is known
    double reached_ = 0.0;
};

}  // namespace plate
