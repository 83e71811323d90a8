#pragma once
// The two ways the solver refuses: a bad parameter (at construction) and a step it cannot take.
#include <limits>
#include <stdexcept>
#include <string>

namespace plate {

// A parameter or input outside its allowed range. what() names the parameter, its value and
// the allowed range, ready for the FMU's log.
class ParameterError : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

// A time step that cannot be taken (input past an obstacle, non-finite input, QP failure). A scheme's
// refusal carries the time of the step it could not take, t_{n+1} in the scheme's time (NaN where no
// step is named: a communication step refused before it starts).
class StepError : public std::runtime_error {
public:
    explicit StepError(const std::string& what, double time = std::numeric_limits<double>::quiet_NaN())
        : std::runtime_error(what), time_(time) {}
    double time() const { return time_; }

private:
    double time_;
};

}  // namespace plate
