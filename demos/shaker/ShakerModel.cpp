// The Shaker model binding: shaker::Shaker (Shaker.h) behind fmu::Model, the armature of the
// two-way system model (demos/shaker.py): SineSweep.fmu's signal drives drive_force, the
// armature carries PlateImpact's clamp (armature_velocity -> base_velocity), and the plate's
// clamp_force comes back as plate_force. No output depends directly on an input: the forces
// act over the next step, and armature_acceleration is the end-of-step value of that step.
#include <cmath>
#include <memory>
#include <sstream>
#include <string>

#include "core/Model.h"
#include "Shaker.h"
#include "ShakerGuid.h"  // generated at build time: FMU_GUID

namespace shaker {

namespace {

using fmu::Causality;
using fmu::VariableType;

const fmu::ModelInfo kInfo{
    "Shaker",
    "Shaker",
    "Armature of an electrodynamic shaker: mass on its suspension spring and damper, m x'' + c x' + k x = "
    "drive_force + plate_force (forces held over each communication step; trapezoidal rule on substeps of at "
    "most dt), with an energy ledger that closes to roundoff",
    /*canInterpolateInputs=*/false,
    /*maxOutputDerivativeOrder=*/0,
    /*canGetAndSetFMUstate=*/true,
    /*defaultStopTime=*/1.0,
    /*defaultStepSize=*/1e-4,
    /*documentationHtml=*/nullptr,
    /*stateMagic=*/"SHAKERAR",
};

enum Vr : fmu::ValueReference {
    kMass = 0,
    kStiffness = 1,
    kDamping = 2,
    kDt = 3,
    kDriveForce = 10,
    kPlateForce = 11,
    kDisplacement = 20,
    kVelocity = 21,
    kAcceleration = 22,
    kEnergy = 23,
    kDriveWork = 24,
    kPlateWork = 25,
    kDamperLoss = 26,
    // The transmission-line coupling (docs/theory.md §19).
    kCoupling = 4,
    kTlmImpedance = 5,
    kTlmWaveIn = 12,
    kTlmWaveOut = 27,
    kTlmTransit = 28,
    kTlmLineLoss = 29,
};

fmu::Variable parameter(fmu::ValueReference vr, const char* name, const char* unit, const char* description) {
    return {vr, name, VariableType::Real, Causality::Parameter, description, unit, nullptr, true, false};
}

fmu::Variable switchParameter(fmu::ValueReference vr, const char* name, const char* description, int lo, int hi) {
    fmu::Variable v{vr, name, VariableType::Integer, Causality::Parameter, description, nullptr, nullptr, true, false};
    v.min = lo;
    v.max = hi;
    return v;
}

// The inputs set the acceleration at t = 0: a new value before initialization ends rebuilds.
fmu::Variable input(fmu::ValueReference vr, const char* name, const char* description) {
    return {vr, name, VariableType::Real, Causality::Input, description, "N", nullptr, true, false};
}

fmu::Variable output(fmu::ValueReference vr, const char* name, const char* unit, const char* description) {
    return {vr, name, VariableType::Real, Causality::Output, description, unit, nullptr, false, false};
}

const std::vector<fmu::Variable>& shakerVariables() {
    static const std::vector<fmu::Variable> table = {
        parameter(kMass, "mass", "kg", "Moving mass of the armature and table (0 < mass <= 1e12)"),
        parameter(kStiffness, "stiffness", "N/m", "Suspension stiffness k (0 <= k <= 1e15)"),
        parameter(kDamping, "damping", "N.s/m", "Suspension damping c (0 <= c <= 1e15)"),
        parameter(kDt, "dt", "s",
                  "Largest internal substep (1e-9 to 1 s): a communication step h is split into ceil(h/dt) equal "
                  "trapezoidal substeps, so any h is accepted"),
        input(kDriveForce, "drive_force", "Force of the drive (the coil) on the armature, positive upward"),
        input(
            kPlateForce, "plate_force",
            "Force the load exerts on the armature, positive upward: connect PlateImpact's clamp_force (coupling = 1; "
            "with held values unstable when the load's rigid mass is not small against the armature's, and "
            "through impacts: use coupling = 2)"),
        output(kDisplacement, "armature_displacement", "m", "Armature displacement x, positive upward"),
        output(kVelocity, "armature_velocity", "m/s", "Armature velocity: connect to PlateImpact's base_velocity"),
        output(kAcceleration, "armature_acceleration", "m/s2",
               "Armature acceleration at the end of the last step, (forces of that step - k x - c v) / m"),
        output(kEnergy, "energy", "J", "Kinetic + spring energy of the armature, m v^2/2 + k x^2/2"),
        output(kDriveWork, "drive_work", "J", "Work of drive_force on the armature since t = 0"),
        output(kPlateWork, "plate_work", "J",
               "Work of plate_force on the armature since t = 0 (minus the work the armature did on the load)"),
        output(kDamperLoss, "damper_loss", "J", "Energy dissipated in the suspension damper since t = 0"),
        switchParameter(kCoupling, "coupling",
                        "How the load is coupled: 1 = force (plate_force, held: unstable through impacts and for "
                        "armatures lighter than the plate, docs/system-model.md), 2 = tlm (a transmission line: "
                        "tlm_wave_in / tlm_wave_out with PlateImpact's base_drive = tlm, stable and energy-conserving)",
                        1, 2),
        parameter(kTlmImpedance, "tlm_impedance", "N.s/m",
                  "Characteristic impedance Z of the line (coupling = 2; 0 < Z <= 1e15): the same value on both ends"),
        input(kTlmWaveIn, "tlm_wave_in",
              "Wave arriving from the partner (coupling = 2): connect PlateImpact's tlm_wave_out"),
        output(kTlmWaveOut, "tlm_wave_out", "N",
               "Mean wave the armature launched over the last step (coupling = 2): connect PlateImpact's tlm_wave_in"),
        output(kTlmTransit, "tlm_transit", "J",
               "Energy of that wave, stored in the line until the partner receives it"),
        output(kTlmLineLoss, "tlm_line_loss", "J",
               "Energy launched that the mean wave does not carry, since t = 0 (>= 0: the line is passive)"),
    };
    return table;
}

class ShakerModel final : public fmu::Model {
public:
    const fmu::ModelInfo& info() const override { return kInfo; }
    const std::vector<fmu::Variable>& variables() const override { return shakerVariables(); }

    double get(const fmu::Variable& v) const override;
    void set(const fmu::Variable& v, double x) override;

    void build() override;
    bool built() const override { return shaker_ != nullptr; }
    void drop() override { shaker_.reset(); }
    double time() const override { return time_; }
    void doStep(double, double h) override;

    void saveState(std::vector<double>& out) const override;
    void restoreState(const double*& in, const double* end) override;

private:
    ShakerState current() const { return shaker_ ? shaker_->state() : ShakerState{}; }
    static void checkForce(const fmu::Variable& v, double x);

    ShakerParameters p_;
    double driveForce_ = 0.0, plateForce_ = 0.0, waveIn_ = 0.0;
    double loadInput() const { return p_.tlm ? waveIn_ : plateForce_; }  // the load's input of the coupling
    std::unique_ptr<Shaker> shaker_;
    double time_ = 0.0;  // since the start of the experiment
};

double ShakerModel::get(const fmu::Variable& v) const {
    const ShakerState s = current();
    switch (v.vr) {
        case kMass: return p_.mass;
        case kStiffness: return p_.stiffness;
        case kDamping: return p_.damping;
        case kDt: return p_.dt;
        case kDriveForce: return driveForce_;
        case kPlateForce: return plateForce_;
        case kDisplacement: return s.displacement;
        case kVelocity: return s.velocity;
        case kAcceleration: return s.acceleration;
        case kEnergy: return shaker_ ? shaker_->energy() : 0.0;
        case kDriveWork: return s.driveWork;
        case kPlateWork: return s.plateWork;
        case kDamperLoss: return s.damperLoss;
        case kCoupling: return p_.tlm ? 2.0 : 1.0;
        case kTlmImpedance: return p_.impedance;
        case kTlmWaveIn: return waveIn_;
        case kTlmWaveOut: return s.waveOut;
        case kTlmTransit: return s.transit;
        case kTlmLineLoss: return s.lineLoss;
    }
    throw fmu::ModelError("unknown variable");
}

void ShakerModel::checkForce(const fmu::Variable& v, double x) {
    if (std::fabs(x) <= kMaxForce) return;
    std::ostringstream text;
    text << v.name << " = " << x << " N rejected: |" << v.name << "| must be <= 1e12 N";
    throw fmu::ModelError(text.str());
}

void ShakerModel::set(const fmu::Variable& v, double x) {
    switch (v.vr) {
        case kMass: p_.mass = x; break;
        case kStiffness: p_.stiffness = x; break;
        case kDamping: p_.damping = x; break;
        case kDt: p_.dt = x; break;
        case kCoupling:
            if (x != 1.0 && x != 2.0) {
                std::ostringstream text;
                text << "coupling = " << x << " is out of range; allowed: 1 (force) or 2 (tlm)";
                throw fmu::ModelError(text.str());
            }
            p_.tlm = x == 2.0;
            break;
        case kTlmImpedance: p_.impedance = x; break;
        case kTlmWaveIn:
            checkForce(v, x);
            waveIn_ = x;
            return;
        case kDriveForce:
            checkForce(v, x);
            driveForce_ = x;
            return;
        case kPlateForce:
            checkForce(v, x);
            plateForce_ = x;
            return;
        default: throw fmu::ModelError(std::string(v.name) + " cannot be set");
    }
    shaker_.reset();  // a parameter changed: build again
}

void ShakerModel::build() {
    try {
        shaker_ = std::make_unique<Shaker>(p_);
    } catch (const std::invalid_argument& e) {
        throw fmu::ModelError(e.what());
    }
    if (p_.tlm && plateForce_ != 0.0)
        throw fmu::ModelError(
            "invalid parameter coupling = 2 (tlm) with plate_force set: the line carries the load "
            "(connect tlm_wave_in), plate_force must stay 0");
    shaker_->settle(driveForce_, loadInput());
}

void ShakerModel::doStep(double, double h) {
    if (!shaker_) throw fmu::ModelError("the shaker is not built");
    try {
        if (p_.tlm && plateForce_ != 0.0)
            throw std::invalid_argument(
                "invalid parameter coupling = 2 (tlm) with plate_force set: the line "
                "carries the load (connect tlm_wave_in), plate_force must stay 0");
        shaker_->step(h, driveForce_, loadInput());
    } catch (const std::invalid_argument& e) {
        throw fmu::ModelError(e.what());
    }
    time_ += h;
}

void ShakerModel::saveState(std::vector<double>& out) const {
    const ShakerState s = current();
    out.insert(out.end(), {shaker_ ? 1.0 : 0.0, time_, s.displacement, s.velocity, s.acceleration, s.driveWork,
                           s.plateWork, s.damperLoss, s.waveOut, s.transit, s.lineLoss});
}

void ShakerModel::restoreState(const double*& in, const double* end) {
    constexpr std::ptrdiff_t kSize = 11;
    if (end - in != kSize || (in[0] != 0.0 && in[0] != 1.0)) throw fmu::ModelError("bad shaker state");
    for (std::ptrdiff_t i = 1; i < kSize; ++i)
        if (!std::isfinite(in[i])) throw fmu::ModelError("bad shaker state");
    const bool wasBuilt = in[0] == 1.0;
    const ShakerState s{in[2], in[3], in[4], in[5], in[6], in[7], in[8], in[9], in[10]};
    time_ = in[1];
    in += kSize;
    if (!wasBuilt) {
        drop();
        return;
    }
    build();
    shaker_->setState(s);
}

}  // namespace

}  // namespace shaker

namespace fmu {
std::unique_ptr<Model> createModel() { return std::make_unique<shaker::ShakerModel>(); }
const char* modelGuid() { return FMU_GUID; }
}  // namespace fmu
