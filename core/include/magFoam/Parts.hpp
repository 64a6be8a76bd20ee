// Compound bodies (docs/compound-bodies.md): one rigid body made of parts,
// each a shape of its own material and magnetization. The field and induction
// models work on parts, one uniformly magnetized polyhedron each, and never
// see a compound: MagneticSystem hands them the parts of every body
// (PartBodies) and sums the parts' wrenches back to their bodies.
#pragma once

#include "magFoam/Body.hpp"
#include "magFoam/Wrench.hpp"

#include <span>
#include <vector>

namespace mag {

// A compound from parts placed in a layout frame (each part's position is its
// centre of mass there): its mass properties, exact from the parts' with each
// part's density, and the union of the parts' meshes as the body's shape. The
// parts come back placed about the compound's centre of mass, which is
// `centreOfMass` in the layout frame.
struct CompoundLayout {
    std::shared_ptr<const Compound> compound;
    std::shared_ptr<const Shape> shape;
    Vec3 centreOfMass = Vec3::Zero();
};
CompoundLayout makeCompound(std::vector<Part> parts);

// The compound's mean magnetization in the body frame (total moment / total
// volume) from its parts' magnetizations.
Vec3 meanMagnetization(const Compound& c, std::span<const Vec3> partMagnetization);

// Whether any body is compound.
bool hasCompounds(std::span<const Body> bodies);

// Every body's parts as bodies of their own: a compound's parts placed where
// the body is (moving with it; named "<body>/<k>", in one nonzero group per
// compound), a body of one part as it is. `owner[p]` is the body of part p,
// `first[i]` body i's first part.
struct PartBodies {
    std::vector<Body> parts;
    std::vector<std::size_t> owner, first;

    explicit PartBodies(std::span<const Body> bodies);
    // Part p as a body of its own (placed, magnetized) from its owner.
    static Body part(const Body& owner, std::size_t k, std::uint32_t group);
    // The parts' magnetizations (soft parts converged) back to their bodies.
    void storeMagnetizations(std::span<Body> bodies) const;
    // The parts' wrenches summed to their bodies: forces and torques added,
    // and each part's force moved to the body's centre of mass.
    std::vector<Wrench> sum(std::span<const Body> bodies, std::span<const Wrench> partWrenches) const;
};

} // namespace mag
