// The instance's FMI 3.0 arrays (core/Instance.h): the structural parameters that size them (a view
// of an Integer parameter of the table, or a value of its own; some settable in Configuration Mode
// only), and the arrays' values, read and (a parameter array) set with the checks every set makes.
#include <climits>
#include <cmath>

#include "core/Instance.h"

namespace fmu {

std::size_t Instance::arrayLength(const ArrayVariable& array) const {
    std::size_t n = 1;
    for (ValueReference extent : array.extents) {
        const StructuralParameter* s = model_->findStructural(extent);
        n *= s ? structuralValue(*s) : 0;
    }
    return n;
}

std::size_t Instance::structuralValue(const StructuralParameter& s) const {
    const Variable* base = model_->find(s.parameter);
    const double value = s.ownValue() ? model_->ownStructuralValue(s) : base ? model_->get(*base) + s.offset : 0.0;
    return value > 0 ? static_cast<std::size_t>(value) : 0;
}

Status Instance::setStructural(const StructuralParameter& s, double value) {
    if (s.configurationOnly && state_ != ConfigurationMode)
        return fail(
            "%s is a structural parameter: set it in Configuration Mode (fmi3EnterConfigurationMode, set it, "
            "fmi3ExitConfigurationMode, before fmi3EnterInitializationMode), not in state %s",
            s.name, stateName(state_));
    if (s.ownValue()) {
        if (!(state_ & (Instantiated | ConfigurationMode)))
            return fail(
                "%s is a fixed structural parameter: set it before initialization (instantiated or "
                "configuration mode)",
                s.name);
        if (!(value >= s.min && value <= s.max))
            return fail("%s = %.0f rejected: allowed %d to %d", s.name, value, s.min, s.max);
        model_->setOwnStructuralValue(s, value);
        return Status::OK;
    }
    const double parameter = value - s.offset;
    const Variable* base = model_->find(s.parameter);
    if (!base) return fail("internal error: %s is a view of no parameter", s.name);
    if (!(parameter >= INT_MIN && parameter <= INT_MAX))
        return fail("%s = %.0f rejected: it sets %s = %s - %d out of the Int32 range", s.name, value, base->name,
                    s.name, s.offset);
    return setValues(VariableType::Integer, &s.parameter, 1, &parameter);
}

Status Instance::getArray(const ArrayVariable& array, double value[], std::size_t n) {
    if (n > 0 && !value) return fail("argument values[] must not be NULL");
    if (array.causality == Causality::Parameter) {  // the model's values, built or not
        model_->getArray(array, value, n);
        return Status::OK;
    }
    // As getValues: an output read in initialization mode builds what the parameters describe.
    if (state_ == InitializationMode && !model_->built()) model_->build();
    if (!model_->built()) return fail("%s is not available before initialization", array.name);
    model_->getArray(array, value, n);
    return Status::OK;
}

Status Instance::setArray(const ArrayVariable& array, const double value[], std::size_t n) {
    if (array.causality != Causality::Parameter)
        return fail("%s (vr %u) is an output array and cannot be set", array.name, array.vr);
    if (!(state_ & (Instantiated | ConfigurationMode | InitializationMode))) {
        log(Status::Error, LogStatusError,
            "illegal call sequence: %s of fixed parameter array %s (vr %u) in state %s; fixed parameters can only "
            "be set before %s",
            function_, array.name, array.vr, stateName(state_), names_.exitInitializationMode);
        return Status::Error;
    }
    if (n > 0 && !value) return fail("argument values[] must not be NULL");
    for (std::size_t k = 0; k < n; ++k)
        if (!std::isfinite(value[k]))
            return fail("%s[%zu] = %g rejected: NaN and Inf are not allowed", array.name, k, value[k]);
    model_->setArray(array, value, n);
    // Before initialization ends, what was built (an output was read) came from the old values.
    if (model_->built()) model_->drop();
    return Status::OK;
}

}  // namespace fmu
