#pragma once
// The two flat obstacles as absolute heights; an absent one is at ±infinity. Each covers a stop of
// the plate (docs/theory.md §25): the contact rows it holds carry its bit (StopBits), the others
// are free of it, and the clamp is held between the obstacles whose stops reach the clamped edge.
#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <vector>

#include "fe/StopBits.h"

namespace plate {

struct Obstacles {
    double lower = -std::numeric_limits<double>::infinity();  // absolute height, m
    double upper = std::numeric_limits<double>::infinity();
    // Whether each obstacle's stop reaches the clamped edge x = 0 (a whole-plate obstacle does).
    bool lowerAtClamp = true, upperAtClamp = true;
    bool any() const { return std::isfinite(lower) || std::isfinite(upper); }
    // The bounds on the clamp's height: the obstacles under whose stops it moves.
    double clampLower() const { return lowerAtClamp ? lower : -std::numeric_limits<double>::infinity(); }
    double clampUpper() const { return upperAtClamp ? upper : std::numeric_limits<double>::infinity(); }
    // The absolute bounds of each contact row: the height of an obstacle whose stop covers it, ±∞
    // where none does (the row is then free of that obstacle).
    void rowBounds(const std::vector<unsigned char>& stops, Eigen::VectorXd& rowLower,
                   Eigen::VectorXd& rowUpper) const {
        const auto n = static_cast<Eigen::Index>(stops.size());
        rowLower.resize(n);
        rowUpper.resize(n);
        for (Eigen::Index i = 0; i < n; ++i) {
            const unsigned char bits = stops[static_cast<std::size_t>(i)];
            rowLower[i] = (bits & kUnderLower) ? lower : -std::numeric_limits<double>::infinity();
            rowUpper[i] = (bits & kUnderUpper) ? upper : std::numeric_limits<double>::infinity();
        }
    }
};

}  // namespace plate
