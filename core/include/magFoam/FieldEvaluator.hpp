// FieldEvaluator: the field of one magnetized body and the wrench it exerts on
// another (paper Secs. 3-4), and the wrenches within a set of bodies. Selected at run time from
// system/magSchemes.yaml `field: {type: ...}`.
//
// Contract: all inputs and outputs are in the WORLD frame; torques are about
// the target's centre of mass. Implementations cache per-shape tables (they
// may key them by the Shape pointer: shapes are immutable and shared).
#pragma once

#include "magFoam/Body.hpp"
#include "magFoam/Dictionary.hpp"
#include "magFoam/Registry.hpp"
#include "magFoam/Wrench.hpp"

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mag {

// One evaluation of a pair: the source's field acts on the target's samples.
struct BodyPair {
    std::size_t source, target;
};

// Named counters of an evaluator, in a fixed order. Nested evaluators' counters
// come with a prefix ("near.", "far.").
struct FieldStats {
    std::vector<std::pair<std::string, std::uint64_t>> counts;

    // The counter `name`, 0 when absent.
    std::uint64_t count(std::string_view name) const {
        for (const auto& [k, v] : counts)
            if (k == name) return v;
        return 0;
    }
    void add(std::string name, std::uint64_t value) { counts.emplace_back(std::move(name), value); }
    // Another evaluator's counters under `prefix`.
    void add(const std::string& prefix, const FieldStats& other) {
        for (const auto& [k, v] : other.counts) counts.emplace_back(prefix + k, v);
    }
    // Per-pair sample counts of an adaptive quadrature (MBM's counters pairs,
    // pairSamplesMin, pairSamplesMax, boundarySamples, cappedPairs, under any
    // prefix such as "near."): one log line per evaluator that has them.
    std::vector<std::string> pairSampleLines() const {
        std::vector<std::string> lines;
        const std::string key = "pairSamplesMin";
        for (const auto& [k, v] : counts) {
            if (k.size() < key.size() || k.compare(k.size() - key.size(), key.size(), key) != 0) continue;
            const std::string prefix = k.substr(0, k.size() - key.size());
            const std::uint64_t pairs = count(prefix + "pairs");
            if (pairs == 0) continue;
            const std::uint64_t mean = count(prefix + "boundarySamples") / pairs;
            std::string line = (prefix.empty() ? "" : prefix.substr(0, prefix.size() - 1) + ": ") +
                               "adaptive quadrature, " + std::to_string(pairs) +
                               " pair evaluations, samples per pair min " + std::to_string(v) + " / mean " +
                               std::to_string(mean) + " / max " + std::to_string(count(prefix + "pairSamplesMax"));
            if (const std::uint64_t capped = count(prefix + "cappedPairs"))
                line += ", " + std::to_string(capped) + " stopped at maxSamples";
            lines.push_back(line);
        }
        return lines;
    }
    // "name N, name N, ..." for logs; empty without counters.
    std::string format() const {
        std::string s;
        for (const auto& [k, v] : counts) s += (s.empty() ? "" : ", ") + k + " " + std::to_string(v);
        return s;
    }
};

class FieldEvaluator {
public:
    virtual ~FieldEvaluator() = default;

    // Fields of `source` at world points: flux density B (T, always), and when
    // the spans are non-empty the vector potential A (T m) and H (A/m).
    virtual void evaluate(const Body& source, std::span<const Vec3> points, std::span<Vec3> B,
                          std::span<Vec3> A = {}, std::span<Vec3> H = {}) const = 0;

    // Wrench on `target` exerted by `source`.
    virtual Wrench interaction(const Body& source, const Body& target) const = 0;

    // The field `source` exerts on `target`, integrated over the target's
    // volume as the interaction energy sees it: -dU/dM_t (T m^3, world frame),
    // U = interaction(source, target).energy, which is linear in the target's
    // magnetization M_t. An induced magnetization solved from it is stationary
    // for the energy the forces are the gradient of (docs/physics.md#demag).
    // The default takes three energies with unit target magnetizations; the
    // evaluators here read Wrench::fieldIntegral of one interaction() instead.
    virtual Vec3 fieldIntegral(const Body& source, const Body& target) const;

    // fieldIntegral() per unit source magnetization: K (T m^3 per A/m, world
    // frame) with fieldIntegral = K M_s for the source's world magnetization
    // M_s, the poses as given (fieldIntegral is linear in M_s). Induction
    // models take a soft source's map from it (docs/physics.md#demag). The
    // default: three fieldIntegral() calls with unit source magnetizations;
    // MBM's regular rule reads it off one pass of the geometric field.
    virtual Mat3 fieldIntegralMap(const Body& source, const Body& target) const;

    // One line for logs: type and main settings.
    virtual std::string describe() const = 0;

    // The relative force error per pair that the evaluator's settings promise
    // (e.g. MBM's adaptive tolerance); 0 when they promise none. The energy
    // audit of magFoam allows for it.
    virtual double forceTolerance() const { return 0.0; }

    // The wrench on every body of a set from all the others in it: the scene
    // entry point (MagneticSystem calls it once per step). `out` is indexed
    // like `bodies`; only bodies listed in `active` take part, and with
    // skipFixedPairs pairs of two fixed bodies are left out. An evaluator may
    // treat some pairs in bulk (e.g. far pairs as point dipoles, by a fast
    // sum); the default evaluates every pair once with interaction()
    // (addPairWrenches), in increasing (i, j) order of `active`.
    virtual void addWrenches(std::span<const Body> bodies, std::span<const std::size_t> active,
                             bool skipFixedPairs, std::span<Wrench> out) const;

    // How addWrenches() evaluates the pair i < j: interaction(source, target)
    // with the body that moves sampled (a fixed body needs no wrench of its
    // own; a held one, Body::held, counts as moving), otherwise target j.
    // The pair's energy comes from the target's samples, so an induction
    // model that wants the response of either body to be stationary for
    // that energy asks in this orientation.
    static BodyPair orientedPair(std::span<const Body> bodies, std::size_t i, std::size_t j) {
        const bool fi = bodies[i].fixed && !bodies[i].held, fj = bodies[j].fixed && !bodies[j].held;
        return fj && !fi ? BodyPair{j, i} : BodyPair{i, j};
    }

    // Whether a and b are parts of one compound body (Body::group): an
    // evaluator's addWrenches() leaves their pair out. (A pair it treats in
    // bulk, as the hybrid's dipole sum, may stay in: its action and reaction
    // cancel in the body's sum.)
    static bool sameRigidBody(const Body& a, const Body& b) { return a.group != 0 && a.group == b.group; }

    // Counters since construction (pairs by tier, softened pairs, ...) for
    // logs, tests and benchmarks; the default has none.
    virtual FieldStats stats() const { return {}; }

    // Registry and selection by `type`.
    using Registry = mag::Registry<FieldEvaluator>;
    static Registry& registry();
    static std::unique_ptr<FieldEvaluator> New(const Dict& dict);

    template <class T> struct Add {
        explicit Add(const std::string& name, TypeDoc doc = {}) {
            noteModelLayout(sizeof(Body), alignof(Quat));
            registry().add(
                name, [](const Dict& d) { return std::unique_ptr<FieldEvaluator>(new T(d)); }, std::move(doc));
        }
    };

protected:
    // Adds the wrenches of the given pairs, each evaluated once with
    // interaction(): the target gets the wrench, the source the opposite force
    // and the torque that conserves angular momentum about any point (reported
    // as `torque`, mechanicalTorque zero). A quadrature error then cannot make
    // a cluster of touching magnets push itself along or spin itself up. Pairs
    // run on the worker threads (Threads.hpp) into per-pair slots that are
    // summed in pair order: bit-identical for any thread count.
    void addPairWrenches(std::span<const Body> bodies, std::span<const BodyPair> pairs, std::span<Wrench> out) const;

    // Pairs (i, j) collected in chunks for addPairWrenches: each is oriented so
    // that the body that moves is sampled (a fixed body needs no wrench of its
    // own), otherwise j; a chunk bounds the memory of large scenes without
    // changing any sum's order. finish() evaluates what is left.
    class PairChunks {
    public:
        PairChunks(const FieldEvaluator& f, std::span<const Body> bodies, std::span<Wrench> out)
            : f_(f), bodies_(bodies), out_(out) {}
        void add(std::size_t i, std::size_t j);
        void finish();

    private:
        static constexpr std::size_t kChunk = 65536;
        const FieldEvaluator& f_;
        std::span<const Body> bodies_;
        std::span<Wrench> out_;
        std::vector<BodyPair> pairs_;
    };
};

} // namespace mag
