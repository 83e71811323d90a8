// The tables that list a struct's members once: the outputs' (PlateOutputs.h), the carrier
// state's (Armature.h) and the flat form of the Newmark state (NewmarkState.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "schemes/Armature.h"
#include "schemes/NewmarkState.h"
#include "schemes/PlateOutputs.h"

namespace {

using plate::NewmarkState;

// Every double of S reached by exactly one row: writing k + 1 through row k fills the struct with
// 1..N, each once (the static_asserts next to the tables check the same at compile time).
template <class S, class Rows>
void expectEachDoubleOnce(const Rows& rows) {
    constexpr std::size_t kDoubles = sizeof(S) / sizeof(double);
    ASSERT_EQ(sizeof(S), kDoubles * sizeof(double));
    ASSERT_EQ(std::size(rows), kDoubles);
    S s{};
    std::set<std::string> names;
    double k = 0.0;
    for (const auto& row : rows) {
        EXPECT_EQ(row.field(s), 0.0) << row.name << ": a field reached by two rows";
        row.field(s) = ++k;
        EXPECT_EQ(row.value(s), k) << row.name;
        EXPECT_TRUE(names.insert(row.name).second) << row.name << ": a name used twice";
    }
    double flat[kDoubles];
    std::memcpy(flat, &s, sizeof(S));
    std::sort(flat, flat + kDoubles);
    for (std::size_t i = 0; i < kDoubles; ++i) EXPECT_EQ(flat[i], double(i + 1)) << "a double no row reaches";
}

TEST(StateTables, OutputsTableReachesEveryOutputOnce) {
    expectEachDoubleOnce<plate::PlateOutputs>(plate::kOutputFields);
}

TEST(StateTables, CarrierTableReachesEveryFieldOnce) {
    expectEachDoubleOnce<plate::CarrierState>(plate::kCarrierFields);
}

// A state of n coordinates, m contact vertices and k impulses per level, every member nonzero.
NewmarkState sampleState(Eigen::Index n, std::size_t m, Eigen::Index k) {
    NewmarkState s;
    double i = 0.0;
    for (Eigen::VectorXd* v : {&s.w, &s.wPrev, &s.wPrev2, &s.kw, &s.kwPrev}) {
        i += 1.0;
        *v = Eigen::VectorXd::LinSpaced(n, 0.1 * i, -0.37 * i);
    }
    s.contactImpulse = Eigen::VectorXd::LinSpaced(k, 1.5, 2.75);
    s.contactImpulsePrev = Eigen::VectorXd::LinSpaced(k, -1.5, 0.25);
    s.contactState.assign(m, 0);
    s.contactState[0] = -1;
    s.contactState[m - 1] = 1;
    s.z = 1e-3, s.zPrev = 2e-3, s.zPrev2 = 3e-3;
    s.p = 10.0, s.pPrev = 11.0, s.pPrev2 = 12.0;
    s.pressureWork = 0.5, s.pressureWorkPrev = 0.25;
    s.baseCoupling = 1.25, s.baseCouplingPrev = 1.5, s.baseCouplingPrev2 = 1.75;
    s.step = 123456789012LL;
    s.energyInput = 3.5, s.energyDissipated = 0.125, s.energyDamped = 0.0625, s.maxKktResidual = 1e-13;
    s.contactSolves = 98765432109LL, s.contactIterationsMax = 17, s.contactIterationsLast = 3;
    s.contactPoints = 2;
    s.stepContactForce[0] = 4.0, s.stepContactForce[1] = -5.0, s.stepContactMoment = 0.75;
    s.contactImpulseSum[0] = 6.0, s.contactImpulseSum[1] = -7.0;
    s.contactOnsets[0] = 8, s.contactOnsets[1] = 9;
    return s;
}

TEST(StateTables, NewmarkStateRoundTripIsIdentical) {
    const NewmarkState s = sampleState(4, 3, 3);
    const std::vector<double> flat = plate::serialize(s);
    ASSERT_EQ(flat.size(), 4u + 5 * 4 + 27 + 3 + 2 * 3);  // the format version 4 layout
    const NewmarkState back = plate::deserialize(flat, 4, 3, 3);
    EXPECT_EQ(plate::serialize(back), flat);
    EXPECT_EQ(back.step, s.step);
    EXPECT_EQ(back.contactSolves, s.contactSolves);
    EXPECT_EQ(back.contactOnsets[1], 9);
    EXPECT_EQ(back.contactState, s.contactState);
    EXPECT_EQ(back.wPrev2, s.wPrev2);
    EXPECT_EQ(back.contactImpulsePrev, s.contactImpulsePrev);
    // Every position of the flat form set to some valid value: the round trip keeps each.
    std::vector<double> every = flat;
    for (std::size_t i = 4; i < every.size(); ++i)
        if (every[i] == 0.0) every[i] = 1.0;  // a count, a real and a contact state alike
    EXPECT_EQ(plate::serialize(plate::deserialize(every, 4, 3, 3)), every);
}

// The archive's layout (what a test that damages a state on purpose patches) is where the values
// stand: each named member's first value, after the 4-value header, and the members fill the flat
// form exactly.
TEST(StateTables, NewmarkStateLayoutIsWhereTheValuesStand) {
    const NewmarkState s = sampleState(4, 3, 3);
    const std::vector<double> flat = plate::serialize(s);
    const auto layout = plate::stateLayout(4, 3, 3);
    const auto offset = [&layout](const std::string& name) {
        const auto it = std::find_if(layout.begin(), layout.end(), [&](const auto& f) { return f.first == name; });
        EXPECT_NE(it, layout.end()) << name;
        return 4 + it->second;
    };
    EXPECT_EQ(offset("displacement"), 4u);
    EXPECT_EQ(flat[offset("z")], s.z);
    EXPECT_EQ(flat[offset("step")], double(s.step));
    EXPECT_EQ(flat[offset("contact points")], double(s.contactPoints));
    EXPECT_EQ(flat[offset("contact state")], double(s.contactState[0]));
    EXPECT_EQ(layout.back().first, "contact impulse");  // the last member: its second level, 3 values
    EXPECT_EQ(4 + layout.back().second + 3, flat.size());
}

TEST(StateTables, NewmarkStateRefusesCorruptCountsAndSizes) {
    const NewmarkState s = sampleState(4, 3, 3);
    const std::vector<double> flat = plate::serialize(s);
    const auto at = [&flat](double value) {  // the position of a value the sample holds once
        const auto it = std::find(flat.begin(), flat.end(), value);
        EXPECT_EQ(std::count(flat.begin(), flat.end(), value), 1) << value;
        return static_cast<std::size_t>(it - flat.begin());
    };
    const auto refused = [&flat](std::size_t i, double value, Eigen::Index n = 4, std::size_t m = 3,
                                 std::size_t k = 3) {
        std::vector<double> bad = flat;
        bad[i] = value;
        try {
            plate::deserialize(bad, n, m, k);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    const std::size_t step = at(123456789012.0), total = at(98765432109.0), most = at(17.0);
    const std::size_t vertices = at(2.0), onsets = at(9.0), z = at(1e-3);
    EXPECT_EQ(refused(step, 1.5), "corrupt state: step is not a count in range");
    EXPECT_EQ(refused(step, -1.0), "corrupt state: step is not a count in range");
    EXPECT_EQ(refused(step, 1e16), "corrupt state: step is not a count in range");
    EXPECT_EQ(refused(total, std::nan("")), "corrupt state: contact solves is not a count in range");
    EXPECT_EQ(refused(most, 4294967296.0), "corrupt state: contact iterations is not a count in range");
    EXPECT_EQ(refused(vertices, 4.0), "corrupt state: contact points is not a count in range");  // > m
    EXPECT_EQ(refused(onsets, HUGE_VAL), "corrupt state: contact onsets is not a count in range");
    EXPECT_EQ(refused(z, std::nan("")), "corrupt state: z is not finite");
    EXPECT_EQ(refused(at(-1.0), 2.0), "corrupt contact state");
    EXPECT_EQ(refused(4, HUGE_VAL), "corrupt state: non-finite displacement");
    EXPECT_EQ(refused(flat.size() - 1, std::nan("")), "corrupt state: non-finite contact impulse");
    // The header: the format version and the sizes must be this plate's.
    const std::string other = "state does not belong to this plate (size or format differs)";
    // An earlier release's format (or another scheme's) is refused as such.
    EXPECT_EQ(refused(0, 2.0), "state does not belong to this plate (another scheme, or an earlier release's format)");
    for (std::size_t i : {1, 2, 3}) EXPECT_EQ(refused(i, flat[i] + 1.0), other);
    EXPECT_EQ(refused(1, 4.0, 5), other);  // another plate's sizes
    EXPECT_EQ(refused(2, 3.0, 4, 2), other);
    EXPECT_EQ(refused(3, 3.0, 4, 3, 0), other);
    std::vector<double> shorter(flat.begin(), flat.end() - 1);
    EXPECT_THROW(plate::deserialize(shorter, 4, 3, 3), std::invalid_argument);
    std::vector<double> longer = flat;
    longer.push_back(0.0);
    EXPECT_THROW(plate::deserialize(longer, 4, 3, 3), std::invalid_argument);
    EXPECT_THROW(plate::deserialize({}, 4, 3, 3), std::invalid_argument);
}

}  // namespace
