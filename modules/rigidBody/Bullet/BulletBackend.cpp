// `type: Bullet` (constant/rigidBody.yaml): the paper's rigid-body engine,
// Bullet Physics (Debian's libbullet-dev, double precision: bullet-float64).
//
// Bodies. The Bullet body frame is the body's principal frame (Bullet wants a
// diagonal inertia): the inertia tensor about the COM (Body::inertiaBody) is
// diagonalised once per body, and the collision shape is placed in that frame
// by a compound wrapper when the principal axes are not the body axes.
// Integration is Bullet's semi-implicit Euler (v += a h, x += v h, rotation by
// the exponential map), the wrench held over the sub-steps. No damping, no
// deactivation; fixed bodies are static objects.
//
// Collision shapes (`collisionShapes: auto`): boxes and spheres map to
// Bullet's primitives; a convex mesh, a cylinder's included, to a convex hull
// (with its polyhedral features, so hull contacts are clipped faces, full
// manifolds in one step); a concave mesh with convex pieces (its
// <stem>.pieces.yaml, docs/rigid-bodies.md#convex-pieces) to a compound of
// their hulls; another concave mesh of a dynamic body to a GImpact triangle
// mesh, of a fixed body to a BVH triangle mesh; a compound body
// (docs/compound-bodies.md) to a compound of its parts' shapes. `trimesh`
// ignores the pieces; `mesh` makes every dynamic body's shape a GImpact mesh.
// Margins: `contact.margin` (m) around hulls and meshes; a box's margin lies
// inside it.
//
// Contacts are found anew every sub-step (`contact.persistent: false`, the
// default): the pair cache is kept sorted and the collision algorithms (and
// their manifolds) are dropped before each sub-step, so the solver sees the
// same contacts in the same order whatever came before, and a restart
// continues bit for bit. Persistent manifolds (true) warm-start the solver,
// which helps tall stacks, at the price of exact restarts.
//
// Friction and restitution are Bullet's products of the two objects' values:
// each object gets the square root of the key's value, so a pair (and a body
// on the ground) has exactly the value given.
//
// Restart state (<time>/rigidBody.yaml): each body's rotation matrix as
// Bullet holds it (the quaternion written in bodies.yaml is derived from it,
// and turning it back into a matrix would change its last bits).
#include <magFoam/ContactSettings.hpp>
#include <magFoam/ConvexPieces.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/ResultsWriter.hpp>
#include <magFoam/RigidBodyBackend.hpp>

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/BroadphaseCollision/btOverlappingPairCache.h>
#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <limits>
#include <cmath>
#include <map>
#include <memory>
#include <sstream>

namespace mag {

namespace {

btVector3 bt(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
Vec3 eig(const btVector3& v) { return {v.x(), v.y(), v.z()}; }
btMatrix3x3 btMat(const Mat3& m) {
    return {m(0, 0), m(0, 1), m(0, 2), m(1, 0), m(1, 1), m(1, 2), m(2, 0), m(2, 1), m(2, 2)};
}
Mat3 eig(const btMatrix3x3& m) {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r(i, j) = m[i][j];
    return r;
}

// Bullet applies a contact's impulse to A at the contact's point on A and to
// B at its point on B. The two lie the penetration depth apart, so each
// friction impulse also turns the pair by (depth x impulse): two magnets
// pressed together by 30 N spun up as a pair from rest, with no torque on
// them. Here both bodies take each impulse at the points' midpoint (ODE has
// one contact position), set before every solve (docs/rigid-bodies.md#bullet).
class MidpointContactWorld final : public btDiscreteDynamicsWorld {
public:
    using btDiscreteDynamicsWorld::btDiscreteDynamicsWorld;
    void solveConstraints(btContactSolverInfo& info) override {
        btDispatcher* d = getDispatcher();
        for (int k = 0; k < d->getNumManifolds(); ++k) {
            btPersistentManifold* m = d->getManifoldByIndexInternal(k);
            for (int c = 0; c < m->getNumContacts(); ++c) {
                btManifoldPoint& p = m->getContactPoint(c);
                p.m_positionWorldOnA = p.m_positionWorldOnB = 0.5 * (p.m_positionWorldOnA + p.m_positionWorldOnB);
            }
        }
        btDiscreteDynamicsWorld::solveConstraints(info);
    }
};

// Bullet's sequential-impulse solver sets up a contact's normal row with the
// velocity the step's external force and torque add, but its friction rows
// with the force's share only: a torque's slip was invisible to friction,
// so a magnet's torque turned it on a face friction should have held (two
// cubes pressed together, each turned by 0.025 N m against 15 N of
// friction, spun up at 12 rad/s per 0.1 ms). The friction rows get the
// torque's share here, after Bullet's setup.
class TorqueAwareSolver final : public btSequentialImpulseConstraintSolver {
protected:
    btScalar solveGroupCacheFriendlySetup(btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds,
                                          int numManifolds, btTypedConstraint** constraints, int numConstraints,
                                          const btContactSolverInfo& info, btIDebugDraw* debug) override {
        const btScalar result = btSequentialImpulseConstraintSolver::solveGroupCacheFriendlySetup(
            bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debug);
        for (int k = 0; k < m_tmpSolverContactFrictionConstraintPool.size(); ++k) {
            btSolverConstraint& c = m_tmpSolverContactFrictionConstraintPool[k];
            const btSolverBody& a = m_tmpSolverBodyPool[c.m_solverBodyIdA];
            const btSolverBody& b = m_tmpSolverBodyPool[c.m_solverBodyIdB];
            const btScalar slip = c.m_relpos1CrossNormal.dot(a.m_externalTorqueImpulse) +
                                  c.m_relpos2CrossNormal.dot(b.m_externalTorqueImpulse);
            c.m_rhs -= slip * c.m_jacDiagABInv;
        }
        return result;
    }
};

// A Bullet shape and what it keeps alive (triangle arrays, children).
struct ShapeHolder {
    std::unique_ptr<btCollisionShape> shape;
    std::vector<std::unique_ptr<btCollisionShape>> children;
    std::unique_ptr<btTriangleIndexVertexArray> triangles;
    std::vector<btScalar> vertices;
    std::vector<int> indices;
    std::string kind;  // for describe()
};

class BulletBackend final : public RigidBodyBackend {
public:
    explicit BulletBackend(const Dict& d) {
        const Dict c = d.subOrEmpty("contact");
        s_ = ContactSettings::read(d, c);
        margin_ = c.get<double>("margin", 1e-5);
        if (!(margin_ > 0)) c.fail("margin", "margin must be > 0 (m)");
        splitImpulse_ = c.get<bool>("splitImpulse", true);
        splitThreshold_ = c.get<double>("splitImpulseThreshold", -1e-5);
        if (!(splitThreshold_ <= 0)) c.fail("splitImpulseThreshold", "a penetration depth, <= 0 (m)");
        if (s_.friction == 0 && (s_.rollingFriction > 0 || s_.spinningFriction > 0))
            c.fail(s_.rollingFriction > 0 ? "rollingFriction" : "spinningFriction",
                   "Bullet scales rolling and spinning friction by the friction: they need friction > 0");
        persistent_ = c.get<bool>("persistent", false);
        stiffness_ = c.get<double>("stiffness", 0.0);
        if (!(stiffness_ >= 0)) c.fail("stiffness", "a contact spring constant, >= 0 (N/m; 0: rigid contacts)");
        damping_ = c.get<double>("damping", 0.0);
        if (!(damping_ >= 0)) c.fail("damping", "a contact damping, >= 0 (N s/m)");
        if (damping_ > 0 && stiffness_ == 0) c.fail("damping", "damping needs a contact stiffness");
        breakingShare_ = c.get<double>("breakingThreshold", 0.1);
        if (!(breakingShare_ > 0)) c.fail("breakingThreshold", "a share of the smallest body's bounding radius, > 0");
        c.reportUnused();

        // Magnets pressed together by tens of newtons while resting on the
        // ground by millinewtons need many sweeps of the sequential solver
        // before friction holds them (Fig. 7: at rest with 300, asleep with
        // 1000; never with 50, Bullet's usual count; docs/rigid-bodies.md#bullet).
        iterations_ = d.get<int>("solverIterations", iterations_);
        if (iterations_ < 1 || iterations_ > 10000) d.fail("solverIterations", "solverIterations must be 1..10000");
        const std::string shapes = d.getWord("collisionShapes", {"auto", "trimesh", "mesh"}, "auto");
        meshOnly_ = shapes == "mesh", usePieces_ = shapes == "auto";
        const Dict ccd = d.subOrEmpty("ccd");
        ccdThreshold_ = ccd.get<double>("motionThreshold", 0.5);
        if (!(ccdThreshold_ >= 0)) ccd.fail("motionThreshold", "a share of the body's size, >= 0 (0: off)");
        ccdRadius_ = ccd.get<double>("sweptSphere", 0.25);
        if (!(ccdRadius_ > 0 && ccdRadius_ <= 1)) ccd.fail("sweptSphere", "a share of the body's size, (0, 1]");
        ccd.reportUnused();
        d.reportUnused();
    }

    ~BulletBackend() override { destroyWorld(); }

    void setup(const std::vector<Body>& bodies) override {
        destroyWorld();
        config_ = std::make_unique<btDefaultCollisionConfiguration>();
        // Several contact points from one call (convex pairs and convex on plane):
        // needed when contacts are found anew every sub-step.
        config_->setConvexConvexMultipointIterations(3, 3);
        config_->setPlaneConvexMultipointIterations(3, 3);
        dispatcher_ = std::make_unique<btCollisionDispatcher>(config_.get());
        btGImpactCollisionAlgorithm::registerAlgorithm(dispatcher_.get());
        // Sorted pairs: the broadphase orders them by the objects' ids every
        // sub-step, so contacts are processed in an order that has no history.
        pairCache_ = std::make_unique<btSortedOverlappingPairCache>();
        broadphase_ = std::make_unique<btDbvtBroadphase>(pairCache_.get());
        solver_ = std::make_unique<TorqueAwareSolver>();
        world_ = std::make_unique<MidpointContactWorld>(dispatcher_.get(), broadphase_.get(), solver_.get(),
                                                        config_.get());
        world_->setGravity(bt(s_.gravity));
        // Hull-hull contacts from the separating-axis test on the hulls' faces
        // and edges, not from GJK/EPA. Bullet's GJK has absolute tolerances
        // made for metre-sized shapes (its simplex solver calls a tetrahedron
        // degenerate when its triple product is under 1e-8 m^3, i.e. edges
        // under ~2 mm) and on millimetre pieces it stopped early and reported
        // overlapping pieces as apart: the bend pieces of two Fig. 8 clips,
        // 0.2 mm into each other, came out 50-250 um apart, so no contact held
        // them and the clips ended 0.37 mm (of a 0.9 mm wire) into each other.
        // The same pieces scaled up 10x give the right depths, and so does the
        // separating-axis test, which compares projections on unit axes only.
        // Boxes against boxes and anything against the ground plane have
        // their own algorithms and are not affected.
        world_->getDispatchInfo().m_enableSatConvex = true;
        btContactSolverInfo& info = world_->getSolverInfo();
        info.m_numIterations = iterations_;
        info.m_erp2 = s_.erp;
        info.m_splitImpulse = splitImpulse_ ? 1 : 0;
        info.m_splitImpulsePenetrationThreshold = splitThreshold_;
        info.m_restitutionVelocityThreshold = s_.bounceVelocity;
        // Penetration left uncorrected: a resting face then touches with all its
        // corners (a box-box contact takes only penetrating points; corrected to
        // zero, the corners drop in and out and the body rocks).
        info.m_linearSlop = s_.surfaceLayer;
        if (!persistent_) info.m_solverMode &= ~SOLVER_USE_WARMSTARTING;
        // Friction in both tangent directions. Bullet's default has one, along
        // the contact's sliding velocity before the solve; where a magnet's
        // pull sets that velocity (two magnets pressed together on the
        // ground: along their axis), nothing held them across it and the
        // pair crept sideways without end.
        info.m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;

        if (s_.groundHeight) {
            groundShape_ = std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), *s_.groundHeight);
            btRigidBody::btRigidBodyConstructionInfo ci(0, nullptr, groundShape_.get());
            ground_ = std::make_unique<btRigidBody>(ci);
            setSurface(*ground_);
            world_->addRigidBody(ground_.get());
        }

        // Bullet's contact breaking threshold is one global length (0.02 m,
        // made for metre-sized games): it also sets how far the multipoint
        // search turns a body to find more contacts, 22 degrees for a 1 cm
        // magnet. Here it scales with the smallest body; set before every step.
        double smallest = std::numeric_limits<double>::infinity();
        for (const Body& b : bodies)
            if (b.shape && b.shape->boundingRadius > 0) smallest = std::min(smallest, b.shape->boundingRadius);
        breakingThreshold_ = std::isfinite(smallest) ? breakingShare_ * smallest : 0.02;
        gContactBreakingThreshold = breakingThreshold_;

        entries_.clear();
        entries_.resize(bodies.size());
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            const Body& b = bodies[i];
            if (!b.shape) throw InputError("body '" + b.name + "' has no shape");
            Entry& e = entries_[i];
            e.scale = b.shape->boundingRadius;
            e.fixed = b.fixed;
            btCollisionShape* shape = &shapeOf(b);
            btVector3 inertia(0, 0, 0);
            double mass = 0;
            if (!b.fixed) {
                mass = b.mass();
                const Mat3 I = b.inertiaBody();
                if (!(mass > 0) || !std::isfinite(mass))
                    throw InputError("body '" + b.name + "': mass must be positive and finite, got " +
                                     std::to_string(mass) + " kg");
                // Principal axes (columns of P, a proper rotation) and moments.
                Eigen::SelfAdjointEigenSolver<Mat3> eigen(I);
                Mat3 P = eigen.eigenvectors();
                if (P.determinant() < 0) P.col(2) = -P.col(2);
                const Vec3 moments = eigen.eigenvalues();
                if (!(moments.minCoeff() > 0)) throw InputError("body '" + b.name + "': inertia tensor is not positive definite");
                // Diagonal already (boxes, cylinders, spheres): the body axes are principal.
                const Mat3 offDiagonal = I - Mat3(I.diagonal().asDiagonal());
                if (offDiagonal.norm() <= 1e-12 * I.norm()) {
                    P.setIdentity();
                    inertia = bt(Vec3(I.diagonal()));
                } else {
                    inertia = bt(moments);
                    // The shape in the principal frame: p_principal = P^T p_body.
                    e.wrapper = std::make_unique<btCompoundShape>(false, 1);
                    e.wrapper->addChildShape(btTransform(btMat(P.transpose())), shape);
                    shape = e.wrapper.get();
                }
                e.principal = P;
                e.mass = mass;
                e.inertiaDiagonal = eig(inertia);
            }
            btRigidBody::btRigidBodyConstructionInfo ci(mass, nullptr, shape, inertia);
            ci.m_linearDamping = ci.m_angularDamping = 0;
            ci.m_linearSleepingThreshold = ci.m_angularSleepingThreshold = 0;
            e.body = std::make_unique<btRigidBody>(ci);
            setSurface(*e.body);
            e.body->setActivationState(DISABLE_DEACTIVATION);
            if (!b.fixed && ccdThreshold_ > 0) {
                // Continuous collision: a body moving more than this in a sub-step
                // is swept (a sphere of this radius) and stopped at the first hit.
                const double smallest = smallestExtent(*b.shape);
                e.body->setCcdMotionThreshold(ccdThreshold_ * smallest);
                e.body->setCcdSweptSphereRadius(ccdRadius_ * smallest);
            }
            world_->addRigidBody(e.body.get());
            push(b, e);
        }
    }

    void step(std::vector<Body>& bodies, std::span<const Wrench> wrenches, double dt) override {
        if (!world_ || bodies.size() != entries_.size())
            throw std::logic_error("Bullet rigid-body backend: step() with " + std::to_string(bodies.size()) +
                                   " bodies after setup() with " + std::to_string(entries_.size()));
        if (wrenches.size() != bodies.size())
            throw std::invalid_argument("Bullet rigid-body backend: one wrench per body expected");
        if (!(dt > 0) || !std::isfinite(dt))
            throw std::invalid_argument("Bullet rigid-body backend: time step must be positive and finite");
        // Bullet would carry a NaN into every body it touches: refuse it first.
        for (std::size_t i = 0; i < bodies.size(); ++i)
            if (!entries_[i].fixed && !(wrenches[i].force.allFinite() && wrenches[i].totalTorque().allFinite()))
                throw std::invalid_argument("Bullet rigid-body backend: the wrench on body '" + bodies[i].name +
                                            "' is not finite");
        gContactBreakingThreshold = breakingThreshold_;
        const int n = subStepsFor(wrenches, dt);
        steps_ += 1, subStepsTaken_ += n;
        const double h = dt / n;
        for (int s = 0; s < n; ++s) {
            if (!persistent_) forgetContacts();
            for (std::size_t i = 0; i < bodies.size(); ++i) {
                Entry& e = entries_[i];
                if (e.fixed || e.asleep) continue;
                e.body->applyCentralForce(bt(wrenches[i].force));
                e.body->applyTorque(bt(wrenches[i].totalTorque()));
            }
            world_->stepSimulation(h, 0, h);
            contactsUsed_ += countContacts();
        }
        for (std::size_t i = 0; i < bodies.size(); ++i) pull(bodies[i], entries_[i]);
    }

    bool canSleep() const override { return true; }
    void setSleeping(std::vector<Body>& bodies, const std::vector<char>& asleep) override {
        // A sleeping body is held still (static for the solver: no velocity, no
        // force); its neighbours rest on it as on a fixed body.
        for (std::size_t i = 0; i < bodies.size() && i < entries_.size(); ++i) {
            Entry& e = entries_[i];
            if (e.fixed) continue;
            const bool sleep = i < asleep.size() && asleep[i];
            if (sleep == e.asleep) continue;
            e.asleep = sleep;
            // Mass 0 makes it static in place (it stays in the world, so the
            // order of the objects, and of the contacts, is kept).
            if (sleep) {
                bodies[i].velocity.setZero(), bodies[i].angularVelocity.setZero();
                e.body->setLinearVelocity(btVector3(0, 0, 0));
                e.body->setAngularVelocity(btVector3(0, 0, 0));
                e.body->setMassProps(0, btVector3(0, 0, 0));
            } else {
                e.body->setMassProps(e.mass, bt(e.inertiaDiagonal));
            }
            e.body->updateInertiaTensor();
        }
    }
    std::vector<char> sleeping() const override {
        std::vector<char> out(entries_.size(), 0);
        for (std::size_t i = 0; i < entries_.size(); ++i) out[i] = entries_[i].asleep;
        return out;
    }

    void setState(const std::vector<Body>& bodies) override {
        if (!world_ || bodies.size() != entries_.size())
            throw std::logic_error("Bullet rigid-body backend: setState() with " + std::to_string(bodies.size()) +
                                   " bodies after setup() with " + std::to_string(entries_.size()));
        for (std::size_t i = 0; i < bodies.size(); ++i) push(bodies[i], entries_[i]);
        forgetContacts();
    }

    void writeState(std::ostream& os, const std::vector<Body>& bodies) const override {
        if (!world_ || bodies.size() != entries_.size()) return;
        os << "# Bullet backend: each body's rotation matrix (principal frame), as Bullet holds it\ntype: Bullet\n"
              "bodies:\n";
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            const btMatrix3x3& m = entries_[i].body->getWorldTransform().getBasis();
            os << "  - name: " << bodies[i].name << "\n    basis: [" << formatExact(eig(m.getRow(0))) << ", "
               << formatExact(eig(m.getRow(1))) << ", " << formatExact(eig(m.getRow(2))) << "]\n";
        }
    }

    void readState(const Dict& d, const std::vector<Body>& bodies) override {
        if (!world_ || bodies.size() != entries_.size())
            throw std::logic_error("Bullet rigid-body backend: readState() before setup()");
        if (d.get<std::string>("type") != "Bullet") {
            spdlog::warn("{}: not the state of a Bullet backend: ignored", d.file());
            return;
        }
        for (const Dict& b : d.list("bodies")) {
            const std::size_t i = stateBodyIndex(b, bodies);
            const std::string& name = bodies[i].name;
            const auto rows = b.get<std::vector<std::vector<double>>>("basis");
            if (rows.size() != 3 || rows[0].size() != 3 || rows[1].size() != 3 || rows[2].size() != 3)
                b.fail("basis", "a 3 x 3 rotation matrix, three rows of three numbers");
            Mat3 m;
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c) m(r, c) = rows[r][c];
            // Only the same rotation as the state's quaternion, to round-off: an
            // edited bodies.yaml wins.
            const Mat3 fromQuaternion = bodies[i].orientation.normalized().toRotationMatrix() * entries_[i].principal;
            if ((m - fromQuaternion).norm() > 1e-12) {
                spdlog::warn("{}: body '{}': the rotation differs from bodies.yaml's orientation; bodies.yaml's is used",
                             d.file(), name);
                continue;
            }
            entries_[i].body->getWorldTransform().setBasis(btMat(m));
            entries_[i].body->setInterpolationWorldTransform(entries_[i].body->getWorldTransform());
            entries_[i].body->updateInertiaTensor();
        }
        d.reportUnused();
    }

    std::string describe() const override {
        std::ostringstream os;
        os << "Bullet " << btGetVersion() << " (double), gravity [" << s_.gravity.x() << ", " << s_.gravity.y() << ", "
           << s_.gravity.z() << "] m/s^2";
        if (s_.groundHeight) os << ", ground z = " << *s_.groundHeight;
        os << ", friction " << s_.friction;
        if (s_.rollingFriction > 0 || s_.spinningFriction > 0)
            os << ", rolling friction " << s_.rollingFriction << " m, spinning friction " << s_.spinningFriction << " m";
        os << ", restitution " << s_.restitution << ", erp " << s_.erp << ", margin "
           << margin_ << " m, " << iterations_ << " solver iterations, split impulse " << (splitImpulse_ ? "on" : "off")
           << ", contacts " << (persistent_ ? "persistent" : "found anew every sub-step") << ", subSteps " << s_.subSteps;
        if (stiffness_ > 0) os << ", contact springs " << stiffness_ << " N/m, " << damping_ << " N s/m";
        std::map<std::string, int> count;
        for (const auto& [shape, holder] : shapes_) ++count[holder->kind];
        os << "; collision shapes:";
        const char* sep = " ";
        for (const auto& [name, n] : count) os << sep << n << " " << name, sep = ", ";
        if (steps_ > 0)
            os << "; sub-steps taken " << subStepsTaken_ << " in " << steps_ << " steps; contact points used "
               << contactsUsed_;
        return os.str();
    }

private:
    struct Entry {
        std::unique_ptr<btRigidBody> body;
        std::unique_ptr<btCompoundShape> wrapper;  // the shape in the principal frame, when not the body frame
        Mat3 principal = Mat3::Identity();         // principal axes in the body frame (columns)
        Vec3 inertiaDiagonal = Vec3::Zero();
        double mass = 0, scale = 0;
        bool fixed = false, asleep = false;
    };

    void setSurface(btRigidBody& b) const {
        b.setFriction(std::sqrt(s_.friction));
        b.setRestitution(std::sqrt(s_.restitution));
        // Bullet combines two objects' stiffnesses as springs in series and
        // adds their dampings: each gets 2 k and d / 2, a pair k and d.
        if (stiffness_ > 0) b.setContactStiffnessAndDamping(2 * stiffness_, 0.5 * damping_);
        // Bullet combines r0 f1 + r1 f0 (btManifoldResult): with f = sqrt(mu)
        // on every object, r = b / (2 sqrt(mu)) gives the pair b (a length:
        // torque impulse per normal impulse, as ODE's rho).
        // Bullet adds a contact's spinning-friction row only where its rolling
        // friction is positive: a spinning one alone gets a rolling friction
        // too small to act.
        const double f = std::sqrt(s_.friction);
        const double rolling = s_.rollingFriction > 0   ? s_.rollingFriction
                               : s_.spinningFriction > 0 ? std::numeric_limits<double>::min()
                                                         : 0.0;
        b.setRollingFriction(f > 0 ? rolling / (2 * f) : 0.0);
        b.setSpinningFriction(f > 0 ? s_.spinningFriction / (2 * f) : 0.0);
    }

    static double smallestExtent(const Shape& s) {
        Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
        for (const Vec3& v : s.mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
        return (hi - lo).minCoeff();
    }

    // Sub-steps so that no body travels more than maxTravel of its bounding
    // radius in one (as the ODE backend).
    int subStepsFor(std::span<const Wrench> wrenches, double dt) const {
        if (s_.maxTravel <= 0) return s_.subSteps;
        double worst = 0;
        for (std::size_t i = 0; i < entries_.size(); ++i) {
            const Entry& e = entries_[i];
            if (e.fixed || e.asleep || !(e.scale > 0)) continue;
            const Vec3 v = eig(e.body->getLinearVelocity()), w = eig(e.body->getAngularVelocity());
            const Vec3 a = wrenches[i].force / e.mass + s_.gravity;
            const double travel = (v.norm() + w.norm() * e.scale) * dt + 0.5 * a.norm() * dt * dt;
            worst = std::max(worst, travel / e.scale);
        }
        return s_.subStepsFor(worst);
    }

    // Drop every pair's collision algorithm and manifold: the next sub-step
    // finds its contacts anew, in the sorted pair order.
    void forgetContacts() {
        btBroadphasePairArray& pairs = pairCache_->getOverlappingPairArray();
        for (int k = 0; k < pairs.size(); ++k) pairCache_->cleanOverlappingPair(pairs[k], dispatcher_.get());
    }

    long countContacts() const {
        long n = 0;
        for (int k = 0; k < dispatcher_->getNumManifolds(); ++k)
            n += dispatcher_->getManifoldByIndexInternal(k)->getNumContacts();
        return n;
    }

    // Body -> Bullet: the principal frame's pose and the velocities.
    static void push(const Body& b, Entry& e) {
        const Mat3 R = b.orientation.normalized().toRotationMatrix() * e.principal;
        e.body->setWorldTransform(btTransform(btMat(R), bt(b.position)));
        e.body->setInterpolationWorldTransform(e.body->getWorldTransform());
        if (e.fixed) return;
        e.body->setLinearVelocity(bt(b.velocity));
        e.body->setAngularVelocity(bt(b.angularVelocity));
        e.body->setInterpolationLinearVelocity(bt(b.velocity));
        e.body->setInterpolationAngularVelocity(bt(b.angularVelocity));
        e.body->updateInertiaTensor();
    }

    // Bullet -> Body.
    static void pull(Body& b, const Entry& e) {
        if (e.fixed) {
            b.velocity.setZero(), b.angularVelocity.setZero();
            return;
        }
        const btTransform& t = e.body->getWorldTransform();
        b.position = eig(t.getOrigin());
        b.orientation = Quat(Mat3(eig(t.getBasis()) * e.principal.transpose())).normalized();
        b.velocity = eig(e.body->getLinearVelocity());
        b.angularVelocity = eig(e.body->getAngularVelocity());
    }

    // The collision shape of a body, built once per shape (or compound).
    btCollisionShape& shapeOf(const Body& b) {
        const void* key = b.compound ? static_cast<const void*>(b.compound.get()) : b.shape.get();
        const bool staticMesh = b.fixed;
        const auto id = std::make_pair(key, staticMesh);
        if (auto it = shapes_.find(id); it != shapes_.end()) return *it->second->shape;
        auto holder = std::make_unique<ShapeHolder>();
        if (b.compound) {
            auto compound = std::make_unique<btCompoundShape>(true, static_cast<int>(b.compound->parts.size()));
            for (const Part& p : b.compound->parts) {
                auto child = std::make_unique<ShapeHolder>();
                buildShape(*p.shape, staticMesh, *child);
                const Mat3 R = p.orientation.normalized().toRotationMatrix();
                compound->addChildShape(btTransform(btMat(R), bt(p.position)), child->shape.get());
                holder->kind = "compound";
                parts_.push_back(std::move(child));
            }
            holder->shape = std::move(compound);
        } else {
            buildShape(*b.shape, staticMesh, *holder);
        }
        return *shapes_.emplace(id, std::move(holder)).first->second->shape;
    }

    void buildShape(const Shape& s, bool staticMesh, ShapeHolder& h) const {
        using K = ShapeKind::Kind;
        if (!meshOnly_ && s.kind.kind == K::box) {
            auto box = std::make_unique<btBoxShape>(bt(Vec3(0.5 * s.kind.size)));
            box->setMargin(std::min(margin_, 0.25 * s.kind.size.minCoeff()));
            box->initializePolyhedralFeatures();
            h.shape = std::move(box), h.kind = "box";
        } else if (!meshOnly_ && s.kind.kind == K::sphere) {
            h.shape = std::make_unique<btSphereShape>(s.kind.radius), h.kind = "sphere";
        } else if (usePieces_ && !s.pieces.empty()) {
            // A concave mesh's convex pieces (docs/rigid-bodies.md#convex-pieces):
            // a compound of hulls, each about its centroid.
            auto compound = std::make_unique<btCompoundShape>(true, static_cast<int>(s.pieces.size()));
            for (const ConvexHull& piece : s.pieces) {
                auto hull = std::make_unique<btConvexHullShape>();
                for (const Vec3& v : piece.points) hull->addPoint(bt(Vec3(v - piece.centroid)), false);
                // The margin before the AABB: recalcLocalAabb() stores the box
                // with the margin then set (Bullet's default, 0.04 m), and every
                // AABB query adds the margin again. Set after, each piece's box
                // was 8 cm wide, every piece met every piece of every body
                // nearby in the narrow phase and a Fig. 8 rigid step cost 95 ms
                // (5 ms with the right boxes).
                hull->setMargin(margin_);
                hull->recalcLocalAabb();
                hull->initializePolyhedralFeatures();
                btTransform at;
                at.setIdentity();
                at.setOrigin(bt(piece.centroid));
                compound->addChildShape(at, hull.get());
                h.children.push_back(std::move(hull));
            }
            h.shape = std::move(compound), h.kind = "convex pieces";
        } else if (!meshOnly_ && isConvex(s.mesh)) {
            // Cylinders too (their mesh's hull): Bullet's own cylinder rocks on
            // the ground plane when contacts are found anew every sub-step.
            auto hull = std::make_unique<btConvexHullShape>();
            for (const Vec3& v : s.mesh.vertices) hull->addPoint(bt(v), false);
            hull->setMargin(margin_);  // before the AABB (as for the pieces above)
            hull->recalcLocalAabb();
            hull->initializePolyhedralFeatures();
            h.shape = std::move(hull), h.kind = "convex hull";
        } else {
            for (const Vec3& v : s.mesh.vertices) h.vertices.insert(h.vertices.end(), {v.x(), v.y(), v.z()});
            for (const auto& t : s.mesh.triangles) h.indices.insert(h.indices.end(), {t[0], t[1], t[2]});
            h.triangles = std::make_unique<btTriangleIndexVertexArray>(
                s.mesh.nTriangles(), h.indices.data(), 3 * static_cast<int>(sizeof(int)), s.mesh.nVertices(),
                h.vertices.data(), 3 * static_cast<int>(sizeof(btScalar)));
            if (staticMesh) {
                auto bvh = std::make_unique<btBvhTriangleMeshShape>(h.triangles.get(), true);
                bvh->setMargin(margin_);
                h.shape = std::move(bvh), h.kind = "static triangle mesh";
            } else {
                auto gimpact = std::make_unique<btGImpactMeshShape>(h.triangles.get());
                gimpact->setMargin(margin_);
                gimpact->updateBound();
                h.shape = std::move(gimpact), h.kind = "GImpact mesh";
            }
        }
    }

    void destroyWorld() {
        if (world_) {
            for (Entry& e : entries_)
                if (e.body) world_->removeRigidBody(e.body.get());
            if (ground_) world_->removeRigidBody(ground_.get());
        }
        entries_.clear();
        ground_.reset(), groundShape_.reset();
        world_.reset(), solver_.reset(), broadphase_.reset(), pairCache_.reset(), dispatcher_.reset(), config_.reset();
        shapes_.clear(), parts_.clear();
    }

    // Settings.
    ContactSettings s_;
    double margin_ = 1e-5, stiffness_ = 0, damping_ = 0, breakingShare_ = 0.1, breakingThreshold_ = 0.02;
    double splitThreshold_ = -1e-5, ccdThreshold_ = 0.5, ccdRadius_ = 0.25;
    int iterations_ = 1000; // solverIterations' default (see the constructor)
    bool splitImpulse_ = true, persistent_ = false, meshOnly_ = false, usePieces_ = true;

    // Bullet objects (destroyed in reverse order of creation).
    std::unique_ptr<btDefaultCollisionConfiguration> config_;
    std::unique_ptr<btCollisionDispatcher> dispatcher_;
    std::unique_ptr<btSortedOverlappingPairCache> pairCache_;
    std::unique_ptr<btDbvtBroadphase> broadphase_;
    std::unique_ptr<TorqueAwareSolver> solver_;
    std::unique_ptr<MidpointContactWorld> world_;
    std::unique_ptr<btCollisionShape> groundShape_;
    std::unique_ptr<btRigidBody> ground_;
    std::map<std::pair<const void*, bool>, std::unique_ptr<ShapeHolder>> shapes_;
    std::vector<std::unique_ptr<ShapeHolder>> parts_;  // compounds' children
    std::vector<Entry> entries_;
    long steps_ = 0, subStepsTaken_ = 0, contactsUsed_ = 0;
};

const TypeDoc kDoc{
    "Bullet Physics (double precision), the paper's engine: rigid bodies with contacts,\n"
    "gravity and a ground plane; primitives, convex hulls, GImpact meshes for concave\n"
    "bodies, compounds; continuous collision detection for fast thin parts.",
    {"type: Bullet\ngravity: [0, 0, -9.81]\nground: {height: 0}\n"
     "contact: {friction: 0.5, restitution: 0.1, bounceVelocity: 0.1, erp: 0.2, margin: 1e-5}\n"
     "subSteps: 1\nmaxTravel: 0.1\nsolverIterations: 1000\n"},
    {{"gravity", "m/s^2", "uniform acceleration of every dynamic body (energy.csv uses the same)"},
     {"ground", "-", "a ground plane z = height; without this key, no plane"},
     {"ground.height", "m", "height of the ground plane"},
     {"contact", "-", "contact parameters of every pair"},
     {"contact.friction", "-", "Coulomb coefficient mu of every pair, >= 0"},
     {"contact.rollingFriction", "m",
      "rolling resistance: a contact resists rolling with a torque up to this times its normal force, >= 0 "
      "(default 0; needs friction > 0)"},
     {"contact.spinningFriction", "m",
      "spinning resistance: the same about the contact's normal, >= 0 (default 0; needs friction > 0)"},
     {"contact.restitution", "-", "0..1"},
     {"contact.bounceVelocity", "m/s", "slower impacts do not bounce"},
     {"contact.erp", "-", "share of the penetration corrected per sub-step, (0, 1]"},
     {"contact.surfaceLayer", "m", "penetration left uncorrected, >= 0 (resting faces touch with all corners)"},
     {"contact.margin", "m", "collision margin around hulls and meshes (inside boxes and cylinders), > 0"},
     {"contact.splitImpulse", "-", "correct penetration by a separate impulse that adds no velocity"},
     {"contact.splitImpulseThreshold", "m", "penetration (<= 0) beyond which the split impulse is used"},
     {"contact.stiffness", "N/m",
      "a contact spring of this constant (penetrating contacts, as a soft body's); 0: rigid contacts"},
     {"contact.damping", "N s/m", "the contact spring's damping (with stiffness)"},
     {"contact.breakingThreshold", "-",
      "Bullet's contact breaking threshold as a share of the smallest body's bounding radius, > 0"},
     {"contact.persistent", "-",
      "keep contact manifolds between sub-steps (warm starting; restarts are then not bit for bit)"},
     {"subSteps", "-", "Bullet steps per solver step, 1..10000 (the wrench is held over them)"},
     {"maxTravel", "-",
      "more sub-steps while a body would travel more than this times its bounding radius in one;\n"
      "0: always subSteps"},
     {"maxSubSteps", "-", "cap of the automatic sub-steps, subSteps..100000"},
     {"solverIterations", "-",
      "sequential-impulse sweeps per sub-step, 1..10000 (magnets pressed together need many: 1000)"},
     {"collisionShapes", "-",
      "auto (primitives, convex pieces, hulls, meshes), trimesh (no convex pieces) or mesh (every dynamic body a "
      "GImpact mesh)"},
     {"ccd", "-", "continuous collision detection of dynamic bodies"},
     {"ccd.motionThreshold", "-", "swept when moving more than this share of its smallest extent per sub-step; 0: off"},
     {"ccd.sweptSphere", "-", "radius of the swept sphere, a share of the smallest extent, (0, 1]"}}};

const RigidBodyBackend::Add<BulletBackend> addBullet("Bullet", kDoc);

} // namespace

} // namespace mag
