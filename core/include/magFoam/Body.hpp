// A rigid magnetic body: its fixed model (name, material, an immutable shape
// shared by every body built from the same geometry: mesh in the body frame,
// origin at the centre of mass, mass properties) and its per-step state (pose,
// velocities, magnetization). A compound body is made of several parts, each
// with its own shape, material and magnetization (docs/compound-bodies.md).
#pragma once

#include "magFoam/ConvexPieces.hpp"
#include "magFoam/Material.hpp"
#include "magFoam/SurfaceMesh.hpp"
#include "magFoam/Types.hpp"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace mag {

// What the geometry was made from; backends use it to choose native
// collision shapes (ODE box/sphere/cylinder) instead of a triangle mesh.
struct ShapeKind {
    enum class Kind { box, sphere, cylinder, mesh, compound };
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
    // Convex pieces whose union is the mesh, for collision only (a concave
    // mesh file's <stem>.pieces.yaml; ConvexPieces.hpp), body frame. Empty:
    // none given (backends use the mesh).
    std::vector<ConvexHull> pieces;
};

// One part of a compound body: a shape of its own material, placed in the
// compound's body frame.
struct Part {
    std::shared_ptr<const Shape> shape;  // part frame: the part's centre of mass at the origin
    Material material;
    Vec3 position = Vec3::Zero();        // the part's centre of mass in the body frame
    Quat orientation = Quat::Identity(); // part frame -> body frame
};

// What makes a body compound, shared by its copies: the parts and the exact
// mass properties of their union (each part with its own density).
struct Compound {
    std::vector<Part> parts;
    double mass = 0;                      // kg
    Mat3 inertia = Mat3::Zero();          // about the compound's centre of mass, body frame
    std::vector<std::size_t> firstTriangle; // the body's mesh (the parts' meshes in turn): part k's from here
    bool anySoft = false;

    // The part a triangle of the body's mesh belongs to.
    std::size_t partOfTriangle(std::size_t triangle) const {
        return static_cast<std::size_t>(std::upper_bound(firstTriangle.begin(), firstTriangle.end(), triangle) -
                                        firstTriangle.begin()) - 1;
    }
};

// What a body is, fixed for a run: read from the case, shared by the models.
// A compound body's shape is the union of its parts' meshes in the body frame
// (for collision, bounds and output); the field models never see it, only its
// parts (Parts.hpp).
struct BodyModel {
    std::string name;
    std::shared_ptr<const Shape> shape;
    Material material;
    bool fixed = false;
    // A dynamic body that a view of the scene marks fixed for now (a sleeping
    // one, docs/dynamics.md#sleeping): its pairs are skipped like a fixed
    // body's, but each pair keeps the orientation it has while the body moves
    // (FieldEvaluator::orientedPair), so its wrench is the same either way.
    bool held = false;
    std::shared_ptr<const Compound> compound;  // null for a body of one part
    // Parts of one compound body, as the field models see them, share a
    // nonzero group: their pairs exert no net force on the body and are left
    // out of the wrenches (FieldEvaluator::sameRigidBody).
    std::uint32_t group = 0;

    double mass() const { return compound ? compound->mass : material.density * shape->volume; }
    Mat3 inertiaBody() const { return compound ? compound->inertia : Mat3(material.density * shape->unitInertia); }
    // A compound is soft when one of its parts is.
    bool soft() const { return compound ? compound->anySoft : material.soft(); }
};

// Where a body is and how it moves and is magnetized: the per-step state that
// the solver owns, writes to each time folder (<time>/bodies.yaml) and reads
// back on restart. Models keep their own extra state (InductionModel,
// RigidBodyBackend) and write it beside it.
struct BodyState {
    // Magnetization in the BODY frame, A/m. Permanent: Br/mu0 along the given
    // direction; soft: the induced value (carried with the body between steps).
    // A compound's: its parts' mean, total moment / total volume (for
    // outputs and its far field; its parts' own are below).
    Vec3 magnetizationBody = Vec3::Zero();
    // A compound's parts' magnetizations, each in its part's frame, A/m.
    std::vector<Vec3> partMagnetization;

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
