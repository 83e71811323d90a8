#include "SineSweep.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace plate {

namespace {

void require(bool ok, const char* name, double value, const char* allowed) {
    if (ok) return;
    std::ostringstream msg;
    msg.precision(15);
    msg << "invalid parameter " << name << " = " << value << " (allowed: " << allowed << ")";
    throw std::invalid_argument(msg.str());
}

}  // namespace

SineSweep::SineSweep(const SineSweepParameters& p) : p_(p) {
    require(std::isfinite(p.amplitude), "amplitude", p.amplitude, "a finite number");
    require(std::isfinite(p.startFrequency) && p.startFrequency > 0, "start_frequency", p.startFrequency,
            "0 < start_frequency < inf");
    require(std::isfinite(p.endFrequency) && p.endFrequency > 0, "end_frequency", p.endFrequency,
            "0 < end_frequency < inf");
    require(std::isfinite(p.duration) && p.duration > 0, "duration", p.duration, "0 < duration < inf");
    require(std::isfinite(p.rampTime) && p.rampTime >= 0, "ramp_time", p.rampTime, "0 <= ramp_time < inf");
}

SweepSample SineSweep::at(double t) const {
    // Phase φ and its derivatives. Linear law: f = f0 + (f1 - f0) t / T. Logarithmic law:
    // f = f0 k^(t/T), k = f1/f0, φ = 2π f0 T (k^(t/T) - 1) / ln k. Past T the frequency stays f1.
    const double f0 = p_.startFrequency, f1 = p_.endFrequency, T = p_.duration;
    const double tau = std::min(t, T);
    double phase, frequency, rate;  // φ(tau), f(tau), df/dt (0 past T)
    if (p_.law == SweepLaw::Linear || f0 == f1) {
        const double slope = (f1 - f0) / T;
        phase = 2.0 * M_PI * (f0 * tau + 0.5 * slope * tau * tau);
        frequency = f0 + slope * tau;
        rate = t < T ? slope : 0.0;
    } else {
        const double logK = std::log(f1 / f0);
        const double growth = std::exp(logK * tau / T);
        phase = 2.0 * M_PI * f0 * T * (growth - 1.0) / logK;
        frequency = f0 * growth;
        rate = t < T ? frequency * logK / T : 0.0;
    }
    if (t > T) phase += 2.0 * M_PI * f1 * (t - T);
    const double w = 2.0 * M_PI * frequency, wRate = 2.0 * M_PI * rate;
    const double sn = std::sin(phase), cs = std::cos(phase);
    // Carrier c = a sin φ: c' = a w cos φ, c'' = a (w' cos φ - w² sin φ).
    const double a = p_.amplitude;
    const double c = a * sn, c1 = a * w * cs, c2 = a * (wRate * cs - w * w * sn);
    // Envelope s = sin²(πt/(2R)) on [0, R], 1 after: s' = (π/2R) sin(πt/R), s'' = 2(π/2R)² cos(πt/R).
    double s = 1.0, s1 = 0.0, s2 = 0.0;
    if (p_.rampTime > 0.0 && t < p_.rampTime) {
        const double k = M_PI / (2.0 * p_.rampTime);
        const double sk = std::sin(k * t);
        s = sk * sk;
        s1 = k * std::sin(2.0 * k * t);
        s2 = 2.0 * k * k * std::cos(2.0 * k * t);
    }
    SweepSample out;
    out.value = s * c;
    out.d1 = s1 * c + s * c1;
    out.d2 = s2 * c + 2.0 * s1 * c1 + s * c2;
    out.frequency = frequency;
    return out;
}

}  // namespace plate
