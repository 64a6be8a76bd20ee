// Physical soft iron (docs/physics.md#demag): each soft body carries a uniform
// magnetization M solving
//   M = f(H_eff),  H_eff = B-bar_applied/mu0 + B-bar_others/mu0 - N M,
// with N the body's demagnetization tensor computed from its mesh
// (DemagTensor.hpp, once per shape) and B-bar the fields of everything else
// averaged over the body's volume as the field evaluator's interaction energy
// sees them (FieldEvaluator::fieldIntegral: the same samples and overlap model
// as the forces). Linear: f(H) = chi H; with saturation
// f(H) = Ms tanh(chi |H| / Ms) H/|H| (monotone, reaching Ms, the gradient of a
// convex co-energy). The force on a uniformly magnetized body with M held is
// the gradient of its interaction energy, linear in M; with M stationary for
// E = mu0 V (g(M) + 1/2 M.N M) - M.I the induced wrench is the gradient of E
// and energy is conserved; the paper's LLG model (field at the centre) is not.
//
//   induction: {type: demag, tolerance: 1e-8, maxIterations: 200}
//
// Keys: kDoc at the registration below (magFoam -doc demag). Materials:
//   steel: {model: soft, chi: 1000, Js: 2.0, density: 7850}   # or mur: 1001
// chi (or mur = 1 + chi) > 0, Js > 0 (saturation polarization mu0 Ms, T);
// `saturation: false` in the material keeps it linear.
//
// Solve: the other bodies' field integrals are linear in their
// magnetizations, so per call they are evaluated once per source (permanent
// bodies and the applied field as they are, each soft body as a 3x3 map per
// soft pair, FieldEvaluator::fieldIntegralMap: one geometric pass with MBM's
// regular rules, three calls otherwise), then block Gauss-Seidel over the
// soft bodies, each block solved exactly (linear: (I/chi + N) M = h) or by
// Newton (saturating), until no M changes by more than tolerance * Ms.
#include "DemagTensor.hpp"

#include <magFoam/AppliedField.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/FieldEvaluator.hpp>
#include <magFoam/InductionModel.hpp>
#include <magFoam/SoftFieldIntegrals.hpp>

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

// The internal energy density of a soft material over mu0, g(|M|) with
// g' = f^-1 ((A/m)^2):
// linear |M|^2 / (2 chi); tanh (Ms^2 / chi) (x artanh x + 1/2 ln(1 - x^2)),
// x = |M| / Ms, the Legendre transform of the co-energy (Ms^2/chi) ln cosh.
double internalEnergy(const SoftMaterial& m, double M) {
    if (!m.saturation) return M * M / (2 * m.chi);
    const double x = std::min(M / m.Ms, 1 - 1e-16);
    if (x < 1e-4) return M * M / (2 * m.chi) * (1 + x * x / 6); // series: x^2/2 + x^4/12
    return m.Ms * m.Ms / m.chi * (x * std::atanh(x) + 0.5 * std::log1p(-x * x));
}

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
        tensorOrder_ = d.get<int>("tensorOrder", 20);
        if (tensorOrder_ < 2 || tensorOrder_ > 32) d.fail("tensorOrder", "Gauss points per side of each fan piece for N, 2..32");
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
        for (std::size_t a = 0; a < n; ++a) {
            const Body& b = bodies[soft[a]];
            mat[a] = material(b);
            const Mat3 R = b.orientation.toRotationMatrix();
            N[a] = R * shapeData(b.shape).N * R.transpose();
        }
        // What each soft body responds to: the field integral I = -dU/dM of
        // every energy it takes part in, U as the forces see it, over its
        // volume (SoftFieldIntegrals.hpp). Then M is stationary for exactly the
        // energy the forces derive from.
        const SoftFieldIntegrals fields = softFieldIntegrals(bodies, soft, field, applied, true);
        const std::vector<Vec3>& fixedB = fields.fixed;  // from the applied field and permanent bodies
        const std::vector<Mat3>& C = fields.coupling;    // C[a n + b]: B-bar at a per unit world M of b

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

    // Every pair once (interaction energies at the converged M, as the forces
    // see them), the applied field's, and each soft body's own energy
    // mu0 V (g(M) + 1/2 M . N M), g the material's internal energy density
    // (dg/dM = f^-1(M)): at the solution the total is the minimum over M of
    // the energy the forces are the gradient of (docs/physics.md#energy). For a
    // linear material this is the -1/2 m . B of the default.
    double sceneEnergy(const std::vector<Body>& bodies, const std::vector<Wrench>& wrenches) const override {
        double e = 0;
        for (std::size_t i = 0; i < wrenches.size(); ++i) e += 0.5 * wrenches[i].energy + wrenches[i].ownEnergy;
        for (const Body& b : bodies) {
            if (!b.soft()) continue;
            const SoftMaterial m = material(b);
            const Vec3& M = b.magnetizationBody;
            e += mu0 * b.shape->volume * (internalEnergy(m, M.norm()) + 0.5 * M.dot(shapeData(b.shape).N * M));
        }
        return e;
    }

    std::string describe() const override {
        return fmt::format("demag (tolerance {:g}, maxIterations {}, fields averaged as the evaluator's energy sees "
                           "them, N from the mesh: graded fan of order {} or fewer points on fine meshes)",
                           tolerance_, maxIterations_, tensorOrder_);
    }

private:
    struct Data {
        Mat3 N;
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
            // the richest rule within the budget, the fan down to order 2, then
            // the symmetric 7-, 6- and 3-point rules (an icosphere of 5120
            // triangles: 3 points, 2.3e-6 off 1/3; of 1280: fan order 4, 1.5e-7).
            const double F = static_cast<double>(shape->mesh.triangles.size());
            int order = tensorOrder_;
            while (F * F * demag::tensorRulePoints(order) > kTensorBudget && order != -3)
                order = order > 2 ? order - 1 : order == 2 ? -7 : order == -7 ? -6 : -3;
            Data d{demag::demagTensor(shape, *mbm_, order)};
            it = cache_.emplace(shape.get(), std::make_pair(shape, std::move(d))).first;
        }
        return it->second.second;
    }

    // Points x triangles for N, ~5 s on one core.
    static constexpr double kTensorBudget = 1.2e8;
    double tolerance_ = 1e-8;
    int maxIterations_ = 200, tensorOrder_ = 20;
    std::unique_ptr<FieldEvaluator> mbm_;
    mutable std::mutex mutex_;
    mutable std::map<const Shape*, std::pair<std::shared_ptr<const Shape>, Data>> cache_;
};

const TypeDoc kDoc{
    "Physical soft iron: susceptibility, the exact demagnetization tensor, volume averages.\n"
    "Each soft body's uniform M solves M = f(H_applied + H_others - N M), N from the body's mesh,\n"
    "the other fields averaged over its volume as the field evaluator's energy sees them, so the\n"
    "induced wrench conserves energy. Materials: {model: soft, chi (or mur), Js, density[, saturation: false]}.",
    {"type: demag\ntolerance: 1e-8\nmaxIterations: 200\ntensorOrder: 20\n"},
    {{"tolerance", "-", "converged when no magnetization changed by more than tolerance * Ms in a sweep, (0, 0.01]"},
     {"maxIterations", "-", "Gauss-Seidel sweeps over the soft bodies before a step is reported unconverged"},
     {"tensorOrder", "-", "Gauss points per side of each of a triangle's three graded fan pieces for N (once\n"
                          "per shape), 2..32; lowered for meshes of many triangles (cost ~ points x triangles),\n"
                          "down to a symmetric 3-point rule"}}};

const InductionModel::Add<DemagInduction> addDemag("demag", kDoc);

} // namespace

} // namespace mag
