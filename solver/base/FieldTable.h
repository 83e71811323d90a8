#pragma once
// Tables that list the double fields of a plain struct once (PlateOutputs, CarrierState): a row
// reaches its field through the member pointer (and the index of an array member), so that every
// user walks the same table and a new field is one row.
#include <cstddef>

namespace plate {

namespace field_table {
template <class Pointer>
struct StructOf;
template <class S, class M>
struct StructOf<M S::*> {
    using type = S;
};
}  // namespace field_table

// The double `s.*Member` (Index < 0) or `(s.*Member)[Index]`, as a function a table row points to.
template <auto Member, int Index = -1>
constexpr double& fieldOf(typename field_table::StructOf<decltype(Member)>::type& s) {
    if constexpr (Index < 0)
        return s.*Member;
    else
        return (s.*Member)[Index];
}

// A row that says no more than which field: its name (for messages) and the field.
template <class S>
struct NamedField {
    const char* name;
    double& (*field)(S&);
    double value(const S& s) const { return field(const_cast<S&>(s)); }  // reads only
};

// Whether the rows of a table reach every double of S exactly once: as many rows as S holds
// doubles, and no two rows the same field (a static_assert next to each table).
template <class S, class Row, std::size_t N>
constexpr bool coversEachFieldOnce(const Row (&rows)[N]) {
    if (sizeof(S) != N * sizeof(double)) return false;
    S s{};
    for (std::size_t i = 0; i < N; ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (&rows[i].field(s) == &rows[j].field(s)) return false;
    return true;
}

}  // namespace plate
