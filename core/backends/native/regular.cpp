// Regular (weighted Delaunay) triangulations by geogram (vendored in geogram/: its Delaunay
// PSM, exact predicates with symbolic perturbation), behind a small C API that
// core/backends/geogram.py calls through ctypes (which releases the GIL).
//
// as_regular(dim, n, points, weights, &count) triangulates n points of dimension 2 or 3 with
// their weights (squared radii) and returns a handle holding `count` cells; as_take(handle,
// cells, neighbours) copies them into caller-allocated (count, dim + 1) int32 arrays and frees
// the handle (as_free frees it unread). Each cell row is ascending; neighbour i is the cell
// opposite vertex i, -1 on the hull; cells are in ascending lexicographic order of their
// rows, so the result depends on the input alone (not on geogram's random insertion order).
// Hidden points are in no cell. geogram runs on the calling thread (its own threads off,
// logger quiet), one triangulation at a time: its random generator is global.

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
#include <cstdint>
#include <exception>
#include <mutex>
#include <new>
#include <vector>

#if defined(_WIN32)
#define AS_API extern "C" __declspec(dllexport)
#else
#define AS_API extern "C" __attribute__((visibility("default")))
#endif

namespace {

struct Result {
    int width = 0;                  // vertices per cell: dim + 1
    std::vector<int32_t> cells;     // (count, width), rows ascending, rows sorted
    std::vector<int32_t> neighbours;
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
    GEO::initialize(GEO::GEOGRAM_INSTALL_NONE);
    GEO::Logger::instance()->set_quiet(true);
    GEO::Process::enable_multithreading(false);
    GEO::Process::set_max_threads(1);
    GEO::set_assert_mode(GEO::ASSERT_THROW);
    usable = true;
}

// Sort each row ascending (neighbours alongside), then the rows lexicographically: a counting
// sort on the first vertex, each bucket (a few cells) sorted by the rest; neighbours renamed.
void canonical(Result& r, const GEO::index_t* to_v, const GEO::index_t* to_cell, size_t count,
               size_t n) {
    const int w = r.width;
    std::vector<int32_t> cells(count * w), nbrs(count * w);
    for (size_t c = 0; c < count; ++c) {
        int32_t v[4], t[4];
        for (int i = 0; i < w; ++i) {
            v[i] = int32_t(to_v[c * w + i]);
            GEO::index_t across = to_cell[c * w + i];
            t[i] = across == GEO::NO_INDEX ? -1 : int32_t(across);
        }
        for (int i = 1; i < w; ++i) {  // insertion sort of at most 4
            for (int j = i; j > 0 && v[j - 1] > v[j]; --j) {
                std::swap(v[j - 1], v[j]);
                std::swap(t[j - 1], t[j]);
            }
        }
        std::copy(v, v + w, &cells[c * w]);
        std::copy(t, t + w, &nbrs[c * w]);
    }
    std::vector<size_t> start(n + 1, 0);
    for (size_t c = 0; c < count; ++c) ++start[size_t(cells[c * w]) + 1];
    for (size_t i = 0; i < n; ++i) start[i + 1] += start[i];
    std::vector<size_t> order(count);
    {
        std::vector<size_t> next(start.begin(), start.end() - 1);
        for (size_t c = 0; c < count; ++c) order[next[size_t(cells[c * w])]++] = c;
    }
    auto less = [&](size_t a, size_t b) {
        return std::lexicographical_compare(&cells[a * w + 1], &cells[a * w + w],
                                            &cells[b * w + 1], &cells[b * w + w]);
    };
    for (size_t i = 0; i < n; ++i) {
        if (start[i + 1] - start[i] > 1) {
            std::sort(order.begin() + start[i], order.begin() + start[i + 1], less);
        }
    }
    std::vector<int32_t> rank(count);
    for (size_t k = 0; k < count; ++k) rank[order[k]] = int32_t(k);
    r.cells.resize(count * w);
    r.neighbours.resize(count * w);
    for (size_t k = 0; k < count; ++k) {
        size_t c = order[k];
        for (int i = 0; i < w; ++i) {
            r.cells[k * w + i] = cells[c * w + i];
            int32_t t = nbrs[c * w + i];
            r.neighbours[k * w + i] = t < 0 ? -1 : rank[size_t(t)];
        }
    }
}

}  // namespace

// 1 when the library can triangulate (initialised, exact arithmetic intact), else 0.
AS_API int as_ready() {
    std::call_once(started, start);
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
        const size_t m = size_t(n), stride = size_t(dim) + 1;
        // geogram lifts a point to |p|² - t² with t = sqrt(W - w), W the largest weight
        double top = weights[0];
        for (size_t i = 1; i < m; ++i) top = std::max(top, weights[i]);
        std::vector<double> rows(m * stride);
        for (size_t i = 0; i < m; ++i) {
            for (int k = 0; k < dim; ++k) rows[i * stride + k] = points[i * dim + k];
            rows[i * stride + dim] = std::sqrt(top - weights[i]);
        }
        Result* out = new Result;
        out->width = dim + 1;
        {
            std::lock_guard<std::mutex> hold(geogram_lock);
            GEO::Numeric::random_reset(0);
            GEO::Delaunay_var tri = GEO::Delaunay::create(
                GEO::coord_index_t(dim + 1), dim == 3 ? "BPOW" : "BPOW2d");
            tri->set_vertices(GEO::index_t(m), rows.data());
            size_t cells = tri->nb_cells();
            if (cells == 0) {
                delete out;
                return 3;
            }
            canonical(*out, tri->cell_to_v(), tri->cell_to_cell(), cells, m);
        }
        *count = int64_t(out->cells.size() / size_t(out->width));
        *handle = out;
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
