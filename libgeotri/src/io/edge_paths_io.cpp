#include "io/atomic_file.h"
#include "io/text_reader.h"

#include <geodesic/errors.h>
#include <geotri/edge_paths_io.h>

#include <cinttypes>
#include <cstdio>
#include <tuple>

namespace geotri {

void write_edge_paths(const std::string& path, const EdgePaths& paths) {
    detail::AtomicFile out(path);
    std::FILE* file = out.stream();
    std::fprintf(file, "geotri-edge-paths %d\n", k_edge_paths_version);
    std::fprintf(file, "fine %d %016" PRIx64 "\n", paths.fine_vertices, paths.fine_checksum);
    std::fprintf(file, "coarse %d %zu\n", paths.coarse_vertices, paths.edges.size());
    for (const DecimatedEdge& edge : paths.edges) {
        std::fprintf(file, "%d %d %zu", edge.a, edge.b, edge.fine_path.size());
        for (const int v : edge.fine_path) std::fprintf(file, " %d", v);
        std::fputc('\n', file);
    }
    out.commit();
}

EdgePaths read_edge_paths(const std::string& path) {
    detail::LineReader in(path, detail::read_text(path));
    auto expect_words = [&](const std::vector<std::string_view>& w, std::size_t n, const char* what) {
        if (w.size() != n) in.fail(std::string("expected ") + what);
    };
    EdgePaths paths;
    paths.name = path;

    auto w = detail::words(in.next("the header 'geotri-edge-paths 1'"));
    if (w.size() != 2 || w[0] != "geotri-edge-paths")
        in.fail("not an edge paths file (expected 'geotri-edge-paths 1')");
    if (detail::parse_count(in, w[1], "version") != k_edge_paths_version)
        in.fail("version " + std::string(w[1]) + " is not supported (this build reads version " +
                std::to_string(k_edge_paths_version) + ")");

    w = detail::words(in.next("'fine VERTICES CHECKSUM'"));
    expect_words(w, 3, "'fine VERTICES CHECKSUM'");
    if (w[0] != "fine") in.fail("expected 'fine VERTICES CHECKSUM', not " + detail::quoted(w[0]));
    paths.fine_vertices = detail::parse_count(in, w[1], "vertex count");
    const auto parsed = std::from_chars(w[2].data(), w[2].data() + w[2].size(), paths.fine_checksum, 16);
    if (w[2].size() != 16 || parsed.ec != std::errc() || parsed.ptr != w[2].data() + w[2].size())
        in.fail("bad checksum " + detail::quoted(w[2]) + " (expected 16 hexadecimal digits)");

    w = detail::words(in.next("'coarse VERTICES EDGES'"));
    expect_words(w, 3, "'coarse VERTICES EDGES'");
    if (w[0] != "coarse") in.fail("expected 'coarse VERTICES EDGES', not " + detail::quoted(w[0]));
    paths.coarse_vertices = detail::parse_count(in, w[1], "vertex count");
    const int num_edges = detail::parse_count(in, w[2], "edge count");

    for (int e = 0; e < num_edges; ++e) {
        w = detail::words(in.next("an edge 'A B N V1 ... VN'"));
        if (w.size() < 3) in.fail("expected an edge 'A B N V1 ... VN'");
        DecimatedEdge edge;
        edge.a = detail::parse_count(in, w[0], "coarse vertex");
        edge.b = detail::parse_count(in, w[1], "coarse vertex");
        const int n = detail::parse_count(in, w[2], "path length");
        if (edge.b >= paths.coarse_vertices || edge.a >= edge.b)
            in.fail("bad edge (" + std::string(w[0]) + ", " + std::string(w[1]) + "): coarse vertices must be " +
                    "increasing and below " + std::to_string(paths.coarse_vertices));
        if (!paths.edges.empty() && std::tie(paths.edges.back().a, paths.edges.back().b) >= std::tie(edge.a, edge.b))
            in.fail("edges out of order or repeated");
        if (n < 2 || w.size() != static_cast<std::size_t>(n) + 3)
            in.fail("the path of edge (" + std::to_string(edge.a) + ", " + std::to_string(edge.b) + ") should list " +
                    std::to_string(n) + " fine vertices, at least 2; the line has " + std::to_string(w.size() - 3));
        for (int i = 0; i < n; ++i) {
            const int v = detail::parse_count(in, w[static_cast<std::size_t>(i) + 3], "fine vertex");
            if (v >= paths.fine_vertices)
                in.fail("fine vertex " + std::to_string(v) + " is out of range (" +
                        std::to_string(paths.fine_vertices) + " vertices)");
            edge.fine_path.push_back(v);
        }
        paths.edges.push_back(std::move(edge));
    }
    if (!in.at_end()) in.fail("unexpected content after the last edge");
    return paths;
}

}  // namespace geotri
