#include "NewmarkState.h"

#include <stdexcept>

namespace plate {

namespace {
constexpr double kFormatVersion = 1.0;
constexpr std::size_t kScalars = 16;
}  // namespace

std::vector<double> serialize(const NewmarkState& s) {
    const auto n = static_cast<std::size_t>(s.w.size());
    std::vector<double> out;
    out.reserve(3 + 4 * n + kScalars + s.contactState.size());
    out.push_back(kFormatVersion);
    out.push_back(static_cast<double>(n));
    out.push_back(static_cast<double>(s.contactState.size()));
    for (const Eigen::VectorXd* v : {&s.w, &s.wPrev, &s.kw, &s.kwPrev}) out.insert(out.end(), v->data(), v->data() + n);
    for (double x : {s.z, s.zPrev, s.p, s.pPrev, s.pressureWork, s.pressureWorkPrev, s.baseCoupling, s.baseCouplingPrev,
                     static_cast<double>(s.step), s.energyInput, s.energyDissipated, s.maxKktResidual,
                     static_cast<double>(s.qpIterationsTotal), static_cast<double>(s.qpIterationsMax),
                     static_cast<double>(s.qpIterationsLast), static_cast<double>(s.contactVertices)})
        out.push_back(x);
    for (signed char c : s.contactState) out.push_back(c);
    return out;
}

NewmarkState deserialize(const std::vector<double>& in, Eigen::Index n, std::size_t m) {
    const auto nn = static_cast<std::size_t>(n);
    if (in.size() != 3 + 4 * nn + kScalars + m || in[0] != kFormatVersion || in[1] != static_cast<double>(n) ||
        in[2] != static_cast<double>(m))
        throw std::invalid_argument("state does not belong to this plate (size or format differs)");
    NewmarkState s;
    std::size_t k = 3;
    for (Eigen::VectorXd* v : {&s.w, &s.wPrev, &s.kw, &s.kwPrev}) {
        *v = Eigen::Map<const Eigen::VectorXd>(in.data() + k, n);
        k += nn;
    }
    s.z = in[k++];
    s.zPrev = in[k++];
    s.p = in[k++];
    s.pPrev = in[k++];
    s.pressureWork = in[k++];
    s.pressureWorkPrev = in[k++];
    s.baseCoupling = in[k++];
    s.baseCouplingPrev = in[k++];
    s.step = static_cast<long long>(in[k++]);
    s.energyInput = in[k++];
    s.energyDissipated = in[k++];
    s.maxKktResidual = in[k++];
    s.qpIterationsTotal = static_cast<long long>(in[k++]);
    s.qpIterationsMax = static_cast<int>(in[k++]);
    s.qpIterationsLast = static_cast<int>(in[k++]);
    s.contactVertices = static_cast<int>(in[k++]);
    s.contactState.resize(m);
    for (std::size_t i = 0; i < m; ++i) {
        const double c = in[k++];
        if (c != -1.0 && c != 0.0 && c != 1.0) throw std::invalid_argument("corrupt contact state");
        s.contactState[i] = static_cast<signed char>(c);
    }
    for (const Eigen::VectorXd* v : {&s.w, &s.wPrev, &s.kw, &s.kwPrev})
        if (!v->allFinite()) throw std::invalid_argument("corrupt state: non-finite displacement");
    return s;
}

}  // namespace plate
