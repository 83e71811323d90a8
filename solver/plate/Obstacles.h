#pragma once
// The two flat obstacles as absolute heights; an absent one is at ±infinity.
#include <cmath>
#include <limits>

namespace plate {

struct Obstacles {
    double lower = -std::numeric_limits<double>::infinity();  // absolute height, m
    double upper = std::numeric_limits<double>::infinity();
    bool any() const { return std::isfinite(lower) || std::isfinite(upper); }
};

}  // namespace plate
