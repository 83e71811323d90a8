#include "plate/Spectrum.h"

#include <Eigen/Cholesky>
#include <Spectra/SymGEigsShiftSolver.h>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "plate/DenseEigenproblem.h"
#include "plate/SparseCholesky.h"

namespace plate {

// The Weyl sequence frac(a (i + 1) + b (j + 1)) − 1/2 has no structure that a mode could be
// orthogonal to, in exact arithmetic but for one rounding per operation — the same bits on every
// CPU (the C library's sine, used before, is not).
double startEntry(Eigen::Index i, Eigen::Index j) {
    const double x = 0.6180339887498949 * double(i + 1) + 0.4142135623730951 * double(j + 1);
    return (x - std::floor(x)) - 0.5;
}

namespace {

// Dense generalized eigensolver: fine up to a few thousand dofs (O(n³) once at start).
constexpr Eigen::Index kDenseLimit = 3000;

void denseModes(const ClampedPlate& plate, Eigen::Index modes, Eigen::MatrixXd& phi, Eigen::VectorXd& omega2) {
    const Eigen::MatrixXd k = Eigen::MatrixXd(plate.stiffness);
    const Eigen::MatrixXd m = Eigen::MatrixXd(plate.mass);
    if (Eigen::LLT<Eigen::MatrixXd>(m).info() != Eigen::Success) {
        // A singular mass (docs/theory.md §11): M φ = (1/ω²) K φ with K SPD; the massless
        // directions are the zero eigenvalues (ω = ∞) and are left out.
        Eigen::VectorXd mu;
        Eigen::MatrixXd vectors;  // Φᵀ K Φ = I, ascending
        if (!solveDenseEigenproblem(m, k, mu, vectors)) throw std::runtime_error("modal analysis failed");
        const double cut = 1e-12 * mu.maxCoeff();
        Eigen::Index massive = 0;
        while (massive < mu.size() && mu[mu.size() - 1 - massive] > cut) ++massive;
        const Eigen::Index count = std::min(modes, massive);
        phi.resize(m.rows(), count);
        omega2.resize(count);
        for (Eigen::Index j = 0; j < count; ++j) {
            const Eigen::Index c = mu.size() - 1 - j;  // largest 1/ω² first
            omega2[j] = 1.0 / mu[c];
            phi.col(j) = vectors.col(c) * std::sqrt(omega2[j]);  // Φᵀ M Φ = I
        }
        return;
    }
    // Eigen normalizes the eigenvectors to Φᵀ M Φ = I and sorts the eigenvalues ascending.
    Eigen::VectorXd values;
    if (!solveDenseEigenproblem(k, m, values, phi)) throw std::runtime_error("modal analysis failed");
    phi.conservativeResize(Eigen::NoChange, modes);
    omega2 = values.head(modes);
}

// K⁻¹ as Spectra's shift-invert operator at σ = 0: one solve with the factor of K per product.
class StiffnessInverse {
public:
    using Scalar = double;
    explicit StiffnessInverse(const Eigen::SparseMatrix<double>& k) : factor_(k), b_(k.rows()), x_(k.rows()) {}
    Eigen::Index rows() const { return factor_.size(); }
    Eigen::Index cols() const { return factor_.size(); }
    void set_shift(double sigma) {
        if (sigma != 0.0) throw std::logic_error("StiffnessInverse: only the shift 0 is factored");
    }
    void perform_op(const double* in, double* out) const {
        b_ = Eigen::Map<const Eigen::VectorXd>(in, rows());
        factor_.solve(b_, x_);
        Eigen::Map<Eigen::VectorXd>(out, rows()) = x_;
    }

private:
    SparseCholesky factor_;
    mutable Eigen::VectorXd b_, x_;  // Spectra calls perform_op on a const operator
};

// M as Spectra's B operator (its inner products): the plain product over both stored triangles,
// 3x faster than Spectra's SparseSymMatProd reading one (its products were 27 % of 112x40's modes).
class MassProduct {
public:
    using Scalar = double;
    explicit MassProduct(const Eigen::SparseMatrix<double>& m) : m_(m) {}
    Eigen::Index rows() const { return m_.rows(); }
    Eigen::Index cols() const { return m_.cols(); }
    void perform_op(const double* in, double* out) const {
        Eigen::Map<Eigen::VectorXd>(out, m_.rows()).noalias() = m_ * Eigen::Map<const Eigen::VectorXd>(in, m_.cols());
    }

private:
    const Eigen::SparseMatrix<double>& m_;
};

// The lowest modes of K φ = ω² M φ by Spectra's shift-invert Lanczos at σ = 0 (README: why
// Spectra): the largest 1/ω² of K⁻¹ M in M's inner product, from the deterministic start vector
// (the same bits on every CPU), M-orthonormal. The subspace iteration it replaces took 142 s for 60
// modes of 56x20 (single-vector solves over 2m vectors, ~100 iterations on close pairs).
void lanczosModes(const ClampedPlate& plate, Eigen::Index modes, Eigen::MatrixXd& phi, Eigen::VectorXd& omega2) {
    const Eigen::Index n = plate.mass.rows();
    StiffnessInverse op(plate.stiffness);
    MassProduct mass(plate.mass);
    const Eigen::Index vectors = std::min(n, modes + std::max<Eigen::Index>(80, modes));  // as CondensedSparse.cpp
    Spectra::SymGEigsShiftSolver<StiffnessInverse, MassProduct, Spectra::GEigsMode::ShiftInvert> eigs(op, mass, modes,
                                                                                                      vectors, 0.0);
    Eigen::VectorXd start(n);
    for (Eigen::Index i = 0; i < n; ++i) start[i] = startEntry(i, 0);
    eigs.init(start.data());
    eigs.compute(Spectra::SortRule::LargestMagn, 1000, 1e-12, Spectra::SortRule::SmallestAlge);
    if (eigs.info() != Spectra::CompInfo::Successful)
        throw std::runtime_error("modal analysis failed (Spectra's Lanczos did not converge)");
    omega2 = eigs.eigenvalues();
    phi = eigs.eigenvectors();
    for (Eigen::Index j = 0; j < modes; ++j) phi.col(j) /= std::sqrt(phi.col(j).dot(plate.mass * phi.col(j)));
}

}  // namespace

// A few modes of a large space: Lanczos (about 2m solves in all); the dense O(n³) solution where it
// is cheap or where most modes are wanted (the limits were set against the subspace iteration before
// it, so that the scenes the dense solution served keep their bits: m = 40, Argyris 28x10 (2727 dofs)
// 11 s against 64 s dense; FVS 40x14 (1800) 1.8 s against 5–13 s; Argyris 14x5 (734) dense 0.5 s).
bool denseSolutionServes(Eigen::Index n, int modes) {
    const Eigen::Index m = (modes <= 0 || modes >= n) ? n : modes;
    return !(m < n && 4 * m <= n && n > 1200) && n <= kDenseLimit;
}

// The dense solution's columns are each computed whole, in ascending order (largest 1/ω² first with a
// singular mass), whatever the count asked: its leading m are denseModes(plate, m)'s, bit for bit.
void leadingModes(const Eigen::MatrixXd& allPhi, const Eigen::VectorXd& allOmega2, int modes, Eigen::MatrixXd& phi,
                  Eigen::VectorXd& omega2) {
    const Eigen::Index n = allPhi.cols();
    const Eigen::Index m = (modes <= 0 || modes >= n) ? n : modes;
    phi = allPhi.leftCols(m);
    omega2 = allOmega2.head(m);
}

void lowestModes(const ClampedPlate& plate, int modes, Eigen::MatrixXd& phi, Eigen::VectorXd& omega2) {
    const Eigen::Index n = plate.mass.rows();
    const Eigen::Index m = (modes <= 0 || modes >= n) ? n : modes;
    if (denseSolutionServes(n, modes))
        denseModes(plate, m, phi, omega2);
    else if (m < n)
        lanczosModes(plate, m, phi, omega2);
    else
        throw std::runtime_error("a complete modal basis needs a space of at most 3000 dofs");
}

// Largest eigenvalue of M⁻¹K by power iteration with the Rayleigh quotient. The top of the FE
// spectrum is clustered, so the quotient is within a fraction of a percent after a few hundred
// iterations even where the eigenvector converges slowly.
double largestEigenvalue(const ClampedPlate& plate) {
    const SparseCholesky massFactor(plate.mass);
    Eigen::VectorXd x = Eigen::VectorXd::Ones(plate.mass.rows());
    for (Eigen::Index i = 0; i < x.size(); ++i) x[i] += 0.74 * startEntry(i, 0);
    Eigen::VectorXd kx, y, mx;
    double lambda = 0.0;
    for (int it = 0; it < 2000; ++it) {
        kx = plate.stiffness * x;
        massFactor.solve(kx, y);
        mx = plate.mass * y;
        const double next = y.dot(plate.stiffness * y) / y.dot(mx);
        x = y / std::sqrt(y.dot(mx));
        if (it > 50 && std::abs(next - lambda) <= 1e-7 * next) {
            lambda = next;
            break;
        }
        lambda = next;
    }
    return lambda;
}

}  // namespace plate
