#pragma once
// Quadrature rules exact for polynomials up to a requested degree.
// The triangle rule is the collapsed (Duffy) tensor Gauss rule: a polynomial of total degree d
// on the triangle becomes, after the collapse, a polynomial of degree <= d+1 per direction, so
// n = ceil((d+2)/2) Gauss points per direction integrate it exactly.
#include <Eigen/Core>
#include <vector>

namespace plate {

struct QuadratureNode {
    Eigen::Vector2d point;  // physical coordinates
    double weight;  // includes the Jacobian
};

// Gauss–Legendre nodes and weights on [0, 1].
void gaussLegendre01(int n, std::vector<double>& nodes, std::vector<double>& weights);

// Rule on the triangle (a, b, c), exact for total degree <= degree.
std::vector<QuadratureNode> triangleRule(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                                         int degree);

}  // namespace plate
