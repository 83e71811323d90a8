#pragma once
// The FMI 3.0 front end's get and set of values (fmi3Get/Set<Type>, fmi3Functions.cpp): the FMI 3.0
// types against the table's, the independent variable time, the structural parameters (UInt64) and
// the arrays (as many values as their extents give now), checked, then handed to the core.
#include <cstddef>
#include <string>

#include "core/Instance.h"
#include "fmi3PlatformTypes.h"

namespace fmu {
namespace fmi3 {

// The FMI 3.0 types of the get/set functions, as far as they concern this layer.
enum class Kind { Float64, Int32, Int64, UInt64, Boolean, Other };

// The FMI 3.0 type and name of the variable behind vr, for messages ("the Float64 variable length").
std::string describe(const Model& model, fmi3ValueReference vr);
// fmi3Get<Kind> and fmi3Set<Kind> of nvr value references, nValues values (T: the C type of Kind).
template <class T>
Status getValues(Instance& i, Kind kind, const fmi3ValueReference vrs[], size_t nvr, T values[], size_t nValues);
template <class T>
Status setValues(Instance& i, Kind kind, const fmi3ValueReference vrs[], size_t nvr, const T values[], size_t nValues);
// fmi3Get/Set of a type this FMU has no variables of.
Status noVariables(Instance& i, const char* type, const fmi3ValueReference vrs[], size_t nvr);

}  // namespace fmi3
}  // namespace fmu
