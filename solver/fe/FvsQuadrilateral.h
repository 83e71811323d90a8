#pragma once
// Reduced Fraeijs de Veubeke–Sanders (FVS) quadrilateral: the composite C1 element of the
// paper's §3.1 (Ciarlet 1978, 1991). Each mesh cell is cut by its two diagonals into four
// sub-triangles; the shape functions are cubic on each sub-triangle, C1 across the four
// internal edges, and their normal derivative is linear along each outer edge ("reduced").
// That leaves 12 local dofs: w, w_x, w_y at the four corners, and makes the space C1 across
// cells, since the trace of w (a cubic) and of its normal derivative (linear) on an outer edge
// are both fixed by the dofs of that edge's two end vertices.
//
// The factory makeFvsSpace(mesh) is declared in FiniteElementSpace.h; this header exposes
// the local construction so the unit tests can check it.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "fe/FiniteElementSpace.h"

namespace plate {

// Local FVS basis on one convex quadrilateral (corners counter-clockwise).
// Piece k is the sub-triangle (corner k, corner k+1, centre), centre = diagonals' intersection.
// Each piece's cubic is stored as monomial coefficients in the scaled coordinates
// (x - centre) / scale, for conditioning.
struct FvsLocalBasis {
    static constexpr int kMonomials = 10;  // cubics in 2D
    static constexpr int kDofs = 12;  // corner k = 0..3, then (w, w_x, w_y)
    using PieceCoefficients = Eigen::Matrix<double, kMonomials, kDofs>;

    std::array<Eigen::Vector2d, 4> corners;
    Eigen::Vector2d centre;
    double scale = 1.0;
    std::array<PieceCoefficients, 4> coefficients;
};

// Builds the basis; throws std::runtime_error if the constrained space is not 12-dimensional
// (a degenerate or non-convex quadrilateral).
FvsLocalBasis buildFvsLocalBasis(const std::array<Eigen::Vector2d, 4>& corners);

// Dimension of the piecewise-cubic space on the diagonal split of the quadrilateral that is
// C1 across the internal edges, with (reduced = true) or without the condition that the
// normal derivative be linear along the outer edges. Expected: 12 reduced, 16 unreduced
// (the full FVS element, whose extra dofs are the four mid-edge normal derivatives).
int fvsLocalSpaceDimension(const std::array<Eigen::Vector2d, 4>& corners, bool reduced);

// The reduced FVS space on the mesh cells. Global dofs 3*v + (0, 1, 2) = w, w_x, w_y at mesh
// vertex v (physical derivatives).
class FvsSpace final : public FiniteElementSpace {
public:
    static constexpr int kLocalDofs = FvsLocalBasis::kDofs;
    static constexpr int kVertexDofs = 3;
    static constexpr int kPieces = 4;

    explicit FvsSpace(const Mesh& mesh);

    ElementType type() const override { return ElementType::Fvs; }
    const Mesh& mesh() const override { return mesh_; }
    Eigen::Index dofCount() const override { return kVertexDofs * static_cast<Eigen::Index>(mesh_.vertexCount()); }
    int elementCount() const override { return static_cast<int>(elements_.size()); }

    // Local order: corner k of cellVertices(c), k = 0..3, then (w, w_x, w_y).
    const std::vector<Eigen::Index>& elementDofs(int element) const override;

    // Composite rule: a degree-6 triangle rule (the mass integrand of cubics; the stiffness
    // one has degree 2) on each sub-triangle, tagged with that piece. A Gauss rule on the
    // whole quadrilateral would straddle the kinks of the second derivatives: inexact.
    std::vector<ElementQuadratureNode> quadrature(int element) const override;

    int elementContaining(const Eigen::Vector2d& x) const override;
    // The sub-triangle containing x; on a border, one of the sharing pieces (the field is C1,
    // so w and its gradient agree; only second derivatives jump between pieces).
    int pieceContaining(int element, const Eigen::Vector2d& x) const override;

    void evaluate(int element, int piece, const Eigen::Vector2d& x, LocalBasis& out) const override;

    Eigen::Index vertexValueDof(int vertex) const override { return kVertexDofs * vertex; }

    // Exact clamp along x = 0: w, w_x, w_y at every clamped vertex. Along a clamped edge w is
    // the cubic Hermite interpolant of (w, w_y) at its ends and w_x the linear interpolant of
    // its end values (the reduced condition), so both vanish identically.
    std::vector<Eigen::Index> clampedDofs() const override;

    const FvsLocalBasis& localBasis(int element) const { return elements_[element]; }

private:
    Mesh mesh_;  // a copy: Mesh is a small value type, so the space cannot dangle
    std::vector<FvsLocalBasis> elements_;
    std::vector<std::vector<Eigen::Index>> elementDofs_;
};

}  // namespace plate
