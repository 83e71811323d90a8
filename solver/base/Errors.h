#pragma once
// The two ways the solver refuses: a bad parameter (at construction) and a step it cannot take.
#include <stdexcept>

namespace plate {

// A parameter or input outside its allowed range. what() names the parameter, its value and
// the allowed range, ready for the FMU's log.
class ParameterError : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

// A time step that cannot be taken (input past an obstacle, non-finite input, QP failure).
class StepError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace plate
