// Tests of the MBM kernel's per-mesh tables and closed-form polyhedron field
// (modules/fields/MBM: PolyhedronTables, PolyhedronField; paper Eqs. 9-15).
// Every check is against an independent reference: brute-force quadrature of the face
// integrals, finite-difference identities (curl A = B, div B = 0, H = -grad phi), the
// closed-form cuboid field (reference/oracles/cuboidField.hpp), the uniformly magnetized
// sphere / dipole (reference/oracles/dipole.hpp), and exact solid-angle values.
#include <catch2/catch.hpp>

#include "PolyhedronField.hpp"
#include "PolyhedronTables.hpp"
#include "oracles/chargeQuadrature.hpp" // oracle::detail::gaussLegendre
#include "oracles/cuboidField.hpp"
#include "oracles/dipole.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <vector>

using namespace mag::mbm;

namespace {

struct Mesh {
    std::vector<Vec3> V;
    std::vector<std::array<int, 3>> T;
};

// Box with half sizes h, each face split into s x s squares (2 triangles each), CCW
// about the outward normal. s > 1 gives coplanar triangles and collinear boundary
// vertices that the tables must merge.
Mesh boxMesh(const Vec3& h, int s = 1, const Vec3& centre = Vec3::Zero()) {
    Mesh m;
    std::map<std::array<int, 3>, int> index;
    auto vertex = [&](std::array<int, 3> g) {
        auto it = index.find(g);
        if (it != index.end()) return it->second;
        const Vec3 p(centre.x() + h.x() * (2.0 * g[0] / s - 1.0),
                     centre.y() + h.y() * (2.0 * g[1] / s - 1.0),
                     centre.z() + h.z() * (2.0 * g[2] / s - 1.0));
        m.V.push_back(p);
        const int i = static_cast<int>(m.V.size()) - 1;
        index.emplace(g, i);
        return i;
    };
    for (int k = 0; k < 3; ++k)
        for (int sg = 0; sg <= 1; ++sg) {
            const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
            for (int i = 0; i < s; ++i)
                for (int j = 0; j < s; ++j) {
                    std::array<std::array<int, 3>, 4> q;
                    const int a[4] = {i, i + 1, i + 1, i}, b[4] = {j, j, j + 1, j + 1};
                    for (int c = 0; c < 4; ++c) {
                        q[c][k] = sg ? s : 0;
                        q[c][k1] = a[c];
                        q[c][k2] = b[c];
                    }
                    int v[4];
                    for (int c = 0; c < 4; ++c) v[c] = vertex(q[c]);
                    // (k1, k2, k) is right-handed: CCW about +e_k; reverse on the - face
                    if (!sg) std::swap(v[1], v[3]);
                    m.T.push_back({v[0], v[1], v[2]});
                    m.T.push_back({v[0], v[2], v[3]});
                }
        }
    return m;
}

// Icosphere of radius R: icosahedron subdivided k times, vertices on the sphere.
Mesh icosphere(double R, int k) {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    Mesh m;
    m.V = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
           {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    m.T = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
           {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
           {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
           {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (auto& v : m.V) v.normalize();
    for (int level = 0; level < k; ++level) {
        std::map<std::pair<int, int>, int> mid;
        auto midpoint = [&](int a, int b) {
            const auto key = std::minmax(a, b);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            m.V.push_back((m.V[a] + m.V[b]).normalized());
            const int i = static_cast<int>(m.V.size()) - 1;
            mid.emplace(key, i);
            return i;
        };
        std::vector<std::array<int, 3>> next;
        for (const auto& f : m.T) {
            const int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
            next.push_back({f[0], a, c});
            next.push_back({f[1], b, a});
            next.push_back({f[2], c, b});
            next.push_back({a, b, c});
        }
        m.T = next;
    }
    for (auto& v : m.V) v *= R;
    return m;
}

// Irregular tetrahedron (all faces different, no symmetry), outward oriented.
Mesh tetrahedron() {
    Mesh m;
    m.V = {{0.001, -0.002, 0.0005}, {0.011, 0.001, -0.001}, {0.002, 0.009, 0.0015},
           {0.003, 0.002, 0.012}};
    m.T = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
    return m;
}

// L-shaped prism (non-convex planar faces of 6 corners), 1 cm scale, height hz.
Mesh lPrism(double hz = 0.006) {
    const double u = 0.005;
    const Vec3 p[6] = {{0, 0, 0}, {2 * u, 0, 0}, {2 * u, u, 0}, {u, u, 0}, {u, 2 * u, 0}, {0, 2 * u, 0}};
    Mesh m;
    for (int i = 0; i < 6; ++i) m.V.push_back(p[i]);
    for (int i = 0; i < 6; ++i) m.V.push_back(p[i] + Vec3(0, 0, hz));
    // top (CCW about +z) and bottom (reversed) from a valid triangulation of the L
    const int tri[4][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 5}, {3, 4, 5}};
    for (const auto& t : tri) {
        m.T.push_back({t[0] + 6, t[1] + 6, t[2] + 6});
        m.T.push_back({t[0], t[2], t[1]});
    }
    for (int i = 0; i < 6; ++i) {
        const int j = (i + 1) % 6;
        m.T.push_back({i, j, j + 6});
        m.T.push_back({i, j + 6, i + 6});
    }
    return m;
}

// Integral of f over triangle (r0, r1, r2): 4^levels sub-triangles, collapsed
// Gauss-Legendre order x order on each (independent of the production rules).
template <class F, class T>
void triangleQuadrature(const Vec3& r0, const Vec3& r1, const Vec3& r2, int levels, int order,
                        F f, T& sum) {
    if (levels > 0) {
        const Vec3 a = 0.5 * (r0 + r1), b = 0.5 * (r1 + r2), c = 0.5 * (r2 + r0);
        triangleQuadrature(r0, a, c, levels - 1, order, f, sum);
        triangleQuadrature(a, r1, b, levels - 1, order, f, sum);
        triangleQuadrature(c, b, r2, levels - 1, order, f, sum);
        triangleQuadrature(a, b, c, levels - 1, order, f, sum);
        return;
    }
    Eigen::VectorXd x, w;
    oracle::detail::gaussLegendre(order, x, w);
    const double twiceArea = (r1 - r0).cross(r2 - r0).norm();
    for (int i = 0; i < order; ++i)
        for (int j = 0; j < order; ++j) {
            const double u = 0.5 * (x[i] + 1), v = 0.5 * (x[j] + 1);
            const Vec3 p = r0 + u * (r1 - r0) + u * v * (r2 - r1);
            sum += (0.25 * w[i] * w[j] * twiceArea * u) * f(p);
        }
}

double meshSize(const PolyhedronTables& t) { return 2.0 * t.boundingRadius(); }

// Minimum distance from r to any face PLANE (conservative "away from the boundary").
double planeDistance(const PolyhedronTables& t, const Vec3& r) {
    double d = 1e300;
    for (const auto& f : t.faces()) d = std::min(d, std::abs(f.normal.dot(r) - f.offset));
    return d;
}

const Vec3 kM(0.3e6, -0.5e6, 0.7e6); // a generic magnetization (A/m), ~1.1 T

} // namespace

TEST_CASE("tables: a box's 12 triangles become 6 squares with 12 edges", "[mbm][tables]") {
    const Mesh m = boxMesh(Vec3(0.005, 0.004, 0.003));
    const PolyhedronTables t(m.V, m.T);
    REQUIRE(t.faces().size() == 6);
    REQUIRE(t.edges().size() == 12);
    REQUIRE(t.triangles().size() == 12);
    // volume exact up to rounding: 8 h_x h_y h_z
    CHECK(t.volume() == Approx(8 * 0.005 * 0.004 * 0.003).epsilon(1e-14));
    CHECK(t.centroid().norm() < 1e-17);
    for (std::size_t f = 0; f < t.faces().size(); ++f) {
        const PolyFace& face = t.faces()[f];
        CHECK(face.loops.size() == 1);
        CHECK(face.loops[0].size() == 4);
        CHECK(t.edgesOf(static_cast<int>(f)).size() == 4);
        for (const FaceEdge& fe : t.edgesOf(static_cast<int>(f))) {
            const PolyEdge& e = t.edges()[fe.edge];
            const Vec3 mid = 0.5 * (t.vertices()[e.v0] + t.vertices()[e.v1]);
            // n_p x u_e: unit, in the face plane, pointing into the face
            CHECK(fe.inward.norm() == Approx(1.0).epsilon(1e-15));
            CHECK(std::abs(fe.inward.dot(face.normal)) < 1e-15);
            CHECK(fe.inward.dot(face.centroid - mid) > 0.0);
            CHECK((fe.reversed ? e.face1 : e.face0) == static_cast<int>(f));
        }
    }
    // edge-major: both faces of each edge differ and see opposite directions
    for (const auto& e : t.edges()) {
        CHECK(e.face0 != e.face1);
        CHECK(e.length > 0.0);
    }
}

TEST_CASE("tables: coplanar merging on subdivided boxes and non-convex faces",
          "[mbm][tables]") {
    // 3 x 3 squares per face: 108 triangles -> 6 faces; each box edge has 3 segments
    const Mesh m = boxMesh(Vec3(0.005, 0.005, 0.005), 3);
    const PolyhedronTables t(m.V, m.T);
    CHECK(t.faces().size() == 6);
    CHECK(t.edges().size() == 36);
    for (const auto& f : t.faces()) {
        CHECK(f.loops.size() == 1);
        CHECK(f.loops[0].size() == 12);
        CHECK(f.area == Approx(1e-4).epsilon(1e-13));
    }
    // L prism: top and bottom are 6-corner non-convex polygons
    const Mesh l = lPrism();
    const PolyhedronTables tl(l.V, l.T);
    CHECK(tl.faces().size() == 8);
    CHECK(tl.edges().size() == 18);
    CHECK(tl.volume() == Approx(3 * 0.005 * 0.005 * 0.006).epsilon(1e-13));
    // icosphere: no two triangles coplanar
    const Mesh s = icosphere(0.01, 2);
    const PolyhedronTables ts(s.V, s.T);
    CHECK(ts.faces().size() == s.T.size());
    CHECK(ts.edges().size() == 3 * s.T.size() / 2);
}

TEST_CASE("tables: unusable meshes throw std::invalid_argument with a clear message",
          "[mbm][tables]") {
    const Mesh box = boxMesh(Vec3(0.005, 0.005, 0.005));
    auto message = [](const Mesh& m) {
        try {
            PolyhedronTables t(m.V, m.T);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no exception");
    };
    Mesh open = box;
    open.T.pop_back();
    CHECK_THAT(message(open), Catch::Contains("open"));
    Mesh twice = box;
    twice.T.push_back(box.T[0]); // an edge used three times / same direction twice
    CHECK_THAT(message(twice), Catch::Contains("non-manifold"));
    Mesh flipped = box;
    std::swap(flipped.T[3][1], flipped.T[3][2]);
    CHECK_THAT(message(flipped), Catch::Contains("non-manifold or inconsistently oriented"));
    Mesh inward = box;
    for (auto& t : inward.T) std::swap(t[1], t[2]);
    CHECK_THAT(message(inward), Catch::Contains("inwards"));
    Mesh range = box;
    range.T[0][0] = 99;
    CHECK_THAT(message(range), Catch::Contains("outside"));
    Mesh degenerate = box;
    degenerate.T[0] = {0, 0, 1};
    CHECK_THAT(message(degenerate), Catch::Contains("repeats a vertex"));
    Mesh collinear;
    collinear.V = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}};
    collinear.T = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}};
    CHECK_THAT(message(collinear), Catch::Contains("degenerate"));
    CHECK_THAT(message(Mesh{}), Catch::Contains("no triangles"));
    // unused vertices are fine (dropped)
    Mesh extra = box;
    extra.V.push_back(Vec3(1, 2, 3));
    CHECK(PolyhedronTables(extra.V, extra.T).vertices().size() == 8);
}

TEST_CASE("W_p, grad W_p and Omega_p match brute-force quadrature off the face",
          "[mbm][field]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    for (const Mesh& m : {tetrahedron(), lPrism(), boxMesh(Vec3(0.005, 0.003, 0.004))}) {
        const PolyhedronTables t(m.V, m.T);
        const double L = meshSize(t);
        for (int f = 0; f < static_cast<int>(t.faces().size()); ++f) {
            const PolyFace& face = t.faces()[f];
            for (int trial = 0; trial < 6; ++trial) {
                // points at 0.3 to 1 mesh sizes from the face plane, and in the plane
                // outside the face (trial 0): the integrands are smooth there
                Vec3 r = face.centroid + 0.6 * L * Vec3(uni(rng), uni(rng), uni(rng));
                const double h = face.normal.dot(r) - face.offset;
                if (trial == 0) {
                    r -= h * face.normal;
                    const Vec3 away = (r - face.centroid) - face.normal.dot(r - face.centroid) * face.normal;
                    r = face.centroid + away.normalized() * 1.2 * L;
                } else if (std::abs(h) < 0.3 * L) {
                    r += (0.3 * L - std::abs(h)) * (h >= 0 ? 1.0 : -1.0) * face.normal;
                }
                double W = 0.0, Om = 0.0;
                Vec3 gradW = Vec3::Zero();
                for (int i = face.triBegin; i < face.triEnd; ++i) {
                    const auto& tri = t.triangles()[i];
                    const Vec3 &r0 = t.vertices()[tri.v[0]], &r1 = t.vertices()[tri.v[1]],
                               &r2 = t.vertices()[tri.v[2]];
                    triangleQuadrature(r0, r1, r2, 2, 16,
                                       [&](const Vec3& p) { return 1.0 / (p - r).norm(); }, W);
                    triangleQuadrature(
                        r0, r1, r2, 2, 16,
                        [&](const Vec3& p) { return Vec3((p - r) / std::pow((p - r).norm(), 3)); },
                        gradW);
                    // Omega_p = int (r' - r) . n_p / |r' - r|^3: positive on the inner side
                    triangleQuadrature(r0, r1, r2, 2, 16,
                                       [&](const Vec3& p) {
                                           return (p - r).dot(face.normal) /
                                                  std::pow((p - r).norm(), 3);
                                       },
                                       Om);
                }
                const FaceIntegrals fi = faceIntegrals(t, f, r);
                // quadrature is converged to ~1e-13 at >= 0.3 sizes (16 x 16 points on each
                // of 16 sub-triangles per triangle): 1e-10 leaves margin
                CHECK(std::abs(fi.W - W) <= 1e-10 * std::abs(W));
                CHECK((fi.gradW - gradW).norm() <= 1e-10 * gradW.norm());
                CHECK(std::abs(fi.solidAngle - Om) <= 1e-10 * (std::abs(Om) + 1e-3));
            }
        }
    }
}

TEST_CASE("evaluate: B and S = sum W_p n_p match quadrature of the face integrals",
          "[mbm][field]") {
    // The fast edge-major path against sums of brute-force face integrals (Eqs. 9, 11).
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    for (const Mesh& m : {tetrahedron(), lPrism()}) {
        const PolyhedronTables t(m.V, m.T);
        const double L = meshSize(t);
        int tested = 0;
        while (tested < 10) {
            const Vec3 r = t.centroid() + 1.2 * L * Vec3(uni(rng), uni(rng), uni(rng));
            if (planeDistance(t, r) < 0.25 * L) continue;
            ++tested;
            Vec3 S = Vec3::Zero(), B = Vec3::Zero();
            for (const auto& face : t.faces()) {
                double W = 0.0;
                Vec3 gW = Vec3::Zero();
                for (int i = face.triBegin; i < face.triEnd; ++i) {
                    const auto& tri = t.triangles()[i];
                    const Vec3 &r0 = t.vertices()[tri.v[0]], &r1 = t.vertices()[tri.v[1]],
                               &r2 = t.vertices()[tri.v[2]];
                    triangleQuadrature(r0, r1, r2, 2, 16,
                                       [&](const Vec3& p) { return 1.0 / (p - r).norm(); }, W);
                    triangleQuadrature(
                        r0, r1, r2, 2, 16,
                        [&](const Vec3& p) { return Vec3((p - r) / std::pow((p - r).norm(), 3)); },
                        gW);
                }
                S += W * face.normal;
                B += mu0 / (4 * M_PI) * gW.cross(kM.cross(face.normal));
            }
            const PointField f = evaluate(t, kM, r);
            // quadrature converged to ~1e-13 relative; sums over faces cancel at most
            // one digit here (points within ~1.2 sizes)
            CHECK((f.S - S).norm() <= 1e-10 * S.norm());
            CHECK((f.B - B).norm() <= 1e-10 * (B.norm() + 1e-3));
            CHECK((f.A - mu0 / (4 * M_PI) * kM.cross(S)).norm() <=
                  1e-10 * mu0 / (4 * M_PI) * kM.norm() * S.norm());
        }
    }
}

TEST_CASE("curl A = B, div B = 0 and H = -grad phi by central differences",
          "[mbm][field]") {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    for (const Mesh& m : {tetrahedron(), lPrism(), icosphere(0.006, 1)}) {
        const PolyhedronTables t(m.V, m.T);
        const double L = meshSize(t);
        const double h = 1e-5 * L; // truncation ~(h/dist)^2 ~ 1e-8, roundoff ~eps A/h ~ 1e-11
        int inside = 0, outside = 0;
        for (int trial = 0; trial < 100000 && (inside < 15 || outside < 15); ++trial) {
            const Vec3 r = t.centroid() + 0.6 * L * Vec3(uni(rng), uni(rng), uni(rng));
            if (planeDistance(t, r) < 0.05 * L) continue;
            const PointField c = evaluate(t, kM, r);
            const bool in = c.insideFraction > 0.5;
            if ((in && inside >= 15) || (!in && outside >= 15)) continue;
            (in ? inside : outside)++;
            Vec3 dA[3], dB[3], gradPhi;
            for (int j = 0; j < 3; ++j) {
                Vec3 e = Vec3::Zero();
                e[j] = h;
                const PointField p = evaluate(t, kM, Vec3(r + e));
                const PointField q = evaluate(t, kM, Vec3(r - e));
                dA[j] = (p.A - q.A) / (2 * h);
                dB[j] = (p.B - q.B) / (2 * h);
                gradPhi[j] = (p.scalarPotential - q.scalarPotential) / (2 * h);
            }
            const Vec3 curlA(dA[1].z() - dA[2].y(), dA[2].x() - dA[0].z(), dA[0].y() - dA[1].x());
            const double divB = dB[0].x() + dB[1].y() + dB[2].z();
            const double scale = mu0 * kM.norm(); // ~1 T
            // 1e-6 of mu0 |M|: well above the FD errors estimated above
            CHECK((curlA - c.B).norm() <= 1e-6 * scale);
            CHECK(std::abs(divB) * L <= 1e-6 * scale);
            const Vec3 H = chargeField(c.B, kM, c.insideFraction);
            CHECK((-gradPhi - H).norm() <= 1e-6 * kM.norm());
        }
        CHECK(inside == 15);
        CHECK(outside == 15);
    }
}

TEST_CASE("solid angles: sum Omega_p = 4 pi inside, 0 outside, fractions on the boundary",
          "[mbm][field]") {
    const double a = 0.005;
    const Mesh m = boxMesh(Vec3(a, a, a));
    const PolyhedronTables t(m.V, m.T);
    auto frac = [&](const Vec3& r) { return evaluate(t, kM, r).insideFraction; };
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> uni(-3 * a, 3 * a);
    for (int i = 0; i < 500; ++i) {
        const Vec3 r(uni(rng), uni(rng), uni(rng));
        const bool in = r.cwiseAbs().maxCoeff() < a;
        // atan2 sums are exact to a few ulp of 4 pi
        CHECK(std::abs(frac(r) - (in ? 1.0 : 0.0)) < 1e-14);
    }
    // exactly on the boundary: the interior solid-angle fraction (principal values)
    CHECK(frac(Vec3(0.001, -0.002, a)) == Approx(0.5).epsilon(1e-14));     // face
    CHECK(frac(Vec3(0, 0, -a)) == Approx(0.5).epsilon(1e-14));             // face centre (diagonal)
    CHECK(frac(Vec3(a, 0.001, a)) == Approx(0.25).epsilon(1e-14));         // edge
    CHECK(frac(Vec3(a, a, a)) == Approx(0.125).epsilon(1e-14));            // vertex
    CHECK(frac(Vec3(-a, -a, -a)) == Approx(0.125).epsilon(1e-14));
    // icosphere vertices (convex): fraction = interior cone's solid angle / 4 pi, which
    // for a convex cone of n faces is (sum of interior dihedral angles - (n - 2) pi)
    const Mesh s = icosphere(0.01, 3);
    const PolyhedronTables ts(s.V, s.T);
    for (int v : {5, 100, 641}) {
        std::map<int, std::pair<int, Vec3>> next; // p -> (q, normal) for triangles (v, p, q)
        for (const auto& tri : s.T)
            for (int k = 0; k < 3; ++k)
                if (tri[k] == v) {
                    const int p = tri[(k + 1) % 3], q = tri[(k + 2) % 3];
                    const Vec3 n = (s.V[p] - s.V[v]).cross(s.V[q] - s.V[v]).normalized();
                    next[p] = {q, n};
                }
        std::vector<Vec3> normals;
        int p = next.begin()->first;
        for (std::size_t i = 0; i < next.size(); ++i) {
            normals.push_back(next[p].second);
            p = next[p].first;
        }
        double sum = 0.0;
        const std::size_t n = normals.size();
        for (std::size_t i = 0; i < n; ++i)
            sum += M_PI - std::acos(std::clamp(normals[i].dot(normals[(i + 1) % n]), -1.0, 1.0));
        const double expected = (sum - (double(n) - 2.0) * M_PI) / (4 * M_PI);
        // acos near 1 (dihedral ~ pi) loses ~1e-9 (sqrt(eps)); the kernel is exact to ulps
        CHECK(evaluate(ts, kM, s.V[v]).insideFraction == Approx(expected).epsilon(1e-8));
    }
    // L prism: on the reflex (interior angle 270 deg) edge: 3/4
    const Mesh l = lPrism();
    const PolyhedronTables tl(l.V, l.T);
    CHECK(evaluate(tl, kM, Vec3(0.005, 0.005, 0.003)).insideFraction ==
          Approx(0.75).epsilon(1e-14));
}

TEST_CASE("points within rounding of a merged face keep their side", "[mbm][field]") {
    // A rotated box whose faces are 3 x 3 squares (18 coplanar triangles each): the
    // face's solid angle is one atan2 of a product of 18 complex factors, which must not
    // wrap from +2 pi to -2 pi when the point is a few ulps from the plane.
    Mesh m = boxMesh(Vec3(0.005, 0.004, 0.003), 3);
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.9, Vec3(-1, 2, 0.3).normalized()).toRotationMatrix();
    for (auto& v : m.V) v = R * v + Vec3(0.001, 0.002, -0.003);
    const PolyhedronTables t(m.V, m.T);
    std::mt19937 rng(23);
    std::uniform_real_distribution<double> uni(-0.9, 0.9);
    for (const auto& f : t.faces()) {
        // two in-plane directions of the face
        const Vec3 e1 = f.normal.unitOrthogonal(), e2 = f.normal.cross(e1);
        for (int i = 0; i < 20; ++i) {
            // a point well inside the face (within 0.9 of the inscribed radius ~ 3 mm)
            const Vec3 p = f.centroid + 0.0027 * (uni(rng) * e1 + uni(rng) * e2) / std::sqrt(2.0);
            for (double off : {1e-16, 1e-15, 1e-13, 1e-10}) {
                const double in = evaluate(t, kM, Vec3(p - off * f.normal)).insideFraction;
                const double out = evaluate(t, kM, Vec3(p + off * f.normal)).insideFraction;
                // inside: 1 - O(off / size), or 1/2 where |h| is within rounding (on the
                // plane); never the wrong side
                CHECK(((std::abs(in - 1) < 1e-6) || (std::abs(in - 0.5) < 1e-14)));
                CHECK(((std::abs(out) < 1e-6) || (std::abs(out - 0.5) < 1e-14)));
                if (off >= 1e-13) {
                    CHECK(std::abs(in - 1) < 1e-6); // beyond rounding: the true side
                    CHECK(std::abs(out) < 1e-6);
                }
            }
        }
    }
}

TEST_CASE("box field equals the closed-form cuboid field (>= 1000 points)", "[mbm][field]") {
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    // axis-aligned and rotated boxes, general magnetizations
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    for (int rotated = 0; rotated <= 1; ++rotated) {
        oracle::Cuboid c;
        c.halfSize = Vec3(0.005, 0.003, 0.002);
        c.centre = rotated ? Vec3(0.001, -0.002, 0.003) : Vec3::Zero();
        c.R = rotated ? R : Eigen::Matrix3d::Identity();
        c.M = kM;
        Mesh m = boxMesh(c.halfSize);
        for (auto& v : m.V) v = c.centre + c.R * v;
        const PolyhedronTables t(m.V, m.T);
        double maxErr = 0.0;
        int n = 0;
        while (n < 1200) {
            // half the points inside, half outside up to 3 half-sizes away
            const Vec3 local = (n % 2 ? 1.0 : 3.0) * c.halfSize.cwiseProduct(
                                                          Vec3(uni(rng), uni(rng), uni(rng)));
            // "away from edges": distance to every edge line >= 1e-3 of the box size
            const Vec3 d = (local.cwiseAbs() - c.halfSize).cwiseAbs();
            const double tol = 1e-3 * 2 * c.halfSize.maxCoeff();
            if ((d.x() < tol && d.y() < tol) || (d.y() < tol && d.z() < tol) ||
                (d.z() < tol && d.x() < tol))
                continue;
            ++n;
            const Vec3 r = c.centre + c.R * local;
            const PointField f = evaluate(t, kM, r);
            const Vec3 Bo = oracle::cuboidB(c, r);
            const Vec3 Ho = oracle::cuboidH(c, r);
            const double err = (f.B - Bo).norm() / Bo.norm();
            maxErr = std::max(maxErr, err);
            // both closed forms are accurate to ~1e-14 here; 1e-10 is the brief's bar
            CHECK(err <= 1e-10);
            CHECK((chargeField(f.B, kM, f.insideFraction) - Ho).norm() <= 1e-10 * Ho.norm());
        }
        std::printf("box vs cuboid closed form (%s): max relative error %.2e\n",
                    rotated ? "rotated" : "axis-aligned", maxErr);
    }
}

TEST_CASE("icosphere: dipole M V outside and 2/3 mu0 M inside at second order",
          "[mbm][field]") {
    const double R = 0.01;
    const Vec3 M(0, 0, 1.0 / mu0); // 1 T
    const Vec3 outsidePoints[] = {{0.02, 0.003, 0.011}, {-0.005, 0.025, -0.01}, {0, 0, 0.03}};
    const Vec3 insidePoints[] = {{0.001, 0.002, -0.001}, {-0.003, 0, 0.002}};
    double prevOut = 0.0, prevIn = 0.0;
    for (int k = 1; k <= 4; ++k) {
        const Mesh m = icosphere(R, k);
        const PolyhedronTables t(m.V, m.T);
        double errOut = 0.0, errIn = 0.0;
        for (const Vec3& r : outsidePoints) {
            const Vec3 Bd = oracle::dipoleB(M * t.volume(), Vec3::Zero(), r);
            const Vec3 Bs = oracle::sphereB(Vec3::Zero(), R, M, r);
            errOut = std::max(errOut, (evaluate(t, M, r).B - Bs).norm() / Bs.norm());
            // with the polyhedron's own volume only the shape (l >= 6 multipoles) differs
            CHECK((evaluate(t, M, r).B - Bd).norm() <= 0.02 * errOut * Bd.norm() + 1e-12);
        }
        for (const Vec3& r : insidePoints)
            errIn = std::max(errIn, (evaluate(t, M, r).B - 2.0 / 3.0 * mu0 * M).norm() /
                                        (2.0 / 3.0 * mu0 * M.norm()));
        std::printf("icosphere k=%d (%zu triangles): error outside %.3e inside %.3e", k,
                    m.T.size(), errOut, errIn);
        if (k > 1) {
            const double rateOut = std::log2(prevOut / errOut), rateIn = std::log2(prevIn / errIn);
            std::printf("  rates %.2f %.2f", rateOut, rateIn);
            // second order in the edge length (halved per subdivision): rate -> 2
            CHECK(rateOut > 1.8);
            CHECK(rateIn > 1.8);
        }
        std::printf("\n");
        prevOut = errOut;
        prevIn = errIn;
    }
}

TEST_CASE("values are finite and principal on the source's faces, edges and vertices",
          "[mbm][field]") {
    for (const Mesh& m : {boxMesh(Vec3(0.005, 0.005, 0.005)), tetrahedron(), lPrism(),
                          icosphere(0.01, 2), boxMesh(Vec3(0.005, 0.003, 0.002), 2)}) {
        const PolyhedronTables t(m.V, m.T);
        std::vector<Vec3> pts;
        for (const auto& v : t.vertices()) pts.push_back(v);
        for (const auto& e : t.edges()) {
            const Vec3 r0 = t.vertices()[e.v0];
            for (double s : {0.5, 1e-9, 1.0 - 1e-12, 0.3}) pts.push_back(r0 + s * e.delta);
            // just off the edge: 1e-13 m
            pts.push_back(r0 + 0.4 * e.delta + 1e-13 * e.inward0);
        }
        for (const auto& f : t.faces()) pts.push_back(f.centroid);
        for (const auto& tri : t.triangles())
            pts.push_back((t.vertices()[tri.v[0]] + t.vertices()[tri.v[1]]) / 2.0 * 0.75 +
                          0.25 * t.vertices()[tri.v[2]]);
        std::vector<Vec3> B(pts.size()), A(pts.size());
        std::vector<double> f(pts.size()), phi(pts.size());
        evaluate(t, kM, pts, FieldOutputs{B, A, f, phi, {}});
        for (std::size_t i = 0; i < pts.size(); ++i) {
            CHECK(B[i].allFinite());
            CHECK(A[i].allFinite());
            CHECK(std::isfinite(f[i]));
            CHECK(std::isfinite(phi[i]));
            CHECK(f[i] >= -1e-14);
            CHECK(f[i] <= 1.0 + 1e-14);
        }
    }
    // On a face (off edges): the principal value is the mean of both one-sided limits,
    // for B, H and the inside fraction; A is continuous.
    const double a = 0.005;
    const Mesh m = boxMesh(Vec3(a, a, a));
    const PolyhedronTables t(m.V, m.T);
    for (const Vec3& r : {Vec3(0.001, 0.002, a), Vec3(-a, 0.0, 0.0), Vec3(0.0031, a, -0.004)}) {
        Vec3 normal = Vec3::Zero(); // outward normal of the face r lies on
        for (int k = 0; k < 3; ++k)
            if (std::abs(r[k]) == a) normal[k] = r[k] > 0 ? 1 : -1;
        const double eps = 1e-9; // one-sided limits to O(eps / a) = 2e-7
        const PointField on = evaluate(t, kM, r);
        const PointField in = evaluate(t, kM, Vec3(r - eps * normal));
        const PointField out = evaluate(t, kM, Vec3(r + eps * normal));
        CHECK(on.insideFraction == Approx(0.5).epsilon(1e-14));
        CHECK((on.B - 0.5 * (in.B + out.B)).norm() <= 1e-6 * mu0 * kM.norm());
        CHECK((on.A - in.A).norm() <= 1e-6 * on.A.norm());
        CHECK((on.A - out.A).norm() <= 1e-6 * on.A.norm());
        // the normal component of B is continuous, the tangential one jumps by mu0 M_t
        const Vec3 jump = out.B - in.B;
        CHECK(std::abs(jump.dot(normal)) <= 1e-5 * mu0 * kM.norm());
        CHECK((jump + mu0 * (kM - kM.dot(normal) * normal)).norm() <= 1e-5 * mu0 * kM.norm());
    }
}

TEST_CASE("edge term: stable forms agree with the asinh form near and far",
          "[mbm][field]") {
    // Independent reference: omega = asinh(x/rho) + asinh((L - x)/rho) for a point at
    // distance rho from the line and abscissa x (0 <= x <= L: no cancellation), in long
    // double. Edge along x with exactly representable inputs: a x delta is exact, so the
    // stable form must be accurate to a few ulp even at rho = 1e-8 L, where the literal
    // Eq. 14 has lost everything (S - L ~ rho^2/L against eps L).
    const double L = 0.0125;
    const Vec3 r1(0.0, 0.0, 0.0), r2(L, 0.0, 0.0), d = r2 - r1;
    for (double rho : {1e-1, 1e-3, 1e-5, 1e-7, 1e-8, 2e-9}) {
        for (double x : {0.5, 0.125, 0.9990234375, 0.0009765625}) {
            const Vec3 r(x * L, rho * L, 0.0);
            const Vec3 a = r1 - r, b = r2 - r;
            const double w = edgeLogTerm(a, b, a.norm(), b.norm(), L, d);
            const long double X = static_cast<long double>(r.x()) / L;
            const long double Rho = static_cast<long double>(r.y()) / L;
            const long double ref = std::asinh(X / Rho) + std::asinh((1.0L - X) / Rho);
            // a few ulp of the log argument: 1e-14 relative
            CHECK(std::abs(w - static_cast<double>(ref)) <= 1e-14 * static_cast<double>(ref));
        }
    }
    // General orientation: a x delta carries eps |a| |delta| rounding, i.e. an error
    // ~ 2 eps x / rho in omega; still far better than the literal form's O(1).
    const Vec3 g1(0.001, 0.002, -0.003), g2(0.011, -0.002, 0.004);
    const Vec3 gd = g2 - g1;
    const double gL = gd.norm();
    const Vec3 perp = gd.cross(Vec3(0, 0, 1)).normalized();
    for (double rho : {1e-3, 1e-6, 1e-8}) {
        const Vec3 r = g1 + 0.4 * gd + rho * gL * perp;
        const Vec3 a = g1 - r, b = g2 - r;
        const double w = edgeLogTerm(a, b, a.norm(), b.norm(), gL, gd);
        // reference from the actual (rounded) point, in long double
        const long double ax = a.x(), ay = a.y(), az = a.z();
        const long double dx = gd.x(), dy = gd.y(), dz = gd.z();
        const long double cx = ay * dz - az * dy, cy = az * dx - ax * dz, cz = ax * dy - ay * dx;
        const long double LL = std::sqrt(dx * dx + dy * dy + dz * dz);
        const long double Rho = std::sqrt(cx * cx + cy * cy + cz * cz) / LL;
        const long double X = -(ax * dx + ay * dy + az * dz) / LL;
        const long double ref = std::asinh(X / Rho) + std::asinh((LL - X) / Rho);
        CHECK(std::abs(w - static_cast<double>(ref)) <= 1e-14 * static_cast<double>(ref) + 4e-16 / rho);
    }
    // Far away (log1p form) vs the asinh form sideways, up to 1e4 lengths.
    for (double dist : {10.0, 1e3, 1e4}) {
        const Vec3 r(0.25 * L, dist * L, 0.0);
        const Vec3 a = r1 - r, b = r2 - r;
        const double w = edgeLogTerm(a, b, a.norm(), b.norm(), L, d);
        const long double Rho = static_cast<long double>(r.y()) / L;
        const long double ref = std::asinh(0.25L / Rho) + std::asinh(0.75L / Rho);
        CHECK(std::abs(w - static_cast<double>(ref)) <= 1e-14 * static_cast<double>(ref));
    }
    // Near a vertex, beyond the end: ln((S + L)/(S - L)) with S - L = 2 x' on the line,
    // once x' is well above delta L; at x' ~ delta L the regularized value (the point
    // moved to delta L off the line), long double reference.
    for (double xp : {1e-3, 1e-6, 1e-9, 1e-12}) {
        const Vec3 r(-xp * L, 0.0, 0.0);
        const Vec3 a = r1 - r, b = r2 - r;
        const double w = edgeLogTerm(a, b, a.norm(), b.norm(), L, d);
        const long double X = static_cast<long double>(r.x()) / L, Rho = kEdgeRegularization;
        const long double R1 = std::sqrt(X * X + Rho * Rho);
        const long double R2 = std::sqrt((1 - X) * (1 - X) + Rho * Rho);
        const long double ref = std::log((R1 + R2 + 1) / (R1 + R2 - 1));
        // long double S - L keeps >= 8 digits at x' >= 1e-12 (S - L >= 2e-12)
        CHECK(w == Approx(static_cast<double>(ref)).epsilon(1e-8));
    }
    // Regularized (distance to the line below delta L): the point is moved to delta L
    // off the line, so on the segment omega = asinh(x/delta) + asinh((1 - x)/delta),
    // continuous up to the vertex (ln(2/delta) there), finite on the line beyond.
    const double dl = kEdgeRegularization;
    for (double x : {0.0, 1.0, 0.5, 0.25, 1e-12, 1e-9, 1.0 - 1e-10}) {
        for (double rho : {0.0, 0.3 * dl}) {
            const Vec3 r(x * L, rho * L, 0.0);
            const Vec3 a = r1 - r, b = r2 - r;
            const double w = edgeLogTerm(a, b, a.norm(), b.norm(), L, d);
            const long double X = static_cast<long double>(r.x()) / L;
            const long double ref = std::asinh(X / dl) + std::asinh((1.0L - X) / dl);
            // omega varies on the scale delta L here: an ulp of x (eps L) moves it by
            // ~eps/delta = 2e-7; that conditioning is all the tolerance allows for
            CHECK(std::abs(w - static_cast<double>(ref)) <= 1e-12 * static_cast<double>(ref) + 4 * 2.2e-16 / dl);
        }
    }
    for (double x : {-0.5, 1.5, -1e-12, 1.0 + 1e-12}) {
        const Vec3 r(x * L, 0.0, 0.0);
        const Vec3 a = r1 - r, b = r2 - r;
        const double w = edgeLogTerm(a, b, a.norm(), b.norm(), L, d);
        CHECK(std::isfinite(w));
        CHECK(w > 0.0);
        CHECK(w <= std::log(2.0 / dl) + 1e-9);
        if (x == -0.5 || x == 1.5) CHECK(w == Approx(std::log(3.0)).epsilon(1e-14));
    }
}

TEST_CASE("far field: the stable forms follow the dipole out to 1e3 sizes", "[mbm][field]") {
    const double a = 0.005;
    const Mesh m = boxMesh(Vec3(a, a, a));
    const PolyhedronTables t(m.V, m.T);
    const Vec3 dir = Vec3(0.3, -0.5, 0.8).normalized();
    for (double sizes : {10.0, 100.0, 1000.0}) {
        const Vec3 r = sizes * 2 * a * dir;
        const Vec3 Bd = oracle::dipoleB(kM * t.volume(), Vec3::Zero(), r);
        const double err = (evaluate(t, kM, r).B - Bd).norm() / Bd.norm();
        std::printf("cube far field at %g sizes: relative difference to the dipole %.2e\n", sizes,
                    err);
        // a cube has no quadrupole: the physical difference is O((a/r)^4) (measured 1.1e-5
        // at 10 sizes, 1.1e-9 at 100); the rounding error of the stable forms grows like
        // eps (r/a)^2 (~2e-10 at 1e3 sizes), the literal forms' like eps (r/a)^3 (1e-7)
        const double tol = 0.2 / std::pow(sizes, 4) + 1e-15 * sizes * sizes;
        CHECK(err <= tol);
    }
}

TEST_CASE("evaluate: speed on a 12-triangle cube", "[.][benchmark][mbm]") {
    const Mesh m = boxMesh(Vec3(0.005, 0.005, 0.005));
    const PolyhedronTables t(m.V, m.T);
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> uni(-0.02, 0.02);
    std::vector<Vec3> pts(200000), B(pts.size()), A(pts.size());
    std::vector<double> f(pts.size());
    for (auto& p : pts) p = Vec3(uni(rng), uni(rng), uni(rng));
    for (int rep = 0; rep < 3; ++rep) {
        auto t0 = std::chrono::steady_clock::now();
        evaluate(t, kM, pts, B);
        auto t1 = std::chrono::steady_clock::now();
        evaluate(t, kM, pts, B, A, f);
        auto t2 = std::chrono::steady_clock::now();
        std::printf("B only: %.1f ns/point   B, A, fraction: %.1f ns/point\n",
                    std::chrono::duration<double, std::nano>(t1 - t0).count() / pts.size(),
                    std::chrono::duration<double, std::nano>(t2 - t1).count() / pts.size());
    }
    CHECK(B[0].allFinite());
}
