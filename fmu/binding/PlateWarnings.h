#pragma once
// The plate's plausibility warnings at build (PlateWarnings.cpp), and the message formatting the
// binding's messages share.
#include <string>
#include <vector>

#include "binding/PlateVariables.h"

namespace plateimpact {

// printf of up to four numbers into a message (of up to 599 characters).
std::string format(const char* fmt, double a, double b = 0.0, double c = 0.0, double d = 0.0);
// The warnings of a build from these values, in order: units and the thin-plate range, dt against the first period,
// modes beyond the model (values.simulation: the one just built), tolerances the
// scheme ignores, probes that are not what they seem (arrays: the FMI 3.0 FMU's names).
std::vector<std::string> buildWarnings(const PlateValues& values, bool arrays);

}  // namespace plateimpact
