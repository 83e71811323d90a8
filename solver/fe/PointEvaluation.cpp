#include "fe/PointEvaluation.h"

namespace plate {

PointLocation locate(const FiniteElementSpace& space, const Eigen::Vector2d& x) {
    PointLocation at;
    at.element = space.elementContaining(x);
    at.piece = space.pieceContaining(at.element, x);
    at.point = x;
    return at;
}

PointFunctional pointFunctional(const FiniteElementSpace& space, const PointLocation& at, PointQuantity quantity) {
    LocalBasis basis;
    space.evaluate(at.element, at.piece, at.point, basis);
    const Eigen::VectorXd& row = quantity == PointQuantity::Value ? basis.value
                                 : quantity == PointQuantity::Dxx ? basis.dxx
                                 : quantity == PointQuantity::Dyy ? basis.dyy
                                                                  : basis.dxy;
    PointFunctional f;
    const std::vector<Eigen::Index>& dofs = space.elementDofs(at.element);
    for (std::size_t a = 0; a < dofs.size(); ++a) {
        if (row[Eigen::Index(a)] == 0.0) continue;
        f.dofs.push_back(dofs[a]);
        f.coefficients.push_back(row[Eigen::Index(a)]);
    }
    return f;
}

std::vector<PointLocation> clampedEdgeSamples(const FiniteElementSpace& space) {
    const Mesh& mesh = space.mesh();
    const bool c2AtVertices = space.type() == ElementType::Argyris;
    std::vector<PointLocation> samples;
    for (int j = 0; j < mesh.ny(); ++j) {
        const double y0 = j * mesh.hy(), y1 = (j + 1) * mesh.hy();
        // The element bounded by this edge piece: the one holding its middle (on x = 0 only the
        // element and piece next to the edge contain it).
        const PointLocation middle = locate(space, {0.0, 0.5 * (y0 + y1)});
        for (double y : {y0, 0.5 * (y0 + y1), y1}) {
            if (c2AtVertices && j > 0 && y == y0) continue;  // the vertex the edge below gave
            if (!c2AtVertices && y != y0 && y != y1) continue;  // FVS: w_xx linear there, largest at an end
            PointLocation at = middle;
            at.point = {0.0, y};
            samples.push_back(at);
        }
    }
    return samples;
}

std::vector<PointLocation> vertexSamples(const FiniteElementSpace& space, std::vector<int>& vertexOf) {
    const Mesh& mesh = space.mesh();
    std::vector<PointLocation> samples;
    vertexOf.clear();
    for (int v = 0; v < mesh.vertexCount(); ++v) {
        samples.push_back(locate(space, mesh.point(v)));
        vertexOf.push_back(v);
    }
    return samples;
}

}  // namespace plate
