#include "binding/PlateAdvice.h"

#include <algorithm>
#include <cmath>

#include "binding/PlateArrays.h"
#include "binding/PlateVariables.h"
#include "binding/PlateWarnings.h"

namespace plateimpact {

namespace {

// Three significant digits, rounded down: a step of the stated length passes the check.
double roundedDown(double x) {
    const double scale = std::pow(10.0, std::floor(std::log10(x)) - 2.0);
    return std::floor(x / scale) * scale;
}

}  // namespace

std::string capAdvice(const plate::PlateParameters& p) {
    const plate::PlateParameters defaults;
    if (p.law.timeScheme != plate::TimeScheme::Flow || p.refinement.tolerance > 0.0 ||
        p.refinement.maxSubsteps == defaults.refinement.maxSubsteps)
        return "";
    return format(
        "max_contact_substeps = %g caps the sub-steps of time_scheme = flow with a tolerance > 0 only; with "
        "tolerance = 0 every contact step takes contact_substeps = %g sub-steps and this run ignores the cap: "
        "to bound a contact step's work set contact_substeps (e.g. %g), or a tolerance in m",
        double(p.refinement.maxSubsteps), double(p.refinement.substeps), double(p.refinement.maxSubsteps));
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
    if (p.outputs.stressOutputs) return "";
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
    return format("communicationStepSize h = %.6g s at t = %.17g is longer than T1/%g = %.3g s", h, t,
                  kCommunicationPointsPerPeriod, longest) +
           format(" (T1 = %.3g s, the plate's first period)", period) + ", and " + input +
           " changed over it: sampled this rarely, the input's motion at the plate's frequencies is not in its "
           "values and the reconstruction between them (base_input_mode, load_input_mode) kicks the plate at "
           "every communication point, so the outputs can be far off (docs/input-accuracy.md); take h <= " +
           format("%.3g s", roundedDown(longest));
}

std::string missAdvice(const DriveSample& s, double start, double amplitude, double h, double dt, const char* input) {
    const double miss = std::fabs(s.value - s.modelEnd), jump = std::fabs(start - s.modelEnd);
    const bool missTooLarge = miss > kMissOfAmplitude * amplitude;
    // A jump over a step of one internal step is the scheme's own motion of the clamp on its grid.
    const bool jumpTooLarge = jump > kJumpOfAmplitude * amplitude && h > 1.5 * dt;
    if (!(amplitude > 0.0) || !(missTooLarge || jumpTooLarge)) return "";
    // The miss of a model of degree p shrinks as h^(p + 1): the step that brings it to its limit.
    const double power = 1.0 / double(s.order + 1);
    double enough = h;
    if (missTooLarge) enough = std::min(enough, h * std::pow(kMissOfAmplitude * amplitude / miss, power));
    // A continuous model jumps only where its parabola would pass an obstacle: its spread miss sets the step.
    if (jumpTooLarge && !s.continuous)
        enough = std::min(enough, h * std::pow(kJumpOfAmplitude * amplitude / jump, power));
    std::string text = std::string(input) +
                       format(
                           " = %.6g set at t = %.6g s is %.3g from where the FMU's model of it over the last step "
                           "ended (",
                           s.value, s.t, s.value - s.modelEnd) +
                       s.model +
                       format("): %.2g of its amplitude (%.3g, half its range so far); ", miss / amplitude, amplitude);
    text += jumpTooLarge ? format("the clamp jumps by it in one internal step (%.3g m/s for dt = %g s)", jump / dt, dt)
                         : std::string("the step after bends the clamp by it");
    text += format(
        ", a kick to the plate at every such communication point: the outputs can be far off (the energy grows, "
        "impacts are missed; docs/input-accuracy.md). The input moves too much between communication points for "
        "this step: take h <= %.3g s",
        roundedDown(std::max(enough, dt)));
    if (s.order == 0)
        text += ", or base_input_mode = quadratic (the default: continuous, the miss spread over the step)";
    return text;
}

void PlateAdvisor::onDriveSample(const DriveSample& sample, double start, double h, double dt, const char* input) {
    if (state_.samples++ == 0) state_.lowest = state_.highest = state_.lastValue = sample.value;
    state_.lowest = std::min(state_.lowest, sample.value);
    state_.highest = std::max(state_.highest, sample.value);
    // Its amplitude is known once it turned twice (a whole swing); before, the range is still growing.
    const double increment = sample.value - state_.lastValue;
    state_.lastValue = sample.value;
    const int direction = increment > 0.0 ? 1 : increment < 0.0 ? -1 : state_.direction;
    if (state_.direction != 0 && direction != state_.direction) ++state_.turns;
    state_.direction = direction;
    if (state_.missWarned) return;
    // The worst sample so far, from the fourth value on (before, the model's history is still filling:
    // its miss measures the start, not the step); a jump counts where the step is longer than dt.
    const double jumpScore = h > 1.5 * dt ? std::fabs(start - sample.modelEnd) / kJumpOfAmplitude : 0.0;
    const double score = std::max(std::fabs(sample.value - sample.modelEnd) / kMissOfAmplitude, jumpScore);
    if (state_.samples > plate::InputHistory::kCapacity && score > state_.worstScore) {
        state_.worstScore = score;
        state_.worst = {sample, start, h};
    }
    if (state_.turns < 2 || state_.worstScore == 0.0) return;
    const std::string advice = missAdvice(state_.worst.sample, state_.worst.start,
                                          0.5 * (state_.highest - state_.lowest), state_.worst.h, dt, input);
    state_.missWarned = !advice.empty();
    say(advice);
}

std::string driftAdvice(double t, double elapsed, double drift, double swing) {
    const double mean = drift / elapsed;
    if (!(elapsed > 0.0) || !(std::fabs(mean) > kDriftOfSwing * swing)) return "";
    return format(
               "base_acceleration has moved the clamp by %.3g m from its start by t = %.6g s: a mean velocity "
               "of %.3g m/s",
               drift, t, mean) +
           format(
               ", %.2g of the %.3g m/s its velocity swings, so the clamp drifts away rather than oscillating "
               "about where it started",
               std::fabs(mean) / swing, swing) +
           format(
               ". base_drive = acceleration starts the clamp at rest: an acceleration whose integral does not "
               "average to zero, as a sine's -A w^2 sin(w t) (its velocity from rest A w (cos(w t) - 1)), drifts "
               "it by that mean times t; this run's clamp lacks a start velocity of about %.3g m/s. Drive "
               "base_velocity (base_drive = velocity: its first value is the clamp's start velocity) or "
               "base_displacement instead, or give the acceleration a velocity of zero mean",
               -mean);
}

void PlateAdvisor::onIntegratedClamp(double t, double elapsed, double drift, double velocity, double acceleration) {
    state_.slowest = std::min(state_.slowest, velocity);
    state_.fastest = std::max(state_.fastest, velocity);
    const int sign = acceleration > 0.0 ? 1 : acceleration < 0.0 ? -1 : 0;
    if (sign != 0 && state_.accelerationSign != 0 && sign != state_.accelerationSign) ++state_.accelerationTurns;
    if (sign != 0) state_.accelerationSign = sign;
    if (state_.driftWarned || state_.accelerationTurns < 3) return;
    const std::string advice = driftAdvice(t, elapsed, drift, state_.fastest - state_.slowest);
    state_.driftWarned = !advice.empty();
    say(advice);
}

void PlateAdvisor::say(const std::string& advice) {
    if (!advice.empty()) warn_(advice);
}

void PlateAdvisor::onBuild(const plate::PlateParameters& p) {
    state_ = {};
    say(capAdvice(p));
}

void PlateAdvisor::onRead(fmu::ValueReference vr, const char* name, const plate::PlateParameters& p) {
    if (state_.stressReadWarned || !isStressOutput(vr)) return;
    state_.stressReadWarned = !p.outputs.stressOutputs;
    say(stressReadAdvice(name, p));
}

void PlateAdvisor::onStep(const plate::PlateParameters& p, const plate::StepPlan& plan, double h, double t,
                          const InputPort& drive, const char* driveName, const InputPort& load) {
    if (!plan.endsOnGrid && plan.steps < 2 && !state_.interpolationWarned) {
        state_.interpolationWarned = true;
        warn_(
            format("communicationStepSize h = %.17g is shorter than two internal steps of dt = %g: the outputs "
                   "are interpolated between the grid points around t (docs/theory.md §15); for the scheme's own "
                   "values take h a whole multiple of dt, or a smaller dt",
                   h, p.law.dt));
    }
    if (state_.longStepWarned || h <= longestCommunicationStep(p)) return;
    const char* input = inputChanged(drive) ? driveName : inputChanged(load) ? "load" : nullptr;
    if (!input) return;
    state_.longStepWarned = true;
    say(longStepAdvice(p, h, t, input));
}

void PlateAdvisor::afterStep(const plate::PlateParameters& p, const plate::PlateOutputs& o, double t,
                             const plate::ToleranceHorizon& horizon) {
    if (p.refinement.tolerance <= 0.0 || p.law.timeScheme != plate::TimeScheme::Flow) return;
    if (!state_.errorWarned && o.errorEstimate > p.refinement.tolerance) {
        state_.errorWarned = true;
        warn_(format("error_estimate = %.3g m passed tolerance = %.3g m at t = %.17g", o.errorEstimate,
                     p.refinement.tolerance, horizon.lostAt) +
              ": the flow law cannot hold the tolerance from this time on (errors made at earlier impacts grew at "
              "later ones, or the sub-step cap bounded a step): this is the scene's horizon for this tolerance. " +
              format("Later contact steps take %g sub-steps (contact_substeps = %g down to a power of two, at most "
                     "max_contact_substeps = %g)",
                     double(horizon.substeps), double(p.refinement.substeps), double(p.refinement.maxSubsteps)) +
              "; between two obstacles error_estimate reads their gap from now on, the one bound left (docs/theory.md "
              "section 22)");
    }
    if (!state_.cappedWarned && o.cappedSteps > 0) {
        state_.cappedWarned = true;
        warn_(format("a contact step before t = %.17g needed more than max_contact_substeps = %g sub-steps for "
                     "its target",
                     t, double(p.refinement.maxSubsteps)) +
              (p.refinement.maxSubsteps < plate::ranges::kMaxContactSubsteps.max
                   ? "; raise max_contact_substeps (capped_steps counts such steps; error_estimate includes them)"
                   : format("; max_contact_substeps = %g is its largest: take a larger tolerance or a smaller dt "
                            "(capped_steps counts such steps; error_estimate includes them)",
                            double(p.refinement.maxSubsteps))));
    }
}

}  // namespace plateimpact
