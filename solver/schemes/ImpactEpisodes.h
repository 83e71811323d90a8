#pragma once
// Impact episodes per obstacle (docs/theory.md §14): what a person counts as one impact on a
// corner's plot. An episode starts when the plate touches an obstacle after the whole plate was free
// of that obstacle for at least a quarter of its first natural period, T1/4 = 1/(4 f1): the plate
// as a whole cannot leave an obstacle and come back in less (a free rebound of its first mode is
// away about T1/2), while the chatter of single vertices inside one contact (the higher modes) parts
// for far less. Counted after every internal step from the scheme's contact sums; no allocation.
#include <cmath>

#include "schemes/Scheme.h"

namespace plate {

struct ImpactEpisodes {
    long long gapSteps = 1;  // internal steps the plate must be free of an obstacle: ceil(T1/4 / dt)
    long long freeSteps[2] = {-1, -1};  // steps since it last touched each obstacle; -1: never
    long long episodes[2] = {0, 0};
    long long onsetsSeen[2] = {0, 0};  // the scheme's contact onsets after the last step counted

    ImpactEpisodes() = default;
    ImpactEpisodes(double firstFrequency, double dt)
        : gapSteps(std::max(1LL, static_cast<long long>(std::ceil(0.25 / (firstFrequency * dt))))) {}

    // After each internal step: the plate touched obstacle k in it if its contact force is not zero
    // at the step's end or a contact started inside it (the flow law's sub-steps may touch and leave).
    void count(const Scheme& scheme) {
        for (int k = 0; k < 2; ++k) {
            const long long onsets = scheme.contactOnsets(k);
            const bool touched = scheme.contactForce(k) != 0.0 || onsets != onsetsSeen[k];
            onsetsSeen[k] = onsets;
            if (touched) {
                if (freeSteps[k] < 0 || freeSteps[k] >= gapSteps) ++episodes[k];
                freeSteps[k] = 0;
            } else if (freeSteps[k] >= 0) {
                ++freeSteps[k];
            }
        }
    }
};

}  // namespace plate
