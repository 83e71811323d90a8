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
    // After a step, the simulation at time t with outputs o: under tolerance > 0 (docs/theory.md §22)
    // the error estimate past the tolerance at horizon.lostAt (the scene's horizon for it, in the
    // simulation's time as t), a contact step the cap bounded.
    void afterStep(const plate::PlateParameters& p, const plate::PlateOutputs& o, double t,
                   const plate::ToleranceHorizon& horizon);

private:
    void say(const std::string& advice);

    const Sink& warn_;
    bool interpolationWarned_ = false;  // a step shorter than two grid steps
    bool longStepWarned_ = false;  // a communication step too long for the plate and the inputs
    bool stressReadWarned_ = false;  // a stress output read while stress_outputs = false
    bool errorWarned_ = false;  // the error estimate past the tolerance
    bool cappedWarned_ = false;  // a contact step the sub-step cap bounded
};

}  // namespace plateimpact
