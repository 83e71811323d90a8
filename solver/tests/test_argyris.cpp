// Unit tests of the Argyris P5 space: dof layout, duality, P5 reproduction, C1 continuity,
// exact clamp, quadrature.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "fe/ArgyrisTriangle.h"

namespace plate {
namespace {

// The paper's plate (14 x 5 cells, 140 triangles) and a coarse, anisotropic one
// (cells 0.3 x 0.125) so that nothing relies on square cells or on h ≈ 1.
struct MeshCase {
    double length, width;
    int nx, ny;
};
const MeshCase kMeshes[] = {{1.2, 0.4, 14, 5}, {0.9, 0.5, 3, 4}};

// ∂ξ^p ∂η^q (ξ^a η^b).
double monomialDerivative(int a, int b, int p, int q, double xi, double eta) {
    if (p > a || q > b) return 0.0;
    double c = 1.0;
    for (int k = 0; k < p; ++k) c *= a - k;
    for (int k = 0; k < q; ++k) c *= b - k;
    return c * std::pow(xi, a - p) * std::pow(eta, b - q);
}

// p(x, y) = Σ c_ab ((x - x0)/L)^a ((y - y0)/L)^b, a + b <= degree, random coefficients.
struct Polynomial {
    std::vector<int> a, b;
    std::vector<double> c;
    Eigen::Vector2d origin;
    double scale;

    Polynomial(int degree, const Eigen::Vector2d& o, double L, std::mt19937& rng) : origin(o), scale(L) {
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        for (int d = 0; d <= degree; ++d)
            for (int q = 0; q <= d; ++q) {
                a.push_back(d - q);
                b.push_back(q);
                c.push_back(u(rng));
            }
    }
    // ∂x^p ∂y^q p at x.
    double operator()(const Eigen::Vector2d& x, int p = 0, int q = 0) const {
        const double xi = (x.x() - origin.x()) / scale, eta = (x.y() - origin.y()) / scale;
        double s = 0.0;
        for (size_t j = 0; j < c.size(); ++j) s += c[j] * monomialDerivative(a[j], b[j], p, q, xi, eta);
        return s / std::pow(scale, p + q);
    }
};

constexpr int kVertexDerivative[6][2] = {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}};

// Global dofs of a polynomial, computed exactly from their definition.
Eigen::VectorXd interpolate(const ArgyrisSpace& space, const Polynomial& p) {
    const Mesh& mesh = space.mesh();
    Eigen::VectorXd u(space.dofCount());
    for (int v = 0; v < mesh.vertexCount(); ++v)
        for (int k = 0; k < 6; ++k) u[6 * v + k] = p(mesh.point(v), kVertexDerivative[k][0], kVertexDerivative[k][1]);
    for (int e = 0; e < space.edgeCount(); ++e) {
        const auto& ev = space.edgeVertices(e);
        const Eigen::Vector2d mid = 0.5 * (mesh.point(ev[0]) + mesh.point(ev[1]));
        const Eigen::Vector2d n = space.edgeNormal(e);
        u[space.edgeDof(e)] = n.x() * p(mid, 1, 0) + n.y() * p(mid, 0, 1);
    }
    return u;
}

// w, w_x, w_y, w_xx, w_xy, w_yy of the global field u at x, from element t.
std::array<double, 6> field(const ArgyrisSpace& space, const Eigen::VectorXd& u, int t, const Eigen::Vector2d& x) {
    LocalBasis basis;
    space.evaluate(t, space.pieceContaining(t, x), x, basis);
    const auto& dofs = space.elementDofs(t);
    Eigen::VectorXd ul(dofs.size());
    for (size_t i = 0; i < dofs.size(); ++i) ul[i] = u[dofs[i]];
    return {basis.value.dot(ul), basis.dx.dot(ul),  basis.dy.dot(ul),
            basis.dxx.dot(ul),   basis.dxy.dot(ul), basis.dyy.dot(ul)};
}

Eigen::Vector2d randomPointIn(const Mesh& mesh, int t, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double r = u(rng), s = u(rng);
    if (r + s > 1.0) {
        r = 1.0 - r;
        s = 1.0 - s;
    }
    const auto v = mesh.triangleVertices(t);
    return mesh.point(v[0]) + r * (mesh.point(v[1]) - mesh.point(v[0])) + s * (mesh.point(v[2]) - mesh.point(v[0]));
}

double longestEdge(const Mesh& mesh, int t) {
    const auto v = mesh.triangleVertices(t);
    double h = 0.0;
    for (int l = 0; l < 3; ++l) h = std::max(h, (mesh.point(v[l]) - mesh.point(v[(l + 1) % 3])).norm());
    return h;
}

// Random dofs of O(1) effect: derivative dofs scaled by 1/h^order.
Eigen::VectorXd randomDofs(const ArgyrisSpace& space, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const double h = std::max(space.mesh().hx(), space.mesh().hy());
    Eigen::VectorXd x(space.dofCount());
    for (Eigen::Index i = 0; i < x.size(); ++i) {
        int order = 1;  // edge dofs
        if (i < 6 * space.mesh().vertexCount()) {
            const int k = static_cast<int>(i % 6);
            order = kVertexDerivative[k][0] + kVertexDerivative[k][1];
        }
        x[i] = u(rng) / std::pow(h, order);
    }
    return x;
}

TEST(Argyris, DofLayout) {
    for (const auto& mc : kMeshes) {
        const Mesh mesh(mc.length, mc.width, mc.nx, mc.ny);
        const ArgyrisSpace space(mesh);
        const int nEdges = mc.nx * (mc.ny + 1) + (mc.nx + 1) * mc.ny + mc.nx * mc.ny;
        EXPECT_EQ(space.edgeCount(), nEdges);
        EXPECT_EQ(space.dofCount(), 6 * mesh.vertexCount() + nEdges);
        EXPECT_EQ(space.elementCount(), 2 * mc.nx * mc.ny);
        EXPECT_EQ(space.type(), ElementType::Argyris);
        std::vector<int> edgeUse(nEdges, 0);
        for (int t = 0; t < space.elementCount(); ++t) {
            const auto& dofs = space.elementDofs(t);
            ASSERT_EQ(dofs.size(), 21u);
            const auto v = mesh.triangleVertices(t);
            for (int l = 0; l < 3; ++l)
                for (int k = 0; k < 6; ++k) EXPECT_EQ(dofs[6 * l + k], 6 * v[l] + k);
            for (int l = 0; l < 3; ++l) {
                const Eigen::Index e = dofs[18 + l] - 6 * mesh.vertexCount();
                ASSERT_GE(e, 0);
                ASSERT_LT(e, nEdges);
                ++edgeUse[e];
                // Local edge l joins local vertices l and l+1.
                const auto& ev = space.edgeVertices(static_cast<int>(e));
                EXPECT_EQ(ev[0], std::min(v[l], v[(l + 1) % 3]));
                EXPECT_EQ(ev[1], std::max(v[l], v[(l + 1) % 3]));
            }
        }
        // Boundary edges belong to one triangle, interior ones to two.
        const int boundary = 2 * (mc.nx + mc.ny);
        EXPECT_EQ(std::count(edgeUse.begin(), edgeUse.end(), 1), boundary);
        EXPECT_EQ(std::count(edgeUse.begin(), edgeUse.end(), 2), nEdges - boundary);
        for (int v = 0; v < mesh.vertexCount(); ++v) EXPECT_EQ(space.vertexValueDof(v), 6 * v);
        // Global normal: unit, orthogonal to the edge, rot(-90°) of lower -> higher tangent.
        for (int e = 0; e < space.edgeCount(); ++e) {
            const auto& ev = space.edgeVertices(e);
            const Eigen::Vector2d t = mesh.point(ev[1]) - mesh.point(ev[0]);
            const Eigen::Vector2d n = space.edgeNormal(e);
            EXPECT_NEAR(n.norm(), 1.0, 1e-15);
            EXPECT_NEAR(n.dot(t), 0.0, 1e-15);
            EXPECT_NEAR(n.x(), t.y() / t.norm(), 1e-15);  // n = rot(-90°) t: clockwise of t
            EXPECT_NEAR(n.y(), -t.x() / t.norm(), 1e-15);
        }
    }
}

// Each local shape function, evaluated through evaluate(), is dual to the global dofs of its
// element (with the global edge normals), and the scaled dof matrices are well conditioned.
TEST(Argyris, LocalBasisIsDualToGlobalDofs) {
    for (const auto& mc : kMeshes) {
        const Mesh mesh(mc.length, mc.width, mc.nx, mc.ny);
        const ArgyrisSpace space(mesh);
        double worstCond = 0.0, worstError = 0.0;
        for (int t = 0; t < space.elementCount(); ++t) {
            // Dynamic size: GCC 12 warns (falsely) on the fixed-size 21x21 JacobiSVD.
            const Eigen::MatrixXd V = space.scaledDofMatrix(t);
            const Eigen::JacobiSVD<Eigen::MatrixXd> svd(V);
            const auto& sv = svd.singularValues();
            worstCond = std::max(worstCond, sv[0] / sv[sv.size() - 1]);

            const auto v = mesh.triangleVertices(t);
            const auto& dofs = space.elementDofs(t);
            const double h = longestEdge(mesh, t);
            LocalBasis b;
            for (int i = 0; i < 21; ++i) {
                Eigen::VectorXd row;  // dof i applied to all 21 shape functions
                int order;
                if (i < 18) {
                    const int l = i / 6, k = i % 6;
                    space.evaluate(t, 0, mesh.point(v[l]), b);
                    const Eigen::VectorXd* q[6] = {&b.value, &b.dx, &b.dy, &b.dxx, &b.dxy, &b.dyy};
                    row = *q[k];
                    order = kVertexDerivative[k][0] + kVertexDerivative[k][1];
                } else {
                    const int e = static_cast<int>(dofs[i] - 6 * mesh.vertexCount());
                    const auto& ev = space.edgeVertices(e);
                    space.evaluate(t, 0, 0.5 * (mesh.point(ev[0]) + mesh.point(ev[1])), b);
                    const Eigen::Vector2d n = space.edgeNormal(e);
                    row = n.x() * b.dx + n.y() * b.dy;
                    order = 1;
                }
                for (int j = 0; j < 21; ++j) {
                    const int orderJ = j < 18 ? kVertexDerivative[j % 6][0] + kVertexDerivative[j % 6][1] : 1;
                    // dof_i(φ_j) scales like h^{d_j - d_i}: compare the scaled value.
                    const double scaled = row[j] * std::pow(h, order - orderJ);
                    const double err = std::abs(scaled - (i == j ? 1.0 : 0.0));
                    worstError = std::max(worstError, err);
                    EXPECT_LT(err, 1e-10) << "element " << t << " dof " << i << " shape " << j;
                }
            }
        }
        std::cout << "[ info ] mesh " << mc.nx << "x" << mc.ny << ": worst cond(V) = " << worstCond
                  << ", worst duality error = " << worstError << "\n";
        EXPECT_LT(worstCond, 1e6);
    }
}

TEST(Argyris, ReproducesQuinticPolynomials) {
    std::mt19937 rng(12345);
    for (const auto& mc : kMeshes) {
        const Mesh mesh(mc.length, mc.width, mc.nx, mc.ny);
        const ArgyrisSpace space(mesh);
        for (int trial = 0; trial < 3; ++trial) {
            const Polynomial p(5, {0.3 * mc.length, 0.6 * mc.width}, mc.length, rng);
            const Eigen::VectorXd u = interpolate(space, p);
            // Sample, then compare each derivative order against the largest exact value of
            // that order over the plate (relative error of the field, not of each sample).
            struct Sample {
                std::array<double, 6> fe, exact;
            };
            std::vector<Sample> samples;
            std::array<double, 6> scale{};
            for (int t = 0; t < space.elementCount(); ++t)
                for (int s = 0; s < 8; ++s) {
                    const Eigen::Vector2d x = randomPointIn(mesh, t, rng);
                    Sample smp{field(space, u, t, x), {}};
                    for (int k = 0; k < 6; ++k) {
                        smp.exact[k] = p(x, kVertexDerivative[k][0], kVertexDerivative[k][1]);
                        scale[k] = std::max(scale[k], std::abs(smp.exact[k]));
                    }
                    samples.push_back(smp);
                }
            const double orderScale[3] = {std::max(scale[0], 0.0), std::max(scale[1], scale[2]),
                                          std::max({scale[3], scale[4], scale[5]})};
            double worst = 0.0;
            for (const auto& smp : samples)
                for (int k = 0; k < 6; ++k) {
                    const int order = kVertexDerivative[k][0] + kVertexDerivative[k][1];
                    const double rel = std::abs(smp.fe[k] - smp.exact[k]) / orderScale[order];
                    worst = std::max(worst, rel);
                    ASSERT_LT(rel, 1e-9) << "component " << k;
                }
            if (trial == 0)
                std::cout << "[ info ] mesh " << mc.nx << "x" << mc.ny
                          << ": worst relative P5 reproduction error = " << worst << "\n";
        }
    }
}

// Degree 6 is NOT reproduced: guards the previous test against a vacuous comparison.
TEST(Argyris, DoesNotReproduceSexticPolynomials) {
    std::mt19937 rng(7);
    const Mesh mesh(0.9, 0.5, 3, 4);
    const ArgyrisSpace space(mesh);
    const Polynomial p(6, {0.2, 0.1}, 0.9, rng);
    const Eigen::VectorXd u = interpolate(space, p);
    double worst = 0.0, scale = 0.0;
    for (int t = 0; t < space.elementCount(); ++t)
        for (int s = 0; s < 8; ++s) {
            const Eigen::Vector2d x = randomPointIn(mesh, t, rng);
            worst = std::max(worst, std::abs(field(space, u, t, x)[0] - p(x)));
            scale = std::max(scale, std::abs(p(x)));
        }
    EXPECT_GT(worst / scale, 1e-6);
}

TEST(Argyris, GlobalFieldIsC1AcrossEdges) {
    std::mt19937 rng(2024);
    for (const auto& mc : kMeshes) {
        const Mesh mesh(mc.length, mc.width, mc.nx, mc.ny);
        const ArgyrisSpace space(mesh);
        const Eigen::VectorXd u = randomDofs(space, rng);
        // Triangles of every edge.
        std::map<int, std::vector<int>> edgeElements;
        for (int t = 0; t < space.elementCount(); ++t)
            for (int l = 0; l < 3; ++l)
                edgeElements[static_cast<int>(space.elementDofs(t)[18 + l] - 6 * mesh.vertexCount())].push_back(t);
        struct Pair {
            std::array<double, 6> left, right;
            Eigen::Vector2d n;
        };
        std::vector<Pair> pairs;
        std::array<double, 6> scale{};
        for (const auto& [e, ts] : edgeElements) {
            if (ts.size() != 2) continue;
            const auto& ev = space.edgeVertices(e);
            for (double s : {0.0, 0.13, 0.31, 0.5, 0.72, 0.94, 1.0}) {
                const Eigen::Vector2d x = (1 - s) * mesh.point(ev[0]) + s * mesh.point(ev[1]);
                Pair pr{field(space, u, ts[0], x), field(space, u, ts[1], x), space.edgeNormal(e)};
                for (int k = 0; k < 6; ++k)
                    scale[k] = std::max({scale[k], std::abs(pr.left[k]), std::abs(pr.right[k])});
                pairs.push_back(pr);
            }
        }
        ASSERT_EQ(pairs.size() / 7, static_cast<size_t>(space.edgeCount() - 2 * (mc.nx + mc.ny)));
        const double gradScale = std::max(scale[1], scale[2]);
        const double hessScale = std::max({scale[3], scale[4], scale[5]});
        double worstC1 = 0.0, worstNormalCurvatureJump = 0.0;
        for (const auto& pr : pairs) {
            EXPECT_LT(std::abs(pr.left[0] - pr.right[0]), 1e-9 * scale[0]);
            EXPECT_LT(std::abs(pr.left[1] - pr.right[1]), 1e-9 * gradScale);
            EXPECT_LT(std::abs(pr.left[2] - pr.right[2]), 1e-9 * gradScale);
            worstC1 = std::max({worstC1, std::abs(pr.left[0] - pr.right[0]) / scale[0],
                                std::abs(pr.left[1] - pr.right[1]) / gradScale,
                                std::abs(pr.left[2] - pr.right[2]) / gradScale});
            const auto wnn = [&](const std::array<double, 6>& f) {
                return pr.n.x() * pr.n.x() * f[3] + 2 * pr.n.x() * pr.n.y() * f[4] + pr.n.y() * pr.n.y() * f[5];
            };
            worstNormalCurvatureJump =
                std::max(worstNormalCurvatureJump, std::abs(wnn(pr.left) - wnn(pr.right)) / hessScale);
        }
        std::cout << "[ info ] mesh " << mc.nx << "x" << mc.ny << ": worst C1 jump = " << worstC1
                  << ", worst w_nn jump = " << worstNormalCurvatureJump << "\n";
        // The element is C1, not C2: w_nn does jump, so the samples do come from two elements.
        EXPECT_GT(worstNormalCurvatureJump, 1e-3);
    }
}

TEST(Argyris, ExactClampAlongXEqualsZero) {
    std::mt19937 rng(99);
    for (const auto& mc : kMeshes) {
        const Mesh mesh(mc.length, mc.width, mc.nx, mc.ny);
        const ArgyrisSpace space(mesh);
        const auto clamped = space.clampedDofs();

        // Exactly: 5 dofs per clamped vertex (w_xx free) + one per edge on x = 0.
        ASSERT_EQ(clamped.size(), static_cast<size_t>(5 * (mc.ny + 1) + mc.ny));
        EXPECT_TRUE(std::is_sorted(clamped.begin(), clamped.end()));
        EXPECT_EQ(std::adjacent_find(clamped.begin(), clamped.end()), clamped.end());
        const std::set<Eigen::Index> clampedSet(clamped.begin(), clamped.end());
        for (int v = 0; v < mesh.vertexCount(); ++v) {
            for (int k = 0; k < 6; ++k) {
                const bool expected = mesh.isClamped(v) && k != 3;
                EXPECT_EQ(clampedSet.count(6 * v + k) == 1, expected) << "vertex " << v << " k " << k;
            }
        }

        // Column-0 triangles, with the part of x = 0 they touch.
        std::vector<int> boundaryElements;
        for (int t = 0; t < space.elementCount(); ++t) {
            const auto v = mesh.triangleVertices(t);
            if (mesh.isClamped(v[0]) || mesh.isClamped(v[1]) || mesh.isClamped(v[2])) boundaryElements.push_back(t);
        }
        // Trace of (w, w_x) on x = 0, from every column-0 element: along its edge on x = 0,
        // or at its single vertex there.
        const auto clampTrace = [&](const Eigen::VectorXd& u, double& wMax, double& wxMax) {
            wMax = wxMax = 0.0;
            for (int t : boundaryElements) {
                std::vector<Eigen::Vector2d> onAxis;
                for (int v : mesh.triangleVertices(t))
                    if (mesh.isClamped(v)) onAxis.push_back(mesh.point(v));
                const int samples = onAxis.size() == 2 ? 9 : 1;
                for (int j = 0; j < samples; ++j) {
                    const double s = samples == 1 ? 0.0 : j / (samples - 1.0);
                    const Eigen::Vector2d x =
                        onAxis.size() == 2 ? ((1 - s) * onAxis[0] + s * onAxis[1]).eval() : onAxis[0];
                    const auto f = field(space, u, t, x);
                    wMax = std::max(wMax, std::abs(f[0]));
                    wxMax = std::max(wxMax, std::abs(f[1]));
                }
            }
        };
        // Size of the field elsewhere, for relative tolerances.
        const auto fieldScale = [&](const Eigen::VectorXd& u, double& wScale, double& gScale) {
            wScale = gScale = 0.0;
            for (int t = 0; t < space.elementCount(); ++t)
                for (int s = 0; s < 4; ++s) {
                    const auto f = field(space, u, t, randomPointIn(mesh, t, rng));
                    wScale = std::max(wScale, std::abs(f[0]));
                    gScale = std::max({gScale, std::abs(f[1]), std::abs(f[2])});
                }
        };

        Eigen::VectorXd u = randomDofs(space, rng);
        for (Eigen::Index d : clamped) u[d] = 0.0;
        double wMax, wxMax, wScale, gScale;
        clampTrace(u, wMax, wxMax);
        fieldScale(u, wScale, gScale);
        std::cout << "[ info ] mesh " << mc.nx << "x" << mc.ny << ": clamp |w|/scale = " << wMax / wScale
                  << ", |w_x|/scale = " << wxMax / gScale << "\n";
        EXPECT_LT(wMax, 1e-12 * wScale);
        EXPECT_LT(wxMax, 1e-12 * gScale);

        // w_xx at clamped vertices is free: it does change w_xx there, and does not disturb
        // the clamp.
        const double h = std::max(mesh.hx(), mesh.hy());
        for (int j = 0; j <= mc.ny; ++j) {
            const int v = mesh.vertex(0, j);
            u[6 * v + 3] = (j % 2 ? 1.0 : -2.0) / (h * h);
        }
        clampTrace(u, wMax, wxMax);
        EXPECT_LT(wMax, 1e-12 * wScale);
        EXPECT_LT(wxMax, 1e-12 * gScale);
        for (int j = 0; j <= mc.ny; ++j) {
            const int v = mesh.vertex(0, j);
            const int t = space.elementContaining(mesh.point(v));
            EXPECT_NEAR(field(space, u, t, mesh.point(v))[3], u[6 * v + 3], 1e-9 / (h * h));
        }

        // Every clamped dof is needed: alone, each one breaks the clamp (no dof is fixed that
        // the trace of (w, w_x) does not see).
        for (Eigen::Index d : clamped) {
            Eigen::VectorXd e = Eigen::VectorXd::Zero(space.dofCount());
            e[d] = 1.0;
            double wm, wxm;
            clampTrace(e, wm, wxm);
            EXPECT_GT(std::max(wm, wxm * h), 1e-6) << "clamped dof " << d << " is invisible";
        }
    }
}

TEST(Argyris, QuadratureIntegratesDegreeTenExactly) {
    const Mesh mesh(0.9, 0.5, 3, 4);
    const ArgyrisSpace space(mesh);
    const double hx = mesh.hx(), hy = mesh.hy();
    for (int t = 0; t < space.elementCount(); ++t) {
        const auto nodes = space.quadrature(t);
        const Eigen::Vector2d o = mesh.point(mesh.cellVertices(t / 2)[0]);
        double area = 0.0;
        for (const auto& q : nodes) {
            EXPECT_EQ(q.piece, 0);
            EXPECT_EQ(space.pieceContaining(t, q.point), 0);
            EXPECT_EQ(space.elementContaining(q.point), t);  // nodes are interior
            area += q.weight;
        }
        EXPECT_NEAR(area, 0.5 * hx * hy, 1e-15);
        // Shifted monomials X^a Y^b, X = x - x_o, Y = y - y_o. Triangle 2c is
        // {0 <= Y <= X hy/hx}: ∫ = hx^{a+1} hy^{b+1} / ((b+1)(a+b+2)); triangle 2c+1 is
        // {0 <= X <= Y hx/hy}: ∫ = hx^{a+1} hy^{b+1} / ((a+1)(a+b+2)).
        for (int a = 0; a <= 10; ++a)
            for (int b = 0; a + b <= 10; ++b) {
                double s = 0.0;
                for (const auto& q : nodes)
                    s += q.weight * std::pow(q.point.x() - o.x(), a) * std::pow(q.point.y() - o.y(), b);
                const double exact =
                    std::pow(hx, a + 1) * std::pow(hy, b + 1) / ((t % 2 == 0 ? b + 1 : a + 1) * (a + b + 2.0));
                EXPECT_NEAR(s, exact, 1e-13 * exact) << "t " << t << " a " << a << " b " << b;
            }
    }
}

TEST(Argyris, FactoryAndEvaluateReuseStorage) {
    const Mesh mesh(1.2, 0.4, 14, 5);
    const auto space = makeArgyrisSpace(mesh);
    ASSERT_NE(space, nullptr);
    EXPECT_EQ(space->type(), ElementType::Argyris);
    EXPECT_EQ(space->elementCount(), 140);
    LocalBasis b;
    space->evaluate(3, 0, {0.1, 0.02}, b);
    const double* p = b.value.data();
    space->evaluate(7, 0, {0.2, 0.05}, b);
    EXPECT_EQ(b.value.data(), p);  // no reallocation on the second call
    EXPECT_EQ(b.dyy.size(), 21);
    // Partition of unity: the w-value shape functions sum to 1 (constants are in P5).
    double s = 0.0;
    for (int l = 0; l < 3; ++l) s += b.value[6 * l];
    EXPECT_NEAR(s, 1.0, 1e-12);
}

}  // namespace
}  // namespace plate
