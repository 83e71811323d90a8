#pragma once
// The armature of an electrodynamic shaker as a linear oscillator, the numerics of Shaker.fmu
// (demos/shaker/ShakerModel.cpp): m x'' + c x' + k x = drive_force + plate_force, x the armature
// displacement (positive upward), plate_force the force the load exerts on the armature
// (PlateImpact's clamp_force). Both forces are held over a communication step (what a master
// passes), which is split into n = ceil(h / dt) equal substeps of the trapezoidal rule (Newmark
// beta = 1/4, gamma = 1/2): unconditionally stable, second order, and its discrete energy
// E = m v²/2 + k x²/2 obeys, over every substep, exactly
//     E1 - E0 = (drive_force + plate_force) (x1 - x0) - c tau ((v0 + v1)/2)²,
// so the ledger (drive_work, plate_work, damper_loss) closes to roundoff for any h.
//
// Coupled through a transmission line instead (tlm, docs/theory.md §19): the load is the line's
// end, which pushes the armature with -(c + Z x') — c the wave arriving from the partner, held
// over the step, Z the line's impedance — and the armature launches the wave a = c + 2 Z x'
// (its mean over the step is the output tlm_wave_out). plate_work is then the line's work on the
// armature, exactly -(a² - c²) tau / (4 Z) summed over the substeps.
#include <stdexcept>

namespace shaker {

struct ShakerParameters {
    double mass = 20.0;  // kg, armature (with the table the plate is clamped to)
    double stiffness = 3158.0;  // N/m, suspension: f = sqrt(k/m)/(2 pi) = 2.0 Hz
    double damping = 50.0;  // N s/m, suspension: damping ratio c / (2 sqrt(k m)) = 0.1
    double dt = 1e-5;  // s, largest internal substep
    bool tlm = false;  // coupled by a transmission line: the second force input is its wave
    double impedance = 2.0e4;  // N s/m, the line's characteristic impedance (tlm only)
};

// Ranges: 0 < mass <= kMaxMass, 0 <= stiffness <= kMaxStiffness, 0 <= damping <= kMaxDamping,
// kMinDt <= dt <= kMaxDt. Throws std::invalid_argument naming the parameter, value and range.
constexpr double kMaxMass = 1e12, kMaxStiffness = 1e15, kMaxDamping = 1e15, kMinDt = 1e-9, kMaxDt = 1.0;
// |drive_force|, |plate_force| (N); larger values are refused by the FMU.
constexpr double kMaxForce = 1e12;
void validate(const ShakerParameters& p);

// The armature's motion and the cumulative energy ledger since t = 0.
struct ShakerState {
    double displacement = 0.0, velocity = 0.0, acceleration = 0.0;  // m, m/s, m/s²
    double driveWork = 0.0;  // J, work of drive_force on the armature
    double plateWork = 0.0;  // J, work of plate_force on the armature
    double damperLoss = 0.0;  // J, energy dissipated in the damper (>= 0)
    // tlm: the mean wave launched over the last step (N), its energy h ā²/(4Z) carried to the
    // partner (J), and what the mean wave cannot carry, sum over steps of (∫a² - h ā²)/(4Z) >= 0 (J).
    double waveOut = 0.0, transit = 0.0, lineLoss = 0.0;
};

class Shaker {
public:
    explicit Shaker(const ShakerParameters& p);  // validates

    // Advances the armature by h > 0 with both forces held; throws std::invalid_argument if h
    // needs more than kMaxSubsteps substeps.
    void step(double h, double driveForce, double plateForce);
    // The acceleration the forces give at the current displacement and velocity (the output
    // armature_acceleration at t = 0, before the first step).
    void settle(double driveForce, double plateForce);

    double energy() const;  // J, m v²/2 + k x²/2

    const ShakerState& state() const { return s_; }
    void setState(const ShakerState& s) { s_ = s; }
    const ShakerParameters& parameters() const { return p_; }

    static constexpr double kMaxSubsteps = 1e9;

private:
    void substep(double tau, double force, double driveForce, double plateForce);
    // One substep with the line's end as the load (wave c held): returns a tau, adds a² tau to squares.
    double substepLine(double tau, double driveForce, double wave, double& squares);

    ShakerParameters p_;
    ShakerState s_;
};

}  // namespace shaker
