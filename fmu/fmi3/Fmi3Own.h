#pragma once
// The FMI 3.0 header for this copy's own implementations (fmi3Functions.cpp, fmi3Unsupported.cpp):
// every fmi3X they define is plateimpactOwn_fmi3X, not exported; fmi3Exports.cpp defines the
// exported fmi3X, which call these or the primary copy's (core/PrimaryCopy.h).
#define FMI3_FUNCTION_PREFIX plateimpactOwn_
#include "fmi3Functions.h"
