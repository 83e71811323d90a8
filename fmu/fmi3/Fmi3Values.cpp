#include "fmi3/Fmi3Values.h"

#include <type_traits>

#include "fmi3/Fmi3Interface.h"

namespace fmu {
namespace fmi3 {

// The FMI 3.0 type of the variable behind vr, for messages ("Float64 variable length").
std::string describe(const fmu::Model& model, fmi3ValueReference vr) {
    if (vr == kTimeValueReference) return "the Float64 variable time";
    if (const StructuralParameter* s = model.findStructural(vr)) return std::string("the UInt64 variable ") + s->name;
    if (const ArrayVariable* a = model.findArray(vr))
        return std::string("the Float64 ") +
               (a->causality == fmu::Causality::Parameter ? "parameter array " : "array ") + a->name;
    if (const fmu::Variable* v = model.find(vr))
        return std::string("the ") + fmu::fmi3::typeName(v->type) + " variable " + v->name;
    return "no variable (unknown value reference)";
}

// The table's type a Kind reads and writes (Int64 and the rest: none of the table's).
static bool tableTypeOf(Kind kind, const fmu::Variable& v, VariableType* type) {
    switch (kind) {
        case Kind::Float64: *type = VariableType::Real; return v.type == VariableType::Real;
        case Kind::Int32: *type = VariableType::Integer; return v.type == VariableType::Integer;
        case Kind::Boolean: *type = VariableType::Boolean; return v.type == VariableType::Boolean;
        default: return false;
    }
}

// One scalar of an fmi3Get<kind> call into *x.
static Status getScalar(Instance& i, Kind kind, fmi3ValueReference vr, double* x) {
    const fmu::Model& model = i.model();
    if (vr == kTimeValueReference && kind == Kind::Float64) {
        *x = i.currentTime();
        return Status::OK;
    }
    if (const StructuralParameter* s = model.findStructural(vr)) {
        if (kind != Kind::UInt64) return i.fail("value reference %u is %s", vr, describe(model, vr).c_str());
        *x = double(i.structuralValue(*s));
        return Status::OK;
    }
    const fmu::Variable* v = model.find(vr);
    VariableType type;
    if (!v || !tableTypeOf(kind, *v, &type)) return i.fail("value reference %u is %s", vr, describe(model, vr).c_str());
    return i.getValues(type, &vr, 1, x);
}

// Outputs exist from initialization mode on (parameters and inputs can be read before).
static bool beforeInitialization(const Instance& i, fmi3ValueReference vr) {
    if (!(i.state() & (fmu::Instantiated | fmu::ConfigurationMode))) return false;
    const fmu::Variable* v = i.model().find(vr);
    const ArrayVariable* a = i.model().findArray(vr);
    return (a && a->causality == fmu::Causality::Output) || vr == kTimeValueReference ||
           (v && v->causality == fmu::Causality::Output);
}

template <class T>
Status getValues(Instance& i, Kind kind, const fmi3ValueReference vrs[], size_t nvr, T values[], size_t nValues) {
    if (nvr == 0) return Status::OK;
    if (!vrs || !values) return i.fail("arguments valueReferences[] and values[] must not be NULL");
    std::size_t next = 0;
    for (size_t k = 0; k < nvr; ++k) {
        if (beforeInitialization(i, vrs[k]))
            return i.fail("value reference %u is %s, an output: available from initialization mode on", vrs[k],
                          describe(i.model(), vrs[k]).c_str());
        const ArrayVariable* array = i.model().findArray(vrs[k]);
        if (array && kind != Kind::Float64)
            return i.fail("value reference %u is %s", vrs[k], describe(i.model(), vrs[k]).c_str());
        const std::size_t n = array ? i.arrayLength(*array) : 1;
        if (nValues - next < n || next > nValues)
            return i.fail(
                "nValues = %zu is too small: %s (value reference %u) needs %zu values, from position %zu "
                "of values[]",
                nValues, describe(i.model(), vrs[k]).c_str(), vrs[k], n, next);
        if (array) {
            if constexpr (std::is_same_v<T, double>) {  // an emptied array (an extent 0) has nothing to ask
                if (n > 0 && i.getArray(*array, values + next, n) != Status::OK) return Status::Error;
            }
        } else {
            double x = 0.0;
            if (getScalar(i, kind, vrs[k], &x) != Status::OK) return Status::Error;
            values[next] = static_cast<T>(x);
        }
        next += n;
    }
    if (next != nValues) {
        std::string arrays;  // which of them are arrays, and their sizes
        for (size_t k = 0; k < nvr; ++k)
            if (const ArrayVariable* array = i.model().findArray(vrs[k]))
                arrays += std::string(arrays.empty() ? "" : ", ") + array->name + " needs " +
                          std::to_string(i.arrayLength(*array)) + " values";
        return i.fail("nValues = %zu, but the %zu value references have %zu values%s%s%s", nValues, nvr, next,
                      arrays.empty() ? "" : " (", arrays.c_str(), arrays.empty() ? "" : ")");
    }
    return Status::OK;
}

static Status setScalar(Instance& i, Kind kind, fmi3ValueReference vr, double x) {
    const fmu::Model& model = i.model();
    if (const StructuralParameter* s = model.findStructural(vr); s && kind == Kind::UInt64)
        return i.setStructural(*s, x);
    if (vr == kTimeValueReference)
        return i.fail("value reference %u is %s, which cannot be set", vr, describe(model, vr).c_str());
    const fmu::Variable* v = model.find(vr);
    VariableType type;
    if (!v || !tableTypeOf(kind, *v, &type)) return i.fail("value reference %u is %s", vr, describe(model, vr).c_str());
    return i.setValues(type, &vr, 1, &x);
}

// The values of every value reference, an array's as many as its extents give now (a parameter
// array: Float64; an output array is refused by name).
template <class T>
Status setValues(Instance& i, Kind kind, const fmi3ValueReference vrs[], size_t nvr, const T values[], size_t nValues) {
    if (nvr == 0) return Status::OK;
    if (!vrs || !values) return i.fail("arguments valueReferences[] and values[] must not be NULL");
    std::size_t next = 0;
    for (size_t k = 0; k < nvr; ++k) {
        const ArrayVariable* array = i.model().findArray(vrs[k]);
        if (array && (kind != Kind::Float64 || array->causality != fmu::Causality::Parameter))
            return i.fail("value reference %u is %s, which cannot be set%s", vrs[k],
                          describe(i.model(), vrs[k]).c_str(), kind != Kind::Float64 ? " with this type" : "");
        const std::size_t n = array ? i.arrayLength(*array) : 1;
        if (next > nValues || nValues - next < n)
            return i.fail(
                "nValues = %zu is too small: %s (value reference %u) takes %zu values, from position %zu of values[]",
                nValues, describe(i.model(), vrs[k]).c_str(), vrs[k], n, next);
        if (array) {
            if constexpr (std::is_same_v<T, double>) {
                if (i.setArray(*array, values + next, n) != Status::OK) return Status::Error;
            }
        } else {
            const double x = kind == Kind::Boolean ? double(values[next] != 0) : double(values[next]);
            if (setScalar(i, kind, vrs[k], x) != Status::OK) return Status::Error;
        }
        next += n;
    }
    if (next != nValues)
        return i.fail("nValues = %zu, but the %zu value references take %zu values", nValues, nvr, next);
    return Status::OK;
}

Status noVariables(Instance& i, const char* type, const fmi3ValueReference vrs[], size_t nvr) {
    if (nvr == 0) return Status::OK;
    const fmi3ValueReference vr = vrs ? vrs[0] : 0u;
    return i.fail("this FMU has no %s variables (value reference %u is %s)", type, vr, describe(i.model(), vr).c_str());
}

// The C types of fmi3Get/Set<Float64, Int32, Int64, UInt64, Boolean>.
template Status getValues(Instance&, Kind, const fmi3ValueReference[], size_t, fmi3Float64[], size_t);
template Status getValues(Instance&, Kind, const fmi3ValueReference[], size_t, fmi3Int32[], size_t);
template Status getValues(Instance&, Kind, const fmi3ValueReference[], size_t, fmi3Int64[], size_t);
template Status getValues(Instance&, Kind, const fmi3ValueReference[], size_t, fmi3UInt64[], size_t);
template Status getValues(Instance&, Kind, const fmi3ValueReference[], size_t, fmi3Boolean[], size_t);
template Status setValues(Instance&, Kind, const fmi3ValueReference[], size_t, const fmi3Float64[], size_t);
template Status setValues(Instance&, Kind, const fmi3ValueReference[], size_t, const fmi3Int32[], size_t);
template Status setValues(Instance&, Kind, const fmi3ValueReference[], size_t, const fmi3Int64[], size_t);
template Status setValues(Instance&, Kind, const fmi3ValueReference[], size_t, const fmi3UInt64[], size_t);
template Status setValues(Instance&, Kind, const fmi3ValueReference[], size_t, const fmi3Boolean[], size_t);

}  // namespace fmi3
}  // namespace fmu
