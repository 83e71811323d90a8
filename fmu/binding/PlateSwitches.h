#pragma once
// The plate's Integer switches and their named items (PlateSwitches.cpp): element, base_input_mode
// and load_input_mode, mass, time_scheme, base_drive.
#include "core/Model.h"

namespace plateimpact {

const fmu::EnumerationType& elementType();
const fmu::EnumerationType& inputMode();
const fmu::EnumerationType& massModel();
const fmu::EnumerationType& timeScheme();
const fmu::EnumerationType& baseDrive();

}  // namespace plateimpact
