// Adaptive boundary quadrature of the MBM interaction (see the header).
#include "AdaptiveQuadrature.hpp"

#include "SurfaceQuadrature.hpp"

#include <magFoam/Threads.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <mutex>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace mag::mbm {

namespace {

constexpr int kMaxDepth = 40; // parameter boxes of 2^-40
constexpr int kMaxOrder = 12;
// Graded directions take max(2 n, 8) points: a graded rule with fewer resolves the
// feature too poorly for the parent/children difference to see its error (measured:
// with n + 1 sinh-graded points, 1 mm gaps were off by 6e-5 at tolerance 1e-6).
constexpr int kGradedOrder = 8;
// The accepted value is the children's sum, whose error is that of the parent
// (|children - parent|) reduced by the halving: by 2^(2n) for a smooth integrand, by
// at least 4 for every integrand the grading leaves with two derivatives; the estimate
// takes the 4. (The tolerance chart of cases/benchmarks checks it: achieved error below
// the requested one on every contact case; 1/10 was not.)
constexpr double kEstimateFactor = 0.25;
// Elements at least this many widths from the source (and never on a feature) are
// integrated by order instead of by halving (see `raiseOrder`).
constexpr double kOrderSeparation = 0.05;
constexpr int kOrderStep = 2;

// Gauss-Legendre on [0, 1] for every order, built once.
struct Rule1D {
    std::vector<double> x, w;
};
const Rule1D& gauss01(int n) {
    static const auto table = [] {
        std::vector<Rule1D> t(kMaxOrder + 1);
        for (int k = 1; k <= kMaxOrder; ++k) {
            std::vector<double> gx, gw;
            gaussLegendre(k, gx, gw);
            for (int i = 0; i < k; ++i) {
                t[static_cast<std::size_t>(k)].x.push_back(0.5 * (gx[static_cast<std::size_t>(i)] + 1.0));
                t[static_cast<std::size_t>(k)].w.push_back(0.5 * gw[static_cast<std::size_t>(i)]);
            }
        }
        return t;
    }();
    return table[static_cast<std::size_t>(n)];
}

// Points of the rule r on [a, b] graded towards a for a feature at distance g (units
// of b - a) beyond a. g = 0 (on the end): x = tau^3, which turns a log x into
// tau^2 ln tau and keeps the rule exact for polynomials of degree (2m - 3) / 3 in x.
// g > 0 (a gap): a geometric chain of intervals, each three times as wide as its
// distance to the feature, [0, 3g], [3g, 15g], ... up to the end, with plain Gauss on
// each: the feature sits 1/3 of a width beyond every interval, where m-point Gauss
// converges like 3^(-2m) (8 points: 2e-8), and the chain reaches the scale g in
// log_4(1 / g) intervals - a 1 um gap under a 1 cm face in 7. (A sinh map on fewer,
// longer intervals costs fewer points but is not exact for constants; its bias repeats
// at every refinement level, where the estimate cannot see it.)
void gradedChain(const Rule1D& r, double g, double a, double b, double chainWidth,
                 std::vector<double>& x, std::vector<double>& w) {
    const double L = b - a, absL = std::abs(L);
    if (g <= 0.0) {
        for (std::size_t i = 0; i < r.x.size(); ++i) {
            const double t = r.x[i];
            x.push_back(a + L * t * t * t);
            w.push_back(absL * 3.0 * t * t * r.w[i]);
        }
        return;
    }
    double lo = 0.0; // in units of L, from a
    while (lo < 1.0) {
        const double hi = std::min(1.0, lo + chainWidth * (g + lo));
        const double h = hi - lo;
        for (std::size_t i = 0; i < r.x.size(); ++i) {
            x.push_back(a + L * (lo + h * r.x[i]));
            w.push_back(absL * h * r.w[i]);
        }
        lo = hi;
    }
}

// The n-point rule on [0, 1] for features at distances gLow, gHigh beyond its ends
// (units of the interval; < 0 or >= 1: none): plain Gauss, graded towards one end, or
// towards both. A parent's rule must differ from the union of its children's near the
// features, or |children - parent| cannot see the error there: with a feature on both
// ends the whole interval takes the two-sided map x = tau^3 / (tau^3 + (1 - tau)^3)
// (its children grade one end each); otherwise two graded parts meeting at 0.4 (the
// children meet at 0.5), and a gap's chain alternates its width factor between
// refinement levels (chainWidth 3 or 2), since a child's chain would repeat its
// parent's near the feature.
void rule1D(int n, double gLow, double gHigh, double chainWidth, std::vector<double>& x,
            std::vector<double>& w) {
    const bool lo = gLow >= 0.0 && gLow < 1.0, hi = gHigh >= 0.0 && gHigh < 1.0;
    x.clear();
    w.clear();
    if (!lo && !hi) {
        const Rule1D& r = gauss01(n);
        x = r.x;
        w = r.w;
        return;
    }
    const Rule1D& r = gauss01(std::min(kMaxOrder, std::max(2 * n, kGradedOrder)));
    if (lo && hi && gLow <= 0.0 && gHigh <= 0.0) {
        for (std::size_t i = 0; i < r.x.size(); ++i) {
            const double t = r.x[i], a = t * t * t, b = (1 - t) * (1 - t) * (1 - t);
            x.push_back(a / (a + b));
            w.push_back(3.0 * t * t * (1 - t) * (1 - t) / ((a + b) * (a + b)) * r.w[i]);
        }
        return;
    }
    // Both ends otherwise: graded halves split at 0.4, not at the children's 0.5.
    const double mid = lo && hi ? 0.4 : (lo ? 1.0 : 0.0);
    if (lo) gradedChain(r, gLow / mid, 0.0, mid, chainWidth, x, w);
    if (hi) gradedChain(r, gHigh / (1.0 - mid), 1.0, mid, chainWidth, x, w); // reversed: b < a
}

// An element's geometry: a bilinear quadrilateral c0..c3 or a collapsed triangle with
// apex c0. Per parameter side (s = 0, s = 1, t = 0, t = 1): the distance (m) to a
// source feature beyond it (-1: none) and the element's extent (m) across it.
struct Geometry {
    std::array<Vec3, 4> c;
    bool triangle = false;
    int face = -1;
    std::array<double, 4> feature{-1.0, -1.0, -1.0, -1.0};
    std::array<double, 4> extent{};
};

void mapPoint(const Geometry& g, double s, double t, Vec3& p, double& jac) {
    const auto& c = g.c;
    if (g.triangle) {
        const Vec3 e = (c[1] - c[0]) + t * (c[2] - c[1]);
        p = c[0] + s * e;
        jac = s * (c[1] - c[0]).cross(c[2] - c[1]).norm();
        return;
    }
    bilinearMap(c, s, t, p, jac);
}

// The elements of a convex piece: a quadrilateral, a triangle, or a fan of both from
// corner 0 (fan diagonals carry no feature).
void addElements(const FacePiece& piece, std::vector<Geometry>& out) {
    const auto& c = piece.corners;
    const std::size_t k = c.size();
    auto side = [&](std::size_t i) { return piece.feature[i % k]; };
    for (std::size_t i = 1; i + 1 < k;) {
        Geometry g;
        g.face = piece.face;
        const bool first = i == 1;
        if (i + 2 < k) { // quad c0, ci, ci+1, ci+2
            const bool last = i + 2 == k - 1;
            g.c = {c[0], c[i], c[i + 1], c[i + 2]};
            // s = 0: ci+2 -> c0; s = 1: ci -> ci+1; t = 0: c0 -> ci; t = 1: ci+1 -> ci+2
            g.feature = {last ? side(k - 1) : -1.0, side(i), first ? side(0) : -1.0, side(i + 1)};
            const double area = 0.5 * ((g.c[2] - g.c[0]).cross(g.c[3] - g.c[1])).norm();
            const double ls = 0.5 * ((g.c[0] - g.c[3]).norm() + (g.c[2] - g.c[1]).norm());
            const double lt = 0.5 * ((g.c[1] - g.c[0]).norm() + (g.c[3] - g.c[2]).norm());
            g.extent = {area / ls, area / ls, area / lt, area / lt};
            i += 2;
        } else { // triangle c0, ci, ci+1 (apex c0)
            const bool last = i + 1 == k - 1;
            g.triangle = true;
            g.c = {c[0], c[i], c[i + 1], c[i + 1]};
            const double t0 = first ? side(0) : -1.0, t1 = last ? side(k - 1) : -1.0;
            // s = 0: the apex (graded when a side through it is); s = 1: ci -> ci+1;
            // t = 0: c0 -> ci; t = 1: ci+1 -> c0
            const double apex = t0 < 0.0 ? t1 : (t1 < 0.0 ? t0 : std::min(t0, t1));
            g.feature = {apex, side(i), t0, t1};
            const double twiceArea = (g.c[1] - g.c[0]).cross(g.c[2] - g.c[0]).norm();
            const double hs = twiceArea / (g.c[2] - g.c[1]).norm();
            g.extent = {hs, hs, twiceArea / (g.c[1] - g.c[0]).norm(), twiceArea / (g.c[2] - g.c[0]).norm()};
            i += 1;
        }
        out.push_back(g);
    }
}

// A node of the refinement: a parameter box of one geometry.
struct Node {
    int geometry = 0;
    double s0 = 0, s1 = 1, t0 = 0, t1 = 1;
    int depth = 0;
    Wrench own;                 // this box's own rule
    std::array<Wrench, 4> kids; // the rules of its four children
    Wrench value;               // sum of kids
    double error = 0.0;
    // An order node (away from the source): own = Gauss(order - step), value =
    // Gauss(order) on the same box, refined by raising the order up to kMaxOrder,
    // then by halving into order nodes.
    bool byOrder = false;
    int order = 0;
    double rho = 0.0; // its convergence rate (order nodes; the box never changes)
};

struct Context {
    const PolyhedronTables& source;
    const Vec3& Ms;
    const Vec3& Mt;
    const Vec3& rc;
    OverlapModel model;
    ForceForm form;
    int order;
    const std::vector<Geometry>& geometry;
    const TargetPieces& pieces;
    double length; // L of the error metric
    const std::vector<std::pair<Vec3, Vec3>>& sourceBoxes; // per source face: centre, half size
    double tolerance;
    mutable std::atomic<std::size_t> samples{0};
};

double metric(const Wrench& w, double L) {
    return std::max(w.force.norm(), w.totalTorque().norm() / L);
}

// The tensor rule rs x rt (on [0, 1]) on the box [s0, s1] x [t0, t1] of geometry g,
// its points moved by `shift`.
Wrench tensorRule(const Context& ctx, const Geometry& g, double s0, double s1, double t0, double t1,
                  const Rule1D& rs, const Rule1D& rt, const Vec3& shift) {
    const Vec3& n = ctx.pieces.normals[static_cast<std::size_t>(g.face)];
    const double hs = s1 - s0, ht = t1 - t0;
    thread_local std::vector<Vec3> points, normals;
    thread_local std::vector<double> weights;
    points.clear();
    normals.clear();
    weights.clear();
    for (std::size_t i = 0; i < rs.x.size(); ++i)
        for (std::size_t j = 0; j < rt.x.size(); ++j) {
            Vec3 p;
            double jac;
            mapPoint(g, s0 + hs * rs.x[i], t0 + ht * rt.x[j], p, jac);
            points.push_back(p + shift);
            normals.push_back(n);
            weights.push_back(rs.w[i] * rt.w[j] * hs * ht * jac);
        }
    ctx.samples.fetch_add(points.size(), std::memory_order_relaxed);
    return interactionWrench(ctx.source, ctx.Ms, points, weights, normals, ctx.Mt, ctx.rc, ctx.model, ctx.form);
}

// The element rule on the box [s0, s1] x [t0, t1] of geometry g.
Wrench boxRule(const Context& ctx, int gi, double s0, double s1, double t0, double t1, int depth) {
    const Geometry& g = ctx.geometry[static_cast<std::size_t>(gi)];
    // Feature distances beyond the box's sides in units of its width (a box away from
    // a feature sees it at >= 1 width and takes plain Gauss).
    auto beyond = [&](int side, double outside, double width) {
        const double f = g.feature[static_cast<std::size_t>(side)];
        return f < 0.0 ? -1.0 : (f / g.extent[static_cast<std::size_t>(side)] + outside) / width;
    };
    const double hs = s1 - s0, ht = t1 - t0;
    thread_local Rule1D rs, rt;
    const double chainWidth = depth % 2 ? 2.0 : 3.0;
    rule1D(ctx.order, beyond(0, s0, hs), beyond(1, 1.0 - s1, hs), chainWidth, rs.x, rs.w);
    rule1D(ctx.order, beyond(2, t0, ht), beyond(3, 1.0 - t1, ht), chainWidth, rt.x, rt.w);
    const Vec3 shift = -ctx.pieces.inwardOffset[static_cast<std::size_t>(g.face)] *
                       ctx.pieces.normals[static_cast<std::size_t>(g.face)];
    return tensorRule(ctx, g, s0, s1, t0, t1, rs, rt, shift);
}

// Plain m x m Gauss on the box (the rule of an order node: never on a source
// plane that it touches, so no inward offset).
Wrench plainRule(const Context& ctx, const Node& nd, int m) {
    const Rule1D& r = gauss01(m);
    return tensorRule(ctx, ctx.geometry[static_cast<std::size_t>(nd.geometry)], nd.s0, nd.s1, nd.t0, nd.t1, r, r,
                      Vec3::Zero());
}

// A lower bound of the box's distance to the source, in units of the box's longest
// side: the smallest over the source's faces of the largest gap between the
// projections of the box's corners and of the face's bounding box on separating axes
// (the coordinate axes, the face normal, the box's in-plane side normals). 0 when
// they touch. (Per face, not the source's bounding box: a clip lying beside another
// is far from most of its faces and inside its bounding box.)
double separation(const Context& ctx, const Node& nd, double* boxWidth = nullptr) {
    const Geometry& g = ctx.geometry[static_cast<std::size_t>(nd.geometry)];
    std::array<Vec3, 4> c;
    double jac;
    mapPoint(g, nd.s0, nd.t0, c[0], jac);
    mapPoint(g, nd.s1, nd.t0, c[1], jac);
    mapPoint(g, nd.s1, nd.t1, c[2], jac);
    mapPoint(g, nd.s0, nd.t1, c[3], jac);
    const Vec3& n = ctx.pieces.normals[static_cast<std::size_t>(g.face)];
    std::array<Vec3, 8> axes{Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(), n};
    std::size_t count = 4;
    double width = 0.0;
    for (std::size_t k = 0; k < 4; ++k) {
        const Vec3 side = c[(k + 1) % 4] - c[k];
        width = std::max(width, side.norm());
        const Vec3 axis = side.cross(n);
        if (axis.norm() > 0.0) axes[count++] = axis.normalized();
    }
    std::array<double, 8> lo, hi;
    for (std::size_t k = 0; k < count; ++k) {
        lo[k] = hi[k] = axes[k].dot(c[0]);
        for (const Vec3& x : c) {
            lo[k] = std::min(lo[k], axes[k].dot(x));
            hi[k] = std::max(hi[k], axes[k].dot(x));
        }
    }
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& [mid, half] : ctx.sourceBoxes) {
        double d = 0.0;
        for (std::size_t k = 0; k < count; ++k) {
            const Vec3& a = axes[k];
            const double reach = a.cwiseAbs().dot(half), m = a.dot(mid);
            d = std::max({d, lo[k] - (m + reach), (m - reach) - hi[k]});
        }
        nearest = std::min(nearest, d);
        if (nearest <= 0.0) break;
    }
    if (boxWidth) *boxWidth = width;
    return width > 0.0 && nearest > 0.0 ? nearest / width : 0.0;
}

// Gauss-Legendre on an interval converges like rho^(-2m) for an integrand analytic
// inside the Bernstein ellipse E_rho (foci at the ends). The source's singularities
// (its edges, and its faces where the field jumps) lie at least `delta` box widths
// from the box. Those nearer to the face plane than the contact split's dNear were
// cut along, so they lie on the box's sides or beyond them: the smallest ellipse
// they reach passes a point delta from an END, off the axis (a source edge below the
// box's side): semi-major axis a = (sqrt(4 + eta^2) + eta) / 2, eta = 2 delta
// half-widths. The others may hover over the box's interior, at least dNear away:
// a = sqrt(1 + eta^2) with eta = 2 max(delta, dNear / width). The rate is the smaller.
double convergenceRate(double delta, double nearDelta) {
    auto rate = [](double a) { return a + std::sqrt(a * a - 1.0); };
    const double eta = 2.0 * delta, etaMid = 2.0 * std::max(delta, nearDelta);
    return std::min(rate(0.5 * (std::sqrt(4.0 + eta * eta) + eta)), rate(std::sqrt(1.0 + etaMid * etaMid)));
}

// The rate of a box `delta` widths (of `width` m) from the source, its face's dNear known.
double boxRate(const Context& ctx, const Node& nd, double delta, double width) {
    const int face = ctx.geometry[static_cast<std::size_t>(nd.geometry)].face;
    const double dNear = ctx.pieces.nearDistance[static_cast<std::size_t>(face)];
    return convergenceRate(delta, width > 0.0 ? dNear / width : 0.0);
}

// An order node's rules and estimate. First evaluation: Gauss(order - 2) and
// Gauss(order). Raising: the accepted rule becomes the reference and the order
// jumps by the steps its geometric convergence needs to bring the node's estimate to
// `share` (the tolerance's equal share per element), at most to kMaxOrder. The
// estimate of the accepted Gauss(m) from the difference to Gauss(m') (m' < m) is
// |G(m) - G(m')| r / (1 - r), r = rho^(-2 (m - m')); and at least the previous
// estimate times r, so that one reference rule landing close to the integral by
// chance cannot hide the error.
void evaluateByOrder(const Context& ctx, Node& nd, bool raise, double share) {
    if (nd.rho == 0.0) {
        double width = 0.0;
        const double delta = separation(ctx, nd, &width);
        nd.rho = boxRate(ctx, nd, delta, width);
    }
    const double rho = nd.rho;
    int step = kOrderStep;
    const double previous = nd.error;
    if (raise) {
        nd.own = nd.value;
        if (share > 0.0 && nd.error > share)
            step = static_cast<int>(std::ceil(std::log(nd.error / share) / (2.0 * std::log(rho))));
        step = std::clamp(step, 1, kMaxOrder - nd.order);
        nd.order += step;
    } else {
        // The first order: the one the rate predicts for the tolerance (relative to
        // the element's own value), at least 2, at most n + 2; its reference two
        // orders lower (one from 2).
        const double need = std::ceil(std::log(1.0 / ctx.tolerance) / (2.0 * std::log(rho)));
        nd.order = static_cast<int>(std::clamp(need, 2.0, static_cast<double>(nd.order)));
        step = nd.order >= 3 ? kOrderStep : 1;
        nd.own = plainRule(ctx, nd, nd.order - step);
    }
    nd.value = plainRule(ctx, nd, nd.order);
    const double r = std::pow(rho, -2.0 * step);
    Wrench diff = nd.value;
    diff.force -= nd.own.force;
    diff.torque -= nd.own.torque;
    diff.mechanicalTorque -= nd.own.mechanicalTorque;
    nd.error = (r < 0.5 ? r / (1.0 - r) : 1.0) * metric(diff, ctx.length);
    if (raise) nd.error = std::max(nd.error, previous * r);
}

// Children 0..3: (s low, t low), (s high, t low), (s low, t high), (s high, t high).
void childBox(const Node& n, int k, double& s0, double& s1, double& t0, double& t1) {
    const double sm = 0.5 * (n.s0 + n.s1), tm = 0.5 * (n.t0 + n.t1);
    s0 = (k & 1) ? sm : n.s0;
    s1 = (k & 1) ? n.s1 : sm;
    t0 = (k & 2) ? tm : n.t0;
    t1 = (k & 2) ? n.t1 : tm;
}

void expand(const Context& ctx, Node& n) {
    n.value = Wrench{};
    for (int k = 0; k < 4; ++k) {
        double s0, s1, t0, t1;
        childBox(n, k, s0, s1, t0, t1);
        n.kids[static_cast<std::size_t>(k)] = boxRule(ctx, n.geometry, s0, s1, t0, t1, n.depth + 1);
        n.value += n.kids[static_cast<std::size_t>(k)];
    }
    Wrench diff = n.value;
    diff.force -= n.own.force;
    diff.torque -= n.own.torque;
    diff.mechanicalTorque -= n.own.mechanicalTorque;
    n.error = kEstimateFactor * metric(diff, ctx.length);
}

} // namespace

AdaptiveResult adaptiveInteraction(const PolyhedronTables& source, const Vec3& Ms,
                                   const PolyhedronTables& target, const Eigen::Isometry3d& T,
                                   const Vec3& Mt, const Vec3& rc, OverlapModel model,
                                   const AdaptiveSettings& settings) {
    if (settings.order < 1 || settings.order > kMaxOrder)
        throw std::invalid_argument("adaptive quadrature: order must be 1..12");
    if (!(settings.tolerance > 0.0))
        throw std::invalid_argument("adaptive quadrature: tolerance must be > 0");
    thread_local TargetPieces pieces;
    splitTargetFaces(source, target, T, pieces);
    std::vector<Geometry> geometry;
    for (const FacePiece& p : pieces.pieces) addElements(p, geometry);
    thread_local std::vector<std::pair<Vec3, Vec3>> boxes;
    boxes.clear();
    for (const PolyFace& f : source.faces()) {
        Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
        for (const auto& loop : f.loops)
            for (int v : loop) {
                low = low.cwiseMin(source.vertices()[static_cast<std::size_t>(v)]);
                high = high.cwiseMax(source.vertices()[static_cast<std::size_t>(v)]);
            }
        boxes.emplace_back(0.5 * (low + high), 0.5 * (high - low));
    }
    const Context ctx{source, Ms, Mt, rc, model, settings.form, settings.order, geometry, pieces,
                      target.boundingRadius(), boxes, settings.tolerance};
    const int firstOrder = std::min(kMaxOrder, settings.order + kOrderStep);

    std::vector<Node> nodes(geometry.size());
    std::vector<std::size_t> active(geometry.size());
    std::iota(active.begin(), active.end(), std::size_t{0});
    parallelFor(nodes.size(), [&](std::size_t i) {
        Node& n = nodes[i];
        n.geometry = static_cast<int>(i);
        // Elements on a feature, or near the source, are refined by halving with
        // graded rules; the others by order.
        bool onFeature = false;
        for (double f : geometry[i].feature) onFeature |= f == 0.0;
        double width = 0.0;
        const double delta = onFeature ? 0.0 : separation(ctx, n, &width);
        if (!onFeature && delta >= kOrderSeparation) {
            n.rho = boxRate(ctx, n, delta, width);
            n.byOrder = true;
            n.order = firstOrder;
            evaluateByOrder(ctx, n, false, 0.0);
            return;
        }
        n.own = boxRule(ctx, n.geometry, 0, 1, 0, 1, 0);
        expand(ctx, n);
    });
    AdaptiveResult r;
    r.samples = ctx.samples.load();
    std::vector<std::size_t> order, fresh, next, raised, freshByOrder;
    std::vector<char> marked;
    while (true) {
        Wrench total;
        double error = 0.0, magnitude = 0.0;
        for (std::size_t i : active) {
            total += nodes[i].value;
            error += nodes[i].error;
            magnitude += nodes[i].value.force.norm();
        }
        r.wrench = total;
        const double scale = std::max(metric(total, ctx.length), 1e-9 * magnitude);
        r.estimate = scale > 0.0 ? error / scale : 0.0;
        if (error <= settings.tolerance * scale) break;
        if (r.samples >= settings.maxSamples) {
            r.capped = true;
            break;
        }
        // Mark the largest errors holding half the estimate (Doerfler marking).
        order.assign(active.begin(), active.end());
        std::stable_sort(order.begin(), order.end(),
                         [&](std::size_t a, std::size_t b) { return nodes[a].error > nodes[b].error; });
        marked.assign(nodes.size(), 0);
        double sum = 0.0;
        bool any = false;
        for (std::size_t i : order) {
            if (sum >= 0.5 * error) break;
            if (nodes[i].depth >= kMaxDepth) continue;
            marked[i] = 1;
            any = true;
            sum += nodes[i].error;
        }
        if (!any) {
            r.capped = true;
            break;
        }
        // Children of the marked nodes take their places in `active`.
        fresh.clear();
        next.clear();
        raised.clear();
        freshByOrder.clear();
        for (std::size_t i : active) {
            if (!marked[i]) {
                next.push_back(i);
                continue;
            }
            if (nodes[i].byOrder && nodes[i].order < kMaxOrder) {
                next.push_back(i);
                raised.push_back(i);
                continue;
            }
            if (nodes[i].byOrder) { // at the highest order: halve into order nodes
                for (int k = 0; k < 4; ++k) {
                    Node c;
                    c.geometry = nodes[i].geometry;
                    childBox(nodes[i], k, c.s0, c.s1, c.t0, c.t1);
                    c.depth = nodes[i].depth + 1;
                    c.byOrder = true;
                    c.order = firstOrder;
                    next.push_back(nodes.size());
                    freshByOrder.push_back(nodes.size());
                    nodes.push_back(c);
                }
                continue;
            }
            for (int k = 0; k < 4; ++k) {
                Node c;
                c.geometry = nodes[i].geometry;
                childBox(nodes[i], k, c.s0, c.s1, c.t0, c.t1);
                c.depth = nodes[i].depth + 1;
                c.own = nodes[i].kids[static_cast<std::size_t>(k)];
                next.push_back(nodes.size());
                fresh.push_back(nodes.size());
                nodes.push_back(c);
            }
        }
        active.swap(next);
        const double share = settings.tolerance * scale / static_cast<double>(active.size());
        parallelFor(fresh.size(), [&](std::size_t k) { expand(ctx, nodes[fresh[k]]); });
        parallelFor(raised.size(), [&](std::size_t k) { evaluateByOrder(ctx, nodes[raised[k]], true, share); });
        parallelFor(freshByOrder.size(), [&](std::size_t k) { evaluateByOrder(ctx, nodes[freshByOrder[k]], false, 0.0); });
        r.samples = ctx.samples.load();
    }
    r.elements = active.size();
    return r;
}

} // namespace mag::mbm
