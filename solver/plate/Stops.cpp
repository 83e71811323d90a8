#include "plate/Stops.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "base/Errors.h"

namespace plate {

namespace {

constexpr double kSlack = 1e-9;  // relative to the plate's size: far above i·length/nx's roundoff

bool covers(const ObstacleParameters::StopRect& r, const Eigen::Vector2d& x, double slack) {
    return x.x() >= r.xMin - slack && x.x() <= r.xMax + slack && x.y() >= r.yMin - slack && x.y() <= r.yMax + slack;
}

// The distance from a point to a rectangle (0 inside it).
double distance(const ObstacleParameters::StopRect& r, const Eigen::Vector2d& x) {
    const double dx = std::max({r.xMin - x.x(), 0.0, x.x() - r.xMax});
    const double dy = std::max({r.yMin - x.y(), 0.0, x.y() - r.yMax});
    return std::hypot(dx, dy);
}

}  // namespace

StopMap::StopMap(const ObstacleParameters& o, const MeshParameters& mesh)
    : o_(o), slack_(kSlack * std::max(mesh.length, mesh.width)), whole_(true) {
    for (int k = 0; k < 2; ++k) {
        const auto& r = o.stop(k);
        if (o.present(k))
            whole_ = whole_ && r.xMin <= 0.0 && r.yMin <= 0.0 && r.xMax >= mesh.length && r.yMax >= mesh.width;
    }
}

unsigned char StopMap::at(const Eigen::Vector2d& x) const {
    if (!o_.present(0) && !o_.present(1)) return kUnderBoth;
    unsigned char bits = 0;
    if (o_.present(0) && covers(o_.lowerStop, x, slack_)) bits |= kUnderLower;
    if (o_.present(1) && covers(o_.upperStop, x, slack_)) bits |= kUnderUpper;
    return bits;
}

Obstacles obstaclesOf(const ObstacleParameters& p) {
    Obstacles o;
    if (p.lowerEnabled) o.lower = p.lower;
    if (p.upperEnabled) o.upper = p.upper;
    o.lowerAtClamp = p.lowerStop.xMin <= 0.0;
    o.upperAtClamp = p.upperStop.xMin <= 0.0;
    return o;
}

void validateStops(const ObstacleParameters& o, const MeshParameters& mesh) {
    const char* names[2] = {"obstacle_lower", "obstacle_upper"};
    const double slack = kSlack * std::max(mesh.length, mesh.width);
    for (int k = 0; k < 2; ++k) {
        if (!o.present(k)) continue;
        const ObstacleParameters::StopRect& r = o.stop(k);
        const std::string n = names[k];
        std::ostringstream msg;
        msg.precision(15);
        msg << "invalid stop of " << n << ": " << n << "_x_min..x_max = " << r.xMin << ".." << r.xMax << ", " << n
            << "_y_min..y_max = " << r.yMin << ".." << r.yMax << " m (allowed: ";
        const double coordinates[4] = {r.xMin, r.xMax, r.yMin, r.yMax};
        for (double c : coordinates)
            if (!ranges::kStopCoordinate.contains(c))
                throw ParameterError(msg.str() + "every edge in [0, 1e4] m; 1e4 reaches past any plate)");
        if (r.xMin > r.xMax || r.yMin > r.yMax) throw ParameterError(msg.str() + "x_min <= x_max and y_min <= y_max)");
        if (r.xMin > mesh.length + slack || r.yMin > mesh.width + slack) {
            msg << "a rectangle that meets the plate [0, " << mesh.length << "] x [0, " << mesh.width << "] m)";
            throw ParameterError(msg.str());
        }
        // The contact points: vertex (i, j) at (i length/nx, j width/ny), i ≥ 1 (Mesh.h).
        Eigen::Vector2d nearest(0.0, 0.0);
        double best = HUGE_VAL;
        for (int i = 1; i <= mesh.nx && best > 0.0; ++i)
            for (int j = 0; j <= mesh.ny && best > 0.0; ++j) {
                const Eigen::Vector2d x(i * (mesh.length / mesh.nx), j * (mesh.width / mesh.ny));
                const double d = covers(r, x, slack) ? 0.0 : distance(r, x);
                if (d < best) best = d, nearest = x;
            }
        if (best > 0.0) {
            msg << "a rectangle holding at least one contact point, a mesh vertex (i length/nx, j width/ny) with i >= "
                   "1; "
                << "the nearest to this one is (" << nearest.x() << ", " << nearest.y() << ") m)";
            throw ParameterError(msg.str());
        }
    }
}

void requireStartBetween(const Obstacles& obstacles, double baseDisplacement0) {
    if (std::isfinite(baseDisplacement0) && baseDisplacement0 >= obstacles.lower &&
        baseDisplacement0 <= obstacles.upper)
        return;
    std::ostringstream msg;
    msg.precision(15);  // round-trips what users type (0.7, not 0.69999999999999996)
    // The plate starts flat at the clamp's height: what is refused is the plate under the stop, which
    // reaches the clamped edge or not (a tip stop: issue 71's user read the clamp blamed).
    const bool below = !(baseDisplacement0 >= obstacles.lower);
    const bool atClamp = below ? obstacles.lowerAtClamp : obstacles.upperAtClamp;
    msg << "invalid initial state: base_displacement = " << baseDisplacement0
        << " starts the plate flat at that height, " << (below ? "below obstacle_lower = " : "above obstacle_upper = ")
        << (below ? obstacles.lower : obstacles.upper)
        << (atClamp ? " (its stop covers the clamped edge)"
                    : " under that obstacle's stop (which does not reach the clamped edge: the plate there, not the "
                      "clamp, is outside)")
        << " (allowed: obstacle_lower = " << obstacles.lower
        << " <= base_displacement <= obstacle_upper = " << obstacles.upper << " at the start)";
    throw ParameterError(msg.str());
}

}  // namespace plate
