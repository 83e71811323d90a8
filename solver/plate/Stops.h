#pragma once
// Where the obstacles are (docs/theory.md §25): each obstacle covers a stop, a rectangle of the
// plate, and holds the contact points (mesh vertices off the clamped edge) inside it. Only those
// points are contact rows: the QP, the condensed operators and the row space are built for them.
#include <Eigen/Core>

#include "plate/Obstacles.h"
#include "plate/PlateParameters.h"

namespace plate {

// Which present obstacles' stops cover a point of the plate (StopBits). With no obstacle present
// every point carries both bits: there is nothing to hold, and the plate keeps a row at every
// vertex as it had before stops (its outputs bit for bit).
class StopMap {
public:
    StopMap(const ObstacleParameters& obstacles, const MeshParameters& mesh);
    unsigned char at(const Eigen::Vector2d& x) const;
    // Whether the present obstacles' stops cover every point of the plate (the rows are every vertex).
    bool wholePlate() const { return whole_; }

private:
    ObstacleParameters o_;
    double slack_;  // a vertex on a stop's edge is under it, whatever the roundoff of i·length/nx
    bool whole_;
};

// The heights and which of them hold the clamp (a stop that reaches x = 0).
Obstacles obstaclesOf(const ObstacleParameters& obstacles);

// Throws ParameterError unless each present obstacle's stop is a rectangle (min ≤ max) that meets
// the plate and holds a contact point; the message names the nearest contact point.
void validateStops(const ObstacleParameters& obstacles, const MeshParameters& mesh);

// Throws ParameterError unless the plate, flat at the clamp's height baseDisplacement0, starts
// between the obstacles (under a stop that does not reach the clamp: the plate there is outside).
void requireStartBetween(const Obstacles& obstacles, double baseDisplacement0);

}  // namespace plate
