// Fast multipole sum of the dipole far field: the same pairs as addDipoleFarField()
// (DipoleFarField.hpp), in O(N) instead of O(N^2).
//
// The bodies go in a k-d tree (halves at the median); every cell carries the
// multipole expansion of its dipoles' scalar potential
// phi = sum m . (x - y) / |x - y|^3 (B = -mu0/(4 pi) grad phi) in solid harmonics
// up to degree p. A dual-tree walk (Dehnen 2002) pairs cells that are well apart,
// (r_A + r_B) < theta |z_A - z_B|, and whose every body pair is a dipole pair,
// |z_A - z_B| - r_A - r_B > reach_A + reach_B: such a pair costs one
// multipole-to-local translation each way. Leaf pairs that are not, and cell
// pairs with at most directPairs body pairs, are summed directly, pair by pair,
// with the test of isDipolePair(), so exactly the dipole pairs are counted and
// the near pairs are left to the field evaluator. A body then gets B and grad B at its centre from
// its cell's local expansion: force grad(m . B), torque m x B, energy -m . B.
//
// Accuracy: the truncation error of a translation is O(theta^(p - 2)) relative to
// the interacting cells' pair forces (the force on a dipole takes the second
// derivatives of phi). tests/test_dipoleMultipole.cpp measures, against the direct
// sum, the largest error of a body's force and torque over the sum of the
// magnitudes of its dipole pairs' forces and torques (the scale the dipole
// approximation's own error, DipoleFarField.hpp, is relative to).
//
// Threads: the walk is serial; translations run per target cell and the direct
// sums per target leaf, each in a fixed order, so results are bit-identical for
// any thread count. Fixed bodies with skipFixedPairs get the direct sum (they are
// few: the pairs of two fixed bodies must be left out, which a cell's expansion
// cannot do).
#pragma once

#include "DipoleFarField.hpp"
#include "magFoam/Dictionary.hpp"

#include <cstdint>
#include <span>

namespace mag {

struct MultipoleSettings {
    int order = 12;           // p, the highest degree of the expansions
    double theta = 0.5;       // opening angle of the cell pair test
    std::size_t leafSize = 64;  // bodies per leaf cell, at most
    // Cell pairs with at most this many body pairs are summed directly: a
    // translation costs about as much as a few hundred direct pairs.
    double directPairs = 300;
};

// Same contract as addDipoleFarField(): adds the wrench from every dipole pair to
// out[i] and returns the number of dipole pairs.
std::uint64_t addDipoleFarFieldMultipole(std::span<const FarFieldBody> bodies, bool skipFixedPairs,
                                         std::span<Wrench> out, const MultipoleSettings& settings = {});

// How the hybrid evaluator sums its dipole pairs; system/magSchemes.yaml:
//   field: {type: hybrid, ...,
//           farField: {method: auto, multipoleAbove: 3000, order: 12, theta: 0.5, leafSize: 64,
//                      directPairs: 300}}
// method: direct (all pairs, O(N^2), exact to rounding) | multipole (above) | auto
// (multipole when more than multipoleAbove bodies take part, else direct).
struct FarFieldSettings {
    enum class Method { automatic, direct, multipole };
    Method method = Method::automatic;
    std::size_t multipoleAbove = 3000;
    MultipoleSettings multipole;

    static FarFieldSettings read(const Dict& d);
    bool usesMultipole(std::size_t bodies) const {
        return method == Method::multipole || (method == Method::automatic && bodies > multipoleAbove);
    }
    std::string describe() const;
};

// The dipole far field by the chosen method.
std::uint64_t addDipoleFarField(std::span<const FarFieldBody> bodies, bool skipFixedPairs, std::span<Wrench> out,
                                const FarFieldSettings& settings);

} // namespace mag
