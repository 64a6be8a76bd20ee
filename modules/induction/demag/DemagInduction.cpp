// Physical soft iron (docs/physics.md#demag): each soft body carries a uniform
// magnetization M solving
//   M = f(H_eff),  H_eff = B-bar_applied/mu0 + B-bar_others/mu0 - N M,
// with N the body's demagnetization tensor computed from its mesh
// (DemagTensor.hpp, once per shape) and the fields of everything else averaged
// over the body's volume by the boundary integral of n x A. Linear:
// f(H) = chi H; with saturation f(H) = Ms tanh(chi |H| / Ms) H/|H| (monotone,
// reaching Ms, the gradient of a convex energy). A uniformly magnetized body's
// force with M held is the gradient of M . integral B dV (what MBM's boundary
// integral of Eq. 16 computes), so with the volume averages here the induced
// wrench is the gradient of U = -1/2 mu0 V H-bar . M (linear material) and
// energy is conserved; the paper's LLG model (field at the centre) is not.
//
//   induction: {type: demag, tolerance: 1e-8, maxIterations: 200, order: 3}
//
// Keys: kDoc at the registration below (magFoam -doc demag). Materials:
//   steel: {model: soft, chi: 1000, Js: 2.0, density: 7850}   # or mur: 1001
// chi (or mur = 1 + chi) >= 0, Js > 0 (saturation polarization mu0 Ms, T);
// `saturation: false` in the material keeps it linear.
//
// Solve: the other bodies' volume-averaged fields are linear in their
// magnetizations, so per call they are evaluated once per source (permanent
// bodies and the applied field as they are, each soft body with its three unit
// magnetizations: a 3x3 map per soft pair), then block Gauss-Seidel over the
// soft bodies, each block solved exactly (linear: (I/chi + N) M = h) or by
// Newton (saturating), until no M changes by more than tolerance * Ms.
#include "DemagTensor.hpp"

#include <magFoam/AppliedField.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/FieldEvaluator.hpp>
#include <magFoam/InductionModel.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>

namespace mag {

namespace {

struct SoftMaterial {
    double chi = 0, Ms = 0;
    bool saturation = true;
};

// M = f(H) and its Jacobian dM/dH.
Vec3 response(const SoftMaterial& m, const Vec3& H, Mat3* J) {
    if (!m.saturation) {
        if (J) *J = m.chi * Mat3::Identity();
        return m.chi * H;
    }
    const double h = H.norm();
    const double x = m.chi * h / m.Ms;
    if (x < 1e-8) { // tanh(x)/x = 1 - x^2/3: the linear limit
        if (J) *J = m.chi * Mat3::Identity();
        return m.chi * H;
    }
    const double t = std::tanh(x), s = m.Ms * t / h; // M = s H
    if (J) {
        const Vec3 u = H / h;
        const double ds = m.chi * (1 - t * t); // d|M|/d|H|
        *J = s * (Mat3::Identity() - u * u.transpose()) + ds * u * u.transpose();
    }
    return s * H;
}

class DemagInduction final : public InductionModel {
public:
    explicit DemagInduction(const Dict& d) {
        tolerance_ = d.get<double>("tolerance", 1e-8);
        if (!(tolerance_ > 0 && tolerance_ <= 1e-2)) d.fail("tolerance", "must be in (0, 0.01] (change of M per sweep relative to Ms)");
        maxIterations_ = d.get<int>("maxIterations", 200);
        if (maxIterations_ < 1) d.fail("maxIterations", "must be >= 1");
        order_ = d.get<int>("order", 3);
        if (order_ < 1 || order_ > 20) d.fail("order", "Gauss points per triangle side for the volume averages, 1..20");
        tensorOrder_ = d.get<int>("tensorOrder", 8);
        if (tensorOrder_ < 1 || tensorOrder_ > 20) d.fail("tensorOrder", "Gauss points per sub-triangle side, 1..20");
        tensorSplit_ = d.get<int>("tensorSplit", 4);
        if (tensorSplit_ < 1 || tensorSplit_ > 16) d.fail("tensorSplit", "sub-triangles per triangle side, 1..16");
        mbm_ = FieldEvaluator::New(Dict::fromString("type: MBM\n", "demag: the bodies' own fields"));
    }

    using InductionModel::converge;
    InductionReport converge(std::vector<Body>& bodies, const FieldEvaluator& field,
                             const AppliedField& applied) override {
        std::vector<std::size_t> soft;
        for (std::size_t i = 0; i < bodies.size(); ++i)
            if (bodies[i].soft()) soft.push_back(i);
        const std::size_t n = soft.size();
        InductionReport report;
        if (n == 0) return report;

        std::vector<SoftMaterial> mat(n);
        std::vector<Mat3> N(n);
        std::vector<std::vector<Vec3>> points(n), normals(n);
        for (std::size_t a = 0; a < n; ++a) {
            const Body& b = bodies[soft[a]];
            mat[a] = material(b);
            const Data& s = shapeData(b.shape);
            const Mat3 R = b.orientation.toRotationMatrix();
            N[a] = R * s.N * R.transpose();
            points[a].resize(s.rule.points.size()), normals[a].resize(s.rule.points.size());
            for (std::size_t q = 0; q < s.rule.points.size(); ++q) {
                points[a][q] = b.toWorld(s.rule.points[q]);
                normals[a][q] = R * s.rule.weightedNormals[q];
            }
        }
        // Fixed sources: the applied field and every magnetized non-soft body.
        std::vector<Vec3> fixedB(n, Vec3::Zero());
        for (std::size_t a = 0; a < n; ++a) {
            const double V = bodies[soft[a]].shape->volume;
            std::vector<Vec3> B(points[a].size(), Vec3::Zero()), A(points[a].size(), Vec3::Zero());
            if (applied.active()) {
                applied.add(points[a], B, A);
                fixedB[a] += demag::volumeAverage(normals[a], A, V);
            }
            for (const Body& source : bodies) {
                if (source.soft() || source.magnetizationBody.squaredNorm() == 0) continue;
                field.evaluate(source, points[a], B, A);
                fixedB[a] += demag::volumeAverage(normals[a], A, V);
            }
        }
        // Soft-soft maps: C[a][b] = B-bar at a per unit world M of b.
        std::vector<Mat3> C(n * n, Mat3::Zero());
        for (std::size_t b = 0; b < n; ++b) {
            Body unit = bodies[soft[b]];
            const Mat3 toBody = unit.orientation.conjugate().toRotationMatrix();
            for (std::size_t a = 0; a < n; ++a) {
                if (a == b) continue;
                std::vector<Vec3> B(points[a].size()), A(points[a].size());
                Mat3 perUnitBody;
                for (int c = 0; c < 3; ++c) {
                    unit.magnetizationBody = Vec3::Unit(c);
                    field.evaluate(unit, points[a], B, A);
                    perUnitBody.col(c) = demag::volumeAverage(normals[a], A, bodies[soft[a]].shape->volume);
                }
                C[a * n + b] = perUnitBody * toBody;
            }
        }

        // Block Gauss-Seidel, from the magnetizations of the last call.
        std::vector<Vec3> M(n);
        for (std::size_t a = 0; a < n; ++a) M[a] = bodies[soft[a]].magnetization();
        double change = 0;
        int it = 0;
        for (; it < maxIterations_; ++it) {
            change = 0;
            for (std::size_t a = 0; a < n; ++a) {
                Vec3 h = fixedB[a] / mu0;
                for (std::size_t b = 0; b < n; ++b)
                    if (b != a) h += C[a * n + b] * M[b] / mu0;
                const Vec3 next = solveBlock(mat[a], N[a], h, M[a]);
                change = std::max(change, (next - M[a]).norm() / mat[a].Ms);
                M[a] = next;
            }
            if (change <= tolerance_) break;
        }
        report.iterations = std::min(it + 1, maxIterations_);
        report.residual = change;
        report.converged = change <= tolerance_;
        for (std::size_t a = 0; a < n; ++a) {
            Body& b = bodies[soft[a]];
            b.magnetizationBody = b.orientation.conjugate() * M[a];
            if (!report.converged) report.unconverged.push_back(b.name);
        }
        return report;
    }

    std::string describe() const override {
        return fmt::format("demag (tolerance {:g}, maxIterations {}, volume averages {} x {} Gauss per triangle, "
                           "N from the mesh: {} x {} sub-triangles x {} x {})",
                           tolerance_, maxIterations_, order_, order_, tensorSplit_, tensorSplit_, tensorOrder_,
                           tensorOrder_);
    }

private:
    struct Data {
        Mat3 N;
        demag::SurfaceRule rule;
    };

    // M = f(h - N M) for one body: exact for a linear material; otherwise Newton
    // on g(M) = M - f(h - N M), each step halved until |g| falls (near the knee
    // of tanh a full step overshoots).
    static Vec3 solveBlock(const SoftMaterial& m, const Mat3& N, const Vec3& h, Vec3 M) {
        if (!m.saturation) return (Mat3::Identity() / m.chi + N).ldlt().solve(h);
        auto residual = [&](const Vec3& x, Mat3* J) { return Vec3(x - response(m, h - N * x, J)); };
        Mat3 J;
        Vec3 g = residual(M, &J);
        for (int k = 0; k < 100 && g.norm() > 1e-15 * m.Ms; ++k) {
            const Vec3 step = (Mat3::Identity() + J * N).partialPivLu().solve(g);
            double a = 1;
            Vec3 next = M - step, gn = residual(next, nullptr);
            for (int halve = 0; halve < 40 && gn.norm() >= g.norm(); ++halve) {
                a *= 0.5;
                next = M - a * step;
                gn = residual(next, nullptr);
            }
            if (gn.norm() >= g.norm()) break; // no descent left: at the rounding floor
            M = next;
            g = residual(M, &J);
        }
        return M;
    }

    static SoftMaterial material(const Body& body) {
        const Material& m = body.material;
        static const std::vector<std::string> keys = {"chi", "mur", "Js", "saturation"};
        for (const auto& [key, value] : m.properties)
            if (std::find(keys.begin(), keys.end(), key) == keys.end())
                m.fail(key, "the demag induction model does not use soft-material key '" + key + "' (body '" +
                                body.name + "'); it reads chi (or mur), Js and saturation" +
                                (key == "k" || key == "alpha" ? "; k and alpha are LLG's" : ""));
        SoftMaterial s;
        const bool hasChi = m.properties.count("chi") != 0, hasMur = m.properties.count("mur") != 0;
        if (hasChi == hasMur)
            m.fail(hasChi ? "mur" : "chi", "give the susceptibility chi or the relative permeability mur = 1 + chi, "
                                           "one of them (body '" + body.name + "')");
        s.chi = hasChi ? m.property("chi") : m.property("mur") - 1;
        if (hasChi && !(s.chi > 0)) m.fail("chi", "the susceptibility chi must be > 0 (body '" + body.name + "')");
        if (hasMur && !(s.chi > 0)) m.fail("mur", "the relative permeability mur must be > 1 (body '" + body.name + "')");
        const double Js = m.property("Js");
        if (!(Js > 0)) m.fail("Js", "the saturation polarization Js must be > 0 (tesla; body '" + body.name + "')");
        s.Ms = Js / mu0;
        const double sat = m.property("saturation", 1.0);
        if (sat != 0 && sat != 1) m.fail("saturation", "1 (true: tanh saturation at Js) or 0 (false: linear)");
        s.saturation = sat != 0;
        return s;
    }

    const Data& shapeData(const std::shared_ptr<const Shape>& shape) const {
        std::lock_guard<std::mutex> lock(mutex_);
        auto it = cache_.find(shape.get());
        if (it == cache_.end()) {
            // Cost ~ points x triangles: fine meshes get fewer points per
            // triangle (their edges bend little, so A's log term is weak there):
            // an icosphere of 5120 triangles at 2 x 2 points is 1.6e-6 off 1/3.
            const double F = static_cast<double>(shape->mesh.triangles.size());
            int split = tensorSplit_, order = tensorOrder_;
            while (F * F * split * split * order * order > kTensorBudget && (split > 1 || order > 2))
                split > 1 ? split /= 2 : --order;
            Data d{demag::demagTensor(shape, *mbm_, order, split), demag::surfaceRule(shape->mesh, order_, 1)};
            it = cache_.emplace(shape.get(), std::make_pair(shape, std::move(d))).first;
        }
        return it->second.second;
    }

    // Points x triangles for N, ~5 s on one core.
    static constexpr double kTensorBudget = 1.2e8;
    double tolerance_ = 1e-8;
    int maxIterations_ = 200, order_ = 3, tensorOrder_ = 8, tensorSplit_ = 4;
    std::unique_ptr<FieldEvaluator> mbm_;
    mutable std::mutex mutex_;
    mutable std::map<const Shape*, std::pair<std::shared_ptr<const Shape>, Data>> cache_;
};

const TypeDoc kDoc{
    "Physical soft iron: susceptibility, the exact demagnetization tensor, volume averages.\n"
    "Each soft body's uniform M solves M = f(H_applied + H_others - N M), N from the body's mesh,\n"
    "the fields averaged over its volume (boundary integral of n x A), so the induced wrench\n"
    "conserves energy. Materials: {model: soft, chi (or mur), Js, density[, saturation: false]}.",
    {"type: demag\ntolerance: 1e-8\nmaxIterations: 200\norder: 3\ntensorOrder: 8\ntensorSplit: 4\n"},
    {{"tolerance", "-", "converged when no magnetization changed by more than tolerance * Ms in a sweep, (0, 0.01]"},
     {"maxIterations", "-", "Gauss-Seidel sweeps over the soft bodies before a step is reported unconverged"},
     {"order", "-", "Gauss points per triangle side of the volume averages of the other bodies' fields, 1..20"},
     {"tensorOrder", "-", "Gauss points per sub-triangle side for N (once per shape), 1..20; lowered (to 2)\n"
                          "with tensorSplit for meshes of many triangles (cost ~ points x triangles)"},
     {"tensorSplit", "-", "sub-triangles per triangle side for N (edges: A's gradient is log-singular), 1..16"}}};

const InductionModel::Add<DemagInduction> addDemag("demag", kDoc);

} // namespace

} // namespace mag
