#include "CheckedPlate.h"

#include <cmath>
#include <stdexcept>

#include "DiscretizationCheck.h"

namespace plate {

CheckedPlate::CheckedPlate(const PlateParameters& p, double baseDisplacement0, double loadAtStart,
                           const ProgressLog& log)
    : PlateSimulation(p, baseDisplacement0, loadAtStart, log) {
    if (p.outputs.discretizationCheck)
        check_ = std::make_unique<DiscretizationCheck>(*this, baseDisplacement0, loadAtStart);
}

CheckedPlate::~CheckedPlate() = default;

void CheckedPlate::communicate(const StepPlan& plan, const InputSignal& base, const InputSignal& load,
                               const GridPointObserver& observer) {
    PlateSimulation::communicate(plan, base, load, observer);
    if (check_) check_->follow(*this, base, load);
}

bool CheckedPlate::communicateUntilContactChange(const StepPlan& plan, const InputSignal& base, const InputSignal& load,
                                                 const GridPointObserver& observer) {
    const bool early = PlateSimulation::communicateUntilContactChange(plan, base, load, observer);
    if (check_) check_->follow(*this, base, load);
    return early;
}

PlateOutputs CheckedPlate::outputs(bool port, FieldOutputs field) const {
    PlateOutputs o = PlateSimulation::outputs(port, field);
    if (check_) o.discretizationError = check_->error();  // the estimate up to now, also between grid points
    return o;
}

std::string CheckedPlate::takeDiscretizationWarning() { return check_ ? check_->takeWarning() : std::string(); }

std::vector<double> CheckedPlate::saveState() const {
    std::vector<double> out = PlateSimulation::saveState();
    if (check_) {
        const std::vector<double> check = check_->saveState();
        out.insert(out.end(), check.begin(), check.end());
    }
    return out;
}

void CheckedPlate::restoreState(const std::vector<double>& all) {
    if (!check_) return PlateSimulation::restoreState(all);
    const double length = all.empty() ? 0.0 : all.back();  // the check's part, last
    if (!(length >= 2.0 && length <= double(all.size())) || length != std::floor(length))
        throw std::invalid_argument("state does not belong to this plate (its discretization check's part)");
    const auto split = all.end() - std::ptrdiff_t(length);
    const std::vector<double> current = PlateSimulation::saveState();
    PlateSimulation::restoreState(std::vector<double>(all.begin(), split));  // throws: nothing set
    try {
        check_->restoreState(std::vector<double>(split, all.end()));
    } catch (const std::invalid_argument&) {
        PlateSimulation::restoreState(current);
        throw;
    }
}

}  // namespace plate
