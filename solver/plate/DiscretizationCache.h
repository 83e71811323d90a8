#pragma once
// The process-wide cache of discretizations (README, "Performance"). What an instance builds
// before its first step — the FE space, the clamped M and K, the modal basis, the condensed
// operators — depends on a few parameters only; instances with the same ones (a sweep's points, a master that re-instantiates, a test
// suite) share one immutable copy instead of each building its own: the default plate's
// complete modal basis is 95 % of its 0.6 s initialization.
//
// - Keyed by the bytes of every parameter that determines the object (the key functions below,
//   the one place they are written; a new field in a part of PlateParameters they read fails a
//   static_assert in DiscretizationCache.cpp until someone decides whether it belongs in a key).
// - Immutable, shared: entries are shared_ptr<const T> of objects without mutable state (the
//   sparse engine's factor has a workspace, so FullOrderPlate is not cached: each instance
//   factors A itself). The same code builds them either way: results are bit for bit the same.
// - Thread-safe: one mutex around the table; an object being built is a shared_future that other
//   threads asking for the same key wait on, so it is built once.
// - Bounded: each entry is charged its bytes; past the budget the least recently used entries
//   are dropped (an instance holding one keeps its copy alive). The budget is read from the
//   environment variable PLATEIMPACT_CACHE_MB at every lookup (default kDefaultCacheMB; 0 turns
//   the cache off: every instance builds its own, as before the cache).
// - It lives as long as the process: the first copy of the FMU's library loaded in a process stays
//   loaded and every later copy of the same build forwards its FMI calls to it, so a master that
//   unloads the library with its instance, or extracts the FMU anew for each run (fmpy's
//   simulate_fmu), still finds the plates built before (fmu/core/PrimaryCopy.h): one cache, one
//   budget per process (per FMI version of the FMU).
#include <Eigen/Core>
#include <Eigen/Sparse>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <typeindex>

#include "plate/PlateParameters.h"

namespace plate {

inline constexpr double kDefaultCacheMB = 256.0;

// The bytes of the parameters an object depends on, after a name for its kind.
class CacheKey {
public:
    explicit CacheKey(const char* kind) : bytes_(kind) { bytes_.push_back('\0'); }
    CacheKey& add(double x);
    CacheKey& add(long long x);
    CacheKey& add(int x) { return add(static_cast<long long>(x)); }
    const std::string& bytes() const { return bytes_; }

private:
    std::string bytes_;
};

// The keys (the one place they are written): the FE space, the clamped plate (space, M, K, the singular mass's
// B and R), Newmark's modal basis (a reduced one sliced from the complete one where the dense solution serves), the condensed plate, κ_h.
CacheKey spaceKey(const PlateParameters& p);
CacheKey clampedPlateKey(const PlateParameters& p);
CacheKey modalBasisKey(const PlateParameters& p, bool completeEngine);
CacheKey condensedPlateKey(const PlateParameters& p);
CacheKey kappaKey(const PlateParameters& p);

// What one instance's lookups did: its log says so (PlateSimulation), tests check it.
struct CacheUse {
    int shared = 0;  // found in the cache (or built by another thread while this one waited)
    int built = 0;  // built here (and kept, if the budget allows)
};

struct CacheStatistics {
    long long hits = 0, builds = 0, evictions = 0;
    std::size_t entries = 0, bytes = 0, budgetBytes = 0;
};
CacheStatistics discretizationCacheStatistics();
// Drops every entry (instances keep theirs); the counters stay.
void clearDiscretizationCache();

// What an Eigen object holds on the heap, for the budget.
template <class Derived>
std::size_t heapBytes(const Eigen::PlainObjectBase<Derived>& m) {
    return sizeof(typename Derived::Scalar) * static_cast<std::size_t>(m.size());
}
template <class Scalar, int Options, class Index>
std::size_t heapBytes(const Eigen::SparseMatrix<Scalar, Options, Index>& m) {
    return (sizeof(Scalar) + sizeof(Index)) * static_cast<std::size_t>(m.nonZeros()) +
           sizeof(Index) * static_cast<std::size_t>(m.outerSize() + 1);
}

namespace detail {
using Built = std::pair<std::shared_ptr<const void>, std::size_t>;  // the object and its bytes
std::shared_ptr<const void> lookupOrBuild(const CacheKey& key, std::type_index type,
                                          const std::function<Built()>& build, CacheUse& use);
}  // namespace detail

// The object of `key`, from the cache or from `build()` (then kept while within the budget).
// `bytes(object)` is what it is charged. An exception of build() reaches every caller waiting
// for that key, and nothing is kept.
template <class T, class Build, class Bytes>
std::shared_ptr<const T> cached(const CacheKey& key, Build&& build, Bytes&& bytes, CacheUse& use) {
    auto object = detail::lookupOrBuild(
        key, typeid(T),
        [&]() -> detail::Built {
            std::shared_ptr<const T> made = build();
            const std::size_t size = bytes(*made);
            return {std::move(made), size};
        },
        use);
    return std::static_pointer_cast<const T>(object);
}

}  // namespace plate
