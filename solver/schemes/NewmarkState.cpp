#include "schemes/NewmarkState.h"

#include <cmath>
#include <string>

#include <stdexcept>

namespace plate {

namespace {
// Version 3: the third time level and the port's contact sums (docs/theory.md §14).
constexpr double kFormatVersion = 3.0;

// The flat form after the header (format version, n, m, impulses): every member in one order,
// written and read by this one table (as CondensedScheme's members()). A new member is one line
// here, with kFormatVersion raised. The bounds of the counts: a long long up to 9e15 (exact as a
// double), an int up to INT_MAX, the contact vertices up to m.
template <class State, class Visit>
void members(State& s, Visit& v) {
    for (auto* x : {&s.w, &s.wPrev, &s.kw, &s.kwPrev, &s.wPrev2}) v.vector(*x, v.n, "displacement");
    v.real(s.z, "z");
    v.real(s.zPrev, "z_prev");
    v.real(s.p, "p");
    v.real(s.pPrev, "p_prev");
    v.real(s.pressureWork, "pressure work");
    v.real(s.pressureWorkPrev, "pressure work");
    v.real(s.baseCoupling, "base coupling");
    v.real(s.baseCouplingPrev, "base coupling");
    v.count(s.step, "step");
    v.real(s.energyInput, "energy input");
    v.real(s.energyDissipated, "energy dissipated");
    v.real(s.maxKktResidual, "KKT residual");
    v.count(s.qpIterationsTotal, "QP iterations");
    v.count(s.qpIterationsMax, "QP iterations");
    v.count(s.qpIterationsLast, "QP iterations");
    v.count(s.contactVertices, "contact vertices", static_cast<double>(v.m));
    v.real(s.energyDamped, "energy damped");
    v.real(s.zPrev2, "z_prev2");
    v.real(s.pPrev2, "p_prev2");
    v.real(s.baseCouplingPrev2, "base coupling");
    for (auto* x : {&s.stepContactForce[0], &s.stepContactForce[1]}) v.real(*x, "contact force");
    v.real(s.stepContactMoment, "contact moment");
    for (auto* x : {&s.contactImpulseSum[0], &s.contactImpulseSum[1]}) v.real(*x, "contact impulse");
    for (auto* k : {&s.impactCount[0], &s.impactCount[1]}) v.count(*k, "impacts");
    v.states(s.contactState, v.m);
    for (auto* x : {&s.contactImpulse, &s.contactImpulsePrev}) v.vector(*x, v.impulses, "contact impulse");
}

// The largest value a count of this type may hold in the flat form.
constexpr double countLimit(long long) { return 9.0e15; }
constexpr double countLimit(int) { return 2147483647.0; }

struct Counter {  // the length of the flat form after the header
    std::size_t n, m, impulses, size = 0;
    void vector(const Eigen::VectorXd&, std::size_t k, const char*) { size += k; }
    void real(const double&, const char*) { ++size; }
    template <class Count>
    void count(const Count&, const char*, double = 0.0) {
        ++size;
    }
    void states(const std::vector<signed char>&, std::size_t k) { size += k; }
};

struct Writer {
    std::vector<double>& out;
    std::size_t n, m, impulses;
    void vector(const Eigen::VectorXd& x, std::size_t k, const char*) { out.insert(out.end(), x.data(), x.data() + k); }
    void real(const double& x, const char*) { out.push_back(x); }
    template <class Count>
    void count(const Count& k, const char*, double = 0.0) {
        out.push_back(static_cast<double>(k));
    }
    void states(const std::vector<signed char>& c, std::size_t) { out.insert(out.end(), c.begin(), c.end()); }
};

// Every value finite and every count a whole number in range before any cast (a cast of NaN or
// of a value out of range is undefined; fuzz/deserialize_state.cpp found one). The caller has
// checked the length.
struct Reader {
    const std::vector<double>& in;
    std::size_t at, n, m, impulses;
    void vector(Eigen::VectorXd& x, std::size_t k, const char* what) {
        x = Eigen::Map<const Eigen::VectorXd>(in.data() + at, static_cast<Eigen::Index>(k));
        at += k;
        if (!x.allFinite()) throw std::invalid_argument(std::string("corrupt state: non-finite ") + what);
    }
    void real(double& x, const char* what) {
        x = in[at++];
        if (!std::isfinite(x)) throw std::invalid_argument(std::string("corrupt state: ") + what + " is not finite");
    }
    template <class Count>
    void count(Count& k, const char* what, double limit = countLimit(Count{})) {
        const double x = in[at++];
        if (!(x >= 0.0 && x <= limit) || std::floor(x) != x)
            throw std::invalid_argument(std::string("corrupt state: ") + what + " is not a count in range");
        k = static_cast<Count>(x);
    }
    void states(std::vector<signed char>& c, std::size_t k) {
        c.resize(k);
        for (signed char& x : c) {
            const double d = in[at++];
            if (d != -1.0 && d != 0.0 && d != 1.0) throw std::invalid_argument("corrupt contact state");
            x = static_cast<signed char>(d);
        }
    }
};

std::size_t flatSize(std::size_t n, std::size_t m, std::size_t impulses) {
    NewmarkState s;
    Counter counter{n, m, impulses};
    members(s, counter);
    return 4 + counter.size;
}

}  // namespace

std::vector<double> serialize(const NewmarkState& s) {
    const auto n = static_cast<std::size_t>(s.w.size()), m = s.contactState.size(),
               impulses = static_cast<std::size_t>(s.contactImpulse.size());
    std::vector<double> out;
    out.reserve(flatSize(n, m, impulses));
    out.push_back(kFormatVersion);
    out.push_back(static_cast<double>(n));
    out.push_back(static_cast<double>(m));
    out.push_back(static_cast<double>(impulses));
    Writer writer{out, n, m, impulses};
    members(s, writer);
    return out;
}

NewmarkState deserialize(const std::vector<double>& in, Eigen::Index n, std::size_t m, std::size_t impulses) {
    const auto nn = static_cast<std::size_t>(n);
    if (in.size() != flatSize(nn, m, impulses) || in[0] != kFormatVersion || in[1] != static_cast<double>(n) ||
        in[2] != static_cast<double>(m) || in[3] != static_cast<double>(impulses))
        throw std::invalid_argument("state does not belong to this plate (size or format differs)");
    NewmarkState s;
    Reader reader{in, 4, nn, m, impulses};
    members(s, reader);
    return s;
}

}  // namespace plate
