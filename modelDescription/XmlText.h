#pragma once
// Text helpers of the model description writers (WriteModelDescription3.cpp): XML escaping,
// the shortest decimal of a double, SI units as BaseUnit exponents.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>

namespace description {

inline std::string escape(const std::string& text) {
    std::string out;
    for (char ch : text) {
        switch (ch) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            default: out += ch;
        }
    }
    return out;
}

// The shortest decimal text that reads back as the same double (0.01, not 0.01000000000000000021).
inline std::string real(double x) {
    char text[40];
    for (int digits = 1; digits <= 17; ++digits) {
        std::snprintf(text, sizeof text, "%.*g", digits, x);
        if (std::strtod(text, nullptr) == x) break;
    }
    // A whole number below 1e6 reads better without an exponent (7770, not 7.77e+03).
    if (std::strchr(text, 'e') && x == std::floor(x) && std::fabs(x) < 1e6) std::snprintf(text, sizeof text, "%.0f", x);
    return text;
}

// SI units as BaseUnit exponents (the same in FMI 2.0 and 3.0).
inline const std::map<std::string, std::string>& baseUnits() {
    static const std::map<std::string, std::string> units = {
        {"m", "m=\"1\""},
        {"Pa", "kg=\"1\" m=\"-1\" s=\"-2\""},
        {"kg/m3", "kg=\"1\" m=\"-3\""},
        {"s", "s=\"1\""},
        {"J", "kg=\"1\" m=\"2\" s=\"-2\""},
        {"1", ""},
        {"Hz", "s=\"-1\""},
        {"1/s", "s=\"-1\""},
        {"N", "kg=\"1\" m=\"1\" s=\"-2\""},
        {"m/s", "m=\"1\" s=\"-1\""},
    };
    return units;
}

}  // namespace description
