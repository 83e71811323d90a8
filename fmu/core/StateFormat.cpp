#include "core/StateFormat.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

// xxHash (Debian's libxxhash-dev), header-only: XXH64 checksums the serialized state.
#define XXH_INLINE_ALL
#include <xxhash.h>

namespace fmu {

namespace {

// Version 3: values walked from the table of variables, outputs no longer stored (they are
// recomputed from the model's state). Version 4: the impact-law parameters and the scheme's
// damping energy and contact impulses (docs/theory.md §11–13). Older states are refused by name.
// Version 5: the port (a third time level, contact sums, the clamp's motion inputs, the
// communication time between grid points; docs/theory.md §14–16).
// Version 6: per input whether its value was set since the last step and the time its signal
// starts (inputs are samples at the times the master set them).
// Version 7: the root stress's peak since t = 0 and the stress and probe outputs of the grid point
// before an off-grid communication time (docs/theory.md §23).
// Version 8: the platform of the binary that wrote it (a state of another CPU architecture is refused
// by name instead of run wrong; issue 46).
constexpr std::uint32_t kFormatVersion = 8;
constexpr std::size_t kGuidField = 48;
constexpr std::size_t kChecksumOffset = 8 + 4 + 4 + kGuidField + 8;
constexpr std::size_t kPlatformOffset = kChecksumOffset + 8;
constexpr std::size_t kPlatformField = 16;
constexpr std::size_t kHeaderBytes = kPlatformOffset + kPlatformField;

// The architecture part of a platform name ("x86_64" of "x86_64-windows").
std::string architecture(const std::string& platform) { return platform.substr(0, platform.find('-')); }

// XXH64 of every byte of a serialized state but the checksum field itself.
std::uint64_t checksum(const Byte* bytes, std::size_t size) {
    XXH64_state_t state;
    XXH64_reset(&state, 0);
    XXH64_update(&state, bytes, kChecksumOffset);
    XXH64_update(&state, bytes + kChecksumOffset + 8, size - kChecksumOffset - 8);  // the platform too
    return XXH64_digest(&state);
}

bool isStateOfSnapshot(double code) {
    for (unsigned s :
         {unsigned(Instantiated), unsigned(InitializationMode), unsigned(StepComplete), unsigned(StepFailed),
          unsigned(StepCanceled), unsigned(Terminated), unsigned(Error), unsigned(EventMode)}) {
        if (code == double(s)) return true;
    }
    return false;
}

// A variable's value as read back: finite, and inside what its type allows.
void checkValue(const Variable& v, double x) {
    const std::string what = std::string(v.name) + " = " + std::to_string(x);
    switch (v.type) {
        case VariableType::Real:
            if (!std::isfinite(x)) throw CorruptState(std::string(v.name) + " is not finite");
            return;
        case VariableType::Integer:
            if (!(x >= -2147483648.0 && x <= 2147483647.0) || std::floor(x) != x)
                throw CorruptState(what + " is not an Integer");
            if (v.enumeration && !v.enumeration->contains(int(x)))
                throw CorruptState(what + " is none of its items (" + v.enumeration->itemList() + ")");
            return;
        case VariableType::Boolean:
            if (x != 0.0 && x != 1.0) throw CorruptState(what + " is not a Boolean");
            return;
    }
}

std::vector<double> payload(const Snapshot& s) {
    std::vector<double> out = {double(unsigned(s.state)), s.startTime};
    out.insert(out.end(), s.values.begin(), s.values.end());
    out.insert(out.end(), s.modelState.begin(), s.modelState.end());
    return out;
}

}  // namespace

Snapshot* asSnapshot(StateHandle state) {
    auto* snapshot = static_cast<Snapshot*>(state);
    return snapshot && snapshot->tag == Snapshot::kTag ? snapshot : nullptr;
}

bool isSettable(const Variable& v) { return v.causality != Causality::Output; }

const char* buildPlatform() {
#if defined(__x86_64__) || defined(_M_X64)
#define PLATEIMPACT_ARCH "x86_64"
#elif defined(__aarch64__) || defined(_M_ARM64)
#define PLATEIMPACT_ARCH "aarch64"
#elif defined(__i386__) || defined(_M_IX86)
#define PLATEIMPACT_ARCH "x86"
#else
#define PLATEIMPACT_ARCH "unknown"
#endif
#if defined(_WIN32)
    return PLATEIMPACT_ARCH "-windows";
#elif defined(__APPLE__)
    return PLATEIMPACT_ARCH "-darwin";
#else
    return PLATEIMPACT_ARCH "-linux";
#endif
#undef PLATEIMPACT_ARCH
}

std::size_t serializedSize(const Snapshot& s) {
    return kHeaderBytes + sizeof(double) * (2 + s.values.size() + s.modelState.size());
}

void serialize(const Snapshot& s, const Model& model, const char* guid, Byte* out, std::size_t size) {
    const std::vector<double> data = payload(s);
    const std::uint32_t version = kFormatVersion;
    const std::uint32_t guidLength = static_cast<std::uint32_t>(std::strlen(guid));
    const std::uint64_t count = data.size();
    if (guidLength > kGuidField || size != kHeaderBytes + sizeof(double) * data.size())
        throw std::logic_error("serialize: size does not match serializedSize");
    std::memset(out, 0, kHeaderBytes);
    std::memcpy(out, model.info().stateMagic, 8);
    std::memcpy(out + 8, &version, 4);
    std::memcpy(out + 12, &guidLength, 4);
    std::memcpy(out + 16, guid, guidLength);
    std::memcpy(out + 16 + kGuidField, &count, 8);
    static_assert(sizeof("aarch64-windows") <= kPlatformField, "platform names fit their field");
    std::memcpy(out + kPlatformOffset, buildPlatform(), std::strlen(buildPlatform()));
    std::memcpy(out + kHeaderBytes, data.data(), sizeof(double) * data.size());
    const std::uint64_t sum = checksum(out, size);
    std::memcpy(out + kChecksumOffset, &sum, 8);
}

Snapshot deserialize(const Byte* bytes, std::size_t size, const char* guid, const Model& model) {
    if (size < kHeaderBytes)
        throw CorruptState(std::to_string(size) + " bytes, shorter than the " + std::to_string(kHeaderBytes) +
                           "-byte header");
    const ModelInfo& info = model.info();
    if (std::memcmp(bytes, info.stateMagic, 8) != 0)
        throw CorruptState(std::string("wrong magic (not a ") + info.modelName + " FMU state)");
    std::uint32_t version = 0, guidLength = 0;
    std::uint64_t count = 0;
    std::memcpy(&version, bytes + 8, 4);
    std::memcpy(&guidLength, bytes + 12, 4);
    std::memcpy(&count, bytes + 16 + kGuidField, 8);
    if (version != kFormatVersion)
        throw CorruptState("format version " + std::to_string(version) + ", expected " +
                           std::to_string(kFormatVersion) + " (states saved by an older " + info.modelName +
                           " cannot be read)");
    if (guidLength != std::strlen(guid) || std::memcmp(bytes + 16, guid, guidLength) != 0)
        throw CorruptState(std::string("the serialized state was written by a different build (GUID mismatch; "
                                       "this FMU has GUID ") +
                           guid + ")");
    const std::size_t payloadBytes = size - kHeaderBytes;
    if (payloadBytes % sizeof(double) != 0 || count != payloadBytes / sizeof(double))
        throw CorruptState("wrong size, " + std::to_string(size) + " bytes for the " + std::to_string(count) +
                           " values its header announces");
    // Before any value is decoded: a state damaged on disk or on the way (a flipped bit, a
    // patched byte) is refused here as a whole.
    std::uint64_t stored = 0;
    std::memcpy(&stored, bytes + kChecksumOffset, 8);
    if (stored != checksum(bytes, size))
        throw CorruptState("checksum mismatch (XXH64 of the state's bytes): the state is damaged");
    // Sound, and now its platform is known for sure: another CPU architecture computes other bits
    // (docs/theory.md §20), and a run continued from its state would not be the run it came from.
    const char* field = reinterpret_cast<const char*>(bytes + kPlatformOffset);
    const std::string platform(field, std::find(field, field + kPlatformField, '\0'));
    if (architecture(platform) != architecture(buildPlatform()))
        throw ForeignState("the state was saved by the " + platform + " binary and this is the " + buildPlatform() +
                           " binary: a state travels only between binaries of one CPU architecture, which compute "
                           "the same bits (x86_64-linux and x86_64-windows do; docs/theory.md §20); restore it with "
                           "an " +
                           architecture(platform) + " binary, or start this one from its parameters");
    std::vector<double> data(static_cast<std::size_t>(count));
    if (count > 0) std::memcpy(data.data(), bytes + kHeaderBytes, payloadBytes);

    std::size_t settable = 0;
    for (const Variable& v : model.variables()) settable += isSettable(v);
    if (data.size() < 2 + settable) throw CorruptState("data end before the values of the variables");
    Snapshot s;
    if (!isStateOfSnapshot(data[0])) throw CorruptState("unknown state-machine state");
    s.state = static_cast<State>(static_cast<unsigned>(data[0]));
    if (!std::isfinite(data[1])) throw CorruptState("start time is not finite");
    s.startTime = data[1];
    std::size_t next = 2;
    for (const Variable& v : model.variables()) {
        if (!isSettable(v)) continue;
        checkValue(v, data[next]);
        s.values.push_back(data[next++]);
    }
    s.modelState.assign(data.begin() + static_cast<std::ptrdiff_t>(next), data.end());
    return s;
}

}  // namespace fmu
