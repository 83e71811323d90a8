#include "NewmarkState.h"

#include <cmath>
#include <string>

#include <stdexcept>

namespace plate {

namespace {
// Version 3: the third time level and the port's contact sums (docs/theory.md §14).
constexpr double kFormatVersion = 3.0;
constexpr std::size_t kScalars = 27;
constexpr std::size_t kVectors = 5;
}  // namespace

std::vector<double> serialize(const NewmarkState& s) {
    const auto n = static_cast<std::size_t>(s.w.size());
    std::vector<double> out;
    const auto k = static_cast<std::size_t>(s.contactImpulse.size());
    out.reserve(4 + kVectors * n + kScalars + s.contactState.size() + 2 * k);
    out.push_back(kFormatVersion);
    out.push_back(static_cast<double>(n));
    out.push_back(static_cast<double>(s.contactState.size()));
    out.push_back(static_cast<double>(k));
    for (const Eigen::VectorXd* v : {&s.w, &s.wPrev, &s.kw, &s.kwPrev, &s.wPrev2})
        out.insert(out.end(), v->data(), v->data() + n);
    for (double x : {s.z,
                     s.zPrev,
                     s.p,
                     s.pPrev,
                     s.pressureWork,
                     s.pressureWorkPrev,
                     s.baseCoupling,
                     s.baseCouplingPrev,
                     static_cast<double>(s.step),
                     s.energyInput,
                     s.energyDissipated,
                     s.maxKktResidual,
                     static_cast<double>(s.qpIterationsTotal),
                     static_cast<double>(s.qpIterationsMax),
                     static_cast<double>(s.qpIterationsLast),
                     static_cast<double>(s.contactVertices),
                     s.energyDamped,
                     s.zPrev2,
                     s.pPrev2,
                     s.baseCouplingPrev2,
                     s.stepContactForce[0],
                     s.stepContactForce[1],
                     s.stepContactMoment,
                     s.contactImpulseSum[0],
                     s.contactImpulseSum[1],
                     static_cast<double>(s.impactCount[0]),
                     static_cast<double>(s.impactCount[1])})
        out.push_back(x);
    for (signed char c : s.contactState) out.push_back(c);
    for (const Eigen::VectorXd* v : {&s.contactImpulse, &s.contactImpulsePrev})
        out.insert(out.end(), v->data(), v->data() + k);
    return out;
}

NewmarkState deserialize(const std::vector<double>& in, Eigen::Index n, std::size_t m, std::size_t impulses) {
    const auto nn = static_cast<std::size_t>(n);
    if (in.size() != 4 + kVectors * nn + kScalars + m + 2 * impulses || in[0] != kFormatVersion ||
        in[1] != static_cast<double>(n) || in[2] != static_cast<double>(m) || in[3] != static_cast<double>(impulses))
        throw std::invalid_argument("state does not belong to this plate (size or format differs)");
    NewmarkState s;
    std::size_t k = 4;
    for (Eigen::VectorXd* v : {&s.w, &s.wPrev, &s.kw, &s.kwPrev, &s.wPrev2}) {
        *v = Eigen::Map<const Eigen::VectorXd>(in.data() + k, n);
        k += nn;
    }
    // Every scalar finite and every count a whole number in range before any cast (a cast
    // of NaN or of a value out of range is undefined; fuzz/deserialize_state.cpp found one).
    const auto finite = [&](const char* what) {
        const double x = in[k++];
        if (!std::isfinite(x)) throw std::invalid_argument(std::string("corrupt state: ") + what + " is not finite");
        return x;
    };
    const auto count = [&](const char* what, double hi) {
        const double x = in[k++];
        if (!(x >= 0.0 && x <= hi) || std::floor(x) != x)
            throw std::invalid_argument(std::string("corrupt state: ") + what + " is not a count in range");
        return x;
    };
    s.z = finite("z");
    s.zPrev = finite("z_prev");
    s.p = finite("p");
    s.pPrev = finite("p_prev");
    s.pressureWork = finite("pressure work");
    s.pressureWorkPrev = finite("pressure work");
    s.baseCoupling = finite("base coupling");
    s.baseCouplingPrev = finite("base coupling");
    s.step = static_cast<long long>(count("step", 9.0e15));
    s.energyInput = finite("energy input");
    s.energyDissipated = finite("energy dissipated");
    s.maxKktResidual = finite("KKT residual");
    s.qpIterationsTotal = static_cast<long long>(count("QP iterations", 9.0e15));
    s.qpIterationsMax = static_cast<int>(count("QP iterations", 2147483647.0));
    s.qpIterationsLast = static_cast<int>(count("QP iterations", 2147483647.0));
    s.contactVertices = static_cast<int>(count("contact vertices", static_cast<double>(m)));
    s.energyDamped = finite("energy damped");
    s.zPrev2 = finite("z_prev2");
    s.pPrev2 = finite("p_prev2");
    s.baseCouplingPrev2 = finite("base coupling");
    for (double& f : s.stepContactForce) f = finite("contact force");
    s.stepContactMoment = finite("contact moment");
    for (double& f : s.contactImpulseSum) f = finite("contact impulse");
    for (long long& c : s.impactCount) c = static_cast<long long>(count("impacts", 9.0e15));
    s.contactState.resize(m);
    for (std::size_t i = 0; i < m; ++i) {
        const double c = in[k++];
        if (c != -1.0 && c != 0.0 && c != 1.0) throw std::invalid_argument("corrupt contact state");
        s.contactState[i] = static_cast<signed char>(c);
    }
    const auto ni = static_cast<Eigen::Index>(impulses);
    for (Eigen::VectorXd* v : {&s.contactImpulse, &s.contactImpulsePrev}) {
        *v = Eigen::Map<const Eigen::VectorXd>(in.data() + k, ni);
        k += impulses;
        if (!v->allFinite()) throw std::invalid_argument("corrupt state: non-finite contact impulse");
    }
    for (const Eigen::VectorXd* v : {&s.w, &s.wPrev, &s.kw, &s.kwPrev, &s.wPrev2})
        if (!v->allFinite()) throw std::invalid_argument("corrupt state: non-finite displacement");
    return s;
}

}  // namespace plate
