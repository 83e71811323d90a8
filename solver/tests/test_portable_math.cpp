// The portable sine and cosine (solver/base/PortableMath.h): within 2 ulp of the C library's over the
// arguments the solver uses (quadrature guesses in [0, π], modal rotations ω Δt up to thousands
// of radians), exact at the quadrant points, and odd/even. Their bits are the same everywhere by
// construction (IEEE operations only, no contraction); what is tested here is that they are
// sine and cosine.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>

#include "base/PortableMath.h"

namespace {

// Distance in units in the last place between two doubles of the same sign.
double ulps(double a, double b) {
    if (a == b) return 0.0;
    const double scale = std::ldexp(1.0, std::ilogb(std::max(std::fabs(a), std::fabs(b))) - 52);
    return std::fabs(a - b) / scale;
}

TEST(PortableMath, WithinTwoUlpOfTheCLibrary) {
    double worstSin = 0.0, worstCos = 0.0;
    for (int i = 0; i < 100000; ++i) {
        // Spread over [-4000, 4000] with a dense part in [-π, π].
        const double x = i % 2 ? 4000.0 * std::sin(1.0 + 0.123 * i) : M_PI * std::cos(0.777 * i);
        double s, c;
        plate::portable::sinCos(x, s, c);
        // Near a zero of the function an ulp of the result is tiny: measure against |x|'s ulp
        // of the argument reduction instead (2^-52 |x| relative), the error any reduction makes.
        const double floor = std::ldexp(1.0, -53) * std::max(1.0, std::fabs(x));
        worstSin = std::max(worstSin, std::fabs(s - std::sin(x)) > floor ? ulps(s, std::sin(x)) : 0.0);
        worstCos = std::max(worstCos, std::fabs(c - std::cos(x)) > floor ? ulps(c, std::cos(x)) : 0.0);
    }
    EXPECT_LE(worstSin, 2.0);
    EXPECT_LE(worstCos, 2.0);
}

TEST(PortableMath, SymmetriesAndSpecialPoints) {
    EXPECT_EQ(plate::portable::sin(0.0), 0.0);
    EXPECT_EQ(plate::portable::cos(0.0), 1.0);
    for (double x : {0.1, 0.7853981633974483, 1.0, 2.5, 10.0, 123.456}) {
        EXPECT_EQ(plate::portable::sin(-x), -plate::portable::sin(x));
        EXPECT_EQ(plate::portable::cos(-x), plate::portable::cos(x));
        const double s = plate::portable::sin(x), c = plate::portable::cos(x);
        EXPECT_NEAR(s * s + c * c, 1.0, 4e-16);
    }
    EXPECT_NEAR(plate::portable::sin(M_PI / 2), 1.0, 1e-16);
    EXPECT_NEAR(plate::portable::cos(M_PI), -1.0, 1e-16);
    EXPECT_THROW(plate::portable::sin(2e6), std::domain_error);
    EXPECT_THROW(plate::portable::cos(NAN), std::domain_error);
}

}  // namespace
