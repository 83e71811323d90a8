#pragma once
// time_scheme = flow (docs/theory.md §21): a step without contact advances every massive mode by
// its exact flow (the base linear and the load linear over the step, the damping exact); a step
// in which a row is or becomes active is taken as m midpoint sub-steps of Δt/m, each with its
// discrete gradient (CondensedScheme). Free flight has no phase error, the contact phases are
// resolved, and the energy identity (T.17d) holds step by step.
#include <Eigen/Core>
#include <memory>

#include "schemes/CondensedScheme.h"

namespace plate {

class FlowScheme final : public CondensedScheme {
public:
    // contactSubsteps = m ≥ 1: the sub-steps of a contact step.
    FlowScheme(std::shared_ptr<const CondensedPlate> plate, Obstacles obstacles, double dt, int contactSubsteps,
               double dampingMass = 0.0, double dampingStiffness = 0.0, OutputRows rows = {});

    void step(double zNext, double pNext) override;  // exact free flight, or the sub-steps on contact

private:
    void substeps(double zNext, double pNext);

    MidpointOperator sub_;  // sub-steps of Δt/m
    int substeps_;  // m
    // The exact flow over Δt of each mode's u = q − q_particular (§21): (u, u̇)⁺ = Φ (u, u̇).
    Eigen::VectorXd flow11_, flow12_, flow21_, flow22_;
    Eigen::VectorXd inverseOmega2_;  // 1/ω²
    bool dampedModes_ = false;  // some c_k ≠ 0
    Eigen::VectorXd slope_, offset_, u0_, ud0_, u1_, ud1_;  // the exact step's buffers
    Eigen::VectorXd qIntegral_;  // ∫ q over the exact step
    // The levels t_n, t_{n−1} kept across the sub-steps of one step.
    Eigen::VectorXd qAtStart_, qBeforeStart_, forceAtStart_, forceBeforeStart_;
};

}  // namespace plate
