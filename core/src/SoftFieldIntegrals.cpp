#include "magFoam/SoftFieldIntegrals.hpp"

#include "magFoam/AppliedField.hpp"
#include "magFoam/FieldEvaluator.hpp"

#include <span>

namespace mag {

SoftFieldIntegrals softFieldIntegrals(const std::vector<Body>& bodies, const std::vector<std::size_t>& soft,
                                      const FieldEvaluator& field, const AppliedField& applied, bool softPairs) {
    const std::size_t n = soft.size();
    SoftFieldIntegrals r;
    r.fixed.assign(n, Vec3::Zero());
    r.coupling.assign(n * n, Mat3::Zero());
    std::vector<int> slot(bodies.size(), -1); // body -> soft index
    for (std::size_t a = 0; a < n; ++a) slot[soft[a]] = static_cast<int>(a);
    // The applied field: its wrench energy, linear in M, per unit magnetization.
    if (applied.active())
        for (std::size_t a = 0; a < n; ++a) {
            Body unit = bodies[soft[a]];
            for (int c = 0; c < 3; ++c) {
                unit.magnetizationBody = unit.orientation.conjugate() * Vec3::Unit(c);
                r.fixed[a][c] -= applied.wrench(unit).ownEnergy;
            }
        }
    // Pairs with another body: U = -M_t . K M_s from the target's samples, so
    // the target responds to K M_s and the source to K^T M_t. Pairs within a
    // compound stay in: the forces between its parts cancel, their fields on
    // each other's magnetization do not (cells).
    const std::span<const Body> all(bodies);
    for (std::size_t i = 0; i < bodies.size(); ++i)
        for (std::size_t j = i + 1; j < bodies.size(); ++j) {
            const BodyPair p = FieldEvaluator::orientedPair(all, i, j);
            const Body &s = bodies[p.source], &t = bodies[p.target];
            const int ss = slot[p.source], ts = slot[p.target];
            if (ss < 0 && ts < 0) continue;
            if (ss >= 0 && ts >= 0) {
                if (!softPairs) continue;
                const Mat3 K = field.fieldIntegralMap(s, t);
                r.coupling[ts * n + ss] = K, r.coupling[ss * n + ts] = K.transpose();
            } else if (ts >= 0) { // soft target, permanent source: K M_s in one call
                if (s.magnetizationBody.squaredNorm() > 0) r.fixed[ts] += field.fieldIntegral(s, t);
            } else if (t.magnetizationBody.squaredNorm() > 0) { // soft source, permanent target: K^T M_t
                r.fixed[ss] += field.fieldIntegralMap(s, t).transpose() * t.magnetization();
            }
        }
    for (std::size_t a = 0; a < n; ++a) {
        const double V = bodies[soft[a]].shape->volume;
        r.fixed[a] /= V;
        for (std::size_t b = 0; b < n; ++b) r.coupling[a * n + b] /= V;
    }
    return r;
}

} // namespace mag
