// What soft bodies respond to when their magnetization is to be stationary for
// the energy the forces derive from (docs/physics.md#demag): the fields of
// everything else averaged over each soft body as the evaluator's interaction
// energy sees them, I / V with I = -dU/dM (FieldEvaluator::fieldIntegral),
// each pair taken in the orientation addWrenches() evaluates it. The demag
// model and LLG with `average` solve their magnetizations from these.
#pragma once

#include "magFoam/Body.hpp"

#include <cstddef>
#include <vector>

namespace mag {

class AppliedField;
class FieldEvaluator;

struct SoftFieldIntegrals {
    // Per soft body a (index into `soft`): the applied field's and the
    // permanent bodies' field averaged over it (T).
    std::vector<Vec3> fixed;
    // coupling[a n + b]: the field of soft body b averaged over soft body a per
    // unit world magnetization of b (T per A/m); zero unless asked for.
    std::vector<Mat3> coupling;
};

// `soft`: the indices of the soft bodies in `bodies`. With softPairs the
// soft-soft maps too (one FieldEvaluator::fieldIntegralMap per pair; the
// source's map transposed for the other side, so the pair's energy is counted
// from one set of samples). A pair with a permanent target and a soft source
// responds through the map's transpose, K^T M_t.
SoftFieldIntegrals softFieldIntegrals(const std::vector<Body>& bodies, const std::vector<std::size_t>& soft,
                                      const FieldEvaluator& field, const AppliedField& applied, bool softPairs);

} // namespace mag
