#pragma once
// The FMU's advice while it runs (issue 56: no silent wrong answer): settings, reads and steps whose
// answer the FMU computes but that the user likely did not mean, each warned once per build, naming the
// setting and what to do. The checks are free functions returning the warning, or "" when there is
// nothing to say; PlateAdvisor (at the end) holds which were said and says them. The warnings of the
// values alone, at build, are PlateWarnings.h's.
#include <functional>
#include <string>

#include "binding/PlateVariables.h"
#include "core/Model.h"

namespace plateimpact {

// max_contact_substeps caps the step doubling of time_scheme = flow with a tolerance (docs/theory.md
// §22). With tolerance = 0 every contact step takes contact_substeps sub-steps and the cap cannot act.
std::string capAdvice(const plate::PlateParameters& p);

// root_stress, root_stress_peak, max_stress and its place, vertex_stress read 0 unless stress_outputs
// = true (the stress costs the curvature rows at every vertex, and the peak a look at the root in
// every internal step): reading one while it is off is said, once.
bool isStressOutput(fmu::ValueReference vr);
std::string stressReadAdvice(const char* name, const plate::PlateParameters& p);

// The communication step against the plate and the inputs (docs/input-accuracy.md, "How long a
// communication step may be"): a step longer than T1/kCommunicationPointsPerPeriod (T1 = 1/f1, the
// plate's first period, PlateParameters::firstFrequencyEstimate) over which an input that moves the
// plate changed. The master then samples that input fewer than kCommunicationPointsPerPeriod times
// per period of the lowest mode: whatever the input does between the samples, at the plate's
// frequencies or above, is not in them, and the reconstruction between them (base_input_mode) kicks
// the plate at every communication point.
constexpr double kCommunicationPointsPerPeriod = 10.0;
// Whether the master set `port` since the last step to a value other than its last sample (or set
// derivatives that move it): called before the step records the value.
bool inputChanged(const InputPort& port);
double longestCommunicationStep(const plate::PlateParameters& p);
std::string longStepAdvice(const plate::PlateParameters& p, double h, double t, const char* input);

// The master's value of the clamp's displacement against the FMU's model of it between communication
// points (issue 71): at each communication point the value the master sets is compared with where the
// FMU's model of the input over the last step (held, the line or the parabola of base_input_mode, or the
// master's derivatives) ended. That miss is spread over the next step as a slope when the reconstruction
// is continuous (linear, quadratic), or is a jump of the clamp in one internal step (held, derivatives
// given, or a parabola that would pass an obstacle dropped to holding) — a kick to the plate at every
// communication point. Judged once the input turned twice (its amplitude, half its range, is known).
// Measured on the README's 10 Hz scene (tools/step_misses.py, docs/step_misses.json): right answers stay
// at or below 0.03 of the input's amplitude as a spread miss and 6.3e-4 as a jump, wrong ones (the energy
// 2x to 2000x, impacts missed or added) at or above 0.12 and 2.6e-3; the limits sit between.
constexpr double kMissOfAmplitude = 0.06;  // a miss spread over the step, against the input's amplitude
constexpr double kJumpOfAmplitude = 1.25e-3;  // a jump of the clamp at a communication point, likewise
struct DriveSample {
    double t = 0.0;  // the communication point
    double value = 0.0;  // what the master set
    double modelEnd = 0.0;  // where the FMU's model of the input over the last step ended
    int order = 2;  // the degree of that model: the miss shrinks as h^(order + 1)
    const char* model = "";  // that model in words
    bool continuous = true;  // the model starts the next step where it ended (linear, quadratic): no jump
};
// The warning for a sample whose miss, or whose jump (the clamp starts the step at `start`), passes its
// limit against `amplitude`, with the step that would do; "" otherwise.
std::string missAdvice(const DriveSample& s, double start, double amplitude, double h, double dt, const char* input);

// base_drive = acceleration (issue 71): the clamp starts at rest, so an acceleration whose integral does
// not average to zero drifts it away — the acceleration of a sine A sin(w t), -A w^2 sin(w t), from rest
// gives the velocity A w (cos(w t) - 1), whose mean -A w moves the clamp by -A w t. Judged once the input
// changed sign three times (a whole swing of it: its velocity's swing is known): the clamp's mean velocity
// since the start, drift / elapsed, against the range its velocity swept. A clamp that oscillates about
// where it started has a mean velocity of at most its excursion over the time, at most 1/(2 pi) of the
// swing after a sine's period; the sine started at rest has half the swing (0.42 after a period).
constexpr double kDriftOfSwing = 0.3;
// The warning for a clamp that moved by `drift` in `elapsed` s (at the master's time t) while its
// velocity swept `swing` m/s; "" when its mean velocity is within kDriftOfSwing of the swing.
std::string driftAdvice(double t, double elapsed, double drift, double swing);

// The advice of one model (PlateModel.cpp), each warned once per build through `warn` (the model's
// fmu::Model::warn, which the instance may replace: held by reference).
class PlateAdvisor {
public:
    using Sink = std::function<void(const std::string&)>;
    explicit PlateAdvisor(const Sink& warn) : warn_(warn) {}
    PlateAdvisor(const PlateAdvisor&) = delete;  // bound to its model's sink
    PlateAdvisor& operator=(const PlateAdvisor&) = delete;
    // At build: every advice may be said again; a cap that cannot act (capAdvice) is said now.
    void onBuild(const plate::PlateParameters& p);
    // A read of the variable or array `vr` named `name`: a stress output while stress_outputs is off.
    void onRead(fmu::ValueReference vr, const char* name, const plate::PlateParameters& p);
    // Before a communication step of h from t planned as `plan`, the drive's input (its port and
    // name) and the load as the master set them: a step shorter than two grid steps (the outputs
    // interpolated, docs/theory.md §15), a step too long for the plate and the inputs (longStepAdvice).
    void onStep(const plate::PlateParameters& p, const plate::StepPlan& plan, double h, double t,
                const InputPort& drive, const char* driveName, const InputPort& load);
    // A fresh value of the clamp's displacement (the drive, base_drive = displacement) at a communication
    // point, after the step's signal is made: the largest miss against the FMU's model of it so far
    // (missAdvice), judged once the values turned twice.
    void onDriveSample(const DriveSample& sample, double start, double h, double dt, const char* input);
    // After a step ending at the master's time t, `elapsed` s after the build, a clamp integrated from its
    // acceleration (base_drive = acceleration): moved by `drift` from its start, at `velocity`, the input
    // at `acceleration` (driftAdvice, once the input swung).
    void onIntegratedClamp(double t, double elapsed, double drift, double velocity, double acceleration);
    // After a step, the simulation at time t with outputs o: under tolerance > 0 (docs/theory.md §22)
    // the error estimate past the tolerance at horizon.lostAt (the scene's horizon for it, in the
    // simulation's time as t), a contact step the cap bounded.
    void afterStep(const plate::PlateParameters& p, const plate::PlateOutputs& o, double t,
                   const plate::ToleranceHorizon& horizon);

private:
    void say(const std::string& advice);

    const Sink& warn_;
    // What was said and seen since the build (onBuild resets it whole).
    struct State {
        bool interpolationWarned = false;  // a step shorter than two grid steps
        bool longStepWarned = false;  // a communication step too long for the plate and the inputs
        bool stressReadWarned = false;  // a stress output read while stress_outputs = false
        bool errorWarned = false;  // the error estimate past the tolerance
        bool cappedWarned = false;  // a contact step the sub-step cap bounded
        bool missWarned = false;  // the master's value far from the FMU's model of the input
        int samples = 0;  // the drive's values set since the build, their range, and how often they turned
        double lowest = 0.0, highest = 0.0, lastValue = 0.0;
        int turns = 0, direction = 0;
        struct Worst {  // the sample whose miss or jump is largest against its limit so far
            DriveSample sample;
            double start = 0.0, h = 0.0;
        } worst;
        double worstScore = 0.0;
        bool driftWarned = false;  // the integrated clamp drifting (driftAdvice)
        double slowest = 0.0, fastest = 0.0;  // the clamp's velocity range since the build (it starts at rest)
        int accelerationSign = 0, accelerationTurns = 0;  // the input's sign and how often it changed
    } state_;
};

}  // namespace plateimpact
