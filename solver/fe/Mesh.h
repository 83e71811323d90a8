#pragma once
// Structured mesh of the plate [0, length] x [0, width] with nx x ny rectangular cells.
// Vertex (i, j) sits at (i*length/nx, j*width/ny); the clamped edge is x = 0 (i = 0).
// Each cell is split into two triangles by the diagonal (x_i, y_j) -> (x_{i+1}, y_{j+1})
// (docs/theory.md: 14 x 5 cells -> the paper's 140 Argyris triangles), or kept as one quadrilateral.
#include <Eigen/Core>
#include <array>

namespace plate {

class Mesh {
public:
    Mesh(double length, double width, int nx, int ny);

    double length() const { return length_; }
    double width() const { return width_; }
    int nx() const { return nx_; }
    int ny() const { return ny_; }
    double hx() const { return length_ / nx_; }
    double hy() const { return width_ / ny_; }

    int vertexCount() const { return (nx_ + 1) * (ny_ + 1); }
    int vertex(int i, int j) const { return i * (ny_ + 1) + j; }
    int vertexColumn(int v) const { return v / (ny_ + 1); }
    int vertexRow(int v) const { return v % (ny_ + 1); }
    Eigen::Vector2d point(int v) const { return {vertexColumn(v) * hx(), vertexRow(v) * hy()}; }
    bool isClamped(int v) const { return vertexColumn(v) == 0; }

    int cellCount() const { return nx_ * ny_; }
    int cell(int i, int j) const { return i * ny_ + j; }
    // Corners of a cell counter-clockwise from (x_i, y_j).
    std::array<int, 4> cellVertices(int c) const;

    int triangleCount() const { return 2 * cellCount(); }
    // Triangle 2c is (v00, v10, v11), 2c+1 is (v00, v11, v01): both counter-clockwise.
    std::array<int, 3> triangleVertices(int t) const;

    // Cell containing a point of the plate (points on cell borders go to the lower-index cell
    // unless they lie on the outer boundary; any cell sharing the point gives the same value
    // for a C1 field, which is all the probes need).
    int cellContaining(const Eigen::Vector2d& x) const;
    int triangleContaining(const Eigen::Vector2d& x) const;

private:
    double length_, width_;
    int nx_, ny_;
};

}  // namespace plate
