#include "fe/Quadrature.h"

#include <cmath>

#include "base/PortableMath.h"

namespace plate {

namespace {

// P_n(x) by the three-term recurrence, and P_n'(x) from P_n and P_{n−1}.
void legendre(int n, double x, double& value, double& derivative) {
    double p0 = 1.0, p1 = x;
    for (int m = 2; m <= n; ++m) {
        const double p2 = ((2.0 * m - 1.0) * x * p1 - (m - 1.0) * p0) / m;
        p0 = p1;
        p1 = p2;
    }
    value = p1;
    derivative = n * (x * p1 - p0) / (x * x - 1.0);
}

}  // namespace

void gaussLegendre01(int n, std::vector<double>& nodes, std::vector<double>& weights) {
    nodes.assign(n, 0.0);
    weights.assign(n, 0.0);
    // Newton on P_n from the Chebyshev-like initial guess; converges to machine precision
    // in a handful of iterations for the small n used here. The guess's cosine is the portable
    // one: the C library's differs by CPU in the last bit, and so could the converged node.
    for (int k = 0; k < n; ++k) {
        double x = portable::cos(M_PI * (k + 0.75) / (n + 0.5)), p, dp;
        for (int it = 0; it < 100; ++it) {
            legendre(n, x, p, dp);
            const double dx = p / dp;
            x -= dx;
            if (std::abs(dx) < 1e-16) break;
        }
        legendre(n, x, p, dp);  // the derivative at the converged node, for the weight
        nodes[k] = 0.5 * (1.0 + x);
        weights[k] = 1.0 / ((1.0 - x * x) * dp * dp);  // 2/((1-x^2)P'^2) scaled by 1/2
    }
}

std::vector<QuadratureNode> triangleRule(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                                         int degree) {
    const int n = (degree + 3) / 2;  // ceil((degree + 2) / 2)
    std::vector<double> x, w;
    gaussLegendre01(n, x, w);
    const Eigen::Vector2d e1 = b - a, e2 = c - a;
    const double area2 = std::abs(e1.x() * e2.y() - e1.y() * e2.x());
    std::vector<QuadratureNode> rule;
    rule.reserve(n * n);
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            // Reference triangle (s, r) = (u, v (1 - u)), Jacobian (1 - u).
            const double s = x[i], r = x[j] * (1.0 - x[i]);
            rule.push_back({a + s * e1 + r * e2, w[i] * w[j] * (1.0 - x[i]) * area2});
        }
    }
    return rule;
}

}  // namespace plate
