#pragma once
// The Argyris P5 triangle (§3.1 of the paper; Ciarlet, "The Finite Element Method for Elliptic
// Problems", §2.2, Theorem 2.2.8 and §6.1) on the mesh triangles, as a C1 space V^h.
//
// Global dofs (all physical quantities, so C1 continuity comes from the local bases alone):
//   6*v + k, k = 0..5     at mesh vertex v: w, w_x, w_y, w_xx, w_xy, w_yy;
//   6*nVertices + e       for mesh edge e: the normal derivative ∂w/∂n at the edge midpoint,
//                         along the edge's GLOBAL normal n = rot(-90°) t, t the unit tangent
//                         from its lower-index vertex to its higher-index vertex.
// On an edge the P5 trace is fixed by (w, w_t, w_tt) at both ends and the P4 normal derivative
// by (w_n, w_nt) at both ends plus the midpoint value; all are shared, so the field is C1.
//
// Local shape functions live in physical coordinates (no reference map: the Argyris element
// is not affine-equivalent, Ciarlet §6.1), as monomials in the scaled coordinates
// ξ = (x - x_c)/h, η = (y - y_c)/h. Local shape function i is dual to global dof
// elementDofs(t)[i], with the global normal orientation inside the functional.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "fe/FiniteElementSpace.h"

namespace plate {

class ArgyrisSpace final : public FiniteElementSpace {
public:
    static constexpr int kLocalDofs = 21;
    static constexpr int kVertexDofs = 6;  // w, w_x, w_y, w_xx, w_xy, w_yy
    using LocalMatrix = Eigen::Matrix<double, kLocalDofs, kLocalDofs>;

    explicit ArgyrisSpace(const Mesh& mesh);

    ElementType type() const override { return ElementType::Argyris; }
    const Mesh& mesh() const override { return mesh_; }
    Eigen::Index dofCount() const override { return dofCount_; }
    int elementCount() const override { return static_cast<int>(elements_.size()); }

    // Local order: vertices 0, 1, 2 of triangleVertices(t) x (w, w_x, w_y, w_xx, w_xy, w_yy),
    // then the mid-edge dofs of the local edges (v0 v1), (v1 v2), (v2 v0).
    const std::vector<Eigen::Index>& elementDofs(int element) const override;

    // One piece; degree 10 = the mass integrand (the stiffness one has degree 6).
    std::vector<ElementQuadratureNode> quadrature(int element) const override;

    int elementContaining(const Eigen::Vector2d& x) const override;
    int pieceContaining(int, const Eigen::Vector2d&) const override { return 0; }

    void evaluate(int element, int piece, const Eigen::Vector2d& x, LocalBasis& out) const override;

    Eigen::Index vertexValueDof(int vertex) const override { return kVertexDofs * vertex; }

    // Exact clamp along x = 0: w, w_x, w_y, w_xy, w_yy at clamped vertices (w_xx free:
    // docs/theory.md, fixing it over-stiffens) and the mid-edge dof of every edge on x = 0.
    std::vector<Eigen::Index> clampedDofs() const override;

    // Mesh edges, in order of first appearance over (triangle, local edge).
    int edgeCount() const { return static_cast<int>(edges_.size()); }
    // Vertices of the edge, lower index first (the orientation of its global normal).
    const std::array<int, 2>& edgeVertices(int edge) const { return edges_[edge]; }
    // The global unit normal of the edge, rot(-90°) of the lower-to-higher tangent.
    Eigen::Vector2d edgeNormal(int edge) const;
    Eigen::Index edgeDof(int edge) const { return kVertexDofs * static_cast<Eigen::Index>(mesh_.vertexCount()) + edge; }

    // The scaled dof matrix V[i][j] = h^{d_i} dof_i(monomial_j) of an element (d_i the
    // derivative order of dof i), whose inverse gives the local basis. Exposed for diagnostics
    // (its condition number) and tests.
    LocalMatrix scaledDofMatrix(int element) const;

private:
    struct Element {
        Eigen::Vector2d centroid;
        double h;  // scaling length: the longest edge
        std::array<int, 3> edges;  // global edge of local edge (v0 v1), (v1 v2), (v2 v0)
        // Column j = monomial coefficients of local shape function j, already multiplied by
        // h^{d_j} so that it is dual to the unscaled (physical) dof.
        LocalMatrix coefficients;
    };

    Mesh mesh_;  // a copy: Mesh is a small value type, so the space cannot dangle
    std::vector<Element> elements_;
    std::vector<std::vector<Eigen::Index>> elementDofs_;
    std::vector<std::array<int, 2>> edges_;
    Eigen::Index dofCount_ = 0;
};

}  // namespace plate
