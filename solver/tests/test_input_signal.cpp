// InputHistory: the reconstruction of held inputs (docs/theory.md §8, (I.1) and (I.2)).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "InputSignal.h"

namespace {

using plate::InputHistory;
using plate::InputMode;

double quadratic(double t) { return 0.3 - 1.5 * t + 40.0 * t * t; }

// (I.1) on three points of a parabola, at uneven and roundoff-laden spacing, gives its exact
// value, slope and curvature at the newest point (to roundoff: values ~0.3, spacing ~1e-3,
// so divided differences carry ~eps·0.3/1e-6 ~ 1e-10 relative error in the curvature).
TEST(InputHistory, QuadraticExtrapolationIsExactForAParabola) {
    InputHistory h;
    const double times[] = {0.0, 1e-3, 3.0000000000000001e-3, 3.5e-3};
    for (double t : times) h.record(t, quadratic(t));
    const plate::InputSignal s = h.extrapolate(InputMode::Quadratic);
    const double t0 = 3.5e-3;
    EXPECT_NEAR(s.value, quadratic(t0), 1e-15);
    EXPECT_NEAR(s.d1, -1.5 + 80.0 * t0, 1e-9);
    EXPECT_NEAR(s.d2, 80.0, 1e-6);
    const plate::InputSignal lin = h.extrapolate(InputMode::Linear);
    EXPECT_DOUBLE_EQ(lin.d2, 0.0);
    EXPECT_NEAR(lin.d1, (quadratic(3.5e-3) - quadratic(3e-3)) / 0.5e-3, 1e-9);
}

// The order drops while fewer points exist: one point holds, two give a line.
TEST(InputHistory, OrderDropsAtTheStart) {
    InputHistory h;
    h.record(0.0, 2.0);
    plate::InputSignal s = h.extrapolate(InputMode::Quadratic);
    EXPECT_EQ(s.value, 2.0);
    EXPECT_EQ(s.d1, 0.0);
    EXPECT_EQ(s.d2, 0.0);
    h.record(0.5, 3.0);
    s = h.extrapolate(InputMode::Quadratic);
    EXPECT_DOUBLE_EQ(s.d1, 2.0);
    EXPECT_EQ(s.d2, 0.0);
}

// (I.2): the continued signal starts where the last step ended and ends on the extrapolation,
// so the input never jumps; Hold keeps the communicated value.
TEST(InputHistory, ContinuedStepsAreContinuous) {
    InputHistory h;
    const double step = 1e-2;
    double end = 0.0;
    for (int k = 0; k < 20; ++k) {
        const double t = k * step;
        h.record(t, std::sin(5.0 * t));
        const plate::InputSignal s = h.continueStep(InputMode::Quadratic, t, step);
        if (k > 0) EXPECT_EQ(s.value, end) << "jump at step " << k;
        const plate::InputSignal target = h.extrapolate(InputMode::Quadratic);
        EXPECT_NEAR(s.at(step), target.at(step), 1e-15);
        end = s.at(step);
    }
    InputHistory held;
    held.record(0.0, 1.0);
    held.continueStep(InputMode::Hold, 0.0, step);
    held.record(step, 4.0);
    EXPECT_EQ(held.continueStep(InputMode::Hold, step, step).value, 4.0);
}

TEST(InputHistory, SerializationRoundTripAndDamagedData) {
    InputHistory h;
    for (int k = 0; k < 5; ++k) {
        h.record(0.1 * k, 0.7 * k * k);
        h.continueStep(InputMode::Quadratic, 0.1 * k, 0.1);
    }
    std::vector<double> data;
    h.serialize(data);
    ASSERT_EQ(data.size(), static_cast<std::size_t>(InputHistory::kSerializedSize));
    InputHistory back = InputHistory::deserialize(data.data());
    std::vector<double> again;
    back.serialize(again);
    EXPECT_EQ(data, again);
    EXPECT_EQ(back.continueStep(InputMode::Quadratic, 0.4, 0.1).d1, h.continueStep(InputMode::Quadratic, 0.4, 0.1).d1);

    std::vector<double> bad = data;
    bad[0] = 4.0;  // more points than kept
    EXPECT_THROW(InputHistory::deserialize(bad.data()), std::invalid_argument);
    bad = data;
    std::swap(bad[1], bad[3]);  // times out of order: a division by zero or worse later
    EXPECT_THROW(InputHistory::deserialize(bad.data()), std::invalid_argument);
    bad = data;
    bad[2] = std::nan("");
    EXPECT_THROW(InputHistory::deserialize(bad.data()), std::invalid_argument);
    bad = data;
    bad[InputHistory::kSerializedSize - 2] = 0.5;  // the reached flag is 0 or 1
    EXPECT_THROW(InputHistory::deserialize(bad.data()), std::invalid_argument);
}

// A step that starts after the newest point without a fresh one (an early return, then a step
// the master did not set the input for): the reconstruction continues the same polynomial — the
// pieces join into the single step's signal (no kink), where a held value recorded as a new
// sample would bend the parabola at the restart.
TEST(InputHistory, AStepWithoutAFreshValueContinuesThePolynomial) {
    InputHistory whole, split;
    const double step = 1e-2;
    const auto z = [](double t) { return 0.09 * std::sin(2.0 * M_PI * 10.0 * t); };
    for (int k = 0; k < 3; ++k) {
        whole.record(k * step, z(k * step));
        split.record(k * step, z(k * step));
        whole.continueStep(InputMode::Quadratic, k * step, step);
        split.continueStep(InputMode::Quadratic, k * step, step);
    }
    const double t0 = 3 * step, early = 0.37 * step;
    whole.record(t0, z(t0));
    split.record(t0, z(t0));
    const plate::InputSignal one = whole.continueStep(InputMode::Quadratic, t0, step);
    const plate::InputSignal first = split.continueStep(InputMode::Quadratic, t0, step);
    split.reached(first.at(early));  // the step ended early
    const plate::InputSignal rest = split.continueStep(InputMode::Quadratic, t0 + early, step - early);
    EXPECT_NEAR(rest.value, one.at(early), 1e-16);
    EXPECT_NEAR(rest.d1, one.d1 + early * one.d2, 1e-12);  // the slope goes on: no kink
    EXPECT_NEAR(rest.d2, one.d2, 1e-9);
    EXPECT_NEAR(rest.at(step - early), one.at(step), 1e-16);
}

}  // namespace

namespace {

// Found by the property test (python_tests/test_properties.py): values 0, 0, 0.0078 near an
// obstacle at 0.01 extrapolate to 0.0234 by the end of the next step; the reconstruction must
// drop its order rather than drive the clamp past an obstacle the values never passed.
TEST(InputHistory, ReconstructionStaysBetweenTheBounds) {
    InputHistory h;
    const double step = 1e-4, lower = -0.01, upper = 0.01;
    const double values[] = {0.0, 0.0, 0.0078};
    plate::InputSignal s;
    for (int k = 0; k < 3; ++k) {
        h.record(k * step, values[k]);
        s = h.continueStep(InputMode::Quadratic, k * step, step, lower, upper);
    }
    for (int i = 0; i <= 100; ++i) {
        const double x = s.at(step * i / 100.0);
        EXPECT_GE(x, lower);
        EXPECT_LE(x, upper);
    }
    EXPECT_GT(h.extrapolate(InputMode::Quadratic).at(step), upper);  // what the unbounded parabola would do
}

}  // namespace
