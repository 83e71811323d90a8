#include "binding/PlateArrays.h"

#include <string>

#include "binding/PlateVariables.h"

namespace plateimpact {

const std::vector<fmu::StructuralParameter>& plateStructuralParameters() {
    static const std::vector<fmu::StructuralParameter> table = {
        {kVrVerticesX, "vertices_x",
         "Mesh vertices along x, nx + 1: the second extent of vertex_displacement (setting it sets nx)", kVrNx, 1},
        {kVrVerticesY, "vertices_y",
         "Mesh vertices along y, ny + 1: the third extent of vertex_displacement (setting it sets ny)", kVrNy, 1},
        {kVrVertexOutput, "vertex_output",
         "Switch of the array output: 1 = vertex_displacement holds the mesh ([1][vertices_x][vertices_y]), 0 = it is "
         "empty (for a master that records every output); the first extent of vertex_displacement",
         fmu::kOwnValue, 1, 0, 1},
    };
    return table;
}

const std::vector<fmu::ArrayOutput>& plateArrayOutputs() {
    static const std::vector<fmu::ArrayOutput> table = {
        {kVrVertexDisplacement,
         "vertex_displacement",
         "Absolute displacement w at every mesh vertex, [vertex_output][vertices_x][vertices_y]: vertex (i, j) at "
         "(i length/nx, j width/ny); a vertex on an obstacle sits at its height; empty when vertex_output = 0",
         "m",
         {kVrVertexOutput, kVrVerticesX, kVrVerticesY}},
        {kVrVertexStress,
         "vertex_stress",
         "Von Mises surface bending stress at every mesh vertex (fvs: its curvatures jump between elements, the "
         "value is that of one element holding it, the one above and right of it where there is one), as "
         "vertex_displacement: "
         "[vertex_output][vertices_x][vertices_y]; 0 unless stress_outputs = true",
         "Pa",
         {kVrVertexOutput, kVrVerticesX, kVrVerticesY}},
    };
    return table;
}

void getPlateArray(const plate::PlateSimulation& simulation, const fmu::ArrayOutput& a, double* out, std::size_t n) {
    if (a.vr != kVrVertexDisplacement && a.vr != kVrVertexStress)
        throw fmu::ModelError(std::string(a.name) + " is not an array of the plate");
    const std::vector<double> u =
        a.vr == kVrVertexStress ? simulation.vertexStress() : simulation.vertexDisplacements();
    if (u.size() != n)
        throw fmu::ModelError(std::string(a.name) + ": nValues gives " + std::to_string(n) + " values, the mesh has " +
                              std::to_string(u.size()) + " vertices");
    for (std::size_t k = 0; k < n; ++k) out[k] = u[k];
}

}  // namespace plateimpact
