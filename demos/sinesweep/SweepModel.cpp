// The SineSweep model binding: plate::SineSweep (SineSweep.h beside it) behind fmu::Model, the
// controller of the two-FMU system model (demos/system_model.py). No inputs; its output
// base_displacement comes with exact first and second derivatives (the output derivatives of
// FMI 2.0), for masters that pass them on.
#include <cmath>
#include <memory>
#include <string>

#include "core/Model.h"
#include "SineSweep.h"
#include "SineSweepGuid.h"  // generated at build time: FMU_GUID

namespace sweep {

namespace {

using fmu::Causality;
using fmu::VariableType;

const fmu::ModelInfo kInfo{
    "SineSweep",
    "SineSweep",
    "Sine sweep for a clamp: z = amplitude s(t) sin(phi(t)), frequency from start_frequency to end_frequency over "
    "duration (linear or logarithmic), optional sin^2 ramp-in; exact output derivatives",
    /*canInterpolateInputs=*/false,
    /*maxOutputDerivativeOrder=*/2,
    /*canGetAndSetFMUstate=*/true,
    /*defaultStopTime=*/1.0,
    /*defaultStepSize=*/1e-4,
    /*documentationHtml=*/nullptr,
    /*stateMagic=*/"SWEEPSIG",
};

const fmu::EnumerationType kSweepLaw{
    "SweepLaw",
    "How the frequency goes from start to end",
    {{"linear", 1, "f = f0 + (f1 - f0) t / duration"}, {"logarithmic", 2, "f = f0 (f1/f0)^(t / duration)"}}};

enum Vr : fmu::ValueReference {
    kAmplitude = 0,
    kStartFrequency = 1,
    kEndFrequency = 2,
    kDuration = 3,
    kLaw = 4,
    kRampTime = 5,
    kBaseDisplacement = 10,
    kFrequency = 11,
};

fmu::Variable parameter(fmu::ValueReference vr, const char* name, VariableType type, const char* unit,
                        const char* description) {
    return {vr, name, type, Causality::Parameter, description, unit, nullptr, true, false};
}

const std::vector<fmu::Variable>& sweepVariables() {
    static const std::vector<fmu::Variable> table = {
        parameter(kAmplitude, "amplitude", VariableType::Real, "m", "Amplitude of the displacement"),
        parameter(kStartFrequency, "start_frequency", VariableType::Real, "Hz", "Frequency at t = 0 (> 0)"),
        parameter(kEndFrequency, "end_frequency", VariableType::Real, "Hz",
                  "Frequency at t = duration and after (> 0)"),
        parameter(kDuration, "duration", VariableType::Real, "s", "Time over which the frequency sweeps (> 0)"),
        fmu::integerSwitch(kLaw, "law", "Sweep law", kSweepLaw),
        parameter(kRampTime, "ramp_time", VariableType::Real, "s",
                  "Ramp-in time of the envelope sin^2(pi t / (2 ramp_time)); 0: none (the sine starts at full "
                  "amplitude)"),
        {kBaseDisplacement, "base_displacement", VariableType::Real, Causality::Output,
         "The displacement z(t) for the clamp of PlateImpact", "m", nullptr, false, true},
        {kFrequency, "frequency", VariableType::Real, Causality::Output, "Instantaneous frequency of the sweep", "Hz",
         nullptr, false, false},
    };
    return table;
}

class SweepModel final : public fmu::Model {
public:
    const fmu::ModelInfo& info() const override { return kInfo; }
    const std::vector<fmu::Variable>& variables() const override { return sweepVariables(); }

    double get(const fmu::Variable& v) const override {
        switch (v.vr) {
            case kAmplitude: return p_.amplitude;
            case kStartFrequency: return p_.startFrequency;
            case kEndFrequency: return p_.endFrequency;
            case kDuration: return p_.duration;
            case kLaw: return static_cast<int>(p_.law);
            case kRampTime: return p_.rampTime;
            case kBaseDisplacement: return sample().value;
            case kFrequency: return sample().frequency;
        }
        throw fmu::ModelError("unknown variable");
    }
    void set(const fmu::Variable& v, double x) override {
        switch (v.vr) {
            case kAmplitude: p_.amplitude = x; break;
            case kStartFrequency: p_.startFrequency = x; break;
            case kEndFrequency: p_.endFrequency = x; break;
            case kDuration: p_.duration = x; break;
            case kLaw: p_.law = static_cast<plate::SweepLaw>(int(x)); break;
            case kRampTime: p_.rampTime = x; break;
            default: throw fmu::ModelError(std::string(v.name) + " cannot be set");
        }
        sweep_.reset();
    }
    double getOutputDerivative(const fmu::Variable& v, int order) const override {
        if (v.vr != kBaseDisplacement) return Model::getOutputDerivative(v, order);
        const plate::SweepSample x = sample();
        return order == 1 ? x.d1 : x.d2;
    }

    void build() override {
        try {
            sweep_ = std::make_unique<plate::SineSweep>(p_);
        } catch (const std::invalid_argument& e) {
            throw fmu::ModelError(e.what());
        }
    }
    bool built() const override { return sweep_ != nullptr; }
    void drop() override { sweep_.reset(); }
    double time() const override { return time_; }
    void doStep(double, double h) override { time_ += h; }

    void saveState(std::vector<double>& out) const override {
        out.push_back(sweep_ ? 1.0 : 0.0);
        out.push_back(time_);
    }
    void restoreState(const double*& in, const double* end) override {
        if (end - in != 2 || (in[0] != 0.0 && in[0] != 1.0) || !std::isfinite(in[1]))
            throw fmu::ModelError("bad sweep state");
        const bool wasBuilt = in[0] == 1.0;
        time_ = in[1];
        in += 2;
        if (wasBuilt)
            build();
        else
            drop();
    }

private:
    plate::SweepSample sample() const { return sweep_ ? sweep_->at(time_) : plate::SweepSample{}; }

    plate::SineSweepParameters p_;
    std::unique_ptr<plate::SineSweep> sweep_;
    double time_ = 0.0;  // since the start of the experiment
};

}  // namespace

}  // namespace sweep

namespace fmu {
std::unique_ptr<Model> createModel() { return std::make_unique<sweep::SweepModel>(); }
const char* modelGuid() { return FMU_GUID; }
}  // namespace fmu
