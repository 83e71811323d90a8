#pragma once
// The plate as a co-simulation component: parameters in, the Newmark–contact scheme (3.3)
// advanced at a fixed Δt, probe values and energies out. No FMI knowledge here.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "InputSignal.h"
#include "PlateParameters.h"

namespace plate {

struct PlateOutputs {
    double corner1 = 0, corner2 = 0, freeEdgeMid = 0;  // w at (L,0), (L,W), (L,W/2), m
    double energy = 0;  // discrete energy E^{n-1/2} (docs/theory.md), J
    double energyDissipated = 0;  // cumulative contact loss, J
    double energyInput = 0;  // cumulative work of base motion and load, J
    double energyDamped = 0;  // cumulative work of the Rayleigh damping, J
    int contactVertices = 0;  // vertices on an obstacle after the last step
    double maxKktResidual = 0;  // largest relative KKT residual of all QPs so far
    int qpIterations = 0;  // active-set iterations of the last step
    long long qpIterationsTotal = 0;
    int qpIterationsMax = 0;
};

class PlateSimulation {
public:
    // Builds the discretization, factors A, and computes the initial static state
    // (equilibrium under initialLoad between the obstacles, clamp at baseDisplacement0). With a
    // singular mass the massless part is then brought to equilibrium under loadAtStart, the
    // load input at t = 0 (docs/theory.md §11).
    // Throws ParameterError with a message naming the parameter, value and allowed range.
    PlateSimulation(const PlateParameters& parameters, double baseDisplacement0, double loadAtStart = 0.0);
    ~PlateSimulation();
    PlateSimulation(const PlateSimulation&) = delete;
    PlateSimulation& operator=(const PlateSimulation&) = delete;

    const PlateParameters& parameters() const;
    double time() const;  // t_n = n Δt
    long long stepCount() const;
    double baseDisplacement() const;  // z(t_n), the clamp position of the last step

    // Advances `steps` internal steps; inside, base and load follow the given signals with
    // s = t - time() at the call. Throws StepError (state left at the last good step).
    void advance(long long steps, const InputSignal& base, const InputSignal& load);

    PlateOutputs outputs() const;

    // Displacement field at any point of the plate at t_n (absolute, includes the base).
    double displacement(double x, double y) const;
    // Vertex values of the absolute displacement at t_n (for plots and checks).
    std::vector<double> vertexDisplacements() const;

    // "sparse" (factor of A), "modal-complete" (exact, all modes) or "modal-<m>" (reduced).
    std::string engine() const;
    Eigen::Index dofCount() const;  // free dofs of the FE space

    // Lowest natural frequency of the clamped plate, Hz (the accuracy yardstick of a mesh).
    double firstFrequency() const;

    // Largest eigenvalue of M^{-1} K of the clamped plate (κ_h, docs/theory.md), s^-2.
    double kappa() const;
    // Time of one solve with the factor of A, measured now (median of repeats), s.
    double measureFloorSolveSeconds(int repeats = 2000) const;

    // Energy of the initial state before the singular mass's massless part was brought to
    // equilibrium (equal to outputs().energy at t = 0 otherwise), J.
    double unprojectedInitialEnergy() const;

    // Full mutable state: serialize for FMU states (bit-identical continuation).
    std::vector<double> saveState() const;
    void restoreState(const std::vector<double>& state);  // throws std::invalid_argument

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace plate
