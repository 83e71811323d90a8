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
        const Eigen::Vector2d x = mesh.point(v);
        if (space.type() == ElementType::Argyris) {
            samples.push_back(locate(space, x));
            vertexOf.push_back(v);
            continue;
        }
        // FVS: the cells around the vertex; corner k of a cell lies in its pieces k and k − 1.
        const int i = mesh.vertexColumn(v), j = mesh.vertexRow(v);
        for (int ci = i - 1; ci <= i; ++ci) {
            for (int cj = j - 1; cj <= j; ++cj) {
                if (ci < 0 || cj < 0 || ci >= mesh.nx() || cj >= mesh.ny()) continue;
                const int c = mesh.cell(ci, cj);
                const std::array<int, 4> corners = mesh.cellVertices(c);
                for (int k = 0; k < 4; ++k) {
                    if (corners[std::size_t(k)] != v) continue;
                    for (int piece : {k, (k + 3) % 4}) {
                        samples.push_back({c, piece, x});
                        vertexOf.push_back(v);
                    }
                }
            }
        }
    }
    return samples;
}

}  // namespace plate
