#pragma once
// Settings and steps whose answer the FMU computes but that the user likely did not mean (issue 56:
// no silent wrong answer). Each function returns the warning to log, naming the setting and what to
// do, or "" when there is nothing to say; PlateModel.cpp logs each once. No state here.
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

}  // namespace plateimpact
