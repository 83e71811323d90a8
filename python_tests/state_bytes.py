"""The serialized FMU-state layout the tests patch (fmu/core/StateFormat.h): a 96-byte header
whose bytes 72..79 hold the XXH64 checksum of all other bytes and bytes 80..95 the platform that
wrote it, then the values as doubles."""

import struct

import xxhash

CHECKSUM = slice(72, 80)
PLATFORM = slice(80, 96)
HEADER = 96


def checksum(blob: bytes) -> int:
    return xxhash.xxh64(blob[: CHECKSUM.start] + blob[CHECKSUM.stop :], seed=0).intdigest()


def with_checksum(blob: bytes) -> bytes:
    """The blob with its checksum field recomputed (a deliberate edit, not damage)."""
    return blob[: CHECKSUM.start] + struct.pack("<Q", checksum(blob)) + blob[CHECKSUM.stop :]
