#pragma once
// How one communication step of length h maps onto the scheme's fixed grid t_k = k Δt
// (docs/theory.md §15): the internal steps to take, where the inputs' time s starts at the
// first of them (s = offset + k Δt), and whether the step ends on a grid point.

namespace plate {

struct StepPlan {
    long long steps = 0;
    double offset = 0.0;  // t_n − t_c: how far the grid leads the communication time
    double span = 0.0;  // the step as taken: t_c(after) − t_c (h, up to the grid's snap)
    double end = 0.0;  // communication time after the step
    bool endsOnGrid = true;
};

// The plan of a step h from the communication time `now`, the grid standing at step n (on the grid:
// now = n Δt). Throws StepError for a step shorter than the smallest the grid can resolve.
StepPlan planStep(double h, double dt, long long n, double now, bool onGrid);

}  // namespace plate
