#include "fe/FvsQuadrilateral.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace plate {

namespace {

constexpr int kM = FvsLocalBasis::kMonomials;
constexpr int kPieces = 4;
constexpr int kCoefficients = kPieces * kM;  // 40 unknowns of the composite cubic

using Row = Eigen::Matrix<double, 1, kM>;
using Mono = Eigen::Matrix<double, kM, 1>;

// Cubic monomials in the scaled coordinates (s, t), in the order
// 1, s, t, s^2, st, t^2, s^3, s^2 t, s t^2, t^3, and their derivatives.
struct Monomials {
    Mono v, ds, dt, dss, dst, dtt;
};

void monomials(const Eigen::Vector2d& p, Monomials& m) {
    const double s = p.x(), t = p.y();
    m.v << 1, s, t, s * s, s * t, t * t, s * s * s, s * s * t, s * t * t, t * t * t;
    m.ds << 0, 1, 0, 2 * s, t, 0, 3 * s * s, 2 * s * t, t * t, 0;
    m.dt << 0, 0, 1, 0, s, 2 * t, 0, s * s, 2 * s * t, 3 * t * t;
    m.dss << 0, 0, 0, 2, 0, 0, 6 * s, 2 * t, 0, 0;
    m.dst << 0, 0, 0, 0, 1, 0, 0, 2 * s, 2 * t, 0;
    m.dtt << 0, 0, 0, 0, 0, 2, 0, 0, 2 * s, 6 * t;
}

Row valueRow(const Eigen::Vector2d& p) {
    Monomials m;
    monomials(p, m);
    return m.v.transpose();
}

// Derivative along the direction n (scaled coordinates).
Row directionalRow(const Eigen::Vector2d& p, const Eigen::Vector2d& n) {
    Monomials m;
    monomials(p, m);
    return (n.x() * m.ds + n.y() * m.dt).transpose();
}

Eigen::Vector2d perp(const Eigen::Vector2d& e) { return {-e.y(), e.x()}; }

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

struct Geometry {
    Eigen::Vector2d centre;
    double scale;
    std::array<Eigen::Vector2d, 4> q;  // corners in scaled coordinates (x - centre) / scale
};

Geometry geometry(const std::array<Eigen::Vector2d, 4>& p) {
    // Intersection of the diagonals p0 + a (p2 - p0) = p1 + b (p3 - p1).
    const Eigen::Vector2d d0 = p[2] - p[0], d1 = p[3] - p[1], r = p[1] - p[0];
    const double det = cross(d0, d1);
    const double size = std::max(d0.norm(), d1.norm());
    if (!(std::abs(det) > 1e-12 * size * size)) {
        throw std::runtime_error("FVS quadrilateral: degenerate cell (parallel diagonals)");
    }
    const double a = cross(r, d1) / det, b = cross(r, d0) / det;
    if (!(a > 0 && a < 1 && b > 0 && b < 1)) {
        throw std::runtime_error("FVS quadrilateral: cell is not strictly convex");
    }
    Geometry g;
    g.centre = p[0] + a * d0;
    g.scale = 0;
    for (const auto& x : p) g.scale = std::max(g.scale, (x - g.centre).norm());
    for (int k = 0; k < 4; ++k) g.q[k] = (p[k] - g.centre) / g.scale;
    return g;
}

// Homogeneous constraints on the 40 coefficients (piece k in columns 10k .. 10k+9).
// Internal edge k runs from the centre to corner k, between pieces k-1 and k. The jump of a
// cubic across it vanishes with its normal derivative iff its trace (a cubic of one variable)
// vanishes at 4 points and its normal derivative (a quadratic) at 3: exact polynomial
// identities, so the composite function is C1 inside the cell. The reduced condition (§3.1):
// the normal derivative along outer edge k (piece k) is linear, i.e. its second difference at
// t = 0, 1/2, 1 (exact for the quadratic it is) vanishes.
Eigen::MatrixXd constraintMatrix(const Geometry& g, bool reduced) {
    const int rows = kPieces * 7 + (reduced ? kPieces : 0);
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(rows, kCoefficients);
    int row = 0;
    for (int k = 0; k < kPieces; ++k) {
        const int left = (k + 3) % kPieces, right = k;
        const Eigen::Vector2d e = g.q[k];
        const Eigen::Vector2d n = perp(e).normalized();
        for (const double t : {0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0}) {
            const Row r = valueRow(t * e);
            A.block<1, kM>(row, kM * right) = r;
            A.block<1, kM>(row, kM * left) = -r;
            ++row;
        }
        for (const double t : {0.0, 0.5, 1.0}) {
            const Row r = directionalRow(t * e, n);
            A.block<1, kM>(row, kM * right) = r;
            A.block<1, kM>(row, kM * left) = -r;
            ++row;
        }
    }
    if (reduced) {
        for (int k = 0; k < kPieces; ++k) {
            const Eigen::Vector2d a = g.q[k], b = g.q[(k + 1) % kPieces];
            const Eigen::Vector2d n = -perp(b - a).normalized();  // outward (CCW corners)
            A.block<1, kM>(row, kM * k) =
                directionalRow(a, n) - 2.0 * directionalRow(0.5 * (a + b), n) + directionalRow(b, n);
            ++row;
        }
    }
    return A;
}

// Orthonormal basis of the null space of A. The SVD gives a reliable rank: the constraint
// rows are O(1) in scaled coordinates and the zero singular values are exact up to roundoff,
// so a relative threshold far above roundoff and far below the smallest true singular value
// separates them. A is padded with zero rows to a square matrix (same null space), which lets
// the SVD skip its QR preconditioner (that path trips a GCC 12 -Wmaybe-uninitialized false
// positive inside Eigen).
Eigen::MatrixXd nullSpace(const Eigen::MatrixXd& constraints) {
    const Eigen::Index n = constraints.cols();
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);  // constraints.rows() <= n here
    A.topRows(constraints.rows()) = constraints;
    Eigen::JacobiSVD<Eigen::MatrixXd, Eigen::NoQRPreconditioner> svd(A, Eigen::ComputeFullV);
    const Eigen::VectorXd& sigma = svd.singularValues();
    const double tol = 1e-9 * sigma(0);
    int rank = 0;
    while (rank < sigma.size() && sigma(rank) > tol) ++rank;
    return svd.matrixV().rightCols(A.cols() - rank);
}

}  // namespace

int fvsLocalSpaceDimension(const std::array<Eigen::Vector2d, 4>& corners, bool reduced) {
    return static_cast<int>(nullSpace(constraintMatrix(geometry(corners), reduced)).cols());
}

namespace {

using ScaledCoefficients = std::array<FvsLocalBasis::PieceCoefficients, kPieces>;

// The basis dual to the scaled dofs (w, s w_x, s w_y) at the corners, s = g.scale. In scaled
// coordinates it depends on the cell's shape g.q only, not on its position or size.
ScaledCoefficients scaledCoefficients(const Geometry& g) {
    const Eigen::MatrixXd N = nullSpace(constraintMatrix(g, true));
    if (N.cols() != FvsLocalBasis::kDofs) {
        throw std::runtime_error("FVS quadrilateral: constrained local space has dimension " +
                                 std::to_string(N.cols()) + ", expected 12");
    }
    // The 12 dof functionals at corner k, read on piece k (corner k also belongs to piece
    // k-1, where the C1 constraints give the same values).
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(FvsLocalBasis::kDofs, kCoefficients);
    for (int k = 0; k < kPieces; ++k) {
        Monomials m;
        monomials(g.q[k], m);
        D.block<1, kM>(3 * k + 0, kM * k) = m.v.transpose();
        D.block<1, kM>(3 * k + 1, kM * k) = m.ds.transpose();
        D.block<1, kM>(3 * k + 2, kM * k) = m.dt.transpose();
    }
    // Coefficients N (D N)^{-1}: in the space, and D * coefficients = I.
    Eigen::FullPivLU<Eigen::MatrixXd> lu(D * N);
    if (!lu.isInvertible()) {
        throw std::runtime_error("FVS quadrilateral: vertex dofs are not unisolvent");
    }
    const Eigen::MatrixXd C = N * lu.inverse();
    ScaledCoefficients out;
    for (int k = 0; k < kPieces; ++k) out[k] = C.middleRows(kM * k, kM);
    return out;
}

// The basis dual to the physical dofs: a derivative dof's shape function is s times the
// scaled one.
FvsLocalBasis physicalBasis(const std::array<Eigen::Vector2d, 4>& corners, const Geometry& g,
                            const ScaledCoefficients& scaled) {
    FvsLocalBasis basis;
    basis.corners = corners;
    basis.centre = g.centre;
    basis.scale = g.scale;
    basis.coefficients = scaled;
    for (auto& piece : basis.coefficients) {
        for (int k = 0; k < kPieces; ++k) piece.middleCols<2>(3 * k + 1) *= g.scale;
    }
    return basis;
}

}  // namespace

FvsLocalBasis buildFvsLocalBasis(const std::array<Eigen::Vector2d, 4>& corners) {
    const Geometry g = geometry(corners);
    return physicalBasis(corners, g, scaledCoefficients(g));
}

FvsSpace::FvsSpace(const Mesh& mesh) : mesh_(mesh) {
    const int cells = mesh_.cellCount();
    elements_.reserve(cells);
    elementDofs_.reserve(cells);
    // One SVD per distinct cell shape (~0.6 ms each): on the structured mesh every cell has
    // the same shape up to roundoff in the coordinates, so one serves all. Shapes are matched
    // to 1e-12 in scaled coordinates; the reused basis then satisfies this cell's constraints
    // and dof duality to that accuracy, far below anything the solver resolves.
    using Shape = std::pair<std::array<Eigen::Vector2d, 4>, ScaledCoefficients>;
    std::vector<Shape> shapes;
    for (int c = 0; c < cells; ++c) {
        const auto v = mesh_.cellVertices(c);
        std::array<Eigen::Vector2d, 4> corners;
        std::vector<Eigen::Index> dofs;
        dofs.reserve(kLocalDofs);
        for (int k = 0; k < 4; ++k) {
            corners[k] = mesh_.point(v[k]);
            for (int j = 0; j < kVertexDofs; ++j) {
                dofs.push_back(kVertexDofs * static_cast<Eigen::Index>(v[k]) + j);
            }
        }
        const Geometry g = geometry(corners);
        auto same = [&g](const Shape& shape) {
            for (int k = 0; k < 4; ++k) {
                if ((shape.first[k] - g.q[k]).lpNorm<Eigen::Infinity>() > 1e-12) return false;
            }
            return true;
        };
        auto it = std::find_if(shapes.begin(), shapes.end(), same);
        if (it == shapes.end()) {
            shapes.emplace_back(g.q, scaledCoefficients(g));
            it = shapes.end() - 1;
        }
        elements_.push_back(physicalBasis(corners, g, it->second));
        elementDofs_.push_back(std::move(dofs));
    }
}

const std::vector<Eigen::Index>& FvsSpace::elementDofs(int element) const { return elementDofs_.at(element); }

std::vector<ElementQuadratureNode> FvsSpace::quadrature(int element) const {
    const FvsLocalBasis& e = elements_.at(element);
    std::vector<ElementQuadratureNode> rule;
    for (int k = 0; k < kPieces; ++k) {
        const auto sub = triangleRule(e.corners[k], e.corners[(k + 1) % kPieces], e.centre, 6);
        for (const auto& node : sub) rule.push_back({node.point, node.weight, k});
    }
    return rule;
}

int FvsSpace::elementContaining(const Eigen::Vector2d& x) const { return mesh_.cellContaining(x); }

int FvsSpace::pieceContaining(int element, const Eigen::Vector2d& x) const {
    const FvsLocalBasis& e = elements_.at(element);
    // For each sub-triangle, the smallest signed distance of x to its three edge lines
    // (positive inside); the piece where it is largest contains x, and a point on a border
    // or just outside the cell (roundoff) still gets a sensible piece.
    int best = 0;
    double bestMargin = -std::numeric_limits<double>::infinity();
    for (int k = 0; k < kPieces; ++k) {
        const std::array<Eigen::Vector2d, 3> t = {e.corners[k], e.corners[(k + 1) % kPieces], e.centre};
        double margin = std::numeric_limits<double>::infinity();
        for (int i = 0; i < 3; ++i) {
            const Eigen::Vector2d edge = t[(i + 1) % 3] - t[i];
            margin = std::min(margin, cross(edge, x - t[i]) / edge.norm());
        }
        if (margin > bestMargin) {
            bestMargin = margin;
            best = k;
        }
    }
    return best;
}

void FvsSpace::evaluate(int element, int piece, const Eigen::Vector2d& x, LocalBasis& out) const {
    const FvsLocalBasis& e = elements_.at(element);
    if (piece < 0 || piece >= kPieces) throw std::out_of_range("FVS: piece out of range");
    const FvsLocalBasis::PieceCoefficients& C = e.coefficients[piece];
    Monomials m;
    monomials((x - e.centre) / e.scale, m);
    const double h1 = 1.0 / e.scale, h2 = h1 * h1;
    // Fixed-size products into vectors that keep their size: no allocation after the first call.
    out.value.noalias() = C.transpose() * m.v;
    out.dx.noalias() = h1 * (C.transpose() * m.ds);
    out.dy.noalias() = h1 * (C.transpose() * m.dt);
    out.dxx.noalias() = h2 * (C.transpose() * m.dss);
    out.dxy.noalias() = h2 * (C.transpose() * m.dst);
    out.dyy.noalias() = h2 * (C.transpose() * m.dtt);
}

std::vector<Eigen::Index> FvsSpace::clampedDofs() const {
    std::vector<Eigen::Index> dofs;
    for (int v = 0; v < mesh_.vertexCount(); ++v) {
        if (!mesh_.isClamped(v)) continue;
        for (int j = 0; j < kVertexDofs; ++j) {
            dofs.push_back(kVertexDofs * static_cast<Eigen::Index>(v) + j);
        }
    }
    return dofs;  // increasing v, then j: sorted
}

std::unique_ptr<FiniteElementSpace> makeFvsSpace(const Mesh& mesh) { return std::make_unique<FvsSpace>(mesh); }

}  // namespace plate
