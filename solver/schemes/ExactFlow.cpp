#include "schemes/ExactFlow.h"

#include <algorithm>
#include <cmath>

#include "base/PortableMath.h"

namespace plate {

namespace {

// The exact flow over h of ü + c u̇ + ω² u = 0 (docs/theory.md §21): (u, u̇)(h) = Φ (u, u̇)(0).
// Undamped, a rotation by ωh (the portable sine and cosine: the same bits on every CPU). Damped,
// exp(A h) of A = [[0, ω], [−ω, −c]] in the balanced variables (u, u̇/ω), by scaling and squaring
// (‖A h‖/2^j ≤ ½, Taylor to degree 20: below 2^-60, then j squarings) — IEEE operations only.
void modalFlow(double omega2, double c, double h, double& f11, double& f12, double& f21, double& f22) {
    const double omega = std::sqrt(omega2);
    if (c == 0.0) {
        double sn, cs;
        portable::sinCos(omega * h, sn, cs);
        f11 = cs, f12 = sn / omega, f21 = -omega * sn, f22 = cs;
        return;
    }
    int exponent = 0;
    std::frexp((omega + c) * h, &exponent);
    const int squarings = std::max(0, exponent + 1);
    const double scale = std::ldexp(h, -squarings);
    const double x12 = omega * scale, x21 = -omega * scale, x22 = -c * scale;  // X = A h / 2^j
    // Taylor: E = Σ X^k / k!, the power kept as T = X^k / k!.
    double e11 = 1.0, e12 = 0.0, e21 = 0.0, e22 = 1.0, t11 = 1.0, t12 = 0.0, t21 = 0.0, t22 = 1.0;
    for (int k = 1; k <= 20; ++k) {
        const double n11 = (t12 * x21) / k, n12 = (t11 * x12 + t12 * x22) / k;
        const double n21 = (t22 * x21) / k, n22 = (t21 * x12 + t22 * x22) / k;
        t11 = n11, t12 = n12, t21 = n21, t22 = n22;
        e11 += t11, e12 += t12, e21 += t21, e22 += t22;
    }
    for (int j = 0; j < squarings; ++j) {
        const double a = e11 * e11 + e12 * e21, b = e11 * e12 + e12 * e22;
        const double d = e21 * e11 + e22 * e21, g = e21 * e12 + e22 * e22;
        e11 = a, e12 = b, e21 = d, e22 = g;
    }
    f11 = e11, f12 = e12 / omega, f21 = e21 * omega, f22 = e22;
}

}  // namespace

ExactFlow::ExactFlow(const Eigen::VectorXd& omega2, const Eigen::VectorXd& damping, double h) {
    const Eigen::Index m = omega2.size();
    for (Eigen::VectorXd* v : {&f11, &f12, &f21, &f22}) v->resize(m);
    for (Eigen::Index k = 0; k < m; ++k) modalFlow(omega2[k], damping[k], h, f11[k], f12[k], f21[k], f22[k]);
}

}  // namespace plate
