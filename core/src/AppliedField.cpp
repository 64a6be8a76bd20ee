// The built-in applied fields: none, uniform, gradient (AppliedField.hpp).
#include "magFoam/AppliedField.hpp"

#include "magFoam/Error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace mag {

namespace {

// `table:` rows [t, s] (scale) or [t, Bx, By, Bz] (replace B), strictly
// increasing in t.
struct TimeTable {
    std::vector<double> t;
    std::vector<Vec3> B;      // replace rows
    std::vector<double> s;    // scale rows
    bool replace = false;

    static TimeTable read(const Dict& d) {
        TimeTable out;
        const auto rows = d.get<std::vector<std::vector<double>>>("table", {});
        if (d.has("table") && rows.empty()) d.fail("table", "expected a list of rows [t, s] or [t, Bx, By, Bz]");
        for (std::size_t i = 0; i < rows.size(); ++i) {
            const auto& v = rows[i];
            if ((v.size() != 2 && v.size() != 4) || v.size() != rows[0].size())
                d.fail("table", fmt::format("row {}: expected [t, s] or [t, Bx, By, Bz], the same form in every row", i));
            if (!out.t.empty() && !(v[0] > out.t.back()))
                d.fail("table", fmt::format("row {}: time {:g} s is not after the previous row's {:g} s (rows must be "
                                            "in increasing time)", i, v[0], out.t.back()));
            out.t.push_back(v[0]);
            if (v.size() == 2) out.s.push_back(v[1]);
            else out.B.emplace_back(v[1], v[2], v[3]);
        }
        out.replace = !rows.empty() && rows[0].size() == 4;
        return out;
    }
    bool empty() const { return t.empty(); }

    // Linear between rows, held outside.
    template <class V> static V interpolate(const std::vector<double>& t, const std::vector<V>& v, double time) {
        if (time <= t.front()) return v.front();
        if (time >= t.back()) return v.back();
        const auto k = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), time) - t.begin());
        const double a = (time - t[k - 1]) / (t[k] - t[k - 1]);
        return (1 - a) * v[k - 1] + a * v[k];
    }
    // B and the scale of G at `time` from the constant B0.
    void at(double time, const Vec3& B0, Vec3& B, double& gScale) const {
        B = B0, gScale = 1;
        if (t.empty()) return;
        if (replace) {
            B = interpolate(t, this->B, time);
        } else {
            gScale = interpolate(t, s, time);
            B = gScale * B0;
        }
    }
};

class NoAppliedField final : public AppliedField {
public:
    explicit NoAppliedField(const Dict&) {}
    void add(std::span<const Vec3>, std::span<Vec3>, std::span<Vec3>) const override {}
    Wrench wrench(const Body&) const override { return {}; }
    bool active() const override { return false; }
    std::string describe() const override { return "none"; }
};

// B(r) = B + G (r - origin); uniform is the case G = 0.
class LinearAppliedField : public AppliedField {
public:
    LinearAppliedField(const Dict& d, bool gradient) : gradient_(gradient) {
        B_ = d.get<Vec3>("B");
        if (gradient_) {
            const auto g = d.get<std::vector<std::vector<double>>>("gradient");
            if (g.size() != 3 || g[0].size() != 3 || g[1].size() != 3 || g[2].size() != 3)
                d.fail("gradient", "expected 3 rows of 3 numbers [[dBx/dx, dBx/dy, dBx/dz], [...], [...]] in T/m");
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) G_(i, j) = g[i][j];
            // Rounding of decimal input: 1e-9 of the largest entry.
            const double scale = std::max(G_.cwiseAbs().maxCoeff(), 1e-300), tol = 1e-9 * scale;
            if ((G_ - G_.transpose()).cwiseAbs().maxCoeff() > tol)
                d.fail("gradient", "must be symmetric (curl B = 0 where the bodies are: no currents there)");
            if (std::abs(G_.trace()) > tol)
                d.fail("gradient", fmt::format("must be traceless (div B = 0); its trace is {:g} T/m", G_.trace()));
            origin_ = d.get<Vec3>("origin", Vec3::Zero());
        }
        table_ = TimeTable::read(d);
    }

    void add(std::span<const Vec3> points, std::span<Vec3> B, std::span<Vec3> A) const override {
        Vec3 B0;
        double s;
        table_.at(time(), B_, B0, s);
        const Mat3 G = s * G_;
        for (std::size_t i = 0; i < points.size(); ++i) {
            const Vec3 r = points[i] - origin_;
            B[i] += B0 + G * r;
            // curl of (B0 x r)/2 is B0, of ((G r) x r)/3 is G r (G symmetric, traceless).
            if (!A.empty()) A[i] += 0.5 * B0.cross(r) + (G * r).cross(r) / 3.0;
        }
    }

    Wrench wrench(const Body& body) const override {
        Vec3 B0;
        double s;
        table_.at(time(), B_, B0, s);
        const Mat3 G = s * G_;
        const Vec3 m = body.magneticMoment();
        const Vec3 Bc = B0 + G * (body.position - origin_);
        Wrench w;
        w.force = G * m;        // grad(m . B), G symmetric
        w.torque = m.cross(Bc); // the first moment about the centre of mass vanishes
        w.ownEnergy = -m.dot(Bc);
        return w;
    }

    bool timeDependent() const override { return !table_.empty(); }
    std::string describe() const override {
        std::string s = fmt::format("{} (B [{:g}, {:g}, {:g}] T", gradient_ ? "gradient" : "uniform", B_.x(), B_.y(),
                                    B_.z());
        if (gradient_) s += fmt::format(", |G| {:g} T/m", G_.norm());
        if (!table_.empty()) s += fmt::format(", table of {} rows", table_.t.size());
        return s + ")";
    }

private:
    bool gradient_;
    Vec3 B_ = Vec3::Zero(), origin_ = Vec3::Zero();
    Mat3 G_ = Mat3::Zero();
    TimeTable table_;
};

class UniformAppliedField final : public LinearAppliedField {
public:
    explicit UniformAppliedField(const Dict& d) : LinearAppliedField(d, false) {}
};
class GradientAppliedField final : public LinearAppliedField {
public:
    explicit GradientAppliedField(const Dict& d) : LinearAppliedField(d, true) {}
};

const char* const kTableMeaning =
    "rows [t, s]: B and G scaled by s; or rows [t, Bx, By, Bz]: B replaced (G kept); times in s,\n"
    "increasing; linear between rows, held outside them";

const AppliedField::Add<NoAppliedField> addNone(
    "none", TypeDoc{"No applied field (the default; also when constant/appliedField.yaml is absent).",
                    {"type: none\n"},
                    {}});
const AppliedField::Add<UniformAppliedField> addUniform(
    "uniform", TypeDoc{"A uniform field B everywhere (Helmholtz coils, the Earth's field).\n"
                       "Torque m x B on every magnetized body, no force.",
                       {"type: uniform\nB: [0, 0, 0.005]\n", "type: uniform\nB: [0, 0, 0.005]\ntable: [[0, 0], [0.1, 1]]\n"},
                       {{"B", "T", "the field"}, {"table", "s", kTableMeaning}}});
const AppliedField::Add<GradientAppliedField> addGradient(
    "gradient", TypeDoc{"A field linear in space, B(r) = B + G (r - origin) (gradient coils).\n"
                        "Force G m and torque m x B(c) on every magnetized body, exact for uniform M.",
                        {"type: gradient\nB: [0, 0, 0.01]\ngradient: [[-0.5, 0, 0], [0, -0.5, 0], [0, 0, 1]]\n"
                         "origin: [0, 0, 0]\n",
                         "type: gradient\nB: [0, 0, 0.01]\ngradient: [[0, 0, 0], [0, 0, 0], [0, 0, 0]]\n"
                         "table: [[0, 0, 0, 0], [1, 0, 0, 0.01]]\n"},
                        {{"B", "T", "the field at the origin"},
                         {"gradient", "T/m", "G_ij = dB_i/dx_j, rows i; symmetric and traceless"},
                         {"origin", "m", "where B is the given value"},
                         {"table", "s", kTableMeaning}}});

} // namespace

} // namespace mag
