// Template field evaluator (etc/templates/fieldModule): every body is a point
// dipole m = M V at its centre of mass. Copy this folder to
// modules/fields/<Name>/ and rename PointDipole / pointDipole (README.md,
// "Plugins"). Selected in system/magSchemes.yaml by
//
//   field: {type: pointDipole, scale: 1}
//
// | key   | default | meaning                                  |
// |-------|---------|------------------------------------------|
// | scale | 1       | factor on every moment (a toy setting)   |
//
// World frame throughout (FieldEvaluator.hpp). For a source dipole m_s at r_s
// and r = p - r_s, R = |r|, u = r / R:
//   B = mu0 / (4 pi R^3) (3 (m_s.u) u - m_s),  A = mu0 / (4 pi R^3) m_s x r,  H = B / mu0
// and on a target dipole m_t at p: force grad(m_t.B), torque m_t x B, energy -m_t.B.
#include <magFoam/Error.hpp>
#include <magFoam/FieldEvaluator.hpp>

#include <cmath>

namespace {

using mag::Vec3;

class PointDipoleField final : public mag::FieldEvaluator {
public:
    explicit PointDipoleField(const mag::Dict& d) : scale_(d.get<double>("scale", 1.0)) {}

    void evaluate(const mag::Body& source, std::span<const Vec3> points, std::span<Vec3> B, std::span<Vec3> A,
                  std::span<Vec3> H) const override {
        const Vec3 m = moment(source);
        for (std::size_t i = 0; i < points.size(); ++i) {
            const Vec3 r = points[i] - source.position;
            const double R = r.norm();
            if (R == 0) throw mag::InputError("pointDipole: field asked at the centre of body '" + source.name + "'");
            const Vec3 u = r / R;
            const double k = mag::mu0 / (4 * mag::pi * R * R * R);
            B[i] = k * (3 * m.dot(u) * u - m);
            if (!A.empty()) A[i] = k * m.cross(r);
            if (!H.empty()) H[i] = B[i] / mag::mu0;
        }
    }

    mag::Wrench interaction(const mag::Body& source, const mag::Body& target) const override {
        const Vec3 ms = moment(source), mt = moment(target);
        const Vec3 r = target.position - source.position;
        const double R = r.norm();
        if (R == 0) throw mag::InputError("pointDipole: bodies '" + source.name + "' and '" + target.name +
                                          "' have the same centre");
        const Vec3 u = r / R;
        const double su = ms.dot(u), tu = mt.dot(u);
        const double k = mag::mu0 / (4 * mag::pi * R * R * R);
        const Vec3 B = k * (3 * su * u - ms);
        mag::Wrench w;
        w.force = (3 * k / R) * (su * mt + tu * ms + ms.dot(mt) * u - 5 * su * tu * u);
        w.torque = mt.cross(B); // about the target's centre, where its dipole sits
        w.energy = -mt.dot(B);
        return w;
    }

    std::string describe() const override { return "pointDipole (scale " + std::to_string(scale_) + ")"; }

private:
    Vec3 moment(const mag::Body& b) const { return scale_ * b.magneticMoment(); }

    double scale_;
};

// What `-doc pointDipole` prints: the keys, types and defaults come from the
// constructor's reads of the examples; units and meaning from here.
const mag::TypeDoc kDoc{"Every body one point dipole at its centre of mass (a template).",
                        {"type: pointDipole\nscale: 1.0\n"},
                        {{"scale", "-", "factor on every field and wrench"}}};

// The type name of magSchemes.yaml; list it in TYPES of mag_add_plugin too.
const mag::FieldEvaluator::Add<PointDipoleField> addPointDipole("pointDipole", kDoc);

} // namespace
