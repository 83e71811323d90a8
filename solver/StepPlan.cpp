#include "StepPlan.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <sstream>

#include "base/Errors.h"

namespace plate {

namespace {

// A communication step that is a whole multiple of Δt up to this relative tolerance runs on the
// grid (importers' step sizes wobble in the last digits).
constexpr double kStepMultipleTolerance = 1e-9;
// A communication time within this fraction of Δt of a grid point is that grid point (§15); it
// is also the shortest step: anything shorter cannot be told from no step at all.
constexpr double kGridSnap = 1e-9;

}  // namespace

StepPlan planStep(double h, double dt, long long n, double now, bool onGrid) {
    StepPlan p;
    // On the grid, a whole multiple of Δt (importers' steps wobble in the last digits): the grid
    // steps, the inputs' time s = k Δt exactly as the scheme has always taken them.
    const double ratio = h / dt;
    const long long whole = ratio < 9.0e15 ? std::llround(ratio) : 0;
    if (onGrid && whole >= 1 && std::fabs(double(whole) * dt - h) <= kStepMultipleTolerance * h) {
        p.steps = whole;
        p.end = double(n + whole) * dt;
        p.span = double(whole) * dt;
        return p;
    }
    // Any other step: the grid leads the communication time by less than Δt (§15).
    const double snap = std::max(kGridSnap * dt, 4.0 * DBL_EPSILON * (now + h));
    if (!(h >= snap) || !std::isfinite(h)) {
        std::ostringstream msg;
        msg.precision(17);
        msg << "communicationStepSize h = " << h << " is shorter than the smallest step the grid of dt = " << dt
            << " resolves (allowed: h >= " << snap << " s = 1e-9 dt)";
        throw StepError(msg.str());
    }
    const double end = now + h;
    const double grid = end / dt;
    long long target = std::llround(grid);
    p.endsOnGrid = std::fabs(double(target) * dt - end) <= snap;
    if (!p.endsOnGrid) target = static_cast<long long>(std::ceil(grid));
    p.steps = std::max(0LL, target - n);
    p.offset = double(n) * dt - now;
    p.end = p.endsOnGrid ? double(target) * dt : end;
    p.span = p.end - now;
    return p;
}

}  // namespace plate
