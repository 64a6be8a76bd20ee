// A rigid magnetic body: its fixed model (name, material, an immutable shape
// shared by every body built from the same geometry: mesh in the body frame,
// origin at the centre of mass, mass properties) and its per-step state (pose,
// velocities, magnetization).
#pragma once

#include "magFoam/Material.hpp"
#include "magFoam/SurfaceMesh.hpp"
#include "magFoam/Types.hpp"

#include <memory>
#include <string>

namespace mag {

// What the geometry was made from; backends use it to choose native
// collision shapes (ODE box/sphere/cylinder) instead of a triangle mesh.
struct ShapeKind {
    enum class Kind { box, sphere, cylinder, mesh };
    Kind kind = Kind::mesh;
    Vec3 size = Vec3::Zero();  // box edge lengths
    double radius = 0;         // sphere, cylinder
    double height = 0;         // cylinder (along body z)
    std::string file;          // mesh source
};

// Immutable per-geometry data: built once, shared (std::shared_ptr) by bodies.
struct Shape {
    SurfaceMesh mesh;          // body frame: centre of mass at the origin
    ShapeKind kind;
    double volume = 0;         // m^3
    Mat3 unitInertia = Mat3::Zero();  // inertia about the COM for density 1
    double boundingRadius = 0; // max vertex distance from the COM
};

// What a body is, fixed for a run: read from the case, shared by the models.
struct BodyModel {
    std::string name;
    std::shared_ptr<const Shape> shape;
    Material material;
    bool fixed = false;

    double mass() const { return material.density * shape->volume; }
    Mat3 inertiaBody() const { return material.density * shape->unitInertia; }
    bool soft() const { return material.soft(); }
};

// Where a body is and how it moves and is magnetized: the per-step state that
// the solver owns, writes to each time folder (<time>/bodies.yaml) and reads
// back on restart. Models keep their own extra state (InductionModel,
// RigidBodyBackend) and write it beside it.
struct BodyState {
    // Magnetization in the BODY frame, A/m. Permanent: Br/mu0 along the given
    // direction; soft: the induced value (carried with the body between steps).
    Vec3 magnetizationBody = Vec3::Zero();

    // World frame: centre of mass, orientation body->world, velocities.
    Vec3 position = Vec3::Zero();
    Quat orientation = Quat::Identity();
    Vec3 velocity = Vec3::Zero();
    Vec3 angularVelocity = Vec3::Zero();

    Vec3 magnetization() const { return orientation * magnetizationBody; }  // world, A/m
    Vec3 toWorld(const Vec3& pBody) const { return orientation * pBody + position; }
    Vec3 toBody(const Vec3& pWorld) const { return orientation.conjugate() * (pWorld - position); }
};

// A body as the models see it in a step: its model and its current state.
struct Body : BodyModel, BodyState {
    Mat3 inertiaWorld() const {
        const Mat3 R = orientation.toRotationMatrix();
        return R * inertiaBody() * R.transpose();
    }
    Vec3 magneticMoment() const { return magnetization() * shape->volume; } // A m^2
};

// Kinetic energy (J) of a body of model `m` in state `s`: 1/2 m |v|^2 + 1/2 w . I_world w
// (0 for a fixed body).
inline double kineticEnergy(const BodyModel& m, const BodyState& s) {
    if (m.fixed) return 0.0;
    const Mat3 R = s.orientation.toRotationMatrix();
    const Mat3 I = R * m.inertiaBody() * R.transpose(); // Body::inertiaWorld()
    return 0.5 * m.mass() * s.velocity.squaredNorm() + 0.5 * s.angularVelocity.dot(I * s.angularVelocity);
}

} // namespace mag
