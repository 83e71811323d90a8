#include "schemes/NewmarkState.h"

#include <array>

#include "base/StateArchive.h"

namespace plate {

namespace {
// Version 4: the base's share first, in the order every scheme archives it (Scheme.h, sharedMembers).
constexpr double kFormatVersion = 4.0;

// The one description of the state (base/StateArchive.h): the flat form after the header (format
// version, n, m, impulses) is every member in this order. A new member is one line here, with
// kFormatVersion raised. The bounds of the counts: a long long up to 9e15 (exact as a double), an
// int up to INT_MAX, the contact vertices up to m.
// Sizes: 0 the coordinates n, 1 the contact vertices m, 2 the carried impulses per level.
constexpr std::size_t kCoordinates = 0, kContacts = 1, kImpulses = 2;

const auto newmarkMembers = [](auto& s, auto& v) {
    for (auto* x : {&s.w, &s.wPrev, &s.kw, &s.kwPrev, &s.wPrev2}) v.vector(*x, kCoordinates, "displacement");
    sharedMembers(s, v, static_cast<double>(v.size(kContacts)));
    for (auto* x : {&s.pressureWork, &s.pressureWorkPrev}) v.real(*x, "pressure work");
    for (auto* x : {&s.baseCoupling, &s.baseCouplingPrev, &s.baseCouplingPrev2}) v.real(*x, "base coupling");
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
