#include "Shaker.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace shaker {

namespace {

void check(bool ok, const char* name, double value, const char* range) {
    if (ok) return;
    std::ostringstream text;
    text.precision(17);
    text << name << " = " << value << " is out of range; allowed: " << range;
    throw std::invalid_argument(text.str());
}

}  // namespace

void validate(const ShakerParameters& p) {
    check(p.mass > 0 && p.mass <= kMaxMass, "mass", p.mass, "0 < mass <= 1e12 kg");
    check(p.stiffness >= 0 && p.stiffness <= kMaxStiffness, "stiffness", p.stiffness, "0 <= stiffness <= 1e15 N/m");
    check(p.damping >= 0 && p.damping <= kMaxDamping, "damping", p.damping, "0 <= damping <= 1e15 N s/m");
    check(p.dt >= kMinDt && p.dt <= kMaxDt, "dt", p.dt, "1e-9 s <= dt <= 1 s");
    if (p.tlm)
        check(p.impedance > 0 && p.impedance <= kMaxDamping, "tlm_impedance", p.impedance,
              "0 < tlm_impedance <= 1e15 N s/m when coupling = 2 (tlm)");
}

Shaker::Shaker(const ShakerParameters& p) : p_(p) { validate(p_); }

void Shaker::settle(double driveForce, double plateForce) {
    const double load = p_.tlm ? -(plateForce + p_.impedance * s_.velocity) : plateForce;  // the line end's push
    s_.acceleration = (driveForce + load - p_.stiffness * s_.displacement - p_.damping * s_.velocity) / p_.mass;
}

void Shaker::step(double h, double driveForce, double plateForce) {
    if (!(h > 0) || !std::isfinite(h)) throw std::invalid_argument("step h must be a finite number > 0");
    // The fewest equal substeps no longer than dt (a step within 1e-12 relative of a multiple
    // of dt takes that multiple: a master's h = 1e-4 is not 10.000000000000002 substeps).
    const double ratio = h / p_.dt;
    const double n = std::max(1.0, std::ceil(ratio * (1.0 - 1e-12)));
    if (n > kMaxSubsteps) {
        std::ostringstream text;
        text << "communication step h = " << h << " s needs " << n << " substeps of dt = " << p_.dt
             << " s (more than 1e9); use a larger dt or smaller steps";
        throw std::invalid_argument(text.str());
    }
    const double tau = h / n;
    if (p_.tlm) {
        double sum = 0.0, squares = 0.0;
        for (long long i = 0; i < static_cast<long long>(n); ++i)
            sum += substepLine(tau, driveForce, plateForce, squares);
        const double z = p_.impedance;
        s_.waveOut = sum / h;
        s_.transit = h * s_.waveOut * s_.waveOut / (4.0 * z);
        s_.lineLoss += (squares - h * s_.waveOut * s_.waveOut) / (4.0 * z);
        settle(driveForce, plateForce);
        return;
    }
    const double force = driveForce + plateForce;
    for (long long i = 0; i < static_cast<long long>(n); ++i) substep(tau, force, driveForce, plateForce);
    settle(driveForce, plateForce);
}

// One trapezoidal substep with the forces held: with s = v0 + v1,
//   x1 = x0 + tau s / 2,   m (v1 - v0) / tau = F - c s / 2 - k (x0 + x1) / 2,
// so s (m / tau + c / 2 + k tau / 4) = F - k x0 + 2 m v0 / tau.
void Shaker::substep(double tau, double force, double driveForce, double plateForce) {
    const double m = p_.mass, c = p_.damping, k = p_.stiffness;
    const double x0 = s_.displacement, v0 = s_.velocity;
    const double s = (force - k * x0 + 2.0 * m * v0 / tau) / (m / tau + 0.5 * c + 0.25 * k * tau);
    const double dx = 0.5 * tau * s;
    s_.displacement = x0 + dx;
    s_.velocity = s - v0;
    s_.driveWork += driveForce * dx;
    s_.plateWork += plateForce * dx;
    s_.damperLoss += c * tau * 0.25 * s * s;
}

// The line's end as the load: force -(c + Z x') with x' = s/2 over the substep, i.e. the substep
// above with the damping c + Z and the force F - c; the launched wave a = c + Z s, and the line's
// work on the armature -(c + Z s/2) dx = -(a² - c²) tau / (4Z) (docs/theory.md §19).
double Shaker::substepLine(double tau, double driveForce, double wave, double& squares) {
    const double m = p_.mass, c = p_.damping, k = p_.stiffness, z = p_.impedance;
    const double x0 = s_.displacement, v0 = s_.velocity;
    const double s = (driveForce - wave - k * x0 + 2.0 * m * v0 / tau) / (m / tau + 0.5 * (c + z) + 0.25 * k * tau);
    const double dx = 0.5 * tau * s;
    s_.displacement = x0 + dx;
    s_.velocity = s - v0;
    s_.driveWork += driveForce * dx;
    s_.plateWork -= (wave + 0.5 * z * s) * dx;
    s_.damperLoss += c * tau * 0.25 * s * s;
    const double a = wave + z * s;
    squares += a * a * tau;
    return a * tau;
}

double Shaker::energy() const {
    return 0.5 * p_.mass * s_.velocity * s_.velocity + 0.5 * p_.stiffness * s_.displacement * s_.displacement;
}

}  // namespace shaker
