#pragma once
// The exact flow over h of each mode's ü + c u̇ + ω² u = 0 (docs/theory.md §21): (u, u̇)(h) = Φ (u, u̇)(0),
// Φ = [[f11, f12], [f21, f22]] per mode. The flow law's free flight, and its error estimate's E
// carried through it (StepDoubling).
#include <Eigen/Core>

namespace plate {

struct ExactFlow {
    Eigen::VectorXd f11, f12, f21, f22;
    ExactFlow() = default;
    ExactFlow(const Eigen::VectorXd& omega2, const Eigen::VectorXd& damping, double h);
};

}  // namespace plate
