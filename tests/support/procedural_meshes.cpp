#include <geotri_test/procedural_meshes.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <stdexcept>
#include <utility>

namespace geotri::test {

namespace {

constexpr double pi = 3.14159265358979323846;

// Own mapping of the generator's bits to [0, 1): std::uniform_real_distribution differs between standard libraries.
double uniform01(std::mt19937& rng) { return static_cast<double>(rng() >> 5) * (1.0 / 134217728.0); }

double symmetric_unit(std::mt19937& rng) { return 2.0 * uniform01(rng) - 1.0; }

void add_quad(std::vector<std::array<int, 3>>& triangles, int v00, int v10, int v11, int v01, bool other_diagonal) {
    if (other_diagonal) {
        triangles.push_back({v00, v10, v01});
        triangles.push_back({v10, v11, v01});
    } else {
        triangles.push_back({v00, v10, v11});
        triangles.push_back({v00, v11, v01});
    }
}

void require_positive_flat_areas(const TriangleMesh& mesh) {
    for (const auto& t : mesh.triangles) {
        const Eigen::Vector3d& a = mesh.positions[t[0]];
        const Eigen::Vector3d& b = mesh.positions[t[1]];
        const Eigen::Vector3d& c = mesh.positions[t[2]];
        const double cross = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
        if (!(cross > 0.0)) throw std::logic_error("flat test mesh generator made a triangle that is not counter-clockwise");
    }
}

double clamp_perturbation(double perturbation) {
    if (perturbation < 0.0 || perturbation > 0.25)
        throw std::invalid_argument("perturbation must lie in [0, 0.25]");
    return perturbation;
}

}  // namespace

geodesic::Mesh TriangleMesh::to_mesh() const { return geodesic::Mesh(positions, triangles); }

TriangleMesh flat_grid(int nx, int ny, double width, double height, double perturbation, unsigned seed) {
    if (nx < 1 || ny < 1) throw std::invalid_argument("flat_grid needs at least one cell");
    clamp_perturbation(perturbation);
    std::mt19937 rng(seed);
    TriangleMesh mesh;
    const auto index = [nx](int i, int j) { return j * (nx + 1) + i; };
    for (int j = 0; j <= ny; ++j) {
        for (int i = 0; i <= nx; ++i) {
            double x = width * i / nx;
            double y = height * j / ny;
            if (perturbation > 0.0 && i > 0 && i < nx && j > 0 && j < ny) {
                x += perturbation * symmetric_unit(rng) * width / nx;
                y += perturbation * symmetric_unit(rng) * height / ny;
            }
            mesh.positions.emplace_back(x, y, 0.0);
        }
    }
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            add_quad(mesh.triangles, index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1),
                     (rng() & 1u) != 0);
    require_positive_flat_areas(mesh);
    return mesh;
}

TriangleMesh flat_cell_polygon(const std::vector<std::string>& rows, int subdivisions, double perturbation,
                               unsigned seed) {
    if (rows.empty() || subdivisions < 1) throw std::invalid_argument("flat_cell_polygon needs cells");
    clamp_perturbation(perturbation);
    const int num_rows = static_cast<int>(rows.size());
    int num_cols = 0;
    for (const auto& r : rows) num_cols = std::max(num_cols, static_cast<int>(r.size()));
    // Cell (cx, cy), cy counted from the bottom.
    const auto filled = [&](int cx, int cy) {
        if (cx < 0 || cy < 0 || cx >= num_cols || cy >= num_rows) return false;
        const std::string& r = rows[num_rows - 1 - cy];
        return cx < static_cast<int>(r.size()) && r[cx] == '#';
    };
    for (int cy = 0; cy <= num_rows; ++cy)
        for (int cx = 0; cx <= num_cols; ++cx) {
            const bool a = filled(cx - 1, cy - 1), b = filled(cx, cy - 1), c = filled(cx - 1, cy), d = filled(cx, cy);
            if ((a && d && !b && !c) || (b && c && !a && !d))
                throw std::invalid_argument("cells that touch only at a corner make a non-manifold vertex");
        }
    const int k = subdivisions;
    const int nx = num_cols * k, ny = num_rows * k;
    // Fine quad (qx, qy) is inside when its cell is filled.
    const auto quad_inside = [&](int qx, int qy) {
        if (qx < 0 || qy < 0 || qx >= nx || qy >= ny) return false;
        return filled(qx / k, qy / k);
    };
    std::mt19937 rng(seed);
    TriangleMesh mesh;
    std::vector<int> index((nx + 1) * (ny + 1), -1);
    for (int iy = 0; iy <= ny; ++iy) {
        for (int ix = 0; ix <= nx; ++ix) {
            const int around = quad_inside(ix - 1, iy - 1) + quad_inside(ix, iy - 1) + quad_inside(ix - 1, iy) +
                               quad_inside(ix, iy);
            if (around == 0) continue;
            double x = static_cast<double>(ix) / k;
            double y = static_cast<double>(iy) / k;
            if (around == 4 && perturbation > 0.0) {
                x += perturbation * symmetric_unit(rng) / k;
                y += perturbation * symmetric_unit(rng) / k;
            }
            index[iy * (nx + 1) + ix] = static_cast<int>(mesh.positions.size());
            mesh.positions.emplace_back(x, y, 0.0);
        }
    }
    const auto at = [&](int ix, int iy) { return index[iy * (nx + 1) + ix]; };
    for (int qy = 0; qy < ny; ++qy)
        for (int qx = 0; qx < nx; ++qx)
            if (quad_inside(qx, qy))
                add_quad(mesh.triangles, at(qx, qy), at(qx + 1, qy), at(qx + 1, qy + 1), at(qx, qy + 1),
                         (rng() & 1u) != 0);
    require_positive_flat_areas(mesh);
    return mesh;
}

std::vector<std::string> l_shape_cells() { return {"#..", "#..", "###"}; }
std::vector<std::string> u_shape_cells() { return {"#.#", "#.#", "###"}; }
std::vector<std::string> comb_cells() { return {"#.#.#", "#.#.#", "#####"}; }
std::vector<std::string> s_shape_cells() { return {"####", "...#", "####", "#...", "####"}; }
std::vector<std::string> square_with_hole_cells() { return {"###", "#.#", "###"}; }

TriangleMesh box(double a, double b, double c, int na, int nb, int nc, bool irregular_diagonals, unsigned seed) {
    if (na < 1 || nb < 1 || nc < 1) throw std::invalid_argument("box needs at least one division per axis");
    const std::array<int, 3> n{na, nb, nc};
    const std::array<double, 3> size{a, b, c};
    std::mt19937 rng(seed);
    TriangleMesh mesh;
    std::vector<int> index(static_cast<std::size_t>(na + 1) * (nb + 1) * (nc + 1), -1);
    const auto vertex = [&](const std::array<int, 3>& l) {
        int& slot = index[(static_cast<std::size_t>(l[2]) * (nb + 1) + l[1]) * (na + 1) + l[0]];
        if (slot < 0) {
            slot = static_cast<int>(mesh.positions.size());
            // Exact at both ends, so that the faces lie exactly in the planes of the box.
            const auto coordinate = [&](int axis) { return l[axis] == n[axis] ? size[axis] : size[axis] * l[axis] / n[axis]; };
            mesh.positions.emplace_back(coordinate(0), coordinate(1), coordinate(2));
        }
        return slot;
    };
    // Each face: the fixed axis and its side, and the two running axes (u, v) with u x v pointing outwards.
    struct Face {
        int fixed;
        bool far;
        int u;
        int v;
    };
    const Face faces[6] = {{2, false, 1, 0}, {2, true, 0, 1}, {1, false, 0, 2},
                           {1, true, 2, 0},  {0, false, 2, 1}, {0, true, 1, 2}};
    for (const Face& face : faces) {
        for (int j = 0; j < n[face.v]; ++j) {
            for (int i = 0; i < n[face.u]; ++i) {
                const auto lattice = [&](int di, int dj) {
                    std::array<int, 3> l{};
                    l[face.fixed] = face.far ? n[face.fixed] : 0;
                    l[face.u] = i + di;
                    l[face.v] = j + dj;
                    return l;
                };
                const int v00 = vertex(lattice(0, 0)), v10 = vertex(lattice(1, 0));
                const int v11 = vertex(lattice(1, 1)), v01 = vertex(lattice(0, 1));
                add_quad(mesh.triangles, v00, v10, v11, v01, irregular_diagonals && (rng() & 1u) != 0);
            }
        }
    }
    return mesh;
}

TriangleMesh cube(int n, double size, bool irregular_diagonals, unsigned seed) {
    return box(size, size, size, n, n, n, irregular_diagonals, seed);
}

TriangleMesh capped_cylinder(double radius, double height, int sides, int rows, int side_subdivisions) {
    if (sides < 3 || rows < 1 || side_subdivisions < 1) throw std::invalid_argument("capped_cylinder: bad counts");
    TriangleMesh mesh;
    const int columns = sides * side_subdivisions;
    std::vector<Eigen::Vector2d> ring;
    for (int j = 0; j < sides; ++j) {
        const double angle0 = 2.0 * pi * j / sides, angle1 = 2.0 * pi * ((j + 1) % sides) / sides;
        const Eigen::Vector2d c0(radius * std::cos(angle0), radius * std::sin(angle0));
        const Eigen::Vector2d c1(radius * std::cos(angle1), radius * std::sin(angle1));
        for (int s = 0; s < side_subdivisions; ++s) {
            const double t = static_cast<double>(s) / side_subdivisions;
            ring.push_back(s == 0 ? c0 : Eigen::Vector2d((1.0 - t) * c0 + t * c1));
        }
    }
    for (int i = 0; i <= rows; ++i) {
        const double z = height * i / rows;
        for (int col = 0; col < columns; ++col) mesh.positions.emplace_back(ring[col].x(), ring[col].y(), z);
    }
    const int bottom = static_cast<int>(mesh.positions.size());
    mesh.positions.emplace_back(0.0, 0.0, 0.0);
    const int top = bottom + 1;
    mesh.positions.emplace_back(0.0, 0.0, height);
    const auto at = [columns](int col, int row) { return row * columns + (col % columns); };
    for (int i = 0; i < rows; ++i)
        for (int col = 0; col < columns; ++col)
            add_quad(mesh.triangles, at(col, i), at(col + 1, i), at(col + 1, i + 1), at(col, i + 1), false);
    for (int col = 0; col < columns; ++col) {
        mesh.triangles.push_back({bottom, at(col + 1, 0), at(col, 0)});
        mesh.triangles.push_back({top, at(col, rows), at(col + 1, rows)});
    }
    return mesh;
}

TriangleMesh geodesic_sphere(int frequency, double radius) {
    if (frequency < 1) throw std::invalid_argument("geodesic_sphere needs frequency >= 1");
    const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
    const std::vector<Eigen::Vector3d> ico = {
        {-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0}, {0, -1, phi}, {0, 1, phi},
        {0, -1, -phi}, {0, 1, -phi}, {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}};
    std::vector<std::array<int, 3>> ico_faces = {
        {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (auto& f : ico_faces) {
        const Eigen::Vector3d normal = (ico[f[1]] - ico[f[0]]).cross(ico[f[2]] - ico[f[0]]);
        if (normal.dot(ico[f[0]] + ico[f[1]] + ico[f[2]]) < 0.0) std::swap(f[1], f[2]);
    }
    const int k = frequency;
    TriangleMesh mesh;
    // A lattice point is the integer combination (w0·A + w1·B + w2·C)/k; its key lists (corner, weight) sorted by
    // corner, so that points on shared edges and corners are made once, with bit-identical coordinates.
    std::map<std::array<int, 6>, int> made;
    const auto point = [&](const std::array<int, 3>& corners, const std::array<int, 3>& weights) {
        std::array<std::pair<int, int>, 3> terms{};
        for (int m = 0; m < 3; ++m) terms[m] = {weights[m] == 0 ? 1000 : corners[m], weights[m]};
        std::sort(terms.begin(), terms.end());
        std::array<int, 6> key{};
        for (int m = 0; m < 3; ++m) {
            key[2 * m] = terms[m].first;
            key[2 * m + 1] = terms[m].second;
        }
        auto it = made.find(key);
        if (it != made.end()) return it->second;
        Eigen::Vector3d p = Eigen::Vector3d::Zero();
        for (int m = 0; m < 3; ++m)
            if (terms[m].second > 0) p += static_cast<double>(terms[m].second) * ico[terms[m].first];
        p *= radius / p.norm();
        const int id = static_cast<int>(mesh.positions.size());
        mesh.positions.push_back(p);
        made.emplace(key, id);
        return id;
    };
    for (const auto& f : ico_faces) {
        const auto p = [&](int i, int j) { return point(f, {k - i - j, i, j}); };
        for (int j = 0; j < k; ++j) {
            for (int i = 0; i + j < k; ++i) {
                mesh.triangles.push_back({p(i, j), p(i + 1, j), p(i, j + 1)});
                if (i + j + 1 < k) mesh.triangles.push_back({p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)});
            }
        }
    }
    return mesh;
}

TriangleMesh icosphere(int level, double radius) {
    if (level < 0 || level > 12) throw std::invalid_argument("icosphere level out of range");
    return geodesic_sphere(1 << level, radius);
}

TriangleMesh torus(double major_radius, double minor_radius, int n_major, int n_minor) {
    if (n_major < 3 || n_minor < 3) throw std::invalid_argument("torus needs at least 3 x 3 quads");
    TriangleMesh mesh;
    for (int i = 0; i < n_major; ++i) {
        const double theta = 2.0 * pi * i / n_major;
        for (int j = 0; j < n_minor; ++j) {
            const double phi = 2.0 * pi * j / n_minor;
            const double ring = major_radius + minor_radius * std::cos(phi);
            mesh.positions.emplace_back(ring * std::cos(theta), ring * std::sin(theta), minor_radius * std::sin(phi));
        }
    }
    const auto at = [&](int i, int j) { return (i % n_major) * n_minor + (j % n_minor); };
    for (int i = 0; i < n_major; ++i)
        for (int j = 0; j < n_minor; ++j)
            add_quad(mesh.triangles, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), false);
    return mesh;
}

TriangleMesh perturbed_sphere(int frequency, double amplitude, unsigned seed) {
    if (amplitude < 0.0 || amplitude >= 0.5) throw std::invalid_argument("perturbed_sphere: amplitude in [0, 0.5)");
    TriangleMesh mesh = geodesic_sphere(frequency);
    std::mt19937 rng(seed);
    for (auto& p : mesh.positions) p *= 1.0 + amplitude * symmetric_unit(rng);
    return mesh;
}

TriangleMesh disjoint_union(const TriangleMesh& a, const TriangleMesh& b, const Eigen::Vector3d& offset) {
    TriangleMesh mesh = a;
    const int shift = static_cast<int>(a.positions.size());
    for (const auto& p : b.positions) mesh.positions.push_back(p + offset);
    for (const auto& t : b.triangles) mesh.triangles.push_back({t[0] + shift, t[1] + shift, t[2] + shift});
    return mesh;
}

double bounding_diagonal(const TriangleMesh& mesh) {
    if (mesh.positions.empty()) return 0.0;
    Eigen::Vector3d lo = mesh.positions.front(), hi = lo;
    for (const auto& p : mesh.positions) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    return (hi - lo).norm();
}

int nearest_vertex(const geodesic::Mesh& mesh, const Eigen::Vector3d& x) {
    int best = 0;
    for (int v = 1; v < mesh.num_vertices(); ++v)
        if ((mesh.position(v) - x).squaredNorm() < (mesh.position(best) - x).squaredNorm()) best = v;
    return best;
}

}  // namespace geotri::test
