// Unit tests of the reduced FVS quadrilateral (FvsQuadrilateral.h): polynomial reproduction,
// C1 continuity across cells and inside them, the reduced (linear normal derivative)
// condition, the exact clamp, and the dimension of the constrained local space.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

#include "fe/FvsQuadrilateral.h"

namespace plate {
namespace {

// A field and its derivatives at one point.
struct Jet {
    double w = 0, wx = 0, wy = 0, wxx = 0, wxy = 0, wyy = 0;
};

Jet evaluateField(const FiniteElementSpace& space, const Eigen::VectorXd& u, int element, int piece,
                  const Eigen::Vector2d& x) {
    LocalBasis b;
    space.evaluate(element, piece, x, b);
    const auto& dofs = space.elementDofs(element);
    Jet j;
    for (size_t i = 0; i < dofs.size(); ++i) {
        const double c = u(dofs[i]);
        j.w += c * b.value(i);
        j.wx += c * b.dx(i);
        j.wy += c * b.dy(i);
        j.wxx += c * b.dxx(i);
        j.wxy += c * b.dxy(i);
        j.wyy += c * b.dyy(i);
    }
    return j;
}

// A polynomial of degree <= 3 and its exact derivatives: sum a_ij x^i y^j.
struct Poly {
    // Coefficients of 1, x, y, x^2, xy, y^2, x^3, x^2 y, x y^2, y^3.
    std::array<double, 10> a{};
    Jet at(const Eigen::Vector2d& p) const {
        const double x = p.x(), y = p.y();
        Jet j;
        j.w = a[0] + a[1] * x + a[2] * y + a[3] * x * x + a[4] * x * y + a[5] * y * y + a[6] * x * x * x +
              a[7] * x * x * y + a[8] * x * y * y + a[9] * y * y * y;
        j.wx = a[1] + 2 * a[3] * x + a[4] * y + 3 * a[6] * x * x + 2 * a[7] * x * y + a[8] * y * y;
        j.wy = a[2] + a[4] * x + 2 * a[5] * y + a[7] * x * x + 2 * a[8] * x * y + 3 * a[9] * y * y;
        j.wxx = 2 * a[3] + 6 * a[6] * x + 2 * a[7] * y;
        j.wxy = a[4] + 2 * a[7] * x + 2 * a[8] * y;
        j.wyy = 2 * a[5] + 2 * a[8] * x + 6 * a[9] * y;
        return j;
    }
};

// Global dof vector interpolating p: w, w_x, w_y at every vertex.
Eigen::VectorXd interpolate(const FiniteElementSpace& space, const Poly& p) {
    const Mesh& mesh = space.mesh();
    Eigen::VectorXd u = Eigen::VectorXd::Zero(space.dofCount());
    for (int v = 0; v < mesh.vertexCount(); ++v) {
        const Jet j = p.at(mesh.point(v));
        u(3 * v) = j.w;
        u(3 * v + 1) = j.wx;
        u(3 * v + 2) = j.wy;
    }
    return u;
}

// Largest relative error of the interpolant of p over random points of every piece of every
// cell: value, first and second derivatives, each relative to that quantity's own scale.
struct ReproductionError {
    double value = 0, first = 0, second = 0;
};

ReproductionError reproductionError(const FvsSpace& space, const Poly& p, std::mt19937& rng) {
    const Eigen::VectorXd u = interpolate(space, p);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    // Scales: the magnitudes of the exact quantities over the samples.
    double s0 = 1e-300, s1 = 1e-300, s2 = 1e-300;
    ReproductionError err;
    struct Sample {
        Jet exact, fe;
    };
    std::vector<Sample> samples;
    for (int c = 0; c < space.elementCount(); ++c) {
        const FvsLocalBasis& e = space.localBasis(c);
        for (int k = 0; k < 4; ++k) {
            for (int n = 0; n < 6; ++n) {
                // Random barycentric point of the sub-triangle (corner k, corner k+1, centre).
                double l1 = U(rng), l2 = U(rng);
                if (l1 + l2 > 1) {
                    l1 = 1 - l1;
                    l2 = 1 - l2;
                }
                const Eigen::Vector2d x =
                    e.corners[k] + l1 * (e.corners[(k + 1) % 4] - e.corners[k]) + l2 * (e.centre - e.corners[k]);
                EXPECT_EQ(space.pieceContaining(c, x), k);
                samples.push_back({p.at(x), evaluateField(space, u, c, k, x)});
                const Jet& j = samples.back().exact;
                s0 = std::max(s0, std::abs(j.w));
                s1 = std::max({s1, std::abs(j.wx), std::abs(j.wy)});
                s2 = std::max({s2, std::abs(j.wxx), std::abs(j.wxy), std::abs(j.wyy)});
            }
        }
    }
    // A derivative that vanishes identically is compared against the size it would have on
    // the mesh scale, s0 / h^k.
    const double h = std::min(space.mesh().hx(), space.mesh().hy());
    s1 = std::max(s1, s0 / h);
    s2 = std::max(s2, s0 / (h * h));
    for (const auto& s : samples) {
        err.value = std::max(err.value, std::abs(s.fe.w - s.exact.w) / s0);
        err.first = std::max({err.first, std::abs(s.fe.wx - s.exact.wx) / s1, std::abs(s.fe.wy - s.exact.wy) / s1});
        err.second = std::max({err.second, std::abs(s.fe.wxx - s.exact.wxx) / s2, std::abs(s.fe.wxy - s.exact.wxy) / s2,
                               std::abs(s.fe.wyy - s.exact.wyy) / s2});
    }
    return err;
}

Poly monomial(int index) {
    Poly p;
    p.a[index] = 1.0;
    return p;
}

// The paper's plate on a coarse, non-square mesh (cells 0.3 x 0.1333: aspect ratio 2.25).
Mesh testMesh() { return Mesh(1.2, 0.4, 4, 3); }

TEST(FvsQuadrilateral, ReproducesQuadraticsExactly) {
    const FvsSpace space(testMesh());
    std::mt19937 rng(1);
    // Each monomial of degree <= 2, and a random quadratic shifted away from the origin.
    for (int i = 0; i < 6; ++i) {
        const ReproductionError e = reproductionError(space, monomial(i), rng);
        EXPECT_LT(e.value, 1e-9) << "monomial " << i;
        EXPECT_LT(e.first, 1e-9) << "monomial " << i;
        EXPECT_LT(e.second, 1e-9) << "monomial " << i;
    }
    Poly q;
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    for (int i = 0; i < 6; ++i) q.a[i] = U(rng);
    const ReproductionError e = reproductionError(space, q, rng);
    EXPECT_LT(std::max({e.value, e.first, e.second}), 1e-9);
}

// Which cubics the reduced space contains on a rectangle: those whose normal derivative is
// linear along every (axis-parallel) outer edge. For x^3 the normal derivative is 0 on the
// horizontal edges and 3x^2 = const on the vertical ones; likewise y^3. For x^2 y it is x^2 on
// the horizontal edges (quadratic) and for x y^2 it is y^2 on the vertical ones, so these two
// are NOT in the space and their interpolants differ from them (by O(h^3) in the value).
// So on rectangles the space holds P2 + span{x^3, y^3} (8 of its 12 dimensions), not all P3.
TEST(FvsQuadrilateral, ReproducesXCubedAndYCubedButNotTheMixedCubics) {
    const FvsSpace space(testMesh());
    std::mt19937 rng(2);
    for (const int i : {6, 9}) {  // x^3, y^3
        const ReproductionError e = reproductionError(space, monomial(i), rng);
        EXPECT_LT(e.value, 1e-9) << "monomial " << i;
        EXPECT_LT(e.first, 1e-9) << "monomial " << i;
        EXPECT_LT(e.second, 1e-9) << "monomial " << i;
    }
    for (const int i : {7, 8}) {  // x^2 y, x y^2
        const ReproductionError e = reproductionError(space, monomial(i), rng);
        EXPECT_GT(e.value, 1e-4) << "monomial " << i << " unexpectedly reproduced";
        EXPECT_GT(e.second, 1e-2) << "monomial " << i << " unexpectedly reproduced";
    }
}

TEST(FvsQuadrilateral, ShapeFunctionsAreDualToTheVertexDofs) {
    const FvsSpace space(testMesh());
    LocalBasis b;
    for (int c = 0; c < space.elementCount(); ++c) {
        const FvsLocalBasis& e = space.localBasis(c);
        for (int k = 0; k < 4; ++k) {
            // Corner k belongs to pieces k-1 and k: both must give the same dual values.
            for (const int piece : {k, (k + 3) % 4}) {
                space.evaluate(c, piece, e.corners[k], b);
                for (int i = 0; i < 12; ++i) {
                    const double h = e.scale;  // derivative dofs scale like 1/h
                    EXPECT_NEAR(b.value(i), i == 3 * k ? 1.0 : 0.0, 1e-10);
                    EXPECT_NEAR(h * b.dx(i), i == 3 * k + 1 ? h : 0.0, 1e-10);
                    EXPECT_NEAR(h * b.dy(i), i == 3 * k + 2 ? h : 0.0, 1e-10);
                }
            }
        }
    }
}

Eigen::VectorXd randomDofs(const FiniteElementSpace& space, std::mt19937& rng) {
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    Eigen::VectorXd u(space.dofCount());
    for (Eigen::Index i = 0; i < u.size(); ++i) u(i) = U(rng);
    return u;
}

// Scale of a random dof field: values O(1), gradients O(1/h) (dof magnitude 1 and the
// Hermite shape functions' slopes), for relative comparisons.
double gradientScale(const Mesh& m) { return 1.0 / std::min(m.hx(), m.hy()); }

TEST(FvsQuadrilateral, IsC1AcrossCellEdges) {
    const Mesh mesh = testMesh();
    const FvsSpace space(mesh);
    std::mt19937 rng(3);
    const Eigen::VectorXd u = randomDofs(space, rng);
    const double g = gradientScale(mesh);
    double maxJump = 0, maxHessJump = 0;
    int edges = 0;
    const int nx = mesh.nx(), ny = mesh.ny();
    for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < ny; ++j) {
            const int c = mesh.cell(i, j);
            // Right neighbour (shared vertical edge) and top neighbour (shared horizontal edge).
            for (int dir = 0; dir < 2; ++dir) {
                if ((dir == 0 && i + 1 >= nx) || (dir == 1 && j + 1 >= ny)) continue;
                const int d = dir == 0 ? mesh.cell(i + 1, j) : mesh.cell(i, j + 1);
                const auto cv = mesh.cellVertices(c);
                const Eigen::Vector2d a = mesh.point(dir == 0 ? cv[1] : cv[3]);
                const Eigen::Vector2d b = mesh.point(cv[2]);
                ++edges;
                for (const double t : {0.0, 0.13, 0.37, 0.5, 0.71, 0.94, 1.0}) {
                    const Eigen::Vector2d x = a + t * (b - a);
                    const Jet p = evaluateField(space, u, c, space.pieceContaining(c, x), x);
                    const Jet q = evaluateField(space, u, d, space.pieceContaining(d, x), x);
                    maxJump =
                        std::max({maxJump, std::abs(p.w - q.w), std::abs(p.wx - q.wx) / g, std::abs(p.wy - q.wy) / g});
                    maxHessJump =
                        std::max({maxHessJump, std::abs(p.wxx - q.wxx) / (g * g), std::abs(p.wyy - q.wyy) / (g * g)});
                }
            }
        }
    }
    EXPECT_EQ(edges, (nx - 1) * ny + nx * (ny - 1));
    EXPECT_LT(maxJump, 1e-9);
    // Sanity: the field is only C1, second derivatives do jump (the comparison is meaningful).
    EXPECT_GT(maxHessJump, 1e-3);
}

TEST(FvsQuadrilateral, IsC1AcrossInternalSubTriangleEdges) {
    const Mesh mesh = testMesh();
    const FvsSpace space(mesh);
    std::mt19937 rng(4);
    const Eigen::VectorXd u = randomDofs(space, rng);
    const double g = gradientScale(mesh);
    double maxJump = 0, maxHessJump = 0;
    for (int c = 0; c < space.elementCount(); ++c) {
        const FvsLocalBasis& e = space.localBasis(c);
        for (int k = 0; k < 4; ++k) {
            // Internal edge from the centre to corner k, between pieces k-1 and k.
            for (const double t : {0.0, 0.21, 0.5, 0.66, 0.9, 1.0}) {
                const Eigen::Vector2d x = e.centre + t * (e.corners[k] - e.centre);
                const Jet p = evaluateField(space, u, c, (k + 3) % 4, x);
                const Jet q = evaluateField(space, u, c, k, x);
                maxJump =
                    std::max({maxJump, std::abs(p.w - q.w), std::abs(p.wx - q.wx) / g, std::abs(p.wy - q.wy) / g});
                maxHessJump = std::max({maxHessJump, std::abs(p.wxx - q.wxx) / (g * g),
                                        std::abs(p.wxy - q.wxy) / (g * g), std::abs(p.wyy - q.wyy) / (g * g)});
            }
        }
    }
    EXPECT_LT(maxJump, 1e-9);
    EXPECT_GT(maxHessJump, 1e-3);  // genuinely piecewise: the pieces are different cubics
}

// d/dn w at 5 equispaced points of a segment, evaluated on the given piece.
std::array<double, 5> normalDerivative(const FvsSpace& space, const Eigen::VectorXd& u, int c, int piece,
                                       const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const Eigen::Vector2d e = b - a;
    const Eigen::Vector2d n = Eigen::Vector2d(e.y(), -e.x()).normalized();
    std::array<double, 5> dn{};
    for (int i = 0; i < 5; ++i) {
        const Eigen::Vector2d x = a + (i / 4.0) * e;
        const Jet j = evaluateField(space, u, c, piece, x);
        dn[i] = n.x() * j.wx + n.y() * j.wy;
    }
    return dn;
}

double maxSecondDifference(const std::array<double, 5>& f) {
    double m = 0;
    for (int i = 1; i < 4; ++i) m = std::max(m, std::abs(f[i - 1] - 2 * f[i] + f[i + 1]));
    return m;
}

TEST(FvsQuadrilateral, NormalDerivativeIsLinearAlongOuterEdges) {
    const Mesh mesh = testMesh();
    const FvsSpace space(mesh);
    std::mt19937 rng(5);
    const Eigen::VectorXd u = randomDofs(space, rng);
    const double g = gradientScale(mesh);
    double outer = 0, internal = 0;
    for (int c = 0; c < space.elementCount(); ++c) {
        const FvsLocalBasis& e = space.localBasis(c);
        for (int k = 0; k < 4; ++k) {
            outer = std::max(
                outer, maxSecondDifference(normalDerivative(space, u, c, k, e.corners[k], e.corners[(k + 1) % 4])));
            // The reduced condition is imposed on outer edges only: along the internal edges
            // the normal derivative stays a genuine quadratic (so the check can fail).
            internal =
                std::max(internal, maxSecondDifference(normalDerivative(space, u, c, k, e.centre, e.corners[k])));
        }
    }
    EXPECT_LT(outer / g, 1e-10);
    EXPECT_GT(internal / g, 1e-3);
}

TEST(FvsQuadrilateral, ExactClampAlongXEqualsZero) {
    const Mesh mesh = testMesh();
    const FvsSpace space(mesh);
    const auto clamped = space.clampedDofs();
    ASSERT_EQ(clamped.size(), static_cast<size_t>(3 * (mesh.ny() + 1)));
    EXPECT_TRUE(std::is_sorted(clamped.begin(), clamped.end()));
    EXPECT_TRUE(std::adjacent_find(clamped.begin(), clamped.end()) == clamped.end());
    for (const Eigen::Index d : clamped) EXPECT_TRUE(mesh.isClamped(static_cast<int>(d / 3)));

    std::mt19937 rng(6);
    Eigen::VectorXd u = randomDofs(space, rng);
    const double g = gradientScale(mesh);
    auto maxOnClamp = [&](const Eigen::VectorXd& field) {
        double m = 0;
        for (int j = 0; j < mesh.ny(); ++j) {
            const int c = mesh.cell(0, j);
            for (const double t : {0.0, 0.1, 0.3, 0.5, 0.77, 1.0}) {
                const Eigen::Vector2d x(0.0, (j + t) * mesh.hy());
                const Jet w = evaluateField(space, field, c, space.pieceContaining(c, x), x);
                m = std::max({m, std::abs(w.w), std::abs(w.wx) / g, std::abs(w.wy) / g});
            }
        }
        return m;
    };
    EXPECT_GT(maxOnClamp(u), 1e-2);  // a random field is not clamped
    for (const Eigen::Index d : clamped) u(d) = 0.0;
    EXPECT_LT(maxOnClamp(u), 1e-12);
}

TEST(FvsQuadrilateral, LocalSpaceOfOneCellHasDimension12) {
    const Mesh mesh(1.2, 0.4, 1, 1);
    std::array<Eigen::Vector2d, 4> corners;
    const auto v = mesh.cellVertices(0);
    for (int k = 0; k < 4; ++k) corners[k] = mesh.point(v[k]);
    EXPECT_EQ(fvsLocalSpaceDimension(corners, true), 12);
    // Without the reduced condition: the full FVS space (12 vertex dofs + 4 mid-edge normal
    // derivatives; the diagonal cross-cut is a singular vertex, hence 16 and not 15).
    EXPECT_EQ(fvsLocalSpaceDimension(corners, false), 16);
    const FvsSpace space(mesh);
    EXPECT_EQ(space.elementCount(), 1);
    EXPECT_EQ(space.dofCount(), 12);
    EXPECT_EQ(space.elementDofs(0).size(), 12u);

    // A general convex quadrilateral (not a parallelogram): still 12 and 16.
    using V = Eigen::Vector2d;
    const std::array<V, 4> quad = {V(0.0, 0.0), V(1.0, 0.1), V(1.3, 0.9), V(0.2, 0.7)};
    EXPECT_EQ(fvsLocalSpaceDimension(quad, true), 12);
    EXPECT_EQ(fvsLocalSpaceDimension(quad, false), 16);
    // A non-convex one is rejected.
    const std::array<V, 4> dart = {V(0.0, 0.0), V(1.0, 0.0), V(0.3, 0.3), V(0.0, 1.0)};
    EXPECT_THROW(buildFvsLocalBasis(dart), std::runtime_error);
}

TEST(FvsQuadrilateral, SharedShapeBasisMatchesAFreshOne) {
    // FvsSpace reuses one local basis for cells of the same shape; it must agree with the
    // basis built from each cell's own corners.
    const Mesh mesh(1.2, 0.4, 14, 5);
    const FvsSpace space(mesh);
    double maxDiff = 0;
    for (int c = 0; c < space.elementCount(); ++c) {
        const FvsLocalBasis& shared = space.localBasis(c);
        const FvsLocalBasis fresh = buildFvsLocalBasis(shared.corners);
        EXPECT_LT((fresh.centre - shared.centre).norm(), 1e-15);
        for (int k = 0; k < 4; ++k) {
            const double scale = fresh.coefficients[k].cwiseAbs().maxCoeff();
            maxDiff = std::max(maxDiff, (fresh.coefficients[k] - shared.coefficients[k]).cwiseAbs().maxCoeff() / scale);
        }
    }
    EXPECT_LT(maxDiff, 1e-11);
}

TEST(FvsQuadrilateral, CompositeQuadratureIntegratesPiecewiseCubicProductsExactly) {
    const Mesh mesh = testMesh();
    const FvsSpace space(mesh);
    // Area, and the exact integral of x^3 y^3 (degree 6) over the plate.
    double area = 0, moment = 0;
    for (int c = 0; c < space.elementCount(); ++c) {
        const auto rule = space.quadrature(c);
        EXPECT_EQ(rule.size(), 64u);
        for (const auto& n : rule) {
            EXPECT_EQ(space.pieceContaining(c, n.point), n.piece);
            area += n.weight;
            moment += n.weight * std::pow(n.point.x(), 3) * std::pow(n.point.y(), 3);
        }
    }
    EXPECT_NEAR(area, 1.2 * 0.4, 1e-14);
    const double exact = std::pow(1.2, 4) / 4 * std::pow(0.4, 4) / 4;
    EXPECT_NEAR(moment / exact, 1.0, 1e-12);
    // Mass of the random field: composite rule vs a much finer composite rule (degree 12).
    std::mt19937 rng(7);
    const Eigen::VectorXd u = randomDofs(space, rng);
    double m6 = 0, m12 = 0;
    for (int c = 0; c < space.elementCount(); ++c) {
        for (const auto& n : space.quadrature(c)) {
            m6 += n.weight * std::pow(evaluateField(space, u, c, n.piece, n.point).w, 2);
        }
        const FvsLocalBasis& e = space.localBasis(c);
        for (int k = 0; k < 4; ++k) {
            for (const auto& n : triangleRule(e.corners[k], e.corners[(k + 1) % 4], e.centre, 12)) {
                m12 += n.weight * std::pow(evaluateField(space, u, c, k, n.point).w, 2);
            }
        }
    }
    EXPECT_NEAR(m6 / m12, 1.0, 1e-12);
}

TEST(FvsQuadrilateral, FactoryAndLookups) {
    const Mesh mesh = testMesh();
    const auto space = makeFvsSpace(mesh);
    EXPECT_EQ(space->type(), ElementType::Fvs);
    EXPECT_EQ(space->elementCount(), mesh.cellCount());
    EXPECT_EQ(space->dofCount(), 3 * mesh.vertexCount());
    for (int v = 0; v < mesh.vertexCount(); ++v) EXPECT_EQ(space->vertexValueDof(v), 3 * v);
    const Eigen::Vector2d x(0.61, 0.21);
    EXPECT_EQ(space->elementContaining(x), mesh.cellContaining(x));
    // Element dofs: corner k of the cell, then (w, w_x, w_y).
    const auto cv = mesh.cellVertices(5);
    const auto& dofs = space->elementDofs(5);
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 3; ++j) EXPECT_EQ(dofs[3 * k + j], 3 * cv[k] + j);
}

}  // namespace
}  // namespace plate
