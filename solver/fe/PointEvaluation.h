#pragma once
// Where a point of the plate lies in the space and the linear functionals of the field there: w and
// its second derivatives (the curvatures of docs/theory.md §23), over the space's global dofs. The
// probes and the stress recovery are built from these; nothing here knows a scheme.
#include <Eigen/Core>
#include <vector>

#include "fe/FiniteElementSpace.h"

namespace plate {

// Which quantity of the field a functional gives at its point.
enum class PointQuantity { Value, Dxx, Dyy, Dxy };

// An element (and its polynomial piece) that holds a point, and the point.
struct PointLocation {
    int element = 0, piece = 0;
    Eigen::Vector2d point = Eigen::Vector2d::Zero();
};

// A linear functional Σ coefficient_k · u[dof_k] over the global dofs.
struct PointFunctional {
    std::vector<Eigen::Index> dofs;
    std::vector<double> coefficients;
};

// The element and piece holding x (on a border: one of those sharing it; w and its gradient agree
// there, the second derivatives of a C1 field may not). x must lie in the plate (callers check).
PointLocation locate(const FiniteElementSpace& space, const Eigen::Vector2d& x);

// The quantity at the location, evaluated with the element's own shape functions.
PointFunctional pointFunctional(const FiniteElementSpace& space, const PointLocation& at, PointQuantity quantity);

// The stress samples of the clamped edge x = 0 (docs/theory.md §23): each element edge on it
// evaluated in the element it bounds — Argyris (w_xx a cubic in y there, C2 at the vertices): its
// ends, each vertex once, and its middle; FVS (w_xx linear along it, jumping between cells): its two
// ends. Ordered by y.
std::vector<PointLocation> clampedEdgeSamples(const FiniteElementSpace& space);

// The stress samples of every mesh vertex, one each: the element and piece `locate` gives. Argyris is
// C2 at its vertices (the curvatures are dofs: every element agrees); the FVS curvatures jump
// between elements and sub-triangles, so its vertex values are those of that one piece (every piece
// would cost eight times the rows, dense over every mode in the modal and condensed engines).
// `vertexOf[k]` is the vertex of sample k.
std::vector<PointLocation> vertexSamples(const FiniteElementSpace& space, std::vector<int>& vertexOf);

}  // namespace plate
