// The rendezvous of the copies of one build (PrimaryCopy.h): where this copy is, its build id,
// pinning it, and finding the primary's module, for Linux (dladdr, the GNU build-id note,
// dlopen RTLD_NOLOAD | RTLD_NODELETE) and Windows (GetModuleHandleEx, the PE time stamp, the pin
// flag); elsewhere every copy runs its own code.
#include "core/PrimaryCopy.h"

#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/Model.h"

#if defined(__linux__)
#include <dlfcn.h>
#include <elf.h>
#include <link.h>
#include <unistd.h>
#elif defined(_WIN32)
#include <windows.h>
#endif

namespace fmu {
namespace {

// This copy: where it is (Linux: its library's path; Windows: its HMODULE in hex) and its build id
// ("" when unknown: then it never forwards nor pins), and the model identifier (the library's name).
struct Copy {
    std::string location, buildId, model;
};

constexpr char kDigits[] = "0123456789abcdef";

std::string hex(const unsigned char* bytes, std::size_t n) {
    std::string out;
    for (std::size_t k = 0; k < n; ++k) out += {kDigits[bytes[k] >> 4], kDigits[bytes[k] & 15]};
    return out;
}

// The library's file name without folder and extension (the FMU's model identifier).
std::string modelOf(const std::string& path) {
    std::string name = path.substr(path.find_last_of("/\\") + 1);
    return name.substr(0, name.find('.'));
}

const void* self() { return reinterpret_cast<const void*>(&primaryModule); }

#if defined(__linux__)

// dl_iterate_phdr: the GNU build-id note of the object that contains self().
int findBuildId(dl_phdr_info* info, std::size_t, void* out) {
    const auto address = reinterpret_cast<ElfW(Addr)>(self());
    bool mine = false;
    for (int i = 0; i < info->dlpi_phnum; ++i) {
        const ElfW(Phdr)& ph = info->dlpi_phdr[i];
        const ElfW(Addr) start = info->dlpi_addr + ph.p_vaddr;
        mine = mine || (ph.p_type == PT_LOAD && address >= start && address < start + ph.p_memsz);
    }
    if (!mine) return 0;
    for (int i = 0; i < info->dlpi_phnum; ++i) {
        const ElfW(Phdr)& ph = info->dlpi_phdr[i];
        if (ph.p_type != PT_NOTE) continue;
        const auto* p = reinterpret_cast<const unsigned char*>(info->dlpi_addr + ph.p_vaddr);
        const unsigned char* end = p + ph.p_memsz;
        while (p + sizeof(ElfW(Nhdr)) <= end) {
            const auto* note = reinterpret_cast<const ElfW(Nhdr)*>(p);
            const unsigned char* name = p + sizeof(ElfW(Nhdr));
            const unsigned char* desc = name + ((note->n_namesz + 3) & ~3u);
            if (note->n_type == NT_GNU_BUILD_ID && note->n_namesz == 4 && std::memcmp(name, "GNU", 4) == 0 &&
                desc + note->n_descsz <= end) {
                *static_cast<std::string*>(out) = hex(desc, note->n_descsz);
                return 1;
            }
            p = desc + ((note->n_descsz + 3) & ~3u);
        }
    }
    return 1;
}

Copy thisCopy() {
    Dl_info info{};
    if (!dladdr(self(), &info) || !info.dli_fname || !info.dli_fname[0]) return {};
    Copy copy{info.dli_fname, "", modelOf(info.dli_fname)};
    dl_iterate_phdr(findBuildId, &copy.buildId);
    return copy;
}

// The module loaded at `location` (a reference the caller keeps), or nullptr when none is.
void* loadedModule(const std::string& location) { return dlopen(location.c_str(), RTLD_LAZY | RTLD_NOLOAD); }

bool pin(const Copy& copy) { return dlopen(copy.location.c_str(), RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE); }

long processId() { return static_cast<long>(getpid()); }

std::string environment(const std::string& name) {
    const char* value = std::getenv(name.c_str());
    return value ? value : "";
}

void publish(const std::string& name, const std::string& value) { setenv(name.c_str(), value.c_str(), 1); }

#elif defined(_WIN32)

HMODULE ownModule(DWORD flags) {
    HMODULE module = nullptr;
    return GetModuleHandleExA(GET_MODULE_HANDLE_EX_FLAG_FROM_ADDRESS | flags, static_cast<LPCSTR>(self()), &module)
               ? module
               : nullptr;
}

Copy thisCopy() {
    HMODULE module = ownModule(GET_MODULE_HANDLE_EX_FLAG_UNCHANGED_REFCOUNT);
    char path[MAX_PATH] = {};
    if (!module || !GetModuleFileNameA(module, path, MAX_PATH)) return {};
    // The link time stamp (ld --insert-timestamp, fmu/CMakeLists.txt): a new link, a new id.
    const auto* base = reinterpret_cast<const unsigned char*>(module);
    const auto* dos = reinterpret_cast<const IMAGE_DOS_HEADER*>(base);
    const auto* nt = reinterpret_cast<const IMAGE_NT_HEADERS*>(base + dos->e_lfanew);
    const DWORD stamp = nt->FileHeader.TimeDateStamp;
    const auto address = reinterpret_cast<std::uintptr_t>(module);
    Copy copy{hex(reinterpret_cast<const unsigned char*>(&address), sizeof address), "", modelOf(path)};
    if (stamp != 0) copy.buildId = hex(reinterpret_cast<const unsigned char*>(&stamp), sizeof stamp);
    return copy;
}

void* loadedModule(const std::string& location) {
    // The module whose base address `location` spells, if one is loaded there (its own base lies in it).
    std::uintptr_t address = 0;
    if (location.size() != 2 * sizeof address) return nullptr;
    for (std::size_t k = 0; k < location.size(); ++k) {
        const char* digit = std::strchr(kDigits, location[k]);
        if (!digit || !*digit) return nullptr;
        reinterpret_cast<unsigned char*>(&address)[k / 2] |=
            static_cast<unsigned char>((digit - kDigits) << (k % 2 ? 0 : 4));
    }
    HMODULE module = nullptr;
    const bool found =
        GetModuleHandleExA(GET_MODULE_HANDLE_EX_FLAG_FROM_ADDRESS | GET_MODULE_HANDLE_EX_FLAG_UNCHANGED_REFCOUNT,
                           reinterpret_cast<LPCSTR>(address), &module);
    return found && reinterpret_cast<std::uintptr_t>(module) == address ? module : nullptr;
}

bool pin(const Copy&) { return ownModule(GET_MODULE_HANDLE_EX_FLAG_PIN) != nullptr; }

long processId() { return static_cast<long>(GetCurrentProcessId()); }

std::string environment(const std::string& name) {
    char value[1024] = {};
    const DWORD n = GetEnvironmentVariableA(name.c_str(), value, sizeof value);
    return n > 0 && n < sizeof value ? value : "";
}

void publish(const std::string& name, const std::string& value) {
    SetEnvironmentVariableA(name.c_str(), value.c_str());
}

#else

Copy thisCopy() { return {}; }
void* loadedModule(const std::string&) { return nullptr; }
bool pin(const Copy&) { return false; }
long processId() { return 0; }
std::string environment(const std::string&) { return ""; }
void publish(const std::string&, const std::string&) {}

#endif

}  // namespace

void* primaryModule(const char* fmiVersion) {
    const Copy copy = thisCopy();
    if (copy.location.empty() || copy.buildId.empty()) return nullptr;
    std::string variable = std::string("PLATEIMPACT_") + fmiVersion + "_PRIMARY_" + copy.model;
    for (char& c : variable)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    const std::string build = copy.buildId + "-" + modelGuid();
    const std::string process = ":" + std::to_string(processId()) + ":";
    // "<build id>:<pid>:<location>"; the build id holds no ':', the location may.
    const std::string published = environment(variable);
    const std::size_t at = published.find(process);
    if (at != std::string::npos && published.find(':') == at) {
        // The published location is this copy's own only in a value left before an exec (a primary is
        // pinned: no other copy loads at its location while it lives); this copy then replaces it below.
        const std::string location = published.substr(at + process.size());
        if (location != copy.location)
            if (void* primary = loadedModule(location))  // a reference never released: the primary is pinned
                // The same build: forward to it; another build: this copy runs its own code, unpinned.
                return published.compare(0, at, build) == 0 ? primary : nullptr;
    }
    // No live primary (none yet, or a value another process left): this copy becomes it.
    if (pin(copy)) publish(variable, build + process + copy.location);
    return nullptr;
}

void* moduleFunction(void* module, const char* name) {
#if defined(__linux__)
    return dlsym(module, name);
#elif defined(_WIN32)
    return reinterpret_cast<void*>(GetProcAddress(static_cast<HMODULE>(module), name));
#else
    (void)module;
    (void)name;
    return nullptr;
#endif
}

}  // namespace fmu
