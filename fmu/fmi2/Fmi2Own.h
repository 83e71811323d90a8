#pragma once
// The FMI 2.0 header for this copy's own implementations (fmi2Functions.cpp): every fmi2X it
// defines is plateimpactOwn_fmi2X, not exported; fmi2Exports.cpp defines the exported fmi2X,
// which call these or the primary copy's (core/PrimaryCopy.h).
#define FMI2_FUNCTION_PREFIX plateimpactOwn_
#include "fmi2Functions.h"
