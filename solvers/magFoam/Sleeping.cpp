#include "Sleeping.hpp"

#include <magFoam/Error.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/ResultsWriter.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

namespace mag::solver {

namespace {

std::string names(const std::vector<std::size_t>& island, const std::vector<Body>& bodies) {
    std::string out;
    for (std::size_t k = 0; k < island.size(); ++k) {
        if (k == 6) return out + " and " + std::to_string(island.size() - 6) + " more";
        out += (k ? ", " : "") + bodies[island[k]].name;
    }
    return out;
}

void writeWrench(std::ostream& os, const Wrench& w) {
    os << "{force: " << formatExact(w.force) << ", torque: " << formatExact(w.torque)
       << ", mechanicalTorque: " << formatExact(w.mechanicalTorque) << ", energy: " << formatExact(w.energy)
       << ", ownEnergy: " << formatExact(w.ownEnergy) << ", fieldIntegral: " << formatExact(w.fieldIntegral) << "}";
}

Wrench readWrench(const Dict& d) {
    Wrench w;
    w.force = d.get<Vec3>("force");
    w.torque = d.get<Vec3>("torque");
    w.mechanicalTorque = d.get<Vec3>("mechanicalTorque");
    w.energy = d.get<double>("energy");
    w.ownEnergy = d.get<double>("ownEnergy");
    w.fieldIntegral = d.get<Vec3>("fieldIntegral");
    d.reportUnused();
    return w;
}

} // namespace

// Union-find with path halving, for the islands.
struct Sleeping::Sets {
    std::vector<std::size_t> parent;
    explicit Sets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), std::size_t{0}); }
    std::size_t find(std::size_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    }
    void unite(std::size_t a, std::size_t b) {
        a = find(a), b = find(b);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
};

Sleeping::Sleeping(const SleepSettings& settings, const std::vector<Body>& bodies, const Vec3& gravity,
                   bool timeDependentField)
    : settings_(settings), asleep_(bodies.size(), 0), calm_(bodies.size()), forceScale_(bodies.size(), 0),
      torqueScale_(bodies.size(), 0) {
    if (settings_.enabled && timeDependentField) {
        spdlog::info("  sleeping: off, the applied field changes in time");
        settings_.enabled = false;
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (bodies[i].fixed) continue;
        forceScale_[i] = bodies[i].mass() * gravity.norm();
        torqueScale_[i] = forceScale_[i] * bodies[i].shape->boundingRadius;
    }
}

const std::vector<Body>& Sleeping::awakeView(const std::vector<Body>& bodies) {
    // Copied whole once (shapes, materials, names); then only the state and
    // the flag are refreshed: no allocation per step.
    if (view_.size() != bodies.size()) view_ = bodies;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        static_cast<BodyState&>(view_[i]) = bodies[i];
        view_[i].fixed = bodies[i].fixed || asleep_[i];
        view_[i].held = !bodies[i].fixed && asleep_[i];
    }
    return view_;
}

bool Sleeping::anyAsleep() const { return std::find(asleep_.begin(), asleep_.end(), 1) != asleep_.end(); }

MagneticSystem::Step Sleeping::magnetic(const MagneticSystem& magnets, std::vector<Body>& bodies) {
    const auto magnetized = [&](std::size_t i) { return bodies[i].magnetizationBody.squaredNorm() != 0; };
    if (!settings_.enabled || !anyAsleep()) {
        if (settings_.enabled) {
            long m = 0, f = 0;
            for (std::size_t i = 0; i < bodies.size(); ++i)
                if (magnetized(i)) ++m, f += bodies[i].fixed;
            pairsEvaluated_ += m * (m - 1) / 2 - f * (f - 1) / 2;
        }
        return magnets.step(bodies);
    }
    MagneticSystem::Step s;
    s.induction = magnets.converge(bodies);
    // Pairs with an awake body: sleeping bodies count as fixed.
    s.wrenches = magnets.wrenches(awakeView(bodies), true);
    // Pairs among sleeping and fixed bodies, once per change of who sleeps:
    // the awake bodies take no part (unmagnetized in this view).
    if (!frozenValid_) {
        std::vector<Body> still = bodies;
        for (std::size_t i = 0; i < still.size(); ++i)
            if (!asleep_[i] && !still[i].fixed) still[i].magnetizationBody.setZero();
        frozen_ = magnets.wrenches(still, MagneticSystem::fixedPairsConstant(still));
        frozenValid_ = true;
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) s.wrenches[i] += frozen_[i];
    long awake = 0, sleeping = 0, fixed = 0;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (!magnetized(i)) continue;
        if (bodies[i].fixed) ++fixed;
        else if (asleep_[i]) ++sleeping;
        else ++awake;
    }
    pairsSkipped_ += sleeping * (sleeping - 1) / 2 + sleeping * fixed;
    pairsEvaluated_ += awake * (awake - 1) / 2 + awake * (sleeping + fixed);
    return s;
}

bool Sleeping::byContacts(const RigidBodyBackend& backend) {
    if (settings_.islands != SleepSettings::Islands::contacts) return false;
    if (backend.touching(touching_)) return true;
    if (!fallbackNoted_)
        spdlog::info("  sleeping: the rigid-body backend does not report contacts that wake a sleeping body: "
                     "islands of bodies whose bounding spheres come near (sleep.islands: boundingSpheres)");
    fallbackNoted_ = true;
    return false;
}

std::vector<std::vector<std::size_t>> Sleeping::islands(const std::vector<Body>& bodies, bool byContacts) const {
    const std::size_t n = bodies.size();
    Sets sets(n);
    if (byContacts) {
        // The backend's contacts of the last step: bodies touching only fixed
        // ones (the ground, a held magnet) are islands of their own.
        for (const auto& [i, j] : touching_)
            if (i < n && j < n && !bodies[i].fixed && !bodies[j].fixed) sets.unite(i, j);
        return groups(bodies, sets);
    }
    // Sort and sweep along x: a pair is tested only when the two reaches
    // overlap in x, so a scene of spread-out bodies costs n log n, not n^2.
    auto reach = [&](std::size_t i) {
        const double r = bodies[i].shape->boundingRadius;
        return r + 0.5 * settings_.margin * r;
    };
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < n; ++i)
        if (!bodies[i].fixed) order.push_back(i);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        const double xa = bodies[a].position.x() - reach(a), xb = bodies[b].position.x() - reach(b);
        return xa < xb || (xa == xb && a < b);
    });
    for (std::size_t k = 0; k < order.size(); ++k) {
        const std::size_t i = order[k];
        const double ri = bodies[i].shape->boundingRadius, right = bodies[i].position.x() + reach(i);
        for (std::size_t l = k + 1; l < order.size(); ++l) {
            const std::size_t j = order[l];
            if (bodies[j].position.x() - reach(j) > right) break;
            const double rj = bodies[j].shape->boundingRadius;
            const double d = ri + rj + settings_.margin * std::min(ri, rj);
            if ((bodies[i].position - bodies[j].position).squaredNorm() < d * d) sets.unite(i, j);
        }
    }
    return groups(bodies, sets);
}

std::vector<std::vector<std::size_t>> Sleeping::groups(const std::vector<Body>& bodies, Sets& sets) {
    const std::size_t n = bodies.size();
    std::vector<std::vector<std::size_t>> byRoot(n), out;
    for (std::size_t i = 0; i < n; ++i)
        if (!bodies[i].fixed) byRoot[sets.find(i)].push_back(i);
    for (auto& island : byRoot)
        if (!island.empty()) out.push_back(std::move(island));
    return out;
}

double Sleeping::wrenchChange(std::size_t i, const Wrench& w) const {
    const Wrench& r = calm_[i].reference;
    const double f = std::max(r.force.norm(), forceScale_[i]);
    const double t = std::max(r.totalTorque().norm(), torqueScale_[i]);
    return std::max((w.force - r.force).norm() / f, (w.totalTorque() - r.totalTorque()).norm() / t);
}

bool Sleeping::wrenchMoved(std::size_t i, const Wrench& w) const {
    return wrenchChange(i, w) > settings_.wrenchChange;
}

void Sleeping::wake(const std::vector<std::size_t>& island, std::vector<Body>& bodies, const std::string& why,
                    long step, double t) {
    bool any = false;
    for (std::size_t i : island) {
        if (!asleep_[i]) continue;
        asleep_[i] = 0;
        calm_[i].seconds = 0;
        any = true;
    }
    if (!any) return;
    ++wakeEvents_;
    frozenValid_ = false;
    changed_ = true;
    spdlog::info("step {} (t = {:.6g} s): woken: {} ({})", step, t, names(island, bodies), why);
}

std::string Sleeping::wakeReason(std::size_t i, const std::vector<Body>& bodies, const Wrench& w) const {
    if (const double c = wrenchChange(i, w); c > settings_.wrenchChange)
        return fmt::format("the magnetic wrench on '{}' changed by {:.2g} of its scale", bodies[i].name, c);
    const Vec3& M0 = calm_[i].magnetization;
    if ((bodies[i].magnetizationBody - M0).norm() > settings_.wrenchChange * M0.norm())
        return "the magnetization of '" + bodies[i].name + "' changed";
    return {};
}

void Sleeping::wakeBeforeStep(std::vector<Body>& bodies, const std::vector<Wrench>& wrenches,
                              RigidBodyBackend& backend, long step, double t) {
    if (!settings_.enabled || !anyAsleep()) return;
    if (byContacts(backend)) {
        // Islands of touching bodies: a sleeping body's own wrench or
        // magnetization wakes it alone; those it rests on or under wake as
        // the backend finds them touching a moving body (after the step),
        // and an awake body comes near only by touching.
        for (std::size_t i = 0; i < bodies.size(); ++i)
            if (asleep_[i])
                if (const std::string why = wakeReason(i, bodies, wrenches[i]); !why.empty())
                    wake({i}, bodies, why, step, t);
    } else {
        for (const auto& island : islands(bodies, false)) {
            const auto sleeping =
                std::count_if(island.begin(), island.end(), [&](std::size_t i) { return asleep_[i]; });
            if (sleeping == 0) continue;
            std::string why;
            if (static_cast<std::size_t>(sleeping) < island.size()) {
                const auto awake =
                    *std::find_if(island.begin(), island.end(), [&](std::size_t i) { return !asleep_[i]; });
                why = "'" + bodies[awake].name + "' came near";
            }
            for (std::size_t k = 0; k < island.size() && why.empty(); ++k)
                why = wakeReason(island[k], bodies, wrenches[island[k]]);
            if (!why.empty()) wake(island, bodies, why, step, t);
        }
    }
    if (changed_) backend.setSleeping(bodies, asleep_), changed_ = false;
}

void Sleeping::sleepAfterStep(std::vector<Body>& bodies, const std::vector<Wrench>& wrenches,
                              RigidBodyBackend& backend, double dt, long step, double t) {
    if (!settings_.enabled) return;
    const auto groups = islands(bodies, byContacts(backend));
    // What a contact woke (the backend holds the body no more).
    if (anyAsleep()) {
        const std::vector<char> held = backend.sleeping();
        for (const auto& island : groups)
            for (std::size_t i : island)
                if (asleep_[i] && i < held.size() && !held[i]) {
                    wake(island, bodies, "a contact woke '" + bodies[i].name + "'", step, t);
                    break;
                }
    }
    // Calm times of the awake bodies.
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (bodies[i].fixed || asleep_[i]) continue;
        const Body& b = bodies[i];
        bool still = b.velocity.norm() < settings_.speed &&
                     b.angularVelocity.norm() * b.shape->boundingRadius < settings_.speed;
        Calm& c = calm_[i];
        if (still && c.seconds > 0 && wrenchMoved(i, wrenches[i])) still = false;
        if (!still) {
            c.seconds = 0;
            continue;
        }
        if (c.seconds == 0) c.reference = wrenches[i];
        c.seconds += dt;
    }
    // Islands calm throughout fall asleep together.
    for (const auto& island : groups) {
        const bool ready = std::all_of(island.begin(), island.end(), [&](std::size_t i) {
            return !asleep_[i] && calm_[i].seconds >= settings_.time && calm_[i].seconds > 0;
        });
        if (!ready) continue;
        for (std::size_t i : island) {
            asleep_[i] = 1;
            calm_[i].reference = wrenches[i];
            calm_[i].magnetization = bodies[i].magnetizationBody;
        }
        ++sleepEvents_;
        frozenValid_ = false;
        changed_ = true;
        spdlog::info("step {} (t = {:.6g} s): asleep: {}", step, t, names(island, bodies));
    }
    if (changed_) backend.setSleeping(bodies, asleep_), changed_ = false;
}

std::string Sleeping::stateText(const std::vector<Body>& bodies) const {
    if (!settings_.enabled) return {};
    std::ostringstream os;
    os << "# magFoam sleeping bodies (docs/dynamics.md#sleeping): who sleeps, how long each has been calm,\n"
          "# the wrench its calm began with (or it fell asleep with), and the cached pairs of sleeping bodies\n"
          "bodies:\n";
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (bodies[i].fixed) continue;
        const Calm& c = calm_[i];
        os << "  - name: " << bodies[i].name << "\n    asleep: " << (asleep_[i] ? "true" : "false")
           << "\n    calm: " << formatExact(c.seconds) << "\n    reference: ";
        writeWrench(os, c.reference);
        os << "\n    magnetization: " << formatExact(c.magnetization) << "\n";
    }
    if (frozenValid_) {
        os << "frozen:\n";
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            os << "  - ";
            writeWrench(os, frozen_[i]);
            os << "\n";
        }
    }
    return os.str();
}

void Sleeping::readState(const Dict& d, std::vector<Body>& bodies, RigidBodyBackend& backend) {
    if (!settings_.enabled) {
        spdlog::info("{}: sleeping is off in constant/rigidBody.yaml: every body starts awake", d.file());
        return;
    }
    for (const Dict& b : d.list("bodies")) {
        const std::size_t i = stateBodyIndex(b, bodies);
        asleep_[i] = b.get<bool>("asleep");
        calm_[i].seconds = b.get<double>("calm");
        calm_[i].reference = readWrench(b.sub("reference"));
        calm_[i].magnetization = b.get<Vec3>("magnetization");
        b.reportUnused();
    }
    frozenValid_ = d.has("frozen");
    if (frozenValid_) {
        const std::vector<Dict> frozen = d.list("frozen");
        if (frozen.size() != bodies.size())
            d.fail("frozen", "expected one wrench per body (" + std::to_string(bodies.size()) + ")");
        frozen_.resize(bodies.size());
        for (std::size_t i = 0; i < bodies.size(); ++i) frozen_[i] = readWrench(frozen[i]);
    }
    d.reportUnused();
    backend.setSleeping(bodies, asleep_);
}

void Sleeping::summary() const {
    if (!settings_.enabled) return;
    const long n = static_cast<long>(std::count(asleep_.begin(), asleep_.end(), 1));
    const long total = pairsSkipped_ + pairsEvaluated_;
    spdlog::info("  sleeping: {} bodies asleep at the end; {} times an island fell asleep, {} woke; pairs "
                 "evaluated {}, kept from their last wrench {} ({:.1f} %)",
                 n, sleepEvents_, wakeEvents_, pairsEvaluated_, pairsSkipped_,
                 total > 0 ? 100.0 * double(pairsSkipped_) / double(total) : 0.0);
}

} // namespace mag::solver
