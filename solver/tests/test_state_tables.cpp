// The tables that list a struct's members once: the outputs' (PlateOutputs.h) and the carrier
// state's (Armature.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <set>
#include <string>

#include "Armature.h"
#include "PlateOutputs.h"

namespace {

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

}  // namespace
