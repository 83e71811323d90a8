#pragma once
// The time levels a scheme keeps of a scalar input or sum (t_n, t_{n−1}, t_{n−2}): one step's
// rotation, written once for every scheme.
namespace plate {

inline void advanceLevels(double& now, double& prev, double& prev2, double next) {
    prev2 = prev;
    prev = now;
    now = next;
}

}  // namespace plate
