// ODE: rigid bodies with contacts, through the Open Dynamics Engine (Debian
// 12's ODE 0.16.2: double precision, OPCODE trimesh collider, not
// thread-safe). Bodies feel the magnetic wrench (force at the COM, torque +
// mechanical torque), gravity, the ground and each other.
//
//   # constant/rigidBody.yaml
//   type: ODE
//   gravity: [0, 0, -9.81]
//   ground: {height: 0}              # omit for no ground
//   contact: {friction: 0.5, restitution: 0.1, erp: 0.2, cfm: 1e-9, maxContacts: 8}
//   subSteps: 1
//
// Keys: kDoc at the registration below (magFoam -doc ODE).
//
// Why these defaults (measured on 1 cm, 7.5 g cubes pulled together by 50 N,
// i.e. ~680 g, as in the magnet scenes; tests/test_odeBackend.cpp):
// - erp 0.2, cfm 1e-9 (the issue's values): contacts effectively rigid in SI
//   (spring erp/(h cfm) = 2e11 N/m at h = 1 ms) while the LCP stays regular.
// - maxCorrectingVelocity 0.1 m/s (ODE: unlimited): ODE has no split impulse,
//   the push-out velocity erp * depth / h stays in the body. Unlimited, 1 mm
//   of penetration at h = 0.1 ms leaves at 2 m/s: energy injected. Capped, a
//   body gains at most m (0.1 m/s)^2 / 2 from penetration correction.
// - bounceVelocity 0.1 m/s = maxCorrectingVelocity: push-out and resting
//   velocities never bounce (no pumping of resting contacts); restitution
//   acts on real impacts only and always returns less than it took.
// - surfaceLayer 1 um (ODE: 0): with 0, touching trimesh faces lose their
//   contacts every other step (coplanar triangles), so a pulled cube sinks
//   30 um, is pushed out, sinks again: bursts of 60 rad/s. With a layer the
//   bodies rest 1 um into each other and keep their contacts. Invisible at
//   mm..m scales, and the same for primitives.
// - maxTravel 0.1: at 50 N and deltaT = 1 ms a cube moves 7 mm in one step
//   and tunnels through the other (also with ODE's own box-box collider).
//   Sub-steps are added from the body's speed, spin and external
//   acceleration (contacts ignored: conservative, e.g. 4 sub-steps for the
//   resting cubes at 1 ms, 386 at 10 ms). The wrench is held over them.
// - stepper step: dWorldStep solves each island's LCP directly, so stacks
//   under 1000 g forces rest exactly (no iteration residual, no creep); its
//   cost grows with the cube of the contact count, fine for tens of magnets.
//   quickStep (iterative, O(contacts)) for large heaps.
// - frictionBound normalForce: dWorldStep's findex rows take their friction
//   bound from a solve without friction; where that solve leaves a contact
//   unloaded, it slides with zero friction however hard it is pressed (four
//   magnets in a chain glided over the ground for ever). A sub-step with
//   such a starved contact is solved once more (its islands only), that
//   contact's friction bounded by mu times its normal force from the first
//   solve (docs/rigid-bodies.md#friction-bounds).
//
// Bodies. The ODE body origin is the COM: mass and inertia tensor about the
// COM from the mesh (Body::mass, inertiaBody; dMassSetParameters), finite
// rotation mode (exact rotation by w h per step), no auto-disable, no damping.
// Fixed bodies are static geoms (no ODE body): they never move, their wrench
// is ignored, their velocities are written as zero. setState() (a restart,
// a script) moves the bodies there in ODE, exactly: ODE renormalises every
// quaternion it is given, which can change its last bit, so the quaternion
// handed over is the one ODE turns into the given one (found by trying the
// neighbouring doubles; ODE's own quaternions are unit already).
//
// Collision shapes (`collisionShapes: auto`): box, sphere and cylinder
// bodies get ODE's native geoms (exact, fast; ODE cylinders lie along z like
// ours; sphere/cylinder geoms are the true shapes, the mass is the mesh's);
// a mesh body that is exactly a box (face normals along three orthogonal
// axes, volume = that of its bounding box) becomes a box geom with an
// offset; a concave mesh with convex pieces (its <stem>.pieces.yaml,
// docs/rigid-bodies.md#convex-pieces) one dConvex geom per piece, a convex
// mesh of at most 256 vertices one dConvex of its hull (ODE 0.16 collides
// convex geoms through libccd, one contact per pair, which is clipped to the
// touching faces' contact set below; exactly with the ground plane); every
// other mesh a dGeomTriMesh of the body-frame mesh.
// Convex geoms are centred on their hull's centroid: libccd takes the geom
// centre as a point inside the shape. `trimesh` uses no pieces or hulls;
// `mesh` makes every body a trimesh (for comparisons and the tests).
// A compound body (docs/compound-bodies.md) gets one geom per part, each
// chosen as above from the part's own shape and offset to the part's place
// on the one ODE body; ODE does not collide geoms of one body.
//
// Contacts. A near callback collects up to 64 contacts per pair from
// dCollide; pairs with a triangle mesh get their normals and depths
// corrected from the local geometry (ContactManifold.hpp explains why and
// how: ODE 0.16's trimesh-trimesh contacts between face-to-face meshes carry
// side normals that throw the upper body sideways); libccd's one contact of
// two convex geoms (or a box and a convex geom) becomes the contact set of
// the touching faces (clipFaceContacts there); then coincident contacts
// are merged and at most maxContacts kept (deepest first, then farthest
// apart). Contact joints: dContactApprox1 | SoftERP | SoftCFM (| Bounce).
//
// Determinism: every ODE call runs under one process-wide lock; ODE's global
// random generator is set to this backend's own state before each world step
// and read back after, so runs are bit-identical, also with several backends
// in one process. dInitODE2 runs once per process.
//
// Restart state. A step depends on the bodies' state, the wrench, and two
// things ODE carries: its random generator (quickStep's constraint order)
// and the order of the geoms in the collision space, which sets the order of
// the contact joints and so the round-off of the LCP solution (ODE moves a
// geom to the front of the space when it moves; a restart would create them
// in another order). Nothing else: dWorldStep has no warm starting, joint
// feedback is read only within the sub-step that made it, auto-disable is
// off, contact joints are made anew every sub-step, the sub-step count
// comes from the state. Both are written as
// <time>/rigidBody.yaml
//   type: ODE
//   random: 12345                        # ODE's dRandGetSeed()
//   spaceOrder: [cube, disc, (ground)]   # geoms, first to last; (ground): the plane
// and restored at a restart, which then continues bit for bit.
#include "ContactManifold.hpp"

#include <magFoam/ContactSettings.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/RigidBodyBackend.hpp>

#include <ode/ode.h>

#include <magFoam/ResultsWriter.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <exception>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace mag {

namespace {

// ---------------------------------------------------------------------------
// Process-wide ODE state. ODE keeps global collider caches and one global
// random generator: every ODE call of every backend instance runs under this
// lock, and dInitODE2 runs once per process.
// ---------------------------------------------------------------------------
std::mutex& odeMutex() {
    static std::mutex m;
    return m;
}

std::string formatMessage(const char* msg, va_list ap) {
    char text[1024];
    std::vsnprintf(text, sizeof text, msg, ap);
    return text;
}

// ODE messages (e.g. "LCP internal error") are warnings: the first few are
// logged, the rest only at debug level.
void onMessage(int errnum, const char* msg, va_list ap) {
    static int count = 0;
    const std::string text = formatMessage(msg, ap);
    if (++count <= 5)
        spdlog::warn("ODE message {}: {}{}", errnum, text, count == 5 ? " (further ODE messages at debug level)" : "");
    else
        spdlog::debug("ODE message {}: {}", errnum, text);
}

// ODE errors must not return: they become a StateError the solver reports.
void onError(int errnum, const char* msg, va_list ap) {
    throw StateError("ODE error " + std::to_string(errnum) + ": " + formatMessage(msg, ap));
}

void initODE() {
    static std::once_flag once;
    std::call_once(once, [] {
        dInitODE2(0);
        dSetMessageHandler(onMessage);
        dSetErrorHandler(onError);
        dSetDebugHandler(onError);
    });
    dAllocateODEDataForThread(dAllocateMaskAll);
}

// ---------------------------------------------------------------------------
// Collision shapes, built once per Shape and shared by its bodies.
// ---------------------------------------------------------------------------
struct CollisionShape {
    enum class Type { box, sphere, cylinder, convex, trimesh };
    Type type = Type::trimesh;
    Vec3 size = Vec3::Zero();           // box edge lengths
    double radius = 0, height = 0;      // sphere, cylinder (along the geom's z)
    Vec3 offset = Vec3::Zero();         // geom centre in the body frame
    Quat offsetRotation = Quat::Identity(); // geom axes in the body frame
    double scale = 0;                   // bounding radius about the COM, m
    std::shared_ptr<const Shape> shape; // keeps the mesh (and the ODE data's arrays) alive
    std::vector<double> vertices;       // trimesh arrays handed to ODE (not copied by it)
    std::vector<dTriIndex> indices;
    dTriMeshDataID data = nullptr;
    ode::TriangleSet triangles;         // trimesh: for the contact correction
    ConvexHull hull;                    // convex: about the geom centre (the hull's centroid)
    std::vector<double> planes;         // convex arrays handed to ODE (not copied by it)
    std::vector<double> points;
    std::vector<unsigned int> polygons;

    CollisionShape() = default;
    CollisionShape(const CollisionShape&) = delete;
    CollisionShape& operator=(const CollisionShape&) = delete;
    ~CollisionShape() {
        if (data) dGeomTriMeshDataDestroy(data);
    }

    std::string name() const {
        switch (type) {
        case Type::box: return "box";
        case Type::sphere: return "sphere";
        case Type::cylinder: return "cylinder";
        case Type::convex: return "convex";
        case Type::trimesh: return "trimesh";
        }
        return "?";
    }
};

// A mesh that is exactly a box (every face normal along one of three
// orthogonal axes, and the volume of its bounding box along them): its edge
// lengths, centre and axes in the body frame.
struct DetectedBox {
    Vec3 size;
    Vec3 centre;
    Mat3 axes;
};
std::optional<DetectedBox> detectBox(const Shape& shape) {
    // Relative tolerances of STL-in-float accuracy (~1e-7).
    const double tol = 1e-6;
    const std::vector<Vec3> normals = triangleNormals(shape.mesh);
    std::optional<Vec3> u, v;
    for (const Vec3& n : normals) {
        if (n.squaredNorm() < 0.5) continue;
        if (!u)
            u = n;
        else if (!v && std::abs(n.dot(*u)) < tol)
            v = n;
    }
    if (!u || !v) return std::nullopt;
    Mat3 axes;
    axes.col(0) = *u;
    axes.col(1) = (*v - v->dot(*u) * *u).normalized();
    axes.col(2) = axes.col(0).cross(axes.col(1));
    for (const Vec3& n : normals)
        if (n.squaredNorm() > 0.5 && (axes.transpose() * n).cwiseAbs().maxCoeff() < 1 - tol) return std::nullopt;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec3& p : shape.mesh.vertices) {
        const Vec3 q = axes.transpose() * p;
        lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
    }
    const Vec3 size = hi - lo;
    if (std::abs(size.prod() - shape.volume) > tol * shape.volume) return std::nullopt;
    return DetectedBox{size, axes * (0.5 * (lo + hi)), axes};
}

// Boxes and convex hulls: the shapes whose face contacts are clipped.
bool polytope(const CollisionShape& cs) {
    return cs.type == CollisionShape::Type::convex || cs.type == CollisionShape::Type::box;
}
// A geom's world pose: its centre and its rotation (geom frame -> world).
void geomPose(dGeomID g, Vec3& position, Mat3& rotation) {
    const dReal* p = dGeomGetPosition(g);
    const dReal* r = dGeomGetRotation(g); // 3x4, row major
    position = Vec3(p[0], p[1], p[2]);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) rotation(i, j) = r[4 * i + j];
}

ode::PolytopeView polytopeView(dGeomID g, const CollisionShape& cs) {
    ode::PolytopeView view;
    geomPose(g, view.position, view.rotation);
    view.hull = &cs.hull;
    return view;
}

// A geom as the contact correction sees it (ContactManifold.hpp): pose,
// support function, and triangles (meshes) or surface normals (primitives).
ode::GeomView geomView(dGeomID g, const CollisionShape& cs) {
    ode::GeomView view;
    geomPose(g, view.position, view.rotation);
    const Vec3 c = view.position;
    const Mat3 R = view.rotation;
    switch (cs.type) {
    case CollisionShape::Type::box:
        view.support = [c, R, half = 0.5 * cs.size](const Vec3& u) {
            return c.dot(u) + (R.transpose() * u).cwiseAbs().dot(half);
        };
        view.surfacePlanes = [c, R, half = 0.5 * cs.size](const Vec3&, std::vector<ode::Plane>& out) {
            for (int k = 0; k < 3; ++k)
                for (double sign : {1.0, -1.0}) {
                    const Vec3 n = sign * R.col(k);
                    out.push_back({n, n.dot(c) + half[k]});
                }
        };
        break;
    case CollisionShape::Type::sphere:
        view.support = [c, r = cs.radius](const Vec3& u) { return c.dot(u) + r * u.norm(); };
        view.surfacePlanes = [c, r = cs.radius](const Vec3& x, std::vector<ode::Plane>& out) {
            if ((x - c).norm() == 0) return;
            const Vec3 n = (x - c).normalized();
            out.push_back({n, n.dot(c) + r});
        };
        break;
    case CollisionShape::Type::cylinder: {
        const Vec3 a = R.col(2);
        view.support = [c, a, r = cs.radius, hh = 0.5 * cs.height](const Vec3& u) {
            const double along = u.dot(a);
            return c.dot(u) + r * std::sqrt(std::max(0.0, u.squaredNorm() - along * along)) + hh * std::abs(along);
        };
        view.surfacePlanes = [c, a, r = cs.radius, hh = 0.5 * cs.height](const Vec3& x, std::vector<ode::Plane>& out) {
            out.push_back({a, a.dot(c) + hh});
            out.push_back({-a, -a.dot(c) + hh});
            const Vec3 radial = (x - c) - (x - c).dot(a) * a;
            if (radial.norm() == 0) return;
            const Vec3 n = radial.normalized();
            out.push_back({n, n.dot(c) + r});
        };
        break;
    }
    case CollisionShape::Type::convex: {
        const ConvexHull* hull = &cs.hull;
        view.support = [c, R, hull](const Vec3& u) {
            const Vec3 ub = R.transpose() * u;
            double best = -std::numeric_limits<double>::infinity();
            for (const Vec3& v : hull->points) best = std::max(best, v.dot(ub));
            return c.dot(u) + best;
        };
        view.surfacePlanes = [c, R, hull](const Vec3&, std::vector<ode::Plane>& out) {
            for (std::size_t f = 0; f < hull->normals.size(); ++f) {
                const Vec3 n = R * hull->normals[f];
                out.push_back({n, n.dot(c) + hull->offsets[f]});
            }
        };
        break;
    }
    case CollisionShape::Type::trimesh: {
        const std::vector<Vec3>* vertices = &cs.shape->mesh.vertices;
        view.support = [c, R, vertices](const Vec3& u) {
            const Vec3 ub = R.transpose() * u;
            double best = -std::numeric_limits<double>::infinity();
            for (const Vec3& v : *vertices) best = std::max(best, v.dot(ub));
            return c.dot(u) + best;
        };
        view.triangles = &cs.triangles;
        break;
    }
    }
    return view;
}

// ---------------------------------------------------------------------------
// The backend.
// ---------------------------------------------------------------------------
class ODEBackend final : public RigidBodyBackend {
public:
    explicit ODEBackend(const Dict& d) {
        const Dict c = d.subOrEmpty("contact");
        s_ = ContactSettings::read(d, c);
        cfm_ = c.get<double>("cfm", 1e-9);
        if (!(cfm_ >= 0)) c.fail("cfm", "cfm must be >= 0");
        maxContacts_ = c.get<int>("maxContacts", 8);
        if (maxContacts_ < 1 || maxContacts_ > 64) c.fail("maxContacts", "maxContacts must be 1..64");
        maxCorrectingVelocity_ = c.get<double>("maxCorrectingVelocity", 0.1);
        if (!(maxCorrectingVelocity_ > 0)) c.fail("maxCorrectingVelocity", "maxCorrectingVelocity must be > 0 (m/s)");
        meshCorrection_ = c.get<bool>("meshCorrection", true);
        frictionBounds_ = c.getWord("frictionBound", {"normalForce", "findex"}, "normalForce") == "normalForce";
        rolling_ = s_.rollingFriction > 0 || s_.spinningFriction > 0;

        c.reportUnused();

        quickStep_ = d.getWord("stepper", {"step", "quickStep"}, "step") == "quickStep";
        iterations_ = d.get<int>("iterations", 20);
        if (iterations_ < 1 || iterations_ > 10000) d.fail("iterations", "iterations must be 1..10000");
        if (!quickStep_ && d.has("iterations")) d.fail("iterations", "iterations is for stepper: quickStep only");
        const std::string shapes = d.getWord("collisionShapes", {"auto", "trimesh", "mesh"}, "auto");
        meshOnly_ = shapes == "mesh", usePieces_ = shapes == "auto";
        const int seed = d.get<int>("seed", 0);
        if (seed < 0) d.fail("seed", "seed must be >= 0");
        seed_ = static_cast<unsigned long>(seed);
    }

    ~ODEBackend() override {
        std::lock_guard lock(odeMutex());
        destroyWorld();
    }

    void setup(const std::vector<Body>& bodies) override {
        std::lock_guard lock(odeMutex());
        initODE();
        destroyWorld();
        world_ = dWorldCreate();
        dWorldSetGravity(world_, s_.gravity.x(), s_.gravity.y(), s_.gravity.z());
        dWorldSetERP(world_, s_.erp);
        dWorldSetCFM(world_, cfm_);
        dWorldSetContactMaxCorrectingVel(world_, maxCorrectingVelocity_);
        dWorldSetContactSurfaceLayer(world_, s_.surfaceLayer);
        dWorldSetAutoDisableFlag(world_, 0);
        dWorldSetQuickStepNumIterations(world_, iterations_);
        space_ = bodies.size() > 32 ? dHashSpaceCreate(nullptr) : dSimpleSpaceCreate(nullptr);
        group_ = dJointGroupCreate(0);
        if (s_.groundHeight) dCreatePlane(space_, 0, 0, 1, *s_.groundHeight);
        rng_ = seed_;

        entries_.assign(bodies.size(), Entry{});
        double smallest = std::numeric_limits<double>::infinity(), largest = 0;
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            const Body& b = bodies[i];
            if (!b.shape) throw InputError("body '" + b.name + "' has no shape");
            Entry& e = entries_[i];
            e.fixed = b.fixed;
            e.scale = b.shape->boundingRadius > 0 ? b.shape->boundingRadius : boundingSphereRadius(*b.shape);
            smallest = std::min(smallest, e.scale), largest = std::max(largest, e.scale);
            if (!b.fixed) {
                e.body = dBodyCreate(world_);
                dBodySetData(e.body, reinterpret_cast<void*>(i)); // its entry, for entryOf()
                setMass(e.body, b);
                e.mass = b.mass();
                dBodySetFiniteRotationMode(e.body, 1);
                dBodySetAutoDisableFlag(e.body, 0);
            }
            // A compound collides as the union of its parts' shapes: one geom
            // per part on the one ODE body (ODE never collides geoms of one body).
            auto addPiece = [&](const std::shared_ptr<const Shape>& shape, const Vec3& position, const Quat& rotation,
                                const std::string& name) {
                const auto& shapes = collisionShapes(shape);
                for (std::size_t k = 0; k < shapes.size(); ++k) {
                    const CollisionShape& cs = *shapes[k];
                    e.pieces.push_back(Piece{&cs, createGeom(cs), position + rotation * cs.offset,
                                             rotation * cs.offsetRotation, i,
                                             shapes.size() == 1 ? name : name + "#" + std::to_string(k),
                                             shapes.size() > 1});
                }
            };
            if (b.compound) {
                e.pieces.reserve(b.compound->parts.size());
                for (std::size_t k = 0; k < b.compound->parts.size(); ++k) {
                    const Part& part = b.compound->parts[k];
                    addPiece(part.shape, part.position, part.orientation, b.name + "/" + std::to_string(k));
                }
            } else {
                addPiece(b.shape, Vec3::Zero(), Quat::Identity(), b.name);
            }
            for (Piece& piece : e.pieces) {
                dGeomSetData(piece.geom, &piece);
                if (!e.body) continue;
                dGeomSetBody(piece.geom, e.body);
                if (piece.offset != Vec3::Zero() || piece.rotation.coeffs() != Quat::Identity().coeffs())
                    setGeomOffset(piece.geom, piece.offset, piece.rotation);
            }
            push(b, e);
        }
        // Hash grid cells from the smallest to twice the largest body.
        if (bodies.size() > 32 && largest > 0)
            dHashSpaceSetLevels(space_, static_cast<int>(std::floor(std::log2(smallest))),
                                static_cast<int>(std::ceil(std::log2(4 * largest))));
    }

    void step(std::vector<Body>& bodies, std::span<const Wrench> wrenches, double dt) override {
        std::lock_guard lock(odeMutex());
        if (!world_ || bodies.size() != entries_.size())
            throw std::logic_error("ODE rigid-body backend: step() with " + std::to_string(bodies.size()) +
                                   " bodies after setup() with " + std::to_string(entries_.size()));
        if (wrenches.size() != bodies.size())
            throw std::invalid_argument("ODE rigid-body backend: one wrench per body expected");
        if (!(dt > 0) || !std::isfinite(dt))
            throw std::invalid_argument("ODE rigid-body backend: time step must be positive and finite");

        const int n = subStepsFor(wrenches, dt);
        stats_.steps += 1, stats_.subSteps += n;
        touching_.clear();
        const double h = dt / n;
        // One-shot: the stiffness set for this step (setTiltStiffness).
        const std::vector<Mat3> stiffness = std::exchange(stiffness_, {});
        const std::vector<Quat> start = stiffness.empty() ? std::vector<Quat>{} : orientations();
        for (int s = 0; s < n; ++s) {
            // External wrench (ODE clears its accumulators after every step).
            for (std::size_t i = 0; i < bodies.size(); ++i) {
                const Entry& e = entries_[i];
                if (!e.body || !dBodyIsEnabled(e.body)) continue;
                const Vec3& F = wrenches[i].force;
                const Vec3 T = wrenches[i].totalTorque();
                dBodyAddForce(e.body, F.x(), F.y(), F.z());
                dBodyAddTorque(e.body, T.x(), T.y(), T.z());
            }
            // Contacts, then one step with this backend's random sequence.
            dSpaceCollide(space_, this, &ODEBackend::nearCallback);
            if (collideError_) {
                pool_.clear();  // half a pass: drop it
                dJointGroupEmpty(group_);
                std::rethrow_exception(std::exchange(collideError_, nullptr));
            }
            flushPool();
            const std::vector<dMass> own = stiffen(stiffness, start, h);
            // dWorldStep bounds each friction row by mu times its contact's
            // normal force as solved *before* the friction rows enter the LCP
            // (ODE's findex rows): where that first solve leaves a contact
            // unloaded, it slides without friction however hard it is pressed.
            // A sub-step in which a contact slid with less than half the
            // friction its normal force allows is taken again, that contact's
            // friction bounded by mu times the normal force just solved (the
            // others keep ODE's findex bound).
            const bool check = frictionBounds_ && !quickStep_ && !made_.empty();
            const bool rolling = rolling_ && !made_.empty();
            if (check || rolling) {
                snapshot();
                for (Made& m : made_) dJointSetFeedback(m.joint, &m.feedback); // made_ is complete now
            }
            dRandSetSeed(rng_);
            if (quickStep_)
                dWorldQuickStep(world_, h);
            else
                dWorldStep(world_, h);
            if (check && markStarvedFriction()) {
                stats_.frictionRedone += 1;
                // Only the islands (bodies joined by contacts) with a starved
                // contact are solved again. dWorldStep solves islands apart,
                // so the others would come out the same, bit for bit: they
                // keep this solve and sit the second one out disabled.
                const std::vector<char> redo = islandsOf([](const Made& m) { return m.starved; });
                long bodies = 0;
                if (!solveAgainUnlessGaining(redo, h, nullptr, &bodies)) {
                    stats_.frictionUndone += 1;
                    for (Made& m : made_) m.starved = false; // the rolling pass takes ODE's bounds
                }
                stats_.frictionRedoneBodies += bodies;
            }
            if (rolling) resistRolling(h);
            made_.clear();
            unstiffen(stiffness, own);
            rng_ = dRandGetSeed();
            dJointGroupEmpty(group_);
        }

        for (std::size_t i = 0; i < bodies.size(); ++i) pull(bodies[i], entries_[i]);
    }

    bool setTiltStiffness(std::span<const Mat3> stiffness) override {
        stiffness_.assign(stiffness.begin(), stiffness.end());
        return true;
    }

    // Backward Euler of the magnetic tilt for a sub-step of h: each stiff
    // body's inertia becomes I + h^2 S (in its body frame) and its spin
    // (I + h^2 S)^-1 I w, so that ODE's step, contacts included, solves
    // (I + h^2 S) w' = I w + h (tau + contact torques). The bodies' own masses
    // are returned for unstiffen().
    // The torque is the step's, linearised about the step's start: a sub-step
    // after the first also gets -S phi, phi the rotation since that start, so
    // that sub-steps do not turn the linearised torque explicit again.
    std::vector<dMass> stiffen(const std::vector<Mat3>& stiffness, const std::vector<Quat>& start, double h) {
        std::vector<dMass> own(stiffness.size());
        for (std::size_t i = 0; i < stiffness.size() && i < entries_.size(); ++i) {
            const dBodyID body = entries_[i].body;
            if (!body || !dBodyIsEnabled(body) || stiffness[i].isZero(0.0)) continue;
            dBodyGetMass(body, &own[i]);
            const Eigen::AngleAxisd turned(quaternionOf(body) * start[i].conjugate());
            const Vec3 back = -stiffness[i] * (turned.angle() * turned.axis());
            dBodyAddTorque(body, back.x(), back.y(), back.z());
            const Mat3 R = matrixOf(dBodyGetRotation(body));
            const Mat3 I = matrixOf(own[i].I);
            const Mat3 stiff = I + h * h * R.transpose() * stiffness[i] * R;
            dMass m = own[i];
            dMassSetParameters(&m, own[i].mass, 0, 0, 0, stiff(0, 0), stiff(1, 1), stiff(2, 2), stiff(0, 1),
                               stiff(0, 2), stiff(1, 2));
            dBodySetMass(body, &m);
            const dReal* w = dBodyGetAngularVel(body);
            const Vec3 spinBody = R.transpose() * Vec3(w[0], w[1], w[2]);
            // ODE's gyroscopic term would use the stiffened inertia (a torque
            // w x (I + h^2 S) w that the body does not feel): off for this
            // sub-step, the body's own -w x I w added instead.
            const Vec3 gyro = -(R * spinBody.cross(I * spinBody));
            dBodySetGyroscopicMode(body, 0);
            dBodyAddTorque(body, gyro.x(), gyro.y(), gyro.z());
            const Vec3 spin = R * stiff.ldlt().solve(I * spinBody);
            dBodySetAngularVel(body, spin.x(), spin.y(), spin.z());
        }
        return own;
    }
    std::vector<Quat> orientations() const {
        std::vector<Quat> out(entries_.size(), Quat::Identity());
        for (std::size_t i = 0; i < entries_.size(); ++i)
            if (const dBodyID body = entries_[i].body) out[i] = quaternionOf(body);
        return out;
    }
    // The stiffened bodies get their own mass back, and ODE's gyroscopic term
    // (on for every body this backend makes: ODE's default, never changed).
    void unstiffen(const std::vector<Mat3>& stiffness, const std::vector<dMass>& own) {
        for (std::size_t i = 0; i < stiffness.size() && i < entries_.size(); ++i)
            if (entries_[i].body && own[i].mass > 0) {
                dBodySetMass(entries_[i].body, &own[i]);
                dBodySetGyroscopicMode(entries_[i].body, 1);
            }
    }
    static Quat quaternionOf(dBodyID body) {
        const dReal* q = dBodyGetQuaternion(body);
        return Quat(q[0], q[1], q[2], q[3]);
    }
    // An ODE dMatrix3 (rows of 4) as a 3x3 matrix.
    static Mat3 matrixOf(const dReal* m) {
        Mat3 out;
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) out(a, b) = m[4 * a + b];
        return out;
    }

    // A sleeping body is a disabled ODE body: not stepped, at rest. ODE
    // enables a disabled body again when a contact joins it to an enabled
    // one; sleeping() reports it.
    bool canSleep() const override { return true; }
    void setSleeping(std::vector<Body>& bodies, const std::vector<char>& asleep) override {
        std::lock_guard lock(odeMutex());
        for (std::size_t i = 0; i < bodies.size() && i < entries_.size(); ++i) {
            const dBodyID body = entries_[i].body;
            if (!body) continue;
            if (i < asleep.size() && asleep[i]) {
                bodies[i].velocity.setZero(), bodies[i].angularVelocity.setZero();
                dBodySetLinearVel(body, 0, 0, 0);
                dBodySetAngularVel(body, 0, 0, 0);
                dBodyDisable(body);
            } else {
                dBodyEnable(body);
            }
        }
    }
    bool touching(std::vector<std::pair<std::size_t, std::size_t>>& pairs) const override {
        std::lock_guard lock(odeMutex());
        pairs = touching_;
        std::sort(pairs.begin(), pairs.end());
        pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
        return true;
    }
    std::vector<char> sleeping() const override {
        std::lock_guard lock(odeMutex());
        std::vector<char> out(entries_.size(), 0);
        for (std::size_t i = 0; i < entries_.size(); ++i)
            out[i] = entries_[i].body && !dBodyIsEnabled(entries_[i].body);
        return out;
    }

    void setState(const std::vector<Body>& bodies) override {
        std::lock_guard lock(odeMutex());
        if (!world_ || bodies.size() != entries_.size())
            throw std::logic_error("ODE rigid-body backend: setState() with " + std::to_string(bodies.size()) +
                                   " bodies after setup() with " + std::to_string(entries_.size()));
        for (std::size_t i = 0; i < bodies.size(); ++i) push(bodies[i], entries_[i], true);
    }

    // The random generator and the space order (Restart state above).
    void writeState(std::ostream& os, const std::vector<Body>& bodies) const override {
        std::lock_guard lock(odeMutex());
        if (!space_ || bodies.size() != entries_.size()) return;
        os << "# ODE backend: its random generator and the order of the collision space\ntype: ODE\nrandom: "
           << rng_ << "\nspaceOrder: [";
        const int n = dSpaceGetNumGeoms(space_);
        for (int k = 0; k < n; ++k) {
            const auto* piece = static_cast<const Piece*>(dGeomGetData(dSpaceGetGeom(space_, k)));
            os << (k ? ", " : "") << (piece ? piece->name : kGroundName);
        }
        os << "]\n";
    }

    void readState(const Dict& d, const std::vector<Body>& bodies) override {
        std::lock_guard lock(odeMutex());
        if (!space_ || bodies.size() != entries_.size())
            throw std::logic_error("ODE rigid-body backend: readState() before setup()");
        if (d.get<std::string>("type") != "ODE") {
            spdlog::warn("{}: not the state of an ODE backend: ignored", d.file());
            return;
        }
        const double random = d.get<double>("random");
        if (!(random >= 0 && random <= 4294967295.0 && random == std::floor(random)))
            d.fail("random", "expected ODE's random seed, an integer 0..2^32-1");
        // The geoms by name; each exactly once.
        const std::vector<std::string> order = d.get<std::vector<std::string>>("spaceOrder");
        std::vector<dGeomID> geoms;
        std::map<std::string, dGeomID> byName;
        const int n = dSpaceGetNumGeoms(space_);
        for (int k = 0; k < n; ++k) {
            const dGeomID g = dSpaceGetGeom(space_, k);
            const auto* piece = static_cast<const Piece*>(dGeomGetData(g));
            byName[piece ? piece->name : kGroundName] = g;
        }
        for (const std::string& name : order) {
            auto it = byName.find(name);
            if (it == byName.end())
                d.fail("spaceOrder", "'" + name + "' is not a body of constant/bodies.yaml" +
                                         (name == kGroundName ? " (the ground: no ground in rigidBody.yaml)" : "") +
                                         ", or named twice");
            geoms.push_back(it->second);
            byName.erase(it);
        }
        if (!byName.empty())
            d.fail("spaceOrder", "body '" + byName.begin()->first + "' is missing (bodies changed since the write?)");
        d.reportUnused();
        rng_ = static_cast<unsigned long>(random);
        // dSpaceAdd puts a geom at the front: add the last first.
        for (dGeomID g : geoms) dSpaceRemove(space_, g);
        for (auto it = geoms.rbegin(); it != geoms.rend(); ++it) dSpaceAdd(space_, *it);
    }

    std::string describe() const override {
        std::ostringstream os;
        os << "ODE " << (quickStep_ ? "dWorldQuickStep (" + std::to_string(iterations_) + " iterations)" : "dWorldStep")
           << ", gravity [" << s_.gravity.x() << ", " << s_.gravity.y() << ", " << s_.gravity.z() << "] m/s^2";
        if (s_.groundHeight) os << ", ground z = " << *s_.groundHeight;
        os << ", friction " << s_.friction << (frictionBounds_ ? "" : " (bound: findex)");
        if (rolling_)
            os << ", rolling friction " << s_.rollingFriction << " m, spinning friction " << s_.spinningFriction << " m";
        os << ", restitution " << s_.restitution << ", erp " << s_.erp << ", cfm " << cfm_
           << ", maxContacts " << maxContacts_ << ", subSteps " << s_.subSteps;
        // Bodies per collision shape, then (once stepping) what the steps did.
        std::map<std::string, int> count;
        for (const Entry& e : entries_)
            for (const Piece& piece : e.pieces) ++count[piece.collision->name()];
        os << "; collision shapes:";
        const char* sep = " ";
        for (const auto& [name, n] : count) os << sep << n << " " << name, sep = ", ";
        if (stats_.steps > 0) {
            os << "; sub-steps taken " << stats_.subSteps << " in " << stats_.steps << " steps; contacts found "
               << stats_.contactsFound << ", clipped from convex faces " << stats_.contactsClipped << ", dropped "
               << stats_.contactsDropped << ", merged " << stats_.contactsMerged
               << ", used " << stats_.contactsUsed << "; sub-steps solved again for friction "
               << stats_.frictionRedone << " (bodies in them " << stats_.frictionRedoneBodies << "; undone, "
               << "as they added kinetic energy, " << stats_.frictionUndone << ")";
            if (rolling_)
                os << ", for rolling friction " << stats_.rollingRedone << " (undone " << stats_.rollingUndone << ")";
        }
        return os.str();
    }

    // Counters of the contact post-processing (for tests and logs).
    struct Stats {
        long contactsFound = 0, contactsDropped = 0, contactsMerged = 0, contactsUsed = 0;
        long contactsClipped = 0; // face contacts clipped from libccd's one point per convex pair
        long frictionRedone = 0, frictionRedoneBodies = 0; // sub-steps solved again, bodies in them
        long frictionUndone = 0;                           // second solves undone: they added kinetic energy
        long rollingRedone = 0, rollingUndone = 0;         // sub-steps solved again with rolling friction, undone
        long steps = 0, subSteps = 0;
    };

private:
    // One geom of a body: the body's shape, or one part's of a compound.
    struct Piece {
        const CollisionShape* collision = nullptr;
        dGeomID geom = nullptr;
        Vec3 offset = Vec3::Zero();             // geom centre in the body frame
        Quat rotation = Quat::Identity();       // geom axes in the body frame
        std::size_t body = 0;
        std::string name;                       // the body's, or "<body>/<part>", + "#<piece>" (restart spaceOrder)
        bool pooled = false;                    // one of several convex pieces of a shape
    };
    std::vector<Mat3> stiffness_; // for the next step only (setTiltStiffness)

    struct Entry {
        std::vector<Piece> pieces;
        dBodyID body = nullptr; // null for fixed bodies: static geoms
        bool fixed = false;
        double mass = 0;
        double scale = 0;       // bounding radius about the COM, m
    };

    // The ground plane in the restart file's spaceOrder.
    static constexpr const char* kGroundName = "(ground)";

    // Sub-steps for this step: subSteps, or more so that no body travels
    // more than maxTravel times its bounding radius in one sub-step (velocity,
    // spin and the external acceleration; contacts ignored, so conservative).
    int subStepsFor(std::span<const Wrench> wrenches, double dt) const {
        if (s_.maxTravel <= 0) return s_.subSteps;
        double worst = 0;
        for (std::size_t i = 0; i < entries_.size(); ++i) {
            const Entry& e = entries_[i];
            if (!e.body || !dBodyIsEnabled(e.body)) continue;  // fixed, or sleeping: it does not travel
            const double r = e.scale;
            const dReal* v = dBodyGetLinearVel(e.body);
            const dReal* w = dBodyGetAngularVel(e.body);
            const Vec3 a = wrenches[i].force / e.mass + s_.gravity;
            const double travel = (Vec3(v[0], v[1], v[2]).norm() + Vec3(w[0], w[1], w[2]).norm() * r) * dt +
                                  0.5 * a.norm() * dt * dt;
            worst = std::max(worst, travel / r);
        }
        return s_.subStepsFor(worst);
    }

    // An exception must not leave dSpaceCollide (the space stays locked and
    // its destruction fails again): kept, and thrown after the pass.
    static void nearCallback(void* self, dGeomID a, dGeomID b) {
        auto* backend = static_cast<ODEBackend*>(self);
        if (backend->collideError_) return;
        try {
            backend->collide(a, b);
        } catch (...) {
            backend->collideError_ = std::current_exception();
        }
    }

    void collide(dGeomID g1, dGeomID g2) {
        dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
        if (!b1 && !b2) return; // fixed-fixed, fixed-ground
        // Sleeping (disabled) bodies among themselves or on fixed ones: nothing moves.
        if ((!b1 || !dBodyIsEnabled(b1)) && (!b2 || !dBodyIsEnabled(b2))) return;
        const int n = dCollide(g1, g2, kCapacity, &buffer_[0].geom, sizeof(dContact));
        if (n <= 0) return;
        stats_.contactsFound += n;
        contacts_.clear();
        for (int i = 0; i < n; ++i) {
            const dContactGeom& c = buffer_[i].geom;
            const Vec3 normal(c.normal[0], c.normal[1], c.normal[2]), position(c.pos[0], c.pos[1], c.pos[2]);
            // libccd returns a zero normal for a convex shape touching another at
            // zero depth (Fig. 8: a clip's piece on the magnet's box, 4e-17 m);
            // a contact row without a direction makes the LCP's solution NaN.
            // There is nothing to push along: dropped, counted.
            if (!(std::abs(normal.norm() - 1) < 1e-6) || !position.allFinite() || !std::isfinite(c.depth)) {
                ++stats_.contactsDropped;
                continue;
            }
            contacts_.push_back({position, normal, c.depth, i});
        }
        if (contacts_.empty()) return;
        const auto* e1 = static_cast<const Piece*>(dGeomGetData(g1));
        const auto* e2 = static_cast<const Piece*>(dGeomGetData(g2));
        const bool mesh = (e1 && e1->collision->type == CollisionShape::Type::trimesh) ||
                          (e2 && e2->collision->type == CollisionShape::Type::trimesh);
        // Meshes: correct normals and depths (ContactManifold.hpp); contacts
        // between primitives or with the ground plane are exact.
        if (meshCorrection_ && mesh && e1 && e2) {
            const double scale = std::min(e1->collision->scale, e2->collision->scale);
            stats_.contactsDropped += ode::correctMeshContacts(contacts_, geomView(g1, *e1->collision),
                                                               geomView(g2, *e2->collision), 0.02 * scale,
                                                               s_.surfaceLayer + 1e-6 * scale);
        }
        // Convex polytopes: libccd's one contact becomes the clipped face
        // contact (ContactManifold.hpp; box-box is ODE's own, already whole).
        if (n == 1 && e1 && e2 && polytope(*e1->collision) && polytope(*e2->collision) &&
            !(e1->collision->type == CollisionShape::Type::box && e2->collision->type == CollisionShape::Type::box)) {
            const double scale = std::min(e1->collision->scale, e2->collision->scale);
            clipped_.clear();
            if (ode::clipFaceContacts(polytopeView(g1, *e1->collision), polytopeView(g2, *e2->collision),
                                      contacts_.front(), s_.surfaceLayer + 1e-6 * scale, clipped_)) {
                stats_.contactsClipped += static_cast<long>(clipped_.size());
                contacts_.swap(clipped_);
            }
        }
        // Convex pieces: the contacts of all piece pairs of two bodies are
        // pooled and reduced together after the collision pass (neighbouring
        // pieces touch the same spot: duplicate contact rows make the LCP singular).
        if ((e1 && e1->pooled) || (e2 && e2->pooled)) {
            pool(g1, g2, e1, e2);
            return;
        }
        // Merge coincident contacts, keep at most maxContacts.
        const double scale = std::min(e1 ? e1->collision->scale : std::numeric_limits<double>::infinity(),
                                      e2 ? e2->collision->scale : std::numeric_limits<double>::infinity());
        stats_.contactsMerged += ode::mergeContacts(contacts_, 1e-3 * scale);
        ode::reduceContacts(contacts_, maxContacts_, scale);
        stats_.contactsUsed += static_cast<long>(contacts_.size());
        for (const ode::ContactPoint& c : contacts_) addJoint(buffer_[c.source].geom, c, b1, b2);
    }

    void addJoint(const dContactGeom& geom, const ode::ContactPoint& c, dBodyID b1, dBodyID b2) {
        dContact joint{};
        joint.geom = geom;
        for (int k = 0; k < 3; ++k) joint.geom.pos[k] = c.position[k], joint.geom.normal[k] = c.normal[k];
        joint.geom.depth = c.depth;
        joint.surface.mode = dContactApprox1 | dContactSoftERP | dContactSoftCFM;
        if (s_.restitution > 0) joint.surface.mode |= dContactBounce;
        joint.surface.mu = s_.friction;
        joint.surface.bounce = s_.restitution;
        joint.surface.bounce_vel = s_.bounceVelocity;
        joint.surface.soft_erp = s_.erp;
        joint.surface.soft_cfm = cfm_;
        const dJointID id = dJointCreateContact(world_, group_, &joint);
        dJointAttach(id, b1, b2);
        if ((frictionBounds_ && s_.friction > 0) || rolling_) made_.push_back({joint, b1, b2, id, {}, 0, false});
        if (b1 && b2) {
            const std::size_t i = entryOf(b1), j = entryOf(b2);
            touching_.emplace_back(std::min(i, j), std::max(i, j));
        }
    }

    // The contact joints of this sub-step, with ODE's answer (feedback; its
    // address is handed to ODE once made_ is complete, before the step).
    struct Made {
        dContact contact;
        dBodyID b1, b2;
        dJointID joint;
        dJointFeedback feedback;
        double normalForce;
        bool starved;
    };
    std::vector<Made> made_; // cleared every sub-step, its storage kept
    // Pairs of dynamic bodies joined by a contact in the last step (touching()).
    std::vector<std::pair<std::size_t, std::size_t>> touching_;
    // resistRolling's touching pairs and torques per entry (storage kept).
    struct Pair {
        dBodyID b1, b2;
        double normalForce = 0;
        Vec3 normal = Vec3::Zero();
    };
    std::vector<Pair> pairs_;
    std::vector<Vec3> rollingTorque_;
    // The entries_ index of an ODE body (its user data, set at setup).
    static std::size_t entryOf(dBodyID body) { return reinterpret_cast<std::size_t>(dBodyGetData(body)); }

    // Rolling and spinning friction (ContactSettings::rollingFriction,
    // spinningFriction). ODE's own rolling rows (dContactRolling) are the same
    // for every contact of a pair, and wherever contacts close a loop they
    // repeat the other pairs' rows: dWorldStep's LCP then meets a zero pivot
    // and stops (Fig. 9 within 400 steps). So they are a torque instead, found
    // from the sub-step just solved: per touching pair, its normal force N
    // (the contacts' feedback) and the relative spin it came out with, split
    // about the pair's mean normal into rolling and spinning; against each a
    // torque of rollingFriction x N (spinningFriction x N), at most the one that
    // stops that relative spin in the sub-step (it never turns it round). The
    // islands with such a torque are solved again with it, from the same
    // start, contacts and friction bounds. The cap takes the bodies' own
    // inertia, not what their contacts add (a ball rolling on its contact
    // turns about the contact point): a torque below the bound leaves a slow
    // creep instead of rest (tests/backendFixture.hpp, rollingSpinning).
    void resistRolling(double h) {
        // The touching pairs: their total normal force and its direction
        // (from b1's side).
        pairs_.clear();
        for (const Made& m : made_) {
            const Vec3 n = normalOf(m);
            const double N = contactForce(m).dot(n);
            if (!(N > 0)) continue;
            auto it = std::find_if(pairs_.begin(), pairs_.end(), [&](const Pair& p) {
                return (p.b1 == m.b1 && p.b2 == m.b2) || (p.b1 == m.b2 && p.b2 == m.b1);
            });
            if (it == pairs_.end()) it = pairs_.insert(pairs_.end(), Pair{m.b1, m.b2});
            it->normalForce += N;
            it->normal += (it->b1 == m.b1 ? N : -N) * n;
        }
        rollingTorque_.assign(entries_.size(), Vec3::Zero());
        bool any = false;
        for (const Pair& p : pairs_) {
            if (!(p.normal.norm() > 0)) continue;
            const Vec3 n = p.normal.normalized();
            const Vec3 w = spinOf(p.b1) - spinOf(p.b2);
            const Vec3 spin = w.dot(n) * n;
            const Mat3 compliance = inverseInertia(p.b1) + inverseInertia(p.b2);
            for (const auto& [part, length] : {std::pair(spin, s_.spinningFriction), std::pair(Vec3(w - spin), s_.rollingFriction)}) {
                const double rate = part.norm();
                if (!(length > 0) || !(rate > 0)) continue;
                const Vec3 u = part / rate;
                const double k = u.dot(compliance * u);
                if (!(k > 0)) continue;
                const double T = std::min(length * p.normalForce, rate / (k * h));
                if (p.b1) rollingTorque_[entryOf(p.b1)] -= T * u;
                if (p.b2) rollingTorque_[entryOf(p.b2)] += T * u;
                any = true;
            }
        }
        if (!any) return;
        stats_.rollingRedone += 1;
        // The islands of the bodies with a torque are solved again.
        auto turned = [&](dBodyID b) { return b && rollingTorque_[entryOf(b)].squaredNorm() > 0; };
        if (!solveAgainUnlessGaining(islandsOf([&](const Made& m) { return turned(m.b1) || turned(m.b2); }), h,
                                     &rollingTorque_))
            stats_.rollingUndone += 1;
    }
    // solveAgain, undone where it leaves the bodies solved again with more
    // than kEnergyGainUndone x the kinetic energy of the solve before: the
    // friction taken again and the rolling torque only resist motion, so they
    // should take energy out. The other contacts' findex bounds shift a
    // little between the solves (Fig. 8's ordinary sub-steps: at most 0.2 %
    // more). Their fixed bounds (the first solve's normal forces) can do far
    // more where contacts push a wedge apart: a Fig. 8 clip struck by a
    // spinning one left at 1 m/s, the pair's kinetic energy 14x, three steps
    // later 1.5x what it had (docs/rigid-bodies.md#friction-bounds). Undoing
    // the small gains too (one sub-step in ten) left that friction starved as
    // often; on one path two clips pressed onto the magnet then spun up at
    // 250 rad/s. Returns false when undone.
    bool solveAgainUnlessGaining(const std::vector<char>& redo, double h, const std::vector<Vec3>* torque,
                                 long* bodies = nullptr) {
        capture(lastSolve_);
        const double before = kineticEnergy(redo);
        const long n = solveAgain(redo, h, torque);
        if (bodies) *bodies = n;
        if (!(kineticEnergy(redo) > kEnergyGainUndone * before)) return true;
        for (std::size_t k = 0; k < redo.size(); ++k)
            if (redo[k] && lastSolve_[k].body) restore(lastSolve_[k]);
        return false;
    }
    // A contact's force as solved (its feedback), on geom 1's side. f1 is the
    // force on the joint's first body; ODE attaches a joint given (none,
    // body) as (body, none), so where geom 1 is fixed f1 is geom 2's body's
    // force (f2 stays zero: reading it, the friction check once saw no normal
    // force there).
    static Vec3 contactForce(const Made& m) {
        const Vec3 f1(m.feedback.f1[0], m.feedback.f1[1], m.feedback.f1[2]);
        return m.b1 ? f1 : Vec3(-f1);
    }
    static Vec3 normalOf(const Made& m) {
        const dReal* n = m.contact.geom.normal;
        return Vec3(n[0], n[1], n[2]);
    }
    // The sub-step again for the bodies marked in `redo` (whole islands), from
    // its start (snapshot) with its contacts (boundedContact) and, where
    // given, an extra torque per entry. dWorldStep solves islands apart, so
    // the others would come out the same, bit for bit: they keep this solve
    // and sit the second one out disabled. Returns the bodies solved again.
    long solveAgain(const std::vector<char>& redo, double h, const std::vector<Vec3>* torque = nullptr) {
        long count = 0;
        std::vector<char> wasEnabled(saved_.size(), 0);
        for (std::size_t k = 0; k < saved_.size(); ++k) {
            if (!saved_[k].body) continue; // fixed
            if (redo[k]) {
                restore(saved_[k]);
                if (torque) dBodyAddTorque(saved_[k].body, (*torque)[k].x(), (*torque)[k].y(), (*torque)[k].z());
                ++count;
            } else {
                wasEnabled[k] = static_cast<char>(dBodyIsEnabled(saved_[k].body));
                dBodyDisable(saved_[k].body);
            }
        }
        dJointGroupEmpty(group_);
        for (const Made& m : made_) {
            if (!redo[entryOf(m.b1 ? m.b1 : m.b2)]) continue;
            const dContact joint = boundedContact(m);
            dJointAttach(dJointCreateContact(world_, group_, &joint), m.b1, m.b2);
        }
        dRandSetSeed(rng_);
        if (quickStep_)
            dWorldQuickStep(world_, h);
        else
            dWorldStep(world_, h);
        for (std::size_t k = 0; k < saved_.size(); ++k)
            if (wasEnabled[k]) dBodyEnable(saved_[k].body);
        return count;
    }
    // The kinetic energy of the bodies marked in `which` (per entry), as ODE
    // has them now.
    double kineticEnergy(const std::vector<char>& which) const {
        double e = 0;
        for (std::size_t k = 0; k < entries_.size() && k < which.size(); ++k) {
            const dBodyID body = entries_[k].body;
            if (!which[k] || !body) continue;
            const MassFrame f = massFrame(body);
            const dReal* v = dBodyGetLinearVel(body);
            const Vec3 w = f.R.transpose() * spinOf(body); // body frame
            e += 0.5 * f.mass * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + 0.5 * w.dot(f.I * w);
        }
        return e;
    }
    static Vec3 spinOf(dBodyID body) {
        if (!body) return Vec3::Zero();
        const dReal* w = dBodyGetAngularVel(body);
        return Vec3(w[0], w[1], w[2]);
    }
    // World-frame inverse inertia of a body as ODE has it now (zero: fixed).
    static Mat3 inverseInertia(dBodyID body) {
        if (!body || !dBodyIsEnabled(body)) return Mat3::Zero();
        const MassFrame f = massFrame(body);
        return f.R * f.I.inverse() * f.R.transpose();
    }
    // A body's mass, body-frame inertia about its centre of mass and
    // rotation, as ODE has them now.
    struct MassFrame {
        double mass;
        Mat3 I, R;
    };
    static MassFrame massFrame(dBodyID body) {
        dMass mass;
        dBodyGetMass(body, &mass);
        MassFrame f{mass.mass, Mat3(), Mat3()};
        const dReal* r = dBodyGetRotation(body);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) f.I(i, j) = mass.I[4 * i + j], f.R(i, j) = r[4 * i + j];
        return f;
    }
    // A made contact as solved again: a starved one with its friction
    // bounded by mu times the normal force found (markStarvedFriction).
    dContact boundedContact(const Made& m) const {
        dContact joint = m.contact;
        if (m.starved) {
            joint.surface.mode &= ~dContactApprox1;
            joint.surface.mu = s_.friction * m.normalForce;
        }
        return joint;
    }

    // Marks the contacts whose friction was starved: sliding (faster than
    // 1e-5 m/s, well above the LCP's round-off and 100x below the sleep
    // speed) in a friction direction (ODE's dPlaneSpace of the normal, as the
    // contact joint uses it) with less than half of mu times the normal force
    // solved. Half, not all: a findex bound from a normal force that differs
    // a little is ODE's approximation; the fault is a bound near zero. Stores
    // each contact's normal force for the second solve.
    bool markStarvedFriction() {
        bool any = false;
        for (Made& m : made_) {
            m.starved = false;
            const dContactGeom& g = m.contact.geom;
            const Vec3 p(g.pos[0], g.pos[1], g.pos[2]);
            const Vec3 f = contactForce(m);
            m.normalForce = f.dot(normalOf(m));
            if (!(m.normalForce > 0)) continue;
            const Vec3 v = pointVelocity(m.b1, p) - pointVelocity(m.b2, p);
            dVector3 t1, t2;
            dPlaneSpace(g.normal, t1, t2);
            for (const dVector3* t : {&t1, &t2}) {
                const Vec3 dir((*t)[0], (*t)[1], (*t)[2]);
                if (std::abs(v.dot(dir)) > 1e-5 && std::abs(f.dot(dir)) < 0.5 * s_.friction * m.normalForce)
                    m.starved = true;
            }
            any = any || m.starved;
        }
        return any;
    }
    static Vec3 pointVelocity(dBodyID body, const Vec3& p) {
        if (!body) return Vec3::Zero();
        dVector3 v;
        dBodyGetPointVel(body, p.x(), p.y(), p.z(), v);
        return Vec3(v[0], v[1], v[2]);
    }

    // Everything a world step changes in the bodies, for taking it again:
    // pose, velocities, the force and torque accumulated for it, enabled.
    // One per entry (body null for fixed ones), storage kept between steps.
    struct Saved {
        dBodyID body;
        dReal position[3], quaternion[4], velocity[3], spin[3], force[3], torque[3];
        int enabled;
    };
    std::vector<Saved> saved_, lastSolve_;
    static constexpr double kEnergyGainUndone = 1.1;
    void snapshot() { capture(saved_); }
    void capture(std::vector<Saved>& into) const {
        into.resize(entries_.size());
        for (std::size_t i = 0; i < entries_.size(); ++i) {
            const Entry& e = entries_[i];
            Saved& s = into[i];
            s.body = e.body;
            if (!e.body) continue;
            const dReal *x = dBodyGetPosition(e.body), *q = dBodyGetQuaternion(e.body), *v = dBodyGetLinearVel(e.body),
                        *w = dBodyGetAngularVel(e.body), *F = dBodyGetForce(e.body), *T = dBodyGetTorque(e.body);
            std::copy(x, x + 3, s.position), std::copy(q, q + 4, s.quaternion), std::copy(v, v + 3, s.velocity);
            std::copy(w, w + 3, s.spin), std::copy(F, F + 3, s.force), std::copy(T, T + 3, s.torque);
            s.enabled = dBodyIsEnabled(e.body);
        }
    }
    static void restore(const Saved& s) {
        dBodySetPosition(s.body, s.position[0], s.position[1], s.position[2]);
        setQuaternionExactly(s.body, s.quaternion);
        dBodySetLinearVel(s.body, s.velocity[0], s.velocity[1], s.velocity[2]);
        dBodySetAngularVel(s.body, s.spin[0], s.spin[1], s.spin[2]);
        dBodySetForce(s.body, s.force[0], s.force[1], s.force[2]);
        dBodySetTorque(s.body, s.torque[0], s.torque[1], s.torque[2]);
        if (s.enabled) dBodyEnable(s.body); else dBodyDisable(s.body);
    }
    // Per entry: does its body share an island (bodies joined by contacts;
    // fixed bodies and the ground join none) with a contact that `marked`?
    template <class Marked>
    std::vector<char> islandsOf(Marked marked) const {
        std::vector<std::size_t> parent(saved_.size());
        for (std::size_t k = 0; k < parent.size(); ++k) parent[k] = k;
        auto root = [&](std::size_t k) {
            while (parent[k] != k) k = parent[k] = parent[parent[k]];
            return k;
        };
        for (const Made& m : made_)
            if (m.b1 && m.b2) parent[root(entryOf(m.b1))] = root(entryOf(m.b2));
        std::vector<char> markedRoot(saved_.size(), 0), redo(saved_.size(), 0);
        for (const Made& m : made_)
            if (marked(m)) markedRoot[root(entryOf(m.b1 ? m.b1 : m.b2))] = 1;
        for (std::size_t k = 0; k < saved_.size(); ++k) redo[k] = markedRoot[root(k)];
        return redo;
    }

    // Contacts of two bodies' pieces, gathered over one collision pass; keyed
    // by the body indices (the ground: kNone), lower first, so that the
    // joints are made in a fixed order.
    static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
    struct Pooled {
        dBodyID b1 = nullptr, b2 = nullptr;
        std::vector<ode::ContactPoint> contacts;
        std::vector<dContactGeom> geoms;
    };

    void pool(dGeomID g1, dGeomID g2, const Piece* e1, const Piece* e2) {
        std::size_t i1 = e1 ? e1->body : kNone, i2 = e2 ? e2->body : kNone;
        const bool swap = i1 > i2;
        if (swap) std::swap(i1, i2), std::swap(g1, g2);
        Pooled& p = pool_[{i1, i2}];
        p.b1 = dGeomGetBody(g1), p.b2 = dGeomGetBody(g2);
        for (ode::ContactPoint c : contacts_) {
            p.geoms.push_back(buffer_[c.source].geom);
            c.source = static_cast<int>(p.geoms.size()) - 1;
            if (swap) c.normal = -c.normal;
            p.contacts.push_back(c);
        }
    }

    // Entries stay (their vectors keep their storage from sub-step to
    // sub-step); pairs without contacts this pass are empty and skipped.
    void flushPool() {
        for (auto& [key, p] : pool_) {
            if (p.contacts.empty()) continue;
            const double scale = std::min(key.first == kNone ? std::numeric_limits<double>::infinity()
                                                             : entries_[key.first].scale,
                                          key.second == kNone ? std::numeric_limits<double>::infinity()
                                                              : entries_[key.second].scale);
            stats_.contactsMerged += ode::mergeContacts(p.contacts, 1e-3 * scale);
            ode::reduceContacts(p.contacts, maxContacts_, scale);
            stats_.contactsUsed += static_cast<long>(p.contacts.size());
            for (const ode::ContactPoint& c : p.contacts) addJoint(p.geoms[c.source], c, p.b1, p.b2);
            p.contacts.clear(), p.geoms.clear();
        }
    }

    // The geoms' shapes of a Shape, built once: one native geom, one convex
    // geom per convex piece (or the hull of a convex mesh), or a trimesh.
    const std::vector<std::unique_ptr<CollisionShape>>& collisionShapes(const std::shared_ptr<const Shape>& shape) {
        auto it = shapes_.find(shape.get());
        if (it != shapes_.end()) return it->second;
        std::vector<std::unique_ptr<CollisionShape>> list;
        const Shape& s = *shape;
        auto add = [&] {
            list.push_back(std::make_unique<CollisionShape>());
            list.back()->shape = shape;
            list.back()->scale = s.boundingRadius > 0 ? s.boundingRadius : boundingSphereRadius(s);
            return list.back().get();
        };
        using K = ShapeKind::Kind;
        std::optional<DetectedBox> box;
        if (!meshOnly_ && s.kind.kind == K::box) {
            CollisionShape* cs = add();
            cs->type = CollisionShape::Type::box;
            cs->size = s.kind.size;
            cs->hull = boxHull(cs->size);
        } else if (!meshOnly_ && s.kind.kind == K::sphere) {
            CollisionShape* cs = add();
            cs->type = CollisionShape::Type::sphere;
            cs->radius = s.kind.radius;
        } else if (!meshOnly_ && s.kind.kind == K::cylinder) {
            CollisionShape* cs = add();
            cs->type = CollisionShape::Type::cylinder;
            cs->radius = s.kind.radius;
            cs->height = s.kind.height;
        } else if (!meshOnly_ && (box = detectBox(s))) {
            CollisionShape* cs = add();
            cs->type = CollisionShape::Type::box;
            cs->size = box->size;
            cs->hull = boxHull(cs->size);
            cs->offset = box->centre;
            cs->offsetRotation = Quat(box->axes).normalized();
        } else if (usePieces_ && !s.pieces.empty()) {
            for (const ConvexHull& hull : s.pieces) makeConvex(*add(), hull);
        } else if (usePieces_ && s.mesh.nVertices() <= 256 && isConvex(s.mesh)) {
            makeConvex(*add(), convexHull(s.mesh.vertices, s.mesh.source));
        } else {
            CollisionShape* cs = add();
            cs->type = CollisionShape::Type::trimesh;
            cs->triangles = ode::TriangleSet::build(s.mesh);
            for (const Vec3& v : s.mesh.vertices) cs->vertices.insert(cs->vertices.end(), {v.x(), v.y(), v.z()});
            for (const auto& t : s.mesh.triangles)
                for (int k : t) cs->indices.push_back(static_cast<dTriIndex>(k));
            cs->data = dGeomTriMeshDataCreate();
            dGeomTriMeshDataBuildDouble(cs->data, cs->vertices.data(), 3 * sizeof(double),
                                        static_cast<int>(s.mesh.vertices.size()), cs->indices.data(),
                                        static_cast<int>(cs->indices.size()), 3 * sizeof(dTriIndex));
            // Face angles: ODE's libccd convex-trimesh collider refuses a mesh without them.
            dGeomTriMeshDataPreprocess2(cs->data,
                                        (1U << dTRIDATAPREPROCESS_BUILD_CONCAVE_EDGES) |
                                            (1U << dTRIDATAPREPROCESS_BUILD_FACE_ANGLES),
                                        nullptr);
        }
        return shapes_.emplace(shape.get(), std::move(list)).first->second;
    }

    // A box geom's faces, for clipping its contacts with convex geoms.
    static ConvexHull boxHull(const Vec3& size) {
        std::vector<Vec3> corners;
        for (int k = 0; k < 8; ++k)
            corners.push_back(0.5 * Vec3((k & 1) ? size.x() : -size.x(), (k & 2) ? size.y() : -size.y(),
                                         (k & 4) ? size.z() : -size.z()));
        return convexHull(corners, "box geom");
    }

    // A dConvex geom's data: the hull about its centroid, which is the geom's
    // centre (ODE's libccd colliders take the geom centre as the interior point).
    static void makeConvex(CollisionShape& cs, const ConvexHull& hull) {
        cs.type = CollisionShape::Type::convex;
        cs.offset = hull.centroid;
        cs.hull = hull;
        cs.scale = 0;
        for (Vec3& p : cs.hull.points) p -= hull.centroid, cs.scale = std::max(cs.scale, p.norm());
        for (std::size_t f = 0; f < cs.hull.normals.size(); ++f) {
            cs.hull.offsets[f] -= cs.hull.normals[f].dot(hull.centroid);
            const Vec3& n = cs.hull.normals[f];
            cs.planes.insert(cs.planes.end(), {n.x(), n.y(), n.z(), cs.hull.offsets[f]});
        }
        for (const Vec3& p : cs.hull.points) cs.points.insert(cs.points.end(), {p.x(), p.y(), p.z()});
        for (const auto& face : cs.hull.faces) {
            cs.polygons.push_back(static_cast<unsigned>(face.size()));
            for (int v : face) cs.polygons.push_back(static_cast<unsigned>(v));
        }
        cs.hull.centroid = Vec3::Zero();
    }

    static double boundingSphereRadius(const Shape& s) {
        double r = 0;
        for (const Vec3& v : s.mesh.vertices) r = std::max(r, v.norm());
        return r;
    }

    dGeomID createGeom(const CollisionShape& cs) {
        switch (cs.type) {
        case CollisionShape::Type::box: return dCreateBox(space_, cs.size.x(), cs.size.y(), cs.size.z());
        case CollisionShape::Type::sphere: return dCreateSphere(space_, cs.radius);
        case CollisionShape::Type::cylinder: return dCreateCylinder(space_, cs.radius, cs.height);
        case CollisionShape::Type::convex:
            return dCreateConvex(space_, cs.planes.data(), static_cast<unsigned>(cs.hull.normals.size()),
                                 cs.points.data(), static_cast<unsigned>(cs.hull.points.size()), cs.polygons.data());
        case CollisionShape::Type::trimesh: break;
        }
        return dCreateTriMesh(space_, cs.data, nullptr, nullptr, nullptr);
    }

    static void setGeomOffset(dGeomID g, const Vec3& offset, const Quat& rotation) {
        dGeomSetOffsetPosition(g, offset.x(), offset.y(), offset.z());
        const dQuaternion q = {rotation.w(), rotation.x(), rotation.y(), rotation.z()};
        dGeomSetOffsetQuaternion(g, q);
    }

    static void setMass(dBodyID body, const Body& b) {
        const double m = b.mass();
        const Mat3 I = b.inertiaBody();
        if (!(m > 0) || !std::isfinite(m))
            throw InputError("body '" + b.name + "': mass must be positive and finite (density * volume), got " +
                             std::to_string(m) + " kg");
        if (!(I.determinant() > 0) || !(I.trace() > 0))
            throw InputError("body '" + b.name + "': inertia tensor is not positive definite");
        // Inertia about the COM, which is the ODE body's origin.
        dMass mass;
        dMassSetParameters(&mass, m, 0, 0, 0, I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2));
        dBodySetMass(body, &mass);
    }

    // Body -> ODE (at setup, and from setState: `exact`, see the header).
    static void push(const Body& b, Entry& e, bool exact = false) {
        const Quat& q = b.orientation; // ODE normalises it
        const dQuaternion dq = {q.w(), q.x(), q.y(), q.z()};
        if (e.body) {
            dBodySetPosition(e.body, b.position.x(), b.position.y(), b.position.z());
            if (exact)
                setQuaternionExactly(e.body, dq);
            else
                dBodySetQuaternion(e.body, dq);
            dBodySetLinearVel(e.body, b.velocity.x(), b.velocity.y(), b.velocity.z());
            dBodySetAngularVel(e.body, b.angularVelocity.x(), b.angularVelocity.y(), b.angularVelocity.z());
        } else {
            // Static geoms: the body pose composed with each geom's offset.
            const Quat qb = q.normalized();
            for (const Piece& piece : e.pieces) {
                const Vec3 p = b.position + qb * piece.offset;
                const Quat qg = qb * piece.rotation;
                const dQuaternion dqg = {qg.w(), qg.x(), qg.y(), qg.z()};
                dGeomSetPosition(piece.geom, p.x(), p.y(), p.z());
                dGeomSetQuaternion(piece.geom, dqg);
            }
        }
    }

    // dBodySetQuaternion with a quaternion that ODE's renormalisation turns
    // into q itself, where there is one among q's neighbours (up to two
    // doubles away per component; q unit to round-off); else q as ODE makes it.
    static void setQuaternionExactly(dBodyID body, const dQuaternion q) {
        auto same = [&] {
            const dReal* got = dBodyGetQuaternion(body);
            return got[0] == q[0] && got[1] == q[1] && got[2] == q[2] && got[3] == q[3];
        };
        dBodySetQuaternion(body, q);
        if (same()) return;
        std::array<std::array<dReal, 5>, 4> near;
        for (int i = 0; i < 4; ++i) {
            const dReal down = std::nextafter(q[i], -1.0), up = std::nextafter(q[i], 1.0);
            near[i] = {q[i], down, up, std::nextafter(down, -1.0), std::nextafter(up, 1.0)};
        }
        for (int c = 1; c < 625; ++c) {
            dQuaternion trial;
            for (int i = 0, k = c; i < 4; ++i, k /= 5) trial[i] = near[i][k % 5];
            dBodySetQuaternion(body, trial);
            if (same()) return;
        }
        dBodySetQuaternion(body, q);
    }

    // ODE -> Body.
    static void pull(Body& b, const Entry& e) {
        if (e.body) {
            const dReal* p = dBodyGetPosition(e.body);
            const dReal* v = dBodyGetLinearVel(e.body);
            const dReal* w = dBodyGetAngularVel(e.body);
            b.position = Vec3(p[0], p[1], p[2]);
            b.orientation = quaternionOf(e.body);
            b.velocity = Vec3(v[0], v[1], v[2]);
            b.angularVelocity = Vec3(w[0], w[1], w[2]);
        } else {
            b.velocity.setZero();
            b.angularVelocity.setZero();
        }
    }

    void destroyWorld() {
        if (group_) dJointGroupDestroy(group_);
        if (space_) dSpaceDestroy(space_); // destroys its geoms (cleanup mode on)
        if (world_) dWorldDestroy(world_); // destroys the bodies
        group_ = nullptr, space_ = nullptr, world_ = nullptr;
        shapes_.clear(); // trimesh data after the geoms that use it
        entries_.clear();
    }

    // Settings.
    ContactSettings s_;
    double cfm_ = 1e-9, maxCorrectingVelocity_ = 0.1;
    bool frictionBounds_ = true;
    bool rolling_ = false; // rollingFriction or spinningFriction > 0
    int maxContacts_ = 8, iterations_ = 20;
    bool quickStep_ = false, meshOnly_ = false, usePieces_ = true, meshCorrection_ = true;
    unsigned long seed_ = 0, rng_ = 0;

    // ODE objects and per-body data.
    dWorldID world_ = nullptr;
    dSpaceID space_ = nullptr;
    dJointGroupID group_ = nullptr;
    std::map<const Shape*, std::vector<std::unique_ptr<CollisionShape>>> shapes_;
    std::vector<Entry> entries_;

    // Collider output buffer (what ODE may return for one pair) and scratch.
    static constexpr int kCapacity = 64;
    dContact buffer_[kCapacity];
    std::vector<ode::ContactPoint> contacts_, clipped_;
    std::map<std::pair<std::size_t, std::size_t>, Pooled> pool_;
    std::exception_ptr collideError_;
    Stats stats_;
};

const TypeDoc kDoc{
    "Open Dynamics Engine: rigid bodies with contacts, gravity and a ground plane.\n"
    "Bodies feel the magnetic wrench, gravity, the ground and each other (native\n"
    "box/sphere/cylinder geoms, trimeshes for other meshes).",
    {"type: ODE\ngravity: [0, 0, -9.81]\nground: {height: 0}\n"
     "contact: {friction: 0.5, restitution: 0.1, bounceVelocity: 0.1, erp: 0.2, cfm: 1e-9, maxContacts: 8}\n"
     "subSteps: 1\nmaxTravel: 0.1\n"},
    {{"gravity", "m/s^2", "uniform acceleration of every dynamic body (energy.csv uses the same)"},
     {"ground", "-", "a ground plane z = height; without this key, no plane"},
     {"ground.height", "m", "height of the ground plane"},
     {"contact", "-", "contact parameters of every pair"},
     {"contact.friction", "-", "Coulomb coefficient mu (friction pyramid scaled by the normal force), >= 0"},
     {"contact.frictionBound", "-",
      "normalForce (a sub-step in which a contact slid with less than half the friction its normal force allows "
      "is solved again, that contact's friction bounded by mu times that normal force) or findex (ODE's own "
      "bound alone, from a solve without friction)"},
     {"contact.rollingFriction", "m",
      "rolling resistance: a touching pair resists rolling with a torque up to this times its normal force, "
      ">= 0 (default 0)"},
     {"contact.spinningFriction", "m",
      "spinning resistance: the same about the contact's normal, >= 0 (default 0)"},
     {"contact.restitution", "-", "0..1"},
     {"contact.bounceVelocity", "m/s", "slower impacts do not bounce"},
     {"contact.erp", "-", "share of the penetration corrected per step, (0, 1]"},
     {"contact.cfm", "-", "constraint softness, >= 0"},
     {"contact.maxContacts", "-", "contact joints per pair, 1..64"},
     {"contact.surfaceLayer", "m", "penetration left uncorrected, >= 0 (keeps resting trimesh contacts)"},
     {"contact.maxCorrectingVelocity", "m/s", "cap of the penetration-correction speed, > 0"},
     {"contact.meshCorrection", "-", "correct the depth of trimesh contacts"},
     {"subSteps", "-", "ODE steps per solver step, 1..10000 (the wrench is held over them)"},
     {"maxTravel", "-",
      "more sub-steps while a body would travel more than this times its bounding radius in one;\n"
      "0: always subSteps"},
     {"maxSubSteps", "-", "cap of the automatic sub-steps, subSteps..100000"},
     {"stepper", "-", "step (dWorldStep, exact LCP per island) or quickStep (iterative, large heaps)"},
     {"iterations", "-", "quickStep only: solver iterations, 1..10000"},
     {"collisionShapes", "-",
      "auto (native geoms, convex pieces, convex hulls, else trimeshes), trimesh (no pieces or hulls) or mesh "
      "(every body a trimesh)"},
     {"seed", "-", "ODE's random generator (quickStep's constraint order), >= 0"}}};

const RigidBodyBackend::Add<ODEBackend> addODE("ODE", kDoc);

} // namespace

} // namespace mag
