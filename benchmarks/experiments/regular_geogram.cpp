// geogram's regular (weighted Delaunay) triangulation, timed on the points our weighted build
// gives Qhull: a measurement of a faster exact backend (geogram: BSD-3, exact predicates with
// symbolic perturbation), not part of the build. The build now compiles geogram's Delaunay PSM
// itself (core/backends/native, core/backends/geogram.py); this remains the first measurement.
//
// Build against the static library and headers the PyPI wheel `geogram` ships (0.0.7):
//   pip install --target /tmp/geo geogram==0.0.7
//   cp /tmp/geo/geogram.libs/* . && ln -s libtbb-*.so.2 libtbb.so.2 && ln -s libgomp-*.so.1.0.0 libgomp.so.1
//   g++ -O2 -std=c++17 -I/tmp/geo/include/geogram1 regular_geogram.cpp /tmp/geo/lib64/libgeogram.a \
//       -L. -l:libtbb.so.2 -l:libgomp.so.1 -lpthread -ldl -Wl,-rpath,$PWD -o regular_geogram
// Input: int64 n, then n rows of float64 (x, y, z, sqrt(max(w) - w)) (geogram's lifting of a
// weight w), e.g. from numpy: np.column_stack((p, np.sqrt(w.max() - w))).tofile(f) after n.
// Usage: regular_geogram points.bin [cells.bin]: prints the best of 3 builds; writes the cells
// (uint32 count, then count x 4 uint32 vertex rows) to compare with Qhull's.
#include <geogram/basic/command_line.h>
#include <geogram/basic/command_line_args.h>
#include <geogram/basic/common.h>
#include <geogram/delaunay/delaunay.h>

#include <chrono>
#include <cstdio>
#include <vector>

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s points.bin [cells.bin]\n", argv[0]);
        return 2;
    }
    GEO::initialize(GEO::GEOGRAM_INSTALL_NONE);
    GEO::CmdLine::import_arg_group("standard");
    GEO::CmdLine::import_arg_group("algo");
    GEO::CmdLine::set_arg("sys:max_threads", "1");
    std::FILE* in = std::fopen(argv[1], "rb");
    long n = 0;
    if (!in || std::fread(&n, 8, 1, in) != 1) return 1;
    std::vector<double> rows(4 * n);
    if (std::fread(rows.data(), 8, 4 * n, in) != size_t(4 * n)) return 1;
    std::fclose(in);
    double best = 1e30;
    for (int rep = 0; rep < 3; ++rep) {
        auto start = std::chrono::steady_clock::now();
        GEO::Delaunay_var tri = GEO::Delaunay::create(4, "BPOW");  // sequential, weighted 3D
        tri->set_vertices(GEO::index_t(n), rows.data());
        double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                             .count();
        best = seconds < best ? seconds : best;
        if (rep == 0 && argc > 2) {
            std::FILE* out = std::fopen(argv[2], "wb");
            unsigned count = tri->nb_cells();
            std::fwrite(&count, 4, 1, out);
            std::fwrite(tri->cell_to_v(), 4, 4 * size_t(count), out);
            std::fclose(out);
        }
        if (rep == 0) std::printf("points %ld cells %u\n", n, tri->nb_cells());
    }
    std::printf("best of 3: %.3f s\n", best);
    return 0;
}
