#pragma once
// The two hot loops of a time step, written out (Eigen's generic sparse products cost
// ~1.5–2× the instructions on the per-step product K w, measured with callgrind).
//
// y = K x for symmetric K from its upper triangle in compressed row storage: each stored
// off-diagonal entry serves row i and, mirrored, row j, so the product reads half the matrix
// (on large meshes K no longer fits in cache and the product is bandwidth-bound).
#include <Eigen/Core>
#include <Eigen/Sparse>

namespace plate {

inline void multiplySymmetricUpper(const Eigen::SparseMatrix<double, Eigen::RowMajor>& upper, const Eigen::VectorXd& x,
                                   Eigen::VectorXd& y) {
    const int* outer = upper.outerIndexPtr();
    const int* inner = upper.innerIndexPtr();
    const double* value = upper.valuePtr();
    const double* xs = x.data();
    y.setZero(upper.rows());
    double* ys = y.data();
    for (Eigen::Index i = 0; i < upper.rows(); ++i) {
        int k = outer[i];
        const int end = outer[i + 1];
        const double xi = xs[i];
        double s = value[k] * xi;  // the diagonal entry comes first in each upper row
        for (++k; k < end; ++k) {
            const int j = inner[k];
            s += value[k] * xs[j];
            ys[j] += value[k] * xi;
        }
        ys[i] += s;
    }
}

// y_i = rows.col(i) · x: the vertex values y = (CΦ) α of ModalPlate, with CΦ stored
// transposed so each dot product reads contiguous memory. Compiled for x86-64-v3 (AVX2 + FMA)
// and for the baseline, chosen at load time: the FMU stays portable and uses the wide units
// where the host has them. ELF builds let GCC's target_clones choose (an ifunc); the win64
// build (PE has no ifuncs) chooses the same way by hand. Both bodies compute the same bits: the
// eight partial sums are independent lanes (vectorizing does not reorder a sum) and the build
// forbids contracting a product and a sum into an FMA (-ffp-contract=off), so the wide units
// change the speed, never the result, on any CPU.
__attribute__((always_inline)) inline void multiplyTransposedBody(const Eigen::MatrixXd& rows, const Eigen::VectorXd& x,
                                                                  Eigen::VectorXd& y) {
    const Eigen::Index n = rows.rows(), m = rows.cols();
    y.resize(m);
    const double* xs = x.data();
    for (Eigen::Index i = 0; i < m; ++i) {
        const double* r = rows.data() + i * n;
        double s[8] = {0, 0, 0, 0, 0, 0, 0, 0};
        Eigen::Index k = 0;
        for (; k + 8 <= n; k += 8)
            for (int l = 0; l < 8; ++l) s[l] += r[k + l] * xs[k + l];
        double total = ((s[0] + s[4]) + (s[1] + s[5])) + ((s[2] + s[6]) + (s[3] + s[7]));
        for (; k < n; ++k) total += r[k] * xs[k];
        y[i] = total;
    }
}

#if !defined(__x86_64__)
// Other architectures (aarch64-linux, the FMI 3.0 FMU): the baseline body.
inline void multiplyTransposed(const Eigen::MatrixXd& rows, const Eigen::VectorXd& x, Eigen::VectorXd& y) {
    multiplyTransposedBody(rows, x, y);
}
#elif defined(__ELF__)
__attribute__((target_clones("arch=x86-64-v3", "default"))) inline void multiplyTransposed(const Eigen::MatrixXd& rows,
                                                                                           const Eigen::VectorXd& x,
                                                                                           Eigen::VectorXd& y) {
    multiplyTransposedBody(rows, x, y);
}
#else
__attribute__((target("arch=x86-64-v3"))) inline void multiplyTransposedWide(const Eigen::MatrixXd& rows,
                                                                             const Eigen::VectorXd& x,
                                                                             Eigen::VectorXd& y) {
    multiplyTransposedBody(rows, x, y);
}
inline void multiplyTransposed(const Eigen::MatrixXd& rows, const Eigen::VectorXd& x, Eigen::VectorXd& y) {
    static const bool wide = __builtin_cpu_supports("x86-64-v3");
    if (wide)
        multiplyTransposedWide(rows, x, y);
    else
        multiplyTransposedBody(rows, x, y);
}
#endif

}  // namespace plate
