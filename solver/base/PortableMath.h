#pragma once
// Sine and cosine computed the same to the last bit on every CPU and platform (docs/theory.md
// §20, "What is bit-identical where"). The C library chooses its sin and cos by CPU at load
// time (glibc: FMA, AVX2 or SSE2 variants that differ in the last bit) and by platform
// (glibc, mingw's msvcrt, ...); anything whose bits must not depend on where the FMU runs
// (the quadrature's nodes, a modal rotation over Δt) takes these instead. Only IEEE-754
// additions, multiplications and std::nearbyint (exact), evaluated in the order written: the
// build compiles with -ffp-contract=off, so no fused multiply-add changes a rounding.
//
// Method: x = k π/2 + r with |r| ≤ π/4 (Cody–Waite: π/2 in three parts whose products with k
// are exact for |k| < 2^20), then the Taylor series of sin r and cos r to the term that is
// below 2^-60 of the result on |r| ≤ π/4 (degree 19 and 20), by Horner. Accuracy about 1 ulp
// (tests/test_portable_math.cpp holds it to 2 ulp of the C library over 10^5 points).
#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <stdexcept>

namespace plate::portable {

namespace detail {

// π/2 = kPio2a + kPio2b + kPio2c: kPio2a and kPio2b have 33 significant bits, so k·kPio2a
// and k·kPio2b are exact for |k| < 2^20 (the values of the classic Cody–Waite split).
constexpr double kPio2a = 1.57079632673412561417e+00;
constexpr double kPio2b = 6.07710050630396597660e-11;
constexpr double kPio2c = 2.02226624879595063154e-21;
constexpr double kTwoOverPi = 6.36619772367581382433e-01;
constexpr double kLargest = 1.6e6;  // |x| < 2^20 π/2

// Horner's rule in z over the coefficients, highest first (the same operations, in the same order,
// as the polynomial written out).
template <std::size_t N>
inline double horner(double z, const double (&c)[N]) {
    double p = c[0];
    for (std::size_t k = 1; k < N; ++k) p = p * z + c[k];
    return p;
}

// sin r on |r| ≤ π/4: r − r³/3! + … − r¹⁹/19!.
inline double sinKernel(double r) {
    static constexpr double c[] = {-1.0 / 121645100408832000.0,
                                   1.0 / 355687428096000.0,
                                   -1.0 / 1307674368000.0,
                                   1.0 / 6227020800.0,
                                   -1.0 / 39916800.0,
                                   1.0 / 362880.0,
                                   -1.0 / 5040.0,
                                   1.0 / 120.0,
                                   -1.0 / 6.0};  // 1/19! … 1/3!
    const double z = r * r;
    return r + r * (z * horner(z, c));
}

// cos r on |r| ≤ π/4: 1 − r²/2! + … + r²⁰/20!.
inline double cosKernel(double r) {
    static constexpr double c[] = {1.0 / 2432902008176640000.0,
                                   -1.0 / 6402373705728000.0,
                                   1.0 / 20922789888000.0,
                                   -1.0 / 87178291200.0,
                                   1.0 / 479001600.0,
                                   -1.0 / 3628800.0,
                                   1.0 / 40320.0,
                                   -1.0 / 720.0,
                                   1.0 / 24.0};  // 1/20! … 1/4!
    const double z = r * r;
    // 1 − z/2 + z² p, with the large terms last: 1 − (z/2 − z² p).
    return 1.0 - (0.5 * z - z * (z * horner(z, c)));
}

// x = k π/2 + r; returns r, sets the quadrant k mod 4.
inline double reduce(double x, int& quadrant) {
    if (!(std::fabs(x) < kLargest))
        throw std::domain_error("portable sine/cosine: argument outside |x| < 1.6e6 (or not finite)");
    const double k = std::nearbyint(x * kTwoOverPi);
    const double r = ((x - k * kPio2a) - k * kPio2b) - k * kPio2c;
    quadrant = static_cast<int>(static_cast<long long>(k) & 3);
    return r;
}

}  // namespace detail

inline void sinCos(double x, double& s, double& c) {
    int q = 0;
    const double r = detail::reduce(x, q);
    const double sr = detail::sinKernel(r), cr = detail::cosKernel(r);
    switch (q) {
        case 0: s = sr, c = cr; break;
        case 1: s = cr, c = -sr; break;
        case 2: s = -sr, c = -cr; break;
        default: s = -cr, c = sr; break;
    }
}

inline double sin(double x) {
    double s, c;
    sinCos(x, s, c);
    return s;
}

inline double cos(double x) {
    double s, c;
    sinCos(x, s, c);
    return c;
}

// Eigen blocks its dense matrix products by the cache sizes it reads from the CPU (cpuid) at the
// first product: the blocks decide the order of the sums, so a CPU with other caches computes
// other last bits (the modal bases, the condensed operators of the conserving scheme). Fixed
// sizes instead, once per process (a function-local static: thread-safe, the same values for
// every instance): those of a common x86-64 core.
inline void fixDenseBlocking() {
    static const bool fixed = [] {
        Eigen::setCpuCacheSizes(32 * 1024, 256 * 1024, 2 * 1024 * 1024);
        return true;
    }();
    (void)fixed;
}

}  // namespace plate::portable
