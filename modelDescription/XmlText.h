#pragma once
// Text helpers of the model description writer (WriteModelDescription.cpp): XML escaping,
// the shortest decimal of a double, SI units as BaseUnit exponents (both FMI versions).

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <stdexcept>
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

// A unit as the row spells it — SI symbols joined by "." (product) and "/" (quotient), each
// with an optional integer power: "kg/m3", "m/s2", "N.m", "N.s", "1/s" — as FMI 2.0 BaseUnit
// exponents. A new unit needs no entry anywhere: only a new symbol would.
inline std::string baseUnit(const std::string& unit) {
    if (unit == "MB") return "factor=\"1048576\"";  // memory (memory_limit): dimensionless, 2^20 bytes
    // Exponents of kg, m, s per symbol.
    static const std::map<std::string, std::array<int, 3>> symbols = {
        {"1", {0, 0, 0}},    {"m", {0, 1, 0}},  {"kg", {1, 0, 0}},  {"s", {0, 0, 1}}, {"N", {1, 1, -2}},
        {"Pa", {1, -1, -2}}, {"J", {1, 2, -2}}, {"Hz", {0, 0, -1}}, {"W", {1, 2, -3}}};
    std::array<int, 3> total{0, 0, 0};
    int sign = 1;
    std::size_t at = 0;
    while (at < unit.size()) {
        std::size_t end = unit.find_first_of("./", at);
        if (end == std::string::npos) end = unit.size();
        const std::string token = unit.substr(at, end - at);
        const std::size_t digits = token.find_first_of("-0123456789", 1);
        const std::string symbol = token.substr(0, digits);
        const int power = digits == std::string::npos ? 1 : std::stoi(token.substr(digits));
        const auto found = symbols.find(symbol);
        if (found == symbols.end()) throw std::runtime_error("no SI symbol " + symbol + " in unit " + unit);
        for (int k = 0; k < 3; ++k) total[k] += sign * power * found->second[k];
        if (end < unit.size() && unit[end] == '/') sign = -1;
        at = end + 1;
    }
    std::string out;
    const char* names[3] = {"kg", "m", "s"};
    for (int k = 0; k < 3; ++k)
        if (total[k] != 0)
            out += std::string(out.empty() ? "" : " ") + names[k] + "=\"" + std::to_string(total[k]) + "\"";
    return out;
}

}  // namespace description
