#pragma once
// FMU states: what getting an FMU state captures, and the byte format of a serialized one.
// Model-independent: the values of the settable variables are written by walking the model's
// table, the rest is the model's own saveState().
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "core/FmiState.h"
#include "core/Model.h"

namespace fmu {

struct Snapshot {
    static constexpr std::uint64_t kTag = 0x46'4d'55'53'6e'61'70'00ULL;  // "FMUSnap": guards the cast
    std::uint64_t tag = kTag;
    State state = Instantiated;
    double startTime = 0.0;
    std::vector<double> values;  // parameters and inputs, in table order
    std::vector<double> modelState;  // Model::saveState
};

// The snapshot behind a StateHandle handed out by this layer, or nullptr.
Snapshot* asSnapshot(StateHandle state);

// Parameters and inputs: the variables an FMU state carries, in table order.
bool isSettable(const Variable& v);

class CorruptState : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A sound state written by a binary of another CPU architecture: refused by name (both platforms),
// since a run continued from it would not be the run it came from (docs/theory.md §20).
class ForeignState : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The platform this binary was built for, as FMI 3.0 names binaries folders ("x86_64-linux",
// "x86_64-windows", "aarch64-linux", ...), and its CPU architecture (the part before the dash):
// what decides the arithmetic (docs/theory.md §20). States travel between binaries of one
// architecture (x86_64-linux and x86_64-windows compute the same bits) and are refused across them.
const char* buildPlatform();

// Serialized form (native byte order; little-endian on every platform this FMU is built for):
//   bytes  0..7   magic: the model's ModelInfo::stateMagic (8 characters)
//   bytes  8..11  uint32 format version
//   bytes 12..15  uint32 length of the GUID
//   bytes 16..63  GUID of the FMU build that wrote it (NUL padded)
//   bytes 64..71  uint64 number n of doubles that follow
//   bytes 72..79  uint64 XXH64 checksum of all the other bytes (verified before any value is
//                 decoded)
//   bytes 80..95  the platform of the binary that wrote it (buildPlatform(), NUL padded)
//   bytes 96..    n doubles: the state-machine state, the start time, the values of the
//                 settable variables in table order, then the model's state.
std::size_t serializedSize(const Snapshot& snapshot);
void serialize(const Snapshot& snapshot, const Model& model, const char* guid, Byte* out, std::size_t size);
// Throws CorruptState naming what is wrong (magic, version, GUID, size, checksum, a value out
// of range), in that order; ForeignState (after the checksum, before any value) when another CPU
// architecture wrote it, naming both platforms.
Snapshot deserialize(const Byte* bytes, std::size_t size, const char* guid, const Model& model);

}  // namespace fmu
