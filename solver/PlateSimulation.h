#pragma once
// The plate as a co-simulation component: the communication grid. Parameters in, the scheme
// `time_scheme` chose (made once, MakeScheme.h) advanced at its fixed Δt, the inputs as signals
// over each communication step, the outputs at and between grid points. No FMI knowledge here.
#include <Eigen/Core>
#include <Eigen/Sparse>
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "InputSignal.h"
#include "StepPlan.h"
#include "schemes/PlateOutputs.h"
#include "plate/PlateParameters.h"
#include "plate/ResourceEstimate.h"

namespace plate {

class Scheme;

// discretization_check is not the plate's own: CheckedPlate (CheckedPlate.h) adds it on top, through
// the virtual members below, and the plate never sees it.
class PlateSimulation {
public:
    // Builds the discretization, factors A, and computes the initial static state
    // (equilibrium under initialLoad between the obstacles, clamp at baseDisplacement0). With a
    // singular mass the massless part is then brought to equilibrium under loadAtStart, the
    // load input at t = 0 (docs/theory.md §11).
    // Throws ParameterError with a message naming the parameter, value and allowed range, and
    // ResourceError (before anything large is allocated) when the estimated memory exceeds
    // parameters.memoryLimit. `log` receives the resource estimate and, for initializations
    // estimated at seconds or more, one line per phase.
    PlateSimulation(const PlateParameters& parameters, double baseDisplacement0, double loadAtStart = 0.0,
                    const ProgressLog& log = {});
    virtual ~PlateSimulation();
    PlateSimulation(const PlateSimulation&) = delete;
    PlateSimulation& operator=(const PlateSimulation&) = delete;

    const PlateParameters& parameters() const;
    double time() const;  // the communication time t_c (= t_n = n Δt on the grid)
    long long stepCount() const;

    // Advances `steps` internal steps; inside, base and load follow the given signals with
    // s = t - time() at the call. Throws StepError (state left at the last good step).
    // Only from a communication time on the grid.
    void advance(long long steps, const InputSignal& base, const InputSignal& load);

    // Any communication step h > 0 (docs/theory.md §15): the plan (throws StepError for a step
    // shorter than the smallest the grid can resolve), and the step itself with the inputs over
    // [t_c, t_c + h] as signals from t_c.
    StepPlan plan(double h) const;
    // Called at each grid point inside a communication step (not at its end), the simulation
    // standing there: time() that grid point, outputs() its values (FMI 3.0 intermediate
    // update). communicateUntilContactChange ends the step there when it returns true.
    using GridPointObserver = std::function<bool()>;
    virtual void communicate(const StepPlan& plan, const InputSignal& base, const InputSignal& load,
                             const GridPointObserver& observer = {});
    // As communicate (the same steps, bit for bit), but the step ends early, on the grid point at
    // which the contact set becomes non-empty (an impact) or empty (a release), if the step
    // reaches it (FMI 3.0 early return), or where the observer asks; returns whether the step
    // ended early.
    virtual bool communicateUntilContactChange(const StepPlan& plan, const InputSignal& base, const InputSignal& load,
                                               const GridPointObserver& observer = {});
    // Called before each internal step with s (the grid time it steps to, from the communication
    // time, as the signals') and the base and load the signals give there, which it may replace
    // (FMI 3.0 intermediate update: the master's inputs at that grid point). Empty: the signals.
    using InputSampler = std::function<void(double s, double& base, double& load)>;
    void setInputSampler(InputSampler sampler);

    // At the communication time: on the grid the scheme's values; between grid points the linear
    // interpolation of the two neighbours (counts: the earlier one). `port` adds the port's fields.
    // `field` adds the root's stress, or that and the plate's largest stress (§23).
    virtual PlateOutputs outputs(bool port = false, FieldOutputs field = FieldOutputs::None) const;
    // The probes' motion at the communication time (§23), one entry per probe, interpolated as outputs().
    ProbeOutputs probes() const;

    // Vertex values of the absolute displacement at t_n (for plots and checks).
    std::vector<double> vertexDisplacements() const;
    // The von Mises surface stress at every mesh vertex at t_n, Pa (docs/theory.md §23).
    std::vector<double> vertexStress() const;

    // What this instance was estimated to cost before it was built (ResourceEstimate.h).
    const ResourceEstimate& resources() const;
    CarrierOutputs carrierOutputs() const;
    ToleranceHorizon toleranceHorizon() const;  // the flow law's with a tolerance (Scheme.h)

    // "sparse" (factor of A), "modal-complete" (exact, all modes) or "modal-<m>" (reduced).
    std::string engine() const;
    Eigen::Index dofCount() const;  // free dofs of the FE space

    // Lowest natural frequency of the clamped plate, Hz (the accuracy yardstick of a mesh).
    double firstFrequency() const;

    // Largest eigenvalue of M^{-1} K of the clamped plate (κ_h, docs/theory.md), s^-2.
    double kappa() const;

    // Full mutable state: serialize for FMU states (bit-identical continuation).
    virtual std::vector<double> saveState() const;
    virtual void restoreState(const std::vector<double>& state);  // throws std::invalid_argument

private:
    PlateOutputs gridOutputs(bool port, FieldOutputs field = FieldOutputs::None) const;
    struct Impl;
    template <class StopAfter>
    bool stepThrough(const StepPlan& plan, const InputSignal& base, const InputSignal& load, StopAfter&& stopAfter);
    std::unique_ptr<Impl> impl_;
};

}  // namespace plate
