// libFuzzer harness (b): the FMU-state deserializer fed raw bytes. The first byte picks how:
//   even  the bytes as they are (almost always stopped by the header or the checksum);
//   odd   the bytes after it as the values of a state, behind a valid header with this build's
//         GUID and a repaired checksum, so that the decoder of the values is what gets fuzzed.
// A state that is accepted is set, stepped and read: whatever it holds, the FMU must refuse it
// or run it, never crash.
#include <cstring>
#include <vector>

#include "FuzzSupport.h"

// xxHash, as fmu/core/StateFormat.cpp uses it (the checksum the harness repairs).
#define XXH_INLINE_ALL
#include <xxhash.h>

namespace {

constexpr std::size_t kChecksumOffset = 72, kHeaderBytes = 96;  // fmu/core/StateFormat.h

// A valid header (this build's) around `values`, with the checksum the decoder expects.
std::vector<fmi2Byte> withHeader(const std::uint8_t* values, std::size_t size, std::vector<fmi2Byte> header) {
    const std::size_t n = size / sizeof(double);
    std::vector<fmi2Byte> blob(header.begin(), header.begin() + kHeaderBytes);
    const std::uint64_t count = n;
    std::memcpy(blob.data() + 64, &count, 8);
    blob.insert(blob.end(), values, values + n * sizeof(double));
    XXH64_state_t state;
    XXH64_reset(&state, 0);
    XXH64_update(&state, blob.data(), kChecksumOffset);
    XXH64_update(&state, blob.data() + kChecksumOffset + 8, blob.size() - kChecksumOffset - 8);  // the platform too
    const std::uint64_t sum = XXH64_digest(&state);
    std::memcpy(blob.data() + kChecksumOffset, &sum, 8);
    return blob;
}

// The header of a real state of this build (magic, version, GUID), made once.
const std::vector<fmi2Byte>& realHeader() {
    static const std::vector<fmi2Byte> header = [] {
        fmi2Component c = fuzz::instantiate();
        fuzz::smallPlate(c, 1, 1);
        fmi2EnterInitializationMode(c);
        fmi2ExitInitializationMode(c);
        fmi2FMUstate state = nullptr;
        fmi2GetFMUstate(c, &state);
        size_t size = 0;
        fmi2SerializedFMUstateSize(c, state, &size);
        std::vector<fmi2Byte> blob(size);
        fmi2SerializeFMUstate(c, state, blob.data(), size);
        fmi2FreeFMUstate(c, &state);
        fmi2FreeInstance(c);
        return blob;
    }();
    return header;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const bool repaired = data[0] & 1;
    const std::vector<fmi2Byte> blob =
        repaired ? withHeader(data + 1, size - 1, realHeader()) : std::vector<fmi2Byte>(data + 1, data + size);
    fmi2Component c = fuzz::instantiate();
    fuzz::smallPlate(c, 1, 1);
    fmi2FMUstate state = nullptr;
    if (fmi2DeSerializeFMUstate(c, blob.data(), blob.size(), &state) == fmi2OK) {
        // A state of a large mesh is legal, only slow to rebuild: set only small ones (nx, ny
        // and modes are values 8, 9 and 18 of the state: after the machine state and the start
        // time, in table order).
        const auto value = [&](std::size_t i) {
            double x = 0.0;
            std::memcpy(&x, blob.data() + kHeaderBytes + 8 * i, sizeof x);
            return x;
        };
        const bool small = blob.size() >= kHeaderBytes + 8 * 19 && value(8) <= 2 && value(9) <= 2 && value(18) <= 8;
        if (small && fmi2SetFMUstate(c, state) == fmi2OK) {
            fmi2Real t = 0.0;
            fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &t);
            fmi2DoStep(c, t, 1e-4, fmi2True);
            fmi2Real out[3];
            const fmi2ValueReference vr[3] = {plateimpact::kVrCorner1, plateimpact::kVrEnergy,
                                              plateimpact::kVrEnergyDissipated};
            fmi2GetReal(c, vr, 3, out);
        }
        fmi2FreeFMUstate(c, &state);
    }
    fmi2FreeInstance(c);
    return 0;
}
