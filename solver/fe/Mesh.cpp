#include "fe/Mesh.h"

#include <algorithm>
#include <cmath>

namespace plate {

Mesh::Mesh(double length, double width, int nx, int ny) : length_(length), width_(width), nx_(nx), ny_(ny) {}

std::array<int, 4> Mesh::cellVertices(int c) const {
    const int i = c / ny_, j = c % ny_;
    return {vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1)};
}

std::array<int, 3> Mesh::triangleVertices(int t) const {
    const auto q = cellVertices(t / 2);
    if (t % 2 == 0) return {q[0], q[1], q[2]};
    return {q[0], q[2], q[3]};
}

int Mesh::cellContaining(const Eigen::Vector2d& x) const {
    const int i = std::clamp(static_cast<int>(std::floor(x.x() / hx())), 0, nx_ - 1);
    const int j = std::clamp(static_cast<int>(std::floor(x.y() / hy())), 0, ny_ - 1);
    return cell(i, j);
}

int Mesh::triangleContaining(const Eigen::Vector2d& x) const {
    const int c = cellContaining(x);
    const Eigen::Vector2d origin = point(cellVertices(c)[0]);
    // Below the diagonal (local y/hy <= x/hx) lies triangle 2c.
    const double s = (x.x() - origin.x()) / hx(), r = (x.y() - origin.y()) / hy();
    return r <= s ? 2 * c : 2 * c + 1;
}

}  // namespace plate
