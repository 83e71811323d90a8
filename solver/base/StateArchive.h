#pragma once
// The one archive of the schemes' states (FMU states, docs/architecture.md): a stateful type
// describes its members once, in one function `members(state, archive)` that names each member
// in order (archive.vector, real, count, states); the archive's kinds below walk that one
// description to size the flat form, write it, read it back with its checks, and list its layout.
//
// The flat form: a format tag, the sizes the state's vectors are measured in, then the members.
// Reading checks the tag and the sizes before anything else (a state of another scheme, another
// plate or an earlier release is refused whole), then every value: finite, every count a whole
// number in range before any cast (a cast of NaN or of a value out of range is undefined;
// fuzz/deserialize_state.cpp found one), every contact state −1, 0 or 1.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace plate::archive {

// The largest value a count of this type may hold in the flat form (exact as a double).
constexpr double countLimit(long long) { return 9.0e15; }
constexpr double countLimit(int) { return 2147483647.0; }

// What every kind shares: the sizes (index k of `vector(x, k, …)` and `states(c, k)`).
template <std::size_t N>
struct Sizes {
    std::array<std::size_t, N> sizes;
    std::size_t size(std::size_t k) const { return sizes[k]; }
};

// The length of the members' flat form.
template <std::size_t N>
struct Sizer : Sizes<N> {
    std::size_t length = 0;
    void vector(const Eigen::VectorXd&, std::size_t k, const char*) { length += this->size(k); }
    void real(const double&, const char*) { ++length; }
    template <class Count>
    void count(const Count&, const char*, double = 0.0) {
        ++length;
    }
    void states(const std::vector<signed char>&, std::size_t k) { length += this->size(k); }
};

template <std::size_t N>
struct Writer : Sizes<N> {
    std::vector<double>* out;
    void vector(const Eigen::VectorXd& x, std::size_t k, const char*) {
        out->insert(out->end(), x.data(), x.data() + this->size(k));
    }
    void real(const double& x, const char*) { out->push_back(x); }
    template <class Count>
    void count(const Count& k, const char*, double = 0.0) {
        out->push_back(static_cast<double>(k));
    }
    void states(const std::vector<signed char>& c, std::size_t) { out->insert(out->end(), c.begin(), c.end()); }
};

// The caller has checked the length: every read is in range.
template <std::size_t N>
struct Reader : Sizes<N> {
    const double* at;
    void vector(Eigen::VectorXd& x, std::size_t k, const char* what) {
        x = Eigen::Map<const Eigen::VectorXd>(at, static_cast<Eigen::Index>(this->size(k)));
        at += this->size(k);
        if (!x.allFinite()) throw std::invalid_argument(std::string("corrupt state: non-finite ") + what);
    }
    void real(double& x, const char* what) {
        x = *at++;
        if (!std::isfinite(x)) throw std::invalid_argument(std::string("corrupt state: ") + what + " is not finite");
    }
    template <class Count>
    void count(Count& k, const char* what, double limit = countLimit(Count{})) {
        const double x = *at++;
        if (!(x >= 0.0 && x <= limit) || std::floor(x) != x)
            throw std::invalid_argument(std::string("corrupt state: ") + what + " is not a count in range");
        k = static_cast<Count>(x);
    }
    void states(std::vector<signed char>& c, std::size_t k) {
        c.resize(this->size(k));
        for (signed char& x : c) {
            const double d = *at++;
            if (d != -1.0 && d != 0.0 && d != 1.0) throw std::invalid_argument("corrupt contact state");
            x = static_cast<signed char>(d);
        }
    }
};

// Where each member starts in the flat form (after the header): what the tests that damage a
// state on purpose patch (plate_bench layout=1 prints it).
template <std::size_t N>
struct Layout : Sizes<N> {
    std::vector<std::pair<std::string, std::size_t>> fields;
    std::size_t at = 0;
    void add(const char* what, std::size_t n) {
        fields.emplace_back(what, at);
        at += n;
    }
    void vector(const Eigen::VectorXd&, std::size_t k, const char* what) { add(what, this->size(k)); }
    void real(const double&, const char* what) { add(what, 1); }
    template <class Count>
    void count(const Count&, const char* what, double = 0.0) {
        add(what, 1);
    }
    void states(const std::vector<signed char>&, std::size_t k) { add("contact state", this->size(k)); }
};

// The length of the flat form (header included) of a state `members` describes.
template <class State, std::size_t N, class Members>
std::size_t length(const std::array<std::size_t, N>& sizes, Members members) {
    State state;
    Sizer<N> sizer{{sizes}};
    members(state, sizer);
    return 1 + N + sizer.length;
}

// The flat form of `state`: format, sizes, then its members as `members` names them.
template <class State, std::size_t N, class Members>
std::vector<double> save(const State& state, double format, const std::array<std::size_t, N>& sizes, Members members) {
    Sizer<N> sizer{{sizes}};
    members(state, sizer);
    std::vector<double> out;
    out.reserve(1 + N + sizer.length);
    out.push_back(format);
    for (std::size_t k : sizes) out.push_back(static_cast<double>(k));
    Writer<N> writer{{sizes}, &out};
    members(state, writer);
    return out;
}

// The state back from its flat form; throws std::invalid_argument, naming what does not fit.
template <class State, std::size_t N, class Members>
State load(const std::vector<double>& in, double format, const std::array<std::size_t, N>& sizes, Members members) {
    State state;
    Sizer<N> sizer{{sizes}};
    members(state, sizer);
    if (in.empty() || in[0] != format)
        throw std::invalid_argument(
            "state does not belong to this plate (another scheme, or an earlier release's format)");
    bool fits = in.size() == 1 + N + sizer.length;
    for (std::size_t k = 0; fits && k < N; ++k) fits = in[1 + k] == static_cast<double>(sizes[k]);
    if (!fits) throw std::invalid_argument("state does not belong to this plate (size or format differs)");
    Reader<N> reader{{sizes}, in.data() + 1 + N};
    members(state, reader);
    return state;
}

// The layout of the flat form after its header (1 + N values).
template <class State, std::size_t N, class Members>
std::vector<std::pair<std::string, std::size_t>> layout(const std::array<std::size_t, N>& sizes, Members members) {
    State state;
    Layout<N> layout{{sizes}, {}, 0};
    members(state, layout);
    return layout.fields;
}

}  // namespace plate::archive
