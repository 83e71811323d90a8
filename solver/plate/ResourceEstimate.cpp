#include "plate/ResourceEstimate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "plate/CondensedPlate.h"
#include "plate/SparseCholesky.h"
#include "plate/Stops.h"

namespace plate {

namespace {

constexpr double kMB = 1024.0 * 1024.0;
constexpr double kEntry = 12.0;  // a stored sparse entry: double value + int index, bytes
constexpr double kTriplet = 16.0;  // Eigen::Triplet<double>: two ints and a double, bytes
constexpr double kDouble = 8.0;
// Dense generalized eigensolver (Spectrum.cpp denseModes): K and M dense, the LLT of M, the
// reduced matrix, the eigenvectors and their back-transformed copy, and Φ, n² doubles each,
// some of them short-lived (fitted: 5.5).
constexpr double kDenseEigenMatrices = 5.5;
constexpr double kBaseMB = 2.0;  // the instance's own small structures, probes, QP workspace
// The space's per-element local bases (ArgyrisTriangle.h: a 21 x 21 matrix; FvsQuadrilateral.h:
// four 10 x 16 pieces), with the element's dof list, bytes.
constexpr double kSpacePerElementArgyris = 21 * 21 * 8 + 300;
constexpr double kSpacePerElementFvs = 4 * 10 * 16 * 8 + 250;
// A simplicial factor per nonzero of L: value and row index, with the room CHOLMOD's numeric
// factorization leaves each column to grow (Common.grow1 = 1.2) and its workspace; fitted.
constexpr double kFactorPerNonZero = 16.0;

// The time model, fitted on this project's 2-core machine (docs/performance.md "Resources"):
// seconds per assembled entry (quadrature and element matrices included) per element; per
// entry of the pattern walk and of the clamp's copies; per flop of the simplicial factor; per
// n³ of the dense eigen solution; per entry touched in a time step.
constexpr double kAssemblyPerEntryArgyris = 4.0e-8;
constexpr double kAssemblyPerEntryFvs = 6.0e-8;
constexpr double kPerPatternEntry = 1.5e-8;
constexpr double kPerAnalysisEntry = 8.0e-8;  // AMD ordering, per nonzero of A
constexpr double kPerFactorFlop = 1.0e-9;
constexpr double kPerDenseEigenCube = 2.0e-9;
constexpr double kPerSparseStepEntry = 0.55e-9;  // per nonzero of L and of K/M touched in a step
constexpr double kPerModalStepEntry = 1.0e-9;  // per entry of CΦ and per dof of a modal step
// The sparse condensation's saddle-point factor [[K, R], [Rᵀ, 0]] (CondensedSparse.cpp) against K's:
// nnz(L) 1.70× (56x20: 1.92 M against 1.13 M) and 1.77× (112x40: 11.9 M against 6.7 M), its
// factorization 2.5× the flops (112x40: 5.1 against 2.05 GFlop; CHOLMOD's symbolic analyses).
constexpr double kSaddleFill = 1.75;
constexpr double kSaddleFlops = 2.5;
// Per nominal flop (4 nnz(L) per right-hand side) of the blocked solves (64 right-hand sides, AVX2
// where the CPU has it; the forward sweep skips what unit right-hand sides do not reach), and the
// contact rows' dense work once condensed (D's Cholesky, the schemes' r × r operators) per r³:
// perf of plate_bench init_only=1 (flow, 100 modes): 56x20, the saddle's solves ~0.9 s for 9 GFlop;
// 112x40, ~15 s for 218 GFlop and ~2.9 s of dense kernels (r = 4593).
constexpr double kPerSolveFlop = 0.08e-9;
// The rows' solves without stress_outputs (D's triangle alone, CondensedSparse.cpp) against full
// ones: 112x40, the forward sweeps 16 % of a full solve's work, the backward ones cut at each
// block's first row 60 % of theirs (0.16 + 0.84 · 0.6).
constexpr double kTriangleWork = 0.66;
// Per flop of a Lanczos product's solve, one right-hand side (Spectra, CondensedSparse.cpp): 56x20,
// 201 products of 4 nnz(L) = 4.5 MFlop in 0.37 s; 112x40, 26.8 MFlop each in 3.0 s.
constexpr double kPerLanczosFlop = 0.5e-9;
constexpr double kPerRowCube = 0.3e-10;
constexpr int kPowerIterations = 300;  // typical power iterations for κ_h (up to 2000)

// dof → elements containing it, in compressed rows.
struct DofElements {
    std::vector<int> start, element;
};

DofElements dofElements(const FiniteElementSpace& space) {
    DofElements a;
    a.start.assign(static_cast<std::size_t>(space.dofCount()) + 1, 0);
    for (int e = 0; e < space.elementCount(); ++e)
        for (auto d : space.elementDofs(e)) ++a.start[static_cast<std::size_t>(d) + 1];
    for (std::size_t i = 1; i < a.start.size(); ++i) a.start[i] += a.start[i - 1];
    a.element.resize(static_cast<std::size_t>(a.start.back()));
    std::vector<int> next(a.start.begin(), a.start.end() - 1);
    for (int e = 0; e < space.elementCount(); ++e)
        for (auto d : space.elementDofs(e)) a.element[static_cast<std::size_t>(next[d]++)] = e;
    return a;
}

// Free index of every dof (−1: clamped), numbered in increasing dof order as clamp() does.
std::vector<int> freeIndexOf(const FiniteElementSpace& space) {
    std::vector<int> freeIndex(static_cast<std::size_t>(space.dofCount()), 0);
    for (auto d : space.clampedDofs()) freeIndex[static_cast<std::size_t>(d)] = -1;
    int next = 0;
    for (auto& f : freeIndex)
        if (f >= 0) f = next++;
    return freeIndex;
}

double factorBytes(const ProblemSize& s) {
    // Simplicial L (values and row indices) and CHOLMOD's per-column arrays.
    return kFactorPerNonZero * double(s.factorNonZeros) + 6.0 * 4.0 * double(s.dofs);
}

}  // namespace

ProblemSize predictFromMesh(const PlateParameters& p) {
    ProblemSize s;
    s.predicted = true;
    const double nx = p.mesh.nx, ny = p.mesh.ny, vertices = (nx + 1) * (ny + 1);
    s.contactVertices = static_cast<long long>(nx * (ny + 1));
    double nnzPerEntry, factorPerDof, factorExponent, reference;
    if (p.mesh.element == ElementType::Fvs) {
        // One 12-dof quadrilateral per cell; w, w_x, w_y at each vertex.
        s.elements = static_cast<long long>(nx * ny);
        s.elementEntries = s.elements * 144;
        s.fullDofs = static_cast<long long>(3 * vertices);
        s.dofs = static_cast<long long>(3 * nx * (ny + 1));
        nnzPerEntry = 0.56, factorPerDof = 93.0, factorExponent = 0.2, reference = 54432.0;
    } else {
        // Two 21-dof triangles per cell; six dofs per vertex, one per edge (3 nx ny + nx + ny edges).
        s.elements = static_cast<long long>(2 * nx * ny);
        s.elementEntries = s.elements * 441;
        s.fullDofs = static_cast<long long>(6 * vertices + 3 * nx * ny + nx + ny);
        s.dofs = s.fullDofs - static_cast<long long>(4 * (ny + 1));  // w_xx stays free on the clamp
        nnzPerEntry = 0.47, factorPerDof = 225.0, factorExponent = 0.25, reference = 162929.0;
    }
    const double n = double(s.dofs);
    s.nonZeros = static_cast<long long>(nnzPerEntry * double(s.elementEntries));
    s.fullNonZeros = s.nonZeros;
    s.factorNonZeros = static_cast<long long>(factorPerDof * n * std::pow(n / reference, factorExponent));
    const double perColumn = double(s.factorNonZeros) / n;
    s.factorFlops = n * perColumn * perColumn * 2.0;  // columns grow towards the last separators
    return s;
}

void requireMeshWithinBudget(const PlateParameters& p) {
    if (p.memoryLimit <= 0.0) return;
    PlateParameters margin = p;
    margin.memoryLimit = kPredictionMargin * p.memoryLimit;
    const ResourceEstimate predicted = estimateResources(p, predictFromMesh(p));
    try {
        requireWithinBudget(margin, predicted);
    } catch (const ResourceError&) {
        requireWithinBudget(p, predicted);  // the message names the user's limit
    }
}

ProblemSize countEntries(const FiniteElementSpace& space, const StopsAt& stopsAt) {
    ProblemSize s;
    s.fullDofs = space.dofCount();
    const std::vector<int> freeIndex = freeIndexOf(space);
    s.dofs = std::count_if(freeIndex.begin(), freeIndex.end(), [](int f) { return f >= 0; });
    for (int v = 0; v < space.mesh().vertexCount(); ++v)
        s.contactVertices += freeIndex[static_cast<std::size_t>(space.vertexValueDof(v))] >= 0 &&
                             (!stopsAt || stopsAt(space.mesh().point(v)) != 0);  // under a stop (§25)
    s.elements = space.elementCount();
    for (int e = 0; e < space.elementCount(); ++e) {
        const auto k = static_cast<long long>(space.elementDofs(e).size());
        s.elementEntries += k * k;
    }
    return s;
}

void analyzePattern(const FiniteElementSpace& space, ProblemSize& size) {
    const std::vector<int> freeIndex = freeIndexOf(space);
    const DofElements adjacent = dofElements(space);
    std::vector<int> columnStart(1, 0), rows;
    std::vector<Eigen::Index> mark(freeIndex.size(), -1);
    long long full = 0;
    for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(freeIndex.size()); ++i) {
        const int column = freeIndex[static_cast<std::size_t>(i)];
        const std::size_t first = rows.size();
        for (int k = adjacent.start[i]; k < adjacent.start[i + 1]; ++k)
            for (auto d : space.elementDofs(adjacent.element[static_cast<std::size_t>(k)])) {
                if (mark[static_cast<std::size_t>(d)] == i) continue;
                mark[static_cast<std::size_t>(d)] = i;
                ++full;
                const int row = freeIndex[static_cast<std::size_t>(d)];
                if (column >= 0 && row >= column) rows.push_back(row);  // lower triangle
            }
        if (column < 0) continue;
        std::sort(rows.begin() + static_cast<std::ptrdiff_t>(first), rows.end());
        columnStart.push_back(static_cast<int>(rows.size()));
    }
    size.fullNonZeros = full;
    size.nonZeros = 2 * static_cast<long long>(rows.size()) - size.dofs;
    const SymbolicFactor factor = SparseCholesky::analyze(size.dofs, columnStart, rows);
    size.factorNonZeros = factor.nonZeros;
    size.factorFlops = factor.flops;
}

bool completeModalPays(long long n, long long m, long long stiffnessNonZeros) {
    return n <= 1000 && m * n <= 8 * stiffnessNonZeros;
}

EngineKind engineFor(const PlateParameters& p, const ProblemSize& size) {
    using Engine = LawParameters::Engine;
    if (p.law.condensed()) return EngineKind::Condensed;
    const bool modal =
        !p.law.singularMass() &&
        (p.law.modes > 0 || p.law.engine == Engine::CompleteModal ||
         (p.law.engine == Engine::Auto && completeModalPays(size.dofs, size.contactVertices, size.nonZeros)));
    if (!modal) return EngineKind::Sparse;
    return p.law.modes > 0 && p.law.modes < size.dofs ? EngineKind::ReducedModal : EngineKind::CompleteModal;
}

namespace {

// Does the condensed engine take the sparse condensation (CondensedPlate.h)? q massive coordinates.
bool sparseCondensation(const PlateParameters& p, double massive) {
    return !denseCondensationServes(static_cast<Eigen::Index>(massive), p.law.modes);
}
// Lanczos' products for m modes (CondensedSparse.cpp, Spectrum.cpp: the kept ones and as many more, at
// least 80).
double lanczosSteps(double kept) { return kept + std::max(80.0, kept); }

// The modal engines' memory beyond the clamped matrices (bytes) and their spectrum time (s).
void modalCost(const PlateParameters& p, const ProblemSize& s, EngineKind engine, double& bytes, double& seconds) {
    const double n = double(s.dofs), c = double(s.contactVertices);
    const double m = engine == EngineKind::CompleteModal ? n : double(p.law.modes);
    const bool lanczos = engine == EngineKind::ReducedModal && ((4 * m <= n && n > 1200) || n > 3000);
    if (lanczos) {
        // Spectrum.cpp's Lanczos: per step a solve with the factor of K, a product with M and the
        // basis' reorthogonalization (n × steps, twice: measured 56x20 on 60 modes 1.64 s, 112x40 on
        // 100 modes 11.9 s through fmpy); the basis, the Ritz vectors and the factor kept.
        const double steps = std::min(n, lanczosSteps(m));
        bytes = factorBytes(s) + kDouble * (2 * n * steps + steps * steps);
        seconds = s.factorFlops * kPerFactorFlop +
                  steps * ((4.0 * double(s.factorNonZeros) + 2.0 * double(s.nonZeros)) * kPerLanczosFlop +
                           4.0 * n * steps * kPerFactorFlop);
    } else {
        bytes = kDenseEigenMatrices * kDouble * n * n;
        seconds = kPerDenseEigenCube * n * n * n;
    }
    bytes += kDouble * (n * m + m * c);  // Φ and (CΦ)ᵀ kept for the run
}

// Stress and probes (docs/theory.md §23): with stress_outputs about three functionals per vertex
// (the vertices' curvatures; the root's are a few more), else the probes' alone; sparse rows over an element's dofs, then
// in the engine's coordinates: dense over the modes (modal), over the massive modes and the
// constraint rows with the temporaries of their condensation (conserving), or a sparse copy.
double recoveryBytes(const PlateParameters& p, const ProblemSize& s, EngineKind engine, bool sparse, double massive,
                     double rows) {
    const double n = double(s.dofs);
    const double recoveryRows = p.outputs.stressOutputs
                                    ? 3.0 * double(s.contactVertices + p.mesh.ny + 1) + 2.0 * p.mesh.ny + 5.0
                                    : double(p.outputs.probeCount()) + 5.0;
    const double perRow = p.mesh.element == ElementType::Fvs ? 12.0 : 21.0;
    double recovery = (kTriplet + kEntry) * recoveryRows * perRow;
    if (engine == EngineKind::Condensed)
        recovery += kDouble * recoveryRows * (3.0 * massive + (sparse ? 1.0 : 2.0) * rows);  // sparse: in place
    else if (engine == EngineKind::Sparse)
        recovery += kEntry * recoveryRows * perRow;
    else
        recovery += kDouble * recoveryRows * (engine == EngineKind::CompleteModal ? n : double(p.law.modes));
    return recovery;
}

// The phases' times (s), from the sizes and the engine already in e.
void estimateTimes(const PlateParameters& p, const ProblemSize& s, double massive, double rows, ResourceEstimate& e) {
    const double n = double(s.dofs), t = double(s.elementEntries);
    const double zFull = double(s.fullNonZeros), z = double(s.nonZeros), l = double(s.factorNonZeros);
    const double perEntry = p.mesh.element == ElementType::Fvs ? kAssemblyPerEntryFvs : kAssemblyPerEntryArgyris;
    e.assemblySeconds = perEntry * t * (p.law.singularMass() ? 2.0 : 1.0) + kPerPatternEntry * (t + zFull);
    const double oneFactor = kPerAnalysisEntry * z + kPerFactorFlop * s.factorFlops;
    if (e.engine != EngineKind::ReducedModal) e.factorSeconds = 2 * oneFactor;
    if (e.engine == EngineKind::Condensed && sparseCondensation(p, massive)) {
        // Factors of K and of the saddle point; a solve per Lanczos product (one right-hand side
        // each), then blocked ones per mode (V, with K) and one per row and for the load (with the
        // saddle point's factor, CondensedSparse.cpp).
        const double kept = p.law.modes;
        e.factorSeconds = 2 * kPerAnalysisEntry * z + (1.0 + kSaddleFlops) * kPerFactorFlop * s.factorFlops;
        e.spectrumSeconds = lanczosSteps(kept) * 4.0 * l * kPerLanczosFlop +
                            (kept + kSaddleFill * (rows * (p.outputs.stressOutputs ? 1.0 : kTriangleWork) + 1)) * 4.0 *
                                l * kPerSolveFlop +
                            kPerRowCube * rows * rows * rows;
    } else if (e.engine == EngineKind::Condensed) {
        // One factor of K; a solve per massive coordinate and per row; the dense eigen solution of T.
        e.factorSeconds = oneFactor;
        e.spectrumSeconds =
            (massive + rows) * 4.0 * (l + z) * kPerFactorFlop + kPerDenseEigenCube * massive * massive * massive;
    }
    if (p.law.beta < 0.25) e.spectrumSeconds += oneFactor + kPowerIterations * kPerFactorFlop * 4.0 * (l + z);
    e.staticSeconds = kPerAnalysisEntry * z;  // the QP of the static state is small without contact
    e.initSeconds = e.assemblySeconds + e.factorSeconds + e.spectrumSeconds + e.staticSeconds;
    if (e.engine == EngineKind::Condensed) {
        const double m = p.law.modes > 0 && p.law.modes < massive ? double(p.law.modes) : massive;
        e.stepSeconds = kPerModalStepEntry * (8 * m + m * rows / 10);  // a look at the rows every ~10 steps
    } else if (e.engine == EngineKind::Sparse) {
        e.stepSeconds = kPerSparseStepEntry * (2 * l + 2 * z);
    } else {
        const double m = e.engine == EngineKind::CompleteModal ? n : double(p.law.modes);
        e.stepSeconds = kPerModalStepEntry * (m * double(s.contactVertices) + 8 * m);
    }
}

}  // namespace

ResourceEstimate estimateResources(const PlateParameters& p, const ProblemSize& s) {
    ResourceEstimate e;
    e.size = s;
    e.complete = s.factorNonZeros > 0;
    e.engine = e.complete ? engineFor(p, s) : EngineKind::Sparse;
    const double n = double(s.dofs), nFull = double(s.fullDofs), t = double(s.elementEntries);
    const double zFull = double(s.fullNonZeros), z = double(s.nonZeros);
    // Assembly.cpp: the triplets of M and K, setFromTriplets' temporary, both assembled matrices.
    const double assembly = 2 * kTriplet * t + kEntry * t + 2 * kEntry * zFull + 6 * kDouble * nFull;
    if (p.law.singularMass())
        e.assemblyMB = (assembly + kTriplet * t + kEntry * zFull) / kMB;  // B, C of SingularMass
    else
        e.assemblyMB = assembly / kMB;
    // clamp(): the full matrices, the restriction's triplets, its temporary and result.
    const double clampPeak = 2 * kEntry * zFull + kTriplet * z + 3 * kEntry * z;
    const double clamped = 2 * kEntry * z + 8 * kDouble * n;  // free M and K and vectors
    e.matricesMB = (clamped + kEntry * (z + n)) / kMB;  // + FullOrderPlate's upper row copies
    const double lower = kEntry * (z + n) / 2;  // SparseCholesky's lower-triangle copy
    double phases = std::max(assembly, clampPeak);
    if (p.law.beta < 0.25) phases = std::max(phases, clamped + factorBytes(s) + lower);  // κ_h: factor of M
    double engineBytes = 0.0;
    // The conserving engine (CondensedPlate.cpp): the factor of K, then dense matrices over the
    // massive coordinates (q: one per element, three for P1dg) and the constraint rows (r: the
    // contact vertices and an output point): T, its eigenvectors and the eigen solver's workspace
    // (4 q², measured), C K⁻¹ R and its product with Φ (2 r q), and about sixteen r × r matrices (C K⁻¹ Cᵀ, D,
    // W₂, the two contact matrices and their QP columns, the static problem's).
    const double massive = double(s.elements) * (p.law.mass == MassModel::SingularP1dg ? 3.0 : 1.0);
    const double rows = double(s.contactVertices) + 1.0;
    if (e.engine == EngineKind::Condensed && sparseCondensation(p, massive)) {
        // The sparse condensation (CondensedSparse.cpp): the factor of K, then the saddle point's
        // (one at a time), the Lanczos basis (q × steps), the modes V (n × m) and their right-hand
        // sides, the massless solves' block ((n + q) × 64) and its rows read, the rows' matrices.
        const double kept = p.law.modes;
        e.factorsMB = kSaddleFill * factorBytes(s) / kMB;
        // (six r × r matrices, not sixteen as below: D sorted and in place, then the schemes'; measured
        // 1484 MB at 112x40 on 100 modes, flow)
        engineBytes = kDouble * (massive * lanczosSteps(kept) + 2 * n * kept + 64 * (n + massive) + 2 * 64 * rows +
                                 rows * kept + 6 * rows * rows) +
                      kSaddleFill * factorBytes(s);
        if (p.law.timeScheme == TimeScheme::Flow && p.refinement.tolerance > 0.0)
            engineBytes += kDouble * (3 * std::log2(double(p.refinement.maxSubsteps)) * rows * rows + rows * kept);
        phases = std::max(phases, e.matricesMB * kMB + factorBytes(s) + lower + engineBytes);
    } else if (e.engine == EngineKind::Condensed) {
        e.factorsMB = factorBytes(s) / kMB;
        engineBytes = kDouble * (4 * massive * massive + 2 * rows * massive + 16 * rows * rows);
        // time_scheme = flow with a tolerance (FlowScheme.h): the midpoint matrices of every
        // sub-step level (W₂, ½W₂ + D and its QP columns: three r × r each) and |G|.
        if (p.law.timeScheme == TimeScheme::Flow && p.refinement.tolerance > 0.0)
            engineBytes += kDouble * (3 * std::log2(double(p.refinement.maxSubsteps)) * rows * rows + rows * massive);
        phases = std::max(phases, e.matricesMB * kMB + factorBytes(s) + lower + engineBytes);
    } else if (e.engine == EngineKind::Sparse) {
        // The step factor of A, then the factor of K for the static state beside it.
        e.factorsMB = 2 * factorBytes(s) / kMB;
        phases = std::max(phases, clamped + kEntry * z + lower + factorBytes(s));
        phases = std::max(phases, e.matricesMB * kMB + 2 * factorBytes(s) + lower);
    } else {
        modalCost(p, s, e.engine, engineBytes, e.spectrumSeconds);
        phases = std::max(phases, clamped + engineBytes);
        if (e.engine == EngineKind::CompleteModal) {
            // The static state of the complete basis is solved with a FullOrderPlate (Spectrum:
            // Φ and (CΦ)ᵀ stay): its factor of A and the factor of K.
            e.factorsMB = 2 * factorBytes(s) / kMB;
            engineBytes = kDouble * (n * n + n * double(s.contactVertices));
            phases = std::max(phases, e.matricesMB * kMB + engineBytes + 2 * factorBytes(s) + lower);
        }
    }
    // (the sparse condensation's recovery rows reach the kept modes only, not every massive one)
    const bool sparse = e.engine == EngineKind::Condensed && sparseCondensation(p, massive);
    const double recovery = recoveryBytes(p, s, e.engine, sparse, sparse ? double(p.law.modes) : massive, rows);
    engineBytes += recovery;
    phases += recovery;
    e.engineMB = engineBytes / kMB;
    // The pattern walk and the symbolic analysis (AMD's copy of the pattern and its workspace).
    phases = std::max(phases, 4.0 * (3.0 * z + 8.0 * nFull));
    const double space =
        double(s.elements) * (p.mesh.element == ElementType::Fvs ? kSpacePerElementFvs : kSpacePerElementArgyris);
    e.peakMB = (space + phases + kBaseMB * kMB) / kMB;
    if (!e.complete) e.peakMB = (space + 2 * kTriplet * t) / kMB;  // stage 1: the certain part only
    estimateTimes(p, s, massive, rows, e);
    return e;
}

std::string ResourceEstimate::describe() const {
    const ProblemSize& s = size;
    const char* name = engine == EngineKind::Sparse          ? "sparse"
                       : engine == EngineKind::CompleteModal ? "modal-complete"
                       : engine == EngineKind::Condensed     ? "conserving"
                                                             : "modal-reduced";
    char text[600];
    if (!complete) {
        std::snprintf(text, sizeof text,
                      "resource estimate (from the mesh): %lld dofs (%lld free), %lld contact vertices, assembly of "
                      "2 x %lld entries: at least %.0f MB",
                      s.fullDofs, s.dofs, s.contactVertices, s.elementEntries, peakMB);
        return text;
    }
    std::snprintf(text, sizeof text,
                  "resource estimate: engine %s, %lld free dofs, %lld contact vertices, nnz(K) = %lld, nnz(L) = %lld "
                  "(%.3g GFlop per factorization); memory peak %.0f MB (assembly %.0f MB, matrices %.0f MB, factors "
                  "%.0f MB, modal basis %.0f MB); initialization ~%.3g s, time step ~%.3g s without contact",
                  name, s.dofs, s.contactVertices, s.nonZeros, s.factorNonZeros, s.factorFlops * 1e-9, peakMB,
                  assemblyMB, matricesMB, factorsMB, engineMB, initSeconds, stepSeconds);
    return text;
}

void requireWithinBudget(const PlateParameters& p, const ResourceEstimate& e) {
    if (p.memoryLimit <= 0.0 || e.peakMB <= p.memoryLimit) return;
    std::ostringstream msg;
    msg.precision(6);
    msg << "refused before allocating: this instance needs " << (e.complete ? "an estimated " : "at least ")
        << std::ceil(e.peakMB) << " MB";
    if (!e.complete) msg << " (the element bases and the assembly of M and K alone)";
    if (e.size.predicted)
        msg << " (predicted from the mesh size; factor nnz(L) ~ " << double(e.size.factorNonZeros) << ")";
    msg << " and memory_limit = " << p.memoryLimit << " MB (nx = " << p.mesh.nx << ", ny = " << p.mesh.ny
        << "); raise memory_limit to at least " << std::ceil(e.peakMB)
        << " MB if the machine has that memory (0 = no limit), or use a coarser mesh";
    throw ResourceError(msg.str());
}

InitProgress::InitProgress(ProgressLog log, double estimatedSeconds, double threshold)
    : log_(std::move(log)),
      estimated_(estimatedSeconds),
      threshold_(threshold),
      start_(std::chrono::steady_clock::now()) {}

double InitProgress::elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void InitProgress::phase(const std::string& what, double estimatedSeconds) {
    ++count_;
    if (!log_ || estimated_ < threshold_) return;
    char text[400];
    std::snprintf(text, sizeof text, "initialization step %d: %s (estimated %.2g s); %.3g s of ~%.3g s elapsed", count_,
                  what.c_str(), estimatedSeconds, elapsed(), estimated_);
    log_(text);
}

void InitProgress::done(double peakEstimateMB) {
    if (!log_) return;
    char text[200];
    std::snprintf(text, sizeof text, "initialized in %.3g s (estimated %.3g s; memory peak estimated %.0f MB)",
                  elapsed(), estimated_, peakEstimateMB);
    log_(text);
}

std::vector<std::string> costNotices(const PlateParameters& p, const ResourceEstimate& e) {
    std::vector<std::string> notices;
    if (!e.complete) return notices;
    char text[700];
    const char* modes = e.engine == EngineKind::Condensed || e.engine == EngineKind::ReducedModal ||
                                e.engine == EngineKind::CompleteModal
                            ? "fewer modes (modes), "
                            : "";
    if (e.initSeconds > kLongSetupSeconds) {
        std::snprintf(text, sizeof text,
                      "this initialization will take about %.2g s (estimated: %.2g s to assemble, %.2g s to factor, "
                      "%.2g s for the modes and the condensation); %sa coarser mesh (nx = %d, ny = %d) shortens it",
                      e.initSeconds, e.assemblySeconds, e.factorSeconds, e.spectrumSeconds, modes, p.mesh.nx,
                      p.mesh.ny);
        notices.emplace_back(text);
    }
    const double perSecond = e.stepSeconds / p.law.dt;  // CPU per simulated second, without contact
    if (perSecond > kCostlyRunSeconds) {
        std::snprintf(text, sizeof text,
                      "each simulated second will cost about %.3g s of CPU (%.3g s per time step of dt = %g s, "
                      "without contact; more with it); cheaper: %sa stop covering only the contact region "
                      "(obstacle_lower_x_min ... obstacle_upper_y_max: fewer contact rows), or a coarser mesh "
                      "(nx = %d, ny = %d)",
                      perSecond, e.stepSeconds, p.law.dt, modes, p.mesh.nx, p.mesh.ny);
        notices.emplace_back(text);
    }
    return notices;
}

ResourceEstimate planResources(const PlateParameters& p, const FiniteElementSpace& space, const ProgressLog& log) {
    const StopMap stops(p.obstacles, p.mesh);
    ProblemSize size = countEntries(space, [&stops](const Eigen::Vector2d& x) { return stops.at(x); });
    const ResourceEstimate lowerBound = estimateResources(p, size);
    requireWithinBudget(p, lowerBound);  // the assembly alone exceeds the budget: refuse now
    analyzePattern(space, size);
    const ResourceEstimate estimate = estimateResources(p, size);
    if (log) log(estimate.describe());
    requireWithinBudget(p, estimate);
    if (log)
        for (const std::string& notice : costNotices(p, estimate)) log.warn(notice);
    return estimate;
}

}  // namespace plate
