#include "schemes/NewmarkState.h"

#include <array>

#include "base/StateArchive.h"

namespace plate {

namespace {
// Version 3: the third time level and the port's contact sums (docs/theory.md §14).
constexpr double kFormatVersion = 3.0;

// The one description of the state (base/StateArchive.h): the flat form after the header (format
// version, n, m, impulses) is every member in this order. A new member is one line here, with
// kFormatVersion raised. The bounds of the counts: a long long up to 9e15 (exact as a double), an
// int up to INT_MAX, the contact vertices up to m.
// Sizes: 0 the coordinates n, 1 the contact vertices m, 2 the carried impulses per level.
constexpr std::size_t kCoordinates = 0, kContacts = 1, kImpulses = 2;

const auto newmarkMembers = [](auto& s, auto& v) {
    for (auto* x : {&s.w, &s.wPrev, &s.kw, &s.kwPrev, &s.wPrev2}) v.vector(*x, kCoordinates, "displacement");
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
    v.count(s.contactSolves, "QP iterations");
    v.count(s.contactIterationsMax, "QP iterations");
    v.count(s.contactIterationsLast, "QP iterations");
    v.count(s.contactPoints, "contact vertices", static_cast<double>(v.size(kContacts)));
    v.real(s.energyDamped, "energy damped");
    v.real(s.zPrev2, "z_prev2");
    v.real(s.pPrev2, "p_prev2");
    v.real(s.baseCouplingPrev2, "base coupling");
    for (auto* x : {&s.stepContactForce[0], &s.stepContactForce[1]}) v.real(*x, "contact force");
    v.real(s.stepContactMoment, "contact moment");
    for (auto* x : {&s.contactImpulseSum[0], &s.contactImpulseSum[1]}) v.real(*x, "contact impulse");
    for (auto* k : {&s.impactCount[0], &s.impactCount[1]}) v.count(*k, "impacts");
    v.states(s.contactState, kContacts);
    for (auto* x : {&s.contactImpulse, &s.contactImpulsePrev}) v.vector(*x, kImpulses, "contact impulse");
};

}  // namespace

std::vector<double> serialize(const NewmarkState& s) {
    return archive::save(s, kFormatVersion,
                         std::array<std::size_t, 3>{static_cast<std::size_t>(s.w.size()), s.contactState.size(),
                                                    static_cast<std::size_t>(s.contactImpulse.size())},
                         newmarkMembers);
}

NewmarkState deserialize(const std::vector<double>& in, Eigen::Index n, std::size_t m, std::size_t impulses) {
    return archive::load<NewmarkState>(
        in, kFormatVersion, std::array<std::size_t, 3>{static_cast<std::size_t>(n), m, impulses}, newmarkMembers);
}

std::vector<std::pair<std::string, std::size_t>> stateLayout(Eigen::Index n, std::size_t m, std::size_t impulses) {
    return archive::layout<NewmarkState>(std::array<std::size_t, 3>{static_cast<std::size_t>(n), m, impulses},
                                         newmarkMembers);
}

}  // namespace plate
