#pragma once
// Free flight without looking at the contact points (docs/theory.md §7, §17), for every scheme: at
// the last full look every point was `margin` inside the obstacles with the plate at x0 (its
// coordinates), the base at z0 and the load at p0. A point i moves with the plate by ‖C_i‖ ‖x − x0‖
// at most, with the base by |z − z0| and with the load by |c_i| |p − p0|; while the sum stays below
// the margin no point can touch, and the look, which would find nothing, is skipped. Results are
// identical either way. 1e-12 m: roundoff of the values the bound is compared with.
#include <Eigen/Core>
#include <cmath>

namespace plate {

class FreeFlightBound {
public:
    // rowNorm: the largest ‖C_i‖ (0: no bound, every step looks); loadNorm: the largest |c_i|.
    void setup(Eigen::Index size, double rowNorm, double loadNorm = 0.0) {
        rowNorm_ = rowNorm;
        loadNorm_ = loadNorm;
        if (rowNorm_ > 0.0) x0_.resize(size);
    }
    // No point can have come within `reserve` of an obstacle since the last look.
    bool holds(const Eigen::VectorXd& x, double z, double p = 0.0, double reserve = 0.0) const {
        if (margin_ <= 0.0) return false;
        const double moved = rowNorm_ * (x - x0_).norm() + std::abs(z - z0_) + std::abs(p - p0_) * loadNorm_;
        return moved + reserve + 1e-12 < margin_;
    }
    // A look found every point `margin` inside the obstacles at (x, z, p): the bound starts there.
    void restart(const Eigen::VectorXd& x, double z, double p, double margin) {
        if (rowNorm_ <= 0.0) return;
        x0_ = x;  // same size: no allocation
        z0_ = z;
        p0_ = p;
        margin_ = margin;
    }
    void reset() { margin_ = -1.0; }  // the next step looks

private:
    double rowNorm_ = 0.0, loadNorm_ = 0.0;
    Eigen::VectorXd x0_;
    double z0_ = 0.0, p0_ = 0.0, margin_ = -1.0;
};

}  // namespace plate
