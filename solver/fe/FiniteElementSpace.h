#pragma once
// The C1 finite element space V^h of §3.1 seen through one interface, so that the assembly,
// the contact stepper and the probes never know which element they hold.
//
// Global degrees of freedom are physical quantities (values and derivatives in x, y), so a
// space is C1 across elements by construction of its local bases. Every space has one
// "vertex value" dof per mesh vertex: contact is enforced on those (docs/theory.md).
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "fe/Mesh.h"
#include "fe/Quadrature.h"

namespace plate {

enum class ElementType { Argyris, Fvs };

// Local shape functions of one element evaluated at one point, in physical derivatives.
struct LocalBasis {
    Eigen::VectorXd value, dx, dy, dxx, dxy, dyy;
};

// A quadrature node tagged with the polynomial piece it belongs to (FVS is a composite
// element: the piece is its sub-triangle; Argyris has one piece).
struct ElementQuadratureNode {
    Eigen::Vector2d point;
    double weight;
    int piece;
};

class FiniteElementSpace {
public:
    virtual ~FiniteElementSpace() = default;

    virtual ElementType type() const = 0;
    virtual const Mesh& mesh() const = 0;
    virtual Eigen::Index dofCount() const = 0;
    virtual int elementCount() const = 0;

    // Global dofs of the element's local shape functions, in local order.
    virtual const std::vector<Eigen::Index>& elementDofs(int element) const = 0;

    // Rule exact for the mass (degree 2p) and stiffness integrands of the element.
    virtual std::vector<ElementQuadratureNode> quadrature(int element) const = 0;

    // Element and piece containing a point of the plate.
    virtual int elementContaining(const Eigen::Vector2d& x) const = 0;
    virtual int pieceContaining(int element, const Eigen::Vector2d& x) const = 0;

    // Local shape functions (and their derivatives up to order 2) at x on the given piece.
    virtual void evaluate(int element, int piece, const Eigen::Vector2d& x, LocalBasis& out) const = 0;

    // The dof holding w at mesh vertex v.
    virtual Eigen::Index vertexValueDof(int vertex) const = 0;

    // Dofs fixed by the exact clamp along x = 0 (docs/theory.md: for Argyris w_xx stays free).
    virtual std::vector<Eigen::Index> clampedDofs() const = 0;
};

std::unique_ptr<FiniteElementSpace> makeArgyrisSpace(const Mesh& mesh);
std::unique_ptr<FiniteElementSpace> makeFvsSpace(const Mesh& mesh);
std::unique_ptr<FiniteElementSpace> makeSpace(ElementType type, const Mesh& mesh);

// The plate's rectangle and its mesh (PlateParameters' mesh part): what makeSpace builds a space of.
struct MeshParameters {
    double length = 1.2, width = 0.4;  // m
    int nx = 14, ny = 5;
    ElementType element = ElementType::Argyris;
};
inline std::unique_ptr<FiniteElementSpace> makeSpace(const MeshParameters& m) {
    return makeSpace(m.element, Mesh(m.length, m.width, m.nx, m.ny));
}

}  // namespace plate
