#pragma once
// Linear functionals of a plate's coordinates, y = L x, as whichever coordinates make them cheap:
// sparse rows over the free dofs (the sparse engine), dense rows over modal coordinates (the
// modal engine, the condensed plate). The probes and the stress samples (docs/theory.md §23) are
// read through them; a range of rows is evaluated without allocating (the root's samples every step).
#include <Eigen/Core>
#include <Eigen/Sparse>

namespace plate {

using SparseRows = Eigen::SparseMatrix<double, Eigen::RowMajor>;
using DenseRows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct LinearRows {
    SparseRows sparse;  // used when `dense` has no rows
    DenseRows dense;

    Eigen::Index rows() const { return dense.rows() > 0 ? dense.rows() : sparse.rows(); }
    // out = rows [first, first + out.size()) of L times x.
    void apply(Eigen::Index first, const Eigen::VectorXd& x, Eigen::Ref<Eigen::VectorXd> out) const {
        if (dense.rows() > 0) {
            out.noalias() = dense.middleRows(first, out.size()) * x;
            return;
        }
        for (Eigen::Index i = 0; i < out.size(); ++i) {
            double sum = 0.0;
            for (SparseRows::InnerIterator it(sparse, first + i); it; ++it) sum += it.value() * x[it.index()];
            out[i] = sum;
        }
    }
};

}  // namespace plate
