#pragma once
// FMI 3.0 only (FMI 2.0 has no arrays): the plate's array output — the absolute displacement
// at every mesh vertex — and the UInt64 structural parameters that size it: vertex_output (its
// switch, 1 or 0: a value of its own) and views of the table's nx and ny (vertices_x = nx + 1,
// vertices_y = ny + 1).
#include <cstddef>
#include <vector>

#include "core/Model.h"
#include "PlateSimulation.h"

namespace plateimpact {

// Value references of the FMI 3.0 interface only (time is 1000, fmu/Fmi3Interface.h).
enum PlateArrayVr : fmu::ValueReference {
    kVrVerticesX = 1001,
    kVrVerticesY = 1002,
    kVrVertexDisplacement = 1003,
    kVrVertexOutput = 1004,
    kVrVertexStress = 1005,
};

const std::vector<fmu::StructuralParameter>& plateStructuralParameters();
const std::vector<fmu::ArrayOutput>& plateArrayOutputs();
// The n values of array output `a` (vertex (i, j) at index i (ny + 1) + j: x slowest); throws
// fmu::ModelError if n is not the mesh's vertex count.
void getPlateArray(const plate::PlateSimulation& simulation, const fmu::ArrayOutput& a, double* out, std::size_t n);

}  // namespace plateimpact
