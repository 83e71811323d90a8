#include "InputSignal.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace plate {

void InputHistory::record(double t, double value) {
    if (count_ > 0 && t == t_[0]) {
        value_[0] = value;
        return;
    }
    for (int i = kCapacity - 1; i > 0; --i) {
        t_[i] = t_[i - 1];
        value_[i] = value_[i - 1];
    }
    t_[0] = t;
    value_[0] = value;
    if (count_ < kCapacity) ++count_;
}

InputSignal InputHistory::extrapolate(InputMode mode) const {
    InputSignal s;
    if (count_ == 0) return s;
    s.value = value_[0];
    const int degree = std::min(static_cast<int>(mode) - 1, count_ - 1);
    if (degree >= 1) {
        // p(t) = v0 + [t0,t1](t - t0) + [t0,t1,t2](t - t0)(t - t1), so at t0:
        // p' = [t0,t1] + [t0,t1,t2](t0 - t1), p'' = 2 [t0,t1,t2] (docs/theory.md, eq. (I.1)).
        const double d01 = (value_[0] - value_[1]) / (t_[0] - t_[1]);
        s.d1 = d01;
        if (degree >= 2) {
            const double d12 = (value_[1] - value_[2]) / (t_[1] - t_[2]);
            const double d012 = (d01 - d12) / (t_[0] - t_[2]);
            s.d1 += d012 * (t_[0] - t_[1]);
            s.d2 = 2.0 * d012;
        }
    }
    return s;
}

namespace {

// Whether value + d1 τ + d2 τ²/2 stays in [lower, upper] for τ in [0, h] (ends and vertex).
bool staysWithin(const InputSignal& s, double h, double lower, double upper) {
    const auto inside = [&](double x) { return x >= lower && x <= upper; };
    if (!inside(s.value) || !inside(s.at(h))) return false;
    if (s.d2 != 0.0) {
        const double vertex = -s.d1 / s.d2;
        if (vertex > 0.0 && vertex < h && !inside(s.at(vertex))) return false;
    }
    return true;
}

}  // namespace

InputSignal InputHistory::continueStep(InputMode mode, double now, double h, double lower, double upper, double reach) {
    const double since = count_ > 0 ? now - t_[0] : 0.0;  // how far the step starts after the newest point
    // The miss is spread over the step, or over as far as the signal is read when that is farther
    // (a step much shorter than the internal one, read at the grid point ahead): a slope miss/h
    // read at Δt ≫ h would throw the input by miss·Δt/h.
    const double span = std::max(h, reach);
    for (int order = static_cast<int>(mode);; --order) {
        const InputMode m = static_cast<InputMode>(order);
        InputSignal s = extrapolate(m).shifted(since);
        if (m != InputMode::Hold && hasReached_) {
            s.d1 += (s.value - reached_) / span;  // start where the input is, end on the extrapolation
            s.value = reached_;
        }
        if (m == InputMode::Hold || staysWithin(s, span, lower, upper)) {
            reached(s.at(h));
            return s;
        }
    }
}

void InputHistory::serialize(std::vector<double>& out) const {
    out.push_back(double(count_));
    for (int i = 0; i < kCapacity; ++i) {
        out.push_back(i < count_ ? t_[i] : 0.0);
        out.push_back(i < count_ ? value_[i] : 0.0);
    }
    out.push_back(hasReached_ ? 1.0 : 0.0);
    out.push_back(reached_);
}

InputHistory InputHistory::deserialize(const double* data) {
    InputHistory h;
    const double count = data[0];
    if (!(count >= 0 && count <= kCapacity) || std::floor(count) != count)
        throw std::invalid_argument("input history: point count out of range");
    h.count_ = static_cast<int>(count);
    for (int i = 0; i < kCapacity; ++i) {
        const double t = data[1 + 2 * i], v = data[2 + 2 * i];
        if (!std::isfinite(t) || !std::isfinite(v))
            throw std::invalid_argument("input history: a recorded point is not finite");
        if (i < h.count_) {
            h.t_[i] = t;
            h.value_[i] = v;
            // Strictly decreasing times: the divided differences never divide by zero.
            if (i > 0 && !(t < h.t_[i - 1]))
                throw std::invalid_argument("input history: times not strictly decreasing");
        }
    }
    const double flag = data[1 + 2 * kCapacity], reachedValue = data[2 + 2 * kCapacity];
    if (!(flag == 0.0 || flag == 1.0) || !std::isfinite(reachedValue))
        throw std::invalid_argument("input history: bad end-of-step value");
    h.hasReached_ = flag == 1.0;
    h.reached_ = reachedValue;
    return h;
}

}  // namespace plate
