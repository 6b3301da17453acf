// Regular (weighted Delaunay) triangulations by geogram (vendored in geogram/: its Delaunay
// PSM, exact predicates with symbolic perturbation), behind a small C API that
// core/backends/geogram.py calls through ctypes (which releases the GIL).
//
// as_regular(dim, n, points, weights, &count) triangulates n points of dimension 2 or 3 with
// their weights (squared radii) and returns a handle holding `count` cells; as_take(handle,
// cells, neighbours) copies them into caller-allocated (count, dim + 1) int32 arrays and frees
// the handle (as_free frees it unread). Each cell row is ascending; neighbour i is the cell
// opposite vertex i, -1 on the hull. Hidden points are in no cell, nor are coincident points
// but the heaviest. geogram runs on the calling thread (its own threads off, logger quiet),
// one triangulation at a time, its global random generator reset before each: the result,
// cell order included, depends on the input alone.

#include <Python.h>  // first, as Python asks

#include "geogram/Delaunay_psm.h"

// The two amalgamated files geogram's PSM concatenates each expand GEO_FP_CONTRACT_OFF, which
// under GCC defines a checking object of the same name twice in this one translation unit.
// Build flags pass -ffp-contract=off; as_init checks it once instead (fp_contract_off).
#if defined(__GNUC__) && !defined(__clang__)
#undef GEO_FP_CONTRACT_OFF
#define GEO_FP_CONTRACT_OFF
#endif
#include "geogram/Delaunay_psm.cpp"

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <exception>
#include <memory>
#include <mutex>
#include <new>
#include <unordered_map>
#include <vector>

#if defined(_WIN32)
#define AS_API extern "C" __declspec(dllexport)
#else
#define AS_API extern "C" __attribute__((visibility("default")))
#endif

namespace {

struct Result {
    int width = 0;                   // vertices per cell: dim + 1
    std::vector<int32_t> cells;      // (count, width), rows ascending
    std::vector<int32_t> neighbours;  // (count, width), -1 on the hull
};

std::mutex geogram_lock;  // geogram's random generator and logger are global
std::once_flag started;
bool usable = false;

#if defined(__GNUC__) || defined(__clang__)
__attribute__((noipa))
#endif
double a2plusb(double a, double b) {
    return a * a + b;
}

bool fp_contract_off() {
    // a fused multiply-add keeps the low bits of a*a that the plain sum rounds away
    return a2plusb(0x1.0000002p0, -0x1.0000004p0) == 0.0;
}

void start() {
    if (!fp_contract_off()) return;  // exact predicates would be wrong: stay unusable
    // geogram's initialisation resets SIGINT to its default (its "cancel mode" off), which
    // would make Ctrl-C kill Python instead of raising KeyboardInterrupt: put it back.
#if defined(_WIN32)
    void (*interrupt)(int) = std::signal(SIGINT, SIG_DFL);
    GEO::initialize(GEO::GEOGRAM_INSTALL_NONE);
    std::signal(SIGINT, interrupt);
#else
    struct sigaction interrupt;
    sigaction(SIGINT, nullptr, &interrupt);
    GEO::initialize(GEO::GEOGRAM_INSTALL_NONE);
    sigaction(SIGINT, &interrupt, nullptr);
#endif
    GEO::Logger::instance()->set_quiet(true);
    GEO::Process::enable_multithreading(false);
    GEO::Process::set_max_threads(1);
    GEO::set_assert_mode(GEO::ASSERT_THROW);
    usable = true;
}

// geogram's regular cells of the points `ids` (every point when empty) into `out`, rows
// ascending (neighbours alongside) in input ids; false when they span no cell.
bool triangulate(int dim, size_t m, const double* points, const double* weights,
                 const std::vector<uint32_t>& ids, Result& out) {
    const size_t used = ids.empty() ? m : ids.size(), stride = size_t(dim) + 1;
    // geogram lifts a point to |p|² - t² with t = sqrt(W - w), W the largest weight
    double top = weights[0];
    for (size_t i = 1; i < m; ++i) top = std::max(top, weights[i]);
    std::vector<double> rows(used * stride);
    for (size_t j = 0; j < used; ++j) {
        size_t i = ids.empty() ? j : ids[j];
        for (int k = 0; k < dim; ++k) rows[j * stride + k] = points[i * dim + k];
        rows[j * stride + dim] = std::sqrt(top - weights[i]);
    }
    const int w = dim + 1;
    std::lock_guard<std::mutex> hold(geogram_lock);
    GEO::Numeric::random_reset(0);
    GEO::Delaunay_var tri = GEO::Delaunay::create(GEO::coord_index_t(w),
                                                  dim == 3 ? "BPOW" : "BPOW2d");
    tri->set_vertices(GEO::index_t(used), rows.data());
    const size_t count = tri->nb_cells();
    if (count == 0) return false;
    const GEO::index_t* to_v = tri->cell_to_v();
    const GEO::index_t* to_cell = tri->cell_to_cell();
    out.width = w;
    out.cells.resize(count * w);
    out.neighbours.resize(count * w);
    for (size_t c = 0; c < count; ++c) {
        int32_t* v = &out.cells[c * w];
        int32_t* t = &out.neighbours[c * w];
        for (int i = 0; i < w; ++i) {
            GEO::index_t vertex = to_v[c * w + i], across = to_cell[c * w + i];
            v[i] = int32_t(ids.empty() ? vertex : ids[vertex]);
            t[i] = across == GEO::NO_INDEX ? -1 : int32_t(across);
        }
        for (int i = 1; i < w; ++i) {  // insertion sort of at most 4
            for (int j = i; j > 0 && v[j - 1] > v[j]; --j) {
                std::swap(v[j - 1], v[j]);
                std::swap(t[j - 1], t[j]);
            }
        }
    }
    return true;
}

struct Key {  // a point's coordinates, compared as numbers (-0.0 == 0.0, as geogram does)
    const double* p;
    int dim;
    bool operator==(const Key& o) const { return std::equal(p, p + dim, o.p); }
};

struct KeyHash {  // equal keys hash alike: a zero's bits are +0.0's whatever its sign
    size_t operator()(const Key& k) const {
        uint64_t h = 0x9e3779b97f4a7c15ull;
        for (int i = 0; i < k.dim; ++i) {
            const double x = k.p[i] == 0.0 ? 0.0 : k.p[i];
            uint64_t bits;
            std::memcpy(&bits, &x, 8);
            h = (h ^ bits) * 0x100000001b3ull;
            h ^= h >> 29;
        }
        return size_t(h);
    }
};

// Whether a point in no cell coincides with another point: geogram keeps the first of
// coincident points it inserts, whatever their weights. Costs nothing when every point is
// a vertex, one hashed pass over the points otherwise.
bool coincident_unused(int dim, size_t m, const double* points, const Result& r) {
    std::vector<bool> used(m, false);
    for (int32_t v : r.cells) used[size_t(v)] = true;
    std::unordered_map<Key, int, KeyHash> seen;
    for (size_t i = 0; i < m; ++i) {
        if (!used[i]) seen.emplace(Key{points + i * dim, dim}, 0);
    }
    if (seen.empty()) return false;
    for (size_t i = 0; i < m; ++i) {
        auto it = seen.find(Key{points + i * dim, dim});
        if (it != seen.end() && ++it->second > 1) return true;
    }
    return false;
}

// The points to keep of coincident ones: the heaviest, the first of equal weights; ascending.
std::vector<uint32_t> distinct(int dim, size_t m, const double* points, const double* weights) {
    std::vector<uint32_t> order(m);
    for (size_t i = 0; i < m; ++i) order[i] = uint32_t(i);
    auto coords = [&](uint32_t i) { return points + size_t(i) * dim; };
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return std::lexicographical_compare(coords(a), coords(a) + dim, coords(b),
                                            coords(b) + dim);
    });
    std::vector<bool> kept(m, true);
    for (size_t lo = 0, hi; lo < m; lo = hi) {
        uint32_t best = order[lo];
        for (hi = lo + 1; hi < m && std::equal(coords(order[hi]), coords(order[hi]) + dim,
                                               coords(order[lo])); ++hi) {
            uint32_t i = order[hi];
            bool heavier = weights[i] > weights[best] ||
                           (weights[i] == weights[best] && i < best);
            kept[heavier ? best : i] = false;
            best = heavier ? i : best;
        }
    }
    std::vector<uint32_t> ids;
    for (size_t i = 0; i < m; ++i) {
        if (kept[i]) ids.push_back(uint32_t(i));
    }
    return ids;
}

}  // namespace

// 1 when the library can triangulate (initialised, exact arithmetic intact), else 0 (also
// when initialising threw: no C++ exception may reach ctypes, it would abort the process).
AS_API int as_ready() {
    try {
        std::call_once(started, start);
    } catch (...) {
        return 0;
    }
    return usable ? 1 : 0;
}

// 0 and *handle, *count on success; 1 not ready, 2 bad arguments, 3 no cell (the points are
// flat), 4 geogram failed, 5 out of memory.
AS_API int as_regular(int dim, int64_t n, const double* points, const double* weights,
                      void** handle, int64_t* count) {
    *handle = nullptr;
    *count = 0;
    if (!as_ready()) return 1;
    if ((dim != 2 && dim != 3) || n < dim + 1 || n > INT32_MAX) return 2;
    try {
        const size_t m = size_t(n);
        auto out = std::make_unique<Result>();
        if (!triangulate(dim, m, points, weights, {}, *out)) return 3;
        if (coincident_unused(dim, m, points, *out)) {  // again without the lighter twins
            const std::vector<uint32_t> ids = distinct(dim, m, points, weights);
            if (ids.size() < size_t(dim) + 1) return 2;
            if (!triangulate(dim, m, points, weights, ids, *out)) return 3;
        }
        *count = int64_t(out->cells.size() / size_t(out->width));
        *handle = out.release();
        return 0;
    } catch (const std::bad_alloc&) {
        return 5;
    } catch (...) {
        return 4;
    }
}

// Copies the handle's cells and neighbours into (count, dim + 1) int32 arrays; frees it.
AS_API void as_take(void* handle, int32_t* cells, int32_t* neighbours) {
    Result* r = static_cast<Result*>(handle);
    std::copy(r->cells.begin(), r->cells.end(), cells);
    std::copy(r->neighbours.begin(), r->neighbours.end(), neighbours);
    delete r;
}

AS_API void as_free(void* handle) {
    delete static_cast<Result*>(handle);
}

// A module object, so the library is also an importable extension (setuptools builds it as
// one); its functions are reached through ctypes.
static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_geogram",
                                    "geogram's regular triangulation (C API, used via ctypes)",
                                    -1, nullptr, nullptr, nullptr, nullptr, nullptr};

PyMODINIT_FUNC PyInit__geogram(void) {
    return PyModule_Create(&module);
}
