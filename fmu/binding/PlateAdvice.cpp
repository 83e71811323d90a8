#include "binding/PlateAdvice.h"

#include <cmath>
#include <cstdio>

#include "binding/PlateArrays.h"
#include "binding/PlateVariables.h"

namespace plateimpact {

namespace {

std::string text(const char* fmt, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
    char text[600];
    std::snprintf(text, sizeof text, fmt, a, b, c, d);
    return text;
}

// Three significant digits, rounded down: a step of the stated length passes the check.
double roundedDown(double x) {
    const double scale = std::pow(10.0, std::floor(std::log10(x)) - 2.0);
    return std::floor(x / scale) * scale;
}

}  // namespace

std::string capAdvice(const plate::PlateParameters& p) {
    const plate::PlateParameters defaults;
    if (p.timeScheme != plate::TimeScheme::Flow || p.tolerance > 0.0 ||
        p.maxContactSubsteps == defaults.maxContactSubsteps)
        return "";
    return text(
        "max_contact_substeps = %g caps the sub-steps of time_scheme = flow with a tolerance > 0 only; with "
        "tolerance = 0 every contact step takes contact_substeps = %g sub-steps and this run ignores the cap: "
        "to bound a contact step's work set contact_substeps (e.g. %g), or a tolerance in m",
        double(p.maxContactSubsteps), double(p.contactSubsteps), double(p.maxContactSubsteps));
}

bool isStressOutput(fmu::ValueReference vr) {
    switch (vr) {
        case kVrRootStress:
        case kVrRootStressPeak:
        case kVrMaxStress:
        case kVrMaxStressX:
        case kVrMaxStressY:
        case kVrVertexStress: return true;
        default: return false;
    }
}

std::string stressReadAdvice(const char* name, const plate::PlateParameters& p) {
    if (p.stressOutputs) return "";
    return std::string(name) +
           " was read while stress_outputs = false: it reads 0, not computed (so do root_stress, root_stress_peak, "
           "max_stress, max_stress_x, max_stress_y and vertex_stress); set the parameter stress_outputs = true "
           "before initialization to compute them (a master that records every output reads them anyway: then "
           "ignore this)";
}

double longestCommunicationStep(const plate::PlateParameters& p) {
    return 1.0 / (p.firstFrequencyEstimate() * kCommunicationPointsPerPeriod);
}

bool inputChanged(const InputPort& port) {
    if (!port.fresh || port.history.count() == 0) return false;  // not set since the last sample
    if (port.derivativesGiven) return port.signal.d1 != 0.0 || port.signal.d2 != 0.0;
    return port.signal.value != port.history.extrapolate(plate::InputMode::Hold).value;
}

std::string longStepAdvice(const plate::PlateParameters& p, double h, double t, const char* input) {
    const double longest = longestCommunicationStep(p);
    if (h <= longest) return "";
    const double period = 1.0 / p.firstFrequencyEstimate();
    return text("communicationStepSize h = %.6g s at t = %.17g is longer than T1/%g = %.3g s", h, t,
                kCommunicationPointsPerPeriod, longest) +
           text(" (T1 = %.3g s, the plate's first period)", period) + ", and " + input +
           " changed over it: sampled this rarely, the input's motion at the plate's frequencies is not in its "
           "values and the reconstruction between them (base_input_mode, load_input_mode) kicks the plate at "
           "every communication point, so the outputs can be far off (docs/input-accuracy.md); take h <= " +
           text("%.3g s", roundedDown(longest));
}

}  // namespace plateimpact
