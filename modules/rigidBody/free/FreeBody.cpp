// free: a contact-free, symplectic rigid-body integrator for field-only runs
// (orbits, tumbling magnets in space) and unit tests. Bodies feel the magnetic
// wrench and gravity only: no contacts, no ground, they pass through each other.
//
//   # constant/rigidBody.yaml
//   type: free
//   gravity: [0, 0, -9.81]
//   integrator: symplecticEuler    # or verlet
//   subSteps: 1
//
// Keys: kDoc at the registration below (magFoam -doc free).
//
// `ground` and `contact` are rejected with a message saying that they belong
// to the ODE backend: a case that asks for a floor must not silently lose it.
//
// The solver evaluates the wrench once per step, at the state the step starts
// from. Then no one-step method can be at the same time symplectic, exact for
// a constant force (the parabola) and a function of the written state alone
// (so that a restart from the written state continues bit for bit): the only
// map exact for constant forces is x += v h + a h^2/2, v += a h, which is not
// symplectic (40% energy error after 10 Kepler orbits of 1000 steps). Hence
// two integrators (h = deltaT / subSteps):
// - symplecticEuler (default): kick-drift, v += a h; x += v h (as ODE's
//   dWorldStep). Symplectic, first order for velocities, a function of the
//   written state only: restarts are bit-identical, and a body's motion does
//   not depend on earlier steps. Its positions are those of leapfrog started
//   from v(-h/2) = v0, the written velocity is leapfrog's half-step
//   velocity: the energy error is O(h), bounded (no drift); the angular
//   momentum of central forces is exact. A constant force gives
//   x0 + v0 t + a t^2/2 + a t h/2.
// - verlet: velocity Verlet, v += a h/2; x += v h; v += a h/2. The closing half
//   kick of step n needs a_{n+1}, which only arrives with step n+1: the
//   velocity written at the end of step n uses a prediction of a_{n+1}
//   (linear extrapolation from a_n and a_{n-1}; a_n at the first step), and
//   step n+1 replaces it by the actual value, v += (a_{n+1} - a_predicted) h/2.
//   Positions are exactly velocity Verlet's: symplectic, time-reversible,
//   second order, O(h^2) bounded energy error (8x smaller than holding the
//   wrench constant in that half kick); a constant force gives the exact
//   parabola. The price: state carried between steps (per body the last
//   step's wrench, its prediction, h, deltaT and the world angular momentum
//   L). It is the backend's restart state, written as <time>/rigidBody.yaml
//     type: free
//     integrator: verlet
//     bodies:
//       - {name: top, L: [..], a: [..], tau: [..], predictedA: [..],
//          predictedTau: [..], h: .., deltaT: ..}    # %.17g, SI
//   and read back at a restart: the restarted run continues bit for bit.
//   setState() (a state changed from outside) starts the integrator afresh
//   (no correction in the next step), as does a restart without the file.
// Rotation, either way: the same kick(s) on the world angular momentum L (the
// torque is constant in the world frame) around a free rotation for h. The
// free rotation is a Lie-Poisson splitting of the kinetic energy (Touma and
// Wisdom, Astron. J. 107, 1189 (1994); Fasso, J. Comput. Phys. 189, 527
// (2003)), with l the angular momentum in the principal frame and
// I1 <= I2 <= I3 the principal moments of the full inertia tensor:
//     T = |l|^2 / (2 I2) + (1/I1 - 1/I2) l1^2 / 2 + (1/I3 - 1/I2) l3^2 / 2.
// Each part is solved exactly: the first turns the body about l by h |l| / I2,
// the others turn it about principal axis k by h (1/Ik - 1/I2) lk. The first
// commutes with everything (|l| is a Casimir); the other two are composed
// symmetrically, 1(h/2) 3(h) 1(h/2): second order. Compared with NO_SQUISH's
// three axis rotations (Miller et al., J. Chem. Phys. 116, 8649 (2002)) it is
// exact for spherical and symmetric tops (cubes, cylinders, spheres: most
// magnets), and for the 1:2:3 box of the tests its energy error is half and
// its phase error a third of NO_SQUISH's. Every sub-step is a rotation, so
// the orientation stays a unit quaternion (renormalised only against
// round-off; no Euler angles, no gimbal lock), the free flight keeps the
// world L (exactly with verlet, which carries L; to round-off with
// symplecticEuler, which recomputes it from the written angular velocity), and
// the map is symplectic and time-reversible: energy error bounded, O(h^2).
// Fixed bodies never move: their velocities are written as zero and their
// wrench is ignored.
#include <magFoam/Error.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/RigidBodyBackend.hpp>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include <magFoam/ResultsWriter.hpp>

#include <cmath>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace mag {

namespace {

// Free rigid-body rotation over h with constant world angular momentum L:
// Q is the principal frame -> world rotation, I the ascending principal moments.
Quat freeRotation(Quat Q, const Vec3& L, const Vec3& I, double h) {
    Vec3 l = Q.conjugate() * L;
    // Flow of (1/Ik - 1/I2) lk^2 / 2: the body turns about its axis k by
    // t (1/Ik - 1/I2) lk, and l (seen from the body) turns back; lk is constant.
    auto turn = [&](int k, double t) {
        const Quat r(Eigen::AngleAxisd(t * (1 / I[k] - 1 / I[1]) * l[k], Vec3::Unit(k)));
        Q = Q * r;
        l = r.conjugate() * l;
    };
    turn(0, 0.5 * h);
    turn(2, h);
    turn(0, 0.5 * h);
    // Flow of |l|^2 / (2 I2): the body turns about l by h |l| / I2; l is constant.
    if (const double n = l.norm(); n > 0) Q = Q * Quat(Eigen::AngleAxisd(h * n / I[1], l / n));
    return Q.normalized();
}

class FreeBody final : public RigidBodyBackend {
public:
    explicit FreeBody(const Dict& d) {
        for (const char* key : {"ground", "contact"})
            if (d.has(key))
                d.fail(key, std::string("the free backend has no contacts and no ground; '") + key +
                                "' belongs to type ODE (remove it, or use type: ODE)");
        gravity_ = d.get<Vec3>("gravity", Vec3::Zero());
        verlet_ = d.getWord("integrator", {"symplecticEuler", "verlet"}, "symplecticEuler") == "verlet";
        subSteps_ = d.get<int>("subSteps", 1);
        if (subSteps_ < 1 || subSteps_ > 10000) d.fail("subSteps", "subSteps must be 1..10000");
    }

    void setup(const std::vector<Body>& bodies) override {
        states_.assign(bodies.size(), State{});
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            const Body& b = bodies[i];
            if (!b.shape) throw InputError("body '" + b.name + "' has no shape");
            if (b.fixed) continue;
            State& s = states_[i];
            s.mass = b.mass();
            if (!(s.mass > 0) || !std::isfinite(s.mass))
                throw InputError("body '" + b.name + "': mass must be positive and finite (density * volume), got " +
                                 std::to_string(s.mass) + " kg");
            // Principal axes of the full inertia tensor, as a proper rotation.
            const Eigen::SelfAdjointEigenSolver<Mat3> eig(b.inertiaBody());
            Mat3 axes = eig.eigenvectors();
            if (axes.determinant() < 0) axes.col(2) = -axes.col(2);
            s.moments = eig.eigenvalues();
            if (eig.info() != Eigen::Success || !(s.moments.minCoeff() > 0) || !s.moments.allFinite())
                throw InputError("body '" + b.name + "': inertia tensor is not positive definite");
            s.principal = Quat(axes).normalized();
        }
    }

    void step(std::vector<Body>& bodies, std::span<const Wrench> wrenches, double dt) override {
        if (bodies.size() != states_.size())
            throw std::logic_error("free rigid-body backend: step() with " + std::to_string(bodies.size()) +
                                   " bodies after setup() with " + std::to_string(states_.size()));
        if (wrenches.size() != bodies.size())
            throw std::invalid_argument("free rigid-body backend: one wrench per body expected");
        if (!(dt > 0) || !std::isfinite(dt))
            throw std::invalid_argument("free rigid-body backend: time step must be positive and finite");
        const std::vector<Mat3> stiffness = std::exchange(stiffness_, {}); // this step's only
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            Body& b = bodies[i];
            State& s = states_[i];
            if (b.fixed || s.asleep) {
                b.velocity.setZero();
                b.angularVelocity.setZero();
                continue;
            }
            const Vec3 a = wrenches[i].force / s.mass + gravity_;
            const Vec3 tau = wrenches[i].totalTorque();

            Vec3 x = b.position, v = b.velocity, L;
            Quat Q = b.orientation.normalized() * s.principal;
            if (verlet_)
                verletStep(b, s, a, tau, dt, x, v, Q, L);
            else
                symplecticEulerStep(b, s, a, tau, dt, x, v, Q, L,
                                    i < stiffness.size() && !stiffness[i].isZero(0.0) ? &stiffness[i] : nullptr);

            b.position = x;
            b.velocity = v;
            b.orientation = (Q * s.principal.conjugate()).normalized();
            b.angularVelocity = Q * (Q.conjugate() * L).cwiseQuotient(s.moments);
            s.started = true;
            s.L = L;
        }
    }

    // symplectic only: verlet's closing half kick has no implicit form here.
    bool setTiltStiffness(std::span<const Mat3> stiffness) override {
        if (verlet_) return false;
        stiffness_.assign(stiffness.begin(), stiffness.end());
        return true;
    }

    // A sleeping body does not move; woken, it starts afresh (verlet: no kick
    // carried over its sleep).
    bool canSleep() const override { return true; }
    void setSleeping(std::vector<Body>& bodies, const std::vector<char>& asleep) override {
        for (std::size_t i = 0; i < bodies.size() && i < states_.size(); ++i) {
            const bool now = i < asleep.size() && asleep[i] && !bodies[i].fixed;
            if (now) bodies[i].velocity.setZero(), bodies[i].angularVelocity.setZero();
            if (now != states_[i].asleep) states_[i].started = false;
            states_[i].asleep = now;
        }
    }
    std::vector<char> sleeping() const override {
        std::vector<char> out(states_.size());
        for (std::size_t i = 0; i < states_.size(); ++i) out[i] = states_[i].asleep;
        return out;
    }

    // verlet: the next step starts afresh from the bodies' state.
    void setState(const std::vector<Body>& bodies) override {
        if (bodies.size() != states_.size())
            throw std::logic_error("free rigid-body backend: setState() with " + std::to_string(bodies.size()) +
                                   " bodies after setup() with " + std::to_string(states_.size()));
        for (State& s : states_) s.started = false;
    }

    // verlet: what the next step continues from (see the header); nothing for
    // symplecticEuler, a function of the bodies' state alone.
    void writeState(std::ostream& os, const std::vector<Body>& bodies) const override {
        if (!verlet_) return;
        bool any = false;
        for (std::size_t i = 0; i < bodies.size() && i < states_.size(); ++i) {
            const State& s = states_[i];
            if (bodies[i].fixed || !s.started) continue;
            if (!any) os << "# free backend, velocity Verlet: what each body's next step continues from\n"
                            "type: free\nintegrator: verlet\nbodies:\n";
            any = true;
            os << "  - {name: " << bodies[i].name << ", L: " << formatExact(s.L) << ",\n     a: "
               << formatExact(s.lastA) << ", tau: " << formatExact(s.lastTau) << ",\n     predictedA: "
               << formatExact(s.predictedA) << ", predictedTau: " << formatExact(s.predictedTau)
               << ",\n     h: " << formatExact(s.lastH) << ", deltaT: " << formatExact(s.lastDt) << "}\n";
        }
    }

    void readState(const Dict& d, const std::vector<Body>& bodies) override {
        if (!verlet_) return;
        if (d.get<std::string>("type") != "free" || d.get<std::string>("integrator", "") != "verlet") {
            spdlog::warn("{}: not the state of the free backend's verlet integrator: ignored (the integrator "
                         "starts afresh)", d.file());
            return;
        }
        for (const Dict& e : d.list("bodies")) {
            const std::string name = e.get<std::string>("name");
            std::size_t i = 0;
            while (i < bodies.size() && bodies[i].name != name) ++i;
            if (i == bodies.size() || i >= states_.size() || bodies[i].fixed)
                e.fail("name", "no dynamic body '" + name + "' in constant/bodies.yaml");
            State& s = states_[i];
            s.L = e.get<Vec3>("L");
            s.lastA = e.get<Vec3>("a"), s.lastTau = e.get<Vec3>("tau");
            s.predictedA = e.get<Vec3>("predictedA"), s.predictedTau = e.get<Vec3>("predictedTau");
            s.lastH = e.get<double>("h"), s.lastDt = e.get<double>("deltaT");
            if (!(s.lastH > 0) || !(s.lastDt > 0)) e.fail("h", "h and deltaT must be > 0");
            s.started = true;
            e.reportUnused();
        }
        d.reportUnused();
    }

    std::string describe() const override {
        std::ostringstream os;
        os << "free (" << (verlet_ ? "velocity Verlet" : "symplectic Euler")
           << " + Lie-Poisson rotation splitting; gravity [" << gravity_.x() << ", "
           << gravity_.y() << ", " << gravity_.z() << "] m/s^2; subSteps " << subSteps_ << "; no contacts)";
        return os.str();
    }

private:
    std::vector<Mat3> stiffness_; // for the next step only (setTiltStiffness)

    struct State {
        double mass = 0;
        Vec3 moments = Vec3::Ones();      // principal moments, kg m^2
        Quat principal = Quat::Identity(); // principal frame -> body frame
        bool asleep = false;               // resting until woken (setSleeping)
        // verlet only (the restart state):
        bool started = false;
        Vec3 L = Vec3::Zero();             // world angular momentum at the end of the last step
        Vec3 lastA = Vec3::Zero(), lastTau = Vec3::Zero();           // wrench of the last step
        Vec3 predictedA = Vec3::Zero(), predictedTau = Vec3::Zero(); // used in its closing half kick
        double lastH = 0, lastDt = 0;
    };

    // Kick-drift, a function of the body's state alone.
    // With a tilt stiffness S (setTiltStiffness) the spin is backward Euler
    // of tau - S dtheta: (I + h^2 S) w' = L + h tau.
    void symplecticEulerStep(const Body& b, const State& s, const Vec3& a, const Vec3& tau, double dt, Vec3& x, Vec3& v,
                             Quat& Q, Vec3& L, const Mat3* S = nullptr) const {
        const double h = dt / subSteps_;
        L = Q * s.moments.cwiseProduct(Q.conjugate() * b.angularVelocity);
        const Quat start = Q;
        for (int k = 0; k < subSteps_; ++k) {
            v += h * a;
            x += h * v;
            if (S) {
                // The step's torque linearised about its start (the turn
                // since then, phi, counts in later sub-steps).
                const Eigen::AngleAxisd turned(Q * start.conjugate());
                const Mat3 R = Q.toRotationMatrix();
                const Mat3 I = R * s.moments.asDiagonal() * R.transpose();
                const Vec3 torque = tau - *S * (turned.angle() * turned.axis());
                L = I * (I + h * h * *S).ldlt().solve(L + h * torque);
            } else {
                L += h * tau;
            }
            Q = freeRotation(Q, L, s.moments, h);
        }
    }

    // Kick-drift-kick; continues from the stored state, closing last step's
    // half kicks with this step's wrench, or starts from the body's state.
    void verletStep(const Body& b, State& s, const Vec3& a, const Vec3& tau, double dt, Vec3& x, Vec3& v, Quat& Q,
                    Vec3& L) const {
        const double h = dt / subSteps_;
        const bool continued = s.started;
        if (continued) {
            v += 0.5 * s.lastH * (a - s.predictedA);
            L = s.L + 0.5 * s.lastH * (tau - s.predictedTau);
        } else {
            L = Q * s.moments.cwiseProduct(Q.conjugate() * b.angularVelocity);
        }
        // The last closing half kick uses the wrench predicted for the end of
        // the step (linear extrapolation from the last two steps; constant at
        // the first).
        const double ratio = continued ? dt / s.lastDt : 0.0;
        const Vec3 predictedA = a + ratio * (a - s.lastA);
        const Vec3 predictedTau = tau + ratio * (tau - s.lastTau);
        for (int k = 0; k < subSteps_; ++k) {
            const bool last = k + 1 == subSteps_;
            v += 0.5 * h * a;
            x += h * v;
            v += 0.5 * h * (last ? predictedA : a);
            L += 0.5 * h * tau;
            Q = freeRotation(Q, L, s.moments, h);
            L += 0.5 * h * (last ? predictedTau : tau);
        }
        s.lastA = a, s.lastTau = tau, s.lastH = h, s.lastDt = dt;
        s.predictedA = predictedA, s.predictedTau = predictedTau;
    }

    Vec3 gravity_ = Vec3::Zero();
    bool verlet_ = false;
    int subSteps_ = 1;
    std::vector<State> states_;
};

const TypeDoc kDoc{
    "Contact-free symplectic integrator: magnetic wrench and gravity only.\n"
    "For field-only runs (orbits, tumbling magnets); bodies pass through each other.",
    {"type: free\ngravity: [0, 0, -9.81]\nintegrator: symplecticEuler\nsubSteps: 1\n"},
    {{"ground", "-", "rejected: the free backend has no ground (use type: ODE)"},
     {"contact", "-", "rejected: the free backend has no contacts (use type: ODE)"},
     {"gravity", "m/s^2", "uniform acceleration of every dynamic body"},
     {"integrator", "-",
      "symplecticEuler (kick-drift; restarts bit-identical) or verlet (second order, state kept\n"
      "across steps)"},
     {"subSteps", "-", "integrator steps per solver step, 1..10000 (the wrench is held over them)"}}};

const RigidBodyBackend::Add<FreeBody> addFree("free", kDoc);

} // namespace

} // namespace mag
