#include "magFoam/Parts.hpp"

#include "magFoam/Error.hpp"

#include <string>

namespace mag {

CompoundLayout makeCompound(std::vector<Part> parts) {
    if (parts.empty()) throw InputError("a compound body needs at least one part");
    auto compound = std::make_shared<Compound>();
    double mass = 0, volume = 0;
    Vec3 moment = Vec3::Zero();
    for (const Part& p : parts) {
        const double m = p.material.density * p.shape->volume;
        mass += m, volume += p.shape->volume;
        moment += m * p.position;
    }
    const Vec3 centre = moment / mass;
    // Parallel axes: each part's inertia about its own centre, turned into the
    // body frame, plus m (|d|^2 1 - d d^T) for its offset d from the compound's centre.
    Mat3 inertia = Mat3::Zero();
    auto shape = std::make_shared<Shape>();
    shape->mesh.source = "compound of " + std::to_string(parts.size()) + " parts";
    for (Part& p : parts) {
        p.position -= centre;
        const double m = p.material.density * p.shape->volume;
        const Mat3 R = p.orientation.toRotationMatrix();
        const Vec3& d = p.position;
        inertia += p.material.density * (R * p.shape->unitInertia * R.transpose()) +
                   m * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
        compound->firstTriangle.push_back(shape->mesh.triangles.size());
        const int offset = shape->mesh.nVertices();
        for (const Vec3& v : p.shape->mesh.vertices) shape->mesh.vertices.push_back(R * v + d);
        for (const auto& t : p.shape->mesh.triangles)
            shape->mesh.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
        compound->anySoft = compound->anySoft || p.material.soft();
    }
    for (const Vec3& v : shape->mesh.vertices) shape->boundingRadius = std::max(shape->boundingRadius, v.norm());
    shape->kind.kind = ShapeKind::Kind::compound;
    shape->volume = volume;
    // Per unit mean density, so that mean density * unitInertia is the inertia.
    shape->unitInertia = inertia * (volume / mass);
    compound->mass = mass;
    compound->inertia = inertia;
    compound->parts = std::move(parts);
    return {std::move(compound), std::move(shape), centre};
}

Vec3 meanMagnetization(const Compound& c, std::span<const Vec3> partMagnetization) {
    Vec3 moment = Vec3::Zero();
    double volume = 0;
    for (std::size_t k = 0; k < c.parts.size(); ++k) {
        const Part& p = c.parts[k];
        moment += p.shape->volume * (p.orientation * partMagnetization[k]);
        volume += p.shape->volume;
    }
    return moment / volume;
}

bool hasCompounds(std::span<const Body> bodies) {
    for (const Body& b : bodies)
        if (b.compound) return true;
    return false;
}

Body PartBodies::part(const Body& owner, std::size_t k, std::uint32_t group) {
    const Part& p = owner.compound->parts[k];
    Body b;
    b.name = owner.name + "/" + std::to_string(k);
    b.shape = p.shape;
    b.material = p.material;
    b.fixed = owner.fixed;
    b.held = owner.held;
    b.group = group;
    b.magnetizationBody = owner.partMagnetization[k];
    b.position = owner.toWorld(p.position);
    b.orientation = owner.orientation * p.orientation;
    b.velocity = owner.velocity + owner.angularVelocity.cross(b.position - owner.position);
    b.angularVelocity = owner.angularVelocity;
    return b;
}

PartBodies::PartBodies(std::span<const Body> bodies) {
    first.reserve(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Body& b = bodies[i];
        first.push_back(parts.size());
        if (!b.compound) {
            parts.push_back(b);
            owner.push_back(i);
            continue;
        }
        for (std::size_t k = 0; k < b.compound->parts.size(); ++k) {
            parts.push_back(part(b, k, static_cast<std::uint32_t>(i + 1)));
            owner.push_back(i);
        }
    }
}

void PartBodies::storeMagnetizations(std::span<Body> bodies) const {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        Body& b = bodies[i];
        if (!b.compound) {
            b.magnetizationBody = parts[first[i]].magnetizationBody;
            continue;
        }
        for (std::size_t k = 0; k < b.compound->parts.size(); ++k)
            b.partMagnetization[k] = parts[first[i] + k].magnetizationBody;
        b.magnetizationBody = meanMagnetization(*b.compound, b.partMagnetization);
    }
}

std::vector<Wrench> PartBodies::sum(std::span<const Body> bodies, std::span<const Wrench> partWrenches) const {
    std::vector<Wrench> out(bodies.size());
    for (std::size_t p = 0; p < parts.size(); ++p) {
        const std::size_t i = owner[p];
        const Wrench& w = partWrenches[p];
        out[i] += w;
        if (bodies[i].compound) out[i].mechanicalTorque += (parts[p].position - bodies[i].position).cross(w.force);
    }
    return out;
}

} // namespace mag
