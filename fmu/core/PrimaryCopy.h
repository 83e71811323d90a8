#pragma once
// One copy of the FMU's code per process (README, "Performance"; docs/architecture.md).
//
// An importer that extracts the FMU anew for every simulation (fmpy's simulate_fmu) loads a fresh
// copy of the library from a new path each time and unloads it with its instance: the process-wide
// discretization cache (solver/plate/DiscretizationCache.h) would die with every copy, and every
// simulation would pay the whole setup. So the first copy of a build loaded in a process becomes
// its primary: it pins itself (never unloaded: RTLD_NODELETE, GET_MODULE_HANDLE_EX_FLAG_PIN) and
// publishes where it is in the environment variable PLATEIMPACT_<FMI version>_PRIMARY_<model
// identifier> as "<build id>:<pid>:<path of its library>". A later copy of the same build (the same
// build id, the same pid) forwards every exported FMI function to the primary's, found by name in
// the primary's module (dlsym, GetProcAddress): its instances are the primary's objects, built by the
// primary's code over the primary's cache, and the later copy can be unloaded safely (nothing of
// the primary refers to its code). One copy's code and one cache live in the process, whatever the
// number of copies loaded and unloaded; the cache's budget is as before.
//
// - The build id differs whenever the code does: the GNU build-id note the linker writes (a hash
//   of the linked library; Linux), the PE header's link time stamp (Windows), each with the model's
//   GUID (a hash of the sources). Without one (macOS, a linker without build ids) a copy runs its
//   own code, as every copy did before.
// - The primary is looked up by its path among the modules already loaded (dlopen RTLD_NOLOAD,
//   GetModuleHandle): a value left by another process (an exec'd child inherits the environment;
//   exec keeps the pid) names no loaded module of this process and is replaced.
// - A copy decides once, at its first FMI call. A copy of another build while a primary lives runs
//   its own code and is unloaded as before. Two copies deciding at the same moment in two threads may
//   both pin themselves (two caches); each instance is still one copy's, whole.
// - Never RTLD_GLOBAL: the primary's fmi2*/fmi3* symbols never interpose those of other FMUs.
// - Rather than a cache on disk: nothing is written anywhere, nothing goes stale, no files to lock
//   between processes; the next simulate_fmu's setup costs what a next instance's does (2 % of the
//   first's, tools/instance_setup.py), where a file would still be read and decoded (the default
//   plate's modal basis alone is 4.3 MB).

namespace fmu {

// The module of the primary copy whose functions this copy's exported functions call, or nullptr
// when this copy calls its own (it is the primary, or cannot forward). `fmiVersion`: "FMI2" or
// "FMI3" (the two are different libraries, each with its own primary).
void* primaryModule(const char* fmiVersion);

// The address of the exported function `name` in `module` (a result of primaryModule), or nullptr.
void* moduleFunction(void* module, const char* name);

}  // namespace fmu

// The exported functions of one FMI version, each calling this copy's implementation (compiled
// with the function prefix plateimpactOwn_: fmi2/Fmi2Own.h, fmi3/Fmi3Own.h) or the primary's.
// LIST(X) calls X(return type, name, (parameters), (arguments)) for every function of the version.
#define FMU_OWN_DECLARATION(R, name, params, args) name##TYPE plateimpactOwn_##name;
#define FMU_TABLE_MEMBER(R, name, params, args) name##TYPE* name;
#define FMU_OWN_ENTRY(R, name, params, args) &plateimpactOwn_##name,
#define FMU_PRIMARY_ENTRY(R, name, params, args) reinterpret_cast<name##TYPE*>(fmu::moduleFunction(primary, #name)),
#define FMU_COMPLETE(R, name, params, args) &&table.name
#define FMU_FORWARD(R, name, params, args) \
    R name params { return entryPoints().name args; }
#define FMU_FORWARDED_EXPORTS(LIST, VERSION)              \
    extern "C" {                                          \
    LIST(FMU_OWN_DECLARATION)                             \
    }                                                     \
    namespace {                                           \
    struct EntryPoints {                                  \
        LIST(FMU_TABLE_MEMBER)                            \
    };                                                    \
    EntryPoints choose() {                                \
        const EntryPoints own{LIST(FMU_OWN_ENTRY)};       \
        void* primary = fmu::primaryModule(VERSION);      \
        if (!primary) return own;                         \
        const EntryPoints table{LIST(FMU_PRIMARY_ENTRY)}; \
        return (true LIST(FMU_COMPLETE)) ? table : own;   \
    }                                                     \
    const EntryPoints& entryPoints() {                    \
        static const EntryPoints chosen = choose();       \
        return chosen;                                    \
    }                                                     \
    }                                                     \
    extern "C" {                                          \
    LIST(FMU_FORWARD)                                     \
    }
