// Boundary-integrated force, torques and energy of a target in a source's field (see the
// header for the formulas and the charge-model derivation).
#include "InteractionWrench.hpp"

#include <magFoam/SurfaceMesh.hpp>

#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace mag::mbm {

namespace {

constexpr double kFourPi = 4.0 * std::numbers::pi;
// insideFraction above this counts as inside (outside, the solid angles sum to
// zero up to rounding, ~1e-16).
constexpr double kInsideFloor = 1e-12;

// Field at the samples: B, S = sum_p W_p n_p, insideFraction (scratch reused per thread).
struct SampleField {
    std::vector<Vec3> B, S;
    std::vector<double> f;
};

const SampleField& fieldAtSamples(const PolyhedronTables& source, const Vec3& Ms,
                                  std::span<const Vec3> points, std::span<const double> weights,
                                  std::span<const Vec3> normals, bool wantB) {
    if (weights.size() != points.size() || normals.size() != points.size())
        throw std::invalid_argument(
            "mbm::interactionWrench: points, weights and normals differ in length");
    thread_local SampleField s;
    const std::size_t n = points.size();
    s.B.resize(wantB ? n : 0);
    s.S.resize(n);
    s.f.resize(n);
    evaluate(source, Ms, points, FieldOutputs{s.B, {}, s.f, {}, s.S});
    return s;
}

// The source face nearest to p (source frame): the face of the closest
// triangle. Only samples inside the source ask, so a plain loop serves.
const PolyFace& nearestFace(const PolyhedronTables& source, const Vec3& p) {
    const auto& V = source.vertices();
    double best = std::numeric_limits<double>::infinity();
    int face = 0;
    for (const PolyTriangle& t : source.triangles()) {
        const Vec3 q = closestPointOnTriangle(p, V[static_cast<std::size_t>(t.v[0])],
                                              V[static_cast<std::size_t>(t.v[1])], V[static_cast<std::size_t>(t.v[2])]);
        const double d = (p - q).squaredNorm();
        if (d < best) best = d, face = t.face;
    }
    return source.faces()[static_cast<std::size_t>(face)];
}

} // namespace

OverlapModel overlapModelFromName(std::string_view name) {
    if (name == "charge") return OverlapModel::charge;
    if (name == "amperian") return OverlapModel::amperian;
    if (name == "exterior") return OverlapModel::exterior;
    throw std::invalid_argument("unknown overlap model '" + std::string(name) +
                                "'; valid models: amperian, charge, exterior");
}

ForceForm forceFormFromName(std::string_view name) {
    if (name == "split") return ForceForm::split;
    if (name == "surfaceCharge") return ForceForm::surfaceCharge;
    throw std::invalid_argument("unknown force form '" + std::string(name) +
                                "'; valid forms: split, surfaceCharge");
}

Wrench interactionWrench(const PolyhedronTables& source, const Vec3& Ms,
                         std::span<const Vec3> points, std::span<const double> weights,
                         std::span<const Vec3> normals, const Vec3& Mt, const Vec3& rc,
                         OverlapModel model, ForceForm form) {
    const bool sigma = form == ForceForm::surfaceCharge;
    if (sigma && model == OverlapModel::amperian)
        throw std::invalid_argument("mbm::interactionWrench: the surfaceCharge form needs the charge or "
                                    "exterior overlap model (amperian's field is B, not a potential's gradient)");
    const SampleField& s = fieldAtSamples(source, Ms, points, weights, normals, true);
    const bool charge = model == OverlapModel::charge, exterior = model == OverlapModel::exterior;
    Vec3 F = Vec3::Zero(), Tm = Vec3::Zero();
    Vec3 Tall = Vec3::Zero(); // surfaceCharge: sum w sigma (r - rc) x field, the whole torque
    Vec3 normalPart = Vec3::Zero(); // exterior: int over the overlap of (Ms . n_s) n_s dV
    Vec3 nxA = Vec3::Zero();  // sum w n x (Ms x S)  (amperian: (4 pi/mu0) int B dV)
    Vec3 phiN = Vec3::Zero(); // sum w (Ms . S) n   (charge: int H dV = -phiN / (4 pi))
    double chargeEnergy = 0.0; // sum w (Mt . n)(Ms . S)
    for (std::size_t k = 0; k < points.size(); ++k) {
        const double w = weights[k];
        const Vec3& n = normals[k];
        // Field acting on the sample: B (amperian), mu0 H = B - mu0 Ms f (charge), or
        // exterior: mu0 H plus the normal part of mu0 Ms f across the nearest source face.
        Vec3 field = charge || exterior ? Vec3(s.B[k] - (mu0 * s.f[k]) * Ms) : s.B[k];
        if (exterior && s.f[k] > kInsideFloor) {
            // mu0 H plus the normal part of mu0 Ms: B less its tangential jump.
            const PolyFace& face = nearestFace(source, points[k]);
            const Vec3& ns = face.normal;
            const Vec3 g = Ms.dot(ns) * ns;
            field += (mu0 * s.f[k]) * g;
            // The overlap volume below this face, from div X = 1 with
            // X = ((r - r_face) . n_s) n_s, which vanishes on the face's plane:
            // V = sum over the target's samples inside of w (n_s . r - offset)(n_s . n).
            // surfaceCharge: the same volume integral as the surface charge in the
            // potential psi of g, sum w (M_t . n) f psi, psi = -(n_s . r - offset) Ms . n_s.
            const double depth = w * s.f[k] * (ns.dot(points[k]) - face.offset);
            normalPart += sigma ? Vec3((depth * Ms.dot(ns)) * n) : Vec3((depth * ns.dot(n)) * g);
        }
        if (sigma) {
            const double wSigma = w * Mt.dot(n);
            F += wSigma * field;
            Tall += wSigma * (points[k] - rc).cross(field);
        } else {
            const double wMB = w * Mt.dot(field);
            F += wMB * n;                          // Eq. 16
            Tm += wMB * (points[k] - rc).cross(n); // Eq. 18: -n x (M.B)(r - rc)
        }
        if (charge || exterior) {
            const double wPhi = w * Ms.dot(s.S[k]);
            phiN += wPhi * n;
            chargeEnergy += wPhi * Mt.dot(n);
        } else {
            nxA += w * n.cross(Ms.cross(s.S[k])); // A = mu0/(4 pi) Ms x S (Eq. 9)
        }
    }
    Wrench out;
    out.force = F;
    out.mechanicalTorque = Tm;
    if (charge) {
        // T = mu0 Mt x int H dV, int H dV = -sum w phi n, phi = Ms . S / (4 pi)
        out.torque = -(mu0 / kFourPi) * Mt.cross(phiN);
        out.energy = (mu0 / kFourPi) * chargeEnergy;
        out.fieldIntegral = -(mu0 / kFourPi) * phiN; // mu0 int H dV
        if (sigma) out.mechanicalTorque = Tall - out.torque;
    } else if (exterior) {
        // int B_ext dV = mu0 int H dV + mu0 int_overlap (Ms . n_s) n_s dV: the charge
        // model's split (every sample's own term, so blocks of samples add up) and
        // the normal part of the magnetization where the target is inside.
        const Vec3 integral = -(mu0 / kFourPi) * phiN + mu0 * normalPart;
        out.torque = Mt.cross(integral);
        out.energy = -Mt.dot(integral);
        out.fieldIntegral = integral;
        if (sigma) out.mechanicalTorque = Tall - out.torque;
    } else {
        nxA *= mu0 / kFourPi;       // sum w n x A = int B dV
        out.torque = Mt.cross(nxA); // Eq. 17
        out.energy = -Mt.dot(nxA);
        out.fieldIntegral = nxA;
    }
    return out;
}

Mat3 fieldIntegralMap(const PolyhedronTables& source, std::span<const Vec3> points,
                      std::span<const double> weights, std::span<const Vec3> normals, OverlapModel model,
                      ForceForm form) {
    // S and f do not depend on Ms; the kernel is asked for them alone.
    const SampleField& s = fieldAtSamples(source, Vec3::UnitZ(), points, weights, normals, false);
    const bool exterior = model == OverlapModel::exterior;
    Mat3 phiN = Mat3::Zero();       // sum w n S^T: phiN (interactionWrench) = phiN Ms
    Mat3 normalPart = Mat3::Zero(); // exterior: normalPart = this Ms
    Mat3 nxA = Mat3::Zero();        // sum w [(n . S) I - S n^T]: n x (Ms x S) = this Ms
    for (std::size_t k = 0; k < points.size(); ++k) {
        const double w = weights[k];
        const Vec3& n = normals[k];
        if (model == OverlapModel::amperian) {
            nxA += w * (n.dot(s.S[k]) * Mat3::Identity() - s.S[k] * n.transpose());
            continue;
        }
        phiN += w * n * s.S[k].transpose();
        if (exterior && s.f[k] > kInsideFloor) {
            const PolyFace& face = nearestFace(source, points[k]);
            const Vec3& ns = face.normal;
            const double depth = w * s.f[k] * (ns.dot(points[k]) - face.offset);
            // interactionWrench: sigma: depth (Ms . ns) n; split: depth (ns . n) (Ms . ns) ns.
            normalPart += form == ForceForm::surfaceCharge ? Mat3(depth * n * ns.transpose())
                                                           : Mat3((depth * ns.dot(n)) * ns * ns.transpose());
        }
    }
    if (model == OverlapModel::amperian) return (mu0 / kFourPi) * nxA;
    Mat3 K = -(mu0 / kFourPi) * phiN;
    if (exterior) K += mu0 * normalPart;
    return K;
}

InteractionEnergy interactionEnergy(const PolyhedronTables& source, const Vec3& Ms,
                                    std::span<const Vec3> points,
                                    std::span<const double> weights,
                                    std::span<const Vec3> normals, const Vec3& Mt) {
    const SampleField& s = fieldAtSamples(source, Ms, points, weights, normals, false);
    const double k = mu0 / kFourPi;
    InteractionEnergy e;
    double sn = 0.0;
    Vec3 intB = Vec3::Zero(), intPhiN = Vec3::Zero();
    double charge = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const double w = weights[i];
        const Vec3& n = normals[i];
        const Vec3& S = s.S[i];
        sn += w * S.dot(n);                     // 4 pi x overlap volume
        intB += w * n.cross(Ms.cross(S));       // (4 pi / mu0) int B dV
        const double phi = Ms.dot(S);           // 4 pi phi
        intPhiN += (w * phi) * n;
        charge += w * phi * Mt.dot(n);
    }
    e.overlapVolume = sn / kFourPi;
    e.integralB = k * intB;
    e.integralH = -intPhiN / kFourPi;
    e.amperian = -Mt.dot(e.integralB);
    e.charge = k * charge;
    return e;
}

} // namespace mag::mbm
