#include "DipoleMultipole.hpp"

#include "magFoam/Threads.hpp"

#include "DipoleBlockSum.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

// Solid harmonics, scaled as in Dehnen (2014, Comput. Astrophys. Cosmol. 1:1) but
// without the Condon-Shortley phase:
//   R_n^m(v) = r^n P_n^m(cos t) e^(i m phi) / (n + m)!       (regular)
//   I_n^m(v) = (n - m)! P_n^m(cos t) e^(i m phi) / r^(n + 1)  (irregular)
// with X_n^-m = (-1)^m conj(X_n^m). Then, for |y - z| < |x - z|,
//   1 / |x - y| = sum_nm conj(R_n^m(y - z)) I_n^m(x - z),
//   R_n^m(a + b) = sum_kl R_k^l(a) R_(n-k)^(m-l)(b),
//   I_n^m(s + t) = sum_kl (-1)^k conj(R_k^l(t)) I_(n+k)^(m+l)(s)    (|t| < |s|),
// which give the four translations below. Coefficients of degree n, order m sit at
// n^2 + n + m, negative orders included (the inner loops then run over m without
// branches).

namespace mag {

namespace {

using detail::kMu;

struct Cplx {
    double re = 0, im = 0;
};
inline Cplx operator*(Cplx a, Cplx b) { return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re}; }
inline Cplx operator*(double s, Cplx a) { return {s * a.re, s * a.im}; }
inline Cplx operator+(Cplx a, Cplx b) { return {a.re + b.re, a.im + b.im}; }
inline Cplx operator-(Cplx a, Cplx b) { return {a.re - b.re, a.im - b.im}; }
inline Cplx& operator+=(Cplx& a, Cplx b) { return a = a + b; }
inline Cplx conj(Cplx a) { return {a.re, -a.im}; }

inline int at(int n, int m) { return n * n + n + m; }
inline int size(int p) { return (p + 1) * (p + 1); }

void fillNegative(int p, Cplx* c) {
    for (int n = 1; n <= p; ++n)
        for (int m = 1; m <= n; ++m) {
            const Cplx v = conj(c[at(n, m)]);
            c[at(n, -m)] = (m & 1) ? Cplx{-v.re, -v.im} : v;
        }
}

// R_n^m(v), n = 0..p.
void regular(const Vec3& v, int p, Cplx* R) {
    const Cplx w{v.x(), v.y()};
    const double z = v.z(), r2 = v.squaredNorm();
    R[0] = {1, 0};
    for (int m = 1; m <= p; ++m) R[at(m, m)] = (1.0 / (2 * m)) * (R[at(m - 1, m - 1)] * w);
    for (int m = 0; m < p; ++m) {
        R[at(m + 1, m)] = z * R[at(m, m)];
        for (int n = m + 2; n <= p; ++n)
            R[at(n, m)] = (1.0 / ((n + m) * (n - m))) * ((2 * n - 1) * z * R[at(n - 1, m)] - r2 * R[at(n - 2, m)]);
    }
    fillNegative(p, R);
}

// I_n^m(v), n = 0..p (v != 0).
void irregular(const Vec3& v, int p, Cplx* I) {
    const Cplx w{v.x(), v.y()};
    const double z = v.z(), inv2 = 1.0 / v.squaredNorm();
    I[0] = {std::sqrt(inv2), 0};
    for (int m = 1; m <= p; ++m) I[at(m, m)] = ((2 * m - 1) * inv2) * (I[at(m - 1, m - 1)] * w);
    for (int m = 0; m < p; ++m) {
        I[at(m + 1, m)] = ((2 * m + 1) * z * inv2) * I[at(m, m)];
        for (int n = m + 2; n <= p; ++n)
            I[at(n, m)] = inv2 * ((2 * n - 1) * z * I[at(n - 1, m)] - ((n - 1) * (n - 1) - m * m) * I[at(n - 2, m)]);
    }
    fillNegative(p, I);
}

// Multipole of a dipole mu at y about z: M_n^m = mu . grad_y conj(R_n^m(y - z)), from
// d_z R_n^m = R_(n-1)^m and (d_x -/+ i d_y) R_n^m = +/- R_(n-1)^(m-/+1).
void addDipole(const Vec3& mu, const Vec3& v, int p, Cplx* R, Cplx* M) {
    regular(v, p - 1, R);
    const Cplx plus{0.5 * mu.x(), 0.5 * mu.y()}, minus{0.5 * mu.x(), -0.5 * mu.y()};
    for (int n = 1; n <= p; ++n)
        for (int m = -n; m <= n; ++m) {
            Cplx g{0, 0};
            if (m - 1 >= -(n - 1) && m - 1 <= n - 1) g += plus * R[at(n - 1, m - 1)];
            if (m + 1 >= -(n - 1) && m + 1 <= n - 1) g = g - minus * R[at(n - 1, m + 1)];
            if (m >= -(n - 1) && m <= n - 1) g += mu.z() * R[at(n - 1, m)];
            M[at(n, m)] += conj(g);
        }
}

// M2M: the child's expansion (centre z) about its parent's centre z', v = z - z'.
void shiftMultipole(const Cplx* M, const Vec3& v, int p, Cplx* R, Cplx* out) {
    regular(v, p, R);
    for (int n = 0; n <= p; ++n)
        for (int m = 0; m <= n; ++m) {
            Cplx s{0, 0};
            for (int k = 0; k <= n; ++k) {
                const int j = n - k;
                for (int l = std::max(-k, m - j); l <= std::min(k, m + j); ++l) s += conj(R[at(k, l)]) * M[at(j, m - l)];
            }
            out[at(n, m)] += s;
        }
}

// M2L: source cells' expansions M (centres z_M) as a local expansion about z_L,
// s = z_L - z_M; orders j + n <= p. Four sources at a time, one per vector lane
// (real and imaginary parts apart); the lanes are added in a fixed order at the end.
constexpr int kLanes = 4;
typedef double Lanes __attribute__((vector_size(kLanes * sizeof(double))));
void multipoleToLocal(const Lanes* Mre, const Lanes* Mim, const Lanes* Ire, const Lanes* Iim, int p, Cplx* L) {
    for (int j = 0; j <= p; ++j)
        for (int k = 0; k <= j; ++k) {
            Lanes ar = {}, ai = {};
            for (int n = 0; n <= p - j; ++n) {
                const Lanes *mr = Mre + at(n, 0), *mi = Mim + at(n, 0), *ir = Ire + at(j + n, k), *ii = Iim + at(j + n, k);
                for (int m = -n; m <= n; ++m) {
                    ar += mr[m] * ir[m] - mi[m] * ii[m];
                    ai += mr[m] * ii[m] + mi[m] * ir[m];
                }
            }
            const Cplx acc{(ar[0] + ar[1]) + (ar[2] + ar[3]), (ai[0] + ai[1]) + (ai[2] + ai[3])};
            L[at(j, k)] += (j & 1) ? Cplx{-acc.re, -acc.im} : acc;
        }
}

// L2L: the local expansion about z_L moved to z_L + u, degrees 0..q of the result.
void shiftLocal(const Cplx* L, const Vec3& u, int p, int q, Cplx* R, Cplx* out) {
    regular(u, p, R);
    for (int a = 0; a <= q; ++a)
        for (int b = 0; b <= a; ++b) {
            Cplx s{0, 0};
            for (int n = a; n <= p; ++n) {
                const int d = n - a;
                for (int m = std::max(-n, b - d); m <= std::min(n, b + d); ++m) s += L[at(n, m)] * conj(R[at(d, m - b)]);
            }
            out[at(a, b)] += s;
        }
}

struct Cell {
    Vec3 centre = Vec3::Zero();  // expansion centre: middle of the bodies' bounding box
    double radius = 0;           // largest distance of a body from the centre
    double reach = 0;            // largest reach of a body
    std::size_t begin = 0, end = 0;
    int parent = -1, firstChild = -1, children = 0, depth = 0;
    bool leaf() const { return children == 0; }
};

class Tree {
public:
    Tree(std::vector<Vec3> positions, std::vector<double> reach, std::size_t leafSize)
        : pos_(std::move(positions)), reach_(std::move(reach)), leafSize_(std::max<std::size_t>(1, leafSize)) {
        order.resize(pos_.size());
        for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
        cells.push_back({});
        cells[0].end = order.size();
        build(0);
    }

    std::vector<std::size_t> order;  // tree order -> body index
    std::vector<Cell> cells;         // parents before children

private:
    void build(int ci) {
        Cell c = cells[ci];
        Vec3 lo = pos_[order[c.begin]], hi = lo;
        for (std::size_t k = c.begin; k < c.end; ++k) {
            lo = lo.cwiseMin(pos_[order[k]]);
            hi = hi.cwiseMax(pos_[order[k]]);
            c.reach = std::max(c.reach, reach_[order[k]]);
        }
        c.centre = 0.5 * (lo + hi);
        for (std::size_t k = c.begin; k < c.end; ++k) c.radius = std::max(c.radius, (pos_[order[k]] - c.centre).norm());
        cells[ci] = c;
        // Bodies all on one point are a leaf, however many: no cell pair of theirs
        // could ever be well apart.
        if (c.end - c.begin <= leafSize_ || c.depth >= 100 || c.radius == 0) return;
        // Two halves at the median along the longest side: leaves hold leafSize/2 to
        // leafSize bodies, enough for full vectors in the direct sums (an octree's
        // leaves can hold a handful).
        int axis = 0;
        (hi - lo).maxCoeff(&axis);
        const std::size_t mid = c.begin + (c.end - c.begin) / 2;
        std::nth_element(order.begin() + static_cast<std::ptrdiff_t>(c.begin), order.begin() + static_cast<std::ptrdiff_t>(mid),
                         order.begin() + static_cast<std::ptrdiff_t>(c.end),
                         [&](std::size_t i, std::size_t j) { return pos_[i][axis] < pos_[j][axis]; });
        const int first = static_cast<int>(cells.size());
        Cell left, right;
        left.begin = c.begin, left.end = mid, right.begin = mid, right.end = c.end;
        left.parent = right.parent = ci, left.depth = right.depth = c.depth + 1;
        cells.push_back(left), cells.push_back(right);
        cells[ci].firstChild = first, cells[ci].children = 2;
        build(first), build(first + 1);
    }

    std::vector<Vec3> pos_;
    std::vector<double> reach_;
    std::size_t leafSize_;
};

// A wrench from the local expansion's degrees 0..2 at the body (coefficients
// about the body's centre): grad phi and the Hessian of phi.
Wrench localWrench(const Cplx* Lb, const Vec3& mt) {
    const Cplx l11 = Lb[at(1, 1)], l21 = Lb[at(2, 1)], l22 = Lb[at(2, 2)];
    const double l10 = Lb[at(1, 0)].re, l20 = Lb[at(2, 0)].re;
    const Vec3 gradPhi(l11.re, l11.im, l10);
    Mat3 H;
    H << 0.5 * (l22.re - l20), 0.5 * l22.im, l21.re,  //
        0.5 * l22.im, -0.5 * (l22.re + l20), l21.im,  //
        l21.re, l21.im, l20;
    const Vec3 B = -kMu * gradPhi;
    Wrench w;
    w.force = -kMu * (H * mt);
    w.torque = mt.cross(B);
    w.energy = -mt.dot(B);
    return w;
}

// Cell pairs of the dual-tree walk, grouped by target cell: offset[c] ..
// offset[c + 1] index the source cells of target c, in walk order.
struct CellLists {
    std::vector<std::size_t> offset;
    std::vector<int> source;
};

struct Interactions {
    std::vector<std::pair<int, int>> m2l;  // (target, source) by translation
    CellLists byTranslation, direct;
};

// The dual-tree walk (serial, so the lists come out in one order): cell pairs by
// translation (each way) or, for two leaves and small pairs, by direct sum.
Interactions walk(const std::vector<Cell>& cells, const MultipoleSettings& settings) {
    const double theta = settings.theta, directPairs = settings.directPairs;
    auto separated = [&](const Cell& A, const Cell& B) {
        const double d = (A.centre - B.centre).norm();
        // The margin keeps rounding from letting through a pair that isDipolePair() rejects.
        return A.radius + B.radius < theta * d && d - A.radius - B.radius > (A.reach + B.reach) * (1 + 1e-9);
    };
    std::vector<std::pair<int, int>> m2l, p2p;  // (target cell, source cell)
    std::vector<std::pair<int, int>> stack{{0, 0}};
    while (!stack.empty()) {
        const auto [ia, ib] = stack.back();
        stack.pop_back();
        const Cell &A = cells[ia], &B = cells[ib];
        if (ia == ib) {
            if (A.leaf()) {
                p2p.emplace_back(ia, ia);
                continue;
            }
            for (int i = A.firstChild; i < A.firstChild + A.children; ++i) {
                stack.emplace_back(i, i);
                for (int j = i + 1; j < A.firstChild + A.children; ++j) stack.emplace_back(i, j);
            }
        } else if (static_cast<double>(A.end - A.begin) * static_cast<double>(B.end - B.begin) <= directPairs) {
            p2p.emplace_back(ia, ib), p2p.emplace_back(ib, ia);
        } else if (separated(A, B)) {
            m2l.emplace_back(ia, ib), m2l.emplace_back(ib, ia);
        } else if (A.leaf() && B.leaf()) {
            p2p.emplace_back(ia, ib), p2p.emplace_back(ib, ia);
        } else {
            const bool splitA = !A.leaf() && (B.leaf() || A.radius >= B.radius);
            const Cell& S = splitA ? A : B;
            for (int c = S.firstChild; c < S.firstChild + S.children; ++c)
                stack.emplace_back(splitA ? c : ia, splitA ? ib : c);
        }
    }
    // Lists grouped by target, in walk order.
    const std::size_t nc = cells.size();
    auto group = [&](const std::vector<std::pair<int, int>>& pairs) {
        CellLists g;
        g.offset.assign(nc + 1, 0);
        for (const auto& pr : pairs) ++g.offset[pr.first + 1];
        for (std::size_t c = 0; c < nc; ++c) g.offset[c + 1] += g.offset[c];
        g.source.resize(pairs.size());
        std::vector<std::size_t> fill(g.offset.begin(), g.offset.end() - 1);
        for (const auto& pr : pairs) g.source[fill[pr.first]++] = pr.second;
        return g;
    };
    Interactions out;
    out.byTranslation = group(m2l);
    out.direct = group(p2p);
    out.m2l = std::move(m2l);
    return out;
}

// The expansions of one sum: the tree, its bodies as arrays (tree order), which
// cells need a multipole or carry a local expansion, and the coefficients.
struct Expansions {
    const std::vector<Cell>& cells;
    const detail::DipoleArrays& a;
    int p, S;                              // order, coefficients per cell
    std::vector<std::vector<int>> level;   // cells by depth
    std::vector<char> needM, hasLocal;
    std::vector<Cplx> M, L;
    std::vector<double> pairs;             // dipole pairs counted by translation, per cell

    Expansions(const std::vector<Cell>& c, const detail::DipoleArrays& arrays, int order, const Interactions& in)
        : cells(c), a(arrays), p(order), S(size(order)) {
        const std::size_t nc = cells.size();
        int maxDepth = 0;
        for (const Cell& x : cells) maxDepth = std::max(maxDepth, x.depth);
        level.resize(maxDepth + 1);
        for (std::size_t k = 0; k < nc; ++k) level[cells[k].depth].push_back(static_cast<int>(k));
        // Cells whose multipole is needed (sources of a translation, and all cells
        // below them) and cells with a local expansion (targets, and all below).
        needM.assign(nc, 0), hasLocal.assign(nc, 0);
        for (const auto& [t, s] : in.m2l) needM[s] = 1, hasLocal[t] = 1;
        for (std::size_t k = 1; k < nc; ++k) {
            if (needM[cells[k].parent]) needM[k] = 1;
            if (hasLocal[cells[k].parent]) hasLocal[k] = 1;
        }
        M.assign(nc * S, Cplx{}), L.assign(nc * S, Cplx{});
        pairs.assign(nc, 0.0);
    }

    // Upward: multipoles of leaves from their dipoles, of other cells from children.
    void upward() {
        for (int d = static_cast<int>(level.size()) - 1; d >= 0; --d)
            parallelFor(level[d].size(), [&](std::size_t k) {
                const int ci = level[d][k];
                const Cell& c = cells[ci];
                if (!needM[ci]) return;
                std::vector<Cplx> R(S);
                Cplx* Mc = &M[ci * S];
                if (c.leaf()) {
                    for (std::size_t b = c.begin; b < c.end; ++b)
                        addDipole(Vec3(a.mx[b], a.my[b], a.mz[b]), Vec3(a.x[b], a.y[b], a.z[b]) - c.centre, p, R.data(), Mc);
                } else {
                    for (int ch = c.firstChild; ch < c.firstChild + c.children; ++ch)
                        shiftMultipole(&M[ch * S], cells[ch].centre - c.centre, p, R.data(), Mc);
                }
                fillNegative(p, Mc);
            });
    }

    // Translations into each target cell (kLanes at a time); pairs counted as the
    // bodies of the source cells.
    void translate(const CellLists& m2l) {
        parallelFor(cells.size(), [&](std::size_t t) {
            if (m2l.offset[t] == m2l.offset[t + 1]) return;
            std::vector<Cplx> I(S);
            std::vector<Lanes> Mre(S), Mim(S), Ire(S), Iim(S);
            for (std::size_t k0 = m2l.offset[t]; k0 < m2l.offset[t + 1]; k0 += kLanes) {
                for (int q = 0; q < kLanes; ++q) {
                    const std::size_t k = k0 + q;
                    const bool lane = k < m2l.offset[t + 1];
                    if (lane) {
                        const int si = m2l.source[k];
                        irregular(cells[t].centre - cells[si].centre, p, I.data());
                        pairs[t] += static_cast<double>(cells[si].end - cells[si].begin);
                    }
                    const Cplx* Ms = lane ? &M[m2l.source[k] * S] : nullptr;
                    for (int c = 0; c < S; ++c) {
                        Mre[c][q] = lane ? Ms[c].re : 0.0, Mim[c][q] = lane ? Ms[c].im : 0.0;
                        Ire[c][q] = lane ? I[c].re : 0.0, Iim[c][q] = lane ? I[c].im : 0.0;
                    }
                }
                multipoleToLocal(Mre.data(), Mim.data(), Ire.data(), Iim.data(), p, &L[t * S]);
            }
        });
    }

    // Downward: each cell adds its parent's local expansion (and its pair count).
    void downward() {
        for (std::size_t d = 1; d < level.size(); ++d) {
            parallelFor(level[d - 1].size(), [&](std::size_t k) {
                if (hasLocal[level[d - 1][k]]) fillNegative(p, &L[level[d - 1][k] * S]);
            });
            parallelFor(level[d].size(), [&](std::size_t k) {
                const int ci = level[d][k];
                const Cell& c = cells[ci];
                if (!hasLocal[c.parent]) return;
                std::vector<Cplx> R(S);
                shiftLocal(&L[c.parent * S], c.centre - cells[c.parent].centre, p, p, R.data(), &L[ci * S]);
                pairs[ci] += pairs[c.parent];
            });
        }
    }

    // Leaves: local expansion at each body, plus the direct sums with the
    // neighbouring leaves (target blocks of at most kBlock bodies). Adds the
    // wrenches of movable bodies to out[body[k]] and counts each body's pairs.
    void leaves(const CellLists& direct, const std::vector<std::size_t>& body, std::span<Wrench> out,
                std::vector<double>& bodyPairs) {
        std::vector<int> leafCells;
        for (std::size_t c = 0; c < cells.size(); ++c)
            if (cells[c].leaf()) leafCells.push_back(static_cast<int>(c));
        parallelFor(leafCells.size(), [&](std::size_t li) {
            const int ci = leafCells[li];
            const Cell& c = cells[ci];
            std::vector<Cplx> R(S), Lb(size(2));
            // Direct pairs of this leaf and of the cells above it.
            std::vector<detail::SourceRange> ranges;
            for (int up = ci; up >= 0; up = cells[up].parent)
                for (std::size_t k = direct.offset[up]; k < direct.offset[up + 1]; ++k)
                    ranges.emplace_back(cells[direct.source[k]].begin, cells[direct.source[k]].end);
            if (hasLocal[ci]) fillNegative(p, &L[ci * S]);
            for (std::size_t i0 = c.begin; i0 < c.end; i0 += detail::kBlock) {
                const std::size_t m = std::min(detail::kBlock, c.end - i0);
                detail::BlockSums sums;
                detail::sumBlock(a, i0, std::min(detail::kBlock, (m + 7) / 8 * 8), a, ranges, sums);
                for (std::size_t k = 0; k < m; ++k) {
                    const std::size_t b = i0 + k;
                    Wrench w;
                    if (hasLocal[ci]) {
                        std::fill(Lb.begin(), Lb.end(), Cplx{});
                        shiftLocal(&L[ci * S], Vec3(a.x[b], a.y[b], a.z[b]) - c.centre, p, 2, R.data(), Lb.data());
                        w = localWrench(Lb.data(), Vec3(a.mx[b], a.my[b], a.mz[b]));
                    }
                    w += sums.wrench(k);
                    bodyPairs[b] = pairs[ci] + sums.c[k];
                    if (a.fixed[b] == 0.0) out[body[b]] += w;
                }
            }
        });
    }
};

// Fixed bodies (with skipFixedPairs): a direct sum over all bodies, where the
// pair test leaves out the other fixed ones.
void addFixedBodies(std::span<const FarFieldBody> bodies, bool skipFixedPairs, const detail::DipoleArrays& a,
                    const std::vector<std::size_t>& body, std::span<Wrench> out, std::vector<double>& bodyPairs) {
    const std::size_t nb = body.size();
    std::vector<std::size_t> fixedK;
    for (std::size_t k = 0; k < nb; ++k)
        if (a.fixed[k] != 0.0) fixedK.push_back(k);
    if (fixedK.empty()) return;
    detail::DipoleArrays f;
    f.resize(fixedK.size());
    for (std::size_t q = 0; q < fixedK.size(); ++q) f.set(q, bodies[body[fixedK[q]]], skipFixedPairs);
    const std::size_t nBlocks = (fixedK.size() + detail::kBlock - 1) / detail::kBlock;
    parallelFor(nBlocks, [&](std::size_t blk) {
        const std::size_t i0 = blk * detail::kBlock, m = std::min(detail::kBlock, fixedK.size() - i0);
        detail::BlockSums sums;
        const detail::SourceRange all{0, nb};
        detail::sumBlock(f, i0, m, a, {&all, 1}, sums);
        for (std::size_t k = 0; k < m; ++k) {
            out[body[fixedK[i0 + k]]] += sums.wrench(k);
            bodyPairs[fixedK[i0 + k]] = sums.c[k];
        }
    });
}

} // namespace

std::uint64_t addDipoleFarFieldMultipole(std::span<const FarFieldBody> bodies, bool skipFixedPairs,
                                         std::span<Wrench> out, const MultipoleSettings& settings) {
    // Bodies that can be in a dipole pair at all.
    std::vector<std::size_t> member;
    std::vector<Vec3> pos;
    std::vector<double> reach;
    for (std::size_t i = 0; i < bodies.size(); ++i)
        if (std::isfinite(bodies[i].reach) && bodies[i].position.allFinite()) {
            member.push_back(i);
            pos.push_back(bodies[i].position);
            reach.push_back(bodies[i].reach);
        }
    if (member.size() < 2) return 0;
    const Tree tree(pos, reach, settings.leafSize);
    const std::size_t nb = member.size();
    // Bodies in tree order (index k), as arrays for the direct sums.
    std::vector<std::size_t> body(nb);
    detail::DipoleArrays a;
    // Eight spare entries at the end: a leaf's target block is rounded up to whole
    // vectors (lanes past the leaf compute and are discarded).
    a.resize(nb + 8);
    for (std::size_t k = 0; k < nb; ++k) {
        body[k] = member[tree.order[k]];
        a.set(k, bodies[body[k]], skipFixedPairs);
    }

    const Interactions lists = walk(tree.cells, settings);
    Expansions e(tree.cells, a, settings.order, lists);
    e.upward();
    e.translate(lists.byTranslation);
    e.downward();
    std::vector<double> bodyPairs(nb, 0.0);
    e.leaves(lists.direct, body, out, bodyPairs);
    addFixedBodies(bodies, skipFixedPairs, a, body, out, bodyPairs);

    double total = 0;
    for (double v : bodyPairs) total += v;
    return static_cast<std::uint64_t>(total / 2 + 0.5);  // each pair seen from both ends
}

FarFieldSettings FarFieldSettings::read(const Dict& d) {
    FarFieldSettings s;
    const std::string method = d.getWord("method", {"auto", "direct", "multipole"}, "auto");
    s.method = method == "direct" ? Method::direct : method == "multipole" ? Method::multipole : Method::automatic;
    const int above = d.get<int>("multipoleAbove", static_cast<int>(s.multipoleAbove));
    if (above < 0) d.fail("multipoleAbove", "expected a number of bodies >= 0");
    s.multipoleAbove = static_cast<std::size_t>(above);
    s.multipole.order = d.get<int>("order", s.multipole.order);
    if (s.multipole.order < 2 || s.multipole.order > 30)
        d.fail("order", "expected the expansion degree p in [2, 30] (the force needs degree 2)");
    s.multipole.theta = d.get<double>("theta", s.multipole.theta);
    if (!(s.multipole.theta > 0 && s.multipole.theta < 1)) d.fail("theta", "expected an opening angle in (0, 1)");
    const int leaf = d.get<int>("leafSize", static_cast<int>(s.multipole.leafSize));
    if (leaf < 1 || leaf > static_cast<int>(detail::kBlock))
        d.fail("leafSize", "expected bodies per leaf cell in [1, " + std::to_string(detail::kBlock) + "]");
    s.multipole.leafSize = static_cast<std::size_t>(leaf);
    s.multipole.directPairs = d.get<double>("directPairs", s.multipole.directPairs);
    if (!(s.multipole.directPairs >= 0)) d.fail("directPairs", "expected a number of body pairs >= 0");
    d.reportUnused();
    return s;
}

std::string FarFieldSettings::describe() const {
    std::ostringstream o;
    const std::string mp =
        "multipole (p " + std::to_string(multipole.order) + ", theta " + std::to_string(multipole.theta).substr(0, 4) + ")";
    if (method == Method::direct) o << "direct";
    else if (method == Method::multipole) o << mp;
    else o << "direct up to " << multipoleAbove << " bodies, then " << mp;
    return o.str();
}

std::uint64_t addDipoleFarField(std::span<const FarFieldBody> bodies, bool skipFixedPairs, std::span<Wrench> out,
                                const FarFieldSettings& settings) {
    return settings.usesMultipole(bodies.size()) ? addDipoleFarFieldMultipole(bodies, skipFixedPairs, out, settings.multipole)
                     : addDipoleFarField(bodies, skipFixedPairs, out);
}

} // namespace mag
