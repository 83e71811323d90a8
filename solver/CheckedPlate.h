#pragma once
// The plate with its discretization_check (docs/theory.md §26): the plate as PlateSimulation steps
// it and, when the parameter is on, the check (DiscretizationCheck.h) that follows it after each
// communication step on its coarsened companion. The plate never sees the check (its results are the
// same bits with it or without it); the check's estimate joins the outputs and its part the state.
#include <memory>
#include <string>
#include <vector>

#include "PlateSimulation.h"

namespace plate {

class DiscretizationCheck;

class CheckedPlate final : public PlateSimulation {
public:
    // As PlateSimulation's; with discretization_check the companion too (ParameterError when it
    // cannot be built).
    CheckedPlate(const PlateParameters& parameters, double baseDisplacement0, double loadAtStart = 0.0,
                 const ProgressLog& log = {});
    ~CheckedPlate() override;

    void communicate(const StepPlan& plan, const InputSignal& base, const InputSignal& load,
                     const GridPointObserver& observer = {}) override;
    bool communicateUntilContactChange(const StepPlan& plan, const InputSignal& base, const InputSignal& load,
                                       const GridPointObserver& observer = {}) override;
    // The plate's, with discretization_error the estimate up to now (0 without the check).
    PlateOutputs outputs(bool port = false, FieldOutputs field = FieldOutputs::None) const override;
    // From when discretization_error is a bound rather than an estimate, the message once (then, and
    // without the check, empty).
    std::string takeDiscretizationWarning();

    // The plate's state, then the check's part (its length its own last entry).
    std::vector<double> saveState() const override;
    void restoreState(const std::vector<double>& state) override;  // throws std::invalid_argument

private:
    std::unique_ptr<DiscretizationCheck> check_;  // null without discretization_check
};

}  // namespace plate
