#include "plate/DiscretizationCache.h"

#include <cstdlib>
#include <cstring>
#include <future>
#include <list>
#include <mutex>
#include <stdexcept>
#include <unordered_map>

#include "plate/Stops.h"

namespace plate {

// A field added to a part the keys read changes its size: decide whether it determines the space,
// the matrices, the modal basis or the condensed operators, add it to the keys below if it does,
// then write the new size here. (The same on every platform the FMU is built for: LP64 and LLP64
// lay doubles, ints, enums and bools out alike.) The refinement, the carrier, the initial load and
// the memory limit determine none of them.
static_assert(sizeof(MeshParameters) == 32 && sizeof(MaterialParameters) == 32 && sizeof(ObstacleParameters) == 88 &&
                  sizeof(LawParameters) == 64 && sizeof(OutputParameters) == 56,
              "PlateParameters changed: check the discretization cache's keys (DiscretizationCache.cpp)");

CacheKey& CacheKey::add(double x) {
    char raw[sizeof x];
    std::memcpy(raw, &x, sizeof x);  // the bits: -0.0 and 0.0 are two keys, as they may be two results
    bytes_.append(raw, sizeof raw);
    return *this;
}

CacheKey& CacheKey::add(long long x) {
    char raw[sizeof x];
    std::memcpy(raw, &x, sizeof x);
    bytes_.append(raw, sizeof raw);
    return *this;
}

namespace {

// Mesh and makeSpace: the mesh part.
CacheKey& addSpace(CacheKey& key, const MeshParameters& m) {
    return key.add(static_cast<int>(m.element)).add(m.length).add(m.width).add(m.nx).add(m.ny);
}

// Which vertices are contact rows and which obstacles hold each (docs/theory.md §25): the present
// obstacles (a row's bits name them, whole plate or not), and their rectangles unless they cover
// the whole plate.
CacheKey& addStops(CacheKey& key, const ObstacleParameters& o, const MeshParameters& mesh) {
    key.add(o.present(0) ? 1 : 0).add(o.present(1) ? 1 : 0);
    const bool whole = StopMap(o, mesh).wholePlate();
    key.add(whole ? 0 : 1);
    if (whole) return key;
    for (int k = 0; k < 2; ++k)
        if (o.present(k)) key.add(o.stop(k).xMin).add(o.stop(k).xMax).add(o.stop(k).yMin).add(o.stop(k).yMax);
    return key;
}

// The space, the material part (assemble: ρt, D, ν), the singular mass and the contact rows.
CacheKey& addPlate(CacheKey& key, const PlateParameters& p) {
    const MaterialParameters& m = p.material;
    addSpace(key, p.mesh).add(m.thickness).add(m.youngsModulus).add(m.poissonRatio).add(m.density);
    return addStops(key.add(static_cast<int>(p.law.mass)), p.obstacles, p.mesh);
}

}  // namespace

CacheKey spaceKey(const PlateParameters& p) {
    CacheKey key("space");
    return addSpace(key, p.mesh);
}

CacheKey clampedPlateKey(const PlateParameters& p) {
    CacheKey key("clamped plate");
    return addPlate(key, p);
}

// ModalBasis(clamped, modes): Ω², Φ and what they make of the contact vertices and the loads — not
// Δt, β or the damping (ModalPlate's step diagonal, made per instance), so that a sweep over those
// shares one eigen solution.
CacheKey modalBasisKey(const PlateParameters& p, bool completeEngine) {
    CacheKey key("modal basis");
    return addPlate(key, p).add(completeEngine ? 1 : 0).add(p.law.modes);
}

// condense(clamped, R, the output rows, modes, the recovery functionals): the functionals are the
// probes' points (their count, then each) and, with stress_outputs, samples the space fixes.
CacheKey condensedPlateKey(const PlateParameters& p) {
    CacheKey key("condensed plate");
    const OutputParameters& o = p.outputs;
    addPlate(key, p).add(p.law.modes).add(o.stressOutputs ? 1 : 0).add(double(o.probeCount()));
    for (std::size_t k = 0; k < o.probeCount(); ++k) key.add(o.probeX[k]).add(o.probeY[k]);
    return key;
}

CacheKey kappaKey(const PlateParameters& p) {
    CacheKey key("kappa_h");
    return addPlate(key, p);
}

namespace {

struct Entry {
    std::shared_future<std::shared_ptr<const void>> object;
    std::type_index type;
    std::size_t bytes = 0;
    bool ready = false;  // built; only ready entries are in `recent` and can be dropped
    std::list<std::string>::iterator recent;
};

struct Table {
    std::mutex mutex;
    std::unordered_map<std::string, Entry> entries;
    std::list<std::string> recent;  // ready entries' keys, most recently used first
    CacheStatistics counts;  // hits, builds, evictions; entries and bytes kept up to date
};

Table& table() {
    static Table t;
    return t;
}

// PLATEIMPACT_CACHE_MB: a number ≥ 0 (0: off); anything else, or unset: the default.
std::size_t budgetBytes() {
    double mb = kDefaultCacheMB;
    if (const char* text = std::getenv("PLATEIMPACT_CACHE_MB")) {
        char* end = nullptr;
        const double value = std::strtod(text, &end);
        if (end != text && *end == '\0' && value >= 0.0 && value < 1e9) mb = value;
    }
    return static_cast<std::size_t>(mb * 1024.0 * 1024.0);
}

// Drops the least recently used ready entries until the table holds at most `budget` bytes.
void evictTo(Table& t, std::size_t budget) {
    while (t.counts.bytes > budget && !t.recent.empty()) {
        auto it = t.entries.find(t.recent.back());
        t.counts.bytes -= it->second.bytes;
        t.recent.pop_back();
        t.entries.erase(it);
        --t.counts.entries;
        ++t.counts.evictions;
    }
}

}  // namespace

namespace detail {

std::shared_ptr<const void> lookupOrBuild(const CacheKey& key, std::type_index type,
                                          const std::function<Built()>& build, CacheUse& use) {
    Table& t = table();
    const std::size_t budget = budgetBytes();
    std::unique_lock<std::mutex> lock(t.mutex);
    t.counts.budgetBytes = budget;
    if (budget == 0) {  // off: as before the cache, and nothing kept
        evictTo(t, 0);
        ++t.counts.builds;
        lock.unlock();
        ++use.built;
        return build().first;
    }
    const auto found = t.entries.find(key.bytes());
    if (found != t.entries.end()) {
        Entry& e = found->second;
        if (e.type != type) throw std::logic_error("discretization cache: one key for two types");
        if (e.ready) t.recent.splice(t.recent.begin(), t.recent, e.recent);
        ++t.counts.hits;
        const auto object = e.object;
        lock.unlock();
        ++use.shared;
        return object.get();  // waits while another thread builds it; rethrows what its build threw
    }
    std::promise<std::shared_ptr<const void>> promise;
    t.entries.emplace(key.bytes(), Entry{promise.get_future().share(), type, 0, false, {}});
    ++t.counts.builds;
    lock.unlock();
    Built made;
    try {
        made = build();
    } catch (...) {
        lock.lock();
        t.entries.erase(key.bytes());
        lock.unlock();
        promise.set_exception(std::current_exception());
        throw;
    }
    promise.set_value(made.first);
    ++use.built;
    lock.lock();
    Entry& e = t.entries.find(key.bytes())->second;  // still there: only ready entries are dropped
    e.bytes = made.second;
    e.ready = true;
    t.recent.push_front(key.bytes());
    e.recent = t.recent.begin();
    t.counts.bytes += e.bytes;
    ++t.counts.entries;
    evictTo(t, budget);
    return made.first;
}

}  // namespace detail

CacheStatistics discretizationCacheStatistics() {
    Table& t = table();
    std::lock_guard<std::mutex> lock(t.mutex);
    return t.counts;
}

void clearDiscretizationCache() {
    Table& t = table();
    std::lock_guard<std::mutex> lock(t.mutex);
    evictTo(t, 0);
}

}  // namespace plate
