#pragma once
// The core's own types, of no FMI version (as the Reference FMUs' model.h): the front ends
// (the folders fmi2/ and fmi3/) convert their C types to and from these.
#include <cstddef>
#include <cstdint>
#include <functional>

namespace fmu {

// The outcome of a call; a front end maps it to its own status type.
enum class Status { OK, Warning, Discard, Error, Fatal };

using ValueReference = std::uint32_t;
enum class Causality { Parameter, Input, Output };  // of a variable of a model's table

// One byte of a serialized FMU state.
using Byte = unsigned char;

// An FMU state as the importer holds it: opaque, made and read by the core only.
using StateHandle = void*;

// Where the instance's messages go: the front end fills it with the importer's callback.
// The message is plain text (no printf format); `category` is a log category's name.
using Logger = std::function<void(Status status, const char* category, const char* message)>;

}  // namespace fmu
