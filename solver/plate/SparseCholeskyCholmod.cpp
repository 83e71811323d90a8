#include "plate/SparseCholesky.h"

#include <cholmod.h>

#include <algorithm>
#include <cstring>
#include <new>
#include <stdexcept>
#include <string>

namespace plate {

struct SparseCholesky::Workspace {
    cholmod_common common;
    cholmod_factor* factor = nullptr;
    cholmod_dense* x = nullptr;  // solution and solver workspaces kept between solves
    cholmod_dense* y = nullptr;
    cholmod_dense* e = nullptr;
    // One instance's CHOLMOD runs single-threaded: instances may run in parallel threads.
    Workspace() {
        cholmod_start(&common);
        common.nmethods = 0;  // try AMD, then METIS/NESDIS when AMD's fill is poor
        // Simplicial LLᵀ: on these small 2D meshes the supernodes are tiny (~13 columns) and
        // the per-supernode BLAS calls cost more than they save (default mesh: 27 µs simplicial
        // against 50 µs supernodal per solve, measured).
        common.supernodal = CHOLMOD_SIMPLICIAL;
        common.final_ll = 1;
        common.print = 0;
        common.error_handler = nullptr;
    }
    ~Workspace() {
        cholmod_free_dense(&x, &common);
        cholmod_free_dense(&y, &common);
        cholmod_free_dense(&e, &common);
        cholmod_free_factor(&factor, &common);
        cholmod_finish(&common);
    }
};

SparseCholesky::SparseCholesky(const Eigen::SparseMatrix<double>& spd)
    : n_(spd.rows()), ws_(std::make_unique<Workspace>()) {
    factor(spd, nullptr);
}

SparseCholesky::SparseCholesky(const Eigen::SparseMatrix<double>& symmetric, const std::vector<int>& ordering)
    : n_(symmetric.rows()), ws_(std::make_unique<Workspace>()) {
    if (static_cast<Eigen::Index>(ordering.size()) != n_)
        throw std::invalid_argument("SparseCholesky: the ordering has " + std::to_string(ordering.size()) +
                                    " entries for a matrix of " + std::to_string(n_) + " rows");
    ws_->common.nmethods = 1;
    ws_->common.method[0].ordering = CHOLMOD_GIVEN;
    ws_->common.final_ll = 0;  // L D Lᵀ: negative pivots allowed, zero ones refused
    factor(symmetric, &ordering);
}

void SparseCholesky::factor(const Eigen::SparseMatrix<double>& symmetric, const std::vector<int>* ordering) {
    Eigen::SparseMatrix<double> lower = symmetric.triangularView<Eigen::Lower>();
    lower.makeCompressed();
    cholmod_sparse view{};
    view.nrow = view.ncol = static_cast<size_t>(n_);
    view.nzmax = static_cast<size_t>(lower.nonZeros());
    view.p = lower.outerIndexPtr();
    view.i = lower.innerIndexPtr();
    view.x = lower.valuePtr();
    view.stype = -1;  // lower triangle of a symmetric matrix
    view.itype = CHOLMOD_INT;
    view.xtype = CHOLMOD_REAL;
    view.dtype = CHOLMOD_DOUBLE;
    view.sorted = 1;
    view.packed = 1;
    auto& c = ws_->common;
    ws_->factor = ordering ? cholmod_analyze_p(&view, const_cast<int*>(ordering->data()), nullptr, 0, &c)
                           : cholmod_analyze(&view, &c);
    if (c.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
    if (!ws_->factor) throw std::runtime_error("CHOLMOD analysis failed");
    cholmod_factorize(&view, ws_->factor, &c);
    if (c.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();  // not "not positive definite"
    if (c.status != CHOLMOD_OK || ws_->factor->minor < ws_->factor->n)
        throw std::runtime_error(ordering ? "matrix has a zero pivot in the given order (CHOLMOD LDLᵀ)"
                                          : "matrix is not positive definite (CHOLMOD)");
}

SparseCholesky::~SparseCholesky() = default;

long long SparseCholesky::factorNonZeros() const {
    const auto* f = ws_->factor;
    if (f->is_super) {
        // Supernodal storage holds dense column blocks; count what it stores.
        return static_cast<long long>(f->xsize);
    }
    long long nnz = 0;
    const int* colCount = static_cast<const int*>(f->nz);
    for (size_t j = 0; j < f->n; ++j) nnz += colCount[j];
    return nnz;
}

std::vector<int> SparseCholesky::ordering() const {
    const auto* perm = static_cast<const int*>(ws_->factor->Perm);
    return std::vector<int>(perm, perm + n_);
}

std::vector<int> SparseCholesky::positions() const {
    const auto* perm = static_cast<const int*>(ws_->factor->Perm);
    std::vector<int> at(static_cast<std::size_t>(n_));
    for (Eigen::Index k = 0; k < n_; ++k) at[std::size_t(perm[k])] = static_cast<int>(k);
    return at;
}

SymbolicFactor SparseCholesky::analyze(Eigen::Index n, const std::vector<int>& columnStart,
                                       const std::vector<int>& rowIndex) {
    Workspace ws;  // the same options as a factorization: the same ordering, the same L
    cholmod_sparse view{};
    view.nrow = view.ncol = static_cast<size_t>(n);
    view.nzmax = rowIndex.size();
    view.p = const_cast<int*>(columnStart.data());
    view.i = const_cast<int*>(rowIndex.data());
    view.stype = -1;
    view.itype = CHOLMOD_INT;
    view.xtype = CHOLMOD_PATTERN;
    view.dtype = CHOLMOD_DOUBLE;
    view.sorted = 1;
    view.packed = 1;
    ws.factor = cholmod_analyze(&view, &ws.common);
    if (ws.common.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
    if (!ws.factor) throw std::runtime_error("CHOLMOD analysis failed");
    // cholmod_analyze leaves nnz(L) and the flop count of the selected ordering in Common.
    return {static_cast<long long>(ws.common.lnz), ws.common.fl};
}

void SparseCholesky::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
    cholmod_dense rhs{};
    rhs.nrow = static_cast<size_t>(n_);
    rhs.ncol = 1;
    rhs.nzmax = rhs.nrow;
    rhs.d = rhs.nrow;
    rhs.x = const_cast<double*>(b.data());
    rhs.xtype = CHOLMOD_REAL;
    rhs.dtype = CHOLMOD_DOUBLE;
    // cholmod_solve2's simplicial path transposes one right-hand side into Y and leaves Y shaped
    // 1 × n (ptrans); the next call would find it "the wrong size" (it wants 4 × n, leading
    // dimension 4) and allocate it again. Its storage holds 4 × n: give it back that shape.
    if (ws_->y && ws_->y->nzmax >= 4 * rhs.nrow && ws_->y->ncol == rhs.nrow && ws_->y->nrow == 1) {
        ws_->y->nrow = 4;
        ws_->y->d = 4;
    }
    if (!cholmod_solve2(CHOLMOD_A, ws_->factor, &rhs, nullptr, &ws_->x, nullptr, &ws_->y, &ws_->e, &ws_->common))
        throw std::runtime_error("CHOLMOD solve failed");
    x.resize(n_);
    std::memcpy(x.data(), ws_->x->x, sizeof(double) * static_cast<size_t>(n_));
}

namespace {

// The block solve's sweeps (SparseCholesky::solve below) for GCC on x86-64 Linux twice, for the
// baseline and for AVX2, the loader picking by CPU (target_clones): the row updates are the same
// element-wise products and differences at either width (no FMA, no reordering), so the same bits
// on every CPU, twice as many per instruction where AVX2 is there (56x20's massless solves,
// docs/performance.md). Elsewhere (MinGW, aarch64, clang) the baseline alone.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define PLATE_WIDE_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define PLATE_WIDE_CLONES
#endif

inline void subtractScaled(double* __restrict y, const double* __restrict x, double a, Eigen::Index k) {
    for (Eigen::Index c = 0; c < k; ++c) y[c] -= a * x[c];
}
inline void divide(double* y, double d, Eigen::Index k) {
    for (Eigen::Index c = 0; c < k; ++c) y[c] /= d;
}

// w (n × k, row-major, in the factor's order) ← (L Lᵀ)⁻¹ w, or (L Δ Lᵀ)⁻¹ w with Δ in L's diagonal
// slots; the diagonal first in each column of L. A column whose row of the block is still zero in
// the forward sweep changes nothing: skipped, so that unit right-hand sides cost only their paths
// up the elimination tree there. The backward sweep stops at row `from`: a row's solution needs
// only those eliminated after it, so rows from `from` on are exact and the ones before unsolved.
PLATE_WIDE_CLONES void sweeps(const cholmod_factor& f, Eigen::Index n, Eigen::Index k, double* w, Eigen::Index from) {
    const auto* start = static_cast<const int*>(f.p);
    const auto* count = static_cast<const int*>(f.nz);
    const auto* row = static_cast<const int*>(f.i);
    const auto* value = static_cast<const double*>(f.x);
    const bool ll = f.is_ll != 0;
    for (Eigen::Index j = 0; j < n; ++j) {  // L z = P b
        double* wj = w + j * k;
        if (std::all_of(wj, wj + k, [](double v) { return v == 0.0; })) continue;
        if (ll) divide(wj, value[start[j]], k);
        for (int t = start[j] + 1; t < start[j] + count[j]; ++t)
            subtractScaled(w + Eigen::Index(row[t]) * k, wj, value[t], k);
    }
    if (!ll)
        for (Eigen::Index j = from; j < n; ++j) divide(w + j * k, value[start[j]], k);  // z ← Δ⁻¹ z
    for (Eigen::Index j = n - 1; j >= from; --j) {  // Lᵀ y = z
        double* wj = w + j * k;
        for (int t = start[j] + 1; t < start[j] + count[j]; ++t)
            subtractScaled(wj, w + Eigen::Index(row[t]) * k, value[t], k);
        if (ll) divide(wj, value[start[j]], k);
    }
}

}  // namespace

// The block's rows are dofs with their right-hand sides side by side (row-major): each column of
// the simplicial L is read once for the whole block and applied as a vectorized row update, where
// cholmod_solve2 reads L once per four right-hand sides (CondensedSparse.cpp's massless solves).
void SparseCholesky::solveInOrder(RowBlock& w, Eigen::Index from) const {
    sweeps(*ws_->factor, n_, w.cols(), w.data(), from);
}

void SparseCholesky::solve(const Eigen::MatrixXd& b, Eigen::MatrixXd& x) const {
    const auto* perm = static_cast<const int*>(ws_->factor->Perm);
    RowBlock w(n_, b.cols());
    for (Eigen::Index r = 0; r < n_; ++r) w.row(r) = b.row(perm[r]);
    sweeps(*ws_->factor, n_, b.cols(), w.data(), 0);
    x.resize(n_, b.cols());
    for (Eigen::Index r = 0; r < n_; ++r) x.row(perm[r]) = w.row(r);
}

}  // namespace plate
