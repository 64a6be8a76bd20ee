// A rigid magnetic body: an immutable shape (mesh in the body frame, origin at
// the centre of mass, plus mass properties) shared by every body built from the
// same geometry, and the per-step state (pose, velocities, magnetization).
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

struct Body {
    std::string name;
    std::shared_ptr<const Shape> shape;
    Material material;
    bool fixed = false;

    // Magnetization in the BODY frame, A/m. Permanent: Br/mu0 along the given
    // direction; soft: the induced value (carried with the body between steps).
    Vec3 magnetizationBody = Vec3::Zero();

    // State (world frame): centre of mass, orientation body->world, velocities.
    Vec3 position = Vec3::Zero();
    Quat orientation = Quat::Identity();
    Vec3 velocity = Vec3::Zero();
    Vec3 angularVelocity = Vec3::Zero();

    double mass() const { return material.density * shape->volume; }
    Mat3 inertiaBody() const { return material.density * shape->unitInertia; }
    Mat3 inertiaWorld() const {
        const Mat3 R = orientation.toRotationMatrix();
        return R * inertiaBody() * R.transpose();
    }
    Vec3 magnetization() const { return orientation * magnetizationBody; }  // world, A/m
    Vec3 magneticMoment() const { return magnetization() * shape->volume; } // A m^2
    Vec3 toWorld(const Vec3& pBody) const { return orientation * pBody + position; }
    Vec3 toBody(const Vec3& pWorld) const { return orientation.conjugate() * (pWorld - position); }
    bool soft() const { return material.soft(); }
};

} // namespace mag
