#include "fe/ArgyrisTriangle.h"

#include <Eigen/LU>
#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace plate {

namespace {

constexpr int kN = ArgyrisSpace::kLocalDofs;

// Exponents (a, b) of the monomials ξ^a η^b of degree <= 5, graded by degree.
struct MonomialTable {
    std::array<int, kN> a{}, b{};
    constexpr MonomialTable() {
        int j = 0;
        for (int d = 0; d <= 5; ++d)
            for (int q = 0; q <= d; ++q, ++j) {
                a[j] = d - q;
                b[j] = q;
            }
    }
};
constexpr MonomialTable kMonomials;

// Derivative orders (p, q) of the six vertex dofs w, w_x, w_y, w_xx, w_xy, w_yy.
constexpr std::array<std::array<int, 2>, ArgyrisSpace::kVertexDofs> kVertexDerivative = {
    {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}}};

// ∂ξ^p ∂η^q (ξ^a η^b) at (xi, eta).
double monomialDerivative(int a, int b, int p, int q, double xi, double eta) {
    if (p > a || q > b) return 0.0;
    double c = 1.0;
    for (int k = 0; k < p; ++k) c *= a - k;
    for (int k = 0; k < q; ++k) c *= b - k;
    for (int k = 0; k < a - p; ++k) c *= xi;
    for (int k = 0; k < b - q; ++k) c *= eta;
    return c;
}

// Derivative order of local dof i (vertex dofs first, then the three mid-edge dofs).
int derivativeOrder(int i) {
    if (i >= 3 * ArgyrisSpace::kVertexDofs) return 1;
    const auto& pq = kVertexDerivative[i % ArgyrisSpace::kVertexDofs];
    return pq[0] + pq[1];
}

}  // namespace

ArgyrisSpace::ArgyrisSpace(const Mesh& mesh) : mesh_(mesh) {
    const int nt = mesh_.triangleCount();
    elements_.resize(nt);
    elementDofs_.resize(nt);

    // Unique edges, numbered in order of first appearance: deterministic for a given mesh.
    std::map<std::pair<int, int>, int> edgeIndex;
    for (int t = 0; t < nt; ++t) {
        const auto v = mesh_.triangleVertices(t);
        for (int l = 0; l < 3; ++l) {
            const int p = v[l], q = v[(l + 1) % 3];
            const std::pair<int, int> key{std::min(p, q), std::max(p, q)};
            auto [it, inserted] = edgeIndex.emplace(key, static_cast<int>(edges_.size()));
            if (inserted) edges_.push_back({key.first, key.second});
            elements_[t].edges[l] = it->second;
        }
    }
    dofCount_ = kVertexDofs * static_cast<Eigen::Index>(mesh_.vertexCount()) + static_cast<Eigen::Index>(edges_.size());

    for (int t = 0; t < nt; ++t) {
        const auto v = mesh_.triangleVertices(t);
        Element& el = elements_[t];
        const Eigen::Vector2d a = mesh_.point(v[0]), b = mesh_.point(v[1]), c = mesh_.point(v[2]);
        el.centroid = (a + b + c) / 3.0;
        el.h = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});

        auto& dofs = elementDofs_[t];
        dofs.reserve(kN);
        for (int l = 0; l < 3; ++l)
            for (int k = 0; k < kVertexDofs; ++k) dofs.push_back(kVertexDofs * v[l] + k);
        for (int l = 0; l < 3; ++l) dofs.push_back(edgeDof(el.edges[l]));

        // Dual basis: column j of V^{-1} holds the monomial coefficients of the shape function
        // with scaled dof i = δ_ij (Ciarlet §2.3: the basis dual to the dofs). In scaled
        // coordinates the dofs are O(1), so V is well conditioned whatever the element size.
        const LocalMatrix V = scaledDofMatrix(t);
        const Eigen::FullPivLU<LocalMatrix> lu(V);
        if (!lu.isInvertible())
            throw std::runtime_error("Argyris element " + std::to_string(t) +
                                     ": singular dof matrix (degenerate triangle?)");
        el.coefficients = lu.inverse();
        // Scaled dof i is h^{d_i} x physical dof i, so the shape function dual to the physical
        // dof j is h^{d_j} times the one dual to the scaled dof j.
        for (int j = 0; j < kN; ++j) {
            const int d = derivativeOrder(j);
            el.coefficients.col(j) *= d == 0 ? 1.0 : (d == 1 ? el.h : el.h * el.h);
        }
    }
}

Eigen::Vector2d ArgyrisSpace::edgeNormal(int edge) const {
    const auto& e = edges_[edge];
    const Eigen::Vector2d t = (mesh_.point(e[1]) - mesh_.point(e[0])).normalized();
    return {t.y(), -t.x()};  // rot(-90°) t
}

ArgyrisSpace::LocalMatrix ArgyrisSpace::scaledDofMatrix(int element) const {
    const Element& el = elements_[element];
    const auto v = mesh_.triangleVertices(element);
    std::array<Eigen::Vector2d, 3> s;  // vertices in scaled coordinates
    for (int l = 0; l < 3; ++l) s[l] = (mesh_.point(v[l]) - el.centroid) / el.h;

    LocalMatrix V;
    for (int j = 0; j < kN; ++j) {
        const int a = kMonomials.a[j], b = kMonomials.b[j];
        for (int l = 0; l < 3; ++l)
            for (int k = 0; k < kVertexDofs; ++k) {
                const auto& pq = kVertexDerivative[k];
                V(kVertexDofs * l + k, j) = monomialDerivative(a, b, pq[0], pq[1], s[l].x(), s[l].y());
            }
        for (int l = 0; l < 3; ++l) {
            // h ∂/∂n = n_x ∂/∂ξ + n_y ∂/∂η, along the global normal of the edge.
            const Eigen::Vector2d m = 0.5 * (s[l] + s[(l + 1) % 3]);
            const Eigen::Vector2d n = edgeNormal(el.edges[l]);
            V(3 * kVertexDofs + l, j) = n.x() * monomialDerivative(a, b, 1, 0, m.x(), m.y()) +
                                        n.y() * monomialDerivative(a, b, 0, 1, m.x(), m.y());
        }
    }
    return V;
}

const std::vector<Eigen::Index>& ArgyrisSpace::elementDofs(int element) const { return elementDofs_[element]; }

std::vector<ElementQuadratureNode> ArgyrisSpace::quadrature(int element) const {
    const auto v = mesh_.triangleVertices(element);
    const auto rule = triangleRule(mesh_.point(v[0]), mesh_.point(v[1]), mesh_.point(v[2]), 10);
    std::vector<ElementQuadratureNode> nodes;
    nodes.reserve(rule.size());
    for (const auto& q : rule) nodes.push_back({q.point, q.weight, 0});
    return nodes;
}

int ArgyrisSpace::elementContaining(const Eigen::Vector2d& x) const { return mesh_.triangleContaining(x); }

void ArgyrisSpace::evaluate(int element, int /*piece*/, const Eigen::Vector2d& x, LocalBasis& out) const {
    const Element& el = elements_[element];
    const double xi = (x.x() - el.centroid.x()) / el.h;
    const double eta = (x.y() - el.centroid.y()) / el.h;

    // Powers with two leading zeros, so that px[a + 2 - k] is ξ^{a-k} (0 when a < k).
    std::array<double, 8> px{}, py{};
    px[2] = py[2] = 1.0;
    for (int k = 3; k < 8; ++k) {
        px[k] = px[k - 1] * xi;
        py[k] = py[k - 1] * eta;
    }
    using Vec = Eigen::Matrix<double, kN, 1>;
    Vec m, mx, my, mxx, mxy, myy;
    for (int j = 0; j < kN; ++j) {
        const int a = kMonomials.a[j], b = kMonomials.b[j];
        m[j] = px[a + 2] * py[b + 2];
        mx[j] = a * px[a + 1] * py[b + 2];
        my[j] = b * px[a + 2] * py[b + 1];
        mxx[j] = a * (a - 1) * px[a] * py[b + 2];
        mxy[j] = a * b * px[a + 1] * py[b + 1];
        myy[j] = b * (b - 1) * px[a + 2] * py[b];
    }

    // resize() is a no-op once the vectors have the right size: no allocation per call.
    for (Eigen::VectorXd* v : {&out.value, &out.dx, &out.dy, &out.dxx, &out.dxy, &out.dyy}) v->resize(kN);
    const LocalMatrix& C = el.coefficients;
    const double ih = 1.0 / el.h, ih2 = ih * ih;  // ∂/∂x = (1/h) ∂/∂ξ
    out.value.noalias() = C.transpose() * m;
    out.dx.noalias() = ih * (C.transpose() * mx);
    out.dy.noalias() = ih * (C.transpose() * my);
    out.dxx.noalias() = ih2 * (C.transpose() * mxx);
    out.dxy.noalias() = ih2 * (C.transpose() * mxy);
    out.dyy.noalias() = ih2 * (C.transpose() * myy);
}

std::vector<Eigen::Index> ArgyrisSpace::clampedDofs() const {
    std::vector<Eigen::Index> dofs;
    for (int v = 0; v < mesh_.vertexCount(); ++v) {
        if (!mesh_.isClamped(v)) continue;
        // Trace w, w_y, w_yy and normal-derivative trace w_x, w_xy vanish along x = 0;
        // w_xx (k = 3) is not a trace quantity and stays free (docs/theory.md).
        for (int k : {0, 1, 2, 4, 5}) dofs.push_back(kVertexDofs * v + k);
    }
    for (int e = 0; e < edgeCount(); ++e)
        if (mesh_.isClamped(edges_[e][0]) && mesh_.isClamped(edges_[e][1])) dofs.push_back(edgeDof(e));
    std::sort(dofs.begin(), dofs.end());
    dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
    return dofs;
}

std::unique_ptr<FiniteElementSpace> makeArgyrisSpace(const Mesh& mesh) { return std::make_unique<ArgyrisSpace>(mesh); }

}  // namespace plate
